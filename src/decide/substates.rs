//! Impasses and substates (Soar manual, chapter 2, "Creating New States", and 3.4.1 "Impasses in
//! working memory"): a new state with its architecture WMEs for an impasse, and the removal
//! of the states below a goal, with what 9.6's traces list for them.

use super::procedure::PrefType;
use super::state::{Goal, ImpasseKind, MadePref, PrefId};
use crate::agent::AgentCore;
use crate::symbols::Sym;
use crate::trace_events::TraceEvent;
use rustc_hash::FxHashSet;

/// A WME of an object a removed substate holds, with its handle.
type ObjectWme = (crate::wm::WmeId, crate::wm::Wme);

impl AgentCore {
    /// The `<=WM:` lines 9.6 prints for the architecture WMEs of the substates below goal
    /// `gi` when a consistency check removes them within a phase: the smem and epmem links'
    /// children, the links, the state's own WMEs, then the `^non-numeric` and the `^item`
    /// WMEs (each group oldest first; seen on 9.6).
    ///
    /// The substates' own objects go with them: those their other slots hold come first,
    /// the last held first, each one's WMEs oldest first; those their operator slots hold
    /// come after the state's own WMEs, newest first, before the operator `+` WMEs
    /// (soar-sml 9.6.5, agents learn-lookahead and long/fifteen-puzzle: the evaluation
    /// objects, the memories, `^name selection`, `^evaluation`, the proposed operator's
    /// `^superoperator` and `^name`, then `^operator E5 +`). The garbage collection does
    /// not list them again.
    pub(super) fn trace_substate_wmes_removed(&mut self, gi: usize) {
        let lines = self.substate_lines(gi);
        let memories = lines.iter().take_while(|(group, _)| *group <= 2).count();
        let mut made = self.substate_slot_wmes(gi);
        made.sort_by_key(|&(plus, wme)| (plus, wme.timetag));
        let (held, proposed) = self.substate_objects(gi, &made);
        for (_, wme) in &held {
            self.trace_wme(false, wme);
        }
        let links = self.memory_link_lines(gi);
        for wme in &links {
            self.trace_wme(false, wme);
        }
        // The WMEs rules made on the substates (their slots' WMEs) go with them too: after
        // the memories' structure, oldest first, the operator `+` WMEs last.
        for &(plus, wme) in &made {
            if plus {
                continue;
            }
            self.trace_wme(false, &wme);
        }
        for (_, wme) in &proposed {
            self.trace_wme(false, wme);
        }
        for &(plus, wme) in &made {
            if plus {
                self.trace_wme(false, &wme);
            }
        }
        for (_, wme) in &lines[memories..] {
            self.trace_wme(false, wme);
        }
        let traced = held.iter().chain(&proposed).map(|(_, w)| w.timetag);
        let traced = traced.chain(links.iter().map(|w| w.timetag));
        self.decider.wmes_traced_gone.extend(traced);
    }

    /// A consistency check removes the substates below goal `gi`: the objects their other
    /// slots hold go first, before the states' own WMEs, in the order the trace lists them
    /// (see [`Self::trace_substate_wmes_removed`]): 9.6 takes them out of the matcher in
    /// that order, so their alpha memories empty before the states' matches go, which
    /// sets where the matcher's joins stand when they come back (checked on soar-sml
    /// 9.6.5: agent long/fifteen-puzzle, trace 3, the order of the selection rules that a
    /// second selection state's first evaluation fires).
    pub(super) fn remove_held_objects(&mut self, gi: usize) {
        let mut made = self.substate_slot_wmes(gi);
        made.sort_by_key(|&(plus, wme)| (plus, wme.timetag));
        let (held, _) = self.substate_objects(gi, &made);
        for (w, wme) in held {
            if self.wm.get(w).is_none_or(|x| x.timetag != wme.timetag) {
                continue;
            }
            if let Some(slot) = self.decider.slots.remove(&(wme.id, wme.attr)) {
                self.discard_slot(slot, w);
            }
            self.remove_wme(w);
        }
    }

    /// The WMEs of the objects local to the substates below `gi` that their slot WMEs
    /// `made` (as [`Self::trace_substate_wmes_removed`] orders them) hold: those of the
    /// objects other slots hold, the last held first, each one's oldest first; and those
    /// of the objects the operator slots hold, newest first.
    fn substate_objects(
        &self,
        gi: usize,
        made: &[(bool, crate::wm::Wme)],
    ) -> (Vec<ObjectWme>, Vec<ObjectWme>) {
        let levels: Vec<u32> = self.decider.goals[gi + 1..].iter().map(|g| g.level).collect();
        let local = |v: Sym| {
            !self.symbols.is_goal(v)
                && self
                    .symbols
                    .id_data(v)
                    .is_some_and(|d| levels.contains(&d.level))
        };
        let mut seen = FxHashSet::default();
        let mut held = Vec::new();
        let mut proposed = Vec::new();
        for &(plus, wme) in made.iter().rev() {
            if !local(wme.value) || !seen.insert(wme.value) {
                continue;
            }
            let mut of: Vec<ObjectWme> = self
                .wm
                .of_id(wme.value)
                .filter_map(|w| Some((w, self.wm.get(w).copied()?)))
                .collect();
            if plus {
                of.sort_by_key(|(_, w)| std::cmp::Reverse(w.timetag));
                proposed.extend(of);
            } else {
                of.sort_by_key(|(_, w)| w.timetag);
                held.extend(of);
            }
        }
        proposed.sort_by_key(|(_, w)| std::cmp::Reverse(w.timetag));
        (held, proposed)
    }

    /// An operator removal or a GDS change takes the substates below goal `gi` away: their
    /// `<=WM:` lines join this phase's listing, each tagged with its kind, for
    /// `trace_removed_wmes` to put in 9.6's place.
    pub(crate) fn collect_substate_removals(&mut self, gi: usize) {
        use super::state::SubstateLine;
        let mut out = Vec::new();
        let memories = self.memory_link_lines(gi);
        self.decider.wmes_traced_gone.extend(memories.iter().map(|w| w.timetag));
        out.extend(memories.into_iter().map(|w| (SubstateLine::Memories, w)));
        for (group, wme) in self.substate_lines(gi) {
            if group > 2 {
                out.push((SubstateLine::Impasse, wme));
            }
        }
        for (plus, wme) in self.substate_slot_wmes(gi) {
            let place = if plus {
                SubstateLine::OperatorPlus
            } else {
                SubstateLine::Other
            };
            out.push((place, wme));
        }
        for g in self.decider.goals[gi + 1..].iter().rev() {
            if let Some(wme) = g.operator.and_then(|(_, w)| self.wm.get(w).copied()) {
                out.push((SubstateLine::Selected, wme));
            }
        }
        self.substate_removals.extend(out);
    }

    /// The slots of the standing preferences the firings of the goals below `gi` made, in
    /// the order 9.6 removes those preferences with the goals (deepest goal first, as
    /// [`Self::trace_removed_prefs`] lists them), each slot once; only the slots that hold
    /// no other preference (a WME something else supports goes with the garbage).
    pub(crate) fn substate_pref_slots(&self, gi: usize) -> Vec<(Sym, Sym)> {
        let mut order: Vec<(Sym, Sym)> = Vec::new();
        let mut theirs = FxHashSet::default();
        for g in self.decider.goals[gi + 1..].iter().rev() {
            for (pid, what) in self.standing_prefs(g.state, &g.made) {
                theirs.insert(pid);
                let slot = (what.0, what.1);
                if !order.contains(&slot) {
                    order.push(slot);
                }
            }
        }
        order.retain(|key| {
            self.decider
                .slots
                .get(key)
                .is_none_or(|slot| slot.prefs.iter().all(|p| theirs.contains(p)))
        });
        order
    }

    /// The WMEs in the slots of the goals below `gi` (those rules made on them), lowest
    /// goal first, each with whether it is an operator `+` WME.
    fn substate_slot_wmes(&self, gi: usize) -> Vec<(bool, crate::wm::Wme)> {
        let op = self.operator_sym();
        let mut out = Vec::new();
        for g in self.decider.goals[gi + 1..].iter().rev() {
            for key in self.decider.slots.keys_of(g.state) {
                let Some(slot) = self.decider.slots.get(&key) else {
                    continue;
                };
                for (_, acc, w) in slot.wmes.iter() {
                    if let Some(wme) = self.wm.get(w).copied() {
                        out.push((acc && key.1 == op, wme));
                    }
                }
            }
        }
        out
    }

    /// The `<=WM:` lines of the memories' links of the goals below `gi` (`^smem`, `^epmem`,
    /// `^reward-link` and the links' WMEs) and of the objects that go with them (the
    /// commands' cues, the retrievals), in the order 9.6 lists them. 9.6 holds the links
    /// in the state's slots and collects them with the state's garbage: the state's link
    /// WMEs newest first, then each object whose last link went, the last one first (its
    /// WMEs in [`Self::object_in_collection_order`]); the listing runs in reverse, the
    /// shallowest goal's first. Seen on soar-sml 9.6.5, agent
    /// `tests/commands/agents/epmem-superstate-link.soar` at trace 4.
    fn memory_link_lines(&self, gi: usize) -> Vec<crate::wm::Wme> {
        let k = self.symbols.known;
        let mut out = Vec::new();
        for g in &self.decider.goals[gi + 1..] {
            let mut links: Vec<crate::wm::Wme> = g
                .wmes
                .iter()
                .filter_map(|&w| self.wm.get(w).copied())
                .filter(|w| {
                    w.id == g.state
                        && (w.attr == k.smem || w.attr == k.epmem || w.attr == k.reward_link)
                })
                .collect();
            links.sort_by_key(|w| std::cmp::Reverse(w.timetag));
            // What the state's other WMEs link goes with them, before the links.
            let mut gone: FxHashSet<u64> =
                self.wm.of_id(g.state).filter_map(|w| self.wm.get(w)).map(|w| w.timetag).collect();
            let mut removal = Vec::new();
            let mut stack: Vec<Sym> = Vec::new();
            let mut taken = FxHashSet::default();
            let mut next = links;
            loop {
                for w in next {
                    removal.push(w);
                    gone.insert(w.timetag);
                    let v = w.value;
                    let unlinked = self.symbols.is_id(v)
                        && !self.symbols.is_goal(v)
                        && self.wm.parent_wmes(v).iter().all(|&p| {
                            self.wm.get(p).is_none_or(|x| gone.contains(&x.timetag))
                        });
                    if unlinked && taken.insert(v) {
                        stack.push(v);
                    }
                }
                let Some(x) = stack.pop() else {
                    break;
                };
                next = self.object_in_collection_order(x);
            }
            out.extend(removal.into_iter().rev());
        }
        out
    }

    /// The architecture WMEs of the goals below `gi` in 9.6's order, each with its group
    /// (0–2: the memories' structure; 3 and up: the impasse's WMEs).
    fn substate_lines(&self, gi: usize) -> Vec<(u8, crate::wm::Wme)> {
        let mut lines: Vec<(u8, u64, crate::wm::Wme)> = Vec::new();
        for g in &self.decider.goals[gi + 1..] {
            let of = |attr: &str| {
                let a = self.symbols.find_str(attr);
                g.wmes
                    .iter()
                    .filter_map(|&w| self.wm.get(w))
                    .find(|w| Some(w.attr) == a && w.id == g.state)
                    .map(|w| w.value)
            };
            let (smem, epmem) = (of("smem"), of("epmem"));
            for &w in &g.wmes {
                let Some(wme) = self.wm.get(w).copied() else {
                    continue;
                };
                let attr = self.symbols.text(wme.attr);
                let group = if Some(wme.id) == smem {
                    0
                } else if Some(wme.id) == epmem {
                    1
                } else if matches!(attr.as_str(), "reward-link" | "epmem" | "smem") {
                    2
                } else if attr.starts_with("non-numeric") {
                    4
                } else if attr.starts_with("item") {
                    5
                } else {
                    3
                };
                // Counts go after the values they count.
                let count = u64::from(attr.ends_with("-count"));
                lines.push((group, count << 63 | wme.timetag, wme));
            }
        }
        lines.sort_by_key(|(g, k, _)| (*g, *k));
        lines.into_iter().map(|(g, _, w)| (g, w)).collect()
    }

    /// The items of an operator impasse of `state` that no numeric preference values:
    /// the substate's `^non-numeric` (Soar manual, ch. 3, "Impasses in working memory").
    pub(super) fn non_numeric_items(&self, state: Sym, items: &[Sym]) -> Vec<Sym> {
        let slot = self.decider.slots.get(&(state, self.symbols.known.operator));
        let numeric = |it: Sym| {
            slot.is_some_and(|slot| {
                slot.prefs_for(it).any(|pid| {
                    let p = &self.decider.prefs[pid];
                    p.kind == PrefType::NumericIndifferent && p.value == it
                })
            })
        };
        items.iter().copied().filter(|&it| !numeric(it)).collect()
    }

    /// Creates (or keeps) the substate for an impasse at goal `gi`, with its architecture
    /// WMEs in 9.6's order.
    pub(super) fn impasse(
        &mut self,
        gi: usize,
        kind: ImpasseKind,
        on_operator: bool,
        items: Vec<Sym>,
    ) {
        if let Some(sub) = self.decider.goals.get(gi + 1) {
            if sub.impasse == Some((kind, on_operator)) && sub.items == items {
                return;
            }
        }
        self.remove_goals_below(gi);
        let parent = self.decider.goals[gi].state;
        let level = self.decider.goals[gi].level + 1;
        if kind == ImpasseKind::NoChange && !on_operator && self.settings.wait_snc {
            self.flush_impasse_item_updates();
            // Waiting: the bottom state's own line again, impasse included, as 9.6 prints.
            if self.settings.trace.decisions {
                self.emit(&TraceEvent::State {
                    cycle: self.decider.d_cycle_count,
                    level: level - 1,
                    state: parent,
                    impasse: self.decider.goals[gi].impasse,
                });
            }
            return;
        }
        let s = self.symbols.new_id('S', level);
        if let Some(d) = self.symbols.id_data_mut(s) {
            d.is_goal = true;
            d.is_impasse = true;
        }
        let k = self.symbols.known;
        let mut wmes = Vec::with_capacity(16 + 2 * items.len());
        let mut add = |agent: &mut AgentCore, id: Sym, attr: Sym, value: Sym| {
            // Into working memory now; the matcher gets them below, newest first.
            wmes.push(agent.wm.add(id, attr, value, false));
        };
        add(self, s, k.type_, k.state);
        add(self, s, k.superstate, parent);
        let r = self.symbols.new_id('R', level);
        add(self, s, k.reward_link, r);
        let e = self.symbols.new_id('E', level);
        add(self, s, k.epmem, e);
        let c = self.symbols.new_id('C', level);
        add(self, e, k.command, c);
        let r2 = self.symbols.new_id('R', level);
        add(self, e, k.result, r2);
        // The next episode's number (1 until episodic memory stores one).
        let present = self.symbols.int(self.epmem.time());
        add(self, e, k.present_id, present);
        let l = self.symbols.new_id('L', level);
        add(self, s, k.smem, l);
        let c2 = self.symbols.new_id('C', level);
        add(self, l, k.command, c2);
        let r3 = self.symbols.new_id('R', level);
        add(self, l, k.result, r3);
        let attr = if on_operator { k.operator } else { k.state };
        add(self, s, k.attribute, attr);
        let imp = self.symbols.str(kind.word());
        add(self, s, k.impasse, imp);
        let choices = if matches!(kind, ImpasseKind::Tie | ImpasseKind::Conflict) {
            k.multiple
        } else {
            k.none
        };
        add(self, s, k.choices, choices);
        add(self, s, k.quiescence, k.t);
        if !items.is_empty() {
            let non_numeric = self.non_numeric_items(parent, &items);
            // 9.6 backs each `^item` and `^non-numeric` with an instantiation of its own
            // (counted by `chunk stats`).
            self.learn.stats.item_instantiations += (items.len() + non_numeric.len()) as u64;
            for &it in &items {
                add(self, s, k.item, it);
            }
            let n = self.symbols.int(items.len() as i64);
            add(self, s, k.item_count, n);
            for &it in &non_numeric {
                add(self, s, k.non_numeric, it);
            }
            let n = self.symbols.int(non_numeric.len() as i64);
            add(self, s, k.non_numeric_count, n);
        }
        // 9.6 prints the depth message before the new state's WMEs and line.
        if level as i64 > self.settings.max_goal_depth {
            self.emit(&TraceEvent::GoalDepthExceeded {
                max_depth: self.settings.max_goal_depth,
            });
            // 9.6 stops the run here without halting the agent: a later `run` goes on
            // deeper, with the same message at each new state (checked on soar-sml 9.6.5).
            self.decider.depth_exceeded = true;
        }
        self.decider.wme_changes += wmes.len() as u64;
        self.mark_queued_matches();
        for &w in wmes.iter().rev() {
            if let Some(wme) = self.wm.get(w).copied() {
                self.trace_wme(true, &wme);
                self.match_wme_now(w, (wme.id, wme.attr, wme.value), false);
            }
        }
        self.flush_impasse_item_updates();
        if self.settings.trace.decisions {
            self.emit(&TraceEvent::State {
                cycle: self.decider.d_cycle_count,
                level,
                state: s,
                impasse: Some((kind, on_operator)),
            });
        }
        // Each goal level has its RL trace from the first state at that level on.
        self.rl.trace.root(level);
        self.decider.goals.push(Goal {
            state: s,
            level,
            operator: None,
            impasse: Some((kind, on_operator)),
            items,
            wmes,
            slot_changed: true,
            made: self.decider.spare_goal_made.pop().unwrap_or_default(),
                learned_below: false,
                osk: None,
        });
    }

    /// Removes every goal below `gi`, deepest first, with its architecture WMEs; what they
    /// held up goes with the garbage collection.
    pub(crate) fn remove_goals_below(&mut self, gi: usize) {
        while self.decider.goals.len() > gi + 1 {
            let Some(g) = self.decider.goals.pop() else {
                break;
            };
            // A state that goes ends its RL episode: its pending RL rules take the reward
            // collected so far (Soar manual, ch. 5, "Reinforcement Learning").
            self.rl_goal_ends(g.state, false);
            if self.decider.goal_break_level.is_some_and(|l| g.level <= l) {
                self.decider.goal_break_level = None;
                self.decider.goal_retracted = true;
            }
            if self.settings.trace.preferences {
                self.trace_removed_prefs(g.state, &g.made);
            }
            self.remove_goal_prefs(g.state, &g.made);
            if let Some((_, w)) = g.operator {
                self.remove_wme(w);
            }
            for w in g.wmes {
                self.remove_wme(w);
            }
            if let Some(d) = self.symbols.id_data_mut(g.state) {
                d.is_goal = false;
            }
            // Preferences made for the substate's own objects go with it.
            let gone = self.decider.slots.keys_of(g.state);
            for k in gone {
                if let Some(slot) = self.decider.slots.remove(&k) {
                    for &pid in &slot.prefs {
                        self.decider.free_pref(pid);
                    }
                    for w in slot.wmes.values().rev() {
                        self.remove_wme(w);
                    }
                    self.decider.slots.recycle(slot);
                }
            }
            self.decider.gc_candidates.push(g.state);
            if self.decider.gds_sizes.contains_key(&g.state) {
                let orphans = &mut self.decider.gds_orphans;
                self.decider.gds.retain(|&w, member| {
                    let stays = member.goal != g.state;
                    if !stays {
                        orphans.insert(w);
                    }
                    stays
                });
            }
            self.decider.gds_sizes.remove(&g.state);
            let mut made = g.made;
            made.clear();
            self.decider.spare_goal_made.push(made);
        }
        self.collect_garbage();
    }

    /// A removed substate's firings' preferences leave preference memory with it, those
    /// on objects of the states above too: an o-supported result's own preference goes,
    /// and its WME stays only while the learned rule's copy supports it (Soar manual,
    /// ch. 2, "Justifications: Support for results"; 9.6 removes a goal's preferences
    /// with it). The state's own slots go with the state.
    pub(super) fn remove_goal_prefs(&mut self, state: Sym, made: &[MadePref]) {
        for (pid, what) in self.standing_prefs(state, made) {
            if what.0 == state {
                // It goes with the state's slots; its links go now, in this order.
                self.pref_link_removed(pid);
                continue;
            }
            let key = (what.0, what.1);
            if let Some(slot) = self.decider.slots.id_of(&key) {
                if self.decider.slots.slot_mut(slot).remove(pid, what.2) {
                    self.pref_link_removed(pid);
                    self.mark_changed(key, Some(slot));
                    self.decider.slots.drop_if_empty(slot);
                    self.decider.free_pref(pid);
                }
            }
        }
    }

    /// Keeps a substate firing's preference with its goal (a firing's newest first), for
    /// [`Self::trace_removed_prefs`].
    pub(crate) fn note_goal_pref(&mut self, goal: Option<Sym>, pid: PrefId) {
        let Some(gi) = self
            .decider
            .goals
            .iter()
            .position(|g| Some(g.state) == goal)
        else {
            return;
        };
        let p = &self.decider.prefs[pid];
        let what = (p.id, p.attr, p.value);
        let serial = self.decider.pref_serial(pid);
        self.decider.goals[gi].made.push((pid, serial, what));
        // A long-lived substate keeps only the preferences that still stand (amortized).
        let n = self.decider.goals[gi].made.len();
        if n >= 64 && n.is_power_of_two() {
            let state = self.decider.goals[gi].state;
            let mut made = std::mem::take(&mut self.decider.goals[gi].made);
            made.retain(|&(pid, serial, what)| self.made_pref_stands(pid, serial, what, state));
            self.decider.goals[gi].made = made;
        }
    }

    /// Whether preference `pid` is still the one a firing of `state` made saying `what`.
    fn pref_stands(&self, pid: PrefId, what: (Sym, Sym, Sym), state: Sym) -> bool {
        let p = &self.decider.prefs[pid];
        p.alive
            && !p.freed
            && (p.id, p.attr, p.value) == what
            && p.inst
                .is_none_or(|i| self.decider.insts[i].goal == Some(state))
    }

    /// 9.6's trace 5 lists the standing preferences of a removed state's firings as
    /// removed (`- (S1 ^r x +) [level 2] (rule)`) before the state's WMEs go: firings
    /// oldest first, each one's preferences newest first, o-supported ones that outlived
    /// their firing too (checked on soar-sml 9.6.5: agents gds, substate-results,
    /// justification-negation).
    pub(super) fn trace_removed_prefs(&mut self, state: Sym, made: &[MadePref]) {
        for (pid, _) in self.standing_prefs(state, made) {
            if self.decider.prefs_traced_gone.contains(&pid) {
                continue;
            }
            self.trace_pref('-', pid);
            self.decider.prefs_traced_gone.push(pid);
        }
    }

    /// The preferences of `made` (a goal's, oldest first) that still stand, in that order.
    fn standing_prefs(
        &self,
        state: Sym,
        made: &[MadePref],
    ) -> Vec<(PrefId, (Sym, Sym, Sym))> {
        made.iter()
            .filter(|&&(pid, serial, what)| self.made_pref_stands(pid, serial, what, state))
            .map(|&(pid, _, what)| (pid, what))
            .collect()
    }

    /// Whether the preference `made` noted as handle `pid` with allocation number `serial`
    /// still holds the handle and stands (a handle is reused once its preference is freed).
    fn made_pref_stands(&self, pid: PrefId, serial: u64, what: (Sym, Sym, Sym), state: Sym) -> bool {
        self.decider.pref_serial(pid) == serial && self.pref_stands(pid, what, state)
    }
}
