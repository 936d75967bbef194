//! The decision cycle: the run loop and its phases (`cycle.rs`, which lists the files that
//! do each step), the operator decision procedure and the exploration policies
//! (`procedure.rs`), match support (`support.rs`), the goal dependency set (`gds.rs`), and
//! the decider's memory (`state.rs`, `slot.rs`, `ids.rs`, `scratch.rs`) which the agent
//! holds.

mod breaks;
mod ceilings;
mod clear;
pub mod by_token;
pub(crate) mod compiled;
mod consistency;
pub mod cycle;
pub mod cycle_stats;
mod decision;
mod elaborate;
pub(crate) use elaborate::PendingRetraction;
mod fire;
pub mod functions;
mod gc;
mod gds;
pub mod limits;
mod osk;
pub(crate) mod ids;
pub mod procedure;
pub(crate) mod recall;
mod scratch;
mod slot;
pub mod state;
mod substates;
pub(crate) mod support;
mod wm_phase;
