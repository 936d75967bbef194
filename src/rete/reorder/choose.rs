//! Step 3 of the reorderer (see `mod.rs`): choosing the conditions one by one by cost, with
//! 9.6's tie rules. Costs are kept per condition and recomputed only for the conditions
//! that test a variable the last choice bound, so a rule of thousands of conditions orders
//! in about quadratic time, as in 9.6, not worse.
//!
//! The chooser borrows the conditions and numbers their variables once, so that choosing
//! works on flags and indexes rather than on sets of names (every rule is ordered when it
//! is loaded).

use super::{equality_term, Bound};
use crate::ast::Constant;
use crate::production::{Condition, Term, Test};
use rustc_hash::FxHashMap;
use std::cmp::Reverse;
use std::collections::BTreeSet;

/// The cost of a condition that cannot be joined yet (its id is unbound).
const MAX_COST: u64 = 10_000_005;
/// Branching factor for an unbound attribute or value.
const BRANCHING: u64 = 8;

/// A field of a positive condition by its equality test: a constant, a variable (by number),
/// or no equality test.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Field {
    Const,
    Var(u32),
    Untested,
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
pub(super) struct Chooser<'a> {
    /// The variables' names, by number.
    names: Vec<&'a str>,
    /// Per condition: its id, attribute and value fields (positive conditions), or the
    /// numbers of the variables it requires bound (negations and NCCs), in `vars`.
    fields: Vec<[Field; 3]>,
    positive: Vec<bool>,
    required: Vec<std::ops::Range<usize>>,
    vars: Vec<u32>,
    /// Per variable: the conditions whose cost its binding can change, in `user_list`.
    users: Vec<std::ops::Range<usize>>,
    user_list: Vec<u32>,
    bound: Vec<bool>,
    root: Vec<bool>,
    placed: Vec<bool>,
    queue: BTreeSet<Key>,
    costs: Vec<u64>,
    canon: Vec<(u64, u64)>,
    /// Marks for the look-ahead (a generation number per condition).
    marks: Vec<u32>,
    generation: u32,
}

impl<'a> Chooser<'a> {
    /// `required[i]`: the variables negation or NCC `i` needs bound first (see
    /// `Required`); missing entries need none.
    pub fn new(
        conds: &'a [Condition],
        required: &'a [Vec<String>],
        outside: &Bound,
        roots: &[String],
        rank: &dyn Fn(&Constant) -> u64,
    ) -> Self {
        let n = conds.len();
        let mut index: FxHashMap<&'a str, u32> = FxHashMap::default();
        let mut names: Vec<&'a str> = Vec::new();
        let mut number = |v: &'a str| {
            *index.entry(v).or_insert_with(|| {
                names.push(v);
                (names.len() - 1) as u32
            })
        };
        let mut fields = Vec::with_capacity(n);
        let mut positive = Vec::with_capacity(n);
        let mut req = Vec::with_capacity(n);
        let mut vars = Vec::new();
        for (i, c) in conds.iter().enumerate() {
            let start = vars.len();
            match c {
                Condition::Positive(p) => {
                    let mut f = [Field::Untested; 3];
                    for (slot, t) in f.iter_mut().zip([&p.id, &p.attr, &p.value]) {
                        *slot = match equality_term(t) {
                            Some(Term::Const(_)) => Field::Const,
                            Some(Term::Var(v)) => Field::Var(number(v)),
                            None => Field::Untested,
                        };
                    }
                    fields.push(f);
                    positive.push(true);
                }
                _ => {
                    for v in required.get(i).map(Vec::as_slice).unwrap_or(&[]) {
                        vars.push(number(v));
                    }
                    fields.push([Field::Untested; 3]);
                    positive.push(false);
                }
            }
            req.push(start..vars.len());
        }
        let nv = names.len();
        let bound: Vec<bool> = names.iter().map(|v| outside.contains(*v)).collect();
        let mut root = vec![false; nv];
        for r in roots {
            if let Some(&k) = index.get(r.as_str()) {
                root[k as usize] = true;
            }
        }
        let mut c = Chooser {
            names,
            fields,
            positive,
            required: req,
            vars,
            users: Vec::new(),
            user_list: Vec::new(),
            bound,
            root,
            placed: vec![false; n],
            queue: BTreeSet::new(),
            costs: Vec::with_capacity(n),
            canon: conds.iter().map(|c| canonical(c, rank)).collect(),
            marks: vec![0; n],
            generation: 0,
        };
        c.index_users(nv);
        for i in 0..n {
            let k = c.cost(i);
            c.costs.push(k);
        }
        for i in 0..n {
            let k = c.key(i);
            c.queue.insert(k);
        }
        c
    }

    /// The variables whose binding can change condition `i`'s cost.
    fn cost_vars(&self, i: usize) -> impl Iterator<Item = u32> + '_ {
        let from_fields = self.fields[i].iter().filter_map(|f| match f {
            Field::Var(v) => Some(*v),
            _ => None,
        });
        let required = self.vars[self.required[i].clone()].iter().copied();
        from_fields.chain(required)
    }

    fn index_users(&mut self, nv: usize) {
        let n = self.fields.len();
        let mut count = vec![0usize; nv + 1];
        for i in 0..n {
            for v in self.cost_vars(i) {
                count[v as usize + 1] += 1;
            }
        }
        for k in 0..nv {
            count[k + 1] += count[k];
        }
        let mut next = count.clone();
        let mut list = vec![0u32; count[nv]];
        for i in 0..n {
            for v in self.cost_vars(i) {
                list[next[v as usize]] = i as u32;
                next[v as usize] += 1;
            }
        }
        self.users = (0..nv).map(|k| count[k]..count[k + 1]).collect();
        self.user_list = list;
    }

    fn covered(&self, f: Field) -> bool {
        match f {
            Field::Const => true,
            Field::Var(v) => self.bound[v as usize] || self.root[v as usize],
            Field::Untested => false,
        }
    }

    fn cost(&self, i: usize) -> u64 {
        if !self.positive[i] {
            let all = self.vars[self.required[i].clone()]
                .iter()
                .all(|&v| self.bound[v as usize]);
            return if all { 1 } else { MAX_COST };
        }
        let [id, attr, value] = self.fields[i];
        if !self.covered(id) {
            return MAX_COST;
        }
        let mut cost = if self.covered(attr) { 1 } else { BRANCHING };
        if !self.covered(value) {
            cost *= BRANCHING;
        }
        cost
    }

    fn key(&self, i: usize) -> Key {
        let positive = self.positive[i];
        let canon = if positive { self.canon[i] } else { (0, 0) };
        (self.costs[i], positive, Reverse(canon), Reverse(i))
    }

    /// The variables a positive condition binds that are not bound yet.
    fn newly_bound(&self, i: usize) -> [Option<u32>; 3] {
        let mut out = [None; 3];
        if self.positive[i] {
            for (slot, f) in out.iter_mut().zip(self.fields[i]) {
                if let Field::Var(v) = f {
                    if !self.bound[v as usize] {
                        *slot = Some(v);
                    }
                }
            }
        }
        out
    }

    /// The cheapest next condition after `i` were placed (9.6's one-step look-ahead).
    fn lookahead(&mut self, i: usize) -> u64 {
        if self.placed[i] {
            return MAX_COST + 1;
        }
        let new = self.newly_bound(i);
        self.generation += 1;
        let g = self.generation;
        for v in new.into_iter().flatten() {
            self.bound[v as usize] = true;
            for k in self.users[v as usize].clone() {
                let j = self.user_list[k] as usize;
                self.marks[j] = g;
            }
        }
        let mut min = MAX_COST + 1;
        for &(cached, _, _, Reverse(j)) in &self.queue {
            if j == i {
                continue;
            }
            let k = if self.marks[j] == g {
                self.cost(j)
            } else {
                cached
            };
            min = min.min(k);
        }
        for v in new.into_iter().flatten() {
            self.bound[v as usize] = false;
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
            } else if k == best && self.positive[i] && self.canon[chosen] < self.canon[i] {
                chosen = i;
            }
        }
        Some(chosen)
    }

    /// The next condition to place (its index); the caller then calls [`Self::bind`].
    pub fn next(&mut self) -> Option<usize> {
        let i = self.pick()?;
        let k = self.key(i);
        self.queue.remove(&k);
        self.placed[i] = true;
        Some(i)
    }

    /// Records what placed condition `i` binds, updating the costs that depend on it.
    pub fn bind(&mut self, i: usize) {
        let new = self.newly_bound(i);
        for v in new.into_iter().flatten() {
            self.bound[v as usize] = true;
        }
        for v in new.into_iter().flatten() {
            for k in self.users[v as usize].clone() {
                let j = self.user_list[k] as usize;
                if self.placed[j] {
                    continue;
                }
                let c = self.cost(j);
                if c != self.costs[j] {
                    let old = self.key(j);
                    self.queue.remove(&old);
                    self.costs[j] = c;
                    let new_key = self.key(j);
                    self.queue.insert(new_key);
                }
            }
        }
        // Once every root is bound the roots no longer count; they are bound then, so
        // `covered` is unchanged and nothing needs clearing.
    }

    /// Everything bound now, by name: `outside` and what the placed conditions bound.
    pub fn bound_names(&self, outside: &Bound) -> Bound {
        let mut b = outside.clone();
        for (k, name) in self.names.iter().enumerate() {
            if self.bound[k] {
                b.insert(name.to_string());
            }
        }
        b
    }
}
