//! The agent's record of the input WMEs an embedding program made, and of what it changed
//! on the input-link between input phases: data the agent holds; `io.rs` fills it and the
//! input phase applies it.

use crate::symbols::Sym;
use crate::wm::WmeId;
use rustc_hash::FxHashSet;

/// What changing an input WME to the value it already has does (SML's
/// `SetBlinkIfNoChange`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum InputUpdate {
    /// Remove the WME and add it again with a new timetag, so rules that test it match
    /// again: the official kernel's default.
    #[default]
    BlinkIfNoChange,
    /// Leave the WME alone.
    SkipIfNoChange,
}

/// A handle on an input WME made through [`crate::Io::add`] or [`crate::Io::add_object`].
/// It stays valid when its value changes and across `init-soar`, until the WME is removed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct InputWme(pub(crate) u32);

/// One input WME the program made, as the input table remembers it.
#[derive(Debug, Clone)]
pub(crate) struct InputEntry {
    pub(crate) id: Sym,
    pub(crate) attr: Sym,
    pub(crate) value: Sym,
    /// The WME in working memory now; `None` once removed.
    pub(crate) wme: Option<WmeId>,
    /// The value is an identifier this table made (`add_input_object`).
    pub(crate) object: bool,
}

/// The program's input WMEs, in the order they were made, and what the output side has
/// reported and marked.
#[derive(Debug, Default)]
pub(crate) struct InputTable {
    pub(crate) entries: Vec<InputEntry>,
    /// Input-link changes waiting for the next input phase.
    pub(crate) queue: Vec<InputChange>,
    pub(crate) update_mode: InputUpdate,
    /// The newest output-link timetag that new output commands were reported up to.
    pub(crate) output_reported: u64,
    /// Commands marked done since the last `init-soar`.
    pub(crate) done: FxHashSet<Sym>,
}

/// An input-link change the embedding program made, waiting for the next input phase.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum InputChange {
    Add(WmeId),
    Remove(WmeId),
}

