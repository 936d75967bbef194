//! The right index: for each identifier, the alpha memories that hold WMEs with it, and the
//! head of each one's list of those WMEs. A join finds the WMEs of its alpha memory for one
//! identifier with an array index and a scan of a list that is nearly always short (an
//! identifier sits in few alpha memories), instead of hashing the pair.

use super::small_list::SmallList;
use super::AmemId;
use crate::symbols::Sym;

#[derive(Debug, Default)]
pub(crate) struct IdIndex {
    /// By the identifier's symbol number: (alpha memory, head entry).
    by_id: Vec<SmallList<(AmemId, u32)>>,
    /// How many (alpha memory, identifier) pairs are held.
    len: usize,
}

impl IdIndex {
    /// The head entry of alpha memory `a`'s WMEs with identifier `id`.
    #[inline]
    pub(crate) fn get(&self, a: AmemId, id: Sym) -> Option<u32> {
        let list = self.by_id.get(id.0 as usize)?;
        list.as_slice()
            .iter()
            .find(|(m, _)| *m == a)
            .map(|&(_, e)| e)
    }

    /// Makes `e` the head for `(a, id)`; returns the previous head.
    pub(crate) fn insert(&mut self, a: AmemId, id: Sym, e: u32) -> Option<u32> {
        let slot = id.0 as usize;
        if self.by_id.len() <= slot {
            self.by_id.resize_with(slot + 1, SmallList::default);
        }
        let list = &mut self.by_id[slot];
        if let Some(p) = list.as_mut_slice().iter_mut().find(|(m, _)| *m == a) {
            return Some(std::mem::replace(&mut p.1, e));
        }
        list.push((a, e));
        self.len += 1;
        None
    }

    /// Forgets the pair `(a, id)`.
    pub(crate) fn remove(&mut self, a: AmemId, id: Sym) {
        let Some(list) = self.by_id.get_mut(id.0 as usize) else {
            return;
        };
        if let Some(i) = list.as_slice().iter().position(|(m, _)| *m == a) {
            list.remove(i);
            self.len -= 1;
        }
    }

    /// The bytes it takes, for `stats --memory`.
    pub(crate) fn bytes(&self) -> usize {
        self.by_id.capacity() * std::mem::size_of::<SmallList<(AmemId, u32)>>()
            + self.len * std::mem::size_of::<(AmemId, u32)>()
    }
}
