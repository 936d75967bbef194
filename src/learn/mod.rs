//! Learning from substate results (Soar manual, ch. 4, "Procedural Knowledge Learning"):
//! what a substate firing records so it can be backtraced later, the detection of results,
//! and the justifications and chunks built from them. `backtrace.rs` walks from a result to
//! the superstate WMEs it depended on, `build.rs` turns that into a rule.

mod backtrace;
mod backtrace_trace;
mod build;
mod episode;
pub mod explain;
mod memory_results;
mod negations;
mod record;
pub mod settings;
mod singletons;
pub(crate) mod sketch;
pub mod stats;
mod var_order;

use crate::decide::ids::InstId;
use crate::production::Production;
use crate::symbols::Sym;
use crate::wm::{Wme, WmeId};
use rustc_hash::{FxHashMap, FxHashSet};
use std::sync::Arc;


/// An identity (EBC): one variable of one instantiation. Identities that backtracing shows
/// to be the same thing are joined, and each joined set becomes one variable of a chunk.
/// 0 means "no identity": the rule tested or made a literal there.
pub type Ident = u64;

/// One positive condition of a recorded firing.
#[derive(Debug, Clone)]
pub struct TraceCond {
    pub wme: Wme,
    pub wme_id: WmeId,
    /// The level of the WME's identifier when it matched: below the learning goal's level
    /// means superstate knowledge (a chunk condition), otherwise local to the substate.
    pub level: u32,
    /// The identities of the condition's id, attribute and value tests.
    pub ids: [Ident; 3],
    /// Index of the condition in the rule (for its relational tests), when there is a rule.
    pub cond: Option<usize>,
    /// For a local WME: the preference that made it, so backtracing can go on through it.
    pub support: Option<Arc<PrefOrigin>>,
    /// The acceptable preference an impasse's `^item` stands for (see `record.rs`).
    pub via_item: bool,
    /// For a test of the match goal's selected operator: the knowledge that selected it
    /// (`chunk add-osk`), backtraced with the operator's proposal; for any other WME of
    /// an operator slot, that slot's prohibit preferences alone.
    pub osk: Option<Osk>,
    /// `osk` is the whole knowledge that selected the match goal's operator.
    pub osk_local: bool,
}

/// What a firing in a substate looked like, kept as long as its preferences need it (the
/// instantiation itself may retract before a later result backtraces through it).
#[derive(Debug)]
pub struct InstTrace {
    pub name: Arc<str>,
    /// The rule fired (none for a justification).
    pub prod: Option<Arc<Production>>,
    pub conds: Vec<TraceCond>,
    /// Each variable of the rule: its identity and what it was bound to (or made).
    pub vars: TraceVars,
    /// The user rule at the origin of a chunk, and how many learning steps away it is
    /// (`chunk*r*...` is 1, `chunkx2*r*...` 2): names of chunks learned from this firing.
    pub base: Arc<str>,
    pub generation: u32,
    /// The level of the instantiation's match goal (traced with its preferences).
    pub level: u32,
    /// The number of the last backtrace that went through this firing: each is gone
    /// through once per learning episode (an atomic, as traces are shared by `Arc`).
    pub backtraced: std::sync::atomic::AtomicU64,
}

impl Drop for InstTrace {
    /// Firings in a substate chain through the preferences of the local WMEs each tested:
    /// a long run in one substate makes a chain of hundreds of thousands, which goes when
    /// the substate does. The links are let go one at a time here, from a list, where
    /// dropping them in place would recurse once per link and overflow the stack.
    fn drop(&mut self) {
        let mut pending: Vec<Arc<PrefOrigin>> = Vec::new();
        take_links(&mut self.conds, &mut pending);
        while let Some(origin) = pending.pop() {
            // A link someone else still holds stays; one held only here is followed.
            let Some(origin) = Arc::into_inner(origin) else {
                continue;
            };
            if let Some(mut trace) = Arc::into_inner(origin.trace) {
                take_links(&mut trace.conds, &mut pending);
            }
        }
    }
}

/// Moves the links to other firings out of `conds`: the origins of the WMEs they tested,
/// and the selection knowledge they hold alone.
fn take_links(conds: &mut [TraceCond], pending: &mut Vec<Arc<PrefOrigin>>) {
    for c in conds {
        pending.extend(c.support.take());
        if let Some(osk) = c.osk.take() {
            if Arc::strong_count(&osk) == 1 {
                pending.extend(osk.iter().cloned());
            }
        }
    }
}

/// A rule's variables as its recorded firings list them, made once per rule: the names in
/// name order, and where each binding, each variable an action makes and each field of a
/// make action sits among them.
#[derive(Debug, Default)]
pub struct VarTable {
    pub names: Box<[Arc<str>]>,
    /// For binding `k` of the rule's network: its position in `names`.
    pub binding_pos: Box<[u32]>,
    /// The variables the actions make (indexes into the compiled rule's list), in name
    /// order, each with its position in `names`.
    pub new_in_order: Box<[(u32, u32)]>,
    /// For each action: the position in `names` of the variable in its id, attribute,
    /// value and referent (`u32::MAX`: not a variable, or not a make action).
    pub action_pos: Box<[[u32; 4]]>,
}

/// A firing's variables, each with its identity and what it was bound to (or made): slots
/// beside the rule's shared [`VarTable`], `None` for a variable left unbound.
#[derive(Debug, Default)]
pub struct TraceVars {
    table: Arc<VarTable>,
    slots: Box<[Option<(Ident, Sym)>]>,
}

impl TraceVars {
    pub fn new(table: Arc<VarTable>, slots: Box<[Option<(Ident, Sym)>]>) -> Self {
        TraceVars { table, slots }
    }

    pub fn get(&self, var: &str) -> Option<&(Ident, Sym)> {
        let i = self.table.names.binary_search_by(|k| (**k).cmp(var)).ok()?;
        self.slots.get(i)?.as_ref()
    }

    /// The variable at a position of the rule's table.
    pub fn at(&self, pos: u32) -> Option<&(Ident, Sym)> {
        self.slots.get(pos as usize)?.as_ref()
    }

    pub fn contains_key(&self, var: &str) -> bool {
        self.get(var).is_some()
    }

    /// How many variables are bound.
    pub fn len(&self) -> usize {
        self.slots.iter().filter(|s| s.is_some()).count()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// A rule's name and the names of the chunks learned from its firings, shared by every
/// recorded firing of it.
#[derive(Debug)]
pub struct TraceNames {
    pub name: Arc<str>,
    pub base: Arc<str>,
    pub generation: u32,
    /// For each positive condition, the binding index (in the rule's bindings) of the
    /// variable each field tests for equality; `u32::MAX` for none.
    pub cond_bindings: Box<[[u32; 3]]>,
    pub vars: Arc<VarTable>,
}

/// Where a preference came from: the firing and the identities of its fields.
#[derive(Debug)]
pub struct PrefOrigin {
    pub trace: Arc<InstTrace>,
    /// Identities of the id, attribute, value and referent.
    pub ids: [Ident; 4],
    /// The make action of `trace.prod` that made it (for RHS function calls in chunks).
    pub action: Option<usize>,
}

/// The origins of an operator's selection knowledge (`chunk add-osk`), shared by every
/// firing that tests the operator.
pub type Osk = Arc<[Arc<PrefOrigin>]>;

/// A justification alive in preference memory (`print --justifications`).
#[derive(Debug, Clone)]
pub struct Justification {
    body: sketch::Body,
    /// The serial that tells its instantiation from one in a reused slot.
    pub serial: u64,
}

impl Justification {
    pub(crate) fn new(body: sketch::Body, serial: u64) -> Self {
        Justification { body, serial }
    }

    pub fn name(&self) -> &str {
        match &self.body {
            sketch::Body::Rule(p) => &p.name,
            sketch::Body::Sketch(s) => &s.name,
        }
    }

    pub fn flags(&self) -> crate::production::Flags {
        match &self.body {
            sketch::Body::Rule(p) => p.flags.clone(),
            sketch::Body::Sketch(_) => crate::production::Flags {
                justification: true,
                ..Default::default()
            },
        }
    }

    /// The justification as a rule (written out now if it was kept as a sketch).
    pub fn production(&self, symbols: &crate::symbols::Symbols) -> Arc<Production> {
        match &self.body {
            sketch::Body::Rule(p) => Arc::clone(p),
            sketch::Body::Sketch(s) => Arc::new(s.production(symbols)),
        }
    }
}

/// Learning's counters and state that survive `init-soar` (chunks do) and those that do not.
#[derive(Debug, Default)]
pub struct LearnState {
    /// Justifications' names by serial, for the traces that name the instantiation behind
    /// a preference (`+ (S1 ^operator B1 >) (justify1)`).
    pub justification_names: rustc_hash::FxHashMap<u64, String>,
    pub next_ident: Ident,
    /// Chunks learned over the agent's life (names and `stats`).
    pub chunks_learned: u64,
    /// The count used in chunk names (`t<dc>-<n>`).
    pub chunk_name_count: u64,
    pub chunk_name_dc: u64,
    /// The same for justifications named like chunks (learning on).
    pub justification_name_count: u64,
    pub justification_name_dc: u64,
    /// The counter of `chunk naming-style numbered` names (incremented twice per name).
    pub chunk_number: u64,
    /// The justification name counter (incremented twice per name, as in 9.6).
    pub justification_counter: u64,
    pub justifications_learned: u64,
    /// Chunks learned during the current `run` (for its summary line).
    pub learned_this_run: u64,
    /// Chunks learned in the current phase (max-chunks is per phase in 9.6).
    pub chunks_this_phase: i64,
    /// Duplicate chunks learned in the current phase, by the rule whose firing made the
    /// result (max-dupes is per rule, per phase in 9.6).
    pub dupes_this_phase: FxHashMap<Arc<str>, i64>,
    /// The names each fired rule's recorded firings share, by rule.
    pub trace_names: FxHashMap<crate::rete::ProdId, Arc<TraceNames>>,
    /// Scratch for recording a firing: each binding's identity.
    pub binding_idents: Vec<Ident>,
    /// Scratch for recording a firing: the WMEs of its match.
    pub match_scratch: Vec<crate::wm::WmeId>,
    /// Scratch for finding a firing's results: the preferences already seen.
    pub results_seen: FxHashSet<crate::decide::ids::PrefId>,
    /// Backtrace tables not in use, emptied between learning episodes (they keep their
    /// room). A justification's results one level up are learned from while the episode
    /// that made it still holds its own tables, so episodes nest.
    pub spare_backtraces: Vec<backtrace::Backtrace>,
    /// Backtraces begun since the agent was made: each has its own number, with which it
    /// marks the firings it goes through (a nested episode must not take an outer one's
    /// marks, nor an earlier nested one's, for its own).
    pub backtraces_begun: u64,
    pub duplicates: u64,
    /// `chunk`'s counts since the last `init-soar` (9.6 resets them there): chunks,
    /// justifications, and learning episodes that got as far as building either.
    pub chunks_since_init: u64,
    pub justifications_since_init: u64,
    pub substates_analyzed: u64,
    /// The other counts of `chunk stats`, cleared by `init-soar` with those above.
    pub stats: stats::ChunkStats,
    /// `init-soar` calls so far (chunk names after one carry the count).
    pub init_count: u64,
    /// States marked by `force-learn` / `dont-learn` (for `chunk only` / `except`), in the
    /// order they were marked (`chunk` lists them newest first).
    pub force_learn: indexmap::IndexSet<Sym>,
    pub dont_learn: indexmap::IndexSet<Sym>,
    /// Live justifications, by serial.
    pub justifications: Vec<Justification>,
    /// The justifications that test each WME (by handle and timetag): a removal retracts them.
    pub justified_by_wme: FxHashMap<(WmeId, u64), Vec<(InstId, u64)>>,
    /// The WMEs each live justification is listed under in `justified_by_wme`, by serial.
    pub grounds_of: FxHashMap<u64, Vec<(WmeId, u64)>>,
    /// Emptied lists of `justified_by_wme`, kept for their room.
    pub spare_justified: Vec<Vec<(InstId, u64)>>,
    /// Emptied lists of `grounds_of`, kept for their room.
    pub spare_grounds: Vec<Vec<(WmeId, u64)>>,
    /// The superstate negations of live justifications: a new WME that matches one
    /// retracts it.
    pub negations: negations::WatchedNegations,
    pub next_serial: u64,
    /// Retracted justifications kept by o-supported preferences: how many of those are
    /// still in preference memory, by serial.
    pub held_prefs: FxHashMap<u64, u32>,
    /// `explain`'s settings and records.
    pub explainer: explain::Explainer,
    /// The architecture's firings behind memory retrievals in substates, by the timetag
    /// of each WME they made (see `memory_results.rs`).
    pub memory_results: FxHashMap<u64, (WmeId, Arc<PrefOrigin>)>,
}

impl LearnState {
    /// `init-soar`: justifications go with working memory; chunks and their counters stay.
    pub fn reset_for_init(&mut self) {
        self.init_count += 1;
        self.justification_counter = 0;
        self.chunk_name_dc = 0;
        self.chunk_name_count = 0;
        self.justification_name_dc = 0;
        self.justification_name_count = 0;
        self.justifications.clear();
        self.justification_names.clear();
        self.justified_by_wme.clear();
        self.grounds_of.clear();
        self.held_prefs.clear();
        self.negations.clear();
        self.force_learn.clear();
        self.dont_learn.clear();
        self.chunks_this_phase = 0;
        self.dupes_this_phase.clear();
        self.chunks_since_init = 0;
        self.justifications_since_init = 0;
        self.substates_analyzed = 0;
        self.stats = stats::ChunkStats::default();
        self.explainer.reset_for_init();
        self.memory_results.clear();
    }

    /// Fresh identities for `n` variables: the first of them.
    pub fn new_idents(&mut self, n: usize) -> Ident {
        let first = self.next_ident + 1;
        self.next_ident += n as u64;
        first
    }
}
