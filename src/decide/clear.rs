//! Clearing the goal stack at `init-soar`: every state goes, lowest first, and working
//! memory empties in the order 9.6 hands its removals to the matcher. That order is not
//! seen in any trace (9.6 prints no `<=WM:` lines at `init-soar`), but it decides how the
//! matcher's joins are unlinked and linked again, and with that the order in which rules
//! built before `init-soar` match after it.

use crate::agent::AgentCore;
use crate::wm::WmeId;

impl AgentCore {
    /// Removes every goal and every WME. As in 9.6, all of it is one phase: each goal,
    /// lowest first, gives up the preferences its firings made (oldest first), its
    /// selected operator's WME and its own architecture WMEs (newest first), and loses the
    /// link that kept it; then the operators' `+` WMEs go (the top state's first); then the
    /// garbage collection takes everything the goals held. The matcher hears of the
    /// removals in the reverse of that order: the collected WMEs first, the goals'
    /// selected operators last.
    pub(super) fn clear_goal_stack(&mut self) {
        let mut listed: Vec<(WmeId, u64)> = Vec::new();
        let mut states = Vec::new();
        while let Some(g) = self.decider.goals.pop() {
            self.remove_goal_prefs(g.state, &g.made);
            let mut own = g.wmes;
            if g.level == 1 {
                own.extend(self.top_state_architecture_wmes());
            }
            own.sort_by_key(|&w| std::cmp::Reverse(self.wm.get(w).map(|x| x.timetag)));
            for w in g.operator.map(|o| o.1).into_iter().chain(own) {
                self.leave_listed(w, &mut listed);
            }
            if let Some(d) = self.symbols.id_data_mut(g.state) {
                d.is_goal = false;
            }
            self.decider.gc_candidates.push(g.state);
            states.push(g.state);
        }
        let operator = self.top.operator;
        for &state in states.iter().rev() {
            let Some(slot) = self.decider.slots.get(&(state, operator)) else {
                continue;
            };
            let plus: Vec<WmeId> = slot.wmes.iter().rev().filter(|e| e.1).map(|e| e.2).collect();
            for w in plus {
                self.leave_listed(w, &mut listed);
            }
        }
        self.collect_all_garbage();
        for &(w, timetag) in listed.iter().rev() {
            self.unmatch_wme(w, timetag);
        }
        // What no state linked to (input on an unlinked identifier) goes last, newest first.
        for w in self.wm.all().into_iter().rev() {
            self.remove_wme(w);
        }
    }

    /// Takes `w` out of working memory, noting it for the matcher in `listed`.
    fn leave_listed(&mut self, w: WmeId, listed: &mut Vec<(WmeId, u64)>) {
        let Some(timetag) = self.wm.get(w).map(|x| x.timetag) else {
            return;
        };
        if self.remove_wme_leaving_matcher(w).is_some() {
            listed.push((w, timetag));
        }
    }

    /// The top state's `^type state` and `^superstate nil`, which 9.6 keeps with the state
    /// (as it keeps a substate's impasse WMEs) rather than in a slot.
    fn top_state_architecture_wmes(&self) -> Vec<WmeId> {
        let s = self.top.state;
        let pairs = [("type", "state"), ("superstate", "nil")]
            .map(|(a, v)| (self.symbols.find_str(a), self.symbols.find_str(v)));
        self.wm
            .of_id(s)
            .filter(|&w| {
                self.wm.get(w).is_some_and(|x| {
                    self.decider.slots.get(&(s, x.attr)).is_none()
                        && pairs.contains(&(Some(x.attr), Some(x.value)))
                })
            })
            .collect()
    }
}
