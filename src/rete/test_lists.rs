//! The distinct lists of join tests, each stored once and named by an index: a join or
//! negative node keeps the index (4 bytes, where a shared pointer would take 16 and widen
//! every node), and the joins of 100,000 similar rules use a handful of lists.

use super::tests::JoinTest;
use rustc_hash::FxHashMap;

#[derive(Debug, Default)]
pub(crate) struct TestLists {
    /// Each list and the number of nodes using it (0: a free slot).
    lists: Vec<(Box<[JoinTest]>, u32)>,
    /// A list by the hash of its tests. Two lists with one hash (never seen in practice)
    /// are both kept; the second is found by a scan.
    by_hash: FxHashMap<u64, u32>,
    free: Vec<u32>,
}

impl TestLists {
    /// The index of the stored list equal to `tests`, if there is one.
    pub fn find(&self, tests: &[JoinTest]) -> Option<u32> {
        let in_use = |i: u32| self.lists[i as usize].1 > 0 && *self.lists[i as usize].0 == *tests;
        match self.by_hash.get(&hash(tests)) {
            Some(&i) if in_use(i) => Some(i),
            Some(_) => (0..self.lists.len() as u32).find(|&i| in_use(i)),
            None => None,
        }
    }

    /// The index of a list equal to `tests`, stored now if there is none; one more user.
    pub fn intern(&mut self, tests: &[JoinTest]) -> u32 {
        if let Some(i) = self.find(tests) {
            self.lists[i as usize].1 += 1;
            return i;
        }
        let entry = (Box::<[JoinTest]>::from(tests), 1);
        let i = super::alloc(&mut self.lists, &mut self.free, entry);
        self.by_hash.entry(hash(tests)).or_insert(i);
        i
    }

    pub fn get(&self, i: u32) -> &[JoinTest] {
        &self.lists[i as usize].0
    }

    /// One user fewer; a list no node uses is dropped.
    pub fn release(&mut self, i: u32) {
        let slot = &mut self.lists[i as usize];
        slot.1 -= 1;
        if slot.1 > 0 {
            return;
        }
        let tests = std::mem::take(&mut slot.0);
        let h = hash(&tests);
        if self.by_hash.get(&h) == Some(&i) {
            self.by_hash.remove(&h);
        }
        self.free.push(i);
    }
}

fn hash(tests: &[JoinTest]) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut h = rustc_hash::FxHasher::default();
    tests.hash(&mut h);
    h.finish()
}
