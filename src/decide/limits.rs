//! Ceilings on what a run may grow (the `limits` command, [`crate::Agent::set_limits`]): the
//! WMEs in working memory, the partial matches the matcher holds, and the chunks one run
//! learns. An agent that grows without end (a rule whose every firing multiplies its own
//! matches, say) is stopped with a message instead of taking the machine's memory. The
//! ceilings are checked after each elaboration cycle and each phase (`ceilings.rs`), where a
//! run can stop and go on later; one cycle can therefore pass a ceiling before the run stops.

/// The ceilings; 0 is none (the default for each).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Limits {
    /// The most WMEs working memory may hold: a run stops once it holds more.
    pub wmes: u64,
    /// The most partial matches (tokens) the matcher may hold: a run stops once it holds
    /// more.
    pub tokens: u64,
    /// The most preferences preference memory may hold: a run stops once it holds more
    /// (rules can pile up preferences for the same few WMEs).
    pub preferences: u64,
    /// The most chunks one run may learn: the run stops once it has learned this many.
    pub chunks: u64,
}

/// The ceiling a run met, with what it counted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Ceiling {
    Wmes { count: u64, limit: u64 },
    Tokens { count: u64, limit: u64 },
    Preferences { count: u64, limit: u64 },
    Chunks { count: u64 },
}

impl Ceiling {
    /// The message the run stops with.
    pub fn message(self) -> String {
        match self {
            Ceiling::Wmes { count, limit } => format!(
                "\nStopped: working memory holds {count} WMEs, more than its ceiling of {limit} (limits --wmes).\n"
            ),
            Ceiling::Tokens { count, limit } => format!(
                "\nStopped: the matcher holds {count} partial matches, more than its ceiling of {limit} (limits --tokens).\n"
            ),
            Ceiling::Preferences { count, limit } => format!(
                "\nStopped: preference memory holds {count} preferences, more than its ceiling of {limit} (limits --preferences).\n"
            ),
            Ceiling::Chunks { count } => format!(
                "\nStopped: this run learned {count} chunk{}, its ceiling (limits --chunks).\n",
                if count == 1 { "" } else { "s" }
            ),
        }
    }
}
