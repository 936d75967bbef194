//! rusoar: the Soar cognitive architecture (Soar 9.6's semantics) in Rust.
//!
//! An [`Agent`] loads Soar's rule language and command language, runs the decision cycle
//! with impasses, substates and chunking, and talks to its environment through the input
//! and output links ([`Io`]). Everything the kernel offers is reached from [`Agent`].

/// Declares the kernel's modules: private, and public only under the `internals` feature,
/// which the kernel's own benchmarks use to measure its parts (it promises no stable API).
macro_rules! kernel_modules {
    ($($name:ident),* $(,)?) => {$(
        #[cfg(feature = "internals")]
        #[doc(hidden)]
        pub mod $name;
        #[cfg(not(feature = "internals"))]
        mod $name;
    )*};
}

kernel_modules!(
    agent,
    ast,
    commands,
    decide,
    epmem,
    events,
    inputs,
    io,
    learn,
    lexer,
    memory_timers,
    parser,
    percepts,
    percepts_phase,
    pools,
    printer,
    production,
    rete,
    rhs,
    rl,
    rng,
    smem,
    source,
    stdlib,
    symbols,
    trace,
    trace_events,
    trace_text,
    value,
    wm,
    wme_filters,
    wma,
);

mod api;
mod ids;
mod invariants;
/// The README's Rust examples, compiled and run as tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
/// The embedding guide's Rust examples, compiled and run as tests.
#[cfg(doctest)]
#[doc = include_str!("../docs/embedding.md")]
struct EmbeddingGuideDoctests;
pub mod syntax;
#[cfg(test)]
mod tests;

pub use api::{Agent, Error, Io, ListenerId, Location, Printed, RunResult, RunUnit, StopReason};
pub use commands::LoadReport;
pub use decide::limits::Limits;
pub use decide::state::Phase;
pub use events::AgentEvent;
pub use io::{InputUpdate, InputWme, IoError, OutputCommand, Value};
pub use rhs::host::{RhsArg, RhsCall};
pub use symbols::Sym as Symbol;
pub use wm::Wme;
