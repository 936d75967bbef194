//! The RL trace (`rl --set trace on`, Soar manual, ch. 9, `rl`, "RL Trace"): for each
//! goal level, a tree of the operators proposed at each decision, with the chance the
//! exploration policy gave each. A goal walks down its level's tree: each decision with
//! RL learning on records its candidates as children of the goal's node and moves the
//! goal to the selected one's. `rl -t init` (and `init-soar`) sends every goal back to its
//! level's root, so episodes share a tree; `rl -t` prints one level for Graphviz's `dot`.

use std::collections::{BTreeMap, VecDeque};
use std::fmt::Write as _;

/// One candidate as a child of a node.
#[derive(Debug, Clone)]
struct Entry {
    /// The exploration policy's chance of the candidate when it was last recorded; NaN
    /// for a candidate without RL values (printed `-`).
    probability: f64,
    /// How many `rl -t init`s had happened when it was last recorded.
    init: u64,
    next: Option<usize>,
}

/// A node: its children by the candidate's description (`^name NAME` first, then its
/// other `^attr value` pairs in order).
#[derive(Debug, Clone, Default)]
struct Node {
    split: BTreeMap<Vec<String>, Entry>,
}

/// Every level's tree.
#[derive(Debug, Clone)]
pub struct RlTrace {
    /// Nodes of all trees; a cleared tree's nodes stay, unreachable.
    nodes: Vec<Node>,
    roots: BTreeMap<u32, usize>,
    /// The number of `rl -t init`s so far.
    pub init_count: u64,
}

impl Default for RlTrace {
    /// The top level's tree exists from the start, empty.
    fn default() -> Self {
        let mut t = RlTrace {
            nodes: Vec::new(),
            roots: BTreeMap::new(),
            init_count: 0,
        };
        t.root(1);
        t
    }
}

impl RlTrace {
    /// The root of a level's tree, made if it has none (a goal at that level starts there).
    pub fn root(&mut self, level: u32) -> usize {
        if let Some(&r) = self.roots.get(&level) {
            return r;
        }
        self.nodes.push(Node::default());
        let r = self.nodes.len() - 1;
        self.roots.insert(level, r);
        r
    }

    /// Records a decision at node `at`: each candidate (its description and chance) is a
    /// child; returns the selected candidate's node, the goal's next position.
    pub fn record(&mut self, at: usize, candidates: Vec<(Vec<String>, f64)>, chosen: usize) -> usize {
        let init = self.init_count;
        let mut chosen_key = None;
        for (i, (key, probability)) in candidates.into_iter().enumerate() {
            let e = self.nodes[at].split.entry(key.clone()).or_insert(Entry {
                probability,
                init,
                next: None,
            });
            e.probability = probability;
            e.init = init;
            if i == chosen {
                chosen_key = Some(key);
            }
        }
        let Some(key) = chosen_key else {
            return at;
        };
        if let Some(next) = self.nodes[at].split[&key].next {
            return next;
        }
        self.nodes.push(Node::default());
        let next = self.nodes.len() - 1;
        if let Some(e) = self.nodes[at].split.get_mut(&key) {
            e.next = Some(next);
        }
        next
    }

    /// `rl -t clear [LEVEL]`: forgets one level's tree, or all.
    pub fn clear(&mut self, level: Option<u32>) {
        match level {
            Some(l) => {
                self.roots.remove(&l);
            }
            None => self.roots.clear(),
        }
    }

    /// A level's tree in `dot`'s language, breadth first, children in order; `None` when
    /// the level has no tree.
    pub fn dot(&self, level: u32) -> Option<String> {
        let root = *self.roots.get(&level)?;
        let mut out = String::from("digraph RL_Trace {\n");
        let mut queue = VecDeque::from([(root, "0".to_string())]);
        let mut count = 1u64;
        while let Some((node, parent)) = queue.pop_front() {
            for (key, e) in &self.nodes[node].split {
                let label = count.to_string();
                count += 1;
                let _ = writeln!(out, "  {label}");
                let _ = write!(out, "  {parent} -> {label} [label=\"");
                for part in key {
                    let _ = write!(out, "{part}\\n");
                }
                if e.probability.is_nan() {
                    out.push('-');
                } else {
                    out.push_str(&crate::printer::constants::c_general(e.probability, 6));
                }
                let _ = writeln!(out, " ({})\"];", e.init);
                if let Some(next) = e.next {
                    queue.push_back((next, label));
                }
            }
        }
        out.push_str("}\n");
        Some(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(parts: &[&str]) -> Vec<String> {
        parts.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn a_decision_adds_children_and_moves_to_the_chosen_one() {
        let mut t = RlTrace::default();
        let root = t.root(1);
        let at = t.record(
            root,
            vec![(key(&["^name b"]), 0.25), (key(&["^name a"]), f64::NAN)],
            0,
        );
        t.record(at, vec![(key(&["^name c"]), 1.0)], 0);
        assert_eq!(
            t.dot(1).unwrap(),
            "digraph RL_Trace {\n  1\n  0 -> 1 [label=\"^name a\\n- (0)\"];\n  2\n  0 -> 2 [label=\"^name b\\n0.25 (0)\"];\n  3\n  2 -> 3 [label=\"^name c\\n1 (0)\"];\n}\n"
        );
    }

    #[test]
    fn cleared_levels_print_nothing_and_start_again() {
        let mut t = RlTrace::default();
        assert_eq!(t.dot(1).unwrap(), "digraph RL_Trace {\n}\n");
        assert!(t.dot(2).is_none());
        t.clear(None);
        assert!(t.dot(1).is_none());
        t.root(1);
        assert_eq!(t.dot(1).unwrap(), "digraph RL_Trace {\n}\n");
    }
}
