//! Step 3 of the reorderer (see `mod.rs`): choosing the conditions one by one by cost, with
//! 9.6's tie rules. Costs are kept per condition and recomputed only for the conditions
//! that test a variable the last choice bound, so a rule of thousands of conditions orders
//! in about quadratic time, as in 9.6, not worse.

use super::{bound_by, equality_term, Bound};
use crate::ast::Constant;
use crate::production::{Cond, Condition, Term, Test};
use rustc_hash::FxHashMap;
use std::cmp::Reverse;
use std::collections::BTreeSet;

/// The cost of a condition that cannot be joined yet (its id is unbound).
const MAX_COST: u64 = 10_000_005;
/// Branching factor for an unbound attribute or value.
const BRANCHING: u64 = 8;

/// One condition waiting to be placed.
pub(super) struct Pending {
    pub cond: Condition,
    /// For a negation or NCC: the variables positive conditions must bind first.
    pub required: Vec<String>,
    /// For an NCC: what its inner conditions require.
    pub inner: Option<super::Required>,
}

fn covered(t: &Test, bound: &Bound, roots: &[String]) -> bool {
    match equality_term(t) {
        Some(Term::Const(_)) => true,
        Some(Term::Var(v)) => bound.contains(v) || roots.iter().any(|r| r == v),
        None => false,
    }
}

fn cost_of_positive(p: &Cond, bound: &Bound, roots: &[String]) -> u64 {
    if !covered(&p.id, bound, roots) {
        return MAX_COST;
    }
    let mut cost = if covered(&p.attr, bound, roots) {
        1
    } else {
        BRANCHING
    };
    if !covered(&p.value, bound, roots) {
        cost *= BRANCHING;
    }
    cost
}

fn cost(p: &Pending, bound: &Bound, roots: &[String]) -> u64 {
    match &p.cond {
        Condition::Positive(c) => cost_of_positive(c, bound, roots),
        _ if p.required.iter().all(|v| bound.contains(v)) => 1,
        _ => MAX_COST,
    }
}

/// The variables whose binding can change a condition's cost.
fn cost_vars(p: &Pending) -> Vec<&str> {
    match &p.cond {
        Condition::Positive(c) => [&c.id, &c.attr, &c.value]
            .into_iter()
            .filter_map(|t| match equality_term(t) {
                Some(Term::Var(v)) => Some(v.as_str()),
                _ => None,
            })
            .collect(),
        _ => p.required.iter().map(String::as_str).collect(),
    }
}

/// The canonical order key: creation ranks of a condition's constant attribute and value
/// (0 for anything else); the greater key wins a tie.
fn canonical(c: &Condition, rank: &dyn Fn(&Constant) -> u64) -> (u64, u64) {
    let of = |t: &Test| match t {
        Test::Equal(Term::Const(k)) => rank(k),
        _ => 0,
    };
    match c {
        Condition::Positive(p) | Condition::Negative(p) => (of(&p.attr), of(&p.value)),
        Condition::Ncc(_) => (0, 0),
    }
}

/// Where a condition stands among the candidates: cheapest first; at equal cost a
/// negation before a positive condition, a greater canonical key first, and the later
/// condition first. At cost 1 the first entry is 9.6's choice; above it, the entries of
/// equal cost are the tied set that the look-ahead decides between.
type Key = (u64, bool, Reverse<(u64, u64)>, Reverse<usize>);

/// The conditions of one list, with their current costs.
pub(super) struct Chooser {
    pending: Vec<Option<Pending>>,
    queue: BTreeSet<Key>,
    costs: Vec<u64>,
    canon: Vec<(u64, u64)>,
    by_var: FxHashMap<String, Vec<usize>>,
    pub bound: Bound,
    roots: Vec<String>,
    /// Marks for the look-ahead (a generation number per condition).
    marks: Vec<u32>,
    generation: u32,
}

impl Chooser {
    pub fn new(
        pending: Vec<Pending>,
        outside: &Bound,
        roots: Vec<String>,
        rank: &dyn Fn(&Constant) -> u64,
    ) -> Self {
        let mut by_var: FxHashMap<String, Vec<usize>> = FxHashMap::default();
        for (i, p) in pending.iter().enumerate() {
            for v in cost_vars(p) {
                by_var.entry(v.to_string()).or_default().push(i);
            }
        }
        let costs: Vec<u64> = pending.iter().map(|p| cost(p, outside, &roots)).collect();
        let canon = pending.iter().map(|p| canonical(&p.cond, rank)).collect();
        let n = pending.len();
        let mut c = Chooser {
            pending: pending.into_iter().map(Some).collect(),
            queue: BTreeSet::new(),
            costs,
            canon,
            by_var,
            bound: outside.clone(),
            roots,
            marks: vec![0; n],
            generation: 0,
        };
        for i in 0..n {
            let k = c.key(i);
            c.queue.insert(k);
        }
        c
    }

    fn positive(&self, i: usize) -> bool {
        matches!(
            self.pending[i].as_ref().map(|p| &p.cond),
            Some(Condition::Positive(_))
        )
    }

    fn key(&self, i: usize) -> Key {
        let positive = self.positive(i);
        let canon = if positive { self.canon[i] } else { (0, 0) };
        (self.costs[i], positive, Reverse(canon), Reverse(i))
    }

    /// The cheapest next condition after `i` were placed (9.6's one-step look-ahead).
    fn lookahead(&mut self, i: usize) -> u64 {
        let Some(p) = self.pending[i].as_ref() else {
            return MAX_COST + 1;
        };
        let new: Vec<String> = bound_by(&p.cond)
            .into_iter()
            .filter(|v| !self.bound.contains(*v))
            .map(str::to_string)
            .collect();
        self.generation += 1;
        let g = self.generation;
        let mut with = self.bound.clone();
        for v in &new {
            with.insert(v.clone());
            for &j in self.by_var.get(v).map(Vec::as_slice).unwrap_or(&[]) {
                self.marks[j] = g;
            }
        }
        let mut min = MAX_COST + 1;
        for &(cached, _, _, Reverse(j)) in &self.queue {
            if j == i {
                continue;
            }
            let k = if self.marks[j] == g {
                self.pending[j]
                    .as_ref()
                    .map_or(MAX_COST, |p| cost(p, &with, &self.roots))
            } else {
                cached
            };
            min = min.min(k);
        }
        min
    }

    /// Which remaining condition goes next: the cheapest; among several at cost 1 a
    /// negation (the last one), else the greater canonical key; among several above cost 1
    /// the one with the cheapest look-ahead, then the greater canonical key. 9.6 walks the
    /// tied set from the last condition to the first, so equal keys go to the later one.
    fn pick(&mut self) -> Option<usize> {
        let &(min, _, _, Reverse(first)) = self.queue.iter().next()?;
        if min <= 1 {
            return Some(first);
        }
        let mut ties: Vec<usize> = self
            .queue
            .iter()
            .take_while(|k| k.0 == min)
            .map(|k| k.3 .0)
            .collect();
        if ties.len() == 1 {
            return Some(first);
        }
        ties.sort_unstable_by(|a, b| b.cmp(a));
        let mut chosen = ties[0];
        let mut best = MAX_COST + 1;
        for &i in &ties {
            let k = self.lookahead(i);
            if k < best {
                best = k;
                chosen = i;
            } else if k == best && self.positive(i) && self.canon[chosen] < self.canon[i] {
                chosen = i;
            }
        }
        Some(chosen)
    }

    /// Takes the next condition out; the caller places it and then calls [`Self::bind`].
    pub fn next(&mut self) -> Option<Pending> {
        let i = self.pick()?;
        let k = self.key(i);
        self.queue.remove(&k);
        self.pending[i].take()
    }

    /// Records what a placed condition binds, updating the costs that depend on it.
    pub fn bind(&mut self, placed: &Condition) {
        let new: Vec<String> = bound_by(placed)
            .into_iter()
            .filter(|v| !self.bound.contains(*v))
            .map(str::to_string)
            .collect();
        for v in &new {
            self.bound.insert(v.clone());
        }
        for v in &new {
            let users = self.by_var.get(v).cloned().unwrap_or_default();
            for j in users {
                let Some(p) = self.pending[j].as_ref() else {
                    continue;
                };
                let k = cost(p, &self.bound, &self.roots);
                if k != self.costs[j] {
                    let old = self.key(j);
                    self.queue.remove(&old);
                    self.costs[j] = k;
                    let new_key = self.key(j);
                    self.queue.insert(new_key);
                }
            }
        }
        // Once every root is bound the roots no longer count (nothing changes: they are
        // bound), as in 9.6.
        if self.roots.iter().all(|r| self.bound.contains(r)) {
            self.roots.clear();
        }
    }
}
