//! The handles of the decider's tables: an instantiation or a preference is named by its index
//! in [`super::state::DecideState`]'s lists (reused once freed). They live apart so that the
//! slots, the scratch buffers and the decider's state can all name them without naming each
//! other; the tables' indexing by them is declared beside the item types, in `state`.

use crate::ids::id_type;

id_type! {
    /// An instantiation: its place in `DecideState::insts`.
    pub struct InstId;
}

id_type! {
    /// A preference: its place in `DecideState::prefs`.
    pub struct PrefId;
}
