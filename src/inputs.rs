//! The agent's record of the input WMEs an embedding program made, and of what it changed
//! on the input-link between input phases: data the agent holds; `io.rs` fills it and the
//! input phase applies it.

use crate::symbols::Sym;
use crate::wm::WmeId;
use rustc_hash::{FxHashMap, FxHashSet};

/// What changing an input WME to the value it already has does (SML's
/// `SetBlinkIfNoChange`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum InputUpdate {
    /// Remove the WME and add it again with a new timetag, so rules that test it match
    /// again: the official kernel's default.
    #[default]
    BlinkIfNoChange,
    /// Leave the WME alone.
    SkipIfNoChange,
}

/// A handle on an input WME made through [`crate::Io::add`] or [`crate::Io::add_object`].
/// It stays valid when its value changes and across `init-soar`, until the WME is removed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct InputWme {
    /// The entry's place in the table.
    pub(crate) slot: u32,
    /// Which use of that place: a removed WME's place is reused, its handle is not.
    pub(crate) generation: u32,
}

/// One input WME the program made, as the input table remembers it.
#[derive(Debug, Clone)]
pub(crate) struct InputEntry {
    pub(crate) id: Sym,
    pub(crate) attr: Sym,
    pub(crate) value: Sym,
    /// The WME in working memory now; `None` once removed.
    pub(crate) wme: Option<WmeId>,
    /// The value is an identifier this table made (`add_input_object`).
    pub(crate) object: bool,
    generation: u32,
}

/// The program's input WMEs, and what the output side has reported and marked. Removed
/// entries leave their place for the next one, so a program that adds and removes input
/// for hours keeps a table as large as its input-link, and every operation is local: an
/// identifier's entries are listed under it, and the entries pointing at an identifier are
/// counted.
#[derive(Debug, Default)]
pub(crate) struct InputTable {
    entries: Vec<InputEntry>,
    free: Vec<u32>,
    /// The live entries hanging from each identifier, in the order they were made (an
    /// update keeps its place): the order in which `init-soar` adds them again.
    children: FxHashMap<Sym, Vec<u32>>,
    /// How many live entries have each identifier as their value.
    refs: FxHashMap<Sym, u32>,
    /// Input-link changes waiting for the next input phase.
    pub(crate) queue: Vec<InputChange>,
    pub(crate) update_mode: InputUpdate,
    /// The newest output-link timetag that new output commands were reported up to.
    pub(crate) output_reported: u64,
    /// Commands marked done since the last `init-soar`.
    pub(crate) done: FxHashSet<Sym>,
}

impl InputTable {
    /// A new live entry; `value_is_id` tells whether its value is an identifier.
    pub(crate) fn insert(&mut self, e: InputEntry, value_is_id: bool) -> InputWme {
        let id = e.id;
        if value_is_id {
            *self.refs.entry(e.value).or_default() += 1;
        }
        let slot = match self.free.pop() {
            Some(slot) => {
                let generation = self.entries[slot as usize].generation.wrapping_add(1);
                self.entries[slot as usize] = InputEntry { generation, ..e };
                slot
            }
            None => {
                self.entries.push(e);
                self.entries.len() as u32 - 1
            }
        };
        self.children.entry(id).or_default().push(slot);
        InputWme {
            slot,
            generation: self.entries[slot as usize].generation,
        }
    }

    /// A new entry's fields; its generation is set when it takes a place.
    pub(crate) fn entry(id: Sym, attr: Sym, value: Sym, wme: WmeId, object: bool) -> InputEntry {
        InputEntry {
            id,
            attr,
            value,
            wme: Some(wme),
            object,
            generation: 0,
        }
    }

    /// The entry a handle names: `Ok(None)` when its WME was removed, `Err(())` when the
    /// table never gave out this handle.
    pub(crate) fn get(&self, h: InputWme) -> Result<Option<&InputEntry>, ()> {
        let e = self.entries.get(h.slot as usize).ok_or(())?;
        if e.generation != h.generation || e.wme.is_none() {
            return Ok(None);
        }
        Ok(Some(e))
    }

    /// A live entry's new value and WME.
    pub(crate) fn set_value(&mut self, h: InputWme, value: Sym, wme: WmeId, is_id: [bool; 2]) {
        let old = self.entries[h.slot as usize].value;
        if is_id[0] {
            self.unref(old);
        }
        if is_id[1] {
            *self.refs.entry(value).or_default() += 1;
        }
        let e = &mut self.entries[h.slot as usize];
        e.value = value;
        e.wme = Some(wme);
        // A value that was an object of this table is one no longer.
        e.object = false;
    }

    /// Marks entry `slot` removed; `value_is_id` as when it was made live.
    pub(crate) fn kill(&mut self, slot: u32, value_is_id: bool) {
        let e = &mut self.entries[slot as usize];
        if e.wme.take().is_none() {
            return;
        }
        let (id, value) = (e.id, e.value);
        if value_is_id {
            self.unref(value);
        }
        if let Some(list) = self.children.get_mut(&id) {
            list.retain(|&x| x != slot);
            if list.is_empty() {
                self.children.remove(&id);
            }
        }
        self.free.push(slot);
    }

    fn unref(&mut self, id: Sym) {
        if let Some(n) = self.refs.get_mut(&id) {
            *n -= 1;
            if *n == 0 {
                self.refs.remove(&id);
            }
        }
    }

    /// Whether a live entry still has `id` as its value.
    pub(crate) fn linked(&self, id: Sym) -> bool {
        self.refs.contains_key(&id)
    }

    /// The live entries hanging from `id`, in the order they were made.
    pub(crate) fn children(&self, id: Sym) -> &[u32] {
        self.children.get(&id).map_or(&[], Vec::as_slice)
    }

    /// Entry `slot`, live or not.
    pub(crate) fn at(&self, slot: u32) -> &InputEntry {
        &self.entries[slot as usize]
    }

    /// Every live entry's place.
    pub(crate) fn live_slots(&self) -> Vec<u32> {
        (0..self.entries.len() as u32)
            .filter(|&s| self.entries[s as usize].wme.is_some())
            .collect()
    }

    /// Gives a live entry its WME again (after `init-soar` adds it anew).
    pub(crate) fn set_wme(&mut self, slot: u32, wme: WmeId) {
        self.entries[slot as usize].wme = Some(wme);
    }
}

/// An input-link change the embedding program made, waiting for the next input phase.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
/// Each names its WME with its timetag: garbage collection may take a waiting WME (with an
/// object a rule unlinked) and its handle go to another WME before the input phase, which
/// then leaves the other alone.
pub(crate) enum InputChange {
    Add(WmeId, u64),
    Remove(WmeId, u64),
}

