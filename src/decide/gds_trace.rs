//! `trace --gds-wmes` (`trace -G`): the WMEs that join a substate's goal dependency set, as
//! 9.6 lists them when an o-supported preference for a substate's own WME is made (the Soar
//! manual, chapter 2, "Removal of Substates: The Goal Dependency Set"). The listing keeps its
//! own record of the sets it has listed: the set that decides removals is `gds.rs`'s.

use super::state::InstId;
use crate::agent::AgentCore;
use crate::symbols::Sym;
use crate::trace_events::TraceEvent;
use crate::wm::{Wme, WmeId};
use rustc_hash::FxHashSet;
use std::collections::VecDeque;

/// What holds a WME of a goal's own level, for the listing's search.
enum LocalSupport {
    /// An i-supported preference: the search goes on through its instantiation.
    Instantiation(InstId),
    /// An impasse's `^item`: the candidate's acceptable-preference WME in the state above.
    Candidate(WmeId),
    /// An o-supported preference (or the decision that selected an operator): the search
    /// stops.
    OSupported,
    /// No preference: the architecture's WME of the state (or an input WME), listed as
    /// joining the set.
    Architecture,
}

impl AgentCore {
    /// Whether firing `inst` (at goal `level`) grows its goal's GDS: it made an o-supported
    /// acceptable preference for a WME of its own goal's level.
    pub(crate) fn grows_gds(&self, inst: InstId, level: u32) -> bool {
        let i = &self.decider.insts[inst];
        level >= 2
            && i.o_support
            && i.prefs.iter().any(|&pid| {
                let p = &self.decider.prefs[pid];
                p.kind == super::procedure::PrefType::Acceptable && self.sym_level(p.id) >= level
            })
    }

    /// Lists the WMEs that firing `inst` adds to its goal's GDS: the WMEs of higher goals
    /// its match tested, following local i-supported WMEs back through the instantiations
    /// that made them, in the order they are reached (each match's WMEs in condition
    /// order), with the goal's own architecture WMEs.
    pub(crate) fn trace_gds_growth(&mut self, inst: InstId) {
        let Some(goal) = self.decider.insts[inst].goal else {
            return;
        };
        let level = self.sym_level(goal);
        // Entries of goals that are gone list nothing more.
        if self.decider.gds_listed.len() > 4096 {
            let goals: FxHashSet<Sym> = self.decider.goals.iter().map(|g| g.state).collect();
            self.decider.gds_listed.retain(|_, g| goals.contains(g));
        }
        let mut seen: FxHashSet<InstId> = FxHashSet::default();
        let mut queue = VecDeque::from([inst]);
        while let Some(i) = queue.pop_front() {
            if !seen.insert(i) {
                continue;
            }
            for w in self.live_match_wmes(i) {
                let Some(wme) = self.wm.get(w).copied() else {
                    continue;
                };
                if self.sym_level(wme.id) < level {
                    self.list_gds_member(&wme, goal, level);
                    continue;
                }
                match self.local_support(w, &wme) {
                    LocalSupport::Instantiation(j) => queue.push_back(j),
                    LocalSupport::Candidate(a) => {
                        if let Some(acc) = self.wm.get(a).copied() {
                            self.list_gds_member(&acc, goal, level);
                        }
                    }
                    LocalSupport::OSupported => {}
                    LocalSupport::Architecture => {
                        let listed = self.decider.gds_listed.get(&wme.timetag);
                        if listed.is_none_or(|g| !self.decider.goals.iter().any(|x| x.state == *g)) {
                            self.decider.gds_listed.insert(wme.timetag, goal);
                            self.emit(&TraceEvent::GdsAdd { goal, wme: &wme });
                        }
                    }
                }
            }
        }
    }

    /// Lists a WME of a higher goal as joining `goal`'s set, unless the set of `goal` or of
    /// a goal above it has it already.
    fn list_gds_member(&mut self, wme: &Wme, goal: Sym, level: u32) {
        let listed = self
            .decider
            .gds_listed
            .get(&wme.timetag)
            .is_some_and(|&g| {
                self.decider.goals.iter().any(|x| x.state == g) && self.sym_level(g) <= level
            });
        if !listed {
            self.decider.gds_listed.insert(wme.timetag, goal);
            self.emit(&TraceEvent::GdsAdd { goal, wme });
        }
    }

    /// What holds a WME of the goal's own level.
    fn local_support(&self, w: WmeId, wme: &Wme) -> LocalSupport {
        if let Some(j) = self.i_support_of(w) {
            return LocalSupport::Instantiation(j);
        }
        let goals = &self.decider.goals;
        let own = goals.iter().position(|g| g.state == wme.id);
        if let Some(k) = own.filter(|&k| goals[k].wmes.contains(&w)) {
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
        if self.held_by_preferences(w, wme) {
            return LocalSupport::OSupported;
        }
        LocalSupport::Architecture
    }
}
