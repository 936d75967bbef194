//! rusoar: the Soar cognitive architecture in Rust, and Soar-SLAM.
pub mod agent;
mod api;
pub mod ast;
pub mod commands;
pub mod decide;
pub mod io;
pub mod learn;
pub mod lexer;
pub mod parser;
pub mod printer;
pub mod production;
pub mod rete;
pub mod rhs;
pub mod rng;
pub mod source;
pub mod stdlib;
pub mod symbols;
pub mod syntax;
pub mod trace;
pub mod wm;

pub use api::{Agent, Error, Io, ListenerId, Location, Printed, RunResult, RunUnit, StopReason};
pub use commands::LoadReport;
pub use io::{InputUpdate, InputWme, IoError, OutputCommand, Value};
pub use rhs::host::{RhsArg, RhsCall};
pub use symbols::Sym as Symbol;
pub use wm::Wme;
