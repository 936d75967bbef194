//! The timers of the long-term memories (`smem --timers`, `epmem --timers`; Soar manual,
//! the `smem` and `epmem` commands): each timer adds up the wall-clock time spent in one
//! part of its memory, but only while the memory's `timers` setting is at the timer's level
//! or above (`one`, `two`, `three`; `off` times nothing). The times are the machine's, so
//! no two runs print the same figures.

use std::time::{Duration, Instant};

/// A timer: its name as the listing prints it, and its level (1 to 3).
pub type Timer = (&'static str, u8);

/// The time each of a memory's timers has added up (a timer not listed has none).
#[derive(Debug, Clone, Default)]
pub struct MemoryTimers {
    spent: Vec<(&'static str, Duration)>,
}

/// A timer running since an instant, or not running (its level is above the setting's).
#[must_use]
pub struct Running(Option<(&'static str, Instant)>);

impl MemoryTimers {
    /// The level a `timers` setting names: `off` 0, `one` 1, `two` 2, `three` 3.
    pub fn level_of(setting: &str) -> u8 {
        match setting {
            "one" => 1,
            "two" => 2,
            "three" => 3,
            _ => 0,
        }
    }

    /// Starts `timer` if `setting` (the memory's level) reaches its level.
    pub fn start(timer: Timer, setting: u8) -> Running {
        Running((setting >= timer.1).then(|| (timer.0, Instant::now())))
    }

    /// Adds the time since `running` started to its timer.
    pub fn stop(&mut self, running: Running) {
        let Some((name, since)) = running.0 else {
            return;
        };
        let spent = since.elapsed();
        match self.spent.iter_mut().find(|t| t.0 == name) {
            Some(t) => t.1 += spent,
            None => self.spent.push((name, spent)),
        }
    }

    /// The seconds timer `name` has added up, in whole microseconds (the resolution 9.6
    /// prints).
    pub fn seconds(&self, name: &str) -> f64 {
        self.spent
            .iter()
            .find(|t| t.0 == name)
            .map_or(0.0, |t| t.1.as_micros() as f64 / 1e6)
    }

    /// Every timer back to zero.
    pub fn reset(&mut self) {
        self.spent.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_timer_adds_up_only_at_or_above_its_level() {
        const QUERY: Timer = ("query", 2);
        let mut t = MemoryTimers::default();
        let r = MemoryTimers::start(QUERY, 1);
        std::thread::sleep(Duration::from_millis(2));
        t.stop(r);
        assert_eq!(t.seconds("query"), 0.0);
        let r = MemoryTimers::start(QUERY, 2);
        std::thread::sleep(Duration::from_millis(2));
        t.stop(r);
        assert!(t.seconds("query") >= 0.002);
        t.reset();
        assert_eq!(t.seconds("query"), 0.0);
        assert_eq!(MemoryTimers::level_of("three"), 3);
        assert_eq!(MemoryTimers::level_of("off"), 0);
    }
}
