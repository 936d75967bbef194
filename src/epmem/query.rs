//! Cue-based retrieval (Soar manual, ch. 7, "Cue-Based Retrieval"; 9.6's
//! `epmem_process_query`). The cue becomes literals, one per cue WME: a leaf (a constant,
//! or an identifier with no WMEs) scores its weight in an episode when some path of the
//! episode reaches it; an inner literal only links its children, which must hang from the
//! node it matched (and an identifier reached by several cue WMEs must be the same node
//! from all of them). Episodes are walked from the newest back, one stretch at a time
//! between the moments a relevant row came or went (`walk.rs` keeps the literals' matches
//! up to date from one moment to the next); the best score wins, the newest on a tie, and a
//! stretch matching every positive leaf is graph-matched (all cue identifiers bound to one
//! node each at once): the first that passes ends the search.

use super::cue::{Cue, Literal};
use super::store::{Store, ACCEPTABLE};
use super::walk::{Matches, Moments};
use crate::agent::AgentCore;
use crate::symbols::Sym;
use rustc_hash::{FxHashMap, FxHashSet};
use std::collections::BTreeMap;

/// The answer to a query.
pub(crate) struct Found {
    pub episode: i64,
    pub score: f64,
    pub cardinality: i64,
    pub graph_matched: bool,
    /// For a graph match: each identifier literal's cue identifier and node, in the order
    /// of the literals.
    pub bindings: Vec<(Sym, i64)>,
    pub perfect_score: f64,
}

impl AgentCore {
    /// Builds the literals of a cue from working memory (9.6's `epmem_build_dnf`).
    pub(crate) fn epmem_cue(&mut self, pos: Sym, neg: Option<Sym>) -> Cue {
        let mut cue = Cue::default();
        cue.lits.push(Literal {
            id_sym: None,
            value_sym: pos,
            attr: None,
            constant: None,
            is_leaf: false,
            neg: false,
            weight: 0.0,
            children: Vec::new(),
            parents: Vec::new(),
        });
        cue.incoming.insert(pos, 1);
        let mut cache: FxHashMap<u64, usize> = FxHashMap::default();
        let mut visiting: FxHashSet<Sym> = [pos].into_iter().chain(neg).collect();
        for (root, is_neg) in [(Some(pos), false), (neg, true)] {
            let Some(root) = root else { continue };
            for w in self.epmem_augs_of(root) {
                if let Some(child) = self.epmem_literal(&w, is_neg, &mut cue, &mut cache, &mut visiting) {
                    cue.lits[child].id_sym = Some(pos);
                    cue.lits[child].parents.push(0);
                    cue.lits[0].children.push(child);
                }
            }
        }
        cue
    }

    fn epmem_literal(
        &mut self,
        w: &crate::wm::Wme,
        neg: bool,
        cue: &mut Cue,
        cache: &mut FxHashMap<u64, usize>,
        visiting: &mut FxHashSet<Sym>,
    ) -> Option<usize> {
        if visiting.contains(&w.value) {
            return None;
        }
        if let Some(&i) = cache.get(&w.timetag) {
            return Some(i);
        }
        let is_id = self.symbols.is_id(w.value);
        let mut children = Vec::new();
        let mut is_leaf = true;
        // The literal takes its place before its children (9.6 makes it first, and orders
        // literals by when they were made).
        let i = cue.lits.len();
        cue.lits.push(Literal {
            id_sym: Some(w.id),
            value_sym: w.value,
            attr: None,
            constant: None,
            is_leaf: true,
            neg,
            weight: 0.0,
            children: Vec::new(),
            parents: Vec::new(),
        });
        if is_id {
            let augs = self.epmem_augs_of(w.value);
            if !augs.is_empty() {
                is_leaf = false;
                let mut cycle = false;
                visiting.insert(w.value);
                for x in augs {
                    match self.epmem_literal(&x, neg, cue, cache, visiting) {
                        Some(c) => children.push(c),
                        None => cycle = true,
                    }
                }
                visiting.remove(&w.value);
                if cycle && children.is_empty() {
                    // Only cycles below: the literal is dropped (it is the last made).
                    cue.lits.truncate(i);
                    return None;
                }
                *cue.incoming.entry(w.value).or_insert(0) += 1;
            }
        }
        // Below `balance` 1 a cue WME weighs its activation (1 without one), 9.6's way of
        // preferring episodes that match what the agent attends to.
        let weight = if self.epmem.params.balance() >= 1.0 - 1.0e-8 {
            1.0
        } else {
            let d = self.decider.d_cycle_count;
            self.wma.activation(w.timetag, self.wma.clock(d))
        };
        let store = self.epmem.store.as_ref();
        let attr = if w.acceptable {
            Some(ACCEPTABLE)
        } else {
            store.and_then(|s| s.find_hash(&self.epmem_constant_of(w.attr)))
        };
        let constant = (!is_id).then(|| store.and_then(|s| s.find_hash(&self.epmem_constant_of(w.value))));
        if neg {
            cue.neg_literals += 1;
        } else {
            cue.pos_literals += 1;
        }
        if is_leaf {
            cue.leaves += 1;
        }
        for &c in &children {
            cue.lits[c].parents.push(i);
        }
        let l = &mut cue.lits[i];
        l.attr = attr;
        l.constant = constant;
        l.is_leaf = is_leaf;
        l.weight = if neg { -1.0 } else { 1.0 } * weight;
        l.children = children;
        cache.insert(w.timetag, i);
        Some(i)
    }

    /// Searches the episodes before `before` and after `after`, not prohibited, for the
    /// best match of the cue. Each time the best changes, `kings` gets whether it matches
    /// every positive leaf and whether it is graph-matched (what `trace --epmem` prints).
    pub(crate) fn epmem_search(
        &self,
        cue: &Cue,
        before: Option<i64>,
        after: Option<i64>,
        prohibit: &[i64],
        kings: &mut Vec<(bool, bool)>,
    ) -> Option<Found> {
        let store = self.epmem.store.as_ref()?;
        let graph_match = self.epmem.params.graph_match();
        let (perfect_score, perfect_card) = cue
            .lits
            .iter()
            .filter(|l| l.is_leaf && !l.neg)
            .fold((0.0, 0), |(s, c), l| (s + l.weight, c + 1));
        let top = before.map_or(store.time - 1, |b| b - 1);
        let after = after.unwrap_or(0);
        let rows = relevant_rows(store, cue);
        let mut moments = Moments::new(store, &rows, top);
        let mut matches = Matches::new(store, cue);
        let leaves: Vec<usize> = (0..cue.lits.len()).filter(|&i| cue.lits[i].is_leaf).collect();
        let mut prohibit: Vec<i64> = prohibit.to_vec();
        prohibit.sort_unstable();
        let mut best: Option<Found> = None;
        // Which leaves the stretch after this one satisfied: a stretch that satisfies the
        // same ones is not looked at (its newer twin already was).
        let mut previous: Vec<bool> = vec![false; leaves.len()];
        // Each stretch of episodes `lo + 1 ..= hi` has the same rows throughout.
        let mut next = top;
        while next > after {
            let hi = next;
            moments.pass(hi, &mut matches);
            let lo = moments.peek().unwrap_or(after).max(after);
            next = lo;
            let mut changed = false;
            let (mut score, mut cardinality) = (0.0, 0);
            for (k, &i) in leaves.iter().enumerate() {
                let sat = matches.satisfied(i);
                changed |= sat != previous[k];
                previous[k] = sat;
                if sat {
                    score += cue.lits[i].weight;
                    cardinality += if cue.lits[i].neg { -1 } else { 1 };
                }
            }
            let mut ep = hi;
            while ep > lo && prohibit.binary_search(&ep).is_ok() {
                ep -= 1;
            }
            if ep <= lo || !changed {
                continue;
            }
            let better = match &best {
                None => true,
                Some(b) => {
                    score > b.score
                        || (graph_match && score == b.score && !b.graph_matched)
                }
            };
            if !better {
                continue;
            }
            let crowned = best.as_ref().is_none_or(|b| score > b.score);
            if crowned {
                best = Some(Found {
                    episode: ep,
                    score,
                    cardinality,
                    graph_matched: false,
                    bindings: Vec::new(),
                    perfect_score,
                });
            }
            if cardinality == perfect_card {
                let bindings = if graph_match {
                    graph_match_bindings(cue, &matches.matches)
                } else {
                    Some(Vec::new())
                };
                if let (Some(bindings), Some(b)) = (bindings, best.as_mut()) {
                    b.episode = ep;
                    b.graph_matched = true;
                    b.bindings = bindings;
                    kings.push((true, true));
                    break;
                }
            }
            if crowned {
                kings.push((cardinality == perfect_card, false));
            }
        }
        best
    }

    fn epmem_constant_of(&self, s: Sym) -> super::store::Constant {
        use super::store::Constant;
        use crate::symbols::SymData;
        match self.symbols.get(s) {
            SymData::Str(x) => Constant::Str(x.to_string()),
            SymData::Int(i) => Constant::Int(*i),
            SymData::Float(f) => Constant::Float(f.to_bits()),
            SymData::Id(_) => Constant::Str(self.symbols.text(s)),
        }
    }
}

/// The rows that can match some literal: (is an edge, row).
fn relevant_rows(store: &Store, cue: &Cue) -> Vec<(bool, i64)> {
    let mut consts: FxHashSet<(i64, i64)> = FxHashSet::default();
    let mut edge_attrs: FxHashSet<i64> = FxHashSet::default();
    for l in cue.lits.iter().skip(1) {
        match (l.attr, l.constant) {
            (Some(a), Some(Some(v))) => {
                consts.insert((a, v));
            }
            (Some(a), None) => {
                edge_attrs.insert(a);
            }
            _ => {}
        }
    }
    let mut out = Vec::new();
    for key in consts {
        if let Some(rows) = store.consts.by_attr_value.get(&key) {
            out.extend(rows.iter().map(|&r| (false, r)));
        }
    }
    for a in edge_attrs {
        if let Some(rows) = store.edges.by_attr.get(&a) {
            out.extend(rows.iter().map(|&r| (true, r)));
        }
    }
    out
}

/// Binds every positive literal to one of its matches so that each cue identifier is one
/// node (9.6's `epmem_graph_match`, literals in the order they were made).
fn graph_match_bindings(cue: &Cue, matches: &[BTreeMap<(i64, i64), u32>]) -> Option<Vec<(Sym, i64)>> {
    let order: Vec<usize> = (1..cue.lits.len()).filter(|&i| !cue.lits[i].neg).collect();
    let mut bindings: BTreeMap<usize, (i64, i64)> = BTreeMap::new();
    let mut bound: [FxHashMap<i64, Sym>; 2] = [FxHashMap::default(), FxHashMap::default()];
    if !bind(cue, matches, &order, 0, &mut bindings, &mut bound) {
        return None;
    }
    Some(
        bindings
            .iter()
            .filter(|(&i, _)| cue.lits[i].constant.is_none())
            .map(|(&i, &(_, c))| (cue.lits[i].value_sym, c))
            .collect(),
    )
}

fn bind(
    cue: &Cue,
    matches: &[BTreeMap<(i64, i64), u32>],
    order: &[usize],
    at: usize,
    bindings: &mut BTreeMap<usize, (i64, i64)>,
    bound: &mut [FxHashMap<i64, Sym>; 2],
) -> bool {
    let Some(&i) = order.get(at) else {
        return true;
    };
    let l = &cue.lits[i];
    let kind = usize::from(l.constant.is_none());
    let mut failed_parents: FxHashSet<i64> = FxHashSet::default();
    for &(p, c) in matches[i].keys() {
        if failed_parents.contains(&p) {
            continue;
        }
        let parents_ok = l
            .parents
            .iter()
            .all(|j| bindings.get(j).is_none_or(|&(_, bc)| bc == p));
        if !parents_ok {
            failed_parents.insert(p);
            continue;
        }
        if bound[kind].get(&c).is_some_and(|&s| s != l.value_sym) {
            continue;
        }
        let children_ok = l
            .children
            .iter()
            .all(|j| bindings.get(j).is_none_or(|&(bp, _)| bp == c));
        if !children_ok {
            continue;
        }
        bindings.insert(i, (p, c));
        let before = bound[kind].insert(c, l.value_sym);
        if bind(cue, matches, order, at + 1, bindings, bound) {
            return true;
        }
        bindings.remove(&i);
        match before {
            Some(s) => bound[kind].insert(c, s),
            None => bound[kind].remove(&c),
        };
    }
    false
}
