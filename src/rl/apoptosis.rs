//! Apoptosis: learned rules that go unused are excised by base-level decay, with rule
//! firings as the activation events (Soar manual, ch. 5, "Reinforcement Learning", the
//! `apoptosis` parameters of the `rl` command; the decay model is the base-level
//! activation of ch. 8, "Working Memory Activation", after Anderson and Lebiere 1998 and
//! Petrov 2006).
//!
//! Time runs in decisions. A rule is referenced when one of its instantiations retracts;
//! its activation at time `t` is `sum(n_i * (t - t_i)^-d)` over its last ten reference
//! times `t_i` (`n_i` references each), plus Petrov's estimate for the older ones. The
//! rule is forgotten at the first decision where the activation falls below `e^thresh`.
//! That decision is predicted when the rule is referenced and checked when it comes, so
//! a rule costs nothing in the decisions between; the prediction is 9.6's: a cheap
//! estimate from each reference alone (Derbinsky and Laird 2011, "Effective and
//! efficient forgetting of learned knowledge in Soar's working and procedural
//! memories"), then, when the estimate passes without forgetting, the exact decision by
//! a doubling and binary search.

use crate::rete::ProdId;
use crate::wma::decay::{DecayHistory, DecayModel};
use std::collections::{BTreeMap, BTreeSet};

/// One rule's references, and its place in the queue.
#[derive(Debug, Clone)]
struct History {
    refs: DecayHistory,
    /// The decision at which the rule is checked next (0: not queued).
    check_at: u64,
    /// References since the last decision ended.
    buffered: u64,
}

impl History {
    fn new() -> Self {
        History {
            refs: DecayHistory::new(),
            check_at: 0,
            buffered: 0,
        }
    }
}

/// The decay of learned rules' activations, and the rules due to be forgotten.
#[derive(Debug, Clone)]
pub struct RuleDecay {
    /// The decay exponent, threshold and first estimate (Petrov's estimate always on).
    model: DecayModel,
    step: u64,
    histories: BTreeMap<ProdId, History>,
    touched: BTreeSet<ProdId>,
    /// Rules by the decision at which each is checked.
    queue: BTreeMap<u64, BTreeSet<ProdId>>,
}

impl RuleDecay {
    /// A decay with exponent `decay` (0 < d < 1) and threshold `thresh` (a log value,
    /// negative), starting at decision 1.
    pub fn new(decay: f64, thresh: f64) -> Self {
        RuleDecay {
            model: DecayModel::new(decay, thresh, true, true),
            step: 1,
            histories: BTreeMap::new(),
            touched: BTreeSet::new(),
            queue: BTreeMap::new(),
        }
    }

    /// Notes one use of a rule in this decision.
    pub fn reference(&mut self, rule: ProdId) {
        self.histories
            .entry(rule)
            .or_insert_with(History::new)
            .buffered += 1;
        self.touched.insert(rule);
    }

    /// Forgets a rule that has gone (excised).
    pub fn remove(&mut self, rule: ProdId) {
        if let Some(h) = self.histories.remove(&rule) {
            self.touched.remove(&rule);
            self.unqueue(rule, h.check_at);
        }
    }

    /// Ends a decision: records its references, returns the rules whose activation has
    /// fallen below the threshold at it, and moves time on.
    pub fn end_decision(&mut self) -> Vec<ProdId> {
        self.record_references();
        let forgotten = self.forget();
        self.step += 1;
        forgotten
    }

    fn record_references(&mut self) {
        let step = self.step;
        for rule in std::mem::take(&mut self.touched) {
            let Some(h) = self.histories.get_mut(&rule) else {
                continue;
            };
            h.refs.record(h.buffered, step);
            h.buffered = 0;
            let old = h.check_at;
            let at = self
                .model
                .forgetting_time(&self.histories[&rule].refs, step, true);
            self.requeue(rule, old, at);
        }
    }

    fn forget(&mut self) -> Vec<ProdId> {
        let mut forgotten = Vec::new();
        let Some((&first, _)) = self.queue.first_key_value() else {
            return forgotten;
        };
        if first != self.step {
            return forgotten;
        }
        let due = self.queue.remove(&first).unwrap_or_default();
        for rule in due {
            let h = &self.histories[&rule];
            if self.below_threshold(h, self.step) {
                forgotten.push(rule);
                if let Some(h) = self.histories.get_mut(&rule) {
                    h.check_at = 0;
                }
            } else {
                let at = self.model.forgetting_time(&h.refs, self.step, false);
                if let Some(h) = self.histories.get_mut(&rule) {
                    h.check_at = 0;
                }
                self.requeue(rule, 0, at);
            }
        }
        forgotten
    }

    fn unqueue(&mut self, rule: ProdId, at: u64) {
        if at == 0 {
            return;
        }
        if let Some(set) = self.queue.get_mut(&at) {
            set.remove(&rule);
            if set.is_empty() {
                self.queue.remove(&at);
            }
        }
    }

    fn requeue(&mut self, rule: ProdId, old: u64, at: u64) {
        if old == at {
            return;
        }
        self.unqueue(rule, old);
        self.queue.entry(at).or_default().insert(rule);
        if let Some(h) = self.histories.get_mut(&rule) {
            h.check_at = at;
        }
    }

    fn below_threshold(&self, h: &History, t: u64) -> bool {
        // 9.6's value for a rule with no references is e, above any threshold.
        !h.refs.is_empty() && self.model.below_threshold(&h.refs, t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rule(n: u32) -> ProdId {
        ProdId(n)
    }

    /// Runs decisions until the rule is forgotten; returns the decision it happened at.
    fn forgotten_at(d: &mut RuleDecay, r: ProdId, limit: u64) -> Option<u64> {
        for _ in 0..limit {
            let step = d.step;
            if d.end_decision().contains(&r) {
                return Some(step);
            }
        }
        None
    }

    #[test]
    fn one_reference_decays_in_55_decisions_with_the_defaults() {
        // 1 * t^-0.5 < e^-2 first holds at t = 55.
        let mut d = RuleDecay::new(0.5, -2.0);
        d.reference(rule(1));
        assert_eq!(forgotten_at(&mut d, rule(1), 200), Some(56));
    }

    #[test]
    fn a_reference_before_the_due_decision_puts_it_off() {
        let mut d = RuleDecay::new(0.5, -2.0);
        d.reference(rule(1));
        for _ in 0..30 {
            assert!(d.end_decision().is_empty());
        }
        d.reference(rule(1));
        let at = forgotten_at(&mut d, rule(1), 1000).expect("forgotten");
        assert!(at > 56, "{at}");
        // The exact decision: the first where both references together fall below.
        let act = |t: f64| (t - 1.0).powf(-0.5) + (t - 31.0).powf(-0.5);
        let expected = (32..1000).find(|&t| act(t as f64) < (-2.0f64).exp()).unwrap();
        assert_eq!(at, expected);
    }

    #[test]
    fn an_unreferenced_or_removed_rule_is_never_forgotten() {
        let mut d = RuleDecay::new(0.5, -2.0);
        d.reference(rule(1));
        d.reference(rule(2));
        d.end_decision();
        d.remove(rule(1));
        let mut seen = Vec::new();
        for _ in 0..100 {
            seen.extend(d.end_decision());
        }
        assert_eq!(seen, vec![rule(2)]);
    }

    #[test]
    fn many_references_keep_a_rule_longer_and_petrov_counts_the_old_ones() {
        let mut d = RuleDecay::new(0.5, -2.0);
        for _ in 0..12 {
            d.reference(rule(1));
            assert!(d.end_decision().is_empty());
        }
        let h = &d.histories[&rule(1)];
        assert_eq!(h.refs.counts(), (10, 12, 1));
        assert!(forgotten_at(&mut d, rule(1), 100_000).expect("forgotten") > 1000);
    }
}
