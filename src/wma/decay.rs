//! Base-level decay: the activation of a memory element from the times it was referenced
//! (Soar manual, ch. 8, "Working Memory Activation", after Anderson and Lebiere 1998),
//! with Petrov's (2006) estimate of the references too old to keep, and the search for the
//! first decision at which the activation falls below a threshold (Derbinsky and Laird
//! 2011, "Effective and efficient forgetting of learned knowledge in Soar's working and
//! procedural memories"). Working-memory activation decays WMEs with it and
//! reinforcement learning's apoptosis decays rules with it.
//!
//! Time runs in decisions. An element's activation at decision `t` is
//! `ln(sum(n_i * (t - t_i)^-d))` over its last [`HISTORY`] reference decisions `t_i`
//! (`n_i` references each).

/// How many reference decisions an element keeps (older ones enter Petrov's estimate).
pub const HISTORY: usize = 10;
/// The most references in one decision the estimate table allows for.
pub const MAX_REFS: usize = 50;

/// The references of one decision.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Reference {
    pub count: u64,
    pub step: u64,
}

/// One element's references: a ring of the last [`HISTORY`] decisions with references.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DecayHistory {
    refs: [Reference; HISTORY],
    /// Where the next decision goes (the ring's head).
    next: usize,
    /// How many slots of the ring are filled.
    filled: usize,
    /// References in the ring, and in all.
    in_ring: u64,
    total: u64,
    first_step: u64,
}

impl Default for DecayHistory {
    fn default() -> Self {
        Self::new()
    }
}

impl DecayHistory {
    pub fn new() -> Self {
        DecayHistory {
            refs: [Reference::default(); HISTORY],
            next: 0,
            filled: 0,
            in_ring: 0,
            total: 0,
            first_step: 0,
        }
    }

    /// Records `count` references at decision `step`, overwriting the oldest decision
    /// when the ring is full.
    pub fn record(&mut self, count: u64, step: u64) {
        let slot = &mut self.refs[self.next];
        self.in_ring = self.in_ring + count - slot.count;
        *slot = Reference { count, step };
        if self.total == 0 {
            self.first_step = step;
        }
        self.filled = (self.filled + 1).min(HISTORY);
        self.next = (self.next + 1) % HISTORY;
        self.total += count;
    }

    pub fn is_empty(&self) -> bool {
        self.filled == 0
    }

    /// The references in the ring, in all, and the decision of the first.
    pub fn counts(&self) -> (u64, u64, u64) {
        (self.in_ring, self.total, self.first_step)
    }

    /// The ring from the newest decision back.
    pub fn newest_first(&self) -> impl Iterator<Item = &Reference> {
        (1..=self.filled).map(move |k| &self.refs[(self.next + HISTORY - k) % HISTORY])
    }

    /// The sum of decayed references at decision `t` (the activation before its log), 0
    /// without references; `decay` is the exponent `d` (positive). With `petrov`, the
    /// references that left the ring count by Petrov's estimate.
    pub fn sum(&self, t: u64, decay: f64, petrov: bool) -> f64 {
        let mut sum = 0.0;
        let mut oldest_age = 0;
        for r in self.newest_first() {
            oldest_age = t.saturating_sub(r.step);
            // 9.6 reads powers from a table whose entry for age 0 is 0: references of the
            // current decision add nothing yet.
            if oldest_age > 0 {
                sum += r.count as f64 * (oldest_age as f64).powf(-decay);
            }
        }
        if petrov && self.total > self.in_ring {
            let d_inv = 1.0 - decay;
            let span = t.saturating_sub(self.first_step) as f64;
            sum += ((self.total - self.in_ring) as f64
                * (span.powf(d_inv) - (oldest_age as f64).powf(d_inv)))
                / (d_inv * (span - oldest_age as f64));
        }
        sum
    }
}

/// The decay's constants: exponent, threshold, Petrov's estimate, and the table of the
/// cheap first estimate.
#[derive(Debug, Clone)]
pub struct DecayModel {
    /// The exponent `d` (positive).
    pub decay: f64,
    /// The threshold `e^thresh`.
    pub threshold: f64,
    pub petrov: bool,
    /// For each reference count below [`MAX_REFS`], the decisions one decision's
    /// references of that many take to decay below the threshold alone; empty when the
    /// estimate is not used.
    alone: Vec<u64>,
}

impl DecayModel {
    /// A model with exponent `decay` (positive), threshold `thresh` (a log value,
    /// negative); `estimate` turns on the cheap first estimate.
    pub fn new(decay: f64, thresh: f64, petrov: bool, estimate: bool) -> Self {
        let alone = if estimate {
            (0..MAX_REFS)
                .map(|n| {
                    if n == 0 {
                        0
                    } else {
                        ((thresh - (n as f64).ln()) / -decay).exp().ceil() as u64
                    }
                })
                .collect()
        } else {
            Vec::new()
        };
        DecayModel {
            decay,
            threshold: thresh.exp(),
            petrov,
            alone,
        }
    }

    pub fn sum(&self, h: &DecayHistory, t: u64) -> f64 {
        h.sum(t, self.decay, self.petrov)
    }

    pub fn below_threshold(&self, h: &DecayHistory, t: u64) -> bool {
        self.sum(h, t) < self.threshold
    }

    /// The decision at which an element is to be checked: after a fresh reference (with
    /// the estimate on), the sum of what each decision's references alone still need (an
    /// underestimate); otherwise, or when that adds nothing, the exact first decision
    /// below the threshold.
    pub fn forgetting_time(&self, h: &DecayHistory, now: u64, fresh: bool) -> u64 {
        let mut at = now;
        if fresh && !self.alone.is_empty() {
            let mut extra = 0;
            for r in h.newest_first() {
                let age = at.saturating_sub(r.step);
                let n = (r.count as usize).min(MAX_REFS - 1);
                if self.alone[n] > age {
                    extra += self.alone[n] - age;
                }
            }
            at += extra;
        }
        if at == now {
            at += self.exact_extra(h, at);
        }
        at
    }

    /// The decisions after `from` until the activation first falls below the threshold:
    /// doubling, then a binary search.
    fn exact_extra(&self, h: &DecayHistory, from: u64) -> u64 {
        let mut upper = 1;
        if self.below_threshold(h, from + upper) {
            return upper;
        }
        while !self.below_threshold(h, from + upper) {
            upper *= 2;
        }
        let mut lower = if upper < 4 { upper } else { upper / 2 };
        while lower != upper {
            let mid = (lower + upper) / 2;
            if self.below_threshold(h, from + mid) {
                upper = mid;
                if upper - lower <= 1 {
                    lower = mid;
                }
            } else {
                lower = mid;
                if upper - lower <= 1 {
                    lower = upper;
                }
            }
        }
        upper
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_reference_sums_to_its_power() {
        let mut h = DecayHistory::new();
        h.record(3, 1);
        assert!((h.sum(5, 0.5, false) - 1.5).abs() < 1e-12);
    }

    #[test]
    fn the_estimate_predicts_9_6s_forgetting_decision() {
        // 3 references at decision 1, d = 0.5, threshold e^-1.5: checked at decision 182
        // (observed on 9.6 with `wm activation -h`).
        let m = DecayModel::new(0.5, -1.5, false, true);
        let mut h = DecayHistory::new();
        h.record(3, 1);
        assert_eq!(m.forgetting_time(&h, 1, true), 182);
    }

    #[test]
    fn the_ring_keeps_ten_decisions_and_counts_all() {
        let mut h = DecayHistory::new();
        for step in 1..=12 {
            h.record(2, step);
        }
        assert_eq!(h.counts(), (20, 24, 1));
        assert_eq!(h.newest_first().count(), HISTORY);
        assert!(h.sum(13, 0.5, true) > h.sum(13, 0.5, false));
    }
}
