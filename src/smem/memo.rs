//! What the store remembers beside its database, so that a retrieval reads little of
//! SQLite: each LTI's augmentations (the checks on a candidate and the installing of the
//! winner read them), its activation record, the frequency counts a cue's elements are
//! weighed by, the persistent variables, and the candidates of each cue element whose walk
//! once went to its end (a cue that fails is walked again and again).
//!
//! Each entry is a copy of rows the store writes only through its own methods, so an entry
//! is dropped (or updated) wherever those rows change. Two things are written back later:
//! the variables, and the copy of an LTI's new activation on its augmentation rows (which
//! costs an update of two indexes per row); both at each commit, before the augmentations
//! change, and when the store closes (9.6 writes the variables then too). Until then a walk
//! takes the rows of the LTIs activated since from `overlay`, at their new rank.

use rustc_hash::FxHashMap;
use std::collections::BTreeMap;

/// An augmentation's value by symbol numbers, for `Store::has_aug`.
#[derive(Debug, Clone, Copy)]
pub enum AugValue {
    Const(i64),
    Lti(i64),
    Any,
}

/// An augmentation by symbol numbers: (attribute, constant value or 0, LTI value or 0).
pub type AugRow = (i64, i64, i64);

/// An augmentation row as a walk needs it: its symbols, its row number and its copy of the
/// LTI's activation.
#[derive(Debug, Clone, Copy)]
pub struct AugEntry {
    pub row: AugRow,
    pub rowid: i64,
    pub act: Option<f64>,
}

/// Where a row comes in a walk, which reads ranks from the highest down: its activation,
/// then its row number (the order of 9.6's index read backwards; SQLite sorts a missing
/// activation below every number).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub struct Rank(u64, i64);

impl Rank {
    pub fn new(act: Option<f64>, rowid: i64) -> Rank {
        // The bits of a float, turned so that their order as integers is the numbers'.
        let key = act.map_or(0, |a| {
            let bits = a.to_bits();
            if bits >> 63 == 1 {
                !bits
            } else {
                bits | 1 << 63
            }
        });
        Rank(key, rowid)
    }
}

/// The most rows a remembered walk holds; longer ones are read from SQLite each time.
pub const WALK_ROWS: usize = 1 << 16;

/// The activation record of an LTI: (activations, last, first) and the times of the last
/// ten activations, most recent first.
#[derive(Debug, Clone, Default)]
pub struct Record {
    pub total: f64,
    pub last: i64,
    pub first: i64,
    pub history: Vec<i64>,
}

/// The key of a frequency count: an attribute alone (`value` `None`) or with a value.
pub type CountKey = (i64, Option<(i64, i64)>);

#[derive(Debug, Default)]
pub struct Memo {
    /// Each LTI's augmentations, in 9.6's order (by attribute, then value).
    pub augs: FxHashMap<i64, Vec<AugEntry>>,
    /// The rows of the cue elements whose walk went to its end, by rank, with their LTI.
    pub walks: FxHashMap<CountKey, BTreeMap<Rank, i64>>,
    /// The activations not yet copied to their LTI's augmentation rows, by LTI.
    pub pending: FxHashMap<i64, f64>,
    /// The augmentation rows of the LTIs in `pending`, by cue element, at their new rank.
    pub overlay: FxHashMap<CountKey, BTreeMap<Rank, i64>>,
    pub records: FxHashMap<i64, Record>,
    pub counts: FxHashMap<CountKey, i64>,
    /// The persistent variables, and which of them the database has not yet seen.
    pub vars: FxHashMap<i64, i64>,
    pub dirty_vars: Vec<i64>,
}

impl Memo {
    /// Forgets what is known of an LTI's augmentations and of the counts they feed.
    pub fn augs_changed(&mut self, lti: i64, row: AugRow) {
        self.augs.remove(&lti);
        let (a, c, l) = row;
        for key in [(a, None), (a, Some((c, l)))] {
            self.counts.remove(&key);
            self.walks.remove(&key);
        }
    }

    /// Moves an LTI's rows in the remembered walks and the overlay to their new activation
    /// (`rows` as they were before), which its augmentation rows are yet to be given.
    pub fn activation_changed(&mut self, lti: i64, rows: &[AugEntry], value: f64) {
        let was_pending = self.pending.insert(lti, value).is_some();
        for e in rows {
            let (a, c, l) = e.row;
            for key in [(a, None), (a, Some((c, l)))] {
                let over = self.overlay.entry(key).or_default();
                if was_pending {
                    over.remove(&Rank::new(e.act, e.rowid));
                }
                over.insert(Rank::new(Some(value), e.rowid), lti);
                let Some(walk) = self.walks.get_mut(&key) else {
                    continue;
                };
                if walk.remove(&Rank::new(e.act, e.rowid)).is_some() {
                    walk.insert(Rank::new(Some(value), e.rowid), lti);
                } else {
                    // Not where it should be: this walk is read from SQLite again.
                    self.walks.remove(&key);
                }
            }
        }
        if let Some(entries) = self.augs.get_mut(&lti) {
            for e in entries {
                e.act = Some(value);
            }
        }
    }

    /// Everything but the variables (`smem --clear` resets those itself).
    pub fn clear(&mut self) {
        self.augs.clear();
        self.records.clear();
        self.counts.clear();
        self.walks.clear();
        self.pending.clear();
        self.overlay.clear();
    }

    /// Whether an LTI with augmentations `rows` has one with attribute `a` and `value`.
    pub fn has(rows: &[AugEntry], a: i64, value: AugValue) -> bool {
        rows.iter().any(|e| {
            let (ra, rc, rl) = e.row;
            ra == a
                && match value {
                    AugValue::Any => true,
                    AugValue::Lti(l) => rl == l,
                    AugValue::Const(c) => rc == c && rl == 0,
                }
        })
    }
}
