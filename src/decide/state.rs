//! The decider's memory: instantiations, preferences, slots and the goal stack.

pub use super::ids::{InstId, PrefId};
use super::procedure::PrefType;
pub use super::slot::{Slot, Slots};
use crate::rete::small_list::SmallList;
use crate::rete::{ProdId, TokId};
use crate::symbols::Sym;
use crate::wm::WmeId;
use rustc_hash::{FxHashMap, FxHashSet};

/// A state's WMEs that the architecture makes (9.6's impasse WMEs, kept out of slots).
pub(crate) const STATE_ARCH_ATTRS: [&str; 10] = [
    "type",
    "superstate",
    "attribute",
    "impasse",
    "choices",
    "quiescence",
    "item",
    "item-count",
    "non-numeric",
    "non-numeric-count",
];

/// The memories' link WMEs on a state, which 9.6 puts in slots of their own (without
/// preferences), oldest first.
pub(crate) const STATE_MODULE_ATTRS: [&str; 3] = ["reward-link", "epmem", "smem"];

crate::ids::id_type!(index InstId => Instantiation);
crate::ids::id_type!(index PrefId => Preference);

/// A fired rule: the match it fired on and the preferences it made.
#[derive(Debug, Clone)]
pub struct Instantiation {
    pub prod: ProdId,
    pub token: TokId,
    pub goal: Option<Sym>,
    pub o_support: bool,
    pub prefs: Vec<PrefId>,
    pub alive: bool,
    /// A learned rule's instantiation not matched by the network (a justification): its
    /// serial in the learner's list; 0 for rule firings.
    pub serial: u64,
    /// A goal dependency set's walk went through this firing (see `gds.rs`): no walk goes
    /// through it again (9.6's `GDS_evaluated_already`).
    pub gds_evaluated: bool,
}

#[derive(Debug, Clone)]
pub struct Preference {
    pub kind: PrefType,
    pub id: Sym,
    pub attr: Sym,
    pub value: Sym,
    pub referent: Option<Sym>,
    pub number: Option<f64>,
    pub o_support: bool,
    pub inst: Option<InstId>,
    /// The rule whose firing made it, kept when an o-supported preference outlives its
    /// instantiation (the level-5 trace names it).
    pub rule: Option<ProdId>,
    pub alive: bool,
    /// On the free list (guards against freeing twice).
    pub freed: bool,
    /// For a preference made in a substate: the firing and identities that made it, for
    /// backtracing (chunking and justifications).
    pub origin: Option<std::sync::Arc<crate::learn::PrefOrigin>>,
    /// For an o-supported preference made on the top level: the WMEs its firing matched,
    /// which `preferences --timetags`/`--wmes` lists after the firing has retracted.
    pub matched: Option<std::sync::Arc<[crate::wm::Wme]>>,
    /// Made by a memory's retrieval (9.6's `|Memory System Recall|` instantiation): no
    /// rule's firing holds it; the memory removes it when its next command comes.
    pub recall: bool,
    /// Filed in [`DecideState::pref_links`] (its value or referent is an identifier and it
    /// is in its slot).
    pub links_filed: bool,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImpasseKind {
    Tie,
    Conflict,
    ConstraintFailure,
    NoChange,
}

impl ImpasseKind {
    pub fn word(self) -> &'static str {
        match self {
            ImpasseKind::Tie => "tie",
            ImpasseKind::Conflict => "conflict",
            ImpasseKind::ConstraintFailure => "constraint-failure",
            ImpasseKind::NoChange => "no-change",
        }
    }
}

/// A memory's recall preference (see `recall.rs`): its handle with its allocation number
/// (handles are reused: a preference freed with its slot leaves a handle another may take).
pub(crate) type RecallPref = (PrefId, u64);

/// A preference a goal's firing made: its handle, its allocation number (handles are
/// reused) and what it says.
pub type MadePref = (PrefId, u64, (Sym, Sym, Sym));

/// A goal's firings' preferences, oldest first.
pub type MadePrefs = Vec<MadePref>;

/// One state in the goal stack.
#[derive(Debug, Clone)]
pub struct Goal {
    pub state: Sym,
    pub level: u32,
    /// The selected operator and the WME `(state ^operator O)` that shows it.
    pub operator: Option<(Sym, WmeId)>,
    /// For substates: the impasse that made them (`^attribute` is operator when true).
    pub impasse: Option<(ImpasseKind, bool)>,
    pub items: Vec<Sym>,
    /// The architecture's WMEs on this state (removed with it).
    pub wmes: Vec<WmeId>,
    /// The operator slot's preferences changed since it was last decided.
    pub slot_changed: bool,
    /// The preferences its firings made, oldest first, with each one's allocation number
    /// (handles are reused) and what it says: 9.6 lists the standing ones as removed when
    /// the state goes (trace 5).
    pub made: MadePrefs,
    /// A state below this one learned a rule: with `chunk bottom-only`, this one learns no
    /// more while it lasts.
    pub learned_below: bool,
    /// The operator selection knowledge of the last decision that selected this state's
    /// operator (`chunk add-osk`, see `osk.rs`): the origins of the preferences it rests on.
    pub osk: Option<crate::learn::Osk>,
}

/// Where a removed substate's WME goes in a phase's `<=WM:` listing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum SubstateLine {
    /// The `^smem`/`^epmem`/`^reward-link` structure, with the cues and retrievals that
    /// go with it.
    Memories,
    /// Its slots' other WMEs.
    Other,
    /// Its operators' `+` WMEs.
    OperatorPlus,
    /// `^type`, `^superstate`, `^impasse` and the other impasse WMEs.
    Impasse,
    /// Its selected operator.
    Selected,
}

/// The phases of a decision cycle (Soar manual, chapter 2, "Soar's Execution Cycle: Without
/// Substates").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// The environment writes the input-link; its changes reach working memory.
    Input,
    /// Elaborations and operator proposals fire until quiescence.
    Propose,
    /// The decision procedure selects an operator, or an impasse makes a substate.
    Decide,
    /// The selected operator is applied, until quiescence.
    Apply,
    /// The environment reads the output-link.
    Output,
}

/// A WME's place in a goal dependency set.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GdsMember {
    /// The highest goal that depends on the WME.
    pub goal: Sym,
    /// When it joined (a count of joins): `print --gds` lists a set newest member first,
    /// as 9.6 does.
    pub joined: u64,
}

#[derive(Debug, Default)]
pub struct DecideState {
    pub insts: Vec<Instantiation>,
    pub inst_by_token: super::by_token::ByToken<InstId>,
    pub prefs: Vec<Preference>,
    pub slots: Slots,
    /// Slots whose preferences changed in this elaboration cycle, in order of change, with
    /// their generations (a slot that went since is passed over); `Slot::changed` marks
    /// them.
    pub changed: Vec<(super::slot::SlotId, u32)>,
    pub goals: Vec<Goal>,
    pub phase: Option<Phase>,
    /// The propose phase has begun (its elaboration count is reset once, at its start).
    pub phase_started: bool,
    pub d_cycle_count: u64,
    pub decisions: u64,
    pub e_cycles: u64,
    pub e_cycles_this_phase: u64,
    /// Passes of the waterfall over a goal level, one per `Inner Elaboration Phase` header
    /// (9.6's `stats` counts these as "inner elaboration cycles": soar-sml 9.6.5 gives as
    /// many as its trace 3 prints headers, on every agent in tests/agents).
    pub inner_e_cycles: u64,
    pub firings: u64,
    /// Firings per rule, by rule id.
    pub firing_counts: Vec<u64>,
    pub halted: bool,
    pub stop_requested: bool,
    /// A no-change went past `max-goal-depth` in this run: the run stops, interrupted, and
    /// the agent is not halted.
    pub depth_exceeded: bool,
    /// A rule called `(interrupt)` in this run: the run stops after the phase.
    pub rhs_interrupted: bool,
    /// The ceiling (`limits`) this run met, if any: the run stops.
    pub(crate) ceiling: Option<super::limits::Ceiling>,
    /// `run -g`: the level of the lowest goal when the run began. The removal of a goal
    /// at this level or above stops the run after the phase (and clears this).
    pub goal_break_level: Option<u32>,
    /// A goal at or above `goal_break_level` was removed in this run.
    pub goal_retracted: bool,
    /// A rule with a break (`production break`) matched in this run: it stops after the
    /// phase.
    pub break_interrupted: bool,
    /// `decide select`: the operator the next decision takes when it is proposed, as
    /// typed with its first letter upper-cased (9.6 compares the text).
    pub(crate) forced_operator: Option<String>,
    /// The WMEs a traced firing listed (`trace --timetags`, `--fullwmes`), by
    /// instantiation: its retraction lists them again, after its match is gone.
    pub(crate) traced_match_wmes: FxHashMap<InstId, Vec<crate::wm::Wme>>,
    /// `decide predict` seeded the generator with this before predicting: the next
    /// decision seeds it the same way, so that it makes the predicted choice.
    pub(crate) predict_seed: Option<u32>,
    pub wme_changes: u64,
    /// Statistics for `stats`: elaboration cycles that fired o-supported rules (9.6's
    /// p-elaboration cycles), the WM additions and removals counted before this decider
    /// started (`WorkingMemory` counts from agent creation; init-soar restarts the count,
    /// and the new top state's 13 WMEs count again), WM size samples, and the time spent in
    /// each phase (Input, Propose, Decide, Apply, Output) and in the input and output
    /// callbacks.
    pub pe_cycles: u64,
    /// The last wave of firings was of o-supported rules (9.6's `FIRING_TYPE`): set at
    /// each elaboration cycle, and for the apply phase as it begins. The memories' results
    /// take their support from it.
    pub last_wave_o_support: bool,
    /// Where in the print stream the next `RETE: putting` lines go (`trace
    /// --assertions`): before the `=>WM:` lines of the changes that made the matches.
    pub queued_matches_at: Option<usize>,
    /// The instantiations an elaboration cycle's goal level made, oldest first, each with
    /// where its preferences start among the new ones (`trace --assertions` only).
    pub instantiations_made: Vec<(String, usize)>,
    pub wm_base: (u64, u64),
    pub wm_size_sum: u64,
    pub wm_size_samples: u64,
    pub wm_size_max: u64,
    pub phase_time: [std::time::Duration; 5],
    /// During a run, when the last phase ended: the next phase starts then, so a phase
    /// costs one clock read (none between runs, so that the time between them counts
    /// for no phase).
    pub phase_clock: Option<std::time::Instant>,
    pub input_fn_time: std::time::Duration,
    pub output_fn_time: std::time::Duration,
    /// Each decision cycle's time, WM changes and firings (`stats --max`, `--track`).
    pub cycle_stats: super::cycle_stats::CycleStats,
    /// Identifiers that lost a link (or a goal) since the last garbage collection.
    pub gc_candidates: Vec<Sym>,
    /// The preferences in their slots whose value (or binary referent) is an identifier,
    /// by that identifier: 9.6 counts them as links to the object, as it counts WMEs, so
    /// an object only a preference points at stays in working memory (garbage collection,
    /// `gc.rs`). A preference leaves these lists as it leaves its slot or is freed.
    pub(crate) pref_links: FxHashMap<Sym, SmallList<PrefId>>,
    /// Preferences a removed substate's trace has just listed as gone (`trace -r`): the
    /// garbage collection after it does not list them again.
    pub(crate) prefs_traced_gone: Vec<PrefId>,
    /// WMEs (by timetag) a removed substate's trace has just listed as gone: the garbage
    /// collection after it does not list them again.
    pub(crate) wmes_traced_gone: Vec<u64>,
    /// Substate preferences whose result copy (with its justification's support) is an
    /// o-supported reject: in 9.6 the result itself becomes that o-reject, so the original
    /// is neither traced nor asserted.
    pub(crate) results_taken_by_o_rejects: Vec<PrefId>,
    pub(crate) gc_scratch: super::scratch::GcScratch,
    pub(crate) cycle_scratch: super::scratch::CycleScratch,
    pub(crate) slot_scratch: super::scratch::SlotScratch,
    /// Emptied preference lists of freed instantiations, for the next firings.
    pub spare_pref_lists: Vec<Vec<PrefId>>,
    /// The identifiers a firing's actions make, by new-variable slot (scratch).
    pub rhs_new_ids: Vec<Option<Sym>>,
    /// A substate firing's preferences with the actions that made them (scratch).
    pub rhs_made: Vec<(PrefId, usize)>,
    /// A firing's own preferences, kept for its trace and its results (scratch).
    pub rhs_own_prefs: Vec<PrefId>,
    /// Emptied lists of removed goals' preferences, for new goals to reuse.
    pub spare_goal_made: Vec<MadePrefs>,
    /// Each WME in a goal dependency set, with its place there.
    pub gds: FxHashMap<WmeId, GdsMember>,
    /// Joins to goal dependency sets so far (each member's [`GdsMember::joined`]).
    pub gds_joins: u64,
    /// WMEs still in the set of a goal that is gone, until they leave working memory or
    /// join another set: 9.6 keeps such a set and `print --gds` lists them as old values.
    /// They are in no set as far as the goal dependency set goes.
    pub gds_orphans: FxHashSet<WmeId>,
    /// Garbage collection is taking WMEs out (9.6 checks no goal dependency set then).
    pub collecting_garbage: bool,
    /// The goals with a goal dependency set, with the number of WMEs in it.
    pub gds_sizes: FxHashMap<Sym, u32>,
    /// The firings a goal dependency set's walk has still to go through, and those it
    /// found for its next round (kept for their room).
    pub gds_parents: Vec<InstId>,
    pub gds_found: Vec<InstId>,
    /// Goals whose GDS lost a WME, to be removed after the current WM changes.
    pub gds_invalid: Vec<Sym>,
    /// Operator slots changed since the last quiescent working-memory phase: their
    /// impasses are checked for consistency at the next one (9.6 keeps a slot's changed
    /// flag until it is checked).
    pub consistency_pending: Vec<(Sym, Sym)>,
    /// The WMEs of an o-supported firing's match, gathered before they are recorded.
    pub matched_scratch: Vec<crate::wm::Wme>,
    /// The preferences an o-supported reject takes out, kept for its room.
    pub o_reject_removed: Vec<PrefId>,
    /// A consistency check found a goal's decision inconsistent and removed what was below
    /// it: the propose or apply phase ends with the elaboration cycle, for the decision
    /// procedure to run again (9.6's `determine_highest_active_production_level`).
    pub decision_inconsistent: bool,
    /// Impasse WMEs the decision phase added and removed to bring an impasse's items up to
    /// date, in that order: they reach the trace and the matcher with the phase's other
    /// changes (see `update_impasse_items`).
    pub(crate) item_updates: (Vec<WmeId>, Vec<WmeId>),
    /// Retracted instantiations and dead preferences, for reuse (a long run must not grow).
    pub free_insts: Vec<InstId>,
    pub free_prefs: Vec<PrefId>,
    /// Preferences freed, each with its allocation number, while `log_freed_prefs` is on
    /// (working-memory activation lets the sets they held go: `wma_release_holders`).
    pub freed_prefs_log: Vec<(PrefId, u64)>,
    pub log_freed_prefs: bool,
    /// Each preference handle's allocation number: a reused handle gets a new one, so
    /// what is kept about a preference (working-memory activation's o-sets) can tell it
    /// from the one that held the handle before.
    pub pref_serials: Vec<u64>,
    pub prefs_allocated: u64,
    /// Justifications whose conditions lost a WME, retracted in the next elaboration cycle.
    /// (instantiation, serial, place among the rule retractions it goes before: an
    /// index into `MatchSet::retractions`, `usize::MAX` after them all).
    pub justification_retractions: Vec<(InstId, u64, usize)>,
    /// The o-supported preferences that retracted justifications left in preference memory,
    /// with the justification's serial: the justification lives until they are all gone.
    pub held_by_justification: FxHashMap<PrefId, u64>,
    /// Serials of justifications that lost such a preference since it was last looked at.
    pub released_justification_prefs: Vec<u64>,
    /// Retractions of matches at a goal below the active one, waiting for a cycle in which
    /// their goal is the active goal, oldest first.
    pub waiting_retractions: Vec<InstId>,
    /// Rules' actions compiled for firing, by rule id (built at a rule's first firing).
    pub(crate) compiled: Vec<Option<std::rc::Rc<super::compiled::CompiledRule>>>,
    /// Scratch for firing: the WMEs of the match, by token depth.
    pub(crate) rhs_wmes: Vec<WmeId>,
    /// The arguments of a firing's RHS function calls, as a stack (nested calls above).
    pub(crate) rhs_args: Vec<Sym>,
}

impl DecideState {
    /// Files a preference that went into its slot under the identifiers it links to
    /// (`is_id` tells identifiers).
    pub(crate) fn note_pref_links(&mut self, pid: PrefId, is_id: impl Fn(Sym) -> bool) {
        let p = &self.prefs[pid];
        let mut filed = false;
        for s in [Some(p.value), p.referent].into_iter().flatten() {
            if is_id(s) {
                self.pref_links.entry(s).or_default().push(pid);
                filed = true;
            }
        }
        self.prefs[pid].links_filed = filed;
    }

    /// A preference left its slot (or was freed): it links to nothing any more.
    pub(crate) fn forget_pref_links(&mut self, pid: PrefId) {
        let p = &mut self.prefs[pid];
        if !std::mem::replace(&mut p.links_filed, false) {
            return;
        }
        for s in [Some(p.value), p.referent].into_iter().flatten() {
            if let Some(list) = self.pref_links.get_mut(&s) {
                list.retain(|&q| q != pid);
                if list.is_empty() {
                    self.pref_links.remove(&s);
                }
            }
        }
    }

    /// The preferences filed as linking to `x`.
    pub(crate) fn pref_link_parents(&self, x: Sym) -> &[PrefId] {
        self.pref_links.get(&x).map_or(&[], SmallList::as_slice)
    }

    /// The identifier of the `k`th preference filed as linking to `x`.
    pub(crate) fn pref_link_parent(&self, x: Sym, k: usize) -> Option<Sym> {
        let &pid = self.pref_links.get(&x)?.as_slice().get(k)?;
        Some(self.prefs[pid].id)
    }

    /// A fresh decider: the first decision cycle is number 1.
    pub fn new() -> Self {
        DecideState {
            d_cycle_count: 1,
            ..Default::default()
        }
    }

    /// An RL rule's compiled actions take its new value: in place, unless a firing holds
    /// them now, when the rule compiles again at its next firing.
    pub(crate) fn set_compiled_referent(&mut self, rule: crate::rete::ProdId, value: Sym) {
        use super::compiled::{Act, Term};
        let Some(entry) = self.compiled.get_mut(rule.0 as usize) else {
            return;
        };
        let edited = entry.as_mut().and_then(std::rc::Rc::get_mut).is_some_and(|c| {
            match c.actions.first_mut() {
                Some(Act::Make {
                    referent: Some(r), ..
                }) => {
                    *r = Term::Sym(value);
                    true
                }
                _ => false,
            }
        });
        if !edited {
            *entry = None;
        }
    }

    /// The preferences in preference memory (the ones freed aside).
    pub(crate) fn live_prefs(&self) -> usize {
        self.prefs.len() - self.free_prefs.len()
    }

    pub fn alloc_inst(&mut self, inst: Instantiation) -> InstId {
        match self.free_insts.pop() {
            Some(i) => {
                self.insts[i] = inst;
                i
            }
            None => {
                self.insts.push(inst);
                InstId::from_index(self.insts.len() - 1)
            }
        }
    }

    pub fn alloc_pref(&mut self, pref: Preference) -> PrefId {
        self.prefs_allocated += 1;
        match self.free_prefs.pop() {
            Some(i) => {
                self.prefs[i] = pref;
                self.pref_serials[i.index()] = self.prefs_allocated;
                i
            }
            None => {
                self.prefs.push(pref);
                self.pref_serials.push(self.prefs_allocated);
                PrefId::from_index(self.prefs.len() - 1)
            }
        }
    }

    /// The allocation number of the preference now holding handle `pid`.
    pub fn pref_serial(&self, pid: PrefId) -> u64 {
        self.pref_serials[pid.index()]
    }

    /// Frees a retracted instantiation (nothing refers to it any more).
    pub fn free_inst(&mut self, i: InstId) {
        if !self.traced_match_wmes.is_empty() {
            self.traced_match_wmes.remove(&i);
        }
        let inst = &mut self.insts[i];
        inst.alive = false;
        let mut list = std::mem::take(&mut inst.prefs);
        inst.serial = 0;
        self.free_insts.push(i);
        if self.spare_pref_lists.len() < 1024 && list.capacity() > 0 {
            list.clear();
            self.spare_pref_lists.push(list);
        }
    }

    /// Frees a preference already out of its slot: it leaves its instantiation's list too.
    pub fn free_pref(&mut self, pid: PrefId) {
        if self.prefs[pid].freed {
            return;
        }
        self.forget_pref_links(pid);
        let pref = &mut self.prefs[pid];
        pref.freed = true;
        pref.alive = false;
        pref.origin = None;
        pref.matched = None;
        if !self.held_by_justification.is_empty() {
            if let Some(serial) = self.held_by_justification.remove(&pid) {
                self.released_justification_prefs.push(serial);
            }
        }
        if let Some(i) = pref.inst.take() {
            let inst = &mut self.insts[i];
            if let Some(pos) = inst.prefs.iter().position(|x| *x == pid) {
                inst.prefs.remove(pos);
            }
        }
        if self.log_freed_prefs {
            self.freed_prefs_log.push((pid, self.pref_serials[pid.index()]));
        }
        self.free_prefs.push(pid);
    }
}

