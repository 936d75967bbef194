//! The decision cycle (issue 4). This first part is the operator decision procedure and the
//! exploration policies; the phases, support and impasse machinery build on it.

pub mod by_token;
pub(crate) mod compiled;
pub mod cycle;
pub mod functions;
mod gds;
pub mod procedure;
mod slot;
pub mod state;
pub(crate) mod support;
