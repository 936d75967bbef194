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
use std::cell::RefCell;
use std::cmp::Reverse;

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

/// One condition of the list.
struct Cond {
    /// Its id, attribute and value fields (positive conditions).
    fields: [Field; 3],
    positive: bool,
    /// Negations and NCCs: the variables it requires bound, in `Chooser::vars`.
    required: std::ops::Range<u32>,
    cost: u64,
    canon: (u64, u64),
    placed: bool,
    /// Mark for the look-ahead (a generation number).
    mark: u32,
    /// The expected match count of its constant attribute (`multi-attributes`; 1 when not
    /// declared), which 9.6 counts once every root variable is bound.
    multi: u64,
}

/// One variable of the list (its name is in `Chooser::names`).
struct Var {
    bound: bool,
    root: bool,
    /// The conditions whose cost its binding can change, in `Chooser::users`.
    users: std::ops::Range<u32>,
}

/// The conditions of one list, with their current costs.
pub(super) struct Chooser<'a> {
    conds: Vec<Cond>,
    names: Vec<&'a str>,
    vars: Vec<Var>,
    required: Vec<u32>,
    users: Vec<u32>,
    /// The candidates' keys, sorted greatest first: the cheapest is last, where placing
    /// it removes it at no cost.
    queue: Vec<Key>,
    ties: Vec<usize>,
    generation: u32,
    /// Every root variable is bound: from then on 9.6 prices a bound constant attribute
    /// by its `multi-attributes` count (its "common simple case" of a condition's cost).
    roots_done: bool,
    /// Some condition's attribute has a `multi-attributes` count other than 1.
    has_multi: bool,
}

/// A chooser's buffers, kept between lists: every rule is ordered when it is loaded, and
/// allocating them afresh for each cost more than the ordering of a small rule.
#[derive(Default)]
struct Scratch {
    conds: Vec<Cond>,
    vars: Vec<Var>,
    required: Vec<u32>,
    users: Vec<u32>,
    queue: Vec<Key>,
    ties: Vec<usize>,
    start: Vec<u32>,
    next: Vec<u32>,
}

thread_local! {
    static SCRATCH: RefCell<Scratch> = RefCell::default();
}

fn take_scratch() -> Scratch {
    SCRATCH.with(|s| {
        s.try_borrow_mut()
            .map(|mut s| std::mem::take(&mut *s))
            .unwrap_or_default()
    })
}

impl Drop for Chooser<'_> {
    fn drop(&mut self) {
        let mut s = Scratch {
            conds: std::mem::take(&mut self.conds),
            vars: std::mem::take(&mut self.vars),
            required: std::mem::take(&mut self.required),
            users: std::mem::take(&mut self.users),
            queue: std::mem::take(&mut self.queue),
            ties: std::mem::take(&mut self.ties),
            start: Vec::new(),
            next: Vec::new(),
        };
        SCRATCH.with(|cell| {
            if let Ok(mut kept) = cell.try_borrow_mut() {
                // `index_users` parked its counting buffers there.
                s.start = std::mem::take(&mut kept.start);
                s.next = std::mem::take(&mut kept.next);
                *kept = s;
            }
        });
    }
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
        multi: &dyn Fn(&Constant) -> u64,
    ) -> Self {
        let n = conds.len();
        let scratch = take_scratch();
        let (mut cs, mut vars, mut req) = (scratch.conds, scratch.vars, scratch.required);
        cs.clear();
        vars.clear();
        req.clear();
        let mut names: Vec<&'a str> = Vec::new();
        // A linear search numbers the few variables of a list; past a few dozen, a map.
        let mut index: FxHashMap<&'a str, u32> = FxHashMap::default();
        let mut number = |v: &'a str, names: &mut Vec<&'a str>, vars: &mut Vec<Var>| -> u32 {
            if names.len() < 32 {
                if let Some(k) = names.iter().position(|&x| x == v) {
                    return k as u32;
                }
            } else {
                if index.is_empty() {
                    for (k, &x) in names.iter().enumerate() {
                        index.insert(x, k as u32);
                    }
                }
                if let Some(&k) = index.get(v) {
                    return k;
                }
                index.insert(v, names.len() as u32);
            }
            names.push(v);
            vars.push(Var {
                bound: outside.contains(v),
                root: false,
                users: 0..0,
            });
            (vars.len() - 1) as u32
        };
        for (i, c) in conds.iter().enumerate() {
            let start = req.len() as u32;
            let mut fields = [Field::Untested; 3];
            let mut multi_count = 1;
            let positive = match c {
                Condition::Positive(p) => {
                    if let Some(Term::Const(a)) = equality_term(&p.attr) {
                        multi_count = multi(a);
                    }
                    for (slot, t) in fields.iter_mut().zip([&p.id, &p.attr, &p.value]) {
                        *slot = match equality_term(t) {
                            Some(Term::Const(_)) => Field::Const,
                            Some(Term::Var(v)) => Field::Var(number(v, &mut names, &mut vars)),
                            None => Field::Untested,
                        };
                    }
                    true
                }
                _ => {
                    for v in required.get(i).map(Vec::as_slice).unwrap_or(&[]) {
                        let k = number(v, &mut names, &mut vars);
                        req.push(k);
                    }
                    false
                }
            };
            cs.push(Cond {
                fields,
                positive,
                required: start..req.len() as u32,
                cost: 0,
                canon: canonical(c, rank),
                placed: false,
                mark: 0,
                multi: multi_count,
            });
        }
        for r in roots {
            if let Some(k) = names.iter().position(|&v| v == r.as_str()) {
                vars[k].root = true;
            }
        }
        let mut c = Chooser {
            conds: cs,
            names,
            vars,
            required: req,
            users: scratch.users,
            queue: scratch.queue,
            ties: scratch.ties,
            generation: 0,
            roots_done: false,
            has_multi: false,
        };
        c.roots_done = c.all_roots_bound();
        c.has_multi = c.conds.iter().any(|x| x.multi != 1);
        c.index_users(scratch.start, scratch.next);
        for i in 0..n {
            c.conds[i].cost = c.cost(i);
        }
        c.queue.clear();
        for i in 0..n {
            let k = c.key(i);
            c.queue.push(k);
        }
        // The keys are distinct (they end in the index).
        c.queue.sort_unstable_by(|a, b| b.cmp(a));
        c
    }

    /// The variables whose binding can change condition `i`'s cost.
    fn cost_vars(&self, i: usize) -> impl Iterator<Item = u32> + '_ {
        let c = &self.conds[i];
        let from_fields = c.fields.iter().filter_map(|f| match f {
            Field::Var(v) => Some(*v),
            _ => None,
        });
        let r = c.required.start as usize..c.required.end as usize;
        from_fields.chain(self.required[r].iter().copied())
    }

    /// `start` and `next`: buffers to count in, returned to the scratch afterwards.
    fn index_users(&mut self, mut start: Vec<u32>, mut next: Vec<u32>) {
        let (n, nv) = (self.conds.len(), self.vars.len());
        // Counting sort of (variable, condition) pairs: each variable's users in a row.
        start.clear();
        start.resize(nv + 1, 0);
        for i in 0..n {
            for v in self.cost_vars(i) {
                start[v as usize + 1] += 1;
            }
        }
        for k in 0..nv {
            start[k + 1] += start[k];
        }
        let mut users = std::mem::take(&mut self.users);
        users.clear();
        users.resize(start[nv] as usize, 0);
        next.clear();
        next.extend_from_slice(&start);
        for i in 0..n {
            for v in self.cost_vars(i) {
                users[next[v as usize] as usize] = i as u32;
                next[v as usize] += 1;
            }
        }
        for (k, v) in self.vars.iter_mut().enumerate() {
            v.users = start[k]..start[k + 1];
        }
        self.users = users;
        SCRATCH.with(|cell| {
            if let Ok(mut kept) = cell.try_borrow_mut() {
                kept.start = start;
                kept.next = next;
            }
        });
    }

    fn queue_insert(&mut self, k: Key) {
        if let Err(p) = self.queue.binary_search_by(|x| k.cmp(x)) {
            self.queue.insert(p, k);
        }
    }

    fn queue_remove(&mut self, k: &Key) {
        if let Ok(p) = self.queue.binary_search_by(|x| k.cmp(x)) {
            self.queue.remove(p);
        }
    }

    fn users_of(&self, v: u32) -> std::ops::Range<usize> {
        let r = &self.vars[v as usize].users;
        r.start as usize..r.end as usize
    }

    fn covered(&self, f: Field) -> bool {
        match f {
            Field::Const => true,
            Field::Var(v) => {
                let v = &self.vars[v as usize];
                v.bound || v.root
            }
            Field::Untested => false,
        }
    }

    fn cost(&self, i: usize) -> u64 {
        let c = &self.conds[i];
        if !c.positive {
            let r = c.required.start as usize..c.required.end as usize;
            let all = self.required[r]
                .iter()
                .all(|&v| self.vars[v as usize].bound);
            return if all { 1 } else { MAX_COST };
        }
        let [id, attr, value] = c.fields;
        if !self.covered(id) {
            return MAX_COST;
        }
        let mut cost = match (self.covered(attr), self.roots_done) {
            (true, true) => c.multi,
            (true, false) => 1,
            (false, _) => BRANCHING,
        };
        if !self.covered(value) {
            cost *= BRANCHING;
        }
        cost
    }

    fn key(&self, i: usize) -> Key {
        let c = &self.conds[i];
        let canon = if c.positive { c.canon } else { (0, 0) };
        (c.cost, c.positive, Reverse(canon), Reverse(i))
    }

    /// The variables a positive condition binds that are not bound yet.
    fn newly_bound(&self, i: usize) -> [Option<u32>; 3] {
        let mut out = [None; 3];
        let c = &self.conds[i];
        if c.positive {
            for (slot, f) in out.iter_mut().zip(c.fields) {
                if let Field::Var(v) = f {
                    if !self.vars[v as usize].bound {
                        *slot = Some(v);
                    }
                }
            }
        }
        out
    }

    /// The cheapest next condition after `i` were placed (9.6's one-step look-ahead).
    fn lookahead(&mut self, i: usize) -> u64 {
        if self.conds[i].placed {
            return MAX_COST + 1;
        }
        let new = self.newly_bound(i);
        self.generation += 1;
        let g = self.generation;
        for v in new.into_iter().flatten() {
            self.vars[v as usize].bound = true;
            for k in self.users_of(v) {
                let j = self.users[k] as usize;
                self.conds[j].mark = g;
            }
        }
        let mut min = MAX_COST + 1;
        for &(cached, _, _, Reverse(j)) in self.queue.iter().rev() {
            if j == i {
                continue;
            }
            let k = if self.conds[j].mark == g {
                self.cost(j)
            } else {
                cached
            };
            min = min.min(k);
        }
        for v in new.into_iter().flatten() {
            self.vars[v as usize].bound = false;
        }
        min
    }

    /// Which remaining condition goes next: the cheapest; among several at cost 1 a
    /// negation (the last one), else the greater canonical key; among several above cost 1
    /// the one with the cheapest look-ahead, then the greater canonical key. 9.6 walks the
    /// tied set from the last condition to the first, so equal keys go to the later one.
    fn pick(&mut self) -> Option<usize> {
        let &(min, _, _, Reverse(first)) = self.queue.last()?;
        if min <= 1 {
            return Some(first);
        }
        let mut ties = std::mem::take(&mut self.ties);
        ties.clear();
        ties.extend(
            self.queue
                .iter()
                .rev()
                .take_while(|k| k.0 == min)
                .map(|k| k.3 .0),
        );
        if ties.len() == 1 {
            self.ties = ties;
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
            } else if k == best
                && self.conds[i].positive
                && self.conds[chosen].canon < self.conds[i].canon
            {
                chosen = i;
            }
        }
        self.ties = ties;
        Some(chosen)
    }

    /// The next condition to place (its index); the caller then calls [`Self::bind`].
    pub fn next(&mut self) -> Option<usize> {
        let i = self.pick()?;
        let k = self.key(i);
        self.queue_remove(&k);
        self.conds[i].placed = true;
        Some(i)
    }

    /// Records what placed condition `i` binds, updating the costs that depend on it.
    pub fn bind(&mut self, i: usize) {
        let new = self.newly_bound(i);
        for v in new.into_iter().flatten() {
            self.vars[v as usize].bound = true;
        }
        for v in new.into_iter().flatten() {
            for k in self.users_of(v) {
                let j = self.users[k] as usize;
                if self.conds[j].placed {
                    continue;
                }
                let c = self.cost(j);
                if c != self.conds[j].cost {
                    let old = self.key(j);
                    self.queue_remove(&old);
                    self.conds[j].cost = c;
                    let new_key = self.key(j);
                    self.queue_insert(new_key);
                }
            }
        }
        // Once every root is bound the roots no longer count; they are bound then, so
        // `covered` is unchanged, but a declared multi-attribute now prices its conditions.
        if !self.roots_done && self.all_roots_bound() {
            self.roots_done = true;
            if self.has_multi {
                self.price_all_again();
            }
        }
    }

    fn all_roots_bound(&self) -> bool {
        self.vars.iter().all(|v| !v.root || v.bound)
    }

    /// Every unplaced condition's cost computed again, and the queue with it.
    fn price_all_again(&mut self) {
        for j in 0..self.conds.len() {
            if !self.conds[j].placed {
                self.conds[j].cost = self.cost(j);
            }
        }
        let mut queue = std::mem::take(&mut self.queue);
        queue.clear();
        for j in 0..self.conds.len() {
            if !self.conds[j].placed {
                queue.push(self.key(j));
            }
        }
        queue.sort_unstable_by(|a, b| b.cmp(a));
        self.queue = queue;
    }

    /// Everything bound now, by name: `outside` and what the placed conditions bound.
    pub fn bound_names(&self, outside: &Bound) -> Bound {
        let mut b = outside.clone();
        for (v, name) in self.vars.iter().zip(&self.names) {
            if v.bound {
                b.insert(name.to_string());
            }
        }
        b
    }
}
