//! Cue-based retrieval (Soar manual, Semantic Memory, "Cue-Based Retrieval"): the LTIs that
//! have every positive element of the cue, none of the negative ones (`neg-query`), whose
//! numbers meet the math elements (`math-query`) and that are not prohibited; the most
//! activated first, the higher number first among equals (as 9.6 orders them).

use super::store::{DbResult, Store, Val};
use super::Smem;

/// What a cue element asks of an augmentation's value.
#[derive(Debug, Clone, PartialEq)]
pub enum Want {
    /// This constant.
    Const(Val),
    /// This LTI.
    Lti(i64),
    /// Any value (the cue's value is a short-term identifier without an LTI).
    Any,
}

/// A math-query test on an attribute's numbers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Math {
    Less(f64),
    Greater(f64),
    LessOrEqual(f64),
    GreaterOrEqual(f64),
    Max,
    Min,
}

impl Math {
    /// The test named by a math-query's attribute (`less`, `max`, ...).
    pub fn from_word(word: &str, n: Option<f64>) -> Option<Math> {
        Some(match (word, n) {
            ("less", Some(x)) => Math::Less(x),
            ("greater", Some(x)) => Math::Greater(x),
            ("less-or-equal", Some(x)) => Math::LessOrEqual(x),
            ("greater-or-equal", Some(x)) => Math::GreaterOrEqual(x),
            ("max", _) => Math::Max,
            ("min", _) => Math::Min,
            _ => return None,
        })
    }
}

/// A whole cue.
#[derive(Debug, Clone, Default)]
pub struct Cue {
    pub pos: Vec<(Val, Want)>,
    pub neg: Vec<(Val, Want)>,
    pub math: Vec<(Val, Math)>,
    pub prohibit: Vec<i64>,
}

fn number(v: &Val) -> Option<f64> {
    match v {
        Val::Int(i) => Some(*i as f64),
        Val::Float(f) => Some(*f),
        _ => None,
    }
}

fn having(store: &Store, attr: &Val, want: &Want) -> DbResult<Vec<i64>> {
    match want {
        Want::Const(v) => store.with_aug(attr, Some(v)),
        Want::Lti(l) => store.with_aug(attr, Some(&Val::Lti(*l))),
        Want::Any => store.with_aug(attr, None),
    }
}

/// The numbers an LTI has for an attribute.
fn numbers(store: &Store, lti: i64, attr: &Val) -> DbResult<Vec<f64>> {
    Ok(store
        .augs(lti)?
        .into_iter()
        .filter(|(a, _)| a == attr)
        .filter_map(|(_, v)| number(&v))
        .collect())
}

impl Smem {
    /// The LTIs that match the cue, best first.
    pub fn query(&mut self, cue: &Cue) -> DbResult<Vec<i64>> {
        let store = self.store()?;
        let mut candidates: Option<Vec<i64>> = None;
        let firsts = cue
            .pos
            .iter()
            .map(|(a, w)| (a, w.clone()))
            .chain(cue.math.iter().map(|(a, _)| (a, Want::Any)));
        for (attr, want) in firsts {
            let with = having(store, attr, &want)?;
            candidates = Some(match candidates {
                None => with,
                Some(c) => c.into_iter().filter(|x| with.contains(x)).collect(),
            });
        }
        let mut candidates = candidates.unwrap_or_default();
        candidates.retain(|x| !cue.prohibit.contains(x));
        for (attr, want) in &cue.neg {
            let with = having(store, attr, want)?;
            candidates.retain(|x| !with.contains(x));
        }
        for (attr, test) in &cue.math {
            let mut kept = Vec::new();
            for &c in &candidates {
                let ns = numbers(store, c, attr)?;
                let ok = match test {
                    Math::Less(x) => ns.iter().any(|n| n < x),
                    Math::Greater(x) => ns.iter().any(|n| n > x),
                    Math::LessOrEqual(x) => ns.iter().any(|n| n <= x),
                    Math::GreaterOrEqual(x) => ns.iter().any(|n| n >= x),
                    Math::Max | Math::Min => !ns.is_empty(),
                };
                if ok {
                    kept.push((c, ns));
                }
            }
            if matches!(test, Math::Max | Math::Min) {
                let best = |ns: &[f64]| {
                    let it = ns.iter().copied();
                    if *test == Math::Max {
                        it.fold(f64::NEG_INFINITY, f64::max)
                    } else {
                        -it.fold(f64::INFINITY, f64::min)
                    }
                };
                let top = kept
                    .iter()
                    .map(|(_, ns)| best(ns))
                    .fold(f64::NEG_INFINITY, f64::max);
                kept.retain(|(_, ns)| best(ns) == top);
            }
            candidates = kept.into_iter().map(|(c, _)| c).collect();
        }
        let mut ranked = Vec::with_capacity(candidates.len());
        for c in candidates {
            ranked.push((store.activation(c)?, c));
        }
        ranked.sort_by(|a, b| b.0.total_cmp(&a.0).then(b.1.cmp(&a.1)));
        Ok(ranked.into_iter().map(|(_, c)| c).collect())
    }
}
