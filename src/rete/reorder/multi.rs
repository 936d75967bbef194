//! `multi-attributes` (`production optimize-attribute`): attributes the user declares to
//! have several values per identifier, with the number expected. The reorderer prices a
//! condition on such an attribute by that number instead of 1 (Soar manual, chapter 9,
//! `production`).

use crate::ast::Constant;
use crate::symbols::{Sym, Symbols};

/// The declared attributes, in declaration order, each with its expected count.
#[derive(Debug, Default, Clone)]
pub struct MultiAttributes {
    entries: Vec<(Sym, u64)>,
}

impl MultiAttributes {
    /// The count 9.6 gives an attribute when `multi-attributes ATTR` names none.
    pub const DEFAULT_COUNT: u64 = 10;

    /// Declares `attr` with `count`; a second declaration changes the count in place.
    pub fn set(&mut self, attr: Sym, count: u64) {
        match self.entries.iter_mut().find(|(s, _)| *s == attr) {
            Some(e) => e.1 = count,
            None => self.entries.push((attr, count)),
        }
    }

    /// The expected count of `attr`'s values: its declared count, else 1.
    pub fn count(&self, attr: &Constant, syms: &Symbols) -> u64 {
        if self.entries.is_empty() {
            return 1;
        }
        syms.find_constant(attr)
            .and_then(|s| self.entries.iter().find(|(x, _)| *x == s))
            .map_or(1, |e| e.1)
    }

    /// The listing `multi-attributes` prints: newest first, as 9.6 lists them (soar-sml
    /// 9.6.5, including its text when there are none).
    pub fn listing(&self, syms: &Symbols) -> String {
        let mut s = String::new();
        if self.entries.is_empty() {
            s.push_str("No optimized attributes found.");
        }
        s.push_str("Value\tSymbol\n");
        for (sym, count) in self.entries.iter().rev() {
            s.push_str(&format!("{count}\t{}\n", syms.text(*sym)));
        }
        s
    }
}
