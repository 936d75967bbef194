//! `production break` (alias `pbreak`; Soar manual, ch. 9, `production`): a rule with a
//! break interrupts the run when it gets a new match. The interrupt is reported at match
//! time, in 9.6's words, and the run stops after the phase it happened in.

use super::state::Phase;
use crate::agent::AgentCore;

impl AgentCore {
    /// Sets (`on`) or clears the break of a loaded rule; false for no such rule. A break
    /// set again keeps its count of interrupts.
    pub(crate) fn set_break(&mut self, name: &str, on: bool) -> bool {
        let Some(id) = self.loaded(name).map(|l| l.id) else {
            return false;
        };
        if on {
            self.break_rules.entry(name.to_string()).or_insert(1);
            self.matches.breaks.insert(id);
        } else {
            self.break_rules.shift_remove(name);
            self.matches.breaks.remove(&id);
        }
        true
    }

    /// Reports the new matches of rules with a break, as 9.6 does at match time: the rule,
    /// the phase (9.6's numbers: input 0, propose 1, decide 2, apply 3, output 4) and the
    /// rule's count of interrupts; each asks the run to stop after its phase.
    pub(crate) fn report_break_hits(&mut self) {
        self.report_break_hits_in(self.decider.phase.unwrap_or(Phase::Input));
    }

    /// [`AgentCore::report_break_hits`] for matches made in `phase` (which the decider has
    /// left when the phase ends).
    pub(crate) fn report_break_hits_in(&mut self, phase: Phase) {
        if self.matches.break_hits.is_empty() {
            return;
        }
        let phase = match phase {
            Phase::Input => 0,
            Phase::Propose => 1,
            Phase::Decide => 2,
            Phase::Apply => 3,
            Phase::Output => 4,
        };
        for id in std::mem::take(&mut self.matches.break_hits) {
            let Some(name) = self.production_by_id(id).map(|p| p.name.clone()) else {
                continue;
            };
            let Some(count) = self.break_rules.get_mut(name.as_str()) else {
                continue;
            };
            *count += 1;
            let count = *count;
            self.decider.break_interrupted = true;
            self.output.push_str(&format!(
                "\n*** Production match-time interrupt (:interrupt), probably from {name}\n    [Phase] (Interrupt, Stop) is [{phase}] ({count},1)\n"
            ));
        }
    }
}
