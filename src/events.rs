//! What an agent does, as events a program can listen to: the phases of the decision cycle,
//! rule firings and retractions, working-memory changes and `init-soar` (the official
//! kernel's run, production and WME events, which SML programs register for).

use crate::decide::state::Phase;
use crate::wm::Wme;

/// One thing the agent did (see [`crate::Agent::on_event`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AgentEvent<'a> {
    /// A phase of the decision cycle begins.
    BeforePhase(Phase),
    /// A phase of the decision cycle has ended.
    AfterPhase(Phase),
    /// A rule fired (a match of it was instantiated).
    Fired {
        /// The rule's name.
        rule: &'a str,
    },
    /// A rule's instantiation retracted (its match went away).
    Retracted {
        /// The rule's name.
        rule: &'a str,
    },
    /// A WME entered working memory (and the matcher).
    WmeAdded(Wme),
    /// A WME left working memory.
    WmeRemoved(Wme),
    /// `init-soar` emptied working memory and made the top state again.
    InitSoar,
}

/// A program's listener.
pub(crate) type EventListener = Box<dyn FnMut(&AgentEvent)>;

/// The listeners of one agent, by the number they were registered under.
#[derive(Default)]
pub(crate) struct EventListeners {
    list: Vec<(u64, EventListener)>,
}

impl std::fmt::Debug for EventListeners {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "EventListeners({})", self.list.len())
    }
}

impl EventListeners {
    /// Whether anyone listens (checked before an event is made, so that an agent nobody
    /// listens to pays one branch per event).
    #[inline]
    pub(crate) fn any(&self) -> bool {
        !self.list.is_empty()
    }

    pub(crate) fn add(&mut self, id: u64, l: EventListener) {
        self.list.push((id, l));
    }

    /// Removes listener `id`; false if it was not there.
    pub(crate) fn remove(&mut self, id: u64) -> bool {
        let before = self.list.len();
        self.list.retain(|(i, _)| *i != id);
        self.list.len() != before
    }

    pub(crate) fn send(&mut self, e: &AgentEvent) {
        for (_, l) in self.list.iter_mut() {
            l(e);
        }
    }
}
