//! Operator selection knowledge (Soar manual, ch. 4, "Chunking", the `add-osk` setting): the
//! preferences that decided which operator a substate selected. Chunking backtraces through
//! the rules that made them, so a rule learned from reasoning that depended on the choice
//! also tests what the choice depended on.
//!
//! 9.6 gathers them while it runs the preference semantics for an operator slot below the
//! top state, stage by stage: every prohibit and reject; the better and worse preferences
//! that put a surviving candidate above another; the best preferences of the candidates
//! kept for them; the worst preferences of the candidates dropped for them; and, for an
//! indifferent choice, the winner's numeric preferences and the binary indifferent
//! preferences naming it (unary indifferent ones count for nothing). A required operator
//! brings none: its require preference is backtraced as the operator's own support. The
//! set is empty when the slot impasses.

use super::procedure::{Pref, PrefType};
use crate::symbols::Sym;

/// The operator selection knowledge behind `winner`: indices into `prefs` (the slot's
/// preferences, oldest first), in the order 9.6 gathers them. Within each kind 9.6 reads
/// its lists newest first, and leaves out a preference that says what one gathered before
/// says (the same kind for the same value, or the same pair for binary ones), except for
/// numeric preferences.
pub fn selection_knowledge(prefs: &[Pref], winner: Sym) -> Vec<usize> {
    let mut out: Vec<usize> = Vec::new();
    if prefs.iter().any(|p| p.kind == PrefType::Require) {
        return out;
    }
    let newest_first = |kind: PrefType| {
        prefs
            .iter()
            .enumerate()
            .rev()
            .filter(move |(_, p)| p.kind == kind)
    };
    let has = |kind: PrefType, v: Sym| prefs.iter().any(|p| p.kind == kind && p.value == v);
    // Every preference of `kind` for value `c`, newest first.
    let add_of = |out: &mut Vec<usize>, kind: PrefType, c: Sym| {
        for (i, p) in newest_first(kind) {
            if p.value == c {
                add(prefs, out, i, true);
            }
        }
    };
    let mut cands: Vec<Sym> = Vec::new();
    for p in prefs.iter().filter(|p| p.kind == PrefType::Acceptable) {
        if !has(PrefType::Prohibit, p.value)
            && !has(PrefType::Reject, p.value)
            && !cands.contains(&p.value)
        {
            cands.push(p.value);
        }
    }
    for kind in [PrefType::Prohibit, PrefType::Reject] {
        for (i, _) in newest_first(kind) {
            add(prefs, &mut out, i, true);
        }
    }
    if cands.len() <= 1 {
        return out;
    }
    // Better and worse: the preferences that rank a surviving candidate over another.
    let binary = |p: &Pref| matches!(p.kind, PrefType::Better | PrefType::Worse);
    if prefs.iter().any(binary) {
        let mut dominated = vec![false; cands.len()];
        for p in prefs.iter().filter(|p| binary(p)) {
            let Some(r) = p.referent else { continue };
            let (Some(vi), Some(ri)) = (
                cands.iter().position(|c| *c == p.value),
                cands.iter().position(|c| *c == r),
            ) else {
                continue;
            };
            if vi == ri {
                continue;
            }
            match p.kind {
                PrefType::Better => dominated[ri] = true,
                _ => dominated[vi] = true,
            }
        }
        let survivors: Vec<Sym> = cands
            .iter()
            .zip(&dominated)
            .filter(|(_, d)| !**d)
            .map(|(c, _)| *c)
            .collect();
        for &c in &survivors {
            add_of(&mut out, PrefType::Better, c);
            for (i, p) in newest_first(PrefType::Worse) {
                if p.referent == Some(c) {
                    add(prefs, &mut out, i, true);
                }
            }
        }
        cands = survivors;
        if cands.len() <= 1 {
            return out;
        }
    }
    // Best: the preferences of the candidates kept for them.
    if cands.iter().any(|&c| has(PrefType::Best, c)) {
        cands.retain(|&c| has(PrefType::Best, c));
        for &c in &cands {
            add_of(&mut out, PrefType::Best, c);
        }
        if cands.len() <= 1 {
            return out;
        }
    }
    // Worst: the preferences of the candidates dropped for them, when some candidate is
    // not worst.
    if cands.iter().any(|&c| !has(PrefType::Worst, c)) {
        for &c in cands.iter().filter(|&&c| has(PrefType::Worst, c)) {
            add_of(&mut out, PrefType::Worst, c);
        }
        cands.retain(|&c| !has(PrefType::Worst, c));
        if cands.len() <= 1 {
            return out;
        }
    }
    // An indifferent choice: the winner's numeric preferences, and the binary indifferent
    // ones naming it (with numeric preferences about, those not between two candidates
    // that both have a number).
    let numeric = |c: Sym| cands.contains(&c) && has(PrefType::NumericIndifferent, c);
    let some_numeric = cands.iter().any(|&c| numeric(c));
    if some_numeric {
        for (i, p) in newest_first(PrefType::NumericIndifferent) {
            if p.value == winner {
                add(prefs, &mut out, i, false);
            }
        }
    }
    for (i, p) in newest_first(PrefType::BinaryIndifferent) {
        let Some(r) = p.referent else { continue };
        if (p.value == winner || r == winner) && !(some_numeric && numeric(r) && numeric(p.value))
        {
            add(prefs, &mut out, i, true);
        }
    }
    out
}

/// With `add-osk` off, 9.6 still backtraces through an operator slot's prohibit
/// preferences: their indices in `prefs`, newest first.
pub fn prohibits(prefs: &[Pref]) -> Vec<usize> {
    (0..prefs.len())
        .rev()
        .filter(|&i| prefs[i].kind == PrefType::Prohibit)
        .collect()
}

/// Adds preference `i` unless it is there, or (with `unique`) one that says the same is.
fn add(prefs: &[Pref], out: &mut Vec<usize>, i: usize, unique: bool) {
    let p = &prefs[i];
    let same = |q: &Pref| {
        use PrefType::{Better, BinaryIndifferent, Worse};
        match (p.kind, q.kind) {
            (Better | Worse, Better | Worse) if p.kind == q.kind => {
                p.value == q.value && p.referent == q.referent
            }
            (Better | Worse, Better | Worse) => {
                Some(p.value) == q.referent && p.referent == Some(q.value)
            }
            (BinaryIndifferent, BinaryIndifferent) => {
                (p.value == q.value && p.referent == q.referent)
                    || (Some(p.value) == q.referent && p.referent == Some(q.value))
            }
            _ => p.value == q.value && p.kind == q.kind,
        }
    };
    if out
        .iter()
        .any(|&j| j == i || (unique && same(&prefs[j])))
    {
        return;
    }
    out.push(i);
}

#[cfg(test)]
mod tests {
    use super::*;
    use PrefType::*;

    fn s(i: u32) -> Sym {
        Sym(i)
    }

    #[test]
    fn best_brings_its_preference() {
        let prefs = [
            Pref::unary(Acceptable, s(1)),
            Pref::unary(Acceptable, s(2)),
            Pref::unary(Best, s(2)),
        ];
        assert_eq!(selection_knowledge(&prefs, s(2)), vec![2]);
    }

    #[test]
    fn require_brings_none() {
        let prefs = [
            Pref::unary(Acceptable, s(1)),
            Pref::unary(Require, s(1)),
            Pref::unary(Reject, s(2)),
        ];
        assert!(selection_knowledge(&prefs, s(1)).is_empty());
    }

    #[test]
    fn rejects_count_even_for_one_candidate() {
        let prefs = [
            Pref::unary(Acceptable, s(1)),
            Pref::unary(Acceptable, s(2)),
            Pref::unary(Reject, s(2)),
        ];
        assert_eq!(selection_knowledge(&prefs, s(1)), vec![2]);
    }

    #[test]
    fn a_second_best_for_the_same_value_is_left_out() {
        let prefs = [
            Pref::unary(Acceptable, s(1)),
            Pref::unary(Acceptable, s(2)),
            Pref::unary(Best, s(2)),
            Pref::unary(Best, s(2)),
        ];
        // Newest first: the later one is kept.
        assert_eq!(selection_knowledge(&prefs, s(2)), vec![3]);
    }

    #[test]
    fn worse_counts_for_the_candidate_it_ranks_above() {
        let prefs = [
            Pref::unary(Acceptable, s(1)),
            Pref::unary(Acceptable, s(2)),
            Pref::binary(Worse, s(1), s(2)),
        ];
        assert_eq!(selection_knowledge(&prefs, s(2)), vec![2]);
    }

    #[test]
    fn unary_indifference_counts_for_nothing() {
        let prefs = [
            Pref::unary(Acceptable, s(1)),
            Pref::unary(Acceptable, s(2)),
            Pref::unary(UnaryIndifferent, s(1)),
            Pref::unary(UnaryIndifferent, s(2)),
        ];
        assert!(selection_knowledge(&prefs, s(1)).is_empty());
    }
}
