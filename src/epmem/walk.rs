//! The cue's matches kept up to date while a query walks the episodes from the newest back
//! (9.6's `epmem_process_query` walks interval endpoints the same way, with its
//! `epmem_satisfy_literal` and `epmem_unsatisfy_literal`). Between two moments at which a
//! row the cue can match comes or goes, nothing changes; at such a moment only that row's
//! literals, and the literals hanging from the nodes they reach, are looked at again, so a
//! query costs the rows' comings and goings, not the episodes times the cue.
//!
//! The matches always equal what the cue makes of the current episode from scratch: a
//! literal matches `(parent node, child node or value)` when its row is in the episode and
//! its cue identifier is *bound* at the parent node; the root identifier is bound at the
//! root node, and any other cue identifier at a node reached by every inner literal that has
//! it as value. A node is bound only once all of those literals reach it, so a ring of cue
//! identifiers that can only reach each other binds nothing, as in the evaluation from
//! scratch, where such literals never become ready.

use super::cue::Cue;
use super::store::{Life, Store, ROOT};
use crate::symbols::Sym;
use rustc_hash::{FxHashMap, FxHashSet};
use std::collections::{BTreeMap, BinaryHeap};

/// Which literals each stored row can match, and which hang from each cue identifier.
struct Links {
    /// Constant literals by `(attribute, value)`.
    consts: FxHashMap<(i64, i64), Vec<usize>>,
    /// Identifier literals by attribute.
    edges: FxHashMap<i64, Vec<usize>>,
    /// Literals by the cue identifier they hang from.
    under: FxHashMap<Sym, Vec<usize>>,
}

/// The cue's matches in one episode, changed row by row.
pub(super) struct Matches<'a> {
    store: &'a Store,
    cue: &'a Cue,
    links: Links,
    /// The rows the cue can match that are in the episode: (is an edge, row).
    present: FxHashSet<(bool, i64)>,
    /// Each literal's matches, with how many rows give each (edges may repeat a triple).
    pub matches: Vec<BTreeMap<(i64, i64), u32>>,
    /// For each inner literal, how many of its matches reach each child node.
    reach: Vec<FxHashMap<i64, u32>>,
    /// How many inner literals with this cue identifier as value reach each node.
    node_count: FxHashMap<(Sym, i64), usize>,
    /// A list reused from row to row.
    scratch: Vec<usize>,
}

impl<'a> Matches<'a> {
    /// The matches of an episode with none of the cue's rows.
    pub fn new(store: &'a Store, cue: &'a Cue) -> Self {
        let mut links = Links {
            consts: FxHashMap::default(),
            edges: FxHashMap::default(),
            under: FxHashMap::default(),
        };
        for (i, l) in cue.lits.iter().enumerate().skip(1) {
            let Some(a) = l.attr else { continue };
            match l.constant {
                Some(Some(v)) => links.consts.entry((a, v)).or_default().push(i),
                Some(None) => continue,
                None => links.edges.entry(a).or_default().push(i),
            }
            links.under.entry(l.id_sym.unwrap_or(l.value_sym)).or_default().push(i);
        }
        let root = cue.lits[0].value_sym;
        let mut matches = vec![BTreeMap::new(); cue.lits.len()];
        matches[0].insert((ROOT, ROOT), 1);
        Matches {
            store,
            cue,
            links,
            present: FxHashSet::default(),
            matches,
            reach: vec![FxHashMap::default(); cue.lits.len()],
            node_count: FxHashMap::from_iter([((root, ROOT), 1)]),
            scratch: Vec::new(),
        }
    }

    /// Whether leaf `i` has a match.
    pub fn satisfied(&self, i: usize) -> bool {
        !self.matches[i].is_empty()
    }

    /// Whether cue identifier `sym` is bound at `node`.
    fn bound(&self, sym: Sym, node: i64) -> bool {
        let need = self.cue.incoming.get(&sym).copied().unwrap_or(0);
        need > 0 && self.node_count.get(&(sym, node)).copied() == Some(need)
    }

    /// Row `row` (an edge or a constant) is in the episode or not.
    pub fn set_row(&mut self, is_edge: bool, row: i64, present: bool) {
        let was = if present {
            !self.present.insert((is_edge, row))
        } else {
            self.present.remove(&(is_edge, row))
        };
        if was == present {
            return;
        }
        let (p, a, c) = if is_edge {
            self.store.edges.triple(row)
        } else {
            self.store.consts.triple(row)
        };
        let lits = if is_edge {
            self.links.edges.get(&a)
        } else {
            self.links.consts.get(&(a, c))
        };
        let Some(lits) = lits else { return };
        // The literals bound at the row's parent before any change: binding a node on the
        // way can reach this very row again (an edge from a node to itself), and must not
        // count it twice.
        let mut bound = std::mem::take(&mut self.scratch);
        bound.clear();
        bound.extend(lits.iter().copied().filter(|&i| {
            let l = &self.cue.lits[i];
            self.bound(l.id_sym.unwrap_or(l.value_sym), p)
        }));
        for &i in &bound {
            if present {
                self.add(i, p, c);
            } else {
                self.remove(i, p, c, false);
            }
        }
        self.scratch = bound;
    }

    /// One more row gives literal `i` the match `(p, c)`.
    fn add(&mut self, i: usize, p: i64, c: i64) {
        let n = self.matches[i].entry((p, c)).or_insert(0);
        *n += 1;
        if *n > 1 || self.cue.lits[i].is_leaf {
            return;
        }
        let r = self.reach[i].entry(c).or_insert(0);
        *r += 1;
        if *r > 1 {
            return;
        }
        let sym = self.cue.lits[i].value_sym;
        let count = self.node_count.entry((sym, c)).or_insert(0);
        *count += 1;
        if self.bound(sym, c) {
            self.bind(sym, c);
        }
    }

    /// One row less (or, with `all`, none) gives literal `i` the match `(p, c)`.
    fn remove(&mut self, i: usize, p: i64, c: i64, all: bool) {
        let Some(n) = self.matches[i].get_mut(&(p, c)) else {
            return;
        };
        *n = if all { 0 } else { n.saturating_sub(1) };
        if *n > 0 {
            return;
        }
        self.matches[i].remove(&(p, c));
        if self.cue.lits[i].is_leaf {
            return;
        }
        let Some(r) = self.reach[i].get_mut(&c) else {
            return;
        };
        *r -= 1;
        if *r > 0 {
            return;
        }
        self.reach[i].remove(&c);
        let sym = self.cue.lits[i].value_sym;
        let was_bound = self.bound(sym, c);
        if let Some(count) = self.node_count.get_mut(&(sym, c)) {
            *count -= 1;
            if *count == 0 {
                self.node_count.remove(&(sym, c));
            }
        }
        if was_bound {
            self.unbind(sym, c);
        }
    }

    /// Cue identifier `sym` is now bound at `node`: the literals hanging from it match the
    /// episode's rows under the node.
    fn bind(&mut self, sym: Sym, node: i64) {
        let Some(lits) = self.links.under.get(&sym) else {
            return;
        };
        for j in lits.clone() {
            let l = &self.cue.lits[j];
            let Some(a) = l.attr else { continue };
            match l.constant {
                Some(Some(v)) => {
                    let row = self.store.consts.find(&(node, a, v));
                    if row.is_some_and(|r| self.present.contains(&(false, r))) {
                        self.add(j, node, v);
                    }
                }
                Some(None) => {}
                None => {
                    let Some(rows) = self.store.edges.by_parent.get(&(node, a)) else {
                        continue;
                    };
                    for &r in rows {
                        if self.present.contains(&(true, r)) {
                            self.add(j, node, self.store.edges.triple(r).2);
                        }
                    }
                }
            }
        }
    }

    /// Cue identifier `sym` is no longer bound at `node`: the literals hanging from it lose
    /// their matches under the node.
    fn unbind(&mut self, sym: Sym, node: i64) {
        let Some(lits) = self.links.under.get(&sym) else {
            return;
        };
        for j in lits.clone() {
            let gone: Vec<(i64, i64)> = self.matches[j]
                .range((node, i64::MIN)..=(node, i64::MAX))
                .map(|(&k, _)| k)
                .collect();
            for (p, c) in gone {
                self.remove(j, p, c, true);
            }
        }
    }
}

/// The moments, newest first, at which the rows a cue can match come or go, up to episode
/// `top`: an episode whose row set differs from the one after it. A moment `t` means the
/// rows' presence changes between episodes `t + 1` and `t`.
pub(super) struct Moments<'a> {
    store: &'a Store,
    top: i64,
    rows: Vec<Cursor>,
    /// (moment, row's cursor), the newest first.
    heap: BinaryHeap<(i64, usize)>,
}

/// Where the walk is in one row's life: its ranges that start by `top`, read newest first,
/// each giving its end (the row comes, walking back) and the episode before its start (it
/// goes).
struct Cursor {
    is_edge: bool,
    row: i64,
    /// Its closed ranges that start by `top`.
    closed: usize,
    /// The start of its open range, when that starts by `top`.
    open: Option<i64>,
    /// The next moment to give.
    next: usize,
}

impl Cursor {
    fn moment(&self, life: &Life, top: i64) -> Option<i64> {
        let mut k = self.next;
        if let Some(start) = self.open {
            match k {
                0 => return Some(top),
                1 => return Some(start - 1),
                _ => k -= 2,
            }
        }
        let i = self.closed.checked_sub(1 + k / 2)?;
        let (s, e) = life.ranges[i];
        Some(if k.is_multiple_of(2) { e.min(top) } else { s - 1 })
    }
}

impl<'a> Moments<'a> {
    pub fn new(store: &'a Store, rows: &[(bool, i64)], top: i64) -> Self {
        let mut m = Moments {
            store,
            top,
            rows: Vec::with_capacity(rows.len()),
            heap: BinaryHeap::with_capacity(rows.len()),
        };
        for &(is_edge, row) in rows {
            let life = m.life(is_edge, row);
            let c = Cursor {
                is_edge,
                row,
                closed: life.ranges.partition_point(|&(s, _)| s <= top),
                open: life.now.filter(|&s| s <= top),
                next: 0,
            };
            if let Some(t) = c.moment(life, top) {
                m.heap.push((t, m.rows.len()));
            }
            m.rows.push(c);
        }
        m
    }

    fn life(&self, is_edge: bool, row: i64) -> &'a Life {
        let store: &'a Store = self.store;
        if is_edge {
            store.edges.life(row)
        } else {
            store.consts.life(row)
        }
    }

    /// The newest moment not yet passed.
    pub fn peek(&self) -> Option<i64> {
        self.heap.peek().map(|&(t, _)| t)
    }

    /// Passes every moment at or after episode `t`, telling `m` which rows come and go.
    pub fn pass(&mut self, t: i64, m: &mut Matches) {
        while let Some(&(at, k)) = self.heap.peek() {
            if at < t {
                break;
            }
            self.heap.pop();
            let c = &mut self.rows[k];
            // A row's moments alternate: a range's end (walking back, the row comes), then
            // the episode before its start (it goes). Two ranges that touch give a going and
            // a coming at one moment, passed in that order.
            let comes = c.next.is_multiple_of(2);
            c.next += 1;
            let (is_edge, row) = (c.is_edge, c.row);
            let life = self.life(is_edge, row);
            if let Some(next) = self.rows[k].moment(life, self.top) {
                self.heap.push((next, k));
            }
            m.set_row(is_edge, row, comes);
        }
    }
}
