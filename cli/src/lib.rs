//! The `rusoar` command line's parts, apart from argument handling: the interactive REPL
//! ([`repl`]) and the SoarUnit test runner ([`soarunit`]). Both drive the kernel through its
//! public API.

pub mod repl;
pub mod soarunit;
