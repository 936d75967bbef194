//! The decision cycle's trace as typed events (Soar manual, chapter 9, "trace"): the
//! kernel says what happened, at the moment it happens and only when the trace setting
//! that shows it is on; a listener turns each event into text. The default listener,
//! `trace_text`, prints Soar 9.6's trace; another one (a debugger's view, a program's
//! callback) can read the same events without parsing that text.

use crate::decide::state::Phase;
use crate::symbols::Sym;
use crate::wm::Wme;

/// One line (or header) of the decision cycle's trace.
#[derive(Debug, Clone, Copy)]
pub(crate) enum TraceEvent<'a> {
    /// A phase begins (`trace --phases`).
    PhaseBegin(Phase),
    /// A phase ends (`trace --phases`).
    PhaseEnd(Phase),
    /// The apply phase fires one elaboration cycle's productions: all o-supported (PE)
    /// or not (IE), at the goal of this depth (`trace --phases`).
    FiringProductions { o_support: bool, depth: u32 },
    /// The apply phase's elaboration cycle changes working memory (`trace --phases`).
    ChangeWorkingMemory { o_support: bool },
    /// The firings of one goal in an elaboration cycle begin (`trace --waterfall`); no
    /// goal when only the retractions of goals that are gone are pending.
    InnerElaboration { level: u32, goal: Option<Sym> },
    /// A WME enters (`added`) or leaves working memory (`trace --wmes`).
    Wme { added: bool, wme: &'a Wme },
}
