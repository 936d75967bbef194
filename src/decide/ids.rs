//! The handles of the decider's tables: an instantiation or a preference is named by its index
//! in [`super::state::DecideState`]'s lists (reused once freed). They live apart so that the
//! slots, the scratch buffers and the decider's state can all name them without naming each
//! other.

pub type InstId = u32;
pub type PrefId = u32;
