//! The importance-sampling ratio of the GQ(λ) learning policies (Soar manual, ch. 5,
//! "Reinforcement Learning", `learning-policy`; Maei and Sutton, "GQ(λ): A general
//! gradient algorithm for temporal-difference prediction learning with eligibility
//! traces", 2010). An off-policy learner learns about the greedy policy while the agent
//! explores: each eligibility trace is weighted by how likely the greedy policy was to take
//! the selected operator, over how likely the exploration policy was to take it. The
//! on-policy variant learns about the policy it follows, so its ratio is 1.
//!
//! The ratio only scales the eligibility traces; with a trace decay of 0 the GQ policies
//! learn what Sarsa and Q-learning learn.

use crate::decide::procedure::Policy as Exploration;

/// The probability the greedy policy gives each candidate: ties for the highest value
/// share it.
fn greedy_probability(values: &[f64], i: usize) -> f64 {
    let top = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if values[i] != top {
        return 0.0;
    }
    1.0 / values.iter().filter(|v| **v == top).count() as f64
}

/// π(chosen) / b(chosen): the greedy policy's probability for the chosen candidate over
/// the exploration policy's, as 9.6 weighs it. Where the exploration policy gives the
/// chosen candidate no probability of its own (softmax over a value of 0) the ratio is
/// the largest number, as in 9.6.
pub(crate) fn importance_ratio(values: &[f64], exploration: Exploration, chosen: usize) -> f64 {
    let n = values.len();
    if chosen >= n {
        return 1.0;
    }
    let target = greedy_probability(values, chosen);
    let uniform = 1.0 / n as f64;
    match exploration {
        // Degenerate choices: every candidate keeps a ratio of 1.
        Exploration::First | Exploration::Last => 1.0,
        Exploration::EpsilonGreedy { epsilon } => {
            target / ((1.0 - epsilon) * target + epsilon * uniform)
        }
        Exploration::Boltzmann { temperature } => {
            let t = if temperature > 0.0 { temperature } else { 1.0 };
            let top = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            let weight = |v: f64| ((v - top) / t).exp();
            let total: f64 = values.iter().map(|v| weight(*v)).sum();
            target / (weight(values[chosen]) / total)
        }
        Exploration::Softmax => {
            let total: f64 = values.iter().filter(|v| **v > 0.0).sum();
            let v = values[chosen];
            if total == 0.0 {
                // Nothing positive: the choice is uniform.
                target / uniform
            } else if v != 0.0 {
                target / (v / total)
            } else if target > 0.0 {
                f64::MAX
            } else {
                target
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_greedy_choice_under_epsilon_greedy_is_weighted_by_its_odds() {
        let e = Exploration::EpsilonGreedy { epsilon: 0.1 };
        // Greedy probability 1; exploration 0.9 + 0.1 / 2.
        let r = importance_ratio(&[1.0, 0.5], e, 0);
        assert!((r - 1.0 / 0.95).abs() < 1e-12);
        // An exploratory choice: the greedy policy never takes it.
        assert_eq!(importance_ratio(&[1.0, 0.5], e, 1), 0.0);
    }

    #[test]
    fn ties_share_the_greedy_probability() {
        let r = importance_ratio(&[1.0, 1.0], Exploration::Softmax, 0);
        assert!((r - 1.0).abs() < 1e-12);
        let b = Exploration::Boltzmann { temperature: 1.0 };
        assert!((importance_ratio(&[2.0, 2.0, 2.0], b, 2) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn degenerate_and_out_of_range_choices_keep_a_ratio_of_one() {
        assert_eq!(importance_ratio(&[0.0, 3.0], Exploration::First, 0), 1.0);
        assert_eq!(importance_ratio(&[0.0, 3.0], Exploration::Last, 1), 1.0);
        assert_eq!(importance_ratio(&[], Exploration::Softmax, 0), 1.0);
    }

    #[test]
    fn softmax_over_a_zero_value_gives_the_largest_ratio() {
        // 0 is the top value here, yet softmax only ever picks positive values.
        assert_eq!(importance_ratio(&[0.0, -1.0], Exploration::Softmax, 0), 2.0);
        assert_eq!(importance_ratio(&[0.0, 0.0, 1.0], Exploration::Softmax, 2), 1.0);
    }
}
