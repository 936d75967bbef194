//! The buffers the decision cycle keeps between cycles for their room, so that a warm cycle
//! allocates nothing: the elaboration cycle's queues, the working-memory phase's changes and
//! the garbage collection's sets. Their owners fill and empty them (`elaborate.rs`,
//! `wm_phase.rs`, `gc.rs`); [`super::state::DecideState`] holds them between uses.

use super::ids::{InstId, PrefId};
use crate::rete::{ProdId, TokId};
use crate::symbols::Sym;
use crate::wm::WmeId;
use rustc_hash::{FxHashMap, FxHashSet};

/// Distinct values in first-seen order; a set beside the list once it is large.
#[derive(Debug, Default)]
pub(super) struct Wanted {
    list: Vec<Sym>,
    set: FxHashSet<Sym>,
}

impl Wanted {
    pub(super) fn clear(&mut self) {
        self.list.clear();
        if !self.set.is_empty() {
            self.set = FxHashSet::default();
        }
    }

    pub(super) fn insert(&mut self, v: Sym, large: bool) {
        let new = if large {
            self.set.insert(v)
        } else {
            !self.list.contains(&v)
        };
        if new {
            self.list.push(v);
        }
    }

    pub(super) fn contains(&self, v: Sym) -> bool {
        if self.set.is_empty() {
            self.list.contains(&v)
        } else {
            self.set.contains(&v)
        }
    }

    pub(super) fn list(&self) -> &[Sym] {
        &self.list
    }
}

/// The working sets of one garbage collection, kept between collections for their room.
#[derive(Debug, Default)]
pub(crate) struct GcScratch {
    pub(super) roots: FxHashSet<Sym>,
    pub(super) memo: FxHashMap<Sym, bool>,
    pub(super) dead: FxHashSet<Sym>,
    pub(super) visited: FxHashSet<Sym>,
    /// The upward search's path.
    pub(super) path: Vec<SearchFrame>,
    /// The parent objects of the identifiers on `path`, each one's after those of the one
    /// below it.
    pub(super) parents: Vec<Sym>,
    pub(super) stack: Vec<Sym>,
}

/// One identifier on the garbage collector's upward search path (see `AgentCore::linked`).
#[derive(Debug, Clone, Copy)]
pub(crate) struct SearchFrame {
    pub node: Sym,
    /// Its next parent to try, and the end of its parents: places in the search's list of
    /// parents, or, read in place, indexes of its parent WMEs then preferences (the end
    /// then found as they are read).
    pub next: usize,
    pub end: usize,
    /// Where its parents start in the search's list (its length before them, when in place).
    pub start: usize,
    pub in_place: bool,
}

impl GcScratch {
    pub(super) fn clear(&mut self) {
        self.roots.clear();
        self.memo.clear();
        self.dead.clear();
        self.visited.clear();
        self.path.clear();
        self.parents.clear();
        self.stack.clear();
    }
}

/// The buffers of one elaboration cycle, kept between cycles for their room.
#[derive(Debug, Default)]
pub(crate) struct CycleScratch {
    pub(super) keep: Vec<(ProdId, TokId)>,
    pub(super) queued: Vec<Queued>,
    pub(super) retracted_levels: Vec<Option<u32>>,
    pub(super) levels: Vec<u32>,
    pub(super) to_fire_insts: Vec<InstId>,
    pub(super) retracted: Vec<InstId>,
    pub(super) new_prefs: Vec<PrefId>,
    /// The order of the cycle's retractions when justifications retract with them.
    pub(super) pending_retractions: Vec<super::PendingRetraction>,
}

/// A match pending at the start of an elaboration cycle.
#[derive(Debug, Clone, Copy)]
pub(super) struct Queued {
    pub(super) prod: ProdId,
    pub(super) tok: TokId,
    /// Its goal's level.
    pub(super) level: u32,
    pub(super) o_support: bool,
    pub(super) fired: bool,
}

/// The buffers of one working-memory phase, kept between phases for their room.
#[derive(Debug, Default)]
pub(crate) struct SlotScratch {
    pub(super) adds: Vec<(Sym, Sym, Sym, bool)>,
    pub(super) removes: Vec<(WmeId, u64)>,
    pub(super) context: Vec<(Sym, Sym)>,
    pub(super) added: Vec<WmeId>,
    /// Removed WMEs the matcher has still to hear of, with their timetags.
    pub(super) unmatched: Vec<(WmeId, u64)>,
    pub(super) want: Wanted,
}
