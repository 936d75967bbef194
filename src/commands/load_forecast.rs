//! How many rules the rest of a large file will add, judged by the part of it already run,
//! so that the tables that grow with the rules are sized once, early in the load. A table
//! that doubles near the end of a load holds its old copy and the new one at once (and the
//! allocator may keep the old pages a while): at 100,000 rules the network's node table
//! alone is 32 MB.

/// The share of the file read before the forecast is made (1/32).
const SAMPLE_SHIFT: u32 = 5;

pub(super) struct LoadForecast {
    /// The file's length; none for a file too small to forecast.
    len: Option<usize>,
    rules_at_start: usize,
}

impl LoadForecast {
    /// For a file of `len` bytes, when the agent holds `rules` rules.
    pub fn new(len: usize, large: bool, rules: usize) -> Self {
        LoadForecast {
            len: large.then_some(len),
            rules_at_start: rules,
        }
    }

    /// After a command that ended at byte `pos`, with `rules` rules loaded: the rules the
    /// rest of the file will add, once, when the part read is large enough to judge by.
    pub fn rules_to_come(&mut self, pos: usize, rules: usize) -> Option<usize> {
        let len = self.len?;
        if pos < len >> SAMPLE_SHIFT || pos == 0 {
            return None;
        }
        self.len = None;
        let added = rules.saturating_sub(self.rules_at_start);
        let rest = len.saturating_sub(pos);
        Some(added.saturating_mul(rest) / pos)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn forecasts_once_from_the_first_part() {
        let mut f = LoadForecast::new(3200, true, 10);
        assert_eq!(f.rules_to_come(50, 12), None);
        assert_eq!(f.rules_to_come(100, 20), Some(310));
        assert_eq!(f.rules_to_come(200, 30), None);
        let mut small = LoadForecast::new(3200, false, 0);
        assert_eq!(small.rules_to_come(1000, 10), None);
    }
}
