//! What the agent records in the RL trace (see `trace_graph.rs`): at each decision that
//! selects an operator with RL learning on and `rl --set trace on`, the decided goal's
//! candidates, each described by its `^attr value` pairs (9.6's plain text of each
//! symbol), with the chance the exploration policy gave it.

use super::update::Candidate;
use crate::agent::AgentCore;
use crate::decide::procedure::Policy;
use crate::symbols::Sym;

impl AgentCore {
    /// Records a decision of `goal` (at goal-stack `level`) that selected `cands[chosen]`.
    pub(crate) fn rl_trace_record(
        &mut self,
        goal: Sym,
        level: u32,
        cands: &[Sym],
        values: &[Candidate],
        chosen: usize,
        policy: Policy,
    ) {
        if !self.rl.params.trace {
            return;
        }
        let numbers: Vec<f64> = values.iter().map(|c| c.value).collect();
        let recorded: Vec<(Vec<String>, f64)> = cands
            .iter()
            .zip(values)
            .enumerate()
            .map(|(i, (&op, c))| {
                let chance = if c.rl {
                    selection_chance(&numbers, i, policy)
                } else {
                    f64::NAN
                };
                (self.rl_trace_description(op), chance)
            })
            .collect();
        let at = match self.rl.goals.get(&goal).and_then(|d| d.trace_node) {
            Some(at) => at,
            None => self.rl.trace.root(level),
        };
        let next = self.rl.trace.record(at, recorded, chosen);
        self.rl.goals.entry(goal).or_default().trace_node = Some(next);
    }

    /// `rl -t init [LEVEL]`: every goal (or the one at `level`) goes back to its level's
    /// root, and the count of inits goes up.
    pub(crate) fn rl_trace_init(&mut self, level: Option<u32>) {
        let mut goals: Vec<(Sym, u32)> =
            self.decider.goals.iter().map(|g| (g.state, g.level)).collect();
        if goals.is_empty() {
            // The top state before the first run (its goal entry is made then).
            goals.push((self.top.state, 1));
        }
        for (goal, l) in goals {
            if level.is_none_or(|want| want == l) {
                let root = self.rl.trace.root(l);
                self.rl.goals.entry(goal).or_default().trace_node = Some(root);
            }
        }
        self.rl.trace.init_count += 1;
    }

    /// An operator as the trace names it: `^name NAME` (just `^name` without one), then
    /// its other augmentations as `^attr value`, in text order.
    fn rl_trace_description(&self, op: Sym) -> Vec<String> {
        let name_attr = self.symbols.find_str("name");
        let mut name = None;
        let mut others = Vec::new();
        for w in self.wm.of_id(op).filter_map(|w| self.wm.get(w)) {
            if w.acceptable {
                continue;
            }
            if Some(w.attr) == name_attr {
                name.get_or_insert(w.value);
                continue;
            }
            others.push(format!(
                "^{} {}",
                self.symbols.plain(w.attr),
                self.symbols.plain(w.value)
            ));
        }
        others.sort();
        let first = match name {
            Some(n) => format!("^name {}", self.symbols.plain(n)),
            None => "^name".to_string(),
        };
        std::iter::once(first).chain(others).collect()
    }
}

/// The chance `policy` gives candidate `i` of `values` (9.6's
/// `exploration_probability_according_to_policy`).
fn selection_chance(values: &[f64], i: usize, policy: Policy) -> f64 {
    let n = values.len() as f64;
    match policy {
        Policy::First => f64::from(u8::from(i == 0)),
        Policy::Last => f64::from(u8::from(i + 1 == values.len())),
        Policy::Softmax => {
            let total: f64 = values.iter().filter(|v| **v > 0.0).sum();
            if total > 0.0 {
                if values[i] > 0.0 {
                    values[i] / total
                } else {
                    0.0
                }
            } else {
                1.0 / n
            }
        }
        Policy::EpsilonGreedy { epsilon } => {
            let top = values.iter().cloned().fold(values[0], f64::max);
            let tops = values.iter().filter(|v| **v == top).count() as f64;
            let mut chance = epsilon / n;
            if values[i] == top {
                chance += (1.0 - epsilon) / tops;
            }
            chance
        }
        Policy::Boltzmann { temperature } => {
            crate::decide::procedure::boltzmann_chances(values, temperature)[i]
        }
    }
}
