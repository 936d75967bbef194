//! Cue-based retrieval (Soar manual, Semantic Memory, "Cue-Based Retrieval"): the LTIs that
//! have every positive element of the cue, none of the negative ones (`neg-query`), whose
//! numbers meet the math elements (`math-query`) and that are not prohibited; the most
//! activated first, among equals the one whose augmentation was written last (as 9.6 orders
//! them).

use super::params::{Mode, UpdatePolicy};
use super::spread::{Lead, StdHeap};
use super::store::{AugValue, DbResult, Store, Val};
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

/// The numbers an LTI has for an attribute.
fn numbers(store: &Store, lti: i64, attr: &Val) -> DbResult<Vec<f64>> {
    Ok(store
        .augs(lti)?
        .into_iter()
        .filter(|(a, _)| a == attr)
        .filter_map(|(_, v)| number(&v))
        .collect())
}

/// A cue element by symbol numbers, for the checks on each candidate; `None` when the
/// store has never seen its attribute or value, so that no LTI can have it.
fn element(store: &Store, attr: &Val, want: &Want) -> DbResult<Option<(i64, AugValue)>> {
    let Some(a) = store.symbol(attr, false)? else {
        return Ok(None);
    };
    Ok(match want {
        Want::Const(v) => store.symbol(v, false)?.map(|c| (a, AugValue::Const(c))),
        Want::Lti(l) => Some((a, AugValue::Lti(*l))),
        Want::Any => Some((a, AugValue::Any)),
    })
}

/// What an element asks, as `Store::walk_ranked` and `Store::aug_count` take it.
fn value_of(want: &Want) -> Option<Val> {
    match want {
        Want::Const(v) => Some(v.clone()),
        Want::Lti(l) => Some(Val::Lti(*l)),
        Want::Any => None,
    }
}

impl Smem {
    /// The first `limit` LTIs that match the cue, best first. As 9.6 does, the candidates
    /// are those of the element with the fewest augmentations, walked in the order of their
    /// activation, and each is checked against the rest of the cue; without a math element
    /// the walk stops at the `limit`th match, so a cue of one common and one rare element
    /// costs the rare one's candidates, not the common one's.
    pub fn query_first(&mut self, cue: &Cue, limit: usize) -> DbResult<Vec<i64>> {
        let t = self.timer_start(super::timer::QUERY);
        let found = self.query_first_untimed(cue, limit);
        self.timers.stop(t);
        found
    }

    fn query_first_untimed(&mut self, cue: &Cue, limit: usize) -> DbResult<Vec<i64>> {
        let spreading = self.params.spreading();
        let settings = super::spread::Settings::of(&self.params);
        let naive = self.params.mode() == Mode::BaseLevel
            && self.params.update_policy() == UpdatePolicy::Naive;
        self.store()?;
        let Smem {
            store: Some(store),
            spread,
            context,
            ..
        } = &mut *self
        else {
            return Ok(Vec::new());
        };
        let store: &Store = store;
        let firsts: Vec<(&Val, Want)> = cue
            .pos
            .iter()
            .map(|(a, w)| (a, w.clone()))
            .chain(cue.math.iter().map(|(a, _)| (a, Want::Any)))
            .collect();
        if firsts.is_empty() {
            return Ok(Vec::new());
        }
        let mut counts = Vec::with_capacity(firsts.len());
        for (attr, want) in &firsts {
            counts.push(store.aug_count(attr, value_of(want).as_ref())?);
        }
        let lead = (0..firsts.len()).min_by_key(|&i| counts[i]).unwrap_or(0);
        if counts[lead] == 0 {
            return Ok(Vec::new());
        }
        let mut checks = Vec::with_capacity(firsts.len());
        for (i, (attr, want)) in firsts.iter().enumerate() {
            if i == lead {
                continue;
            }
            match element(store, attr, want)? {
                Some(e) => checks.push(e),
                None => return Ok(Vec::new()),
            }
        }
        let mut absent = Vec::with_capacity(cue.neg.len());
        for (attr, want) in &cue.neg {
            if let Some(e) = element(store, attr, want)? {
                absent.push(e);
            }
        }
        let (attr, want) = &firsts[lead];
        // With spreading, the candidates that have spread are ranked by it, beside the
        // others' walk (9.6 keeps them in a queue it takes from while its top is at least
        // the walk's next activation).
        let mut spread_queue: StdHeap<i64> = StdHeap::default();
        let mut with_spread = rustc_hash::FxHashSet::default();
        if spreading {
            if let Some((a, v)) = element(store, attr, want)? {
                let lead_el = Lead {
                    attr: a,
                    constant: match v {
                        AugValue::Const(c) => Some(c),
                        _ => None,
                    },
                    lti: match v {
                        AugValue::Lti(l) => Some(l),
                        _ => None,
                    },
                };
                spread.calculate(store, &settings, context, &lead_el)?;
                with_spread = store.spread_ltis()?;
                if !with_spread.is_empty() {
                    for (l, act) in store.spread_candidates(&lead_el)? {
                        spread_queue.push(act, l);
                    }
                }
            }
        }
        // The naive update policy computes again the activation of every LTI the walk may
        // visit, first (9.6 reads them into a set, so by number).
        if naive {
            let mut visit = std::collections::BTreeSet::new();
            store.walk_ranked(attr, value_of(want).as_ref(), |c| {
                visit.insert(c);
                Ok(false)
            })?;
            let visit: Vec<i64> = visit.into_iter().collect();
            self.touch_all(&visit)?;
        }
        let Some(store) = self.store.as_ref() else {
            return Ok(Vec::new());
        };
        let mut candidates = Vec::new();
        let want_all = !cue.math.is_empty();
        let mut taken = rustc_hash::FxHashSet::default();
        // Whether `c` matches the rest of the cue; true when enough have been found.
        let mut consider = |c: i64, candidates: &mut Vec<i64>| -> DbResult<bool> {
            if cue.prohibit.contains(&c) || taken.contains(&c) {
                return Ok(false);
            }
            for &(a, v) in &checks {
                if !store.has_aug(c, a, v)? {
                    return Ok(false);
                }
            }
            for &(a, v) in &absent {
                if store.has_aug(c, a, v)? {
                    return Ok(false);
                }
            }
            taken.insert(c);
            candidates.push(c);
            Ok(!want_all && candidates.len() >= limit)
        };
        let mut done = false;
        store.walk_ranked(attr, value_of(want).as_ref(), |c| {
            if with_spread.is_empty() {
                return consider(c, &mut candidates);
            }
            if with_spread.contains(&c) {
                return Ok(false);
            }
            let act = store.rank_activation(c)?;
            while let Some(&(top, l)) = spread_queue.top() {
                if act > top {
                    break;
                }
                spread_queue.pop();
                if consider(l, &mut candidates)? {
                    done = true;
                    return Ok(true);
                }
            }
            consider(c, &mut candidates)
        })?;
        if !done && (want_all || candidates.len() < limit) {
            while let Some((_, l)) = spread_queue.pop() {
                if consider(l, &mut candidates)? {
                    break;
                }
            }
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
        candidates.truncate(limit);
        Ok(candidates)
    }
}
