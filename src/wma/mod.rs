//! Working-memory activation (Soar manual, ch. 8, "Working Memory Activation"; the `wm
//! activation` command of ch. 9): o-supported WMEs gain activation when rules that test
//! them fire and when they are created, lose it by base-level decay from decision to
//! decision, and, with forgetting on, leave working memory when it falls below the
//! threshold. Activation is off by default; every hook on the decision cycle checks
//! [`Wma::on`] first, so an agent without it pays one flag test.
//!
//! This module holds the state and its bookkeeping; `hooks.rs` connects it to the decision
//! cycle, `decay.rs` holds the decay arithmetic (shared with reinforcement learning's
//! apoptosis) and `params.rs` the settings.

mod addresses;
pub mod decay;
mod hooks;
pub mod params;
mod trace;

use decay::{DecayHistory, DecayModel};
use params::WmaParams;
use rustc_hash::FxHashMap;
use std::collections::{BTreeMap, BTreeSet};

use crate::decide::ids::PrefId;
use crate::symbols::Sym;
use crate::wm::WmeId;

/// 9.6's activation for a WME without a decay history (architectural and i-supported
/// WMEs): `wm activation` prints it as 1.
pub const ACTIVATION_NONE: f64 = 1.0;
/// The sum (before its log) 9.6 counts for such a WME when it averages activations: e.
pub const TIME_SUM_NONE: f64 = std::f64::consts::E;
/// 9.6's activation for a WME with a decay element but no reference recorded yet.
pub const ACTIVATION_LOW: f64 = -1_000_000_000.0;
/// The forgetting decision of an element created but not yet queued (9.6's `-1` as an
/// unsigned decision count).
const NOT_QUEUED: u64 = u64::MAX;
/// The forgetting decision of an element found below the threshold.
const FORGOTTEN: u64 = 0;

/// A substate firing that holds the WMEs it matched (see `Wma::firing_holds`).
#[derive(Debug, Clone)]
pub(crate) struct FiringHold {
    /// The instantiation, with its rule and match to tell a reused handle.
    pub inst: crate::decide::ids::InstId,
    pub prod: crate::rete::ProdId,
    pub token: crate::rete::TokId,
    /// Its preferences, each with its allocation number and `(id, attr, value)`.
    pub prefs: Vec<(PrefId, u64, (Sym, Sym, Sym))>,
    /// The WMEs held, by timetag.
    pub members: Vec<u64>,
}

/// An activation set (`o_set`) that holds its WMEs (see `Wma::holders`).
#[derive(Debug, Clone)]
pub(crate) struct Holder {
    /// The preference's `(id, attr, value)`: an operator proposal stays while its operator
    /// is selected.
    pub key: (Sym, Sym, Sym),
    /// The WMEs held, by timetag.
    pub members: Vec<u64>,
}

/// The decay element of one o-supported WME.
#[derive(Debug, Clone)]
pub(crate) struct Element {
    pub history: DecayHistory,
    /// References in the current decision, not yet recorded.
    pub buffered: u64,
    /// Created in the current decision: its references are not counted by the average
    /// that gives a new WME its first references.
    pub just_created: bool,
    /// Its WME left working memory in the current decision.
    pub removed: bool,
    /// The decision at which forgetting checks it next.
    pub forget_at: u64,
}

/// Working-memory activation: settings, statistics and the decay elements.
#[derive(Debug, Clone, Default)]
pub struct Wma {
    pub params: WmaParams,
    /// `forgotten-wmes`: WMEs forgetting removed.
    pub forgotten: u64,
    /// The decay's constants, built when activation turns on (9.6 builds its tables then,
    /// which is why their parameters are protected while it is on).
    model: Option<DecayModel>,
    /// Elements by their WME's timetag (handles are reused, timetags are not).
    elements: BTreeMap<u64, Element>,
    /// Elements referenced in the current decision, by timetag.
    touched: BTreeSet<u64>,
    /// The order of 9.6's WME addresses, for the `activate` lines of the WMA trace.
    pub(crate) addresses: addresses::AddressOrder,
    /// For an i-supported preference, by its handle and allocation number: the
    /// o-supported and architectural WMEs its support rests on, found once, at its first
    /// reference (9.6's `wma_o_set`). The set holds its members: 9.6 frees a WME only when
    /// nothing holds it, and a preference's set holds them until the preference is freed
    /// (see `wma_release_holders`).
    pub(crate) holders: FxHashMap<(PrefId, u64), Holder>,
    /// The activation sets of memory results that left working memory, to let go at the
    /// next release.
    pub(crate) released_memory_sets: Vec<Vec<u64>>,
    /// Holders whose preference is freed but whose operator is still selected.
    pub(crate) waiting_holders: Vec<(PrefId, u64)>,
    /// Substate firings, each holding the WMEs it matched (9.6 keeps them with the
    /// instantiation until it is retracted and its preferences are gone).
    pub(crate) firing_holds: Vec<FiringHold>,
    /// How many activation sets and firings hold each WME, by timetag.
    pub(crate) holds: FxHashMap<u64, u32>,
    /// WMEs out of working memory that a set still holds: their elements stay (and can be
    /// referenced) until the last holder goes, when the trace prints their `remove` line.
    pub(crate) held_out: rustc_hash::FxHashSet<u64>,
    /// Elements by the decision at which forgetting checks them.
    queue: BTreeMap<u64, BTreeSet<u64>>,
    /// References to values of non-context slots made before the value's WME exists, by
    /// slot, then value: the WME starts with them (9.6's `wma_val_references`).
    val_refs: FxHashMap<(Sym, Sym), FxHashMap<Sym, u64>>,
    /// For a WME of a non-context slot: the preference its slot's last decision gave it
    /// (9.6's `w->preference`, set whenever the slot is decided). References made before
    /// the slot is decided again, as by a new preference for the same value, go through
    /// it, not through the newer preference.
    pub(crate) decided: FxHashMap<u64, PrefId>,
    /// With the WMA trace on: WMEs whose `remove` line waits for their `<=WM:` line.
    pub(crate) removal_lines: Vec<u64>,
    /// An i-supported result of a memory (semantic or episodic), by timetag: the WMEs,
    /// with their timetags, of the architecture's firing that made it, and the o-set found
    /// at its first reference (9.6 makes such results through an instantiation of its own
    /// and gives them its preference's o-set).
    pub(crate) memory_results: FxHashMap<u64, MemoryResult>,
    /// Elements of WMEs that left working memory in this decision: kept until it ends, so
    /// that the `<=WM:` lines still show their activation.
    removed: Vec<u64>,
    /// The last decision whose references are in the histories: from then on the clock
    /// activations are read at is the next decision (9.6 moves its own clock there).
    recorded: Option<u64>,
}

/// What activation keeps about an i-supported memory result.
#[derive(Debug, Clone, Default)]
pub(crate) struct MemoryResult {
    /// The WMEs the result's firing tested, with their timetags then.
    pub(crate) conditions: Vec<(WmeId, u64)>,
    /// The o-supported and architectural WMEs its support rests on, once referenced.
    pub(crate) o_set: Option<Vec<u64>>,
}

impl Wma {
    /// The decision activations are read at during decision `d`: `d`, or `d + 1` once the
    /// decision's references are recorded.
    pub(crate) fn clock(&self, d: u64) -> u64 {
        if self.recorded == Some(d) {
            d + 1
        } else {
            d
        }
    }

    /// Whether activation is on: the one check every hook makes first.
    #[inline]
    pub fn on(&self) -> bool {
        self.params.activation
    }

    /// A set or firing holds these WMEs (by timetag), each once more.
    pub(crate) fn hold(&mut self, members: &[u64]) {
        for &tt in members {
            *self.holds.entry(tt).or_insert(0) += 1;
        }
    }

    /// The WME `timetag` left working memory while `next_timetag` was the next to be
    /// made: its place is free for the next WME, unless a set still holds it (its place
    /// goes when the last holder lets it go).
    pub(crate) fn address_freed(&mut self, timetag: u64, next_timetag: u64) {
        if !self.held_out.contains(&timetag) {
            self.addresses.freed(timetag, next_timetag);
        }
    }

    /// Builds or drops the decay tables as activation turns on or off (9.6's `wma_init`
    /// and `wma_deinit`).
    pub fn sync(&mut self) {
        if self.params.activation {
            if self.model.is_none() {
                let p = &self.params;
                self.model = Some(DecayModel::new(
                    -p.decay_rate,
                    p.decay_thresh,
                    p.petrov_approx,
                    p.forgetting == params::Forgetting::Approx,
                ));
            }
        } else if self.model.is_some() {
            self.model = None;
            self.clear_elements();
        }
    }

    /// Drops every element and what is kept about them.
    fn clear_elements(&mut self) {
        self.elements.clear();
        self.touched.clear();
        self.queue.clear();
        self.val_refs.clear();
        self.memory_results.clear();
        self.decided.clear();
        self.removal_lines.clear();
        self.removed.clear();
        // (Working memory starts again, or is no longer followed: the places start afresh.)
        self.addresses = Default::default();
        self.holders.clear();
        self.waiting_holders.clear();
        self.released_memory_sets.clear();
        self.firing_holds.clear();
        self.holds.clear();
        self.held_out.clear();
    }

    /// `init-soar`: working memory goes, and with it every element; the count of
    /// forgotten WMEs starts again.
    pub fn reinitialize(&mut self) {
        self.clear_elements();
        self.forgotten = 0;
        self.recorded = None;
    }

    pub(crate) fn element(&self, timetag: u64) -> Option<&Element> {
        self.elements.get(&timetag)
    }

    /// The activation `print --internal` and the WME trace show: the log of the decayed
    /// sum at decision `now`.
    pub fn activation(&self, timetag: u64, now: u64) -> f64 {
        let (Some(el), Some(model)) = (self.elements.get(&timetag), &self.model) else {
            return ACTIVATION_NONE;
        };
        if el.history.is_empty() {
            return ACTIVATION_LOW;
        }
        let sum = model.sum(&el.history, now);
        if sum > 0.0 {
            sum.ln()
        } else {
            ACTIVATION_LOW
        }
    }

    /// The decayed sum of an element at `now` (TIME_SUM_NONE without one), as the average
    /// of a new WME's first references counts it.
    pub(crate) fn time_sum(&self, timetag: u64, now: u64) -> f64 {
        match (self.elements.get(&timetag), &self.model) {
            (Some(el), Some(model)) if !el.history.is_empty() => model.sum(&el.history, now),
            (Some(_), _) => 0.0,
            _ => TIME_SUM_NONE,
        }
    }

    /// Adds `n` references to an element in the current decision.
    pub(crate) fn reference(&mut self, timetag: u64, n: u64) -> bool {
        match self.elements.get_mut(&timetag) {
            Some(el) if el.removed => true,
            Some(el) => {
                el.buffered += n;
                self.touched.insert(timetag);
                true
            }
            None => false,
        }
    }

    /// Gives a WME a decay element with `boost` references to start with.
    pub(crate) fn create(&mut self, timetag: u64, boost: u64) {
        self.elements.insert(
            timetag,
            Element {
                history: DecayHistory::new(),
                buffered: boost,
                just_created: true,
                removed: false,
                forget_at: NOT_QUEUED,
            },
        );
    }

    /// A WME left working memory: its element is no longer referenced or checked, and
    /// goes when the decision ends.
    pub(crate) fn remove(&mut self, timetag: u64) {
        let Some(el) = self.elements.get_mut(&timetag) else {
            return;
        };
        if el.removed {
            return;
        }
        el.removed = true;
        let at = el.forget_at;
        self.touched.remove(&timetag);
        self.unqueue(timetag, at);
        self.removed.push(timetag);
    }

    /// Drops the elements of WMEs removed since the last call.
    pub(crate) fn purge_removed(&mut self) {
        for tt in std::mem::take(&mut self.removed) {
            if self.elements.get(&tt).is_some_and(|e| e.removed) {
                self.elements.remove(&tt);
            }
        }
    }

    /// A preference for `(id, attr, value)` joined a non-context slot without that WME.
    pub(crate) fn value_reference(&mut self, (id, attr, value): (Sym, Sym, Sym)) {
        *self
            .val_refs
            .entry((id, attr))
            .or_default()
            .entry(value)
            .or_insert(0) += 1;
    }

    /// The references made to a value before its WME existed.
    pub(crate) fn take_value_references(&mut self, (id, attr, value): (Sym, Sym, Sym)) -> Option<u64> {
        let refs = self.val_refs.get_mut(&(id, attr))?;
        let n = refs.remove(&value);
        if refs.is_empty() {
            self.val_refs.remove(&(id, attr));
        }
        n
    }

    /// A preference joined a slot that no change had marked since its last decision: the
    /// references its values collected then, for WMEs that never came, are dropped
    /// (9.6's `add_preference_to_tm`).
    pub(crate) fn clear_slot_references(&mut self, slot: (Sym, Sym)) {
        if !self.val_refs.is_empty() {
            self.val_refs.remove(&slot);
        }
    }

    fn unqueue(&mut self, timetag: u64, at: u64) {
        if let Some(set) = self.queue.get_mut(&at) {
            set.remove(&timetag);
            if set.is_empty() {
                self.queue.remove(&at);
            }
        }
    }

    fn requeue(&mut self, timetag: u64, at: u64) {
        let Some(old) = self.elements.get(&timetag).map(|e| e.forget_at) else {
            return;
        };
        if old == at {
            return;
        }
        self.unqueue(timetag, old);
        self.queue.entry(at).or_default().insert(timetag);
        if let Some(el) = self.elements.get_mut(&timetag) {
            el.forget_at = at;
        }
    }

    /// Records the current decision's references (9.6's `wma_update_decay_histories`)
    /// and, with queued forgetting, predicts each referenced element's decision.
    /// With `counts`, each element's references in the decision are listed there.
    pub(crate) fn record_decision(&mut self, now: u64, mut counts: Option<&mut Vec<(u64, u64)>>) {
        let queued = self.params.forgetting.queued();
        self.recorded = Some(now);
        for tt in std::mem::take(&mut self.touched) {
            let Some(el) = self.elements.get_mut(&tt) else {
                continue;
            };
            let n = std::mem::take(&mut el.buffered);
            if let Some(c) = counts.as_mut() {
                c.push((tt, n));
            }
            el.history.record(n, now);
            el.just_created = false;
            if queued {
                if let Some(model) = &self.model {
                    let at = model.forgetting_time(&el.history, now, true);
                    self.requeue(tt, at);
                }
            }
        }
    }

    /// The elements whose activation is below the threshold at decision `now`, by
    /// timetag: with `naive`, any element referenced before `now`; otherwise those the
    /// queue holds for `now`, the others put off to their next predicted decision.
    pub(crate) fn due(&mut self, now: u64) -> Vec<u64> {
        let Some(model) = self.model.clone() else {
            return Vec::new();
        };
        let mut out = Vec::new();
        match self.params.forgetting {
            params::Forgetting::Off => {}
            params::Forgetting::Naive => {
                for (&tt, el) in &self.elements {
                    let last = el.history.newest_first().next().map(|r| r.step);
                    if last.is_some_and(|s| s < now) && model.below_threshold(&el.history, now)
                    {
                        out.push(tt);
                    }
                }
            }
            _ => {
                let Some(set) = self.queue.remove(&now) else {
                    return out;
                };
                for tt in set {
                    let Some(el) = self.elements.get_mut(&tt) else {
                        continue;
                    };
                    el.forget_at = NOT_QUEUED;
                    if model.below_threshold(&el.history, now) {
                        el.forget_at = FORGOTTEN;
                        out.push(tt);
                    } else {
                        let at = model.forgetting_time(&el.history, now, false);
                        self.requeue(tt, at);
                    }
                }
            }
        }
        out
    }

    /// `wm activation --history`: the WME's references, newest first, and with queued
    /// forgetting the decision it is checked at (9.6's `wma_get_wme_history`).
    pub fn history_text(&self, timetag: u64, now: u64) -> String {
        let Some(el) = self.elements.get(&timetag) else {
            return "WME has no decay history".to_string();
        };
        let (in_ring, total, first) = el.history.counts();
        let mut s = format!("history ({in_ring}/{total}, first @ d{first}):");
        for r in el.history.newest_first() {
            s.push_str(&format!(
                "\n {} @ d{} (-{})",
                r.count,
                r.step,
                now.wrapping_sub(r.step)
            ));
        }
        if self.params.forgetting.queued() {
            s.push_str(&format!("\n\nconsidering WME for decay @ d{}", el.forget_at));
        }
        s
    }
}

/// An activation as 9.6 prints it beside a WME: two significant digits (`[2.1]`,
/// `[-1e+09]`).
pub fn activation_text(x: f64) -> String {
    crate::printer::constants::c_general(x, 2)
}
