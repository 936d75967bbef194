//! The working-memory phase of an elaboration cycle: the cycle's new preferences join their
//! slots, and the changed slots bring working memory in line (Soar manual, chapter 2, "Preference
//! Memory: Selection Knowledge", and 3.1.4 "Acceptable preferences in working memory"): a
//! non-context slot shows each value with an acceptable and no reject preference, an operator
//! slot its candidates as `+` WMEs. The changes reach the matcher together, in 9.6's order,
//! and the consistency checks and the garbage collection follow.

use super::procedure::PrefType;
use super::scratch::Wanted;
use super::slot::SlotId;
use super::state::{PrefId, Preference, Slot};
use crate::agent::AgentCore;
use crate::symbols::Sym;
use crate::trace_events::TraceEvent;
use crate::wm::WmeId;
use rustc_hash::FxHashSet;

impl AgentCore {
    /// Marks slot `key` (at `slot`, if it exists) for `update_slots`.
    pub(crate) fn mark_changed(&mut self, key: (Sym, Sym), slot: Option<SlotId>) {
        if let Some(id) = slot {
            let slots = &mut self.decider.slots;
            if !slots.slot(id).changed {
                slots.slot_mut(id).changed = true;
                let generation = slots.generation(id);
                self.decider.changed.push((id, generation));
            }
        }
        let op = self.operator_sym();
        if key.1 == op {
            if let Some(g) = self.decider.goals.iter_mut().find(|g| g.state == key.0) {
                g.slot_changed = true;
            }
        }
    }

    /// O-supported rejects remove every preference for their value first; the other new
    /// preferences join their slots, newest at the head, but for a top-level o-supported
    /// acceptable preference whose value has one already (9.6 ignores it; Soar manual,
    /// "Preference memory").
    pub(super) fn assert_preferences(&mut self, new_prefs: &[PrefId]) {
        let tracing = self.settings.trace.preferences;
        if tracing {
            self.trace_o_reject_removals(new_prefs);
        }
        let taken = std::mem::take(&mut self.decider.results_taken_by_o_rejects);
        for &pid in &taken {
            self.decider.free_pref(pid);
        }
        let mut removed = std::mem::take(&mut self.decider.o_reject_removed);
        for &pid in new_prefs {
            let p = &self.decider.prefs[pid];
            let (kind, o_support, key, value) = (p.kind, p.o_support, (p.id, p.attr), p.value);
            if kind == PrefType::Reject && o_support && p.alive {
                removed.clear();
                let slot = self.decider.slots.id_of(&key);
                if let Some(id) = slot {
                    self.decider
                        .slots
                        .slot_mut(id)
                        .remove_value(value, &mut removed);
                }
                for &r in &removed {
                    self.pref_link_removed(r);
                    self.decider.free_pref(r);
                }
                self.decider.free_pref(pid);
                self.mark_changed(key, slot);
            }
        }
        removed.clear();
        self.decider.o_reject_removed = removed;
        // Instantiations newest first, each one's preferences newest first; `trace
        // --assertions` names each instantiation before its preferences.
        let made = std::mem::take(&mut self.decider.instantiations_made);
        if made.is_empty() {
            for &pid in new_prefs.iter().rev() {
                self.assert_preference(pid, tracing);
            }
        }
        for (k, (rule, start)) in made.iter().enumerate().rev() {
            self.emit(&TraceEvent::AssertingInstantiation { rule });
            let end = made.get(k + 1).map_or(new_prefs.len(), |next| next.1);
            for &pid in new_prefs[(*start).min(end)..end].iter().rev() {
                self.assert_preference(pid, tracing);
            }
            self.emit(&TraceEvent::InstantiationAsserted);
        }
    }

    /// One new preference into its slot (`+` traced when `tracing`), unless it is gone or
    /// its value's top-level o-support is there already.
    pub(super) fn assert_preference(&mut self, pid: PrefId, tracing: bool) {
        let p = &self.decider.prefs[pid];
        if !p.alive {
            return;
        }
        let key = (p.id, p.attr);
        let value = p.value;
        if self.already_top_o_supported(pid) {
            if tracing {
                self.trace_ignored_pref(pid);
            }
            self.decider.free_pref(pid);
            return;
        }
        if tracing {
            self.trace_pref('+', pid);
        }
        let slot = self.decider.slots.entry_id(key);
        self.decider.slots.slot_mut(slot).push(pid, value);
        let symbols = &self.symbols;
        self.decider.note_pref_links(pid, |s| symbols.is_id(s));
        // A memory's retrieval references nothing (its WMEs' activation starts apart).
        let wma = self.wma.on() && !self.decider.prefs[pid].recall;
        if wma && !self.decider.slots.slot(slot).changed {
            self.wma.clear_slot_references(key);
        }
        self.mark_changed(key, Some(slot));
        if wma {
            self.wma_preference_added(pid);
        }
    }

    /// Whether `pid` is a top-level o-supported acceptable preference for a non-context
    /// slot that already holds a top-level o-supported preference for its value.
    fn already_top_o_supported(&mut self, pid: PrefId) -> bool {
        // A memory's retrieval keeps its command's WMEs as `matched` at any level.
        let symbols = &self.symbols;
        let top_level = |p: &Preference| {
            p.o_support
                && p.matched.is_some()
                && (!p.recall || symbols.id_data(p.id).is_some_and(|d| d.level <= 1))
        };
        let p = &self.decider.prefs[pid];
        if p.kind != PrefType::Acceptable || !top_level(p) {
            return false;
        }
        let (key, value) = ((p.id, p.attr), p.value);
        let Some(slot) = self.decider.slots.get(&key) else {
            return false;
        };
        let prefs = &self.decider.prefs;
        // The value's own preferences (a large slot finds them by value, not by a scan).
        let duplicate = slot.prefs_for(value).any(|x| top_level(&prefs[x]));
        duplicate && !self.is_context_slot(key)
    }

    fn is_context_slot(&mut self, key: (Sym, Sym)) -> bool {
        let op = self.operator_sym();
        key.1 == op && self.symbols.is_goal(key.0)
    }

    /// Brings working memory in line with the changed slots: a non-context slot shows each
    /// value with an acceptable and no reject preference; an operator slot shows its
    /// acceptable preferences as `+` WMEs. Then unlinked structure goes.
    pub(crate) fn update_slots(&mut self) {
        // Soar head-inserts changed slots as they are first marked, so they are decided in
        // the reverse of marking order: the first action of the first firing gets the
        // lowest timetag (observed on 9.6).
        let mut changed = std::mem::take(&mut self.decider.changed);
        changed.reverse();
        let mut sc = std::mem::take(&mut self.decider.slot_scratch);
        let mut adds = std::mem::take(&mut sc.adds);
        // Removals are buffered with their timetags (handles are reused).
        let mut removes = std::mem::take(&mut sc.removes);
        let mut context = std::mem::take(&mut sc.context);
        let mut want = std::mem::take(&mut sc.want);
        // The non-context slots decided, for working-memory activation.
        let mut decided = Vec::new();
        for &(id, generation) in &changed {
            if self.decider.slots.generation(id) != generation {
                continue; // The slot went after it changed.
            }
            let slot = self.decider.slots.slot_mut(id);
            slot.changed = false;
            let key = slot.key;
            let incremental = slot.only_touched_changed();
            let mut touched = std::mem::take(&mut slot.touched);
            slot.full = false;
            if self.is_context_slot(key) {
                touched.clear();
                self.decider.slots.slot_mut(id).touched = touched;
                context.push(key);
                continue;
            }
            if self.wma.on() {
                decided.push(key);
            }
            if incremental {
                let slot = self.decider.slots.slot(id);
                let prefs = &self.decider.prefs;
                update_touched_values(slot, prefs, &mut touched, &self.wm, &mut removes, &mut adds);
            }
            touched.clear();
            self.decider.slots.slot_mut(id).touched = touched;
            if incremental {
                continue;
            }
            let slot = self.decider.slots.slot(id);
            let want = wanted_values(slot, &self.decider.prefs, &mut want);
            // Newest first, as 9.6 walks its slot's list.
            for (v, acc, w) in slot.wmes.iter().rev() {
                if !acc && !want.contains(v) {
                    removes.push((w, self.wm.get(w).map_or(0, |x| x.timetag)));
                }
            }
            for &v in want.list() {
                if !slot.wmes.contains_key(&(v, false)) {
                    adds.push((key.0, key.1, v, false));
                }
            }
        }
        // Operators whose proposal went are removed before the `+` WMEs change (9.6's
        // REMOVING lines come first, and its removals are buffered in that order).
        let goals_before = self.decider.goals.len();
        if self.wma.on() {
            self.wma_release_holders();
        }
        if self.settings.trace.wmes || self.settings.trace.wma {
            self.removed_wmes = Some(Vec::new());
        }
        // A substate whose GDS holds a WME the slot decisions remove goes first, before
        // the operator checks (9.6 removes it as the WME goes: its `Removing state ...
        // because element in GDS changed` comes before the `REMOVING: Operator` lines).
        let decided_removes = removes.len();
        if self.settings.trace.gds {
            self.trace_gds_removals(&removes);
        }
        self.remove_gds_goals_of(&removes);
        for &key in &context {
            if let Some(w) = self.check_operator_consistency(key) {
                removes.push((w, self.wm.get(w).map_or(0, |x| x.timetag)));
            }
        }
        for &key in &context {
            let empty = Slot::default();
            let slot = self.decider.slots.get(&key).unwrap_or(&empty);
            want.clear();
            let large = slot.prefs.len() > LARGE_SLOT;
            // Require preferences show as `+` WMEs too, before the acceptable ones, each
            // kind oldest first: that sets their timetags (checked on 9.6).
            for kind in [PrefType::Require, PrefType::Acceptable] {
                for &pid in slot.prefs.iter().rev() {
                    let p = &self.decider.prefs[pid];
                    if p.kind == kind {
                        want.insert(p.value, large);
                    }
                }
            }
            for (v, acc, w) in slot.wmes.iter().rev() {
                if acc && !want.contains(v) {
                    removes.push((w, self.wm.get(w).map_or(0, |x| x.timetag)));
                }
            }
            for &v in want.list() {
                if !slot.wmes.contains_key(&(v, true)) {
                    adds.push((key.0, key.1, v, true));
                }
            }
        }
        if self.settings.trace.gds {
            self.trace_gds_removals(&removes[decided_removes..]);
        }
        // Timetags in action order, but the matcher gets the batch newest first, and the
        // `=>WM:` lines come newest first too (observed on 9.6). Additions reach the
        // matcher before removals, which go in the reverse of the order they were found
        // (9.6 head-inserts both buffers).
        changed.clear();
        if self.decider.changed.is_empty() {
            self.decider.changed = changed;
        }
        let mut added = std::mem::take(&mut sc.added);
        for &(id, attr, value, acc) in &adds {
            added.push(self.add_slot_wme(id, attr, value, acc));
        }
        if self.wma.on() {
            for &w in &added {
                self.wma_wme_created(w);
            }
        }
        // Goal dependency sets grow from the new WMEs before the matcher sees them (as 9.6
        // does it while deciding the slots): the firings behind them still hold their
        // matches.
        for &w in &added {
            self.gds_for_new_wme(w);
        }
        // Where the `=>WM:` lines start: 9.6 warns there of a WME this phase adds and
        // removes (see below).
        let adds_at = self.output.len();
        // This batch's `RETE: putting` lines go before its own `=>WM:` lines, also when
        // an earlier batch of the phase marked a place (forgetting runs this in a phase).
        self.end_queued_matches();
        self.mark_queued_matches();
        let mut traced_adds = Vec::new();
        for (k, &w) in added.iter().enumerate().rev() {
            // Past the partial-match ceiling, the rest of the batch waits unmatched: one
            // phase's additions can make partial matches as the square of their number.
            if self.tokens_over_ceiling() {
                self.defer_additions(&mut added, k + 1);
                break;
            }
            if let Some(wme) = self.wm.get(w).copied() {
                self.trace_wme(true, &wme);
                if self.settings.trace.wmes {
                    traced_adds.push(wme);
                }
                self.match_new_wme(w, &wme);
            }
        }
        self.epmem_trace_present_adds();
        let before_decided = self.removed_wmes.as_ref().map_or(0, Vec::len);
        // The matcher hears of these removals after the garbage's (below): 9.6 collects
        // the objects they unlink before its matcher sees the phase's changes, and hands it
        // the removals newest first (its buffer is head-inserted). That order is the order
        // of the retractions they cause.
        let mut unmatched = std::mem::take(&mut sc.unmatched);
        for &(w, tt) in removes.iter().rev() {
            // A WME already gone (with a substate removed above) may have lent its handle
            // to one just added: only the WME with the timetag seen is removed.
            if self.wm.get(w).is_some_and(|x| x.timetag == tt) {
                self.remove_slot_wme_leaving_matcher(w);
                unmatched.push((w, tt));
            }
        }
        // A substate removed just above may still get this wave's WMEs (9.6 adds them too,
        // removing the goal only at its next consistency check): with the goal gone they
        // are unlinked, and go with the garbage below instead of staying for good, after
        // what the slot decisions unlinked.
        if self.decider.goals.len() < goals_before {
            for &w in &added {
                if let Some(wme) = self.wm.get(w) {
                    self.decider.gc_candidates.push(wme.id);
                }
            }
        }
        if !decided.is_empty() {
            self.wma_slots_decided(&decided);
        }
        let decided = before_decided..self.removed_wmes.as_ref().map_or(0, Vec::len);
        if !self.decider.gds_invalid.is_empty() {
            // A substate leaves with a matcher that has seen the phase's removals.
            self.unmatch_removed(&mut unmatched);
        }
        self.remove_invalid_gds_goals();
        // The `RETE: putting` lines stand before the `=>WM:` lines; the garbage's `-` lines
        // go before them, and 9.6's warning after them.
        let gc_lines = self.collect_garbage_traced_at(Some(adds_at));
        if let Some(at) = self.decider.queued_matches_at.as_mut() {
            *at += gc_lines;
        }
        self.unmatch_removed(&mut unmatched);
        sc.unmatched = unmatched;
        let queued_len = self
            .decider
            .queued_matches_at
            .map_or(0, |at| at.saturating_sub(adds_at + gc_lines));
        self.end_queued_matches();
        if self.settings.trace.wmes {
            self.warn_added_and_removed(&traced_adds, adds_at + gc_lines + queued_len);
        }
        self.trace_removed_wmes(decided);
        self.epmem_trace_present_removals();
        self.classify_new_matches();
        self.end_queued_matches();
        // Impasses are re-checked once i-supported processing is quiescent (9.6 checks at
        // minor quiescence): a result that ends a tie removes the tie's substate before the
        // phase ends.
        for &key in &context {
            if !self.decider.consistency_pending.contains(&key) {
                self.decider.consistency_pending.push(key);
            }
        }
        if !self.decider.consistency_pending.is_empty() && !self.has_pending(false) {
            let mut pending = std::mem::take(&mut self.decider.consistency_pending);
            for &key in &pending {
                self.check_impasse_consistency(key);
            }
            // The list's room serves the next phase (a check may have noted keys anew).
            pending.clear();
            pending.append(&mut self.decider.consistency_pending);
            self.decider.consistency_pending = pending;
        }
        adds.clear();
        removes.clear();
        context.clear();
        added.clear();
        (sc.adds, sc.removes, sc.context, sc.added, sc.want) =
            (adds, removes, context, added, want);
        self.decider.slot_scratch = sc;
    }

    /// Tells the matcher of removals [`Self::remove_slot_wme_leaving_matcher`] made, in
    /// their order, and empties the list.
    fn unmatch_removed(&mut self, unmatched: &mut Vec<(WmeId, u64)>) {
        for (w, timetag) in unmatched.drain(..) {
            self.unmatch_wme(w, timetag);
        }
    }

    /// Takes the first `count` WMEs of `added`, which the matcher has not seen, back out of
    /// working memory, and marks their slots to be decided again: a run stopped at its
    /// ceiling makes them when it goes on.
    fn defer_additions(&mut self, added: &mut Vec<WmeId>, count: usize) {
        for w in added.drain(..count) {
            let Some(wme) = self.wm.get(w).copied() else {
                continue;
            };
            let key = (wme.id, wme.attr);
            let slot = self.decider.slots.id_of(&key);
            if let Some(id) = slot {
                let slots = &mut self.decider.slots;
                slots.slot_mut(id).wmes.remove(&(wme.value, wme.acceptable));
                slots.slot_mut(id).full = true;
            }
            self.decider.wme_changes -= 1;
            // Listeners never heard of it: it goes without an event (its object, now
            // unlinked, goes with the garbage as any other).
            let events = std::mem::take(&mut self.events);
            self.remove_wme(w);
            self.events = events;
            self.mark_changed(key, slot);
        }
        self.ceiling_reached();
    }

    /// Puts a slot's WME into working memory (with its timetag); the caller matches it.
    fn add_slot_wme(&mut self, id: Sym, attr: Sym, value: Sym, acceptable: bool) -> WmeId {
        let links = self.symbols.is_id(value);
        let w = self.wm.add_typed(id, attr, value, acceptable, links);
        self.decider.wme_changes += 1;
        self.decider
            .slots
            .entry((id, attr))
            .wmes
            .insert((value, acceptable), w);
        w
    }

    pub(crate) fn remove_slot_wme(&mut self, w: WmeId) {
        if let Some(timetag) = self.wm.get(w).map(|x| x.timetag) {
            self.unmatch_wme(w, timetag);
            self.remove_slot_wme_leaving_matcher(w);
        }
    }

    /// [`Self::remove_slot_wme`] but for the matcher, which the caller tells later
    /// ([`AgentCore::unmatch_wme`]).
    fn remove_slot_wme_leaving_matcher(&mut self, w: WmeId) {
        let Some(wme) = self.wm.get(w).copied() else {
            return;
        };
        self.trace_wme(false, &wme);
        let key = (wme.id, wme.attr);
        if let Some(id) = self.decider.slots.id_of(&key) {
            let slots = &mut self.decider.slots;
            // Only the slot's own WME (an input WME may say the same).
            if slots.slot(id).wmes.get(&(wme.value, wme.acceptable)) == Some(w) {
                slots.slot_mut(id).wmes.remove(&(wme.value, wme.acceptable));
                slots.drop_if_empty(id);
            }
        }
        self.decider.wme_changes += 1;
        self.remove_wme_leaving_matcher(w);
    }

    /// 9.6's `WARNING: WME added and removed in same phase : (31: S2 ^note hello)`, before
    /// the phase's `=>WM:` lines (at `at` in the output), for each WME it added that is
    /// already gone again (a substate removed in the same phase took it; checked on
    /// soar-sml 9.6.5: agent substate-removed-same-wave).
    fn warn_added_and_removed(&mut self, added: &[crate::wm::Wme], at: usize) {
        let Some(removed) = self.removed_wmes.as_ref() else {
            return;
        };
        let mut text = String::new();
        for wme in added {
            if removed.iter().any(|x| x.timetag == wme.timetag) {
                text.push_str("WARNING: WME added and removed in same phase : ");
                text.push_str(&crate::trace::wme_internal(self, wme));
                text.push('\n');
            }
        }
        if !text.is_empty() && at <= self.output.len() && self.output.is_char_boundary(at) {
            self.output.insert_str(at, &text);
        }
    }
}

/// Slots with more preferences than this get sets for their wanted and rejected values.
const LARGE_SLOT: usize = 16;

/// Brings a large non-context slot in line for its touched values alone, as the full pass
/// of `update_slots` would: a value shows as a WME while it has an acceptable and no reject
/// preference; removals go in newest-WME-first order, additions in the order of each
/// value's oldest acceptable preference (a new wall brings a hundred comparisons at once).
fn update_touched_values(
    slot: &Slot,
    prefs: &[Preference],
    touched: &mut Vec<Sym>,
    wm: &crate::wm::WorkingMemory,
    removes: &mut Vec<(WmeId, u64)>,
    adds: &mut Vec<(Sym, Sym, Sym, bool)>,
) {
    touched.sort_unstable();
    touched.dedup();
    let mut gone: Vec<(usize, WmeId)> = Vec::new();
    let mut add: Vec<Sym> = Vec::new();
    for &v in touched.iter() {
        let (mut acceptable, mut rejected) = (false, false);
        for pid in slot.prefs_for(v) {
            match prefs[pid].kind {
                PrefType::Reject => rejected = true,
                PrefType::Acceptable => acceptable = true,
                _ => {}
            }
        }
        let wanted = acceptable && !rejected;
        match (wanted, slot.wmes.position(&(v, false))) {
            (false, Some(pos)) => {
                if let Some(w) = slot.wmes.get(&(v, false)) {
                    gone.push((pos, w));
                }
            }
            (true, None) => add.push(v),
            _ => {}
        }
    }
    gone.sort_unstable_by_key(|g| std::cmp::Reverse(g.0));
    removes.extend(
        gone.iter()
            .map(|&(_, w)| (w, wm.get(w).map_or(0, |x| x.timetag))),
    );
    if add.len() > 1 {
        // `add` is sorted (from `touched`): walk the slot's preferences oldest first.
        let mut done = vec![false; add.len()];
        let mut ordered = Vec::with_capacity(add.len());
        for (&pid, &v) in slot.prefs.iter().zip(slot.values()) {
            if let Ok(i) = add.binary_search(&v) {
                if !done[i] && prefs[pid].kind == PrefType::Acceptable {
                    done[i] = true;
                    ordered.push(v);
                }
            }
        }
        add = ordered;
    }
    for v in add {
        adds.push((slot.key.0, slot.key.1, v, false));
    }
}

/// The values a non-context slot's WMEs should show: each acceptable value not rejected,
/// oldest preference first. Linear in the slot, with sets only for large slots (one slot can
/// hold thousands of values, most hold one).
fn wanted_values<'a>(slot: &Slot, prefs: &[Preference], out: &'a mut Wanted) -> &'a Wanted {
    out.clear();
    let large = slot.prefs.len() > LARGE_SLOT;
    let rejected = |v: Sym, rejects: &FxHashSet<Sym>| {
        if large {
            rejects.contains(&v)
        } else {
            slot.prefs.iter().any(|&q| {
                let q = &prefs[q];
                q.kind == PrefType::Reject && q.value == v
            })
        }
    };
    let rejects: FxHashSet<Sym> = if large {
        slot.prefs
            .iter()
            .map(|&q| &prefs[q])
            .filter(|q| q.kind == PrefType::Reject)
            .map(|q| q.value)
            .collect()
    } else {
        FxHashSet::default()
    };
    for &pid in &slot.prefs {
        let p = &prefs[pid];
        if p.kind == PrefType::Acceptable && !rejected(p.value, &rejects) {
            out.insert(p.value, large);
        }
    }
    out
}
