//! Slots: the preferences for one (id, attr) and the WMEs they support.
//!
//! Most slots hold one or two values, and appear and go with every firing and retraction:
//! their lists are plain vectors searched in place, indexed by value only once a slot grows
//! large (one slot can hold thousands of values), and emptied slots are kept for reuse, so a
//! decision cycle allocates nothing for its slots once it is warm.

use super::ids::PrefId;
use crate::ids::id_type;
use crate::symbols::Sym;
use crate::wm::WmeId;
use rustc_hash::FxHashMap;

/// Above this many entries a slot's lists get a by-value index.
const SMALL: usize = 32;

/// All preferences for one (id, attr), oldest first (Soar's list read from its tail), and the
/// WMEs they support.
#[derive(Debug, Clone)]
pub struct Slot {
    /// Change it only through [`Slot::push`], [`Slot::remove`] and [`Slot::remove_value`],
    /// which keep `values` and `by_value` in step.
    pub prefs: Vec<PrefId>,
    /// The value of each preference of `prefs`, at the same position.
    values: Vec<Sym>,
    /// The same preferences by value, each list oldest first (large slots only).
    by_value: Option<FxHashMap<Sym, Vec<PrefId>>>,
    /// Value (and acceptable flag) to the WME that shows it.
    pub wmes: SlotWmes,
    /// Its (id, attr).
    pub key: (Sym, Sym),
    /// Large slots (with `by_value`): the values whose preferences came or went since the
    /// slot was last brought in line with working memory, so that one new value among
    /// thousands is decided alone (`update_slots`); `full` when they were not all noted.
    pub touched: Vec<Sym>,
    pub full: bool,
    /// Marked changed in this elaboration cycle (it is in `DecideState::changed`).
    pub changed: bool,
}

impl Default for Slot {
    fn default() -> Self {
        Slot {
            prefs: Vec::new(),
            values: Vec::new(),
            by_value: None,
            wmes: SlotWmes::default(),
            key: (Sym(u32::MAX), Sym(u32::MAX)),
            touched: Vec::new(),
            full: false,
            changed: false,
        }
    }
}

impl Slot {
    pub fn push(&mut self, pid: PrefId, value: Sym) {
        self.prefs.push(pid);
        self.values.push(value);
        match &mut self.by_value {
            Some(index) => {
                index.entry(value).or_default().push(pid);
                self.touched.push(value);
            }
            None if self.prefs.len() > SMALL => {
                let mut index: FxHashMap<Sym, Vec<PrefId>> = FxHashMap::default();
                for (&p, &v) in self.prefs.iter().zip(&self.values) {
                    index.entry(v).or_default().push(p);
                }
                self.by_value = Some(index);
                self.full = true;
            }
            None => {}
        }
    }

    /// Takes one preference out (the newest occurrence); false if it was not there.
    pub fn remove(&mut self, pid: PrefId, value: Sym) -> bool {
        let Some(pos) = self.prefs.iter().rposition(|x| *x == pid) else {
            return false;
        };
        self.prefs.remove(pos);
        self.values.remove(pos);
        if let Some(index) = &mut self.by_value {
            self.touched.push(value);
            if let Some(list) = index.get_mut(&value) {
                if let Some(i) = list.iter().rposition(|x| *x == pid) {
                    list.remove(i);
                }
                if list.is_empty() {
                    index.remove(&value);
                }
            }
        }
        true
    }

    /// Takes out every preference for `value`, appending them to `gone` oldest first.
    pub fn remove_value(&mut self, value: Sym, gone: &mut Vec<PrefId>) {
        let before = gone.len();
        match &mut self.by_value {
            Some(index) => {
                gone.extend(index.remove(&value).unwrap_or_default());
                self.touched.push(value);
            }
            None => gone.extend(self.prefs_for(value)),
        }
        if gone.len() > before {
            let mut keep = self.values.iter().map(|v| *v != value);
            self.prefs.retain(|_| keep.next().unwrap_or(true));
            self.values.retain(|v| *v != value);
        }
    }

    /// The preferences for one value, oldest first (the order of `prefs`).
    pub fn prefs_for(&self, value: Sym) -> PrefsFor<'_> {
        match &self.by_value {
            Some(index) => {
                let list: &[PrefId] = index.get(&value).map_or(&[], Vec::as_slice);
                PrefsFor::Indexed(list.iter())
            }
            None => PrefsFor::Scan(self.prefs.iter().zip(self.values.iter()), value),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.prefs.is_empty() && self.wmes.is_empty()
    }

    /// The value of each preference of `prefs`, at the same position.
    pub fn values(&self) -> &[Sym] {
        &self.values
    }

    /// Whether the touched values alone can bring the slot in line (see `touched`).
    pub fn only_touched_changed(&self) -> bool {
        self.by_value.is_some() && !self.full
    }

    /// Empties the slot, keeping its vectors' room for the next slot made.
    fn clear(&mut self) {
        self.prefs.clear();
        self.values.clear();
        self.by_value = None;
        self.wmes.clear();
        self.touched.clear();
        self.full = false;
        self.changed = false;
    }
}

/// The preferences of a slot for one value (see [`Slot::prefs_for`]).
pub enum PrefsFor<'a> {
    Indexed(std::slice::Iter<'a, PrefId>),
    Scan(
        std::iter::Zip<std::slice::Iter<'a, PrefId>, std::slice::Iter<'a, Sym>>,
        Sym,
    ),
}

impl Iterator for PrefsFor<'_> {
    type Item = PrefId;
    fn next(&mut self) -> Option<PrefId> {
        match self {
            PrefsFor::Indexed(it) => it.next().copied(),
            PrefsFor::Scan(it, value) => it.find(|(_, v)| **v == *value).map(|(p, _)| *p),
        }
    }
}

/// A slot's WMEs in the order they were added (Soar keeps them newest first: read them
/// with `.rev()`), found by value and acceptable flag.
#[derive(Debug, Clone, Default)]
pub struct SlotWmes {
    /// `None` marks an entry removed from a large slot (compacted when half are gone).
    entries: Vec<(Sym, bool, Option<WmeId>)>,
    live: usize,
    /// Position in `entries` by key (large slots only).
    index: Option<FxHashMap<(Sym, bool), u32>>,
}

impl SlotWmes {
    pub fn get(&self, key: &(Sym, bool)) -> Option<WmeId> {
        self.position(key).and_then(|i| self.entries[i].2)
    }

    pub fn contains_key(&self, key: &(Sym, bool)) -> bool {
        self.position(key).is_some()
    }

    pub fn insert(&mut self, key: (Sym, bool), w: WmeId) {
        if let Some(i) = self.position(&key) {
            self.entries[i].2 = Some(w);
            return;
        }
        self.entries.push((key.0, key.1, Some(w)));
        self.live += 1;
        match &mut self.index {
            Some(index) => {
                index.insert(key, (self.entries.len() - 1) as u32);
            }
            None if self.entries.len() > SMALL => self.rebuild_index(),
            None => {}
        }
    }

    pub fn remove(&mut self, key: &(Sym, bool)) -> Option<WmeId> {
        let i = self.position(key)?;
        self.live -= 1;
        match &mut self.index {
            None => self.entries.remove(i).2,
            Some(index) => {
                index.remove(key);
                let w = self.entries[i].2.take();
                if self.live * 2 < self.entries.len() {
                    self.entries.retain(|e| e.2.is_some());
                    self.rebuild_index();
                }
                w
            }
        }
    }

    /// `(value, acceptable, wme)`, oldest first.
    pub fn iter(&self) -> impl DoubleEndedIterator<Item = (Sym, bool, WmeId)> + '_ {
        self.entries
            .iter()
            .filter_map(|&(v, acc, w)| w.map(|w| (v, acc, w)))
    }

    /// The WMEs, oldest first.
    pub fn values(&self) -> impl DoubleEndedIterator<Item = WmeId> + '_ {
        self.iter().map(|(_, _, w)| w)
    }

    pub fn is_empty(&self) -> bool {
        self.live == 0
    }

    /// Where the entry for `key` is (entries are in the order added).
    pub fn position(&self, key: &(Sym, bool)) -> Option<usize> {
        match &self.index {
            Some(index) => index.get(key).map(|&i| i as usize),
            None => self
                .entries
                .iter()
                .position(|e| e.0 == key.0 && e.1 == key.1 && e.2.is_some()),
        }
    }

    fn rebuild_index(&mut self) {
        let index = self
            .entries
            .iter()
            .enumerate()
            .filter(|(_, e)| e.2.is_some())
            .map(|(i, e)| ((e.0, e.1), i as u32))
            .collect();
        self.index = Some(index);
    }

    fn clear(&mut self) {
        self.entries.clear();
        self.live = 0;
        self.index = None;
    }
}

id_type! {
    /// A slot's place in [`Slots`], valid while the slot lives: the changed list holds these
    /// and each firing's retraction finds its slot without hashing (9.6 points preferences at
    /// their slots).
    pub struct SlotId;
    index Slot;
}

/// The slots, in an arena found by (id, attribute), and each identifier's attributes that
/// have one, so that the slots of one identifier are found without a scan of them all (a
/// substate's slots when it goes, a result's objects when they move up).
#[derive(Debug, Default)]
pub struct Slots {
    map: FxHashMap<(Sym, Sym), SlotId>,
    arena: Vec<Slot>,
    /// Each arena place's generation: it grows when the place's slot goes, so that a
    /// [`SlotId`] kept with its generation can tell a later slot in the same place.
    gens: Vec<u32>,
    free: Vec<SlotId>,
    attrs: FxHashMap<Sym, Vec<Sym>>,
    /// Emptied slots and attribute lists, kept for their room.
    spare: Vec<Slot>,
    spare_attrs: Vec<Vec<Sym>>,
}

impl Slots {
    /// Every slot with its key, in no particular order.
    pub fn iter(&self) -> impl Iterator<Item = (&(Sym, Sym), &Slot)> + '_ {
        self.map.iter().map(|(k, &i)| (k, &self.arena[i]))
    }

    pub fn get(&self, key: &(Sym, Sym)) -> Option<&Slot> {
        self.map.get(key).map(|&i| &self.arena[i])
    }

    pub fn id_of(&self, key: &(Sym, Sym)) -> Option<SlotId> {
        self.map.get(key).copied()
    }

    pub fn slot(&self, id: SlotId) -> &Slot {
        &self.arena[id]
    }

    pub fn slot_mut(&mut self, id: SlotId) -> &mut Slot {
        &mut self.arena[id]
    }

    pub fn generation(&self, id: SlotId) -> u32 {
        self.gens[id.index()]
    }

    /// The slot, made empty if there was none.
    pub fn entry(&mut self, key: (Sym, Sym)) -> &mut Slot {
        let id = self.entry_id(key);
        &mut self.arena[id]
    }

    /// The slot's place, made empty if there was none.
    pub fn entry_id(&mut self, key: (Sym, Sym)) -> SlotId {
        if let Some(&id) = self.map.get(&key) {
            return id;
        }
        self.attrs
            .entry(key.0)
            .or_insert_with(|| self.spare_attrs.pop().unwrap_or_default())
            .push(key.1);
        // A freed place holds an emptied slot (with its room) or a default one.
        let id = match self.free.pop() {
            // A place emptied by `remove` holds a slot without room: a spare one has some.
            Some(id) => {
                if self.arena[id].prefs.capacity() == 0 {
                    if let Some(spare) = self.spare.pop() {
                        self.arena[id] = spare;
                    }
                }
                id
            }
            None => {
                self.arena.push(self.spare.pop().unwrap_or_default());
                self.gens.push(0);
                SlotId::from_index(self.arena.len() - 1)
            }
        };
        self.arena[id].key = key;
        self.map.insert(key, id);
        id
    }

    /// Forgets the slot at `id` if it has no preferences and no WMEs, emptying it in place.
    pub fn drop_if_empty(&mut self, id: SlotId) {
        let slot = &mut self.arena[id];
        if !slot.is_empty() {
            return;
        }
        let key = slot.key;
        slot.clear();
        self.map.remove(&key);
        self.gens[id.index()] += 1;
        self.free.push(id);
        self.forget_attr(key);
    }

    fn forget_attr(&mut self, key: (Sym, Sym)) {
        if let Some(list) = self.attrs.get_mut(&key.0) {
            if let Some(i) = list.iter().position(|a| *a == key.1) {
                list.remove(i);
            }
            if list.is_empty() {
                if let Some(list) = self.attrs.remove(&key.0) {
                    if self.spare_attrs.len() < 4096 {
                        self.spare_attrs.push(list);
                    }
                }
            }
        }
    }

    /// Takes a slot out; hand it back with [`Slots::recycle`] once read.
    pub fn remove(&mut self, key: &(Sym, Sym)) -> Option<Slot> {
        let id = self.map.remove(key)?;
        let slot = std::mem::take(&mut self.arena[id]);
        self.gens[id.index()] += 1;
        self.free.push(id);
        self.forget_attr(*key);
        Some(slot)
    }

    /// Keeps a removed slot's room for a later one.
    pub fn recycle(&mut self, mut slot: Slot) {
        if self.spare.len() < 4096 {
            slot.clear();
            self.spare.push(slot);
        }
    }

    /// The attributes of `id`'s slots, in the order the slots were made.
    pub fn attrs_of(&self, id: Sym) -> &[Sym] {
        self.attrs.get(&id).map_or(&[], |l| l.as_slice())
    }

    /// The keys of `id`'s slots, in the order they were made.
    pub fn keys_of(&self, id: Sym) -> Vec<(Sym, Sym)> {
        self.attrs
            .get(&id)
            .map_or_else(Vec::new, |l| l.iter().map(|&a| (id, a)).collect())
    }
}
