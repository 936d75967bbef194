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
use crate::trace_events::TraceEvent;
use crate::wm::WmeId;
use rustc_hash::FxHashSet;

impl AgentCore {
    pub(crate) fn sym_level(&self, s: Sym) -> u32 {
        self.symbols.id_data(s).map_or(0, |d| d.level)
    }

    /// The live instantiation behind a WME, if an i-supported preference makes it: `None`
    /// for o-supported and architecture WMEs (the search stops there).
    fn i_support_of(&self, w: WmeId) -> Option<InstId> {
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

    /// Grows the GDS of the goal `inst` matched in: each WME its match tested that belongs
    /// to a higher goal joins it; a local WME that an i-supported instantiation made leads
    /// on to that instantiation's match; local o-supported WMEs stop the search. The
    /// instantiations are visited in the order they are reached (each match's WMEs in
    /// condition order), which is the order `trace --gds-wmes` lists the WMEs in, as 9.6
    /// does; it also lists the goal's own architecture WMEs the reasoning tested.
    pub(crate) fn elaborate_gds(&mut self, inst: InstId) {
        let Some(goal) = self.decider.insts[inst].goal else {
            return;
        };
        let level = self.sym_level(goal);
        if level <= 1 {
            return;
        }
        let traced = self.settings.trace.gds_wmes;
        let mut seen: FxHashSet<InstId> = FxHashSet::default();
        let mut queue = std::collections::VecDeque::from([inst]);
        while let Some(i) = queue.pop_front() {
            if !seen.insert(i) || !self.decider.insts[i].alive {
                continue;
            }
            let (prod, token) = {
                let x = &self.decider.insts[i];
                (x.prod, x.token)
            };
            for w in self.rete.match_wmes(prod, token) {
                let Some(wme) = self.wm.get(w).copied() else {
                    continue;
                };
                if self.sym_level(wme.id) < level {
                    self.add_to_gds(w, &wme, goal, level, traced);
                    continue;
                }
                match self.local_support(w, &wme) {
                    LocalSupport::Instantiation(j) => queue.push_back(j),
                    LocalSupport::Candidate(a) => {
                        if let Some(acc) = self.wm.get(a).copied() {
                            self.add_to_gds(a, &acc, goal, level, traced);
                        }
                    }
                    LocalSupport::OSupported => {}
                    LocalSupport::Architecture => {
                        if traced && self.decider.gds_traced_local.insert(wme.timetag) {
                            self.emit(&TraceEvent::GdsAdd { goal, wme: &wme });
                        }
                    }
                }
            }
        }
    }

    /// A WME of a higher goal joins `goal`'s GDS: it is charged to the highest goal that
    /// depends on it, since removing that goal removes the lower ones too.
    fn add_to_gds(&mut self, w: WmeId, wme: &crate::wm::Wme, goal: Sym, level: u32, traced: bool) {
        // (A higher goal's own architecture WME is in that goal's GDS for the listing.)
        let keep = self
            .decider
            .gds
            .get(&w)
            .is_some_and(|&g| self.sym_level(g) <= level)
            || (traced && self.decider.gds_traced_local.contains(&wme.timetag));
        if !keep {
            self.decider.gds.insert(w, goal);
            if traced {
                self.emit(&TraceEvent::GdsAdd { goal, wme });
            }
        }
    }

    /// What holds a WME of the goal's own level in working memory, for the GDS search.
    fn local_support(&self, w: WmeId, wme: &crate::wm::Wme) -> LocalSupport {
        if let Some(j) = self.i_support_of(w) {
            return LocalSupport::Instantiation(j);
        }
        let goals = &self.decider.goals;
        let own = goals.iter().position(|g| g.state == wme.id);
        if let Some(k) = own.filter(|&k| goals[k].wmes.contains(&w)) {
            // An impasse's `^item` stands for a candidate's acceptable preference in the
            // state above: that preference's WME joins the GDS in its place.
            if k > 0 && goals[k].items.contains(&wme.value) {
                let above = goals[k - 1].state;
                if let Some(a) = self
                    .decider
                    .slots
                    .get(&(above, self.top.operator))
                    .and_then(|s| s.wmes.get(&(wme.value, true)))
                {
                    return LocalSupport::Candidate(a);
                }
            }
            return LocalSupport::Architecture;
        }
        let from_prefs = self
            .decider
            .slots
            .get(&(wme.id, wme.attr))
            .and_then(|s| s.wmes.get(&(wme.value, wme.acceptable)))
            == Some(w);
        let selected = self
            .decider
            .goals
            .iter()
            .any(|g| g.operator.is_some_and(|(_, ow)| ow == w));
        if from_prefs || selected {
            return LocalSupport::OSupported;
        }
        LocalSupport::Architecture
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

/// What holds a WME of a goal's own level, for the GDS search.
enum LocalSupport {
    /// An i-supported preference: the search goes on through its instantiation.
    Instantiation(InstId),
    /// An impasse's `^item`: the candidate's acceptable-preference WME in the state above.
    Candidate(WmeId),
    /// An o-supported preference (or the decision that selected an operator): the search
    /// stops.
    OSupported,
    /// No preference: the architecture's WME of the state (or an input WME). 9.6 lists it
    /// as joining the GDS; it leaves only with the state.
    Architecture,
}
