//! Where working-memory activation meets the decision cycle (Soar manual, ch. 8,
//! "Working Memory Activation"): the references a WME gets (from the matches about to
//! fire, from preferences for it, at its creation), the end of each decision (histories
//! recorded, forgetting), and the support of a WME as activation sees it. Every caller
//! checks [`super::Wma::on`] first.

use crate::agent::{AgentCore, MatchSet};
use crate::decide::ids::PrefId;
use crate::decide::procedure::PrefType;
use crate::rete::NIL_WME;
use crate::symbols::Sym;
use crate::wm::{Wme, WmeId};
use rustc_hash::FxHashSet;

/// How a WME is supported, as activation sees it (9.6's `wma_activate_wme`).
#[derive(Debug, Clone, Copy)]
enum Support {
    /// By an o-supported preference: the WME decays.
    O,
    /// By an i-supported preference: referencing it references what its support rests on.
    I(PrefId),
    /// Made by the architecture (the goal stack, the io link, input): it never decays.
    Architecture,
    /// An operator impasse's `^item` or `^non-numeric`: 9.6 gives it an architectural
    /// firing whose one condition is the candidate's `+` WME in the state above, so it
    /// stands on that WME's support.
    Item(WmeId),
    /// An i-supported result of a memory, by its timetag: it stands on what the
    /// architecture's firing that made it tested.
    Memory(u64),
}

impl AgentCore {
    /// The WMEs of every match about to fire gain a reference, at the start of each
    /// elaboration cycle (9.6 counts its whole list of new matches there, those that wait
    /// for another phase included).
    pub(crate) fn wma_tested_in_prods(&mut self) {
        let pending: Vec<_> = self
            .matches
            .assertions
            .iter()
            .copied()
            .filter(|&k| k != MatchSet::GONE)
            .collect();
        for (p, t) in pending {
            for w in self.rete.match_wmes(p, t) {
                if w != NIL_WME {
                    self.wma_activate(w, 1);
                }
            }
        }
    }

    /// A preference joined its slot: an acceptable preference for a value already in
    /// working memory references that WME; any preference for a value not there yet is
    /// counted for the WME when it comes (9.6's `add_preference_to_tm`).
    pub(crate) fn wma_preference_added(&mut self, pid: PrefId) {
        let p = &self.decider.prefs[pid];
        let (kind, id, attr, value) = (p.kind, p.id, p.attr, p.value);
        if self.wma_context_slot(id, attr) {
            return;
        }
        let existing = self
            .decider
            .slots
            .get(&(id, attr))
            .and_then(|s| s.wmes.get(&(value, false)));
        match existing {
            Some(w) if kind == PrefType::Acceptable => self.wma_activate(w, 1),
            Some(_) => {}
            None => self.wma.value_reference((id, attr, value)),
        }
    }

    /// A WME a slot decision made: if o-supported, it starts with the references made to
    /// its value before it existed (9.6's `decide_non_context_slot`).
    pub(crate) fn wma_wme_created(&mut self, w: WmeId) {
        let Some(wme) = self.wm.get(w).copied() else {
            return;
        };
        if wme.acceptable {
            return;
        }
        if self.decider.last_wave_o_support && self.o_supported_recall(&wme) {
            // An o-supported memory result has its decay element from the start, with no
            // references until the memory's firing is counted (`wma_memory_results`): 9.6
            // prints its `=>WM:` line with the low activation of an element without any.
            self.wma.create(wme.timetag, 0);
            self.wma_trace_add(&wme);
            return;
        }
        let Some(n) = self
            .wma
            .take_value_references((wme.id, wme.attr, wme.value))
        else {
            return;
        };
        if matches!(self.wma_support(&wme), Support::O) {
            self.wma_ensure_element(&wme);
            self.wma.reference(wme.timetag, n);
        }
    }

    /// Whether an o-supported preference of a memory's retrieval supports the WME.
    fn o_supported_recall(&self, wme: &Wme) -> bool {
        self.decider
            .slots
            .get(&(wme.id, wme.attr))
            .is_some_and(|s| {
                s.prefs_for(wme.value).any(|pid| {
                    let p = &self.decider.prefs[pid];
                    p.alive && p.recall && p.o_support && p.kind == PrefType::Acceptable
                })
            })
    }

    /// A WME left working memory; an activation set may hold it a while longer.
    pub(crate) fn wma_wme_removed(&mut self, wme: &Wme) {
        self.wma.decided.remove(&wme.timetag);
        // A memory result's activation set lets its members go with it.
        if let Some(set) = self
            .wma
            .memory_results
            .remove(&wme.timetag)
            .and_then(|r| r.o_set)
        {
            self.wma.released_memory_sets.push(set);
        }
        if self.wma.holds.contains_key(&wme.timetag) {
            self.wma.held_out.insert(wme.timetag);
            return;
        }
        self.wma_trace_removal(wme.timetag);
        self.wma.remove(wme.timetag);
    }

    /// `n` references to a WME: an o-supported one gets them (and a decay element if it
    /// has none); an i-supported one passes them to the o-supported WMEs its support
    /// rests on; an architectural one ignores them.
    fn wma_activate(&mut self, w: WmeId, n: u64) {
        let Some(wme) = self.wm.get(w).copied() else {
            return;
        };
        if self.wma.reference(wme.timetag, n) {
            return;
        }
        match self.wma_support(&wme) {
            Support::O => {
                self.wma_ensure_element(&wme);
                self.wma.reference(wme.timetag, n);
            }
            Support::I(pid) => {
                for tt in self.wma_o_set(pid) {
                    self.wma.reference(tt, n);
                }
            }
            Support::Item(plus) => self.wma_activate(plus, n),
            Support::Memory(tt) => {
                for member in self.wma_memory_o_set(tt) {
                    self.wma.reference(member, n);
                }
            }
            Support::Architecture => {}
        }
    }

    fn wma_context_slot(&self, id: Sym, attr: Sym) -> bool {
        attr == self.operator_sym() && self.symbols.is_goal(id)
    }

    /// The WME's support: the preference its slot's last decision gave it while that
    /// preference stands, else the one a decision would give it now.
    fn wma_support(&self, wme: &Wme) -> Support {
        let known = &self.symbols.known;
        if (wme.attr == known.item || wme.attr == known.non_numeric)
            && self.symbols.is_goal(wme.id)
        {
            if let Some(plus) = self.candidate_plus_wme(wme.id, wme.value) {
                return Support::Item(plus);
            }
        }
        if self.wma.memory_results.contains_key(&wme.timetag) {
            return Support::Memory(wme.timetag);
        }
        let decided = self.wma.decided.get(&wme.timetag).copied().filter(|&pid| {
            let p = &self.decider.prefs[pid];
            p.alive
                && p.kind == PrefType::Acceptable
                && (p.id, p.attr, p.value) == (wme.id, wme.attr, wme.value)
        });
        match decided.or_else(|| self.wma_candidate(wme)) {
            Some(pid) if self.decider.prefs[pid].o_support => Support::O,
            Some(pid) => Support::I(pid),
            None => Support::Architecture,
        }
    }

    /// The preference a decision of the WME's slot gives it: 9.6 keeps a slot's
    /// preferences of each kind by the level of their firings' match goals, the highest
    /// goal first and the newest first within a level, and gives a WME the first for its
    /// value (so a result's justification or chunk, a level up, wins over the substate
    /// firing that made it). An operator slot's WMEs, the selected operator and the `+`
    /// ones, are supported by their proposals (observed: rules testing them reference what
    /// the proposals rest on).
    fn wma_candidate(&self, wme: &Wme) -> Option<PrefId> {
        let slot = self.decider.slots.get(&(wme.id, wme.attr))?;
        // An operator slot's WME, the selected operator or a `+` one, is supported by its
        // value's require when it has one (9.6 marks the requires first), else its
        // proposal.
        let required = self.wma_context_slot(wme.id, wme.attr)
            && slot.prefs_for(wme.value).any(|pid| {
                let p = &self.decider.prefs[pid];
                p.alive && p.kind == PrefType::Require
            });
        let kind = if required { PrefType::Require } else { PrefType::Acceptable };
        let mut best: Option<(u32, PrefId)> = None;
        for pid in slot.prefs_for(wme.value) {
            let p = &self.decider.prefs[pid];
            // A memory's retrieval is not a decision's: its WMEs keep their own support.
            if p.alive && p.kind == kind && !p.recall {
                let level = p
                    .inst
                    .and_then(|i| self.decider.insts[i].goal)
                    .map_or(1, |g| self.sym_level(g));
                // Newer preferences come later here: a tie in level goes to the later.
                if best.is_none_or(|(l, _)| level <= l) {
                    best = Some((level, pid));
                }
            }
        }
        best.map(|(_, pid)| pid)
    }

    /// Non-context slots were decided: each of their WMEs takes the preference the
    /// decision gives it (9.6's `decide_non_context_slot` sets it on kept and new WMEs).
    pub(crate) fn wma_slots_decided(&mut self, keys: &[(Sym, Sym)]) {
        for key in keys {
            let Some(slot) = self.decider.slots.get(key) else {
                continue;
            };
            for (_, acceptable, w) in slot.wmes.iter() {
                let Some(wme) = self.wm.get(w).copied() else {
                    continue;
                };
                if acceptable {
                    continue;
                }
                match self.wma_candidate(&wme) {
                    Some(pid) => self.wma.decided.insert(wme.timetag, pid),
                    None => self.wma.decided.remove(&wme.timetag),
                };
            }
        }
    }

    /// The WMEs the firing that made a preference matched, while that match is known.
    /// An i-supported preference's are those its firing recorded that are still in working
    /// memory: 9.6's instantiation keeps its conditions' WMEs, so the answer stands when
    /// the match is gone (its retraction pending in the same elaboration cycle).
    fn wma_pref_conditions(&self, pid: PrefId) -> Vec<WmeId> {
        let p = &self.decider.prefs[pid];
        if let (false, Some(recorded)) = (p.o_support, p.matched.as_deref()) {
            return recorded
                .iter()
                .filter_map(|w| self.wm.by_timetag(w.timetag))
                .collect();
        }
        if let Some(i) = p.inst {
            let inst = &self.decider.insts[i];
            // A justification's conditions are the WMEs it was built on.
            if inst.alive && inst.serial != 0 {
                return self
                    .learn
                    .grounds_of
                    .get(&inst.serial)
                    .map(|g| {
                        g.iter()
                            .filter(|&&(w, tt)| self.wm.get(w).is_some_and(|x| x.timetag == tt))
                            .map(|&(w, _)| w)
                            .collect()
                    })
                    .unwrap_or_default();
            }
            let key = (inst.prod, inst.token);
            if inst.alive && self.decider.inst_by_token.get(&key) == Some(&i) {
                return self
                    .rete
                    .match_wmes(inst.prod, inst.token)
                    .into_iter()
                    .filter(|&w| w != NIL_WME)
                    .collect();
            }
        }
        p.matched
            .as_deref()
            .unwrap_or(&[])
            .iter()
            .filter_map(|w| self.wm.by_timetag(w.timetag))
            .collect()
    }

    /// The decay element of an o-supported WME, made with its first references: the
    /// average, rounded down, of the decayed sums of the WMEs its creating firings tested
    /// (9.6's `wma_calculate_initial_boost`).
    fn wma_ensure_element(&mut self, wme: &Wme) {
        if self.wma.element(wme.timetag).is_some() {
            return;
        }
        let creators: Vec<PrefId> = self
            .decider
            .slots
            .get(&(wme.id, wme.attr))
            .map(|s| {
                s.prefs_for(wme.value)
                    .filter(|&pid| {
                        let p = &self.decider.prefs[pid];
                        p.alive && p.o_support && p.kind == PrefType::Acceptable
                    })
                    .collect()
            })
            .unwrap_or_default();
        let conditions: Vec<WmeId> = creators
            .into_iter()
            .flat_map(|pid| self.wma_pref_conditions(pid))
            .collect();
        let boost = self.wma_initial_boost(&conditions);
        self.wma.create(wme.timetag, boost);
        self.wma_trace_add(wme);
    }

    /// The first references of a WME made by firings that tested `conditions`: the
    /// average, rounded down, of their decayed sums (an architecture WME counts as one of
    /// e, an i-supported one by the o-supported WMEs its support rests on, a WME whose
    /// element is new this decision not at all), each WME once.
    fn wma_initial_boost(&mut self, conditions: &[WmeId]) -> u64 {
        let now = self.decider.d_cycle_count;
        let mut seen: FxHashSet<u64> = FxHashSet::default();
        let (mut count, mut sum) = (0u64, 0.0f64);
        for &cw in conditions {
            let Some(c) = self.wm.get(cw).copied() else {
                continue;
            };
            if !seen.insert(c.timetag) {
                continue;
            }
            if let Some(el) = self.wma.element(c.timetag) {
                if !el.just_created {
                    count += 1;
                    sum += self.wma.time_sum(c.timetag, now);
                }
                continue;
            }
            match self.wma_support(&c) {
                Support::Architecture => {
                    count += 1;
                    sum += super::TIME_SUM_NONE;
                }
                // Only a support already found counts (9.6 looks at the o-set the
                // preference has, without making one).
                support @ (Support::I(_) | Support::Memory(_)) => {
                    let members = match support {
                        Support::I(p2) => self.wma_cached_o_set(p2),
                        _ => self.wma_cached_memory_o_set(c.timetag),
                    }
                    .unwrap_or_default();
                    for m in members {
                        let fresh = self.wma.element(m).is_some_and(|e| e.just_created);
                        if !fresh && seen.insert(m) {
                            count += 1;
                            sum += self.wma.time_sum(m, now);
                        }
                    }
                }
                Support::Item(_) | Support::O => {}
            }
        }
        if count > 0 {
            (sum / count as f64).floor() as u64
        } else {
            0
        }
    }

    /// WMEs a memory (semantic or episodic) just put in working memory for a command: 9.6
    /// makes them through an instantiation of the architecture's that tests the memory's
    /// link, command and result WMEs and the command's WMEs (`conditions`), o-supported
    /// when the last wave of firings was, and each starts with that boost and one
    /// reference for its preference.
    pub(crate) fn wma_memory_results(&mut self, results: &[WmeId], conditions: &[WmeId]) {
        if !self.decider.last_wave_o_support {
            // I-supported: referencing one references what the firing tested.
            let tested: Vec<(WmeId, u64)> = conditions
                .iter()
                .filter_map(|&w| self.wm.get(w).map(|x| (w, x.timetag)))
                .collect();
            for &w in results {
                if let Some(wme) = self.wm.get(w) {
                    let result = super::MemoryResult {
                        conditions: tested.clone(),
                        o_set: None,
                    };
                    self.wma.memory_results.insert(wme.timetag, result);
                }
            }
            return;
        }
        // One firing made them all: they share its boost.
        let boost = self.wma_initial_boost(conditions);
        for &w in results {
            let Some(wme) = self.wm.get(w).copied() else {
                continue;
            };
            // Its element came with it, empty (`wma_wme_created`); one with references or
            // a history is another's.
            let fresh = self.wma.element(wme.timetag).map(|e| {
                e.just_created && e.buffered == 0 && e.history.is_empty()
            });
            match fresh {
                Some(false) => continue,
                Some(true) => {}
                None => self.wma_trace_add(&wme),
            }
            self.wma.create(wme.timetag, boost);
            self.wma.reference(wme.timetag, 1);
        }
    }

    fn wma_cached_memory_o_set(&self, timetag: u64) -> Option<Vec<u64>> {
        self.wma.memory_results.get(&timetag)?.o_set.clone()
    }

    /// The o-set of an i-supported memory result, found at its first reference and kept.
    fn wma_memory_o_set(&mut self, timetag: u64) -> Vec<u64> {
        if let Some(set) = self.wma_cached_memory_o_set(timetag) {
            return set;
        }
        let Some(result) = self.wma.memory_results.get(&timetag) else {
            return Vec::new();
        };
        let conditions: Vec<WmeId> = result
            .conditions
            .iter()
            .filter(|&&(w, tt)| self.wm.get(w).is_some_and(|x| x.timetag == tt))
            .map(|&(w, _)| w)
            .collect();
        let mut out = std::collections::BTreeSet::new();
        self.wma_collect_conditions(&conditions, &mut out, &mut FxHashSet::default());
        let set: Vec<u64> = out.into_iter().collect();
        if let Some(result) = self.wma.memory_results.get_mut(&timetag) {
            result.o_set = Some(set.clone());
            // It holds its members, as a preference's set does.
            self.wma.hold(&set);
        }
        set
    }

    fn wma_cached_o_set(&self, pid: PrefId) -> Option<Vec<u64>> {
        if !self.decider.prefs[pid].alive {
            return None;
        }
        let serial = self.decider.pref_serial(pid);
        Some(self.wma.holders.get(&(pid, serial))?.members.clone())
    }

    /// The o-supported and architectural WMEs an i-supported preference's support rests
    /// on, through other i-supported WMEs; found once and kept (9.6's `wma_o_set`).
    /// O-supported WMEs found get their decay elements.
    fn wma_o_set(&mut self, pid: PrefId) -> Vec<u64> {
        if let Some(set) = self.wma_cached_o_set(pid) {
            return set;
        }
        let mut out = std::collections::BTreeSet::new();
        let mut visiting = FxHashSet::default();
        self.wma_collect_o_set(pid, &mut out, &mut visiting);
        let set: Vec<u64> = out.into_iter().collect();
        self.wma_store_o_set(pid, set.clone());
        set
    }

    /// Keeps a preference's activation set, which holds its members (see `Wma::holders`).
    fn wma_store_o_set(&mut self, pid: PrefId, set: Vec<u64>) {
        let serial = self.decider.pref_serial(pid);
        let p = &self.decider.prefs[pid];
        let key = (p.id, p.attr, p.value);
        if !self.wma.holders.contains_key(&(pid, serial)) {
            self.wma.hold(&set);
            let holder = super::Holder { key, members: set };
            self.wma.holders.insert((pid, serial), holder);
            // (A set found for a preference already freed waits for the next release.)
            if !p.alive {
                self.wma.waiting_holders.push((pid, serial));
            }
        }
    }

    /// The activation sets whose preference 9.6 has freed by now (gone, and an operator
    /// proposal's operator no longer selected) and of memory results gone let their WMEs
    /// go, oldest preference first; a WME out of working memory that nothing holds any
    /// more is freed: its element goes, with its `remove` line.
    pub(crate) fn wma_release_holders(&mut self) {
        self.wma_release_firings();
        let next = self.wm.next_timetag();
        for set in std::mem::take(&mut self.wma.released_memory_sets) {
            self.wma_let_go(&set, next);
        }
        let mut freed = std::mem::take(&mut self.decider.freed_prefs_log);
        let mut dead = std::mem::take(&mut self.wma.waiting_holders);
        dead.extend(freed.drain(..).filter(|k| self.wma.holders.contains_key(k)));
        self.decider.freed_prefs_log = freed;
        if dead.is_empty() {
            return;
        }
        let (waiting, mut dead): (Vec<_>, Vec<_>) = dead.into_iter().partition(|k| {
            self.wma
                .holders
                .get(k)
                .is_some_and(|h| self.wma_operator_still_selected(h.key))
        });
        self.wma.waiting_holders = waiting;
        dead.sort_unstable_by_key(|&(_, serial)| serial);
        for k in dead {
            let Some(holder) = self.wma.holders.remove(&k) else {
                continue;
            };
            // (9.6's set lets its members go in the order of their addresses.)
            self.wma_let_go(&holder.members, next);
        }
    }

    /// A holder lets these WMEs go (in the order of their addresses); one out of working
    /// memory that nothing holds any more is freed.
    fn wma_let_go(&mut self, members: &[u64], next: u64) {
        let mut members: Vec<(u64, ())> = members.iter().map(|&tt| (tt, ())).collect();
        self.wma.addresses.sort(&mut members, next);
        for (tt, ()) in members {
            let Some(n) = self.wma.holds.get_mut(&tt) else {
                continue;
            };
            *n -= 1;
            if *n > 0 {
                continue;
            }
            self.wma.holds.remove(&tt);
            if self.wma.held_out.remove(&tt) {
                if self.settings.trace.wma && self.wma.element(tt).is_some_and(|e| !e.removed) {
                    self.wma_removal_line(tt);
                }
                self.wma.remove(tt);
                self.wma.address_freed(tt, next);
            }
        }
    }

    /// A substate firing (instantiation `i`, just made) holds the WMEs it matched.
    pub(crate) fn wma_hold_firing(&mut self, i: crate::decide::ids::InstId) {
        let inst = &self.decider.insts[i];
        let (prod, token) = (inst.prod, inst.token);
        let prefs: Vec<_> = inst
            .prefs
            .iter()
            .map(|&pid| {
                let p = &self.decider.prefs[pid];
                (pid, self.decider.pref_serial(pid), (p.id, p.attr, p.value))
            })
            .collect();
        let members: Vec<u64> = self
            .rete
            .match_row(prod, token)
            .filter_map(|w| self.wm.get(w).map(|x| x.timetag))
            .collect();
        self.wma.hold(&members);
        self.wma.firing_holds.push(super::FiringHold {
            inst: i,
            prod,
            token,
            prefs,
            members,
        });
    }

    /// The substate firings 9.6 has deallocated by now (retracted, and each of their
    /// preferences gone with the WME it supported) let their WMEs go, oldest first.
    fn wma_release_firings(&mut self) {
        if self.wma.firing_holds.is_empty() {
            return;
        }
        let next = self.wm.next_timetag();
        let holds = std::mem::take(&mut self.wma.firing_holds);
        let (released, kept): (Vec<_>, Vec<_>) = holds.into_iter().partition(|h| {
            let inst = &self.decider.insts[h.inst];
            let live = inst.alive && inst.prod == h.prod && inst.token == h.token;
            !live
                && h.prefs.iter().all(|&(pid, serial, key)| {
                    (self.decider.pref_serial(pid) != serial || !self.decider.prefs[pid].alive)
                        && !self.wma_operator_still_selected(key)
                })
        });
        self.wma.firing_holds = kept;
        for h in released {
            self.wma_let_go(&h.members, next);
        }
    }

    /// Whether a gone preference for `(id ^attr value)` is still held by a WME: an operator
    /// proposal's by the selected operator's WME (9.6 frees the proposal when its operator
    /// leaves the slot); others are freed once gone.
    fn wma_operator_still_selected(&self, (id, attr, value): (Sym, Sym, Sym)) -> bool {
        self.wma_context_slot(id, attr)
            && self
                .decider
                .slots
                .get(&(id, attr))
                .is_some_and(|s| s.wmes.get(&(value, false)).is_some())
    }

    fn wma_collect_o_set(
        &mut self,
        pid: PrefId,
        out: &mut std::collections::BTreeSet<u64>,
        visiting: &mut FxHashSet<PrefId>,
    ) {
        if !visiting.insert(pid) {
            return;
        }
        let conditions = self.wma_pref_conditions(pid);
        self.wma_collect_conditions(&conditions, out, visiting);
    }

    /// The o-set of WMEs a firing tested: the o-supported and architectural ones, and
    /// those the i-supported ones rest on.
    fn wma_collect_conditions(
        &mut self,
        conditions: &[WmeId],
        out: &mut std::collections::BTreeSet<u64>,
        visiting: &mut FxHashSet<PrefId>,
    ) {
        for &cw in conditions {
            let Some(c) = self.wm.get(cw).copied() else {
                continue;
            };
            match self.wma_support(&c) {
                Support::O => {
                    self.wma_ensure_element(&c);
                    out.insert(c.timetag);
                }
                Support::I(p2) => match self.wma_cached_o_set(p2) {
                    Some(set) => out.extend(set),
                    None => {
                        let mut sub = std::collections::BTreeSet::new();
                        self.wma_collect_o_set(p2, &mut sub, visiting);
                        let set: Vec<u64> = sub.into_iter().collect();
                        out.extend(set.iter().copied());
                        self.wma_store_o_set(p2, set);
                    }
                },
                Support::Architecture => {
                    out.insert(c.timetag);
                }
                Support::Memory(tt) => out.extend(self.wma_memory_o_set(tt)),
                Support::Item(plus) => {
                    // The item itself is in the set as an architecture WME (it counts in
                    // a new WME's first references: command golden
                    // `wma-impasse-item-boost`), and what its candidate rests on too.
                    out.insert(c.timetag);
                    let Some(p) = self.wm.get(plus).copied() else {
                        continue;
                    };
                    match self.wma_support(&p) {
                        Support::I(p2) => {
                            let set = self.wma_o_set(p2);
                            out.extend(set);
                        }
                        Support::O => {
                            self.wma_ensure_element(&p);
                            out.insert(p.timetag);
                        }
                        _ => {
                            out.insert(p.timetag);
                        }
                    }
                }
            }
        }
    }

    /// The end of a decision, in the output phase (9.6's `wma_go`): the decision's
    /// references join the histories, then forgetting removes the WMEs whose activation
    /// is below the threshold, by removing their o-supported preferences and running a
    /// working-memory phase.
    pub(crate) fn wma_end_decision(&mut self) {
        let now = self.decider.d_cycle_count;
        // A `remove` line whose `<=WM:` line never came is not lost.
        self.wma_flush_removal_lines();
        self.wma_release_holders();
        self.wma.purge_removed();
        if self.settings.trace.wma {
            let mut counts = Vec::new();
            self.wma.record_decision(now, Some(&mut counts));
            let next = self.wm.next_timetag();
            self.wma.addresses.sort(&mut counts, next);
            self.wma_trace_activations(&counts);
        } else {
            self.wma.record_decision(now, None);
        }
        let due = self.wma.due(now);
        if due.is_empty() || self.wma.params.fake_forgetting {
            return;
        }
        let lti_only = self.wma.params.forget_lti_only;
        // 9.6 forgets a long-term identifier's WMEs all together only when forgetting is
        // queued; a naive sweep takes each of its WMEs below the threshold on its own.
        let whole_objects = lti_only && self.wma.params.forgetting.queued();
        let mut forgot = false;
        for tt in due {
            let Some(w) = self.wm.by_timetag(tt) else {
                continue;
            };
            let Some(wme) = self.wm.get(w).copied() else {
                continue;
            };
            if whole_objects {
                forgot |= self.wma_forget_lti_object(wme.id);
            } else if lti_only && self.symbols.lti(wme.id).is_none() {
                continue;
            } else {
                forgot |= self.wma_forget_wme(&wme);
            }
        }
        if !forgot {
            return;
        }
        // The removals are traced as any others, between two headings when the WMA trace
        // is on (9.6.5 prints none with only `watch --wmes`).
        if self.settings.trace.wma {
            self.output.push_str("\n\nWMA: BEGIN FORGOTTEN WME LIST\n\n");
        }
        let before = self.wm.removals();
        self.update_slots();
        self.wma.forgotten += self.wm.removals() - before;
        if self.settings.trace.wma {
            self.output.push_str("\nWMA: END FORGOTTEN WME LIST\n\n");
        }
    }

    /// `forget-wme lti` with queued forgetting: a long-term identifier's WMEs go all
    /// together, once every o-supported one is below the threshold; other identifiers'
    /// never.
    fn wma_forget_lti_object(&mut self, id: Sym) -> bool {
        if self.symbols.lti(id).is_none() {
            return false;
        }
        let wmes: Vec<Wme> = self
            .wm
            .of_id(id)
            .filter_map(|w| self.wm.get(w).copied())
            .collect();
        let all_below = wmes.iter().all(|w| match self.wma_support(w) {
            Support::O => self
                .wma
                .element(w.timetag)
                .is_some_and(|e| e.forget_at == 0),
            _ => true,
        });
        if !all_below {
            return false;
        }
        let mut forgot = false;
        for w in &wmes {
            forgot |= self.wma_forget_wme(w);
        }
        forgot
    }

    /// Takes out of their slot the o-supported preferences for a WME's value (9.6's
    /// `wma_forgetting_forget_wme`); the next working-memory phase removes the WME.
    fn wma_forget_wme(&mut self, wme: &Wme) -> bool {
        let key = (wme.id, wme.attr);
        let Some(slot) = self.decider.slots.id_of(&key) else {
            return false;
        };
        let gone: Vec<PrefId> = self
            .decider
            .slots
            .slot(slot)
            .prefs_for(wme.value)
            .filter(|&pid| {
                let p = &self.decider.prefs[pid];
                p.alive && p.o_support
            })
            .collect();
        for &pid in &gone {
            self.decider.slots.slot_mut(slot).remove(pid, wme.value);
            self.pref_link_removed(pid);
            self.decider.free_pref(pid);
        }
        if gone.is_empty() {
            return false;
        }
        self.mark_changed(key, Some(slot));
        true
    }
}

impl AgentCore {
    /// A WME's activation as 9.6 prints it beside the WME; `None` while activation is off.
    pub(crate) fn wme_activation(&self, w: &Wme) -> Option<f64> {
        self.wma
            .on()
            .then(|| self.wma.activation(w.timetag, self.decider.d_cycle_count))
    }
}
