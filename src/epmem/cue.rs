//! A query's cue as the search sees it (Soar manual, ch. 7, "Cue-Based Retrieval"): one
//! literal per cue WME, built by `query.rs` and matched episode by episode by `walk.rs`.

use crate::symbols::Sym;
use rustc_hash::FxHashMap;

/// A cue WME as the search sees it.
#[derive(Debug, Clone)]
pub(crate) struct Literal {
    /// The cue identifier it hangs from (`None` for the root).
    pub id_sym: Option<Sym>,
    pub value_sym: Sym,
    /// The attribute's number (`None`: never stored, so never matched).
    pub(super) attr: Option<i64>,
    /// A constant value's number (`Some(None)`: never stored); `None` for an identifier.
    pub(super) constant: Option<Option<i64>>,
    pub is_leaf: bool,
    pub neg: bool,
    pub(super) weight: f64,
    pub(super) children: Vec<usize>,
    pub(super) parents: Vec<usize>,
}

/// The literals of a query, root first.
#[derive(Debug, Default)]
pub(crate) struct Cue {
    pub lits: Vec<Literal>,
    /// How many inner literals have each cue identifier as value.
    pub(super) incoming: FxHashMap<Sym, usize>,
    pub leaves: usize,
    pub pos_literals: u64,
    pub neg_literals: u64,
}
