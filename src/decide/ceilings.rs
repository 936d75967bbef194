//! The check of a run against its ceilings (`limits.rs`).

use super::limits::{Ceiling, Limits};
use crate::agent::AgentCore;

impl AgentCore {
    /// Whether the matcher holds more partial matches than its ceiling.
    pub(crate) fn tokens_over_ceiling(&self) -> bool {
        let limit = self.settings.limits.tokens;
        limit > 0 && self.rete.token_total() as u64 > limit
    }

    /// Whether preference memory holds more than its ceiling.
    pub(crate) fn preferences_over_ceiling(&self) -> bool {
        let limit = self.settings.limits.preferences;
        limit > 0 && self.decider.live_prefs() as u64 > limit
    }

    /// The run met the preference ceiling with `count` preferences (held at some moment
    /// of the cycle): it stops as at any ceiling.
    pub(crate) fn preference_ceiling_reached(&mut self, count: u64) {
        if self.decider.ceiling.is_none() {
            self.stop_at_ceiling(Ceiling::Preferences {
                count,
                limit: self.settings.limits.preferences,
            });
        }
    }

    /// The trace says which ceiling the run met, and the run is asked to stop.
    fn stop_at_ceiling(&mut self, hit: Ceiling) {
        self.output.push_str(&hit.message());
        self.decider.ceiling = Some(hit);
        self.decider.stop_requested = true;
    }

    /// Whether the run has met a ceiling: the first time, the trace says which and the run
    /// is asked to stop (it stops where an interrupt would, and `run` may go on later).
    pub(crate) fn ceiling_reached(&mut self) -> bool {
        if self.decider.ceiling.is_some() {
            return true;
        }
        let limits = self.settings.limits;
        if limits == Limits::default() {
            return false;
        }
        let wmes = self.wm.len() as u64;
        let tokens = self.rete.token_total() as u64;
        let prefs = self.decider.live_prefs() as u64;
        let chunks = self.learn.learned_this_run;
        let hit = if limits.wmes > 0 && wmes > limits.wmes {
            Ceiling::Wmes {
                count: wmes,
                limit: limits.wmes,
            }
        } else if limits.tokens > 0 && tokens > limits.tokens {
            Ceiling::Tokens {
                count: tokens,
                limit: limits.tokens,
            }
        } else if limits.preferences > 0 && prefs > limits.preferences {
            Ceiling::Preferences {
                count: prefs,
                limit: limits.preferences,
            }
        } else if limits.chunks > 0 && chunks >= limits.chunks {
            Ceiling::Chunks { count: chunks }
        } else {
            return false;
        };
        self.stop_at_ceiling(hit);
        true
    }
}
