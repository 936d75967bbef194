//! Working memory (Soar manual, ch. 3, "Working Memory"): WMEs with timetags, indexed by
//! identifier for printing and garbage collection. Acceptable-preference WMEs
//! (`(S1 ^operator O1 +)`) carry a flag.

use crate::symbols::Sym;
use rustc_hash::FxHashMap;

/// A working-memory element's handle (reused after removal).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct WmeId(pub u32);

/// A working-memory element: `(id ^attr value)`, with its timetag (Soar manual,
/// chapter 2, "Working Memory").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Wme {
    /// The identifier it hangs from.
    pub id: Sym,
    /// The attribute.
    pub attr: Sym,
    /// The value.
    pub value: Sym,
    /// An acceptable-preference WME (`^operator <o> +`), not a plain one.
    pub acceptable: bool,
    /// Its timetag: the order in which WMEs were added.
    pub timetag: u64,
}

/// An identifier's WMEs, oldest first; a removed WME leaves a gap (`GONE`) until gaps are
/// the majority, so that removal keeps the order and costs constant time however many
/// WMEs one identifier has.
#[derive(Debug, Default)]
struct IdList {
    items: Vec<WmeId>,
    live: u32,
}

const GONE: WmeId = WmeId(u32::MAX);

/// `link_pos` of a WME not in a `parents` list (its value or attribute is a constant).
const NOT_LINKED: u32 = u32::MAX;

#[derive(Debug)]
pub struct WorkingMemory {
    wmes: Vec<Option<Wme>>,
    free: Vec<u32>,
    next_timetag: u64,
    by_id: FxHashMap<Sym, IdList>,
    /// Each WME's place in its identifier's list.
    id_pos: Vec<u32>,
    count: usize,
    additions: u64,
    removals: u64,
    /// The WMEs whose value is a symbol, for garbage collection's upward search; `link_pos`
    /// is each WME's place in those lists. An identifier used as an attribute is not linked
    /// by it: 9.6 counts links only from values, so an object named only as an attribute
    /// stays when the WME goes (checked with soar_sml 9.6.5).
    parents: FxHashMap<Sym, Vec<WmeId>>,
    link_pos: Vec<u32>,
    /// Emptied lists, kept for their room: identifiers come and go with every firing.
    spare_id_lists: Vec<Vec<WmeId>>,
    spare_parent_lists: Vec<Vec<WmeId>>,
    /// A bit per symbol: whether a WME has ever pointed at it. Garbage collection searches
    /// only identifiers that lose a link, so one no WME ever pointed at (the object of an
    /// action whose link to it failed) stays, as in 9.6; the invariant checker tells
    /// those from objects collection missed by this.
    pointed_at: Vec<u64>,
    /// A bit per symbol: whether an action that would have linked it failed (its
    /// identifier was a constant). Such an object stays unlinked, as in 9.6, with whatever
    /// it links, even when a WME of its own structure points back at it.
    failed_link: Vec<u64>,
    /// While episodic memory keeps its record of working memory, every addition and removal
    /// in order (`true` for an addition), for it to read at its next episode.
    journal: Option<Vec<(bool, Wme)>>,
}

/// At most this many emptied lists of each kind are kept.
const SPARE_LISTS: usize = 4096;

impl Default for WorkingMemory {
    fn default() -> Self {
        Self::new()
    }
}

impl WorkingMemory {
    pub fn new() -> Self {
        WorkingMemory {
            wmes: Vec::new(),
            free: Vec::new(),
            next_timetag: 1,
            by_id: FxHashMap::default(),
            id_pos: Vec::new(),
            count: 0,
            additions: 0,
            removals: 0,
            parents: FxHashMap::default(),
            link_pos: Vec::new(),
            spare_id_lists: Vec::new(),
            spare_parent_lists: Vec::new(),
            pointed_at: Vec::new(),
            failed_link: Vec::new(),
            journal: None,
        }
    }

    /// Starts (or stops) keeping the journal of changes episodic memory reads.
    pub(crate) fn keep_journal(&mut self, on: bool) {
        self.journal = on.then(Vec::new);
    }

    /// The changes since the journal was last taken (none when it is not kept).
    pub(crate) fn take_journal(&mut self) -> Vec<(bool, Wme)> {
        match self.journal.as_mut() {
            Some(j) => std::mem::take(j),
            None => Vec::new(),
        }
    }

    /// Adds a WME with the next timetag (one global counter; Soar manual, ch. 3, "Timetags").
    pub fn add(&mut self, id: Sym, attr: Sym, value: Sym, acceptable: bool) -> WmeId {
        self.add_typed(id, attr, value, acceptable, true)
    }

    /// [`WorkingMemory::add`], told whether the value is an identifier: only identifiers
    /// are searched upward by garbage collection, so a constant needs no list of the WMEs
    /// that point at it (most WMEs have constant values).
    pub fn add_typed(
        &mut self,
        id: Sym,
        attr: Sym,
        value: Sym,
        acceptable: bool,
        value_is_id: bool,
    ) -> WmeId {
        let timetag = self.next_timetag;
        self.next_timetag += 1;
        let wme = Wme {
            id,
            attr,
            value,
            acceptable,
            timetag,
        };
        let w = match self.free.pop() {
            Some(i) => {
                self.wmes[i as usize] = Some(wme);
                WmeId(i)
            }
            None => {
                self.wmes.push(Some(wme));
                WmeId((self.wmes.len() - 1) as u32)
            }
        };
        let spare = &mut self.spare_id_lists;
        let list = self.by_id.entry(id).or_insert_with(|| IdList {
            items: spare.pop().unwrap_or_default(),
            live: 0,
        });
        if self.id_pos.len() <= w.0 as usize {
            self.id_pos.resize(w.0 as usize + 1, 0);
        }
        self.id_pos[w.0 as usize] = list.items.len() as u32;
        list.items.push(w);
        list.live += 1;
        self.count += 1;
        self.additions += 1;
        if self.link_pos.len() <= w.0 as usize {
            self.link_pos.resize(w.0 as usize + 1, NOT_LINKED);
        }
        if value_is_id {
            set_bit(&mut self.pointed_at, value);
            let spare = &mut self.spare_parent_lists;
            let list = self
                .parents
                .entry(value)
                .or_insert_with(|| spare.pop().unwrap_or_default());
            self.link_pos[w.0 as usize] = list.len() as u32;
            list.push(w);
        } else {
            self.link_pos[w.0 as usize] = NOT_LINKED;
        }
        if let Some(j) = self.journal.as_mut() {
            j.push((true, wme));
        }
        w
    }

    fn unlink(&mut self, w: WmeId, target: Sym) {
        let pos = self.link_pos[w.0 as usize];
        if pos == NOT_LINKED {
            return;
        }
        let pos = pos as usize;
        let Some(list) = self.parents.get_mut(&target) else {
            return;
        };
        list.swap_remove(pos);
        if let Some(&moved) = list.get(pos) {
            self.link_pos[moved.0 as usize] = pos as u32;
        }
        if list.is_empty() {
            if let Some(list) = self.parents.remove(&target) {
                if self.spare_parent_lists.len() < SPARE_LISTS {
                    self.spare_parent_lists.push(list);
                }
            }
        }
    }

    /// The WMEs whose value is the identifier `x`, in any order (removed ones included:
    /// check with `get`); a constant has none listed when its WMEs were added with
    /// [`WorkingMemory::add_typed`].
    pub fn parent_wmes(&self, x: Sym) -> &[WmeId] {
        self.parents.get(&x).map_or(&[], Vec::as_slice)
    }

    pub fn remove(&mut self, w: WmeId) -> Option<Wme> {
        let wme = self.wmes.get_mut(w.0 as usize)?.take()?;
        if let Some(list) = self.by_id.get_mut(&wme.id) {
            let pos = self.id_pos[w.0 as usize] as usize;
            if list.items.get(pos) == Some(&w) {
                list.items[pos] = GONE;
                list.live -= 1;
            }
            if list.live == 0 {
                if let Some(mut list) = self.by_id.remove(&wme.id) {
                    if self.spare_id_lists.len() < SPARE_LISTS {
                        list.items.clear();
                        self.spare_id_lists.push(list.items);
                    }
                }
            } else if list.items.len() > 8 && list.items.len() > 2 * list.live as usize {
                // Mostly gaps: close them (amortised constant time per removal).
                list.items.retain(|x| *x != GONE);
                for (i, x) in list.items.iter().enumerate() {
                    self.id_pos[x.0 as usize] = i as u32;
                }
            }
        }
        self.unlink(w, wme.value);
        if let Some(j) = self.journal.as_mut() {
            j.push((false, wme));
        }
        self.free.push(w.0);
        self.count -= 1;
        self.removals += 1;
        Some(wme)
    }

    pub fn get(&self, w: WmeId) -> Option<&Wme> {
        self.wmes.get(w.0 as usize).and_then(|x| x.as_ref())
    }

    /// The WME with timetag `tt` (a scan: only commands ask, and keeping an index would
    /// cost every WME change a hash insert and remove).
    /// The timetag the next WME will get.
    pub fn next_timetag(&self) -> u64 {
        self.next_timetag
    }

    pub fn by_timetag(&self, tt: u64) -> Option<WmeId> {
        self.wmes
            .iter()
            .position(|w| w.is_some_and(|w| w.timetag == tt))
            .map(|i| WmeId(i as u32))
    }

    /// The WMEs whose id is `id`, oldest first.
    pub fn of_id(&self, id: Sym) -> impl Iterator<Item = WmeId> + '_ {
        self.by_id
            .get(&id)
            .map_or(&[][..], |l| l.items.as_slice())
            .iter()
            .copied()
            .filter(|w| *w != GONE)
    }

    /// Whether `id` has any WMEs.
    pub fn has_wmes(&self, id: Sym) -> bool {
        self.by_id.contains_key(&id)
    }

    /// Every live WME, in timetag order.
    pub fn all(&self) -> Vec<WmeId> {
        let mut v: Vec<WmeId> = (0..self.wmes.len() as u32)
            .map(WmeId)
            .filter(|w| self.get(*w).is_some())
            .collect();
        v.sort_by_key(|w| self.get(*w).map(|x| x.timetag));
        v
    }

    /// How many WMEs have been removed so far (a cheap change counter).
    pub fn removals(&self) -> u64 {
        self.removals
    }

    /// How many WMEs have been added so far (timetags restart at init-soar; this does not).
    pub fn additions(&self) -> u64 {
        self.additions
    }

    /// The identifiers that have WMEs.
    pub fn ids(&self) -> impl Iterator<Item = Sym> + '_ {
        self.by_id.keys().copied()
    }

    pub(crate) fn len(&self) -> usize {
        self.count
    }

    /// Room for `items` more in the store `memory_pools` names `pool` (`debug allocate`);
    /// `None` for a name that is not working memory's.
    pub(crate) fn reserve_pool(
        &mut self,
        pool: &str,
        items: usize,
    ) -> Option<Result<(), std::collections::TryReserveError>> {
        Some(match pool {
            "wme" => self.wmes.try_reserve(items),
            "wme id place" => self.id_pos.try_reserve(items),
            "wme link place" => self.link_pos.try_reserve(items),
            _ => return None,
        })
    }

    /// Working memory's stores, for `stats --memory`, and the bytes of its hash tables.
    pub(crate) fn memory_pools(&self, pools: &mut Vec<crate::pools::Pool>) -> usize {
        use crate::pools::{hash_table_bytes, Pool};
        pools.push(Pool::of_vec::<Option<Wme>>("wme", self.wmes.capacity()));
        pools.push(Pool::of_vec::<u32>("wme id place", self.id_pos.capacity()));
        pools.push(Pool::of_vec::<u32>("wme link place", self.link_pos.capacity()));
        hash_table_bytes::<Sym, IdList>(self.by_id.capacity())
            + hash_table_bytes::<Sym, Vec<WmeId>>(self.parents.capacity())
    }

    /// Whether a WME has ever pointed at `x` (as its value or attribute).
    pub(crate) fn ever_pointed_at(&self, x: Sym) -> bool {
        bit_set(&self.pointed_at, x)
    }

    /// Notes that an action that would have linked identifier `x` failed.
    pub(crate) fn note_failed_link(&mut self, x: Sym) {
        set_bit(&mut self.failed_link, x);
    }

    /// Whether an action that would have linked `x` failed.
    pub(crate) fn had_failed_link(&self, x: Sym) -> bool {
        bit_set(&self.failed_link, x)
    }

    /// `init-soar`: timetags start again at 1, as in the official kernel.
    pub fn reset_timetags(&mut self) {
        self.next_timetag = 1;
    }
}

/// Sets symbol `x`'s bit in a bit per symbol, growing it as needed.
fn set_bit(bits: &mut Vec<u64>, x: Sym) {
    let word = x.0 as usize / 64;
    if bits.len() <= word {
        bits.resize(word + 1, 0);
    }
    bits[word] |= 1 << (x.0 % 64);
}

/// Whether symbol `x`'s bit is set in a bit per symbol.
fn bit_set(bits: &[u64], x: Sym) -> bool {
    bits.get(x.0 as usize / 64)
        .is_some_and(|word| word & (1 << (x.0 % 64)) != 0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn removing_wmes_of_one_id_keeps_the_order_of_the_rest() {
        let mut wm = WorkingMemory::new();
        let (id, attr) = (Sym(1), Sym(2));
        let ws: Vec<WmeId> = (0..40)
            .map(|i| wm.add(id, attr, Sym(100 + i), false))
            .collect();
        // Remove three in four, out of order: the gaps are closed on the way.
        for (i, w) in ws.iter().enumerate().rev() {
            if i % 4 != 0 {
                wm.remove(*w);
            }
        }
        let left: Vec<WmeId> = wm.of_id(id).collect();
        let want: Vec<WmeId> = ws.iter().copied().step_by(4).collect();
        assert_eq!(left, want);
        // New WMEs go after the old ones, and reused handles are found again.
        let w = wm.add(id, attr, Sym(999), false);
        assert_eq!(wm.of_id(id).last(), Some(w));
        for w in wm.of_id(id).collect::<Vec<_>>() {
            wm.remove(w);
        }
        assert!(!wm.has_wmes(id));
        assert_eq!(wm.of_id(id).count(), 0);
    }
}
