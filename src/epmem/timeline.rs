//! Which rows were in a given episode, without looking at every row: rebuilding or printing
//! an episode costs the rows it holds, not the rows the store has. A closed range of
//! episodes is filed under the few aligned power-of-two blocks that tile it (a segment tree
//! over episode numbers, kept sparse in a hash map); an episode lies in one block per size,
//! so its rows are those of its blocks plus the open ranges that started at or before it.

use rustc_hash::FxHashMap;

/// The rows of each episode, by range.
#[derive(Debug, Default)]
pub struct Timeline {
    /// Rows by block: `(size exponent, episode >> exponent)`.
    blocks: FxHashMap<(u32, i64), Vec<i64>>,
    /// The largest exponent filed, so that a lookup tries only the sizes in use.
    top_exponent: u32,
    /// Rows in working memory, with the start of their open range.
    open: FxHashMap<i64, i64>,
}

impl Timeline {
    /// Row `id` is in every episode from `start` on, until it is closed.
    pub fn open(&mut self, id: i64, start: i64) {
        self.open.insert(id, start);
    }

    /// Row `id`'s open range ends at `end` (inclusive).
    pub fn close(&mut self, id: i64, end: i64) {
        if let Some(start) = self.open.remove(&id) {
            self.file(id, start, end);
        }
    }

    /// Files the closed range `start..=end` of row `id` under the blocks that tile it.
    fn file(&mut self, id: i64, start: i64, end: i64) {
        let mut s = start.max(0);
        while s <= end {
            // The largest aligned block starting at `s` that stays within the range.
            let mut k = 0u32;
            while k < 62 {
                let size = 1i64 << (k + 1);
                if s % size != 0 || s + size - 1 > end {
                    break;
                }
                k += 1;
            }
            self.blocks.entry((k, s >> k)).or_default().push(id);
            self.top_exponent = self.top_exponent.max(k);
            s += 1i64 << k;
        }
    }

    /// The rows in episode `t`, in no particular order.
    pub fn at(&self, t: i64, out: &mut Vec<i64>) {
        if t < 0 {
            return;
        }
        for k in 0..=self.top_exponent {
            if let Some(rows) = self.blocks.get(&(k, t >> k)) {
                out.extend_from_slice(rows);
            }
        }
        out.extend(self.open.iter().filter(|&(_, &s)| s <= t).map(|(&id, _)| id));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_episode_finds_the_ranges_over_it() {
        let mut tl = Timeline::default();
        let ranges = [(1, (1, 2)), (1, (5, 5)), (2, (3, 17)), (3, (0, 64)), (4, (9, 9))];
        for (id, (s, e)) in ranges {
            tl.open(id, s);
            tl.close(id, e);
        }
        tl.open(5, 8);
        for t in 0..80 {
            let mut got = Vec::new();
            tl.at(t, &mut got);
            got.sort_unstable();
            let mut want: Vec<i64> = ranges
                .iter()
                .filter(|&&(_, (s, e))| s <= t && t <= e)
                .map(|&(id, _)| id)
                .chain((t >= 8).then_some(5))
                .collect();
            want.sort_unstable();
            assert_eq!(got, want, "episode {t}");
        }
    }
}
