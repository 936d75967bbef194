//! A map keyed by (rule, token), stored at the token's id: a live token belongs to one
//! production node, hence to one rule, so a vector indexed by token id holds every entry and
//! a lookup is an index instead of a hash (several lookups per firing use it).

use crate::rete::{ProdId, TokId};

#[derive(Debug, Clone)]
pub struct ByToken<T: Copy> {
    slots: Vec<Option<(ProdId, T)>>,
}

impl<T: Copy> Default for ByToken<T> {
    fn default() -> Self {
        ByToken { slots: Vec::new() }
    }
}

impl<T: Copy> ByToken<T> {
    pub fn get(&self, &(p, t): &(ProdId, TokId)) -> Option<&T> {
        match self.slots.get(t.index()) {
            Some(Some((q, v))) if *q == p => Some(v),
            _ => None,
        }
    }

    pub fn contains_key(&self, k: &(ProdId, TokId)) -> bool {
        self.get(k).is_some()
    }

    /// Sets the entry; a stale entry of another rule on a reused token id is replaced.
    pub fn insert(&mut self, (p, t): (ProdId, TokId), v: T) -> Option<T> {
        let i = t.index();
        if self.slots.len() <= i {
            self.slots.resize(i + 1, None);
        }
        let old = self.slots[i].replace((p, v));
        old.filter(|(q, _)| *q == p).map(|(_, v)| v)
    }

    pub fn remove(&mut self, &(p, t): &(ProdId, TokId)) -> Option<T> {
        let slot = self.slots.get_mut(t.index())?;
        match slot {
            Some((q, _)) if *q == p => slot.take().map(|(_, v)| v),
            _ => None,
        }
    }

    pub fn clear(&mut self) {
        self.slots.clear();
    }
}
