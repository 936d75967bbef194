//! Apoptosis on the agent: the uses of learned rules it counts, and the excision of those
//! whose activation has decayed (see `apoptosis.rs` for the decay itself).

use crate::agent::AgentCore;
use crate::rete::ProdId;

impl AgentCore {
    /// Counts a retracted instantiation as a use of its rule, when the rule is a chunk
    /// apoptosis follows (9.6 counts at retraction, the chunk's own first instantiation
    /// included, so a chunk that never fires again is still forgotten).
    pub(crate) fn apoptosis_note_retraction(&mut self, rule: ProdId) {
        if self.rl.rule_decay.is_none() {
            return;
        }
        let is_chunk = self
            .production_by_id(rule)
            .is_some_and(|p| p.flags.chunk && !p.flags.justification);
        if is_chunk && self.rl.apoptosis_tracks(rule) {
            if let Some(decay) = &mut self.rl.rule_decay {
                decay.reference(rule);
            }
        }
    }

    /// Ends a decision for apoptosis (in the output phase, after the memories, as 9.6
    /// does): excises the forgotten rules that have no instantiation left and, if RL
    /// rules, no update and no state naming them. It prints nothing; the run's count of
    /// new rules goes down by each one.
    pub(crate) fn apoptosis_end_decision(&mut self) {
        let Some(decay) = &mut self.rl.rule_decay else {
            return;
        };
        let forgotten = decay.end_decision();
        for rule in forgotten {
            let in_use = self
                .decider
                .insts
                .iter()
                .any(|inst| inst.alive && inst.prod == rule);
            let rl_kept = self.rl.rules.get(&rule).is_some_and(|v| {
                v.updates as i64 != 0 || self.rl.references_from_states(rule) != 0
            });
            if in_use || rl_kept {
                continue;
            }
            let Some(p) = self.production_by_id(rule) else {
                continue;
            };
            if self.excise(&p.name) {
                self.learn.learned_this_run = self.learn.learned_this_run.wrapping_sub(1);
            }
        }
    }
}
