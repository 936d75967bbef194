//! Per-decision-cycle statistics for `stats --max` and cycle tracking (Soar manual, ch. 9,
//! `stats`): each decision cycle's kernel time, working-memory changes and rule firings,
//! recorded when its output phase ends. The largest of each, with the cycle it came in,
//! is always kept (`--max`, zeroed by `--reset` and `init-soar`); with tracking on
//! (`--track`), every cycle's row is kept too (`--cycle`, `--cycle-csv`), until
//! `--stop-track` or `init-soar` clears them.

use std::time::Duration;

/// One decision cycle's figures.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct CycleRow {
    /// The decision cycle's number.
    pub cycle: u64,
    pub time: Duration,
    pub wm_changes: u64,
    pub firings: u64,
}

/// The largest value of one figure and the cycle it came in (cycle 0: none yet).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Max<T> {
    pub value: T,
    pub cycle: u64,
}

impl<T: PartialOrd + Copy> Max<T> {
    fn offer(&mut self, value: T, cycle: u64) {
        if value > self.value {
            *self = Max { value, cycle };
        }
    }
}

/// The decider's per-cycle statistics.
#[derive(Debug, Clone, Default)]
pub struct CycleStats {
    /// Whether each cycle's row is kept (`stats --track`). `init-soar` keeps the setting
    /// and drops the rows.
    pub tracking: bool,
    pub rows: Vec<CycleRow>,
    pub max_time: Max<Duration>,
    pub max_wm_changes: Max<u64>,
    pub max_firings: Max<u64>,
    /// The running totals (kernel time, WM changes, firings) when the last cycle ended:
    /// the next cycle's figures are the totals' growth since.
    base: (Duration, u64, u64),
}

impl CycleStats {
    /// Ends decision cycle `cycle` at the running totals given.
    pub fn end_cycle(&mut self, cycle: u64, time: Duration, wm_changes: u64, firings: u64) {
        let row = CycleRow {
            cycle,
            time: time.saturating_sub(self.base.0),
            wm_changes: wm_changes.saturating_sub(self.base.1),
            firings: firings.saturating_sub(self.base.2),
        };
        self.base = (time, wm_changes, firings);
        self.max_time.offer(row.time, cycle);
        self.max_wm_changes.offer(row.wm_changes, cycle);
        self.max_firings.offer(row.firings, cycle);
        if self.tracking {
            self.rows.push(row);
        }
    }

    /// `stats --reset`: the maxima start again.
    pub fn reset_max(&mut self) {
        self.max_time = Max::default();
        self.max_wm_changes = Max::default();
        self.max_firings = Max::default();
    }

    /// `stats --stop-track`: tracking stops and its rows go.
    pub fn stop_tracking(&mut self) {
        self.tracking = false;
        self.rows.clear();
    }

    /// The kept rows ordered by `sort` as 9.6's `stats --sort N` orders them: by column 1
    /// (cycle), 2 (time), 3 (WM changes) or 4 (firings), ties by cycle; a negative column
    /// gives the reverse order; 0 or any other number keeps cycle order (reversed when
    /// negative).
    pub fn sorted_rows(&self, sort: i64) -> Vec<CycleRow> {
        let mut rows = self.rows.clone();
        match sort.unsigned_abs() {
            2 => rows.sort_by_key(|r| (r.time, r.cycle)),
            3 => rows.sort_by_key(|r| (r.wm_changes, r.cycle)),
            4 => rows.sort_by_key(|r| (r.firings, r.cycle)),
            _ => rows.sort_by_key(|r| r.cycle),
        }
        if sort < 0 {
            rows.reverse();
        }
        rows
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ms(n: u64) -> Duration {
        Duration::from_millis(n)
    }

    #[test]
    fn each_cycle_is_the_growth_of_the_totals() {
        let mut s = CycleStats {
            tracking: true,
            ..Default::default()
        };
        s.end_cycle(1, ms(5), 36, 7);
        s.end_cycle(2, ms(7), 56, 14);
        s.end_cycle(3, ms(8), 101, 25);
        let changes: Vec<u64> = s.rows.iter().map(|r| r.wm_changes).collect();
        assert_eq!(changes, [36, 20, 45]);
        assert_eq!(s.max_wm_changes, Max { value: 45, cycle: 3 });
        assert_eq!(s.max_time, Max { value: ms(5), cycle: 1 });
        let by_firings: Vec<u64> = s.sorted_rows(-4).iter().map(|r| r.cycle).collect();
        assert_eq!(by_firings, [3, 2, 1]);
        let by_time: Vec<u64> = s.sorted_rows(2).iter().map(|r| r.cycle).collect();
        assert_eq!(by_time, [3, 2, 1]);
        s.reset_max();
        assert_eq!(s.max_firings, Max::default());
        s.stop_tracking();
        assert!(s.rows.is_empty() && !s.tracking);
    }
}
