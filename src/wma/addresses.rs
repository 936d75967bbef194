//! The order of WMEs' memory addresses in 9.6, for the WMA trace's `activate` lines (9.6
//! keeps the referenced elements in a set of WME pointers and prints them in its order).
//!
//! 9.6 takes WMEs from a memory pool: a freed WME's place is the next one handed out (the
//! pool's free list is last in, first out), and fresh places come in rising order.
//! Timetags count WMEs in the order they are made, so replaying the agent's WME creations
//! and removals through such a free list gives each WME a place, and the places' order is
//! the addresses' order. The replay lets a WME go when it leaves working memory (a
//! working-memory phase's removals at the phase's end, in the order 9.6 lists them);
//! 9.6 lets some go later (while a substate's firing or an activation set still holds
//! them), and there the order can differ.

use rustc_hash::FxHashMap;

/// Each live WME's place in the simulated pool, by timetag.
#[derive(Debug, Clone, Default)]
pub(crate) struct AddressOrder {
    /// The next timetag to be given a place.
    next: u64,
    /// How many places fresh blocks have handed out.
    fresh: u64,
    /// Freed places, the next to hand out last.
    free: Vec<u64>,
    /// The places of the WMEs given one and not freed, by timetag.
    place: FxHashMap<u64, u64>,
}

impl AddressOrder {
    /// Gives places to the WMEs made before `timetag` (all of them, up to the one before it).
    fn place_before(&mut self, timetag: u64) {
        self.next = self.next.max(1);
        while self.next < timetag {
            let place = self.free.pop().unwrap_or_else(|| {
                self.fresh += 1;

                self.fresh
            });
            self.place.insert(self.next, place);
            self.next += 1;
        }
    }

    /// The WME `timetag` was freed while `next_timetag` was the next to be made.
    pub(crate) fn freed(&mut self, timetag: u64, next_timetag: u64) {
        self.place_before(next_timetag);
        if let Some(place) = self.place.remove(&timetag) {
            self.free.push(place);
        }
    }

    /// Sorts WMEs given by timetag (first of each pair) into their addresses' order,
    /// `next_timetag` being the next WME to be made.
    pub(crate) fn sort<T>(&mut self, items: &mut [(u64, T)], next_timetag: u64) {
        self.place_before(next_timetag);
        items.sort_by_key(|&(tt, _)| (self.place.get(&tt).copied().unwrap_or(u64::MAX), tt));
    }
}
