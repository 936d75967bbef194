//! `run`, `soar init`, `firing-counts` and `stats` over the decision cycle (Soar manual,
//! ch. 9, `run`, `soar`, `production`, `stats`).

use super::options::{self, opt, opt_arg};
use super::{CmdResult, Ctx, Interpreter};
use crate::decide::cycle::RunUnit;
use crate::source::Diagnostic;

/// A `run` count as 9.6 reads it: the leading integer (`1.5` is 1), which must not be
/// negative (`Count must be positive.`, though 0 is accepted).
fn run_count(word: &str) -> Result<u64, &'static str> {
    let digits_end = word
        .char_indices()
        .find(|&(i, c)| !(c.is_ascii_digit() || (i == 0 && (c == '-' || c == '+'))))
        .map_or(word.len(), |(i, _)| i);
    let n: i64 = word[..digits_end]
        .parse()
        .map_err(|_| "Integer count expected.")?;
    u64::try_from(n).map_err(|_| "Count must be positive.")
}

/// How a run went (see [`Interpreter::run_agent`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct RunReport {
    /// Decision cycles, as `run` reports them (9.6's count, see below).
    pub decisions: u64,
    /// Decision phases run.
    pub decided: u64,
    /// Rule firings.
    pub fired: u64,
    /// The agent is halted (now, whether or not it halted in this run).
    pub halted: bool,
    /// A stop request, an interrupt flag or the `interrupt` RHS function ended the run.
    pub interrupted: bool,
    /// The goal stack reached `max-goal-depth`.
    pub depth_exceeded: bool,
    /// A ceiling of `limits` stopped the run.
    pub ceiling: bool,
}

impl Interpreter {
    /// `run [n] [-d|-e|-p|-o] [-f] [-g]`: no count and no unit runs until halted; a count alone is
    /// decisions; a unit alone is one of it (Soar manual, ch. 9, `run`).
    pub(super) fn cmd_run(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let specs = [
            opt('d', "decision"),
            opt('e', "elaboration"),
            opt('p', "phase"),
            opt('f', "forever"),
            opt('o', "output"),
            opt('s', "self"),
            opt('u', "update"),
            opt('n', "noupdate"),
            opt('g', "goal"),
            opt_arg('i', "interleave"),
        ];
        let parsed = options::parse(args, &specs).map_err(|m| ctx.error(m))?;
        if parsed.args.len() > 1 {
            return Err(ctx.error(
                "Syntax: run  [-f|count]\nrun -[d|e|o|p][s][un][g] [f|count]\nrun -[d|e|o|p][un] count [-i e|p|d|o]",
            ));
        }
        let count = match parsed.args.first() {
            Some(c) => Some(run_count(c).map_err(|m| {
                Diagnostic::error(m)
                    .at(ctx.arg_span(0))
                    .with_label("not a count")
            })?),
            None => None,
        };
        let unit = if parsed.has("elaboration") {
            RunUnit::Elaborations
        } else if parsed.has("phase") {
            RunUnit::Phases
        } else if parsed.has("output") && count.is_some() {
            RunUnit::OutputCycles
        } else if parsed.has("output") {
            RunUnit::Forever
        } else if parsed.has("decision") || count.is_some() {
            RunUnit::Decisions
        } else {
            RunUnit::Forever
        };
        if let Some(step) = parsed.value("interleave") {
            check_interleave(step, unit).map_err(|m| ctx.error(m))?;
        }
        // A count of 0 is an error but for decisions, where it runs on to the stop phase
        // (checked on the official kernel).
        if count == Some(0) && unit != RunUnit::Decisions {
            return Err(ctx.error("Count must be positive."));
        }
        let n = count.unwrap_or(1);
        // `-g`: stop when a goal at the level of the lowest goal, or above, goes; a run
        // without it clears the watch (as 9.6 does).
        self.agent.stop_on_goal_retraction(parsed.has("goal"));
        let RunReport {
            decisions, fired, ..
        } = self.run_agent(n, unit);
        let dc = match decisions {
            0 | 1 => format!("{decisions} decision cycle executed."),
            d => format!("{d} decision cycles executed."),
        };
        let rules = match fired {
            0 => "No rules fired.".to_string(),
            1 => "1 rule fired.".to_string(),
            f => format!("{f} rules fired."),
        };
        let halted = if self.agent.decider.halted {
            "\nAn agent halted during the run."
        } else if self.agent.decider.depth_exceeded || self.agent.decider.rhs_interrupted {
            "\nRun stopped (interrupted)."
        } else {
            ""
        };
        // 9.6 adds how many rules the run learned.
        let learned = match self.agent.learn.learned_this_run {
            0 => String::new(),
            1 => "1 new rule learned.".to_string(),
            n => format!("{n} new rules learned."),
        };
        Ok(format!("\n\n--> {dc} {rules} {learned}{halted}"))
    }

    /// Runs the agent `n` units as `run` does: the trace goes to the print stream, with
    /// 9.6's notices of a halt or an interrupt; the report says how it ended.
    pub(crate) fn run_agent(&mut self, n: u64, unit: RunUnit) -> RunReport {
        let dc_before = self.agent.decider.d_cycle_count;
        let decided_before = self.agent.decider.decisions;
        let halted_before = self.agent.decider.halted;
        // A halted agent does not run (and 9.6 prints no second "System halted.").
        let (fired, interrupted) = if halted_before {
            (0, false)
        } else {
            self.sync_line_start();
            let hooks = self.begin_run_hooks();
            let (_, fired) = self.agent.run(n, unit);
            (fired, self.end_run_hooks(hooks))
        };
        self.run_interrupted_in_source = interrupted && !self.source_stack.is_empty();
        self.flush_agent_output();
        if self.agent.decider.halted && !halted_before {
            // 9.6's kernel ends its halt message with a newline (the print column is 0 after
            // it), then its run scheduler says why the run ended; that line does not move
            // the kernel's print column (checked: a `print` after a halt wraps from 0).
            self.print_col.set(0);
            self.events.push(super::Event::Text(
                "\nInterrupt received.This Agent halted.".to_string(),
            ));
        }
        if self.agent.decider.depth_exceeded {
            // 9.6's two interrupt notices: its scheduler's and its run loop's.
            self.print_col.set(0);
            self.events.push(super::Event::Text(
                "\nInterrupt received.Interrupt received.".to_string(),
            ));
        }
        if self.agent.decider.rhs_interrupted && !self.agent.decider.halted {
            self.events
                .push(super::Event::Text("Interrupt received.".to_string()));
        }
        if self.agent.decider.goal_retracted && !self.agent.decider.halted {
            // The kernel's line ends with a newline; the scheduler's does not move the
            // print column, as after a halt.
            self.print_col.set(0);
            self.events.push(super::Event::Text(
                "\nStopped due to substate (goal) retraction.\nInterrupt received.".to_string(),
            ));
        }
        if self.agent.decider.break_interrupted && !self.agent.decider.halted {
            // `production break`: 9.6's reason for stopping, then its scheduler's notice.
            self.print_col.set(0);
            self.events.push(super::Event::Text(
                "\n:interrupt\nInterrupt received.".to_string(),
            ));
        }
        if interrupted {
            self.events
                .push(super::Event::Text("\nInterrupted.".to_string()));
        }
        // 9.6 reports the change of the decision-cycle counter, measured from 0 while the
        // counter is still at its initial 1 (as observed on the official kernel): so the
        // second `run 1` after `init-soar` reports 2 cycles, and a run that ends inside the
        // cycle it started in reports "0 decision cycle" (singular, as printed by 9.6).
        let last_dc = if dc_before > 1 { dc_before } else { 0 };
        let decisions = self.agent.decider.d_cycle_count.saturating_sub(last_dc);
        RunReport {
            decisions,
            decided: self.agent.decider.decisions - decided_before,
            fired,
            halted: self.agent.decider.halted,
            interrupted: interrupted
                || self.agent.decider.rhs_interrupted
                || self.agent.decider.goal_retracted
                || self.agent.decider.break_interrupted
                || (self.agent.decider.stop_requested && !self.agent.decider.halted),
            depth_exceeded: self.agent.decider.depth_exceeded,
            ceiling: self.agent.decider.ceiling.is_some(),
        }
    }

    /// Moves the agent's trace output into the event stream.
    pub(super) fn flush_agent_output(&mut self) {
        let s = &self.agent.settings;
        if !(s.output_enabled && s.output_callbacks) {
            // `output enabled off`: the trace and what rules print are dropped.
            self.agent.output.clear();
        }
        if !self.agent.output.is_empty() {
            // The agent's text goes on after any `*` marks: no newline is owed them any more
            // (9.6 prints both as they come).
            self.after_star = false;
            let text = std::mem::take(&mut self.agent.output);
            super::advance_col(&self.print_col, &text);
            self.events.push(super::Event::Text(text));
        }
    }

    pub(super) fn cmd_init(&mut self) -> CmdResult {
        self.reinitialize();
        Ok("\nAgent reinitialized.\n".into())
    }

    /// `init-soar`'s work: the agent starts again (the initial state is traced, input
    /// WMEs are put back) and the program's listeners hear of it.
    pub(super) fn reinitialize(&mut self) {
        self.sync_line_start();
        self.agent.init_soar();
        self.agent.print_initial_state();
        self.agent.report_break_hits();
        self.agent.reinstate_inputs();
        if self.agent.events.any() {
            self.agent
                .events
                .send(&crate::events::AgentEvent::InitSoar);
        }
        self.flush_agent_output();
    }

    /// `production firing-counts [N] [rule...]`: `%6d:  name`, most fired first; a number
    /// keeps the N most fired (as 9.6: `fc 25`).
    pub(super) fn cmd_firing_counts(&mut self, _ctx: &Ctx, args: &[String]) -> CmdResult {
        let limit = args.first().and_then(|a| a.parse::<usize>().ok());
        let names = &args[usize::from(limit.is_some())..];
        let mut rows: Vec<(u64, String)> = self
            .agent
            .productions()
            .filter(|p| names.is_empty() || names.iter().any(|n| *n == *p.name))
            .map(|p| {
                let id = self.agent.loaded(&p.name).map(|l| l.id);
                (id.map_or(0, |i| self.agent.firing_count(i)), p.name.to_string())
            })
            .collect();
        if rows.is_empty() {
            return Err(
                Diagnostic::error("No productions in memory of those type(s).")
                    .at(_ctx.cmd.span)
                    .with_label("nothing to count"),
            );
        }
        rows.sort_by_key(|r| std::cmp::Reverse(r.0));
        if let Some(n) = limit {
            rows.truncate(n);
        }
        Ok(rows
            .iter()
            .map(|(n, name)| format!("{n:>6}:  {name}\n"))
            .collect())
    }
}

/// `run -i e|p|d|o`: the step by which the kernel interleaves its agents' runs. With one
/// agent it changes nothing, but 9.6 checks it: a step of the run's unit or finer, where a
/// phase run takes phases only and an elaboration run elaborations only (checked on
/// soar-sml 9.6.5).
fn check_interleave(step: &str, unit: RunUnit) -> Result<(), String> {
    let allowed: &[&str] = match unit {
        RunUnit::Elaborations => &["e"],
        RunUnit::Phases => &["p"],
        RunUnit::Decisions => &["e", "p", "d"],
        RunUnit::OutputCycles | RunUnit::Forever => &["e", "p", "d", "o"],
    };
    if !["e", "p", "d", "o"].contains(&step) {
        return Err(format!("Invalid interleave switch: {step}"));
    }
    if !allowed.contains(&step) {
        return Err("Run type and interleave setting incompatible.".to_string());
    }
    Ok(())
}
