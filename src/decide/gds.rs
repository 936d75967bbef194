//! The goal dependency set (Soar manual, chapter 2, "Removal of Substates: The Goal Dependency
//! Set"): when a substate makes an o-supported WME, the superstate WMEs its reasoning
//! tested join that substate's GDS, following local i-supported WMEs back through the
//! instantiations that made them (local o-supported WMEs stop the search). When a WME in a
//! goal's GDS leaves working memory, that goal and every goal below it go, and the next
//! decision can make the impasse again.

use super::procedure::PrefType;
use super::state::InstId;
use crate::agent::AgentCore;
use crate::symbols::Sym;
use crate::wm::WmeId;

impl AgentCore {
    pub(crate) fn sym_level(&self, s: Sym) -> u32 {
        self.symbols.id_data(s).map_or(0, |d| d.level)
    }

    /// The live instantiation behind a WME, if an i-supported preference makes it: `None`
    /// for o-supported and architecture WMEs (the search stops there).
    pub(crate) fn i_support_of(&self, w: WmeId) -> Option<InstId> {
        let wme = self.wm.get(w)?;
        // A selected operator stands on its acceptable preference (its proposal), like any
        // other WME on its slot's acceptable preferences.
        let slot = self.decider.slots.get(&(wme.id, wme.attr))?;
        let mut found = None;
        for pid in slot.prefs_for(wme.value) {
            let p = &self.decider.prefs[pid];
            if !p.alive || p.kind != PrefType::Acceptable || p.value != wme.value {
                continue;
            }
            if p.o_support {
                return None;
            }
            if found.is_none() {
                found = p.inst;
            }
        }
        found
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

    /// A WME just added: if an o-supported preference of an instantiation that matched in a
    /// substate made it, that substate's GDS grows.
    pub(crate) fn gds_for_new_wme(&mut self, w: WmeId) {
        let Some(wme) = self.wm.get(w).copied() else {
            return;
        };
        let Some(slot) = self.decider.slots.get(&(wme.id, wme.attr)) else {
            return;
        };
        let inst = slot.prefs_for(wme.value).find_map(|pid| {
            let p = &self.decider.prefs[pid];
            (p.alive && p.o_support && p.kind == PrefType::Acceptable && p.value == wme.value)
                .then_some(p.inst)
                .flatten()
        });
        if let Some(i) = inst {
            self.elaborate_gds(i);
        }
    }

    fn elaborate_gds(&mut self, inst: InstId) {
        let Some(goal) = self.decider.insts[inst].goal else {
            return;
        };
        let level = self.sym_level(goal);
        if level <= 1 {
            return;
        }
        // The firings waiting and the superstate WMEs found: few in each walk, kept for
        // their room. A firing is walked once per goal (as 9.6 marks an instantiation
        // whose dependencies it has gathered): its match, and so what it adds, never
        // changes.
        let mut stack = std::mem::take(&mut self.decider.gds_scratch.stack);
        let mut found = std::mem::take(&mut self.decider.gds_scratch.found);
        stack.push(inst);
        while let Some(i) = stack.pop() {
            let x = &mut self.decider.insts[i];
            if !x.alive || x.gds_walked == Some(goal) {
                continue;
            }
            x.gds_walked = Some(goal);
            let x = &self.decider.insts[i];
            for w in self.rete.match_row(x.prod, x.token) {
                let Some(wme) = self.wm.get(w) else { continue };
                let l = self.sym_level(wme.id);
                if l < level {
                    found.push(w);
                } else if let Some(j) = self.i_support_of(w) {
                    stack.push(j);
                }
            }
        }
        for &w in &found {
            // A WME is charged to the highest goal that depends on it: removing that goal
            // removes the lower ones too.
            let keep = self
                .decider
                .gds
                .get(&w)
                .is_some_and(|&g| self.sym_level(g) <= level);
            if !keep {
                self.decider.gds.insert(w, goal);
            }
        }
        found.clear();
        self.decider.gds_scratch = super::state::GdsScratch { stack, found };
    }

    /// Removes the highest goal whose GDS holds one of `removes` (WMEs about to go, with
    /// their timetags), and every goal below it.
    pub(crate) fn remove_gds_goals_of(&mut self, removes: &[(crate::wm::WmeId, u64)]) {
        if self.decider.gds.is_empty() {
            return;
        }
        let top_index = removes
            .iter()
            .filter(|&&(w, tt)| self.wm.get(w).is_some_and(|x| x.timetag == tt))
            .filter_map(|(w, _)| self.decider.gds.get(w))
            .filter_map(|g| self.decider.goals.iter().position(|x| x.state == *g))
            .min();
        if let Some(top_index) = top_index.filter(|&i| i > 0) {
            if self.settings.trace.wmes && self.removed_wmes.is_some() {
                let goal = self.decider.goals[top_index].state;
                self.gds_trigger = removes
                    .iter()
                    .find(|&&(w, tt)| {
                        self.wm.get(w).is_some_and(|x| x.timetag == tt)
                            && self.decider.gds.get(&w) == Some(&goal)
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
