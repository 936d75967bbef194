//! Garbage collection (Soar manual, chapter 2, "Working memory: The Current Situation": objects not
//! linked to a state are removed): after working memory changes, the identifiers that lost a
//! link are searched upward for a goal, and the structure below one that has none goes.

use super::scratch::{GcScratch, SearchFrame};
use super::state::PrefId;
use crate::agent::AgentCore;
use crate::symbols::Sym;
use crate::wm::WmeId;

impl AgentCore {
    /// A slot taken out with its object: its preferences are freed and its WMEs other
    /// than `keep` (which the caller removes in its own order) leave working memory.
    pub(super) fn discard_slot(&mut self, slot: super::slot::Slot, keep: WmeId) {
        for &pid in &slot.prefs {
            self.decider.free_pref(pid);
        }
        for sw in slot.wmes.values().rev() {
            if sw != keep {
                self.remove_wme(sw);
            }
        }
        self.decider.slots.recycle(slot);
    }

    /// A preference left its slot. 9.6 counts a preference's identifier value (and a
    /// binary preference's referent) as a link to that object, as it counts a WME's: the
    /// object may now be unlinked, and the first link to go places it in the collection
    /// order.
    pub(crate) fn pref_link_removed(&mut self, pid: PrefId) {
        self.decider.forget_pref_links(pid);
        let p = &self.decider.prefs[pid];
        let linked = [Some(p.value), p.referent];
        for s in linked.into_iter().flatten() {
            if self.symbols.is_id(s) {
                self.decider.gc_candidates.push(s);
            }
        }
    }

    /// Removes WMEs no longer linked to a goal or the io link. Only identifiers that lost a
    /// link can have become unlinked: each is searched upward for a goal, and the structure
    /// below one that has none goes (cycles included).
    pub(crate) fn collect_garbage(&mut self) {
        self.collect_garbage_traced_at(None);
    }

    /// Garbage collection with no goal left: everything the removed goals held goes
    /// (`init-soar`).
    pub(super) fn collect_all_garbage(&mut self) {
        self.collect_garbage_rooted(None, false);
    }

    /// Garbage collection; the preferences it takes with the slots of unlinked identifiers
    /// are traced as `- pref` lines (`trace -r`) at `at` in the output, where the phase's
    /// `=>WM:` lines start, as 9.6 prints them (checked on soar-sml 9.6.5: agent
    /// support-retraction, an operator elaboration's `^to` on an operator that went), or
    /// where the output is now. Returns how many bytes of text went in at `at`.
    pub(super) fn collect_garbage_traced_at(&mut self, at: Option<usize>) -> usize {
        self.collect_garbage_rooted(at, true)
    }

    /// [`Self::collect_garbage_traced_at`], the top state a root while `top_is_root`.
    fn collect_garbage_rooted(&mut self, at: Option<usize>, top_is_root: bool) -> usize {
        if self.decider.gc_candidates.is_empty() {
            // What was traced as gone is forgotten with each collection, also an empty one.
            self.decider.prefs_traced_gone.clear();
            self.decider.wmes_traced_gone.clear();
            return 0;
        }
        let traced_gone = std::mem::take(&mut self.decider.prefs_traced_gone);
        let wmes_traced = std::mem::take(&mut self.decider.wmes_traced_gone);
        let candidates = std::mem::take(&mut self.decider.gc_candidates);
        // The sets live between calls (emptied), so that a collection allocates nothing.
        let mut gc = std::mem::take(&mut self.decider.gc_scratch);
        gc.roots.extend(self.decider.goals.iter().map(|g| g.state));
        if top_is_root {
            gc.roots.insert(self.top.state);
        }
        let mut garbage: Vec<WmeId> = Vec::new();
        for &c in &candidates {
            if gc.dead.contains(&c) || !self.wm.has_wmes(c) || self.linked(c, &mut gc) {
                continue;
            }
            gc.stack.push(c);
            while let Some(x) = gc.stack.pop() {
                if !gc.dead.insert(x) {
                    continue;
                }
                for w in self.wm.of_id(x) {
                    garbage.push(w);
                    // Only values link: an identifier used as an attribute stays, as in 9.6.
                    if let Some(wme) = self.wm.get(w) {
                        self.follow_lost_link(wme.value, &mut gc);
                    }
                }
                // Its slots' preferences go with it, and the links they made.
                let slots = &self.decider.slots;
                let prefs = slots
                    .attrs_of(x)
                    .iter()
                    .filter_map(|&attr| slots.get(&(x, attr)))
                    .flat_map(|slot| slot.prefs.iter().copied());
                for pid in prefs {
                    let p = &self.decider.prefs[pid];
                    for v in [Some(p.value), p.referent].into_iter().flatten() {
                        self.follow_lost_link(v, &mut gc);
                    }
                }
            }
        }
        gc.clear();
        self.decider.gc_scratch = gc;
        if !garbage.is_empty() {
            garbage = self.removal_order(garbage, &candidates);
        }
        self.decider.gc_candidates = candidates;
        self.decider.gc_candidates.clear();
        if garbage.is_empty() {
            return 0;
        }
        // 9.6 lists the removals in the reverse of the order it collects them in; they
        // happen in that order here.
        let mut removed_lines = Vec::new();
        let mut unmatched = Vec::new();
        let mut pref_lines = String::new();
        for w in garbage {
            let Some(wme) = self.wm.get(w).copied() else {
                continue;
            };
            if let Some(slot) = self.decider.slots.remove(&(wme.id, wme.attr)) {
                if self.settings.trace.preferences {
                    // Newest first, as 9.6's list of a slot's preferences runs.
                    for &pid in slot.prefs.iter().rev() {
                        if traced_gone.contains(&pid) {
                            continue;
                        }
                        // The lines go in before text already written, so each starts a line.
                        self.write_pref_event(&mut pref_lines, true, false, pid);
                    }
                }
                // The slot's other WMEs are garbage too, and follow in the order above.
                for &pid in &slot.prefs {
                    self.decider.free_pref(pid);
                }
                self.decider.slots.recycle(slot);
            }
            if self.wm.get(w).is_some() {
                if !wmes_traced.contains(&wme.timetag) {
                    removed_lines.push(wme);
                }
                self.decider.collecting_garbage = true;
                self.remove_wme_leaving_matcher(w);
                self.decider.collecting_garbage = false;
                unmatched.push((w, wme.timetag));
            }
        }
        // The matcher hears of them in the order they are listed, 9.6's order.
        for &(w, timetag) in unmatched.iter().rev() {
            self.unmatch_wme(w, timetag);
        }
        let mut inserted = 0;
        if !pref_lines.is_empty() {
            match at.filter(|&a| a <= self.output.len() && self.output.is_char_boundary(a)) {
                Some(at) => {
                    self.output.insert_str(at, &pref_lines);
                    inserted = pref_lines.len();
                }
                None => {
                    self.fresh_line();
                    self.output.push_str(&pref_lines);
                }
            }
        }
        for wme in removed_lines.iter().rev() {
            self.trace_wme(false, wme);
        }
        // What these removals point at was all collected above.
        self.decider.gc_candidates.clear();
        inserted
    }

    /// The order 9.6 collects unlinked WMEs in: an object's links are counted, and an
    /// object whose last link goes is collected next (the last one to lose its last link
    /// first), starting with the objects the phase's changes unlinked (in the order the
    /// trace lists the changes). An object gives up its WMEs without a slot first, then
    /// its slots newest first (9.6 puts a new slot at the head of its object's list),
    /// each slot's WMEs newest first. What that walk cannot reach (a cycle whose
    /// links never all go) follows, oldest first.
    fn removal_order(&self, garbage: Vec<WmeId>, candidates: &[Sym]) -> Vec<WmeId> {
        use std::cmp::Reverse;
        // (object, attribute, timetag, WME, value), grouped by object, then by slot.
        let mut rows: Vec<(Sym, Sym, u64, WmeId, Sym)> = garbage
            .iter()
            .filter_map(|&w| {
                let x = self.wm.get(w)?;
                Some((x.id, x.attr, x.timetag, w, x.value))
            })
            .collect();
        rows.sort_unstable_by_key(|r| (r.0, r.1, r.2));
        if let Some(order) = self.lone_object_order(&rows, candidates) {
            return order;
        }
        // Each object's rows: (object, start, end).
        let mut objects: Vec<(Sym, usize, usize)> = Vec::new();
        for (i, r) in rows.iter().enumerate() {
            match objects.last_mut() {
                Some(o) if o.0 == r.0 => o.2 = i + 1,
                _ => objects.push((r.0, i, i + 1)),
            }
        }
        let find = |s: Sym| objects.binary_search_by_key(&s, |o| o.0).ok();
        // The links to each collected object from collected WMEs.
        let mut links = vec![0u32; objects.len()];
        for r in &rows {
            if let Some(k) = find(r.4) {
                links[k] += 1;
            }
        }
        // The first unlinked by the phase on top: 9.6 notes an object when the first of
        // its links (a WME or a preference) goes, and collects the objects it noted in
        // that order.
        let mut named = vec![false; objects.len()];
        let mut stack: Vec<usize> = candidates
            .iter()
            .filter_map(|&c| find(c))
            .filter(|&k| !std::mem::replace(&mut named[k], true))
            .filter(|&k| links[k] == 0)
            .collect();
        stack.reverse();
        let mut done = vec![false; objects.len()];
        let mut order = Vec::with_capacity(rows.len());
        let mut slot_rows: Vec<(u64, Reverse<u64>, WmeId, Sym)> = Vec::new();
        while let Some(k) = stack.pop() {
            if std::mem::replace(&mut done[k], true) {
                continue;
            }
            // In 9.6's order for the object's WMEs.
            let (object, start, end) = objects[k];
            let slots = self.decider.slots.attrs_of(object);
            slot_rows.clear();
            for r in &rows[start..end] {
                slot_rows.push((collection_rank(slots, r.1), Reverse(r.2), r.3, r.4));
            }
            slot_rows.sort_unstable();
            for &(_, _, w, value) in &slot_rows {
                order.push(w);
                if let Some(v) = find(value) {
                    links[v] = links[v].saturating_sub(1);
                    if links[v] == 0 && !done[v] {
                        stack.push(v);
                    }
                }
            }
        }
        if order.len() < rows.len() {
            let mut rest: Vec<(u64, WmeId)> = objects
                .iter()
                .zip(&done)
                .filter(|(_, &d)| !d)
                .flat_map(|(o, _)| rows[o.1..o.2].iter().map(|r| (r.2, r.3)))
                .collect();
            rest.sort_unstable();
            order.extend(rest.into_iter().map(|(_, w)| w));
        }
        order
    }

    /// [`Self::removal_order`] of the garbage of one object the phase unlinked, that
    /// points at nothing else collected (an operator's attributes, a memory's command
    /// link): the object's WMEs in collection order, without the general walk's tables.
    /// `None` when the garbage is not of that shape. `rows` are sorted by object.
    fn lone_object_order(
        &self,
        rows: &[(Sym, Sym, u64, WmeId, Sym)],
        candidates: &[Sym],
    ) -> Option<Vec<WmeId>> {
        let object = rows.first()?.0;
        let lone = rows.last()?.0 == object
            && candidates.contains(&object)
            && rows.iter().all(|r| r.4 != object);
        if !lone {
            return None;
        }
        let slots = self.decider.slots.attrs_of(object);
        let mut ranked: Vec<(u64, std::cmp::Reverse<u64>, WmeId)> = rows
            .iter()
            .map(|r| (collection_rank(slots, r.1), std::cmp::Reverse(r.2), r.3))
            .collect();
        ranked.sort_unstable();
        Some(ranked.into_iter().map(|r| r.2).collect())
    }

    /// The WMEs of `object` in the order 9.6's garbage collection removes them (see
    /// [`collection_rank`]).
    pub(super) fn object_in_collection_order(&self, object: Sym) -> Vec<crate::wm::Wme> {
        let slots = self.decider.slots.attrs_of(object);
        let mut wmes: Vec<crate::wm::Wme> =
            self.wm.of_id(object).filter_map(|w| self.wm.get(w).copied()).collect();
        wmes.sort_by_key(|w| (collection_rank(slots, w.attr), std::cmp::Reverse(w.timetag)));
        wmes
    }

    /// A garbage object linked to `v`: when `v` is an identifier no goal reaches any more,
    /// it is garbage too.
    fn follow_lost_link(&self, v: Sym, gc: &mut GcScratch) {
        if self.symbols.is_id(v) && !gc.dead.contains(&v) && !self.linked(v, gc) {
            gc.stack.push(v);
        }
    }

    /// Is `x` reachable from a goal? An upward search through the WMEs that point at it; a
    /// search that finds no goal proves everything it visited unlinked.
    fn linked(&self, x: Sym, gc: &mut GcScratch) -> bool {
        if let Some(&b) = gc.memo.get(&x) {
            return b;
        }
        if gc.roots.contains(&x) {
            gc.memo.insert(x, true);
            return true;
        }
        // Depth first, each object's parents in the order they linked: a wall pointed at
        // by hundreds of comparison objects is found linked through the map it was made
        // in, without a look at the others. A search that goes deep is made again with
        // each object's few parents tried oldest object first: structure grows outward
        // from the states, so an older object is nearer one, and a chain of thousands of
        // items whose newest was also put in the store is found linked through the store,
        // not through the whole chain.
        let found = match self.upward_search(x, gc, false) {
            Some(found) => found,
            None => self
                .upward_search(x, gc, true)
                .expect("an uncapped search ends"),
        };
        if found {
            // Everything on the path hangs off the root found.
            for frame in &gc.path {
                gc.memo.insert(frame.node, true);
            }
        } else {
            for &v in &gc.visited {
                gc.memo.insert(v, false);
            }
        }
        found
    }

    /// [`Self::linked`]'s search from `x`, leaving its path (to the root found) and what
    /// it visited in `gc`. In link order it gives up past [`SHALLOW_SEARCH`] steps (`None`);
    /// oldest first, it does not.
    fn upward_search(&self, x: Sym, gc: &mut GcScratch, oldest_first: bool) -> Option<bool> {
        gc.visited.clear();
        gc.path.clear();
        gc.parents.clear();
        gc.visited.insert(x);
        let first = self.search_frame(x, &mut gc.parents, oldest_first);
        gc.path.push(first);
        while let Some(&frame) = gc.path.last() {
            let by_wmes = if frame.in_place {
                self.wm.parent_wmes(frame.node)
            } else {
                &[]
            };
            let mut up = None;
            for i in frame.next..frame.end {
                let p = if !frame.in_place {
                    gc.parents[i]
                } else if let Some(&w) = by_wmes.get(i) {
                    match self.wm.get(w) {
                        Some(wme) => wme.id,
                        None => continue,
                    }
                } else {
                    // Past the last preference: no more parents.
                    match self.decider.pref_link_parent(frame.node, i - by_wmes.len()) {
                        Some(p) => p,
                        None => break,
                    }
                };
                match gc.memo.get(&p) {
                    Some(true) => return Some(true),
                    Some(false) => continue,
                    None => {}
                }
                if gc.roots.contains(&p) {
                    return Some(true);
                }
                if gc.visited.insert(p) {
                    up = Some((i, p));
                    break;
                }
            }
            match up {
                Some((i, p)) => {
                    if !oldest_first && gc.path.len() >= SHALLOW_SEARCH {
                        return None;
                    }
                    if let Some(top) = gc.path.last_mut() {
                        top.next = i + 1;
                    }
                    let frame = self.search_frame(p, &mut gc.parents, oldest_first);
                    gc.path.push(frame);
                }
                None => {
                    // Its parents all tried: their list goes with it.
                    if let Some(done) = gc.path.pop() {
                        gc.parents.truncate(done.start);
                    }
                }
            }
        }
        Some(false)
    }

    /// The upward search's step to `y`: its parents read in place, or, `oldest_first`
    /// when they are few, listed at the end of `parents`, oldest object first.
    fn search_frame(&self, y: Sym, parents: &mut Vec<Sym>, oldest_first: bool) -> SearchFrame {
        let start = parents.len();
        let in_place = SearchFrame {
            node: y,
            next: 0,
            // (Read until its lists end.)
            end: usize::MAX,
            start,
            in_place: true,
        };
        if !oldest_first {
            return in_place;
        }
        let by_wmes = self.wm.parent_wmes(y);
        let by_prefs = self.decider.pref_link_parents(y);
        const LISTED: usize = 16;
        if !(2..=LISTED).contains(&(by_wmes.len() + by_prefs.len())) {
            return in_place;
        }
        parents.extend(by_wmes.iter().filter_map(|&w| self.wm.get(w).map(|wme| wme.id)));
        parents.extend(by_prefs.iter().map(|&pid| self.decider.prefs[pid].id));
        parents[start..].sort_unstable();
        SearchFrame {
            node: y,
            next: start,
            end: parents.len(),
            start,
            in_place: false,
        }
    }
}

/// How deep [`AgentCore::linked`]'s first search goes before it starts again oldest
/// object first.
const SHALLOW_SEARCH: usize = 32;


/// Where an object's WME with attribute `attr` goes when 9.6's garbage collection takes the
/// object (`slots`: the object's slot attributes, oldest first): the WMEs without a slot
/// (input and architecture WMEs) first, as 9.6 keeps its input WMEs, then the slots newest
/// first (9.6 puts a new slot at the head of its object's list); a slot's WMEs go newest
/// first.
fn collection_rank(slots: &[Sym], attr: Sym) -> u64 {
    match slots.iter().position(|&a| a == attr) {
        Some(i) => 1 + (slots.len() - i) as u64,
        None => 0,
    }
}
