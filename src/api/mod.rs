//! The kernel's public API: [`Agent`] and what it hands out. Everything an embedding
//! program, the command line or Soar-SLAM does with the kernel goes through here.

mod agent;
mod error;
mod io;

pub use agent::{Agent, ListenerId, RunResult, RunUnit, StopReason};
pub use error::{Error, Location, Printed};
pub use io::Io;
