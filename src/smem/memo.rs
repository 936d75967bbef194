//! What the store remembers beside its database, so that a retrieval reads SQLite only for
//! the walk over its candidates: each LTI's augmentations (the checks on a candidate and
//! the installing of the winner read them), its activation record, the frequency counts a
//! cue's elements are weighed by, and the persistent variables.
//!
//! Each entry is a copy of rows the store writes only through its own methods, so an entry
//! is dropped (or updated) wherever those rows change; the variables are written back at
//! each commit and when the store closes, which is when 9.6 writes them.

use super::store::AugValue;
use rustc_hash::FxHashMap;

/// An augmentation by symbol numbers: (attribute, constant value or 0, LTI value or 0).
pub type AugRow = (i64, i64, i64);

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
    pub augs: FxHashMap<i64, Vec<AugRow>>,
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
        self.counts.remove(&(a, None));
        self.counts.remove(&(a, Some((c, l))));
    }

    /// Everything but the variables (`smem --clear` resets those itself).
    pub fn clear(&mut self) {
        self.augs.clear();
        self.records.clear();
        self.counts.clear();
    }

    /// Whether an LTI with augmentations `rows` has one with attribute `a` and `value`.
    pub fn has(rows: &[AugRow], a: i64, value: AugValue) -> bool {
        rows.iter().any(|&(ra, rc, rl)| {
            ra == a
                && match value {
                    AugValue::Any => true,
                    AugValue::Lti(l) => rl == l,
                    AugValue::Const(c) => rc == c && rl == 0,
                }
        })
    }
}
