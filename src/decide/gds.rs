//! The goal dependency set (Soar manual, chapter 2, "Removal of Substates: The Goal Dependency
//! Set"): when a substate's firing makes its first o-supported WME, the superstate WMEs its
//! reasoning tested join that substate's GDS, following local i-supported WMEs back through
//! the instantiations that made them (local o-supported WMEs stop the search), with the
//! architecture's WMEs met on the way. When a WME in a goal's GDS leaves working memory by
//! a slot's decision (or as input, or forgotten), that goal and every goal below it go, and
//! the next decision can make the impasse again.

use super::procedure::PrefType;
use super::state::{GdsMember, InstId, PrefId};
use crate::agent::AgentCore;
use crate::symbols::Sym;
use crate::wm::WmeId;

impl AgentCore {
    pub(crate) fn sym_level(&self, s: Sym) -> u32 {
        self.symbols.id_data(s).map_or(0, |d| d.level)
    }

    /// Whether a WME stands on its slot's preferences, or is the operator a state
    /// selected (rather than the architecture's or input).
    pub(crate) fn held_by_preferences(&self, w: WmeId, wme: &crate::wm::Wme) -> bool {
        let in_slot = self
            .decider
            .slots
            .get(&(wme.id, wme.attr))
            .and_then(|s| s.wmes.get(&(wme.value, wme.acceptable)))
            == Some(w);
        in_slot
            || self
                .decider
                .goals
                .iter()
                .any(|g| g.operator.is_some_and(|(_, ow)| ow == w))
    }

    /// The WMEs an instantiation's match holds, in condition order; none once it is gone.
    pub(crate) fn live_match_wmes(&self, i: InstId) -> Vec<WmeId> {
        let x = &self.decider.insts[i];
        if x.alive {
            self.rete.match_wmes(x.prod, x.token)
        } else {
            Vec::new()
        }
    }

    /// The preference 9.6 keeps with a slot's WME (its `w->preference`): the first require,
    /// else the first acceptable, preference for the WME's value in 9.6's order (see
    /// [`Self::prefs_in_order`]); the operator a state selected stands on its proposal.
    /// `None` for a WME without one (the architecture's, input).
    fn wme_preference(&self, w: WmeId, wme: &crate::wm::Wme) -> Option<PrefId> {
        if !self.held_by_preferences(w, wme) {
            return None;
        }
        let slot = self.decider.slots.get(&(wme.id, wme.attr))?;
        // The first of each kind in 9.6's order: the lowest (level, newest) key.
        let mut best: [Option<(u32, usize, PrefId)>; 2] = [None, None];
        for (k, pid) in slot.prefs_for(wme.value).enumerate() {
            let p = &self.decider.prefs[pid];
            let kind = match p.kind {
                _ if !p.alive => continue,
                PrefType::Require => 0,
                PrefType::Acceptable => 1,
                _ => continue,
            };
            let key = (self.pref_level(pid), usize::MAX - k, pid);
            if best[kind].is_none_or(|b| key < b) {
                best[kind] = Some(key);
            }
        }
        best[0].or(best[1]).map(|b| b.2)
    }

    /// Live preferences of one kind from a slot's list (all of it, or one value's, oldest
    /// first) in the order of 9.6's list: by the goal level they were made at, the highest
    /// goal first (so a result's copy in a learned rule's firing comes before the substate
    /// firing's own), the newest first within a level.
    fn prefs_in_order(
        &self,
        prefs: impl Iterator<Item = PrefId>,
        kind: PrefType,
    ) -> Vec<PrefId> {
        let mut found: Vec<(u32, usize, PrefId)> = prefs
            .enumerate()
            .filter(|&(_, pid)| {
                let p = &self.decider.prefs[pid];
                p.alive && p.kind == kind
            })
            .map(|(k, pid)| (self.pref_level(pid), usize::MAX - k, pid))
            .collect();
        found.sort_unstable();
        found.into_iter().map(|x| x.2).collect()
    }

    /// The goal level a preference was made at: its firing's match goal, or for one without
    /// a firing (a memory's retrieval) its identifier's level.
    fn pref_level(&self, pid: PrefId) -> u32 {
        let p = &self.decider.prefs[pid];
        p.inst
            .and_then(|i| self.decider.insts[i].goal)
            .map_or_else(|| self.sym_level(p.id), |g| self.sym_level(g))
    }

    /// A WME just added to a slot: when its preference is an o-supported one a substate's
    /// firing made and that substate has no GDS yet, the substate's GDS is made now, from
    /// the firings behind that preference and the older acceptable preferences of the slot
    /// made at the same level (9.6's `decide_non_context_slot`). A substate with a GDS
    /// adds nothing for later o-supported WMEs; it gets a new one only after its set has
    /// emptied (its WMEs moved up to a higher goal's set).
    pub(crate) fn gds_for_new_wme(&mut self, w: WmeId) {
        let Some(wme) = self.wm.get(w).copied() else {
            return;
        };
        // Only an o-supported preference from a substate's firing whose goal has no set can
        // make one: most new WMEs are passed over here, before the slot's list is ordered.
        let slot = self.decider.slots.get(&(wme.id, wme.attr));
        let possible = slot.is_some_and(|slot| {
            slot.prefs_for(wme.value).any(|pid| {
                let p = &self.decider.prefs[pid];
                p.o_support
                    && p.inst
                        .and_then(|i| self.decider.insts[i].goal)
                        .is_some_and(|g| {
                            self.sym_level(g) >= 2 && !self.decider.gds_sizes.contains_key(&g)
                        })
            })
        });
        if !possible {
            return;
        }
        let Some(win) = self.wme_preference(w, &wme) else {
            return;
        };
        let p = &self.decider.prefs[win];
        let Some(goal) = p.inst.and_then(|i| self.decider.insts[i].goal) else {
            return;
        };
        if !p.o_support || self.decider.gds_sizes.contains_key(&goal) {
            return;
        }
        let level = self.sym_level(goal);
        if level <= 1 {
            return;
        }
        self.decider.gds_sizes.insert(goal, 0);
        let Some(slot) = self.decider.slots.get(&(wme.id, wme.attr)) else {
            return;
        };
        // The slot's acceptable preferences in 9.6's order, from the WME's own on.
        let acceptable: Vec<PrefId> = self
            .prefs_in_order(slot.prefs.iter().copied(), PrefType::Acceptable)
            .into_iter()
            .skip_while(|&pid| pid != win)
            .collect();
        let mut parents = std::mem::take(&mut self.decider.gds_parents);
        parents.clear();
        for pid in acceptable {
            let Some(i) = self.decider.prefs[pid].inst else {
                continue;
            };
            if !self.decider.insts[i].gds_evaluated && self.pref_level(pid) == level {
                self.decider.insts[i].gds_evaluated = true;
                if !parents.contains(&i) {
                    parents.push(i);
                }
            }
        }
        // 9.6 puts each at the head of its list of firings to walk.
        parents.reverse();
        self.elaborate_gds(&mut parents);
        self.decider.gds_parents = parents;
    }

    /// Grows goal dependency sets from the firings in `parents` (and, through local
    /// i-supported WMEs, the firings that made those), each into its own goal's set: the
    /// WMEs of higher goals its match tested and the architecture's WMEs it tested join the
    /// set; a local o-supported WME stops the walk (9.6's `elaborate_gds`). Each firing is
    /// walked once, ever. The walk goes as 9.6's does (and `trace --gds-wmes` lists the
    /// WMEs in that order): `parents` in order, then the firings they led to, the last
    /// found first, and so on.
    fn elaborate_gds(&mut self, parents: &mut Vec<InstId>) {
        let mut found = std::mem::take(&mut self.decider.gds_found);
        while !parents.is_empty() {
            found.clear();
            for &inst in parents.iter() {
                self.walk_gds_firing(inst, &mut found);
            }
            parents.clear();
            parents.extend(found.iter().rev());
        }
        self.decider.gds_found = found;
    }

    /// One firing of [`Self::elaborate_gds`]'s walk: its WMEs join its goal's set, and the
    /// firings behind its local i-supported WMEs go onto `found`.
    fn walk_gds_firing(&mut self, inst: InstId, found: &mut Vec<InstId>) {
        let Some(goal) = self.decider.insts[inst].goal else {
            return;
        };
        let level = self.sym_level(goal);
        if level <= 1 || !self.decider.gds_sizes.contains_key(&goal) {
            return;
        }
        let matched = self.live_match_wmes(inst);
        for w in matched {
            let Some(wme) = self.wm.get(w).copied() else {
                continue;
            };
            let local = self.sym_level(wme.id) >= level;
            if !local || !self.held_by_preferences(w, &wme) {
                // A higher goal's WME, or the architecture's (a local impasse item
                // stands for the acceptable-preference WME above it).
                let item = local.then(|| self.impasse_item_support(w, &wme)).flatten();
                self.join_gds(item.unwrap_or(w), goal, level);
                continue;
            }
            // A local WME: an o-supported one ends the walk; an i-supported one leads
            // to the firings that make it (none when its preference went this cycle).
            let pref = self.wme_preference(w, &wme);
            if pref.is_some_and(|p| self.decider.prefs[p].o_support) {
                continue;
            }
            let Some(slot) = self.decider.slots.get(&(wme.id, wme.attr)) else {
                continue;
            };
            let makers = self.prefs_in_order(slot.prefs_for(wme.value), PrefType::Acceptable);
            for pid in makers {
                let Some(i) = self.decider.prefs[pid].inst else {
                    continue;
                };
                if self.decider.insts[i].gds_evaluated {
                    continue;
                }
                self.decider.insts[i].gds_evaluated = true;
                // A preference from a lower goal's firing (a result's) is left to the
                // learned rule's firing at this level.
                if self.pref_level(pid) <= level && !found.contains(&i) {
                    found.push(i);
                }
            }
        }
    }

    /// For an impasse's `^item` WME, the acceptable-preference WME in the state above that
    /// it shows (9.6 makes the item with a preference of its own, backed by that WME).
    fn impasse_item_support(&self, w: WmeId, wme: &crate::wm::Wme) -> Option<WmeId> {
        let goals = &self.decider.goals;
        let k = goals.iter().position(|g| g.state == wme.id)?;
        if k == 0 || !goals[k].wmes.contains(&w) || !goals[k].items.contains(&wme.value) {
            return None;
        }
        let above = goals[k - 1].state;
        self.decider
            .slots
            .get(&(above, self.top.operator))
            .and_then(|s| s.wmes.get(&(wme.value, true)))
    }

    /// `w` joins `goal`'s set, unless the set of `goal` or of a goal above it has it: a WME
    /// is charged to the highest goal that depends on it, as removing that goal removes the
    /// lower ones too. A lower goal's set that it leaves empty is no more.
    fn join_gds(&mut self, w: WmeId, goal: Sym, level: u32) {
        if let Some(had) = self.decider.gds.get(&w).map(|m| m.goal) {
            if self.sym_level(had) <= level {
                return;
            }
            self.leave_gds(had);
        }
        self.decider.gds_joins += 1;
        let joined = self.decider.gds_joins;
        self.decider.gds.insert(w, GdsMember { goal, joined });
        if !self.decider.gds_orphans.is_empty() {
            self.decider.gds_orphans.remove(&w);
        }
        *self.decider.gds_sizes.entry(goal).or_insert(0) += 1;
        if self.settings.trace.gds_wmes {
            if let Some(wme) = self.wm.get(w).copied() {
                let activation = self.wme_activation(&wme);
                self.emit(&crate::trace_events::TraceEvent::GdsAdd {
                    goal,
                    wme: &wme,
                    activation,
                });
            }
        }
    }

    /// Whether taking `wme` out of working memory removes the goal whose set holds it: 9.6
    /// checks the WMEs a slot decision takes out, input WMEs, memory results and WMEs
    /// forgotten, but not a state's architecture WMEs, its selected operator, acceptable-
    /// preference WMEs, nor the WMEs garbage collection takes.
    pub(crate) fn gds_watches_removal(&self, wme: &crate::wm::Wme) -> bool {
        if wme.acceptable || self.decider.collecting_garbage {
            return false;
        }
        if !self.symbols.is_goal(wme.id) {
            return true;
        }
        let named = |names: &[&str]| names.iter().any(|n| self.symbols.find_str(n) == Some(wme.attr));
        wme.attr != self.top.operator
            && !named(&super::state::STATE_ARCH_ATTRS)
            && !named(&super::state::STATE_MODULE_ATTRS)
    }

    /// A WME left `goal`'s set; the set goes when it is empty.
    pub(crate) fn leave_gds(&mut self, goal: Sym) {
        if let Some(n) = self.decider.gds_sizes.get_mut(&goal) {
            *n = n.saturating_sub(1);
            if *n == 0 {
                self.decider.gds_sizes.remove(&goal);
            }
        }
    }

    /// Removes the highest goal whose GDS holds one of `removes` (WMEs about to go, with
    /// their timetags), and every goal below it.
    pub(crate) fn remove_gds_goals_of(&mut self, removes: &[(crate::wm::WmeId, u64)]) {
        if self.decider.gds.is_empty() {
            return;
        }
        let top_index = removes
            .iter()
            .filter_map(|&(w, tt)| {
                let goal = self.decider.gds.get(&w)?.goal;
                let watched = self.wm.get(w);
                watched
                    .is_some_and(|x| x.timetag == tt && self.gds_watches_removal(x))
                    .then_some(goal)
            })
            .filter_map(|g| self.decider.goals.iter().position(|x| x.state == g))
            .min();
        if let Some(top_index) = top_index.filter(|&i| i > 0) {
            if self.settings.trace.wmes && self.removed_wmes.is_some() {
                let goal = self.decider.goals[top_index].state;
                self.gds_trigger = removes
                    .iter()
                    .find(|&&(w, tt)| {
                        self.wm
                            .get(w)
                            .is_some_and(|x| x.timetag == tt && self.gds_watches_removal(x))
                            && self.decider.gds.get(&w).map(|m| m.goal) == Some(goal)
                    })
                    .map(|&(_, tt)| tt);
                self.collect_substate_removals(top_index - 1);
                self.substate_slot_order = self.substate_pref_slots(top_index - 1);
                self.substates_by_gds = true;
            }
            self.remove_goal_and_below(top_index);
        }
    }

    /// Removes the goal at `top_index` (not the top state) with every goal below it; the
    /// goal above may impasse again at the next decision.
    fn remove_goal_and_below(&mut self, top_index: usize) {
        self.remove_goals_below(top_index - 1);
        self.decider.goals[top_index - 1].slot_changed = true;
    }

    /// Removes the goals whose GDS lost a WME (the highest first, with all below).
    pub(crate) fn remove_invalid_gds_goals(&mut self) {
        let invalid = std::mem::take(&mut self.decider.gds_invalid);
        let Some(top_index) = invalid
            .iter()
            .filter_map(|g| self.decider.goals.iter().position(|x| x.state == *g))
            .min()
        else {
            return;
        };
        if top_index > 0 {
            self.remove_goal_and_below(top_index);
        }
    }
}
