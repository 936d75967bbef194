//! The relational interval tree under which 9.6 files each closed range of a row (Kriegel,
//! Pötke and Seidl, "Managing Intervals Efficiently in Object-Relational Databases", 2000).
//! rusoar answers queries from its own rows (`store.rs`), so the tree only decides the
//! `rit_id` of each range and the variables it keeps, that a file written here reads in
//! 9.6 as one 9.6 wrote.

use super::schema::OFFSET_INIT;

/// One tree's state (9.6 keeps one for constant rows and one for edge rows).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Tree {
    /// The lower end of the first range filed: every range is shifted by it.
    pub offset: i64,
    pub left_root: i64,
    pub right_root: i64,
    /// The least step at which a range forked below the root.
    pub min_step: i64,
}

impl Default for Tree {
    fn default() -> Self {
        Tree {
            offset: OFFSET_INIT,
            left_root: 0,
            right_root: 1,
            min_step: i64::MAX,
        }
    }
}

impl Tree {
    /// The four persistent variables, in their order in the file.
    pub fn vars(&self) -> [i64; 4] {
        [self.offset, self.left_root, self.right_root, self.min_step]
    }

    pub fn from_vars(v: [i64; 4]) -> Tree {
        Tree {
            offset: v[0],
            left_root: v[1],
            right_root: v[2],
            min_step: v[3],
        }
    }

    /// Files the range `[lower, upper]`: the node it forks at. The roots grow to cover it.
    pub fn insert(&mut self, lower: i64, upper: i64) -> i64 {
        if self.offset == OFFSET_INIT {
            self.offset = lower;
        }
        let l = lower - self.offset;
        let u = upper - self.offset;
        if u < 0 && l <= 2 * self.left_root {
            // 9.6 takes (−2)^⌊log₂(−l)⌋: the sign alternates with the power.
            let k = floor_log2(-l);
            self.left_root = if k.is_multiple_of(2) { 1 << k } else { -(1 << k) };
        }
        if l > 0 && u >= 2 * self.right_root {
            self.right_root = 1 << floor_log2(u);
        }
        let (node, step) = self.fork(l, u);
        if node != 0 && step < self.min_step {
            self.min_step = step;
        }
        node
    }

    /// The highest node inside `[l, u]` on the way down from the root, with the step at
    /// which the walk stopped (0 when it ran out of steps).
    fn fork(&self, l: i64, u: i64) -> (i64, i64) {
        let mut node = if u < 0 {
            self.left_root
        } else if l > 0 {
            self.right_root
        } else {
            0
        };
        let mut step = node.abs() / 2;
        while step >= 1 {
            if u < node {
                node -= step;
            } else if node < l {
                node += step;
            } else {
                break;
            }
            step /= 2;
        }
        (node, step)
    }
}

/// ⌊log₂ x⌋ for x ≥ 1.
fn floor_log2(x: i64) -> u32 {
    63 - x.max(1).leading_zeros()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_range_sets_the_offset_and_forks_at_the_root() {
        let mut t = Tree::default();
        assert_eq!(t.insert(3, 4), 0);
        assert_eq!(t.offset, 3);
        assert_eq!(t.right_root, 1);
        assert_eq!(t.min_step, i64::MAX);
    }

    #[test]
    fn later_ranges_grow_the_right_root_and_fork_below_it() {
        let mut t = Tree::default();
        t.insert(1, 2);
        // Shifted to [9, 12]: the right root becomes 8, and the walk goes 8 → 12, inside.
        let node = t.insert(10, 13);
        assert_eq!(t.right_root, 8);
        assert_eq!(node, 12);
        assert_eq!(t.min_step, 2);
    }
}
