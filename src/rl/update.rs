//! Reinforcement learning on the agent (Soar manual, ch. 5, "Reinforcement Learning"):
//! rewards collected from each state's `^reward-link` at every decision (5.2 "Reward
//! Representation"), and the update of the RL rules of a state's last RL operator when the
//! next operator is selected, when the state goes, or when the agent halts (5.3 "Updating
//! RL Rule Values"), with gaps in rule coverage (5.3.2), eligibility traces and the decay
//! modes of the learning rate. A rule's new value becomes its numeric preference: the
//! rule prints with it, and its current instantiations' preferences take it at once.

use super::params::{DecayMode, Policy};
use crate::agent::AgentCore;
use crate::ast::Constant;
use crate::decide::procedure::PrefType;
use crate::production::{Action, RhsTerm};
use crate::rete::ProdId;
use crate::symbols::{Sym, SymData};
use crate::trace_events::TraceEvent;

/// A candidate operator as the update sees it: its value and whether RL rules gave any of
/// it (9.6's `rl_contribution`).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Candidate {
    pub value: f64,
    pub rl: bool,
}

impl AgentCore {
    /// Whether reinforcement learning is on (`rl --set learning on`).
    pub(crate) fn rl_enabled(&self) -> bool {
        self.rl.params.learning
    }

    /// The sum of the numbers under a state's `^reward-link`: each `^reward` object's
    /// `^value` that is a number (Soar manual, 5.2 "Reward Representation"); other values
    /// are passed over.
    fn reward_on(&self, goal: Sym) -> f64 {
        let (Some(link), Some(reward), Some(value)) = (
            self.symbols.find_str("reward-link"),
            self.symbols.find_str("reward"),
            self.symbols.find_str("value"),
        ) else {
            return 0.0;
        };
        let mut total = 0.0;
        self.each_newest_first(goal, link, &mut |r| {
            self.each_newest_first(r, reward, &mut |x| {
                if !self.symbols.is_id(x) {
                    return;
                }
                self.each_newest_first(x, value, &mut |v| match self.symbols.get(v) {
                    SymData::Int(i) => total += *i as f64,
                    SymData::Float(f) => total += *f,
                    _ => {}
                });
            });
        });
        total
    }

    /// Calls `f` with the values of `id`'s WMEs on `attr` (acceptable preferences aside),
    /// newest first as 9.6 walks a slot; the usual single value is found without
    /// collecting.
    fn each_newest_first(&self, id: Sym, attr: Sym, f: &mut dyn FnMut(Sym)) {
        let mut found = self
            .wm
            .of_id(id)
            .filter_map(|w| self.wm.get(w))
            .filter(|w| w.attr == attr && !w.acceptable)
            .map(|w| (w.timetag, w.value));
        let Some(first) = found.next() else {
            return;
        };
        let Some(second) = found.next() else {
            f(first.1);
            return;
        };
        let mut all = vec![first, second];
        all.extend(found);
        all.sort_by_key(|x| std::cmp::Reverse(x.0));
        for (_, v) in all {
            f(v);
        }
    }

    /// When a decision selects an operator by the preferences: every state with an RL
    /// operator pending collects its reward, top down (observed on 9.6: a decision that
    /// makes an impasse collects none).
    pub(crate) fn rl_tabulate_rewards(&mut self) {
        let n = self.decider.goals.len();
        for i in 0..n {
            let goal = self.decider.goals[i].state;
            self.rl_tabulate_goal(goal, i + 1 < n);
        }
    }

    /// One state's reward, discounted by the decisions since its RL operator (with
    /// `temporal-discount`) and those spent in substates (with `hrl-discount`).
    fn rl_tabulate_goal(&mut self, goal: Sym, above_bottom: bool) {
        if self
            .rl
            .goals
            .get(&goal)
            .is_none_or(|d| d.prev_rules.is_empty())
        {
            return;
        }
        let reward = self.reward_on(goal);
        let p = &self.rl.params;
        let (gamma, temporal_discount, hrl) =
            (p.discount_rate, p.temporal_discount, p.hrl_discount);
        let data = self.rl.goals.entry(goal).or_default();
        let mut age = data.hrl_age;
        if temporal_discount {
            age += data.gap_age;
        }
        data.reward += reward * gamma.powf(f64::from(age));
        if above_bottom && hrl {
            data.hrl_age += 1;
        }
        self.rl.stats.total_reward = reward;
        self.rl.stats.global_reward += reward;
    }

    /// The candidates' values for the update, by the slot's numeric preferences (summed,
    /// or averaged with `numeric-indifferent-mode --avg`), and whether RL rules gave any.
    pub(crate) fn rl_candidates(
        &self,
        goal: Sym,
        prefs: &[crate::decide::procedure::Pref],
        cands: &[Sym],
    ) -> Vec<Candidate> {
        let key = (goal, self.top.operator);
        let slot = self.decider.slots.get(&key);
        cands
            .iter()
            .map(|&c| {
                let value = crate::decide::procedure::numeric_value(
                    prefs,
                    c,
                    self.settings.numeric_mode,
                );
                let rl = slot.is_some_and(|s| {
                    s.prefs.iter().any(|&pid| {
                        let p = &self.decider.prefs[pid];
                        p.kind == PrefType::NumericIndifferent
                            && p.value == c
                            && p.rule.is_some_and(|r| self.rl.is_rl_rule(r))
                    })
                });
                Candidate { value, rl }
            })
            .collect()
    }

    /// The decision selected `chosen` among `cands` for `goal`: the state's pending RL
    /// rules are updated toward the reward plus the discounted value of the next operator
    /// (its own under Sarsa, the best candidate's under Q-learning).
    pub(crate) fn rl_decided(
        &mut self,
        goal: Sym,
        cands: &[Candidate],
        chosen: usize,
        exploration: crate::decide::procedure::Policy,
    ) {
        let Some(first) = cands.first().copied() else {
            return;
        };
        let policy = self.rl.params.learning_policy;
        let target = if policy.is_off_policy() {
            let mut top = first;
            for c in &cands[1..] {
                if c.value > top.value {
                    top = *c;
                }
            }
            top
        } else {
            cands.get(chosen).copied().unwrap_or(first)
        };
        self.rl.selected_rho = match policy {
            Policy::OffPolicyGq => {
                let values: Vec<f64> = cands.iter().map(|c| c.value).collect();
                super::gq::importance_ratio(&values, exploration, chosen)
            }
            _ => 1.0,
        };
        self.rl_perform_update(goal, target.value, target.rl, true);
        // Watkins's Q(lambda): an exploratory choice (below the best value) cuts the
        // eligibility traces (observed on 9.6).
        let explored = cands.get(chosen).is_some_and(|c| c.value < target.value);
        if policy == Policy::QLearning && explored {
            if let Some(data) = self.rl.goals.get_mut(&goal) {
                data.traces.clear();
            }
        }
    }

    /// A state goes, or the agent halts: the state's pending RL rules take the reward
    /// collected so far, with no next operator.
    pub(crate) fn rl_goal_ends(&mut self, goal: Sym, above_bottom: bool) {
        if !self.rl_enabled() {
            if !self.rl.goals.is_empty() {
                self.rl.goals.remove(&goal);
            }
            return;
        }
        self.rl_tabulate_goal(goal, above_bottom);
        self.rl_perform_update(goal, 0.0, true, false);
        self.rl.goals.remove(&goal);
    }

    /// The agent halted: the top state's pending RL rules take the last reward, and a next
    /// value of 0, as at the end of an episode (observed on 9.6: the expected future reward
    /// moves toward 0 too).
    pub(crate) fn rl_halted(&mut self) {
        if !self.rl_enabled() {
            return;
        }
        let top = self.top.state;
        let above = self.decider.goals.len() > 1;
        self.rl_tabulate_goal(top, above);
        self.rl_perform_update(top, 0.0, true, true);
    }

    /// The update of a state's pending RL rules toward `reward + discount * op_value`
    /// (Soar manual, 5.3 "Updating RL Rule Values"). With temporal extension, an operator
    /// that no RL rule valued leaves them pending: the gap goes on.
    fn rl_perform_update(&mut self, goal: Sym, op_value: f64, op_rl: bool, update_efr: bool) {
        let p = self.rl.params.clone();
        let using_gaps = p.temporal_extension;
        if using_gaps && !op_rl {
            return;
        }
        let Some(mut data) = self.rl.goals.remove(&goal) else {
            return;
        };
        if !data.prev_rules.is_empty() {
            let mut age = data.hrl_age;
            if p.temporal_discount {
                age += data.gap_age;
            }
            let discount = p.discount_rate.powf(f64::from(age) + 1.0);
            if data.gap_age > 0 && using_gaps && self.settings.trace.rl {
                self.emit(&TraceEvent::RlGap {
                    started: false,
                    goal,
                });
            }
            if p.et_decay_rate == 0.0 {
                data.traces.clear();
            } else {
                data.traces.retain(|_, t| {
                    *t *= p.et_decay_rate * discount;
                    *t >= p.et_tolerance
                });
            }
            if p.learning_policy.is_gq() {
                data.traces.values_mut().for_each(|t| *t *= data.rho);
            }
            let increment = 1.0 / data.prev_rules.len() as f64;
            let (mut sum_ecr, mut sum_efr, mut weight_of_features) = (0.0, 0.0, 0.0);
            for r in &data.prev_rules {
                if let Some(v) = self.rl.rules.get(r) {
                    sum_ecr += v.ecr;
                    sum_efr += v.efr;
                    weight_of_features += v.gq_weight;
                    *data.traces.entry(*r).or_insert(0.0) += increment;
                }
            }
            let delta_t = (data.reward + discount * op_value) - (sum_ecr + sum_efr);
            let weight_of_traces: f64 = data
                .traces
                .iter()
                .filter_map(|(r, t)| Some(self.rl.rules.get(r)?.gq_weight * t))
                .sum();
            let traced: Vec<(ProdId, f64)> = data.traces.iter().map(|(r, t)| (*r, *t)).collect();
            for (rule, trace) in traced {
                let Some(mut v) = self.rl.rules.get(&rule).copied() else {
                    continue;
                };
                let alpha = match p.decay_mode {
                    DecayMode::Normal => p.learning_rate,
                    DecayMode::Exponential => 1.0 / (v.updates + 1.0),
                    DecayMode::Logarithmic => 1.0 / ((v.updates + 1.0).ln() + 1.0),
                    DecayMode::DeltaBarDelta => {
                        v.dbd_beta += p.meta_learning_rate * delta_t * v.dbd_h;
                        let a = v.dbd_beta.exp();
                        let decay = (1.0 - a).max(0.0);
                        v.dbd_h = v.dbd_h * decay + a * delta_t;
                        a
                    }
                };
                let delta_ecr = alpha * trace * (data.reward - sum_ecr);
                let delta_efr = if update_efr {
                    alpha * trace * (discount * op_value - sum_efr)
                } else {
                    0.0
                };
                let before = [v.ecr, v.efr, v.ecr + v.efr];
                v.ecr += delta_ecr;
                v.efr += delta_efr;
                v.gq_weight += p.step_size_parameter * (delta_ecr + delta_efr);
                v.updates += 1.0;
                let combined = v.ecr + v.efr;
                if self.settings.trace.rl {
                    let name = self.production_name(rule).to_string();
                    let after = [v.ecr, v.efr, combined];
                    self.emit(&TraceEvent::RlUpdate {
                        rule: &name,
                        before,
                        after,
                    });
                    if !p.update_log_path.is_empty() {
                        let line = super::update_log::update_line(&name, before, after);
                        if let Err(e) = super::update_log::append(&p.update_log_path, &line) {
                            self.emit(&TraceEvent::RlLogError {
                                path: &p.update_log_path,
                                message: &e.to_string(),
                            });
                        }
                    }
                }
                self.rl.rules.insert(rule, v);
                self.set_rl_rule_value(rule, combined);
            }
            if p.learning_policy.is_gq() {
                self.gq_corrections(goal, &data.prev_rules, weight_of_traces, weight_of_features);
            }
            data.reward = 0.0;
            data.gap_age = 0;
            data.hrl_age = 0;
        }
        data.prev_rules.clear();
        self.rl.goals.insert(goal, data);
    }

    /// GQ(λ)'s two corrections after an update (Maei and Sutton 2010): the expected future
    /// reward of the rules valuing the state's current candidates moves against the
    /// secondary weights along the traces, `-α·γ·(1-λ)·(w·e)` once per preference, and the
    /// secondary weights of the rules just updated move toward the features' error,
    /// `-α·η·(w·φ)`. The rules' printed values take the first at their next update.
    fn gq_corrections(&mut self, goal: Sym, prev: &[ProdId], w_e: f64, w_phi: f64) {
        let p = &self.rl.params;
        let toward_next =
            p.learning_rate * p.discount_rate * (1.0 - p.et_decay_rate) * w_e;
        let toward_features = p.learning_rate * p.step_size_parameter * w_phi;
        let key = (goal, self.top.operator);
        let valued: Vec<ProdId> = self.decider.slots.get(&key).map_or_else(Vec::new, |slot| {
            slot.prefs
                .iter()
                .map(|&pid| &self.decider.prefs[pid])
                .filter(|pref| pref.kind == PrefType::NumericIndifferent)
                .filter_map(|pref| pref.rule)
                .collect()
        });
        for r in valued {
            if let Some(v) = self.rl.rules.get_mut(&r) {
                v.efr -= toward_next;
            }
        }
        for r in prev {
            if let Some(v) = self.rl.rules.get_mut(r) {
                v.gq_weight -= toward_features;
            }
        }
    }

    /// After the decision for `goal` selected `op`: the RL rules whose preferences valued it
    /// are the state's pending rules; with none, a gap begins or goes on (temporal
    /// extension), or, without temporal extension, nothing is pending.
    pub(crate) fn rl_store(&mut self, goal: Sym, op: Sym) {
        let key = (goal, self.top.operator);
        let mut fired = Vec::new();
        if let Some(slot) = self.decider.slots.get(&key) {
            for &pid in slot.prefs.iter().rev() {
                let pref = &self.decider.prefs[pid];
                if pref.kind == PrefType::NumericIndifferent && pref.value == op {
                    if let Some(r) = pref.rule.filter(|r| self.rl.is_rl_rule(*r)) {
                        fired.push(r);
                    }
                }
            }
        }
        let using_gaps = self.rl.params.temporal_extension;
        let trace = self.settings.trace.rl;
        let rho = self.rl.selected_rho;
        let data = self.rl.goals.entry(goal).or_default();
        if !fired.is_empty() {
            data.prev_rules = fired;
            data.gap_age = 0;
            data.rho = rho;
            return;
        }
        let start_gap = trace && using_gaps && data.gap_age == 0 && !data.prev_rules.is_empty();
        if !using_gaps {
            data.prev_rules.clear();
            data.rho = 1.0;
        } else if !data.prev_rules.is_empty() {
            data.gap_age += 1;
        }
        if start_gap {
            self.emit(&TraceEvent::RlGap {
                started: true,
                goal,
            });
        }
    }

    /// Gives an RL rule a new value: its text shows it, its later firings make it, and its
    /// current instantiations' preferences take it now.
    fn set_rl_rule_value(&mut self, rule: ProdId, value: f64) {
        let doc = self
            .rl
            .params
            .meta
            .then(|| self.rl.rules.get(&rule))
            .flatten()
            .map(|v| super::update_log::meta_text(v.updates, v.dbd_h));
        let loaded = self.edit_production(rule, |p| {
            if let Some(Action::Make(m)) = p.actions.first_mut() {
                m.referent = Some(RhsTerm::Const(Constant::Float(value)));
            }
            if doc.is_some() {
                p.doc = doc.map(Box::from);
            }
        });
        if !loaded {
            return;
        }
        let sym = self.symbols.float(value);
        self.decider.set_compiled_referent(rule, sym);
        for inst in self.decider.insts.iter().filter(|i| i.alive && i.prod == rule) {
            for &pid in &inst.prefs {
                let pref = &mut self.decider.prefs[pid];
                if pref.kind == PrefType::NumericIndifferent {
                    pref.referent = Some(sym);
                    pref.number = Some(value);
                }
            }
        }
    }
}
