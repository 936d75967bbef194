//! rusoar: the Soar cognitive architecture in Rust, and Soar-SLAM.
pub mod agent;
pub mod ast;
pub mod cli;
pub mod lexer;
pub mod parser;
pub mod printer;
pub mod production;
pub mod rete;
pub mod rhs_functions;
pub mod robot;
pub mod source;
pub mod support;
pub mod symbols;
pub mod tokenizer;
pub mod trace;
pub mod wm;
