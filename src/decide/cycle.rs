//! The run loop: `run` goes phase by phase (input, propose, decide, apply, output; Soar
//! manual, 2.5 "Soar's Execution Cycle: Without Substates" and 2.7.8 "Soar's Cycle: With
//! Substates"), counting decisions, phases or elaboration cycles; `init-soar` starts the
//! agent again. The steps the phases take live beside this file:
//!
//! - `elaborate.rs`: one elaboration cycle, which fires at the highest goal with activity and
//!   then at each lower one (the "waterfall");
//! - `fire.rs`: firing an instantiation and retracting one;
//! - `wm_phase.rs`: new preferences into their slots, and the changed slots into working memory;
//! - `decision.rs`: the decision phase, which decides the first decidable operator slot;
//! - `consistency.rs`: a selected operator or an impasse that the preferences no longer give
//!   goes at once;
//! - `substates.rs`: creating a substate for an impasse and removing substates;
//! - `gc.rs`: removing what is no longer linked to a goal.
//!
//! The order of firings, identifiers and timetags follows 9.6's.

use super::state::{Goal, InstId, Phase};
use crate::agent::AgentCore;
use crate::events::AgentEvent;
use crate::symbols::Sym;
use crate::trace_events::TraceEvent;

/// How far `run` goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RunUnit {
    /// Decision cycles, counted at the stop phase (`soar stop-phase`): a run of N stops
    /// there after reaching it N times; a run of 0 goes on to it unless already there.
    Decisions,
    Phases,
    Elaborations,
    /// Output cycles (`run -o`): decision cycles up to one whose output phase found the
    /// output-link changed, or up to `max-nil-output-cycles` cycles without output.
    OutputCycles,
    Forever,
}

impl AgentCore {
    pub(crate) fn operator_sym(&self) -> Sym {
        self.top.operator
    }

    /// `run -g` (Soar manual, ch. 9, `run`: "run agent until a goal retracts"): the next
    /// run stops after the phase in which a goal at the level of the lowest goal now, or
    /// above it, is removed; `None` ends the watch. 9.6 keeps the level of the goal at the
    /// start of the run (checked: the removal of a substate made during the run does not
    /// stop it).
    pub fn stop_on_goal_retraction(&mut self, on: bool) {
        self.decider.goal_break_level =
            on.then(|| self.decider.goals.last().map_or(1, |g| g.level));
    }

    /// Prints `     0: ==>S: S1 ` (trace level ≥ 1), as agent creation and `init-soar` do.
    /// With WME tracing on, the top state's WMEs are traced as 9.6 makes them: the state's
    /// own (timetags 1–10, newest first) before that line, the io link's (11–13) after it
    /// (checked with soar_sml 9.6.5 at `init-soar`).
    pub fn print_initial_state(&mut self) {
        let tops: Vec<crate::wm::Wme> = if self.settings.trace.wmes {
            let mut w: Vec<_> = self.wm.all().into_iter().filter_map(|w| self.wm.get(w).copied()).collect();
            w.retain(|x| x.timetag <= 13);
            w.sort_by_key(|x| std::cmp::Reverse(x.timetag));
            w
        } else {
            Vec::new()
        };
        for w in tops.iter().filter(|w| w.timetag <= 10) {
            self.trace_wme(true, w);
        }
        if self.settings.trace.decisions {
            self.emit(&TraceEvent::State {
                cycle: 0,
                level: 1,
                state: self.top.state,
                impasse: None,
            });
        }
        for w in tops.iter().filter(|w| w.timetag > 10) {
            self.trace_wme(true, w);
        }
    }

    /// Runs `n` units (the `run` command): a decision is counted each time the run reaches
    /// the stop phase (`soar stop-phase`, apply by default), so a run of decisions stops
    /// before it. Returns (decisions executed, rules fired).
    pub fn run(&mut self, n: u64, unit: RunUnit) -> (u64, u64) {
        self.decider.stop_requested = false;
        self.decider.depth_exceeded = false;
        self.decider.rhs_interrupted = false;
        self.decider.ceiling = None;
        self.decider.goal_retracted = false;
        self.decider.break_interrupted = false;
        self.learn.learned_this_run = 0;
        // A run that starts past a ceiling stops before it does anything.
        self.ceiling_reached();
        if self.decider.goals.is_empty() {
            self.decider.goals.push(Goal {
                state: self.top.state,
                level: 1,
                operator: None,
                impasse: None,
                items: Vec::new(),
                wmes: Vec::new(),
                slot_changed: true,
                made: Vec::new(),
                learned_below: false,
                osk: None,
            });
        }
        let start_dc = self.decider.decisions;
        let start_firings = self.decider.firings;
        let mut done = 0u64;
        let stop_phase = self.settings.stop_phase;
        let max_dc_time = u64::try_from(self.settings.max_dc_time).unwrap_or(0);
        let mut decision_start = std::time::Instant::now();
        self.decider.phase_clock = Some(decision_start);
        let max_nil = u64::try_from(self.settings.max_nil_output_cycles.max(1)).unwrap_or(1);
        let mut nil_cycles = 0u64;
        // Read only for output cycles: it walks the output-link.
        let mut output_stamp = if unit == RunUnit::OutputCycles {
            self.output_link_stamp()
        } else {
            (0, 0)
        };
        // A run of decisions that starts past the stop phase of its cycle (in the output
        // phase, with the stop phase apply) counts the end of that cycle as one decision
        // (as 9.6 does: `run 2` from the output phase stops at the next stop phase).
        let cycle_order = |p: Phase| p as u8;
        let mut owes_cycle_end = unit == RunUnit::Decisions
            && self
                .decider
                .phase
                .is_some_and(|p| cycle_order(p) > cycle_order(stop_phase));
        while !self.decider.halted
            && !self.decider.stop_requested
            && !self.decider.depth_exceeded
            && !self.decider.rhs_interrupted
            && !self.decider.goal_retracted
            && !self.decider.break_interrupted
            && match unit {
                RunUnit::Forever => true,
                RunUnit::Decisions => {
                    done < n || self.decider.phase.unwrap_or(Phase::Input) != stop_phase
                }
                _ => done < n,
            }
        {
            let phase = self.decider.phase.unwrap_or(Phase::Input);
            let e_before = self.decider.e_cycles;
            // `run -e` stops after each elaboration cycle, inside the phase.
            self.do_phase(phase, unit == RunUnit::Elaborations);
            self.ceiling_reached();
            match unit {
                RunUnit::Decisions | RunUnit::Forever => {
                    if phase != stop_phase && self.decider.phase == Some(stop_phase) {
                        done += 1;
                    }
                    if owes_cycle_end && phase == Phase::Output && self.decider.phase != Some(phase)
                    {
                        owes_cycle_end = false;
                        done += 1;
                    }
                }
                RunUnit::OutputCycles => {
                    if phase == Phase::Output && self.decider.phase != Some(Phase::Output) {
                        let stamp = self.output_link_stamp();
                        nil_cycles += 1;
                        if stamp != output_stamp || nil_cycles >= max_nil {
                            done += 1;
                            nil_cycles = 0;
                        }
                        output_stamp = stamp;
                    }
                }
                RunUnit::Phases => done += 1,
                RunUnit::Elaborations => done += (self.decider.e_cycles - e_before).max(1),
            }
            // `max-dc-time`: a decision cycle that takes too long interrupts the run.
            if max_dc_time > 0 && self.decider.phase != Some(phase) {
                if phase == Phase::Output {
                    decision_start = std::time::Instant::now();
                } else if decision_start.elapsed().as_secs() >= max_dc_time {
                    self.decider.stop_requested = true;
                }
            }
            // Endless state no-changes stop at max-goal-depth.
            if unit == RunUnit::Forever && done > 1_000_000_000 {
                break;
            }
        }
        self.decider.phase_clock = None;
        if self.decider.halted {
            // The end of an episode: the top state's RL rules take the last reward.
            self.rl_halted();
        }
        if (self.decider.halted || self.decider.depth_exceeded) && self.decider.phase.is_some() {
            self.emit(&TraceEvent::SystemHalted);
        }
        (
            self.decider.decisions - start_dc,
            self.decider.firings - start_firings,
        )
    }

    /// Runs a phase; with `one_cycle`, at most one elaboration cycle of the propose or apply
    /// phase, which then resumes where it stopped on the next call.
    fn do_phase(&mut self, phase: Phase, one_cycle: bool) {
        if self.events.any() && !self.decider.phase_started {
            self.events.send(&AgentEvent::BeforePhase(phase));
        }
        let start = self
            .decider
            .phase_clock
            .unwrap_or_else(std::time::Instant::now);
        self.do_phase_timed(phase, one_cycle);
        self.report_break_hits_in(phase);
        self.release_justifications();
        let i = match phase {
            Phase::Input => 0,
            Phase::Propose => 1,
            Phase::Decide => 2,
            Phase::Apply => 3,
            Phase::Output => 4,
        };
        let end = std::time::Instant::now();
        self.decider.phase_time[i] += end.saturating_duration_since(start);
        if self.decider.phase_clock.is_some() {
            self.decider.phase_clock = Some(end);
        }
        if phase == Phase::Output && self.decider.phase == Some(Phase::Input) {
            self.end_cycle_stats();
        }
        // 9.6 samples the WM size each time it leaves its phase function: at the end of
        // each phase, and under `run -e` after each elaboration cycle as well.
        let phase_ended = self.decider.phase != Some(phase);
        if phase_ended || one_cycle {
            self.sample_wm_size();
        }
        if phase_ended && self.events.any() {
            self.events.send(&AgentEvent::AfterPhase(phase));
        }
    }

    /// The interrupt flag is set (Ctrl-C, [`crate::Agent::interrupt_flag`]): the run stops
    /// after the current elaboration cycle, and the phase goes on at the next run.
    fn interrupt_requested(&mut self) -> bool {
        let set = self
            .interrupt
            .as_ref()
            .is_some_and(|f| f.load(std::sync::atomic::Ordering::Relaxed));
        if set {
            self.decider.stop_requested = true;
        }
        set
    }

    /// The WM additions and removals since this decider started, as `stats` counts them:
    /// an input WME counts when the input phase adds it, as in 9.6 (soar-sml 9.6.5 counts
    /// a client's update only once it is applied).
    pub(crate) fn stats_wm_changes(&self) -> (u64, u64) {
        let d = &self.decider;
        (
            self.wm.additions() - d.wm_base.0 - self.pending_input_additions(),
            self.wm.removals() - d.wm_base.1,
        )
    }

    /// Records the decision cycle whose output phase has just ended (9.6 records its
    /// per-cycle statistics there, so a cycle that halts before its output phase has none).
    fn end_cycle_stats(&mut self) {
        let (additions, removals) = self.stats_wm_changes();
        let d = &mut self.decider;
        let time = d.phase_time.iter().sum();
        // The output phase has already counted this cycle.
        let cycle = d.d_cycle_count - 1;
        d.cycle_stats
            .end_cycle(cycle, time, additions + removals, d.firings);
    }

    /// A sample of the WM size for `stats`, taken at the end of each phase.
    fn sample_wm_size(&mut self) {
        let n = self.wm.len() as u64;
        self.decider.wm_size_sum += n;
        self.decider.wm_size_samples += 1;
        self.decider.wm_size_max = self.decider.wm_size_max.max(n);
    }

    fn do_phase_timed(&mut self, phase: Phase, one_cycle: bool) {
        // max-chunks counts per phase.
        self.learn.chunks_this_phase = 0;
        self.learn.dupes_this_phase.clear();
        match phase {
            Phase::Input => {
                self.trace_phase(TraceEvent::PhaseBegin(Phase::Input));
                self.run_input_callbacks();
                self.replay_input_changes();
                self.capture_input_changes();
                self.apply_input_changes();
                self.epmem_trace_present();
                self.classify_new_matches();
                self.end_queued_matches();
                self.trace_phase(TraceEvent::PhaseEnd(Phase::Input));
                self.decider.phase = Some(Phase::Propose);
            }
            Phase::Propose => {
                if !self.decider.phase_started {
                    self.trace_phase(TraceEvent::PhaseBegin(Phase::Propose));
                    self.decider.e_cycles_this_phase = 0;
                    self.decider.phase_started = true;
                    self.decider.last_wave_o_support = false;
                    self.decider.decision_inconsistent = false;
                }
                while self.has_pending(false) && !self.decider.halted {
                    if !self.elaboration_cycle() {
                        break;
                    }
                    // An inconsistent decision sends the phase on to the decision.
                    if std::mem::take(&mut self.decider.decision_inconsistent) {
                        break;
                    }
                    if self.has_pending(false) && self.max_elaborations_reached(Phase::Decide) {
                        break;
                    }
                    if (one_cycle || self.interrupt_requested() || self.ceiling_reached())
                        && self.has_pending(false)
                        && !self.decider.halted
                    {
                        return;
                    }
                }
                self.decider.phase_started = false;
                // A halt with firings still pending ends the phase without its END line
                // (checked on 9.6).
                if !(self.decider.halted && self.has_pending(false)) {
                    self.trace_phase(TraceEvent::PhaseEnd(Phase::Propose));
                }
                self.decider.phase = Some(Phase::Decide);
            }
            Phase::Decide => {
                self.trace_phase(TraceEvent::PhaseBegin(Phase::Decide));
                self.decide_context_slots();
                self.reduce_exploration_parameters();
                self.classify_new_matches();
                self.end_queued_matches();
                // With `epmem phase selection`, after the decision (9.6's place for it).
                self.epmem_selection_phase();
                self.trace_phase(TraceEvent::PhaseEnd(Phase::Decide));
                self.decider.decisions += 1;
                self.decider.e_cycles_this_phase = 0;
                self.decider.phase = Some(Phase::Apply);
            }
            Phase::Apply => {
                if !self.decider.phase_started {
                    self.trace_phase(TraceEvent::PhaseBegin(Phase::Apply));
                    self.decider.phase_started = true;
                    self.decider.last_wave_o_support = true;
                    self.decider.decision_inconsistent = false;
                }
                while self.has_pending_in_apply() && !self.decider.halted {
                    if !self.elaboration_cycle() {
                        break;
                    }
                    // An inconsistent decision sends the phase on to the output phase.
                    if std::mem::take(&mut self.decider.decision_inconsistent) {
                        break;
                    }
                    if self.has_pending_in_apply() && self.max_elaborations_reached(Phase::Output) {
                        break;
                    }
                    if (one_cycle || self.interrupt_requested() || self.ceiling_reached())
                        && self.has_pending(true)
                        && !self.decider.halted
                    {
                        return;
                    }
                }
                self.decider.phase_started = false;
                if !(self.decider.halted && self.has_pending(true)) {
                    self.trace_phase(TraceEvent::PhaseEnd(Phase::Apply));
                }
                self.decider.phase = Some(Phase::Output);
            }
            Phase::Output => {
                self.trace_phase(TraceEvent::PhaseBegin(Phase::Output));
                self.run_output_callbacks();
                // Semantic memory's commands are processed at the end of the output phase
                // (observed on soar-sml 9.6.5: their results are traced in it).
                self.smem_output_phase();
                // Activation histories, then forgetting, then episodic memory, before
                // apoptosis (9.6's order: a query's cue weighs the activations this
                // decision's references have made, and forgotten WMEs are not stored).
                if self.wma.on() {
                    self.wma_end_decision();
                }
                self.epmem_output_phase();
                self.apoptosis_end_decision();
                self.trace_phase(TraceEvent::PhaseEnd(Phase::Output));
                self.decider.d_cycle_count += 1;
                self.decider.phase = Some(Phase::Input);
            }
        }
    }

    /// Whether the phase has had its `max-elaborations` cycles, with a warning. Asked only
    /// while something is left to fire: a phase whose last allowed cycle reached
    /// quiescence ends without the warning (checked with soar_sml 9.6.5).
    fn max_elaborations_reached(&mut self, next: Phase) -> bool {
        if self.decider.e_cycles_this_phase >= self.settings.max_elaborations.max(1) as u64 {
            if self.settings.warnings {
                self.emit(&TraceEvent::MaxElaborations { next });
            }
            return true;
        }
        false
    }

    /// `has_pending(true)` for the apply phase: retractions of instantiations whose goal
    /// has gone (a substate removed in this phase) do not keep it going; 9.6 processes
    /// them in the next propose phase, with no active goal.
    /// Justifications retract the same way (9.6's matcher holds them like rules).
    fn has_pending_in_apply(&self) -> bool {
        if self.matches.has_assertions() {
            return true;
        }
        let live = |i: InstId| {
            self.decider.insts[i]
                .goal
                .is_none_or(|g| self.symbols.is_goal(g))
        };
        let justification = |&(i, serial, _): &(InstId, u64, usize)| {
            let inst = &self.decider.insts[i];
            inst.alive && inst.serial == serial && live(i)
        };
        self.decider.justification_retractions.iter().any(justification)
            || self.decider.waiting_retractions.iter().any(|&i| live(i))
            || self.matches.retractions.iter().any(|k| {
                let Some(&i) = self.decider.inst_by_token.get(k) else {
                    return true;
                };
                live(i)
            })
    }

    /// Is there an assertion (of i-support only, unless `any`) or a retraction to process?
    pub(super) fn has_pending(&self, any: bool) -> bool {
        // Justifications that lost a WME retract like rules (Soar manual, chapter 2,
        // "Justifications: Support for results").
        if !self.matches.retractions.is_empty()
            || !self.decider.justification_retractions.is_empty()
            || !self.decider.waiting_retractions.is_empty()
        {
            return true;
        }
        self.matches.assertions.iter().any(|&(p, t)| {
            (p, t) != crate::agent::MatchSet::GONE && (any || !self.is_o_supported(p, t))
        })
    }

    fn run_input_callbacks(&mut self) {
        if let Some(mut cb) = self.input_callback.take() {
            let start = std::time::Instant::now();
            cb(self);
            self.decider.input_fn_time += start.elapsed();
            if self.input_callback.is_none() {
                self.input_callback = Some(cb);
            }
        }
    }

    fn run_output_callbacks(&mut self) {
        if let Some(mut cb) = self.output_callback.take() {
            let start = std::time::Instant::now();
            cb(self);
            self.decider.output_fn_time += start.elapsed();
            if self.output_callback.is_none() {
                self.output_callback = Some(cb);
            }
        }
    }

    /// `init-soar` (`soar init`): working memory, preferences, the goal stack, identifier
    /// counters and timetags start again; rules (and chunks) stay.
    pub fn init_soar(&mut self) {
        // The substates go first, lowest first: each ends its RL episode, untraced (observed
        // on 9.6); the top state's pending RL rules are dropped.
        if self.rl_enabled() {
            let traced = std::mem::replace(&mut self.settings.trace.rl, false);
            let substates: Vec<Sym> = self.decider.goals.iter().skip(1).map(|g| g.state).collect();
            for g in substates.into_iter().rev() {
                self.rl_goal_ends(g, false);
            }
            self.settings.trace.rl = traced;
        }
        // Input changes not applied yet go with the rest of working memory.
        self.inputs.queue.clear();
        // 9.6 traces none of it: no `<=WM:` lines, no WMA `remove` lines, no matches queued
        // by the removals (`trace --assertions`).
        let traced = std::mem::take(&mut self.settings.trace);
        self.clear_goal_stack();
        self.settings.trace = traced;
        self.matches.clear();
        // Tracking stays on (its rows go), as in 9.6.
        let tracking = self.decider.cycle_stats.tracking;
        self.decider = crate::decide::state::DecideState::new();
        self.decider.cycle_stats.tracking = tracking;
        self.decider.wm_base = (self.wm.additions(), self.wm.removals());
        self.learn.reset_for_init();
        self.rl.reinitialize();
        // `rl -t init`, as 9.6 does at every init-soar: the RL trace starts from its roots.
        self.rl_trace_init(None);
        self.smem_reinitialize();
        // A file stays with the agent: 9.6 opens it again at once (an empty store in memory
        // is opened at the next episode, with the same effect).
        let reopen = self.epmem.is_open() && self.epmem.params.get("database").as_deref() == Some("file");
        self.epmem_close();
        self.epmem.present_trace.clear();
        self.epmem.timers.reset();
        self.wma.reinitialize();
        self.decider.freed_prefs_log.clear();
        self.symbols.reset_id_counters();
        self.wm.reset_timetags();
        let old = self.top;
        self.top = crate::agent::create_top_state(
            &mut self.symbols,
            &mut self.wm,
            &mut self.rete,
            &mut self.matches,
            Some(old),
        );
        self.trace_queued_matches_now();
        if reopen {
            self.epmem_attach();
        }
    }
}
