//! The agent's record of what an embedding program did to the input-link between input
//! phases, kept as data here so that the agent can hold it; `io.rs` fills it and the input
//! phase applies it.

use crate::wm::WmeId;

/// An input-link change the embedding program made, waiting for the next input phase.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum InputChange {
    Add(WmeId),
    Remove(WmeId),
}
