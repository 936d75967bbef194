//! The decider's memory (spec §3): instantiations, preferences, slots and the goal stack.

use super::procedure::PrefType;
use crate::rete::{ProdId, TokId};
use crate::symbols::Sym;
use crate::wm::WmeId;
use rustc_hash::{FxHashMap, FxHashSet};

pub type InstId = u32;
pub type PrefId = u32;

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
    /// backtracing (spec §4).
    pub origin: Option<std::sync::Arc<crate::learn::PrefOrigin>>,
}

/// All preferences for one (id, attr), oldest first (Soar's list read from its tail), and the
/// WMEs they support.
#[derive(Debug, Clone, Default)]
pub struct Slot {
    /// Change it only through [`Slot::push`], [`Slot::remove`] and [`Slot::remove_value`],
    /// which keep `by_value` in step.
    pub prefs: Vec<PrefId>,
    /// Value (and acceptable flag) to the WME that shows it.
    pub wmes: FxHashMap<(Sym, bool), WmeId>,
    /// The same preferences by value, each list oldest first: one slot can hold thousands
    /// of values, and the questions about one WME concern only its value's preferences.
    by_value: FxHashMap<Sym, Vec<PrefId>>,
}

impl Slot {
    pub fn push(&mut self, pid: PrefId, value: Sym) {
        self.prefs.push(pid);
        self.by_value.entry(value).or_default().push(pid);
    }

    /// Takes one preference out (the newest occurrence); false if it was not there.
    pub fn remove(&mut self, pid: PrefId, value: Sym) -> bool {
        let Some(pos) = self.prefs.iter().rposition(|x| *x == pid) else {
            return false;
        };
        self.prefs.remove(pos);
        if let Some(list) = self.by_value.get_mut(&value) {
            if let Some(i) = list.iter().rposition(|x| *x == pid) {
                list.remove(i);
            }
            if list.is_empty() {
                self.by_value.remove(&value);
            }
        }
        true
    }

    /// Takes out every preference for `value`, returning them oldest first.
    pub fn remove_value(&mut self, value: Sym) -> Vec<PrefId> {
        let gone = self.by_value.remove(&value).unwrap_or_default();
        if !gone.is_empty() {
            self.prefs.retain(|x| !gone.contains(x));
        }
        gone
    }

    /// The preferences for one value, oldest first (the order of `prefs`).
    pub fn prefs_for(&self, value: Sym) -> &[PrefId] {
        self.by_value.get(&value).map_or(&[], Vec::as_slice)
    }
}

/// The slots by (id, attribute), and each identifier's attributes that have one, so that
/// the slots of one identifier are found without a scan of them all (a substate's slots
/// when it goes, a result's objects when they move up).
#[derive(Debug, Default)]
pub struct Slots {
    map: FxHashMap<(Sym, Sym), Slot>,
    attrs: FxHashMap<Sym, Vec<Sym>>,
}

impl Slots {
    pub fn get(&self, key: &(Sym, Sym)) -> Option<&Slot> {
        self.map.get(key)
    }

    pub fn get_mut(&mut self, key: &(Sym, Sym)) -> Option<&mut Slot> {
        self.map.get_mut(key)
    }

    /// The slot, made empty if there was none.
    pub fn entry(&mut self, key: (Sym, Sym)) -> &mut Slot {
        self.map.entry(key).or_insert_with(|| {
            self.attrs.entry(key.0).or_default().push(key.1);
            Slot::default()
        })
    }

    pub fn remove(&mut self, key: &(Sym, Sym)) -> Option<Slot> {
        let slot = self.map.remove(key)?;
        if let Some(list) = self.attrs.get_mut(&key.0) {
            if let Some(i) = list.iter().position(|a| *a == key.1) {
                list.remove(i);
            }
            if list.is_empty() {
                self.attrs.remove(&key.0);
            }
        }
        Some(slot)
    }

    /// The keys of `id`'s slots, in the order they were made.
    pub fn keys_of(&self, id: Sym) -> Vec<(Sym, Sym)> {
        self.attrs
            .get(&id)
            .map_or_else(Vec::new, |l| l.iter().map(|&a| (id, a)).collect())
    }
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
    /// The operator slot's preferences changed since it was last decided (spec §3e).
    pub slot_changed: bool,
}

/// The phases of a decision cycle (spec §3a).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    Input,
    Propose,
    Decide,
    Apply,
    Output,
}

#[derive(Debug, Default)]
pub struct DecideState {
    pub insts: Vec<Instantiation>,
    pub inst_by_token: FxHashMap<(ProdId, TokId), InstId>,
    pub prefs: Vec<Preference>,
    pub slots: Slots,
    /// Slots whose preferences changed in this elaboration cycle, in order of change.
    pub changed: Vec<(Sym, Sym)>,
    /// The same slots as a set, for a constant-time "already marked?".
    pub changed_set: FxHashSet<(Sym, Sym)>,
    pub goals: Vec<Goal>,
    pub phase: Option<Phase>,
    /// The propose phase has begun (its elaboration count is reset once, at its start).
    pub phase_started: bool,
    pub d_cycle_count: u64,
    pub decisions: u64,
    pub e_cycles: u64,
    pub e_cycles_this_phase: u64,
    pub firings: u64,
    /// Firings per rule, by rule id.
    pub firing_counts: Vec<u64>,
    pub halted: bool,
    pub stop_requested: bool,
    /// The top goal's operator slot changed since the last decision, per goal.
    pub context_changed: bool,
    pub wme_changes: u64,
    /// Statistics for `stats` (spec §6a): elaboration cycles that fired o-supported rules
    /// (9.6's p-elaboration cycles), the WM additions and removals counted before this
    /// decider started (`WorkingMemory` counts from agent creation; init-soar restarts
    /// the count, and the new top state's 13 WMEs count again), WM size samples, and
    /// the time spent in each phase (Input, Propose, Decide, Apply, Output) and in the
    /// input and output callbacks.
    pub pe_cycles: u64,
    pub wm_base: (u64, u64),
    pub wm_size_sum: u64,
    pub wm_size_samples: u64,
    pub wm_size_max: u64,
    pub phase_time: [std::time::Duration; 5],
    pub input_fn_time: std::time::Duration,
    pub output_fn_time: std::time::Duration,
    /// Identifiers that lost a link (or a goal) since the last garbage collection.
    pub gc_candidates: Vec<Sym>,
    /// Each WME in a goal dependency set, with the highest goal that depends on it (§3f).
    pub gds: FxHashMap<WmeId, Sym>,
    /// Goals whose GDS lost a WME, to be removed after the current WM changes.
    pub gds_invalid: Vec<Sym>,
    /// Retracted instantiations and dead preferences, for reuse (a long run must not grow).
    pub free_insts: Vec<InstId>,
    pub free_prefs: Vec<PrefId>,
    /// Justifications whose conditions lost a WME, retracted in the next elaboration cycle.
    pub justification_retractions: Vec<(InstId, u64)>,
    /// Rules' actions compiled for firing, by rule id (built at a rule's first firing).
    pub(crate) compiled: Vec<Option<std::rc::Rc<super::compiled::CompiledRule>>>,
    /// Scratch for firing: the WMEs of the match, by token depth.
    pub(crate) rhs_wmes: Vec<WmeId>,
}

impl DecideState {
    /// A fresh decider: the first decision cycle is number 1 (spec §3a).
    pub fn new() -> Self {
        DecideState {
            d_cycle_count: 1,
            ..Default::default()
        }
    }

    pub fn alloc_inst(&mut self, inst: Instantiation) -> InstId {
        match self.free_insts.pop() {
            Some(i) => {
                self.insts[i as usize] = inst;
                i
            }
            None => {
                self.insts.push(inst);
                (self.insts.len() - 1) as InstId
            }
        }
    }

    pub fn alloc_pref(&mut self, pref: Preference) -> PrefId {
        match self.free_prefs.pop() {
            Some(i) => {
                self.prefs[i as usize] = pref;
                i
            }
            None => {
                self.prefs.push(pref);
                (self.prefs.len() - 1) as PrefId
            }
        }
    }

    /// A slot with no preferences and no WMEs is forgotten (new identifiers keep coming;
    /// their slots must not pile up).
    pub fn drop_slot_if_empty(&mut self, key: (Sym, Sym)) {
        if self
            .slots
            .get(&key)
            .is_some_and(|s| s.prefs.is_empty() && s.wmes.is_empty())
        {
            self.slots.remove(&key);
        }
    }

    /// Frees a retracted instantiation (nothing refers to it any more).
    pub fn free_inst(&mut self, i: InstId) {
        let inst = &mut self.insts[i as usize];
        inst.alive = false;
        inst.prefs = Vec::new();
        inst.serial = 0;
        self.free_insts.push(i);
    }

    /// Frees a preference already out of its slot: it leaves its instantiation's list too.
    pub fn free_pref(&mut self, pid: PrefId) {
        let pref = &mut self.prefs[pid as usize];
        if pref.freed {
            return;
        }
        pref.freed = true;
        pref.alive = false;
        pref.origin = None;
        if let Some(i) = pref.inst.take() {
            let inst = &mut self.insts[i as usize];
            if let Some(pos) = inst.prefs.iter().position(|x| *x == pid) {
                inst.prefs.remove(pos);
            }
        }
        self.free_prefs.push(pid);
    }
}
