//! The consistency checks (Soar manual, chapter 2, "Soar's Execution Cycle: Without Substates", and
//! 2.7.7 "Removal of Substates: Impasse Resolution"): a selected operator that is no longer a
//! candidate, or that the preferences would no longer choose, goes at once with every
//! substate below it; so does a substate whose impasse the preferences no longer give. The
//! next decision decides the slot again.

use super::procedure::{self, Outcome, PrefType};
use super::state::ImpasseKind;
use crate::agent::AgentCore;
use crate::symbols::Sym;
use crate::trace_events::TraceEvent;
use crate::wm::WmeId;

impl AgentCore {
    /// The operator installed in a goal stays while it is still a candidate; otherwise it
    /// goes at once, with every substate below. Returns the operator WME to remove
    /// (buffered with the other removals).
    pub(super) fn check_operator_consistency(&mut self, key: (Sym, Sym)) -> Option<WmeId> {
        let gi = self.decider.goals.iter().position(|g| g.state == key.0)?;
        let (op, w) = self.decider.goals[gi].operator?;
        // Read in place: this runs for every changed operator slot.
        let prefs = self.decider.slots.get(&key).map_or(&[][..], |s| s.prefs.as_slice());
        let all = || prefs.iter().map(|&pid| &self.decider.prefs[pid]);
        let still = all().any(|p| p.kind == PrefType::Acceptable && p.value == op)
            && !all().any(|p| matches!(p.kind, PrefType::Reject | PrefType::Prohibit) && p.value == op);
        if still {
            return None;
        }
        if self.settings.trace.consistency {
            self.trace_operator_removal(key, op);
            if let Some(sub) = self.decider.goals.get(gi + 1) {
                let state = sub.state;
                self.emit(&TraceEvent::OperatorRemovalSubstate { state });
            }
        }
        if self.settings.trace.wmes && self.removed_wmes.is_some() {
            self.collect_substate_removals(gi);
        }
        self.remove_goals_below(gi);
        self.decider.goals[gi].operator = None;
        Some(w)
    }

    /// A goal without an operator whose impasse the preferences no longer give (another
    /// kind of impasse, or a choice) loses its substates at once, as 9.6's consistency
    /// check removes them; the next decision decides the slot again.
    pub(super) fn check_impasse_consistency(&mut self, key: (Sym, Sym)) {
        let Some(gi) = self.decider.goals.iter().position(|g| g.state == key.0) else {
            return;
        };
        if let Some((op, w)) = self.decider.goals[gi].operator {
            self.check_selected_operator(gi, key, op, w);
            return;
        }
        let Some(sub) = self.decider.goals.get(gi + 1) else {
            return;
        };
        let Some((kind, on_operator)) = sub.impasse else {
            return;
        };
        // The same kind of impasse is consistent whatever its items: the next decision
        // brings them up to date (checked on soar-sml 9.6.5: a tied candidate evaluated
        // worst leaves the tie, which goes on with the others).
        let consistent = match procedure::candidates(&self.slot_prefs(key)) {
            Ok(_) => false,
            Err(Outcome::NoCandidates) => kind == ImpasseKind::NoChange && !on_operator,
            Err(Outcome::Tie(_)) => kind == ImpasseKind::Tie,
            Err(Outcome::Conflict(_)) => kind == ImpasseKind::Conflict,
            Err(Outcome::ConstraintFailure(_)) => kind == ImpasseKind::ConstraintFailure,
            Err(Outcome::Winner(_)) => false,
        };
        if consistent {
            return;
        }
        self.remove_inconsistent_decision(gi, key, true);
        self.decider.goals[gi].slot_changed = true;
    }

    /// The substates below goal `gi` go because its decision no longer agrees with the
    /// preferences, with 9.6's trace (`remove_current_decision`; the `REMOVING CONTEXT
    /// SLOT` line only when no operator was selected).
    fn remove_inconsistent_decision(&mut self, gi: usize, key: (Sym, Sym), empty_slot: bool) {
        self.decider.decision_inconsistent = true;
        if self.settings.trace.consistency {
            self.emit(&TraceEvent::InconsistentDecision {
                goal: key.0,
                empty_slot,
            });
        }
        if self.settings.trace.preferences {
            // Before the substates' `<=WM:` lines, as 9.6 lists them (not again below).
            for k in (gi + 1..self.decider.goals.len()).rev() {
                let made = self.decider.goals[k].made.clone();
                let state = self.decider.goals[k].state;
                self.trace_removed_prefs(state, &made);
            }
        }
        if self.settings.trace.wmes {
            self.trace_substate_wmes_removed(gi);
        }
        self.remove_held_objects(gi);
        self.remove_goals_below(gi);
    }

    /// A selected operator stays while the preferences still give it among the candidates;
    /// when another operator is now better (or an impasse would come instead), the operator
    /// and every substate below go at once, and the next decision decides the slot again
    /// (consistency.cpp `decision_consistent_with_current_preferences`).
    fn check_selected_operator(&mut self, gi: usize, key: (Sym, Sym), op: Sym, w: WmeId) {
        if matches!(procedure::candidates(&self.slot_prefs(key)), Ok(c) if c.contains(&op)) {
            return;
        }
        self.remove_inconsistent_decision(gi, key, false);
        self.decider.goals[gi].operator = None;
        self.remove_slot_wme(w);
        self.collect_garbage();
        self.decider.goals[gi].slot_changed = true;
    }
}
