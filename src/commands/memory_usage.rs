//! `production memory-usage` (alias `memories`; Soar manual, ch. 9, `production`): for each
//! rule, the partial matches its network holds, most first. 9.6 counts the tokens stored
//! on the rule's path through its rete: each condition's node keeps the matches of the
//! conditions before it, and the first keeps the network's one empty match; rusoar's
//! network has the same matches to count. Justifications are left out: rusoar keeps them
//! outside its network, and 9.6's count for them depends on its order of their conditions.

use super::{CmdResult, Ctx, Interpreter};
use crate::production::Production;

impl Interpreter {
    /// `production memory-usage [-c|-d|-j|-T|-u]... [N | RULE]`.
    pub(super) fn cmd_memory_usage(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let mut kinds = Vec::new();
        let mut rest = Vec::new();
        for a in args {
            match a.as_str() {
                "-c" | "--chunks" => kinds.push("chunks"),
                "-d" | "--default" => kinds.push("defaults"),
                "-j" | "--justifications" => kinds.push("justifications"),
                "-T" | "--template" => kinds.push("template"),
                "-u" | "--user" => kinds.push("user"),
                s if s.starts_with('-') && s.len() > 1 && s.parse::<i64>().is_err() => {
                    return Err(ctx.error(format!("Unknown option: {s}")))
                }
                _ => rest.push(a.as_str()),
            }
        }
        if rest.len() > 1 {
            return Err(ctx.error(
                "Syntax: memories [options] [number]\nmemories production_name",
            ));
        }
        let mut limit = 0usize;
        if let Some(word) = rest.first() {
            match word.parse::<i64>() {
                Ok(n) if n <= 0 => return Err(ctx.error("Expected positive integer.")),
                Ok(n) => limit = n as usize,
                Err(_) => {
                    if !kinds.is_empty() {
                        return Err(ctx.error(
                            "Do not specify production type when specifying a production name.",
                        ));
                    }
                    let Some(p) = self.agent.production(word) else {
                        return Err(ctx.error("Production not found."));
                    };
                    let count = self.tokens_held(p);
                    return Ok(format!("{count:>6}:  {word}\n"));
                }
            }
        }
        let live_justifications = !self.agent.learn.justifications.is_empty();
        if kinds == ["justifications"] && live_justifications {
            return Err(ctx.error(
                "production memory-usage: justifications are not counted by rusoar (they are kept outside its network)",
            ));
        }
        if kinds.is_empty() {
            kinds = vec!["defaults", "user", "chunks", "justifications", "template"];
        }
        // 9.6 goes through its rule kinds in its own order (user, default, chunk,
        // justification, template), each newest first, then lists them by count, most
        // first, the rest in the reverse of that order.
        let mut rows: Vec<(u64, String)> = Vec::new();
        for kind in ["user", "defaults", "chunks", "justifications", "template"] {
            if !kinds.contains(&kind) {
                continue;
            }
            let rules: Vec<&Production> = self
                .agent
                .productions()
                .rev()
                .filter(|p| p.kind_word() == kind)
                .collect();
            for p in rules {
                rows.push((self.tokens_held(p), p.name.to_string()));
            }
        }
        if rows.is_empty() {
            return Err(ctx.error("Production not found."));
        }
        cpp_sort_by_count(&mut rows);
        let shown = if limit == 0 { rows.len() } else { limit.min(rows.len()) };
        Ok(rows
            .iter()
            .rev()
            .take(shown)
            .map(|(n, name)| format!("{n:>6}:  {name}\n"))
            .collect())
    }

    /// The partial matches a rule's network holds (see [`crate::rete::Rete::tokens_held`]).
    fn tokens_held(&self, p: &Production) -> u64 {
        self.agent
            .loaded(&p.name)
            .map_or(0, |l| self.agent.rete.tokens_held(l.id, &self.agent.symbols))
    }
}


/// Sorts by count, fewest first, exactly as the C++ standard library 9.6 is built with
/// (libstdc++'s introsort: median-of-three quicksort down to runs of 16, then one
/// insertion sort), so that rules with equal counts come out in 9.6's order.
fn cpp_sort_by_count(rows: &mut [(u64, String)]) {
    let n = rows.len();
    if n < 2 {
        return;
    }
    let depth = 2 * (usize::BITS - 1 - n.leading_zeros()) as usize;
    introsort_loop(rows, 0, n, depth);
    final_insertion_sort(rows, 0, n);
}

const THRESHOLD: usize = 16;

fn less(rows: &[(u64, String)], a: usize, b: usize) -> bool {
    rows[a].0 < rows[b].0
}

fn introsort_loop(rows: &mut [(u64, String)], first: usize, mut last: usize, mut depth: usize) {
    while last - first > THRESHOLD {
        if depth == 0 {
            heap_sort(&mut rows[first..last]);
            return;
        }
        depth -= 1;
        let cut = partition_pivot(rows, first, last);
        introsort_loop(rows, cut, last, depth);
        last = cut;
    }
}

fn partition_pivot(rows: &mut [(u64, String)], first: usize, last: usize) -> usize {
    let mid = first + (last - first) / 2;
    move_median_to_first(rows, first, first + 1, mid, last - 1);
    // Hoare's partition around rows[first], with no bounds checks needed: the median
    // stops both scans.
    let (mut lo, mut hi) = (first + 1, last);
    loop {
        while less(rows, lo, first) {
            lo += 1;
        }
        hi -= 1;
        while less(rows, first, hi) {
            hi -= 1;
        }
        if lo >= hi {
            return lo;
        }
        rows.swap(lo, hi);
        lo += 1;
    }
}

fn move_median_to_first(rows: &mut [(u64, String)], result: usize, a: usize, b: usize, c: usize) {
    let pick = if less(rows, a, b) {
        if less(rows, b, c) {
            b
        } else if less(rows, a, c) {
            c
        } else {
            a
        }
    } else if less(rows, a, c) {
        a
    } else if less(rows, b, c) {
        c
    } else {
        b
    };
    rows.swap(result, pick);
}

fn final_insertion_sort(rows: &mut [(u64, String)], first: usize, last: usize) {
    if last - first > THRESHOLD {
        insertion_sort(rows, first, first + THRESHOLD);
        for i in first + THRESHOLD..last {
            linear_insert(rows, i);
        }
    } else {
        insertion_sort(rows, first, last);
    }
}

fn insertion_sort(rows: &mut [(u64, String)], first: usize, last: usize) {
    for i in first + 1..last {
        if less(rows, i, first) {
            rows[first..=i].rotate_right(1);
        } else {
            linear_insert(rows, i);
        }
    }
}

/// Moves `rows[i]` down past every larger row before it.
fn linear_insert(rows: &mut [(u64, String)], mut i: usize) {
    while i > 0 && rows[i].0 < rows[i - 1].0 {
        rows.swap(i, i - 1);
        i -= 1;
    }
}

/// The fallback of a quicksort gone too deep: libstdc++'s heap sort (a max-heap built
/// bottom up, then popped to the back).
fn heap_sort(rows: &mut [(u64, String)]) {
    let n = rows.len();
    for start in (0..n / 2).rev() {
        sift_down(rows, start, n);
    }
    for end in (1..n).rev() {
        rows.swap(0, end);
        sift_down(rows, 0, end);
    }
}

fn sift_down(rows: &mut [(u64, String)], mut root: usize, end: usize) {
    loop {
        let mut child = 2 * root + 1;
        if child >= end {
            return;
        }
        if child + 1 < end && rows[child].0 < rows[child + 1].0 {
            child += 1;
        }
        if rows[root].0 >= rows[child].0 {
            return;
        }
        rows.swap(root, child);
        root = child;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sort_orders_by_count_and_keeps_small_runs_stable() {
        let mut rows: Vec<(u64, String)> =
            [3, 1, 2, 1, 3].iter().enumerate().map(|(i, &c)| (c, i.to_string())).collect();
        cpp_sort_by_count(&mut rows);
        let order: Vec<&str> = rows.iter().map(|r| r.1.as_str()).collect();
        assert_eq!(order, ["1", "3", "2", "0", "4"]);
        let mut big: Vec<(u64, String)> =
            (0..200).map(|i| ((i * 7919 % 13) as u64, i.to_string())).collect();
        cpp_sort_by_count(&mut big);
        assert!(big.windows(2).all(|w| w[0].0 <= w[1].0));
    }
}
