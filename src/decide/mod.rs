//! The decision cycle (issue 4). This first part is the operator decision procedure and the
//! exploration policies; the phases, support and impasse machinery build on it.

pub mod by_token;
pub(crate) mod compiled;
mod consistency;
pub mod cycle;
mod decision;
mod elaborate;
mod fire;
pub mod functions;
mod gc;
mod gds;
mod ids;
pub mod procedure;
mod scratch;
mod slot;
pub mod state;
mod substates;
pub(crate) mod support;
mod wm_phase;
