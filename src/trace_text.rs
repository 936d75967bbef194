//! The 9.6 text listener: Soar 9.6's trace text for each trace event, byte for byte as
//! the official kernel prints it (Soar manual, chapter 9, "trace"). The agent owns one as
//! its default listener and appends what it writes to its print stream.

use crate::decide::state::Phase;
use crate::symbols::Symbols;
use crate::trace_events::TraceEvent;
use crate::wm::Wme;
use std::fmt::Write;

/// Writes trace events as Soar 9.6's trace text.
#[derive(Debug, Default, Clone, Copy)]
pub(crate) struct TraceText96;

impl TraceText96 {
    /// Appends the text of `event` to `out`.
    pub(crate) fn write(&self, out: &mut String, symbols: &Symbols, event: &TraceEvent<'_>) {
        match *event {
            TraceEvent::PhaseBegin(phase) => out.push_str(phase_begin(phase)),
            TraceEvent::PhaseEnd(phase) => out.push_str(phase_end(phase)),
            TraceEvent::FiringProductions { o_support, depth } => {
                let _ = writeln!(
                    out,
                    "\t--- Firing Productions ({}) For State At Depth {depth} ---",
                    pe_or_ie(o_support)
                );
            }
            TraceEvent::ChangeWorkingMemory { o_support } => {
                let _ = writeln!(
                    out,
                    "\t--- Change Working Memory ({}) ---",
                    pe_or_ie(o_support)
                );
            }
            TraceEvent::InnerElaboration { level, goal } => {
                let goal = goal.map_or_else(|| "#".to_string(), |g| symbols.text(g));
                let _ = writeln!(
                    out,
                    "\n--- Inner Elaboration Phase, active level {level} goal {goal} ---"
                );
            }
            TraceEvent::Wme { added, wme } => {
                out.push_str(if added { "=>WM: " } else { "<=WM: " });
                wme_text(out, symbols, wme);
                out.push('\n');
            }
        }
    }
}

/// `(tt: id ^attr value[ +])`, as `print --internal` shows a WME.
fn wme_text(out: &mut String, symbols: &Symbols, w: &Wme) {
    let _ = write!(
        out,
        "({}: {} ^{} {}{})",
        w.timetag,
        symbols.text(w.id),
        symbols.text(w.attr),
        symbols.text(w.value),
        if w.acceptable { " +" } else { "" }
    );
}

fn pe_or_ie(o_support: bool) -> &'static str {
    if o_support {
        "PE"
    } else {
        "IE"
    }
}

// The input phase's lines end in a space before the newline; the others do not
// (observed on 9.6).
fn phase_begin(phase: Phase) -> &'static str {
    match phase {
        Phase::Input => "\n--- Input Phase --- \n",
        Phase::Propose => "\n--- Propose Phase ---\n",
        Phase::Decide => "\n--- Decision Phase ---\n",
        Phase::Apply => "\n--- Application Phase ---\n",
        Phase::Output => "\n--- Output Phase ---\n",
    }
}

fn phase_end(phase: Phase) -> &'static str {
    match phase {
        Phase::Input => "\n--- END Input Phase --- \n",
        Phase::Propose => "\n--- END Propose Phase ---\n",
        Phase::Decide => "\n--- END Decision Phase ---\n",
        Phase::Apply => "\n--- END Application Phase ---\n",
        Phase::Output => "\n--- END Output Phase ---\n",
    }
}
