//! Soar 9.6's decision procedure for an operator slot (Soar manual, chapter 2, "How preferences
//! are evaluated to decide an operator") and the exploration policies that choose among
//! indifferent candidates (`decide indifferent-selection`, Soar manual chapter 9).
//!
//! The caller passes the slot's preferences in slot order; candidates keep the order in
//! which their acceptable preferences appear, which the slot keeps as Soar does (newest
//! first, so the candidate list is in reverse firing order).

use crate::rng::Mt19937;
use rustc_hash::{FxHashMap, FxHashSet};
use crate::symbols::Sym;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PrefType {
    Acceptable,
    Reject,
    Require,
    Prohibit,
    Better,
    Worse,
    Best,
    Worst,
    UnaryIndifferent,
    BinaryIndifferent,
    NumericIndifferent,
}

/// One preference for a slot: `value` is the candidate; `referent` the other operator of a
/// binary preference; `number` the value of a numeric-indifferent preference.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pref {
    pub kind: PrefType,
    pub value: Sym,
    pub referent: Option<Sym>,
    pub number: Option<f64>,
}

/// Boltzmann's weight of each value, `e^((Q - Q_max) / t)`: the largest is 1, so no
/// exponential overflows.
fn boltzmann_weights(values: &[f64], temperature: f64) -> Vec<f64> {
    let t = if temperature > 0.0 { temperature } else { 1.0 };
    let max = values.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    values.iter().map(|q| ((q - max) / t).exp()).collect()
}

/// The chance Boltzmann exploration gives each value.
pub fn boltzmann_chances(values: &[f64], temperature: f64) -> Vec<f64> {
    let weights = boltzmann_weights(values, temperature);
    let total: f64 = weights.iter().sum();
    weights.iter().map(|w| w / total).collect()
}

#[cfg(test)]
impl Pref {
    pub fn unary(kind: PrefType, value: Sym) -> Self {
        Pref {
            kind,
            value,
            referent: None,
            number: None,
        }
    }
    pub fn binary(kind: PrefType, value: Sym, referent: Sym) -> Self {
        Pref {
            kind,
            value,
            referent: Some(referent),
            number: None,
        }
    }
    pub fn numeric(value: Sym, number: f64) -> Self {
        Pref {
            kind: PrefType::NumericIndifferent,
            value,
            referent: None,
            number: Some(number),
        }
    }
}

/// What the preferences decide.
#[derive(Debug, Clone, PartialEq)]
pub enum Outcome {
    Winner(Sym),
    /// No acceptable candidate: a no-change impasse.
    NoCandidates,
    Tie(Vec<Sym>),
    Conflict(Vec<Sym>),
    ConstraintFailure(Vec<Sym>),
}

/// How an indifferent choice is made (`indifferent-selection`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Policy {
    #[default]
    Softmax,
    EpsilonGreedy {
        epsilon: f64,
    },
    Boltzmann {
        temperature: f64,
    },
    First,
    Last,
}

/// How numeric-indifferent values combine (`numeric-indifferent-mode`, sum by default).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum NumericMode {
    #[default]
    Sum,
    Avg,
}

fn has(prefs: &[Pref], kind: PrefType, value: Sym) -> bool {
    prefs.iter().any(|p| p.kind == kind && p.value == value)
}

/// Which kinds of preference each value has, and the binary indifferent pairs: a slot with
/// many preferences (an agent proposing an operator per WME of a growing set) is read
/// through this index, where scanning the preferences for each candidate would take time
/// quadratic in their number (cubic for the indifference test).
struct Index<'a> {
    prefs: &'a [Pref],
    kinds: Option<FxHashMap<Sym, u16>>,
    pairs: Option<FxHashSet<(Sym, Sym)>>,
}

/// Slots with more preferences than this are indexed; fewer are scanned.
const SCANNED: usize = 16;

impl<'a> Index<'a> {
    fn new(prefs: &'a [Pref]) -> Self {
        if prefs.len() <= SCANNED {
            return Index {
                prefs,
                kinds: None,
                pairs: None,
            };
        }
        let mut kinds: FxHashMap<Sym, u16> = FxHashMap::default();
        let mut pairs = FxHashSet::default();
        for p in prefs {
            *kinds.entry(p.value).or_default() |= 1 << p.kind as u16;
            if let (PrefType::BinaryIndifferent, Some(r)) = (p.kind, p.referent) {
                pairs.insert((p.value, r));
            }
        }
        Index {
            prefs,
            kinds: Some(kinds),
            pairs: Some(pairs),
        }
    }

    /// Whether `value` has a preference of `kind`.
    fn has(&self, kind: PrefType, value: Sym) -> bool {
        match &self.kinds {
            Some(k) => k.get(&value).is_some_and(|b| b & (1 << kind as u16) != 0),
            None => has(self.prefs, kind, value),
        }
    }

    /// Whether a binary indifferent preference pairs `a` and `b`, either way round.
    fn indifferent_pair(&self, a: Sym, b: Sym) -> bool {
        match &self.pairs {
            Some(p) => p.contains(&(a, b)) || p.contains(&(b, a)),
            None => self.prefs.iter().any(|p| {
                p.kind == PrefType::BinaryIndifferent
                    && ((p.value == a && p.referent == Some(b))
                        || (p.value == b && p.referent == Some(a)))
            }),
        }
    }
}

/// The preference semantics in 9.6's order, up to the choice: the candidates to choose
/// among (one, or several mutually indifferent ones), or the impasse.
pub fn candidates(prefs: &[Pref]) -> Result<Vec<Sym>, Outcome> {
    let index = Index::new(prefs);
    let mut seen: FxHashSet<Sym> = FxHashSet::default();
    let mut push_unique = |v: &mut Vec<Sym>, s: Sym| {
        let new = if index.kinds.is_some() {
            seen.insert(s)
        } else {
            !v.contains(&s)
        };
        if new {
            v.push(s);
        }
    };
    // Step 1: require.
    let mut required = Vec::new();
    for p in prefs.iter().filter(|p| p.kind == PrefType::Require) {
        push_unique(&mut required, p.value);
    }
    if !required.is_empty() {
        if required.len() > 1 {
            return Err(Outcome::ConstraintFailure(required));
        }
        let r = required[0];
        if index.has(PrefType::Prohibit, r) {
            return Err(Outcome::ConstraintFailure(required));
        }
        return Ok(required);
    }
    // Step 2: acceptable, minus prohibit and reject.
    let mut cands = Vec::new();
    for p in prefs.iter().filter(|p| p.kind == PrefType::Acceptable) {
        if !index.has(PrefType::Prohibit, p.value) && !index.has(PrefType::Reject, p.value) {
            push_unique(&mut cands, p.value);
        }
    }
    match cands.len() {
        0 => return Err(Outcome::NoCandidates),
        1 => return Ok(cands),
        _ => {}
    }
    // Step 3: better/worse between current candidates. A dominated candidate is out even if
    // its dominator is dominated too.
    let position: Option<FxHashMap<Sym, usize>> = index
        .kinds
        .as_ref()
        .map(|_| cands.iter().enumerate().map(|(i, &c)| (c, i)).collect());
    let position_of = |s: Sym| match &position {
        Some(m) => m.get(&s).copied(),
        None => cands.iter().position(|c| *c == s),
    };
    let mut dominated = vec![false; cands.len()];
    for p in prefs {
        let (Some(r), true) = (
            p.referent,
            matches!(p.kind, PrefType::Better | PrefType::Worse),
        ) else {
            continue;
        };
        let (Some(vi), Some(ri)) = (position_of(p.value), position_of(r)) else {
            continue;
        };
        match p.kind {
            PrefType::Better => dominated[ri] = true,
            _ => dominated[vi] = true,
        }
    }
    if dominated.iter().all(|d| *d) {
        return Err(Outcome::Conflict(cands));
    }
    let mut cands: Vec<Sym> = cands
        .iter()
        .zip(&dominated)
        .filter(|(_, d)| !**d)
        .map(|(c, _)| *c)
        .collect();
    if cands.len() == 1 {
        return Ok(vec![cands[0]]);
    }
    // Step 4: best.
    if cands.iter().any(|c| index.has(PrefType::Best, *c)) {
        cands.retain(|c| index.has(PrefType::Best, *c));
        if cands.len() == 1 {
            return Ok(vec![cands[0]]);
        }
    }
    // Step 5: worst, unless every candidate is worst.
    if !cands.iter().all(|c| index.has(PrefType::Worst, *c)) {
        cands.retain(|c| !index.has(PrefType::Worst, *c));
        if cands.len() == 1 {
            return Ok(vec![cands[0]]);
        }
    }
    // Step 6: indifference.
    let unary = |c: Sym| {
        index.has(PrefType::UnaryIndifferent, c) || index.has(PrefType::NumericIndifferent, c)
    };
    let binary_with_all = |c: Sym| {
        cands
            .iter()
            .filter(|o| **o != c)
            .all(|o| index.indifferent_pair(c, *o))
    };
    let all_indifferent =
        cands.iter().all(|c| unary(*c)) || cands.iter().all(|c| binary_with_all(*c));
    if !all_indifferent {
        return Err(Outcome::Tie(cands));
    }
    Ok(cands)
}

/// Runs the preference semantics in 9.6's order and, when the remaining candidates are
/// mutually indifferent, chooses one with `policy`.
pub fn decide(prefs: &[Pref], policy: Policy, mode: NumericMode, rng: &mut Mt19937) -> Outcome {
    let cands = match candidates(prefs) {
        Ok(c) => c,
        Err(impasse) => return impasse,
    };
    if cands.len() == 1 {
        return Outcome::Winner(cands[0]);
    }
    let values: Vec<f64> = cands
        .iter()
        .map(|c| numeric_value(prefs, *c, mode))
        .collect();
    Outcome::Winner(cands[choose(&values, policy, rng)])
}

/// A candidate's numeric value: the sum (or average) of its numeric-indifferent
/// preferences; binary indifferents where it is the value contribute their referent as a
/// number when the referent is one (usually 0 here, since referents are operators).
pub fn numeric_value(prefs: &[Pref], c: Sym, mode: NumericMode) -> f64 {
    // Summed in the preferences' order, from -0.0 as `Iterator::sum` does.
    let (mut sum, mut count) = (-0.0, 0usize);
    for n in prefs
        .iter()
        .filter(|p| p.value == c && p.kind == PrefType::NumericIndifferent)
        .filter_map(|p| p.number)
    {
        sum += n;
        count += 1;
    }
    match (count, mode) {
        (0, _) => 0.0,
        (_, NumericMode::Sum) => sum,
        (_, NumericMode::Avg) => sum / count as f64,
    }
}

/// Index of the chosen candidate.
pub fn choose(values: &[f64], policy: Policy, rng: &mut Mt19937) -> usize {
    let n = values.len();
    if n <= 1 {
        return 0;
    }
    let uniform = |rng: &mut Mt19937| rng.rand_int((n - 1) as u32) as usize;
    match policy {
        Policy::First => 0,
        Policy::Last => n - 1,
        Policy::Softmax => {
            let total: f64 = values.iter().filter(|v| **v > 0.0).sum();
            if total <= 0.0 {
                return uniform(rng);
            }
            let r = total * rng.rand_float();
            let mut acc = 0.0;
            for (i, v) in values.iter().enumerate() {
                if *v > 0.0 {
                    acc += v;
                    if acc >= r {
                        return i;
                    }
                }
            }
            n - 1
        }
        Policy::EpsilonGreedy { epsilon } => {
            if rng.rand_float() < epsilon {
                return uniform(rng);
            }
            let max = values.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
            let best: Vec<usize> = (0..n).filter(|i| values[*i] == max).collect();
            if best.len() == 1 {
                best[0]
            } else {
                best[rng.rand_int((best.len() - 1) as u32) as usize]
            }
        }
        Policy::Boltzmann { temperature } => {
            let weights = boltzmann_weights(values, temperature);
            let total: f64 = weights.iter().sum();
            let r = total * rng.rand_float();
            let mut acc = 0.0;
            for (i, w) in weights.iter().enumerate() {
                acc += w;
                if acc >= r {
                    return i;
                }
            }
            n - 1
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use PrefType::*;

    fn s(i: u32) -> Sym {
        Sym(i)
    }

    fn run(prefs: &[Pref]) -> Outcome {
        decide(prefs, Policy::First, NumericMode::Sum, &mut Mt19937::new(1))
    }

    #[test]
    fn single_acceptable_wins() {
        assert_eq!(run(&[Pref::unary(Acceptable, s(1))]), Outcome::Winner(s(1)));
    }

    #[test]
    fn no_acceptable_is_no_change() {
        assert_eq!(run(&[]), Outcome::NoCandidates);
        assert_eq!(
            run(&[Pref::unary(Acceptable, s(1)), Pref::unary(Reject, s(1))]),
            Outcome::NoCandidates
        );
    }

    #[test]
    fn two_requires_or_required_and_prohibited_is_constraint_failure() {
        let p = [Pref::unary(Require, s(1)), Pref::unary(Require, s(2))];
        assert_eq!(run(&p), Outcome::ConstraintFailure(vec![s(1), s(2)]));
        let p = [Pref::unary(Require, s(1)), Pref::unary(Prohibit, s(1))];
        assert_eq!(run(&p), Outcome::ConstraintFailure(vec![s(1)]));
        let p = [Pref::unary(Acceptable, s(2)), Pref::unary(Require, s(1))];
        assert_eq!(run(&p), Outcome::Winner(s(1)));
    }

    #[test]
    fn without_indifference_two_candidates_tie() {
        let p = [Pref::unary(Acceptable, s(1)), Pref::unary(Acceptable, s(2))];
        assert_eq!(run(&p), Outcome::Tie(vec![s(1), s(2)]));
    }

    #[test]
    fn better_removes_the_dominated() {
        let p = [
            Pref::unary(Acceptable, s(1)),
            Pref::unary(Acceptable, s(2)),
            Pref::binary(Better, s(2), s(1)),
        ];
        assert_eq!(run(&p), Outcome::Winner(s(2)));
        let p = [
            Pref::unary(Acceptable, s(1)),
            Pref::unary(Acceptable, s(2)),
            Pref::binary(Worse, s(2), s(1)),
        ];
        assert_eq!(run(&p), Outcome::Winner(s(1)));
    }

    #[test]
    fn a_cycle_of_better_is_a_conflict() {
        let p = [
            Pref::unary(Acceptable, s(1)),
            Pref::unary(Acceptable, s(2)),
            Pref::binary(Better, s(1), s(2)),
            Pref::binary(Better, s(2), s(1)),
        ];
        assert_eq!(run(&p), Outcome::Conflict(vec![s(1), s(2)]));
    }

    #[test]
    fn best_and_worst() {
        let a = |i| Pref::unary(Acceptable, s(i));
        assert_eq!(
            run(&[a(1), a(2), Pref::unary(Best, s(2))]),
            Outcome::Winner(s(2))
        );
        assert_eq!(
            run(&[a(1), a(2), Pref::unary(Worst, s(1))]),
            Outcome::Winner(s(2))
        );
        // All worst: worst is ignored, and without indifference they tie.
        assert_eq!(
            run(&[
                a(1),
                a(2),
                Pref::unary(Worst, s(1)),
                Pref::unary(Worst, s(2))
            ]),
            Outcome::Tie(vec![s(1), s(2)])
        );
    }

    #[test]
    fn indifference_unary_or_binary_with_all() {
        let a = |i| Pref::unary(Acceptable, s(i));
        let u = |i| Pref::unary(UnaryIndifferent, s(i));
        assert_eq!(run(&[a(1), a(2), u(1), u(2)]), Outcome::Winner(s(1)));
        assert_eq!(run(&[a(1), a(2), u(1)]), Outcome::Tie(vec![s(1), s(2)]));
        assert_eq!(
            run(&[a(1), a(2), Pref::binary(BinaryIndifferent, s(1), s(2))]),
            Outcome::Winner(s(1))
        );
    }

    /// On the official kernel, four tied indifferent candidates under softmax with
    /// `srand 1..4` pick index 1, 0, 2, 2 of the candidate list.
    #[test]
    fn softmax_uniform_choice_matches_the_official_kernel() {
        let cands = [s(4), s(3), s(2), s(1)];
        let mut prefs = Vec::new();
        for c in cands {
            prefs.push(Pref::unary(Acceptable, c));
            prefs.push(Pref::unary(UnaryIndifferent, c));
        }
        let picks: Vec<Outcome> = (1..=4)
            .map(|seed| {
                decide(
                    &prefs,
                    Policy::Softmax,
                    NumericMode::Sum,
                    &mut Mt19937::new(seed),
                )
            })
            .collect();
        assert_eq!(
            picks,
            vec![
                Outcome::Winner(s(3)),
                Outcome::Winner(s(4)),
                Outcome::Winner(s(2)),
                Outcome::Winner(s(2))
            ]
        );
    }

    #[test]
    fn numeric_values_weight_softmax_and_greedy() {
        let mut prefs = vec![Pref::unary(Acceptable, s(1)), Pref::unary(Acceptable, s(2))];
        prefs.push(Pref::numeric(s(1), 0.0));
        prefs.push(Pref::numeric(s(2), 5.0));
        prefs.push(Pref::numeric(s(2), 1.0));
        assert_eq!(numeric_value(&prefs, s(2), NumericMode::Sum), 6.0);
        assert_eq!(numeric_value(&prefs, s(2), NumericMode::Avg), 3.0);
        let mut rng = Mt19937::new(3);
        // Only s(2) has a positive value, so softmax always takes it.
        for _ in 0..20 {
            assert_eq!(
                decide(&prefs, Policy::Softmax, NumericMode::Sum, &mut rng),
                Outcome::Winner(s(2))
            );
        }
        let greedy = Policy::EpsilonGreedy { epsilon: 0.0 };
        assert_eq!(
            decide(&prefs, greedy, NumericMode::Sum, &mut rng),
            Outcome::Winner(s(2))
        );
    }

    #[test]
    fn first_and_last() {
        let mut rng = Mt19937::new(1);
        assert_eq!(choose(&[0.0, 0.0, 0.0], Policy::First, &mut rng), 0);
        assert_eq!(choose(&[0.0, 0.0, 0.0], Policy::Last, &mut rng), 2);
    }
}
