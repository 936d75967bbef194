//! The 9.6 text listener: Soar 9.6's trace text for each trace event, byte for byte as
//! the official kernel prints it (Soar manual, chapter 9, "trace"). The agent owns one as
//! its default listener and appends what it writes to its print stream.

use crate::decide::procedure::PrefType;
use crate::decide::state::{ImpasseKind, Phase, Preference};
use crate::symbols::Symbols;
use crate::trace_events::TraceEvent;
use crate::wm::Wme;
use std::fmt::Write;

/// Writes trace events as Soar 9.6's trace text.
#[derive(Debug, Default, Clone, Copy)]
pub(crate) struct TraceText96;

impl TraceText96 {
    /// Appends the text of `event` to `out`; `line_start` says whether the print stream
    /// stands at the start of a line when `out` is empty (its text was taken).
    pub(crate) fn write(
        &self,
        out: &mut String,
        line_start: bool,
        symbols: &Symbols,
        event: &TraceEvent<'_>,
    ) {
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
            TraceEvent::WaterfallAbort {
                id,
                level,
                change_level,
            } => {
                let _ = writeln!(
                    out,
                    "*** Waterfall: aborting firing because ({} * *) level {level} is on or \
                     higher (lower int) than change level {change_level}",
                    symbols.text(id)
                );
            }
            TraceEvent::Wme {
                added,
                wme,
                activation,
            } => {
                out.push_str(if added { "=>WM: " } else { "<=WM: " });
                wme_text_activated(out, symbols, wme, activation);
                out.push('\n');
            }
            TraceEvent::Preference {
                added,
                pref,
                level,
                rule,
            } => {
                fresh_line(out, line_start);
                out.push_str(if added { "+ " } else { "- " });
                pref_text(out, symbols, pref, level, rule);
                out.push('\n');
            }
            TraceEvent::IgnoredPreference { pref, level, rule } => {
                fresh_line(out, line_start);
                out.push_str("+ ");
                pref_text(out, symbols, pref, level, rule);
                out.push_str(" ALREADY SUPPORTED ON TOP LEVEL.  IGNORING.\n");
            }
            TraceEvent::InstantiationPreference { pref, level } => {
                fresh_line(out, line_start);
                out.push(' ');
                pref_text(out, symbols, pref, level, None);
                out.push('\n');
            }
            TraceEvent::MatchQueued { rule, o_support } => {
                fresh_line(out, line_start);
                let list = if o_support { 'o' } else { 'i' };
                let _ = write!(out, "   RETE: putting [{rule}] into ms_{list}_assertions");
            }
            TraceEvent::AssertingInstantiation { rule } => {
                let _ = write!(out, "\n      asserting instantiation: {rule}");
            }
            TraceEvent::InstantiationAsserted => fresh_line(out, line_start),
            TraceEvent::NewMatch { rule, state, level } => {
                let state = state.map_or_else(|| "nil".to_string(), |g| symbols.text(g));
                let _ = writeln!(
                    out,
                    "\nNew match of {rule} in state {state} (level {level}).  Creating instantiation."
                );
            }
            TraceEvent::Firing { rule } => {
                let _ = write!(out, "\nFiring {rule}\n");
            }
            TraceEvent::Retraction { rule } => {
                let _ = write!(out, "\nRetracting {rule}\n");
            }
            TraceEvent::MatchWmes {
                wmes,
                full,
                retracting,
            } => {
                // 9.6's `--fullwmes` prints a firing's WMEs on substates' objects whole and
                // names the others, and all of a retraction's, by their timetags (observed
                // on every agent compared).
                for w in wmes {
                    let top_level = symbols.id_data(w.id).is_none_or(|d| d.level <= 1);
                    if full && (top_level || retracting) {
                        let _ = writeln!(out, "WME with time tag {}", w.timetag);
                    } else if full {
                        out.push(' ');
                        wme_text(out, symbols, w);
                        out.push('\n');
                    } else {
                        let _ = write!(out, " {}", w.timetag);
                    }
                }
                out.push_str(" -->\n");
            }
            TraceEvent::OperatorRemoval { wme, activation } => {
                out.push_str(
                    "\n        REMOVING: Operator from context slot (proposal no longer matches): ",
                );
                if let Some(w) = wme {
                    wme_text_activated(out, symbols, w, activation);
                }
                out.push('\n');
            }
            TraceEvent::GdsAdd {
                goal,
                wme,
                activation,
            } => {
                let _ = write!(out, "Adding to GDS for {}: ", symbols.text(goal));
                wme_text_activated(out, symbols, wme, activation);
                out.push('\n');
            }
            TraceEvent::GdsRemoval {
                goal,
                wme,
                activation,
            } => {
                let g = symbols.text(goal);
                let _ = write!(out, "Removing state {g} because element in GDS changed. WME: ");
                wme_text_activated(out, symbols, wme, activation);
                let _ = write!(out, "\n\n    REMOVING GOAL [{g}] due to change in GDS WME ");
                wme_text_activated(out, symbols, wme, activation);
                out.push('\n');
            }
            TraceEvent::Operator {
                cycle,
                level,
                operator,
                names,
            } => {
                decision_prefix(out, cycle, level);
                out.push_str("   O: ");
                out.push_str(&symbols.text(operator));
                if names.is_empty() {
                    // 9.6 leaves the separating space when the operator has no name.
                    out.push(' ');
                } else {
                    out.push_str(" (");
                    for (i, n) in names.iter().enumerate() {
                        if i > 0 {
                            out.push(' ');
                        }
                        out.push_str(n);
                    }
                    out.push(')');
                }
            }
            TraceEvent::State {
                cycle,
                level,
                state,
                impasse,
            } => {
                decision_prefix(out, cycle, level);
                out.push_str("==>S: ");
                out.push_str(&symbols.text(state));
                out.push(' ');
                if let Some((kind, on_operator)) = impasse {
                    impasse_text(out, kind, on_operator);
                }
            }
            TraceEvent::SystemHalted => out.push_str("\nSystem halted."),
            TraceEvent::RlUpdate {
                rule,
                before,
                after,
            } => {
                out.push_str(&crate::rl::update_line(rule, before, after));
                out.push('\n');
            }
            TraceEvent::Candidate {
                value,
                sum,
                probability,
            } => {
                let _ = write!(out, "\n Candidate {}:  Value (Sum) = {sum:.6}", symbols.text(value));
                if let Some(p) = probability {
                    let _ = write!(out, ", (Prob) = {p:.6}");
                }
            }
            TraceEvent::RlLogError { path, message } => {
                let _ = writeln!(out, "Error: the RL update log {path} cannot be written: {message}");
            }
            TraceEvent::RlGap { started, goal } => {
                let word = if started { "started" } else { "ended" };
                let _ = write!(out, "gap {word} ({})", symbols.text(goal));
            }
            TraceEvent::OperatorRemovalSubstate { state } => {
                let s = symbols.text(state);
                let _ = writeln!(out, "Removing state {s} because of an operator removal.");
            }
            TraceEvent::InconsistentDecision { goal, empty_slot } => {
                let g = symbols.text(goal);
                let _ = writeln!(
                    out,
                    "Removing substates of {g} because the operator last selected in {g} is not\nconsistent with the current preferences."
                );
                // 9.6's `REMOVING CONTEXT SLOT` line only when no operator was selected.
                if empty_slot {
                    let _ = writeln!(
                        out,
                        "\n       REMOVING CONTEXT SLOT: Slot Identifier [{g}] and attribute [operator]"
                    );
                }
                let _ = writeln!(
                    out,
                    "\n          Decision for goal [{g}] is inconsistent.  Replacing it with...."
                );
            }
            TraceEvent::MaxElaborations { next } => {
                let next = match next {
                    Phase::Output => "output",
                    _ => "decide",
                };
                let _ = write!(
                    out,
                    "\nWarning: reached max-elaborations; proceeding to {next} phase."
                );
            }
            TraceEvent::MixedOperatorElaborations { rule } => {
                let _ = write!(
                    out,
                    "WARNING:  Operator elaborations mixed with operator applications\nAssigning i_support to prod {rule}"
                );
            }
            TraceEvent::GoalDepthExceeded { max_depth } => {
                let _ = write!(
                    out,
                    "\nGoal stack depth exceeded {max_depth} on a no-change impasse.\nSoar appears to be in an infinite loop.  \nContinuing to subgoal may cause Soar to \nexceed the program stack of your system.\n"
                );
            }
            TraceEvent::MaxChunksReached => {
                fresh_line(out, line_start);
                out.push_str(
                    "Warning: Maximum number of chunks reached.  Skipping opportunity to learn new rule.\n",
                );
            }
            TraceEvent::LocalNegationRefused { conditions } => {
                // 9.6 leaves the line open after the last condition.
                out.push_str(
                    "\n*** Rule learned that used negative reasoning about local sub-state.***",
                );
                for c in conditions.iter() {
                    let _ = write!(out, "\n   {c}");
                }
            }
            TraceEvent::NotLearning {
                rule,
                state,
                flagged,
            } => {
                let why = if flagged {
                    "was flagged to prevent learning"
                } else {
                    "was not flagged for learning"
                };
                let _ = write!(
                    out,
                    "\nWill not attempt to learn a chunk for match of {rule} because state {state} {why}"
                );
            }
            TraceEvent::LearnedRule { name, text } => {
                let _ = write!(out, "\n\nLearning new rule {name}\n");
                if let Some(text) = text {
                    let _ = writeln!(out, "\n{}", text.trim_end());
                }
            }
            TraceEvent::LearningInterrupt => {
                fresh_line(out, line_start);
                out.push_str("Soar learned a new rule.\n");
            }
            TraceEvent::RhsError {
                message,
                fresh_line: fresh,
            } => {
                if fresh {
                    fresh_line(out, true);
                }
                out.push_str(message);
                out.push('\n');
            }
        }
    }
}

/// The start of a decision line, `\n     N: ` with three spaces more for each level below
/// the top state (Soar manual, chapter 9, "trace").
fn decision_prefix(out: &mut String, cycle: u64, level: u32) {
    let _ = write!(out, "\n{cycle:>6}: ");
    for _ in 1..level {
        out.push_str("   ");
    }
}

/// `(state no-change)`, `(operator tie)`, ...: the slot and kind of an impasse.
fn impasse_text(out: &mut String, kind: ImpasseKind, on_operator: bool) {
    out.push('(');
    out.push_str(if on_operator { "operator" } else { "state" });
    out.push(' ');
    out.push_str(kind.word());
    out.push(')');
}

/// A newline unless the stream stands at the start of a line (9.6's fresh line).
fn fresh_line(out: &mut String, line_start: bool) {
    let at_start = match out.as_bytes().last() {
        Some(&b) => b == b'\n',
        None => line_start,
    };
    if !at_start {
        out.push('\n');
    }
}

/// The character of a preference type in traces (`+`, `-`, `!`, `~`, `=`, `>`, `<`).
pub(crate) fn pref_type_char(k: PrefType) -> char {
    match k {
        PrefType::Acceptable => '+',
        PrefType::Require => '!',
        PrefType::Reject => '-',
        PrefType::Prohibit => '~',
        PrefType::UnaryIndifferent | PrefType::BinaryIndifferent => '=',
        PrefType::NumericIndifferent => '=',
        PrefType::Best | PrefType::Better => '>',
        PrefType::Worst | PrefType::Worse => '<',
    }
}

/// A preference as the level-5 trace shows it, `(S1 ^count 0 +  :O ) [level 2] (rule)`:
/// the referent of a binary or numeric preference after the type, `  :O ` for o-support,
/// the level when below the top state, and the rule whose firing made it.
pub(crate) fn pref_text(
    out: &mut String,
    symbols: &Symbols,
    p: &Preference,
    level: u32,
    rule: Option<&str>,
) {
    let _ = write!(
        out,
        "({} ^{} {} {}",
        symbols.text(p.id),
        symbols.text(p.attr),
        symbols.text(p.value),
        pref_type_char(p.kind)
    );
    if let Some(r) = p.referent {
        out.push(' ');
        out.push_str(&symbols.text(r));
    }
    if p.o_support {
        out.push_str("  :O ");
    }
    out.push(')');
    if level > 1 {
        let _ = write!(out, " [level {level}]");
    }
    if let Some(name) = rule {
        let _ = write!(out, " ({name})");
    }
}

/// `(tt: id ^attr value[ +])`, as `print --internal` shows a WME.
pub(crate) fn wme_text(out: &mut String, symbols: &Symbols, w: &Wme) {
    wme_text_activated(out, symbols, w, None);
}

/// [`wme_text`] with, when working-memory activation is on, the WME's activation before
/// the `+` (`(17: S1 ^name test [2.1])`, 9.6's `print_wme`).
pub(crate) fn wme_text_activated(
    out: &mut String,
    symbols: &Symbols,
    w: &Wme,
    activation: Option<f64>,
) {
    let _ = write!(
        out,
        "({}: {} ^{} {}",
        w.timetag,
        symbols.text(w.id),
        symbols.text(w.attr),
        symbols.text(w.value),
    );
    if let Some(a) = activation {
        let _ = write!(out, " [{}]", crate::wma::activation_text(a));
    }
    out.push_str(if w.acceptable { " +)" } else { ")" });
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
