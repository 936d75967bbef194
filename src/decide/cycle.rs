//! The run loop (spec §3a–§3e): phases, elaboration cycles, firing and retracting
//! instantiations, slots and working-memory changes, operator selection, impasses and
//! substates. The order of firings, identifiers and timetags follows 9.6's; each
//! elaboration cycle fires at the highest goal with activity and then at each lower one
//! (the "waterfall", spec §3b).

use super::compiled::{self, Act, CompiledRule, Term};
use super::procedure::{self, NumericMode, Outcome, Policy, Pref, PrefType};
use super::slot::SlotId;
use super::state::{Goal, ImpasseKind, InstId, Instantiation, Phase, PrefId, Preference, Slot};
use crate::agent::Agent;
use crate::rete::{ProdId, TokId};
use crate::symbols::{Sym, SymData};
use crate::wm::WmeId;
use rustc_hash::{FxHashMap, FxHashSet};
use std::rc::Rc;

/// How far `run` goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RunUnit {
    Decisions,
    Phases,
    Elaborations,
    Forever,
}

impl Agent {
    fn out(&mut self, s: &str) {
        self.output.push_str(s);
    }

    fn operator_sym(&self) -> Sym {
        self.top.operator
    }

    /// The decision-line prefix: dc right-justified to 6, then 3 spaces per level below the
    /// top (spec §6c).
    fn decision_prefix(&self, level: u32) -> String {
        format!(
            "\n{:>6}: {}",
            self.decider.d_cycle_count,
            "   ".repeat(level.saturating_sub(1) as usize)
        )
    }

    /// Prints `     0: ==>S: S1 ` (trace level ≥ 1), as agent creation and `init-soar` do.
    pub fn print_initial_state(&mut self) {
        if self.settings.trace.decisions {
            let s = format!("\n{:>6}: ==>S: {} ", 0, self.symbols.text(self.top.state));
            self.out(&s);
        }
    }

    /// Runs `n` units (spec §3a, `run`): decisions stop before the apply phase, as 9.6's
    /// default stop phase does. Returns (decisions executed, rules fired).
    pub fn run(&mut self, n: u64, unit: RunUnit) -> (u64, u64) {
        self.decider.stop_requested = false;
        self.decider.depth_exceeded = false;
        self.decider.rhs_interrupted = false;
        self.learn.learned_this_run = 0;
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
            });
        }
        let start_dc = self.decider.decisions;
        let start_firings = self.decider.firings;
        let mut done = 0u64;
        while !self.decider.halted
            && !self.decider.stop_requested
            && !self.decider.depth_exceeded
            && !self.decider.rhs_interrupted
            && (unit == RunUnit::Forever || done < n)
        {
            let phase = self.decider.phase.unwrap_or(Phase::Input);
            let e_before = self.decider.e_cycles;
            // `run -e` stops after each elaboration cycle, inside the phase (spec §6a).
            self.do_phase(phase, unit == RunUnit::Elaborations);
            match unit {
                RunUnit::Decisions | RunUnit::Forever => {
                    if phase == Phase::Decide {
                        done += 1;
                    }
                }
                RunUnit::Phases => done += 1,
                RunUnit::Elaborations => done += (self.decider.e_cycles - e_before).max(1),
            }
            // Endless state no-changes stop at max-goal-depth (spec §3a).
            if unit == RunUnit::Forever && done > 1_000_000_000 {
                break;
            }
        }
        if (self.decider.halted || self.decider.depth_exceeded) && self.decider.phase.is_some() {
            self.out("\nSystem halted.");
        }
        (
            self.decider.decisions - start_dc,
            self.decider.firings - start_firings,
        )
    }

    /// Runs a phase; with `one_cycle`, at most one elaboration cycle of the propose or apply
    /// phase, which then resumes where it stopped on the next call.
    fn do_phase(&mut self, phase: Phase, one_cycle: bool) {
        let start = std::time::Instant::now();
        self.do_phase_timed(phase, one_cycle);
        let i = match phase {
            Phase::Input => 0,
            Phase::Propose => 1,
            Phase::Decide => 2,
            Phase::Apply => 3,
            Phase::Output => 4,
        };
        self.decider.phase_time[i] += start.elapsed();
        // 9.6 samples the WM size once per phase, at its end (a phase left mid-way by
        // `run -e` is sampled when it ends).
        if self.decider.phase != Some(phase) {
            self.sample_wm_size();
        }
    }

    /// A sample of the WM size for `stats`, taken at the end of each phase.
    fn sample_wm_size(&mut self) {
        let n = self.wm.len() as u64;
        self.decider.wm_size_sum += n;
        self.decider.wm_size_samples += 1;
        self.decider.wm_size_max = self.decider.wm_size_max.max(n);
    }

    fn do_phase_timed(&mut self, phase: Phase, one_cycle: bool) {
        // max-chunks counts per phase (spec §4).
        self.learn.chunks_this_phase = 0;
        self.learn.dupes_this_phase.clear();
        match phase {
            Phase::Input => {
                self.trace_phase("\n--- Input Phase --- \n");
                self.run_input_callbacks();
                self.apply_input_changes();
                self.classify_new_matches();
                self.trace_phase("\n--- END Input Phase --- \n");
                self.decider.phase = Some(Phase::Propose);
            }
            Phase::Propose => {
                if !self.decider.phase_started {
                    self.trace_phase("\n--- Propose Phase ---\n");
                    self.decider.e_cycles_this_phase = 0;
                    self.decider.phase_started = true;
                }
                while self.has_pending(false) && !self.decider.halted {
                    if !self.elaboration_cycle() {
                        break;
                    }
                    if self.max_elaborations_reached("decide") {
                        break;
                    }
                    if one_cycle && self.has_pending(false) && !self.decider.halted {
                        return;
                    }
                }
                self.decider.phase_started = false;
                // A halt with firings still pending ends the phase without its END line
                // (checked on 9.6).
                if !(self.decider.halted && self.has_pending(false)) {
                    self.trace_phase("\n--- END Propose Phase ---\n");
                }
                self.decider.phase = Some(Phase::Decide);
            }
            Phase::Decide => {
                self.trace_phase("\n--- Decision Phase ---\n");
                self.decide_context_slots();
                self.classify_new_matches();
                self.trace_phase("\n--- END Decision Phase ---\n");
                self.decider.decisions += 1;
                self.decider.e_cycles_this_phase = 0;
                self.decider.phase = Some(Phase::Apply);
            }
            Phase::Apply => {
                if !self.decider.phase_started {
                    self.trace_phase("\n--- Application Phase ---\n");
                    self.decider.phase_started = true;
                }
                while self.has_pending_in_apply() && !self.decider.halted {
                    if !self.elaboration_cycle() {
                        break;
                    }
                    if self.max_elaborations_reached("output") {
                        break;
                    }
                    if one_cycle && self.has_pending(true) && !self.decider.halted {
                        return;
                    }
                }
                self.decider.phase_started = false;
                if !(self.decider.halted && self.has_pending(true)) {
                    self.trace_phase("\n--- END Application Phase ---\n");
                }
                self.decider.phase = Some(Phase::Output);
            }
            Phase::Output => {
                self.trace_phase("\n--- Output Phase ---\n");
                self.run_output_callbacks();
                self.trace_phase("\n--- END Output Phase ---\n");
                self.decider.d_cycle_count += 1;
                self.decider.phase = Some(Phase::Input);
            }
        }
    }

    fn max_elaborations_reached(&mut self, next: &str) -> bool {
        if self.decider.e_cycles_this_phase >= self.settings.max_elaborations.max(1) as u64 {
            if self.settings.warnings {
                let s = format!("\nWarning: reached max-elaborations; proceeding to {next} phase.");
                self.out(&s);
            }
            return true;
        }
        false
    }

    /// `has_pending(true)` for the apply phase: retractions of instantiations whose goal
    /// has gone (a substate removed in this phase) do not keep it going; 9.6 processes
    /// them in the next propose phase, with no active goal.
    fn has_pending_in_apply(&self) -> bool {
        if self.matches.has_assertions() || !self.decider.justification_retractions.is_empty() {
            return true;
        }
        let live = |i: InstId| {
            self.decider.insts[i as usize]
                .goal
                .is_none_or(|g| self.symbols.is_goal(g))
        };
        self.decider.waiting_retractions.iter().any(|&i| live(i))
            || self.matches.retractions.iter().any(|k| {
                let Some(&i) = self.decider.inst_by_token.get(k) else {
                    return true;
                };
                live(i)
            })
    }

    /// Is there an assertion (of i-support only, unless `any`) or a retraction to process?
    fn has_pending(&self, any: bool) -> bool {
        // Justifications that lost a WME retract like rules (spec §4).
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

    /// Decides the support of the matches made since the last call, as 9.6's matcher does
    /// when it queues them, with its warning for rules that both elaborate and apply the
    /// operator (spec §3c, E:t24).
    pub(crate) fn classify_new_matches(&mut self) {
        self.matches.compact();
        let n = self.matches.assertions.len();
        for i in 0..n {
            let key = self.matches.assertions[i];
            if self.matches.support.contains_key(&key) {
                continue;
            }
            self.compiled_rule(key.0);
            let s = crate::decide::support::match_support(self, key.0, key.1);
            if s.mixed && self.settings.warnings {
                let name = self.production_name(key.0).to_string();
                self.out(&format!(
                    "WARNING:  Operator elaborations mixed with operator applications\nAssigning i_support to prod {name}"
                ));
            }
            self.matches.support.insert(key, s.o_support);
        }
    }

    /// One elaboration cycle (spec §3a, §3b): the pending matches of one support type fire
    /// at the active goal and then at each lower goal with activity, the active goal's
    /// retractions follow, then the working-memory changes happen together.
    fn elaboration_cycle(&mut self) -> bool {
        self.decider.e_cycles += 1;
        self.decider.e_cycles_this_phase += 1;
        let apply = self.decider.phase == Some(Phase::Apply);
        let retractions = std::mem::take(&mut self.matches.retractions);
        self.matches.compact();
        let mut pending = std::mem::take(&mut self.matches.assertions);
        let mut sc = std::mem::take(&mut self.decider.cycle_scratch);
        // Token ids are reused: resolve retractions to their instantiations before new
        // matches (possibly on a reused id) fire. Those a higher goal kept waiting in
        // earlier cycles come first (they are older).
        let mut retracted = std::mem::take(&mut sc.retracted);
        retracted.append(&mut self.decider.waiting_retractions);
        retracted.retain(|&i| self.decider.insts[i as usize].alive);
        // Justifications that lost a WME retract with them (spec §4), each in its place
        // among the rules' retractions (see `justification_wme_added`).
        let mut justified = std::mem::take(&mut self.decider.justification_retractions);
        if justified.is_empty() {
            retracted.extend(
                retractions
                    .iter()
                    .filter_map(|k| self.decider.inst_by_token.remove(k)),
            );
        } else {
            self.merge_justification_retractions(&retractions, &mut justified, &mut retracted);
        }
        justified.clear();
        self.decider.justification_retractions = justified;
        let mut retractions = retractions;
        retractions.clear();
        if self.matches.retractions.is_empty() {
            self.matches.retractions = retractions;
        }
        // The waterfall (spec §3b): the pending matches by goal level, newest first (the
        // order they fire in, spec §3i), with their support.
        let mut queued = std::mem::take(&mut sc.queued);
        // With the top state alone every match is at level 1.
        let one_goal = self.decider.goals.len() <= 1;
        queued.extend(
            pending
                .iter()
                .rev()
                .map(|&(prod, tok)| self.queued_match(prod, tok, one_goal)),
        );
        pending.clear();
        // The emptied queue's room serves the next cycle's queue.
        sc.keep = pending;
        // Each retraction's goal level (`None`: its goal is gone).
        let mut retracted_levels = std::mem::take(&mut sc.retracted_levels);
        retracted_levels.extend(retracted.iter().map(|&i| {
            self.decider.insts[i as usize]
                .goal
                .filter(|&g| self.symbols.is_goal(g))
                .and_then(|g| self.symbols.id_data(g))
                .map(|d| d.level)
        }));
        // Goal levels with activity, highest goal first: assertions (in the propose phase
        // only i-supported ones) and retractions.
        let mut levels = std::mem::take(&mut sc.levels);
        levels.extend(
            queued
                .iter()
                .filter(|q| apply || !q.o_support)
                .map(|q| q.level)
                .chain(retracted_levels.iter().flatten().copied()),
        );
        levels.sort_unstable();
        levels.dedup();
        let top = levels.first().copied();
        // The firing type: IE before PE (spec §3a). In the apply phase PE only when the
        // active goal has no i-activity, where retractions count too (consistency.cpp
        // `i_activity_at_goal`); IE when only retractions of goals that are gone are left.
        let o_support = match (apply, top) {
            (true, Some(g)) => {
                !queued.iter().any(|q| q.level == g && !q.o_support)
                    && !retracted_levels.contains(&Some(g))
            }
            _ => false,
        };
        self.decider.pe_cycles += u64::from(o_support);
        if apply && self.settings.trace.phases {
            let kind = if o_support { "PE" } else { "IE" };
            let depth = top.unwrap_or(0);
            self.out(&format!(
                "\t--- Firing Productions ({kind}) For State At Depth {depth} ---\n"
            ));
        }
        // Inner elaboration: each goal with activity, from the active one down, fires its
        // matches of the firing type; below the active goal a match whose actions would
        // change an identifier at or above the change level waits (9.6's "new waterfall":
        // decide.cpp `do_preference_phase`, `shouldCreateInstantiation`).
        let mut new_prefs = std::mem::take(&mut sc.new_prefs);
        let mut level = top;
        let mut next_change = top.unwrap_or(0);
        if top.is_none() {
            self.inner_elaboration_pass(None);
        }
        while let Some(l) = level {
            let change_level = next_change;
            self.inner_elaboration_pass(Some(l));
            let mut exist = false;
            for q in queued.iter_mut() {
                if q.fired || q.level != l || q.o_support != o_support {
                    continue;
                }
                exist = true;
                let (p, t) = (q.prod, q.tok);
                if Some(l) != top && self.waits_for_higher_goal(p, t, change_level) {
                    continue;
                }
                q.fired = true;
                self.matches.support.remove(&(p, t));
                self.matches.taken(p, t);
                // A halt ends the run after this elaboration cycle: the rest still fires.
                self.fire(p, t, o_support, &mut new_prefs);
            }
            if exist && l > next_change {
                next_change = l;
            }
            // New preferences go in before the retractions are processed (9.6 prints the
            // `+` lines before `Retracting`), which sets the order slots change in.
            self.assert_preferences(&new_prefs);
            new_prefs.clear();
            self.queue_new_lower_matches(l, apply, &mut queued, &mut levels);
            level = levels.iter().copied().find(|&x| x > l);
        }
        // Matches that did not fire wait, in their order, before any the firings made.
        self.matches.compact();
        let made = std::mem::take(&mut self.matches.assertions);
        let mut keep = std::mem::take(&mut sc.keep);
        keep.extend(
            queued
                .iter()
                .rev()
                .filter(|q| !q.fired)
                .map(|q| (q.prod, q.tok)),
        );
        keep.extend(made);
        self.matches.assertions = keep;
        self.matches.reindex();
        queued.clear();
        sc.queued = queued;
        // Retractions at the active goal and of goals that are gone happen now; lower
        // goals' wait for a cycle where they are the active goal (rete.cpp
        // `get_next_retraction`).
        let mut now = std::mem::take(&mut sc.to_fire_insts);
        for (&i, &l) in retracted.iter().zip(&retracted_levels) {
            match l {
                Some(l) if Some(l) != top => self.decider.waiting_retractions.push(i),
                _ => now.push(i),
            }
        }
        retracted_levels.clear();
        levels.clear();
        sc.retracted_levels = retracted_levels;
        sc.levels = levels;
        // 9.6 lists the retractions newest first and processes them in that order, each
        // instantiation's preferences newest first: that is the order their slots change
        // in, so the order of the `<=WM:` lines (checked with scripts/trace_compare.py:
        // blocks-world now matches 9.6 at trace 4 and 5).
        if self.settings.trace.preferences || self.settings.trace.any_firings() {
            for &inst in now.iter().rev() {
                self.trace_retraction(inst);
            }
        }
        for &inst in now.iter().rev() {
            self.retract(inst);
        }
        if apply && self.settings.trace.phases {
            let kind = if o_support { "PE" } else { "IE" };
            self.trace_phase(&format!("\t--- Change Working Memory ({kind}) ---\n"));
        }
        now.clear();
        retracted.clear();
        sc.to_fire_insts = now;
        sc.retracted = retracted;
        sc.new_prefs = new_prefs;
        self.decider.cycle_scratch = sc;
        self.update_slots();
        true
    }

    /// The rules' retractions (`retractions`, as the matcher reported them) with the
    /// justifications' (`justified`: each with the place it goes before, past the end for
    /// after them all), as instantiations in that order, after those already in `retracted`.
    fn merge_justification_retractions(
        &mut self,
        retractions: &[(ProdId, TokId)],
        justified: &mut [(InstId, u64, usize)],
        retracted: &mut Vec<InstId>,
    ) {
        let end = retractions.len();
        justified.sort_by_key(|&(_, _, at)| at.min(end));
        let mut next = justified.iter().peekable();
        for at in 0..=end {
            while let Some(&(i, serial, _)) = next.next_if(|j| j.2.min(end) <= at) {
                let inst = &self.decider.insts[i as usize];
                if inst.alive && inst.serial == serial && !retracted.contains(&i) {
                    retracted.push(i);
                }
            }
            if let Some(i) = retractions
                .get(at)
                .and_then(|k| self.decider.inst_by_token.remove(k))
            {
                retracted.push(i);
            }
        }
    }

    /// One pass of the waterfall over a goal level (`None`: no active goal): counted for
    /// `stats` ("inner elaboration cycles", which 9.6 counts exactly as the pass headers its
    /// trace prints) and traced.
    fn inner_elaboration_pass(&mut self, level: Option<u32>) {
        self.decider.inner_e_cycles += 1;
        self.trace_inner_elaboration(level);
    }

    /// A pending match with its goal level and support, for the waterfall.
    #[inline]
    fn queued_match(&mut self, prod: ProdId, tok: TokId, one_goal: bool) -> Queued {
        let level = if one_goal {
            1
        } else {
            crate::decide::support::match_goal(self, prod, tok)
                .and_then(|g| self.symbols.id_data(g))
                .map_or(1, |d| d.level)
        };
        let o_support = self.is_o_supported(prod, tok);
        Queued {
            prod,
            tok,
            level,
            o_support,
            fired: false,
        }
    }

    /// Matches made while goal level `l` fired (a chunk learned there matches at once) that
    /// are at a lower goal join this elaboration cycle's waterfall, ahead of that goal's
    /// older matches: 9.6 fires them when the waterfall reaches their goal (checked on
    /// soar-sml 9.6.5: agent learn-lookahead, trace 3).
    fn queue_new_lower_matches(
        &mut self,
        l: u32,
        apply: bool,
        queued: &mut Vec<Queued>,
        levels: &mut Vec<u32>,
    ) {
        // Goal levels run 1..=goals.len(): below the lowest goal there is nothing to queue,
        // and the matches stay for the next cycle, which classifies them anyway.
        if l as usize >= self.decider.goals.len() || !self.matches.has_assertions() {
            return;
        }
        self.matches.compact();
        let fresh = std::mem::take(&mut self.matches.assertions);
        let one_goal = self.decider.goals.len() <= 1;
        let mut lower = Vec::new();
        let mut stay = Vec::new();
        for &(prod, tok) in fresh.iter().rev() {
            let q = self.queued_match(prod, tok, one_goal);
            if q.level > l {
                self.matches.taken(prod, tok);
                if apply || !q.o_support {
                    levels.push(q.level);
                }
                lower.push(q);
            } else {
                stay.push((prod, tok));
            }
        }
        stay.reverse();
        self.matches.assertions = stay;
        self.matches.reindex();
        if !lower.is_empty() {
            levels.sort_unstable();
            levels.dedup();
            queued.splice(0..0, lower);
        }
    }

    /// Whether a match below the active goal must wait: one of its actions adds to an
    /// identifier at or above the change level (9.6's `shouldCreateInstantiation`; new
    /// identifiers and function calls do not count).
    fn waits_for_higher_goal(&mut self, p: ProdId, t: TokId, change_level: u32) -> bool {
        let Some(rule) = self.compiled_rule(p) else {
            return false;
        };
        let mut wmes = std::mem::take(&mut self.decider.rhs_wmes);
        self.rete.token_wmes(t, &mut wmes);
        let mut waits = false;
        for action in rule.actions.iter() {
            let Act::Make { id, .. } = action else {
                continue;
            };
            let sym = match id {
                Term::Sym(s) => Some(*s),
                Term::Bound(depth, field) => self.rete.field_at(&wmes, *depth, *field),
                _ => None,
            };
            if sym
                .and_then(|s| self.symbols.id_data(s))
                .is_some_and(|d| d.level <= change_level)
            {
                waits = true;
                break;
            }
        }
        self.decider.rhs_wmes = wmes;
        waits
    }

    fn fire(&mut self, p: ProdId, t: TokId, o_support: bool, new_prefs: &mut Vec<PrefId>) {
        let Some(rule) = self.compiled_rule(p) else {
            return;
        };
        self.decider.firings += 1;
        let counts = &mut self.decider.firing_counts;
        if counts.len() <= p.0 as usize {
            counts.resize(p.0 as usize + 1, 0);
        }
        counts[p.0 as usize] += 1;
        let traced = self.settings.trace.firings_of(&rule.flags);
        if traced {
            let s = format!("\nFiring {}\n", self.production_name(p));
            self.out(&s);
            self.trace_match_wmes(p, t);
        }
        let mut wmes = std::mem::take(&mut self.decider.rhs_wmes);
        let mut args = std::mem::take(&mut self.decider.rhs_args);
        self.rete.token_wmes(t, &mut wmes);
        // The match goal (spec §3b), from the WMEs the actions read anyway.
        let goal = crate::decide::support::goal_among(
            self,
            rule.id_places
                .iter()
                .filter_map(|&(d, f)| self.rete.field_at(&wmes, d, f)),
        );
        let level = goal
            .and_then(|g| self.symbols.id_data(g))
            .map_or(1, |d| d.level);
        let mut inst = Instantiation {
            prod: p,
            token: t,
            goal,
            o_support: o_support || rule.flags.o_support,
            prefs: self.decider.spare_pref_lists.pop().unwrap_or_default(),
            alive: true,
            serial: 0,
        };
        if rule.flags.i_support {
            inst.o_support = false;
        }
        // The slot is taken now: the preferences name it.
        let inst_id = self.decider.alloc_inst(inst.clone());
        let mut new_ids = std::mem::take(&mut self.decider.rhs_new_ids);
        new_ids.clear();
        new_ids.resize(rule.new_vars.len(), None);
        // Substate firings are recorded for backtracing: each preference with its action.
        let mut made: Vec<(PrefId, usize)> = Vec::new();
        for (action_index, action) in rule.actions.iter().enumerate() {
            match action {
                Act::Call(f) => {
                    let mut complete = true;
                    for a in &f.args {
                        match self.term_value(&rule, &wmes, a, level, &mut new_ids, &mut args) {
                            Some(v) => args.push(v),
                            None => {
                                complete = false;
                                break;
                            }
                        }
                    }
                    if complete {
                        let _ = self.call_rhs(&f.name, &args);
                    }
                    args.clear();
                }
                Act::Make {
                    id,
                    attr,
                    value,
                    referent,
                    kind,
                } => {
                    let id = self.term_value(&rule, &wmes, id, level, &mut new_ids, &mut args);
                    let attr = self.term_value(&rule, &wmes, attr, level, &mut new_ids, &mut args);
                    let value =
                        self.term_value(&rule, &wmes, value, level, &mut new_ids, &mut args);
                    let referent = match referent {
                        Some(r) => {
                            match self.term_value(&rule, &wmes, r, level, &mut new_ids, &mut args) {
                                Some(x) => Some(x),
                                None => continue,
                            }
                        }
                        None => None,
                    };
                    let (Some(id), Some(attr), Some(value)) = (id, attr, value) else {
                        continue;
                    };
                    if !self.symbols.is_id(id) {
                        continue;
                    }
                    let kind = *kind;
                    let number = match (kind, referent.map(|r| self.symbols.get(r))) {
                        (PrefType::NumericIndifferent, Some(&SymData::Int(i))) => Some(i as f64),
                        (PrefType::NumericIndifferent, Some(&SymData::Float(f))) => Some(f),
                        _ => None,
                    };
                    let pref = Preference {
                        kind,
                        id,
                        attr,
                        value,
                        referent,
                        number,
                        o_support: inst.o_support,
                        inst: Some(inst_id),
                        rule: Some(p),
                        alive: true,
                        freed: false,
                        origin: None,
                    };
                    let pid = self.decider.alloc_pref(pref);
                    inst.prefs.push(pid);
                    new_prefs.push(pid);
                    if level >= 2 {
                        made.push((pid, action_index));
                    }
                }
            }
        }
        self.decider.rhs_wmes = wmes;
        self.decider.rhs_args = args;
        if level >= 2 {
            for &pid in inst.prefs.iter().rev() {
                self.note_goal_pref(goal, pid);
            }
        }
        self.decider.inst_by_token.insert((p, t), inst_id);
        let own_prefs = if traced || level >= 2 {
            inst.prefs.clone()
        } else {
            Vec::new()
        };
        self.decider.insts[inst_id as usize] = inst;
        if traced {
            self.trace_instantiation_prefs(&own_prefs);
        }
        // Results of a substate firing are learned from at once (spec §4): a justification
        // or a chunk takes them over.
        if level >= 2 {
            let new_ids: FxHashMap<String, Sym> = rule
                .new_vars
                .iter()
                .zip(&new_ids)
                .filter_map(|((name, _), s)| Some((name.clone(), (*s)?)))
                .collect();
            let recorded = match self.production_by_id(p) {
                Some(prod) => self.record_firing(p, t, &prod, level, &new_ids, &made),
                None => None,
            };
            if let Some(trace) = recorded {
                let results = self.find_results(&own_prefs, level);
                if !results.is_empty() {
                    self.learn_from_results(results, level, &trace, new_prefs);
                }
            }
        }
        self.decider.rhs_new_ids = new_ids;
    }

    /// A rule's compiled actions (compiled at its first firing); `None` for a rule that
    /// is gone.
    pub(crate) fn compiled_rule(&mut self, p: ProdId) -> Option<Rc<CompiledRule>> {
        let i = p.0 as usize;
        if let Some(Some(r)) = self.decider.compiled.get(i) {
            return Some(Rc::clone(r));
        }
        let prod = self.production_by_id(p)?;
        let info = self.rete.production(p)?;
        let mut rule = compiled::compile(&prod, info, &mut self.symbols);
        rule.id_places = self.rete.condition_id_places(info);
        let rule = Rc::new(rule);
        if self.decider.compiled.len() <= i {
            self.decider.compiled.resize(i + 1, None);
        }
        self.decider.compiled[i] = Some(Rc::clone(&rule));
        Some(rule)
    }

    /// The symbol an RHS term stands for in this firing; an unbound variable makes a new
    /// identifier at its first use, shared by all its uses (spec §1e: its letter, `S` read
    /// as `I`).
    fn term_value(
        &mut self,
        rule: &CompiledRule,
        wmes: &[WmeId],
        term: &Term,
        level: u32,
        new_ids: &mut [Option<Sym>],
        args: &mut Vec<Sym>,
    ) -> Option<Sym> {
        match term {
            Term::Sym(s) => Some(*s),
            Term::Bound(depth, field) => self.rete.field_at(wmes, *depth, *field),
            Term::New(slot) => {
                if let Some(s) = new_ids[*slot] {
                    return Some(s);
                }
                let s = self.symbols.new_id(rule.new_vars[*slot].1, level);
                new_ids[*slot] = Some(s);
                Some(s)
            }
            Term::Call(f) => {
                // The arguments go on the firing's one stack, above the caller's.
                let base = args.len();
                for a in &f.args {
                    // Constants and bindings (nearly every argument) without the recursion.
                    let v = match a {
                        Term::Sym(s) => Some(*s),
                        Term::Bound(depth, field) => self.rete.field_at(wmes, *depth, *field),
                        _ => self.term_value(rule, wmes, a, level, new_ids, args),
                    };
                    match v {
                        Some(v) => args.push(v),
                        None => {
                            args.truncate(base);
                            return None;
                        }
                    }
                }
                let result = self.call_rhs(&f.name, &args[base..]);
                args.truncate(base);
                match result {
                    Ok(Some(s)) => Some(s),
                    _ => None,
                }
            }
        }
    }

    fn retract(&mut self, inst_id: InstId) {
        let serial = self.decider.insts[inst_id as usize].serial;
        if serial != 0 {
            let o = self.decider.insts[inst_id as usize].o_support;
            self.forget_justification(serial, o);
        }
        let inst = &mut self.decider.insts[inst_id as usize];
        inst.alive = false;
        let mut prefs = std::mem::take(&mut inst.prefs);
        // Newest first, as 9.6's list of an instantiation's preferences runs.
        for &pid in prefs.iter().rev() {
            let pref = &mut self.decider.prefs[pid as usize];
            pref.inst = None;
            // O-supported preferences outlive their instantiation (spec §3a).
            if pref.o_support || !pref.alive {
                continue;
            }
            let key = (pref.id, pref.attr);
            let value = pref.value;
            if let Some(slot) = self.decider.slots.id_of(&key) {
                self.decider.slots.slot_mut(slot).remove(pid, value);
                self.mark_changed(key, Some(slot));
                self.decider.slots.drop_if_empty(slot);
            } else {
                self.mark_changed(key, None);
            }
            self.decider.free_pref(pid);
        }
        prefs.clear();
        self.decider.insts[inst_id as usize].prefs = prefs;
        self.decider.free_inst(inst_id);
    }

    /// Marks slot `key` (at `slot`, if it exists) for `update_slots`.
    fn mark_changed(&mut self, key: (Sym, Sym), slot: Option<SlotId>) {
        if let Some(id) = slot {
            let slots = &mut self.decider.slots;
            if !slots.slot(id).changed {
                slots.slot_mut(id).changed = true;
                let generation = slots.generation(id);
                self.decider.changed.push((id, generation));
            }
        }
        let op = self.operator_sym();
        if key.1 == op {
            if let Some(g) = self.decider.goals.iter_mut().find(|g| g.state == key.0) {
                g.slot_changed = true;
            }
        }
    }

    /// O-supported rejects remove every preference for their value first; the other new
    /// preferences join their slots, newest at the head (spec §3a).
    fn assert_preferences(&mut self, new_prefs: &[PrefId]) {
        if self.settings.trace.preferences {
            self.trace_new_preferences(new_prefs);
        }
        let taken = std::mem::take(&mut self.decider.results_taken_by_o_rejects);
        for &pid in &taken {
            self.decider.free_pref(pid);
        }
        let mut removed = Vec::new();
        for &pid in new_prefs {
            let p = &self.decider.prefs[pid as usize];
            let (kind, o_support, key, value) = (p.kind, p.o_support, (p.id, p.attr), p.value);
            if kind == PrefType::Reject && o_support && p.alive {
                removed.clear();
                let slot = self.decider.slots.id_of(&key);
                if let Some(id) = slot {
                    self.decider
                        .slots
                        .slot_mut(id)
                        .remove_value(value, &mut removed);
                }
                for &r in &removed {
                    self.decider.free_pref(r);
                }
                self.decider.free_pref(pid);
                self.mark_changed(key, slot);
            }
        }
        for &pid in new_prefs.iter().rev() {
            let p = &self.decider.prefs[pid as usize];
            if !p.alive {
                continue;
            }
            let key = (p.id, p.attr);
            let value = p.value;
            let slot = self.decider.slots.entry_id(key);
            self.decider.slots.slot_mut(slot).push(pid, value);
            self.mark_changed(key, Some(slot));
        }
    }

    fn is_context_slot(&mut self, key: (Sym, Sym)) -> bool {
        let op = self.operator_sym();
        key.1 == op && self.symbols.is_goal(key.0)
    }

    /// Brings working memory in line with the changed slots (spec §2, §3d): a non-context
    /// slot shows each value with an acceptable and no reject preference; an operator slot
    /// shows its acceptable preferences as `+` WMEs. Then unlinked structure goes.
    fn update_slots(&mut self) {
        // Soar head-inserts changed slots as they are first marked, so they are decided in
        // the reverse of marking order: the first action of the first firing gets the lowest
        // timetag (spec §3i, E:t6).
        let mut changed = std::mem::take(&mut self.decider.changed);
        changed.reverse();
        let mut sc = std::mem::take(&mut self.decider.slot_scratch);
        let mut adds = std::mem::take(&mut sc.adds);
        // Removals are buffered with their timetags (handles are reused).
        let mut removes = std::mem::take(&mut sc.removes);
        let mut context = std::mem::take(&mut sc.context);
        let mut want = std::mem::take(&mut sc.want);
        for &(id, generation) in &changed {
            if self.decider.slots.generation(id) != generation {
                continue; // The slot went after it changed.
            }
            let slot = self.decider.slots.slot_mut(id);
            slot.changed = false;
            let key = slot.key;
            let incremental = slot.only_touched_changed();
            let mut touched = std::mem::take(&mut slot.touched);
            slot.full = false;
            if self.is_context_slot(key) {
                touched.clear();
                self.decider.slots.slot_mut(id).touched = touched;
                context.push(key);
                continue;
            }
            if incremental {
                let slot = self.decider.slots.slot(id);
                let prefs = &self.decider.prefs;
                update_touched_values(slot, prefs, &mut touched, &self.wm, &mut removes, &mut adds);
            }
            touched.clear();
            self.decider.slots.slot_mut(id).touched = touched;
            if incremental {
                continue;
            }
            let slot = self.decider.slots.slot(id);
            let want = wanted_values(slot, &self.decider.prefs, &mut want);
            // Newest first, as 9.6 walks its slot's list.
            for (v, acc, w) in slot.wmes.iter().rev() {
                if !acc && !want.contains(v) {
                    removes.push((w, self.wm.get(w).map_or(0, |x| x.timetag)));
                }
            }
            for &v in want.list() {
                if !slot.wmes.contains_key(&(v, false)) {
                    adds.push((key.0, key.1, v, false));
                }
            }
        }
        // Operators whose proposal went are removed before the `+` WMEs change (9.6's
        // REMOVING lines come first, and its removals are buffered in that order).
        let goals_before = self.decider.goals.len();
        if self.settings.trace.wmes {
            self.removed_wmes = Some(Vec::new());
        }
        // A substate whose GDS holds a WME the slot decisions remove goes first, before
        // the operator checks (9.6 removes it as the WME goes: its `Removing state ...
        // because element in GDS changed` comes before the `REMOVING: Operator` lines).
        let decided_removes = removes.len();
        if self.settings.trace.gds {
            self.trace_gds_removals(&removes);
        }
        self.remove_gds_goals_of(&removes);
        for &key in &context {
            if let Some(w) = self.check_operator_consistency(key) {
                removes.push((w, self.wm.get(w).map_or(0, |x| x.timetag)));
            }
        }
        for &key in &context {
            let empty = Slot::default();
            let slot = self.decider.slots.get(&key).unwrap_or(&empty);
            want.clear();
            let large = slot.prefs.len() > LARGE_SLOT;
            // Require preferences show as `+` WMEs too, before the acceptable ones, each
            // kind oldest first: that sets their timetags (checked on 9.6).
            for kind in [PrefType::Require, PrefType::Acceptable] {
                for &pid in slot.prefs.iter().rev() {
                    let p = &self.decider.prefs[pid as usize];
                    if p.kind == kind {
                        want.insert(p.value, large);
                    }
                }
            }
            for (v, acc, w) in slot.wmes.iter().rev() {
                if acc && !want.contains(v) {
                    removes.push((w, self.wm.get(w).map_or(0, |x| x.timetag)));
                }
            }
            for &v in want.list() {
                if !slot.wmes.contains_key(&(v, true)) {
                    adds.push((key.0, key.1, v, true));
                }
            }
        }
        if self.settings.trace.gds {
            self.trace_gds_removals(&removes[decided_removes..]);
        }
        // Timetags in action order, but the matcher gets the batch newest first, and the
        // `=>WM:` lines come newest first too (spec §3i, E:t6). Additions reach the matcher
        // before removals, which go in the reverse of the order they were found (9.6
        // head-inserts both buffers).
        changed.clear();
        if self.decider.changed.is_empty() {
            self.decider.changed = changed;
        }
        let mut added = std::mem::take(&mut sc.added);
        for &(id, attr, value, acc) in &adds {
            added.push(self.add_slot_wme(id, attr, value, acc));
        }
        // Where the `=>WM:` lines start: 9.6 warns there of a WME this phase adds and
        // removes (see below).
        let adds_at = self.output.len();
        let mut traced_adds = Vec::new();
        for &w in added.iter().rev() {
            if let Some(wme) = self.wm.get(w).copied() {
                self.trace_wme("=>WM: ", &wme);
                if self.settings.trace.wmes {
                    traced_adds.push(wme);
                }
                self.match_new_wme(w, &wme);
            }
        }
        for &w in &added {
            self.gds_for_new_wme(w);
        }
        // A substate removed just above may still get this wave's WMEs (9.6 adds them too,
        // removing the goal only at its next consistency check): with the goal gone they
        // are unlinked, and go with the garbage below instead of staying for good.
        if self.decider.goals.len() < goals_before {
            for &w in &added {
                if let Some(wme) = self.wm.get(w) {
                    self.decider.gc_candidates.push(wme.id);
                }
            }
        }
        let before_decided = self.removed_wmes.as_ref().map_or(0, Vec::len);
        for &(w, tt) in removes.iter().rev() {
            // A WME already gone (with a substate removed above) may have lent its handle
            // to one just added: only the WME with the timetag seen is removed.
            if self.wm.get(w).is_some_and(|x| x.timetag == tt) {
                self.remove_slot_wme(w);
            }
        }
        let decided = before_decided..self.removed_wmes.as_ref().map_or(0, Vec::len);
        self.remove_invalid_gds_goals();
        // 9.6's warning comes after the garbage's `-` lines.
        let gc_lines = self.collect_garbage_traced_at(Some(adds_at));
        if self.settings.trace.wmes {
            self.warn_added_and_removed(&traced_adds, adds_at + gc_lines);
        }
        self.trace_removed_wmes(decided);
        self.classify_new_matches();
        // Impasses are re-checked once i-supported processing is quiescent (9.6 checks at
        // minor quiescence, spec §3b): a result that ends a tie removes the tie's substate
        // before the phase ends.
        for &key in &context {
            if !self.decider.consistency_pending.contains(&key) {
                self.decider.consistency_pending.push(key);
            }
        }
        if !self.decider.consistency_pending.is_empty() && !self.has_pending(false) {
            for key in std::mem::take(&mut self.decider.consistency_pending) {
                self.check_impasse_consistency(key);
            }
        }
        adds.clear();
        removes.clear();
        context.clear();
        added.clear();
        (sc.adds, sc.removes, sc.context, sc.added, sc.want) =
            (adds, removes, context, added, want);
        self.decider.slot_scratch = sc;
    }

    /// Puts a slot's WME into working memory (with its timetag); the caller matches it.
    fn add_slot_wme(&mut self, id: Sym, attr: Sym, value: Sym, acceptable: bool) -> WmeId {
        let links = [self.symbols.is_id(value), self.symbols.is_id(attr)];
        let w = self.wm.add_typed(id, attr, value, acceptable, links);
        self.decider.wme_changes += 1;
        self.decider
            .slots
            .entry((id, attr))
            .wmes
            .insert((value, acceptable), w);
        w
    }

    fn remove_slot_wme(&mut self, w: WmeId) {
        let Some(wme) = self.wm.get(w).copied() else {
            return;
        };
        self.trace_wme("<=WM: ", &wme);
        let key = (wme.id, wme.attr);
        if let Some(id) = self.decider.slots.id_of(&key) {
            let slots = &mut self.decider.slots;
            slots.slot_mut(id).wmes.remove(&(wme.value, wme.acceptable));
            slots.drop_if_empty(id);
        }
        self.decider.wme_changes += 1;
        self.remove_wme(w);
    }

    /// The operator installed in a goal stays while it is still a candidate; otherwise it
    /// goes at once, with every substate below (spec §3b).
    /// Returns the operator WME to remove (buffered with the other removals).
    fn check_operator_consistency(&mut self, key: (Sym, Sym)) -> Option<WmeId> {
        let gi = self.decider.goals.iter().position(|g| g.state == key.0)?;
        let (op, w) = self.decider.goals[gi].operator?;
        let prefs = self.slot_prefs(key);
        let still = prefs
            .iter()
            .any(|p| p.kind == PrefType::Acceptable && p.value == op)
            && !prefs
                .iter()
                .any(|p| matches!(p.kind, PrefType::Reject | PrefType::Prohibit) && p.value == op);
        if still {
            return None;
        }
        if self.settings.trace.consistency {
            self.trace_operator_removal(key, op);
            if let Some(sub) = self.decider.goals.get(gi + 1) {
                let s = format!(
                    "Removing state {} because of an operator removal.\n",
                    self.symbols.text(sub.state)
                );
                self.out(&s);
            }
        }
        if self.settings.trace.wmes && self.removed_wmes.is_some() {
            self.collect_substate_removals(gi);
        }
        self.remove_goals_below(gi);
        self.decider.goals[gi].operator = None;
        Some(w)
    }

    /// A goal without an operator whose impasse the preferences no longer give (another
    /// impasse, other items, or a choice) loses its substates at once, as 9.6's
    /// consistency check removes them; the next decision decides the slot again
    /// (spec §3b).
    fn check_impasse_consistency(&mut self, key: (Sym, Sym)) {
        let Some(gi) = self.decider.goals.iter().position(|g| g.state == key.0) else {
            return;
        };
        if let Some((op, w)) = self.decider.goals[gi].operator {
            self.check_selected_operator(gi, key, op, w);
            return;
        }
        let Some(sub) = self.decider.goals.get(gi + 1) else {
            return;
        };
        let Some((kind, on_operator)) = sub.impasse else {
            return;
        };
        let same_items = |items: &[Sym]| {
            items.len() == sub.items.len() && items.iter().all(|i| sub.items.contains(i))
        };
        let consistent = match procedure::candidates(&self.slot_prefs(key)) {
            Ok(_) => false,
            Err(Outcome::NoCandidates) => kind == ImpasseKind::NoChange && !on_operator,
            Err(Outcome::Tie(items)) => kind == ImpasseKind::Tie && same_items(&items),
            Err(Outcome::Conflict(items)) => kind == ImpasseKind::Conflict && same_items(&items),
            Err(Outcome::ConstraintFailure(items)) => {
                kind == ImpasseKind::ConstraintFailure && same_items(&items)
            }
            Err(Outcome::Winner(_)) => false,
        };
        if consistent {
            return;
        }
        self.remove_inconsistent_decision(gi, key, true);
        self.decider.goals[gi].slot_changed = true;
    }

    /// The substates below goal `gi` go because its decision no longer agrees with the
    /// preferences, with 9.6's trace (`remove_current_decision`; the `REMOVING CONTEXT
    /// SLOT` line only when no operator was selected).
    fn remove_inconsistent_decision(&mut self, gi: usize, key: (Sym, Sym), empty_slot: bool) {
        if self.settings.trace.consistency {
            let goal = self.symbols.text(key.0);
            let slot_line = if empty_slot {
                format!(
                    "\n       REMOVING CONTEXT SLOT: Slot Identifier [{goal}] and attribute [operator]\n"
                )
            } else {
                String::new()
            };
            let s = format!(
                "Removing substates of {goal} because the operator last selected in {goal} is not\nconsistent with the current preferences.\n{slot_line}\n          Decision for goal [{goal}] is inconsistent.  Replacing it with....\n"
            );
            self.out(&s);
        }
        if self.settings.trace.preferences {
            // Before the substates' `<=WM:` lines, as 9.6 lists them.
            for k in (gi + 1..self.decider.goals.len()).rev() {
                let made = std::mem::take(&mut self.decider.goals[k].made);
                let state = self.decider.goals[k].state;
                self.trace_removed_prefs(state, &made);
            }
        }
        if self.settings.trace.wmes {
            self.trace_substate_wmes_removed(gi);
        }
        self.remove_goals_below(gi);
    }

    /// A selected operator stays while the preferences still give it among the candidates;
    /// when another operator is now better (or an impasse would come instead), the operator
    /// and every substate below go at once, and the next decision decides the slot again
    /// (consistency.cpp `decision_consistent_with_current_preferences`, spec §3b).
    fn check_selected_operator(&mut self, gi: usize, key: (Sym, Sym), op: Sym, w: WmeId) {
        if matches!(procedure::candidates(&self.slot_prefs(key)), Ok(c) if c.contains(&op)) {
            return;
        }
        self.remove_inconsistent_decision(gi, key, false);
        self.decider.goals[gi].operator = None;
        self.remove_slot_wme(w);
        self.collect_garbage();
        self.decider.goals[gi].slot_changed = true;
    }

    /// The `<=WM:` lines 9.6 prints for the architecture WMEs of the substates below goal
    /// `gi` when a consistency check removes them within a phase: the smem and epmem links'
    /// children, the links, the state's own WMEs, then the `^non-numeric` and the `^item`
    /// WMEs (each group oldest first; seen on 9.6).
    fn trace_substate_wmes_removed(&mut self, gi: usize) {
        let lines = self.substate_lines(gi);
        let memories = lines.iter().take_while(|(group, _)| *group <= 2).count();
        for (_, wme) in &lines[..memories] {
            self.trace_wme("<=WM: ", wme);
        }
        // The WMEs rules made on the substates (their slots' WMEs) go with them too: after
        // the memories' structure, oldest first, the operator `+` WMEs last (soar-sml 9.6.5,
        // agent learn-lookahead: `^name selection`, `^evaluation`, then `^operator E5 +`).
        let mut made = self.substate_slot_wmes(gi);
        made.sort_by_key(|&(plus, wme)| (plus, wme.timetag));
        for (_, wme) in made {
            self.trace_wme("<=WM: ", &wme);
        }
        for (_, wme) in &lines[memories..] {
            self.trace_wme("<=WM: ", wme);
        }
    }

    /// An operator removal or a GDS change takes the substates below goal `gi` away: their
    /// `<=WM:` lines join this phase's listing, each tagged with its kind, for
    /// `trace_removed_wmes` to put in 9.6's place.
    pub(crate) fn collect_substate_removals(&mut self, gi: usize) {
        use crate::trace::SubstateLine;
        let mut out = Vec::new();
        for (group, wme) in self.substate_lines(gi) {
            let place = if group <= 2 {
                SubstateLine::Memories
            } else {
                SubstateLine::Impasse
            };
            out.push((place, wme));
        }
        for (plus, wme) in self.substate_slot_wmes(gi) {
            let place = if plus {
                SubstateLine::OperatorPlus
            } else {
                SubstateLine::Other
            };
            out.push((place, wme));
        }
        for g in self.decider.goals[gi + 1..].iter().rev() {
            if let Some(wme) = g.operator.and_then(|(_, w)| self.wm.get(w).copied()) {
                out.push((SubstateLine::Selected, wme));
            }
        }
        self.substate_removals.extend(out);
    }

    /// The WMEs in the slots of the goals below `gi` (those rules made on them), lowest
    /// goal first, each with whether it is an operator `+` WME.
    fn substate_slot_wmes(&self, gi: usize) -> Vec<(bool, crate::wm::Wme)> {
        let op = self.operator_sym();
        let mut out = Vec::new();
        for g in self.decider.goals[gi + 1..].iter().rev() {
            for key in self.decider.slots.keys_of(g.state) {
                let Some(slot) = self.decider.slots.get(&key) else {
                    continue;
                };
                for (_, acc, w) in slot.wmes.iter() {
                    if let Some(wme) = self.wm.get(w).copied() {
                        out.push((acc && key.1 == op, wme));
                    }
                }
            }
        }
        out
    }

    /// The architecture WMEs of the goals below `gi` in 9.6's order, each with its group
    /// (0–2: the memories' structure; 3 and up: the impasse's WMEs).
    fn substate_lines(&self, gi: usize) -> Vec<(u8, crate::wm::Wme)> {
        let mut lines: Vec<(u8, u64, crate::wm::Wme)> = Vec::new();
        for g in &self.decider.goals[gi + 1..] {
            let of = |attr: &str| {
                let a = self.symbols.find_str(attr);
                g.wmes
                    .iter()
                    .filter_map(|&w| self.wm.get(w))
                    .find(|w| Some(w.attr) == a && w.id == g.state)
                    .map(|w| w.value)
            };
            let (smem, epmem) = (of("smem"), of("epmem"));
            for &w in &g.wmes {
                let Some(wme) = self.wm.get(w).copied() else {
                    continue;
                };
                let attr = self.symbols.text(wme.attr);
                let group = if Some(wme.id) == smem {
                    0
                } else if Some(wme.id) == epmem {
                    1
                } else if matches!(attr.as_str(), "reward-link" | "epmem" | "smem") {
                    2
                } else if attr.starts_with("non-numeric") {
                    4
                } else if attr.starts_with("item") {
                    5
                } else {
                    3
                };
                // Counts go after the values they count.
                let count = u64::from(attr.ends_with("-count"));
                lines.push((group, count << 63 | wme.timetag, wme));
            }
        }
        lines.sort_by_key(|(g, k, _)| (*g, *k));
        lines.into_iter().map(|(g, _, w)| (g, w)).collect()
    }

    fn slot_prefs(&self, key: (Sym, Sym)) -> Vec<Pref> {
        let Some(slot) = self.decider.slots.get(&key) else {
            return Vec::new();
        };
        // Candidates come out oldest first: the reverse of Soar's head-inserted list (§3d).
        slot.prefs
            .iter()
            .map(|&pid| {
                let p = &self.decider.prefs[pid as usize];
                Pref {
                    kind: p.kind,
                    value: p.value,
                    referent: p.referent,
                    number: p.number,
                }
            })
            .collect()
    }

    /// Decides the first operator slot without an installed operator, from the top; if every
    /// goal has one, the bottom goal has an operator no-change (spec §3e).
    fn decide_context_slots(&mut self) {
        // The decision decides every changed slot anew.
        self.decider.consistency_pending.clear();
        let op = self.operator_sym();
        let policy = match self.settings_policy.as_str() {
            "first" => Policy::First,
            "last" => Policy::Last,
            "epsilon-greedy" => Policy::EpsilonGreedy { epsilon: 0.1 },
            "boltzmann" => Policy::Boltzmann { temperature: 25.0 },
            _ => Policy::Softmax,
        };
        let n = self.decider.goals.len();
        for gi in 0..n {
            let goal = self.decider.goals[gi].clone();
            // Decidable: no installed operator and the preferences changed (spec §3e).
            if goal.operator.is_some() || !goal.slot_changed {
                continue;
            }
            self.decider.goals[gi].slot_changed = false;
            let prefs = self.slot_prefs((goal.state, op));
            let outcome = procedure::decide(&prefs, policy, NumericMode::Sum, &mut self.rng);
            let (kind, on_operator, items) = match outcome {
                Outcome::Winner(o) => {
                    self.remove_goals_below(gi);
                    let w = self.add_wme(goal.state, op, o, false);
                    if let Some(wme) = self.wm.get(w).copied() {
                        self.trace_wme("=>WM: ", &wme);
                    }
                    self.classify_new_matches();
                    self.decider.wme_changes += 1;
                    self.decider.goals[gi].operator = Some((o, w));
                    if self.settings.trace.decisions {
                        let name = self.operator_name(o);
                        let mut line = format!(
                            "{}   O: {} {}",
                            self.decision_prefix(goal.level),
                            self.symbols.text(o),
                            name
                        );
                        if !name.is_empty() {
                            line = line.trim_end().to_string();
                        }
                        self.out(&line);
                    }
                    return;
                }
                Outcome::NoCandidates => (ImpasseKind::NoChange, false, Vec::new()),
                Outcome::Tie(items) => (ImpasseKind::Tie, true, items),
                Outcome::Conflict(items) => (ImpasseKind::Conflict, true, items),
                Outcome::ConstraintFailure(items) => (ImpasseKind::ConstraintFailure, true, items),
            };
            // The same impasse again changes nothing here: look further down.
            let same = self
                .decider
                .goals
                .get(gi + 1)
                .is_some_and(|g| g.impasse == Some((kind, on_operator)) && g.items == items);
            if same {
                continue;
            }
            if gi + 1 < n || kind != ImpasseKind::NoChange || on_operator {
                self.impasse(gi, kind, on_operator, items);
                return;
            }
            self.impasse(gi, kind, on_operator, items);
            return;
        }
        // Nothing decidable: the bottom goal made no progress (spec §3e).
        if let Some(last) = n.checked_sub(1) {
            let on_operator = self.decider.goals[last].operator.is_some();
            self.impasse(last, ImpasseKind::NoChange, on_operator, Vec::new());
        }
    }

    fn operator_name(&mut self, o: Sym) -> String {
        let vals = self.name_values(o);
        if vals.is_empty() {
            String::new()
        } else {
            format!("({})", vals.join(" "))
        }
    }

    /// The `^name` values of an object (operators are printed with them).
    pub(crate) fn name_values(&self, o: Sym) -> Vec<String> {
        let Some(name) = self.symbols.find_str("name") else {
            return Vec::new();
        };
        self.wm
            .of_id(o)
            .filter_map(|w| self.wm.get(w))
            .filter(|w| w.attr == name && !w.acceptable)
            .map(|w| self.symbols.text(w.value))
            .collect()
    }

    /// Creates (or keeps) the substate for an impasse at goal `gi` (spec §2, §3e).
    fn impasse(&mut self, gi: usize, kind: ImpasseKind, on_operator: bool, items: Vec<Sym>) {
        if let Some(sub) = self.decider.goals.get(gi + 1) {
            if sub.impasse == Some((kind, on_operator)) && sub.items == items {
                return;
            }
        }
        self.remove_goals_below(gi);
        let parent = self.decider.goals[gi].state;
        let level = self.decider.goals[gi].level + 1;
        if kind == ImpasseKind::NoChange && !on_operator && self.settings.wait_snc {
            // Waiting: the bottom state's own line again, impasse included (E:t12).
            if self.settings.trace.decisions {
                let what = self.decider.goals[gi]
                    .impasse
                    .map(|(k, on_op)| {
                        format!(
                            "({} {})",
                            if on_op { "operator" } else { "state" },
                            k.word()
                        )
                    })
                    .unwrap_or_default();
                let s = format!(
                    "{}==>S: {} {}",
                    self.decision_prefix(level - 1),
                    self.symbols.text(parent),
                    what
                );
                self.out(&s);
            }
            return;
        }
        let s = self.symbols.new_id('S', level);
        if let Some(d) = self.symbols.id_data_mut(s) {
            d.is_goal = true;
            d.is_impasse = true;
        }
        let mut wmes = Vec::new();
        let mut add = |agent: &mut Agent, id: Sym, attr: &str, value: Sym| {
            let a = agent.symbols.str(attr);
            // Into working memory now; the matcher gets them below, newest first.
            wmes.push(agent.wm.add(id, a, value, false));
        };
        let state = self.symbols.str("state");
        add(self, s, "type", state);
        add(self, s, "superstate", parent);
        let r = self.symbols.new_id('R', level);
        add(self, s, "reward-link", r);
        let e = self.symbols.new_id('E', level);
        add(self, s, "epmem", e);
        let c = self.symbols.new_id('C', level);
        add(self, e, "command", c);
        let r2 = self.symbols.new_id('R', level);
        add(self, e, "result", r2);
        let one = self.symbols.int(1);
        add(self, e, "present-id", one);
        let l = self.symbols.new_id('L', level);
        add(self, s, "smem", l);
        let c2 = self.symbols.new_id('C', level);
        add(self, l, "command", c2);
        let r3 = self.symbols.new_id('R', level);
        add(self, l, "result", r3);
        let attr = self
            .symbols
            .str(if on_operator { "operator" } else { "state" });
        add(self, s, "attribute", attr);
        let imp = self.symbols.str(kind.word());
        add(self, s, "impasse", imp);
        let choices = self.symbols.str(
            if matches!(kind, ImpasseKind::Tie | ImpasseKind::Conflict) {
                "multiple"
            } else {
                "none"
            },
        );
        add(self, s, "choices", choices);
        let t = self.symbols.str("t");
        add(self, s, "quiescence", t);
        if !items.is_empty() {
            for &it in &items {
                add(self, s, "item", it);
            }
            let n = self.symbols.int(items.len() as i64);
            add(self, s, "item-count", n);
            for &it in &items {
                add(self, s, "non-numeric", it);
            }
            add(self, s, "non-numeric-count", n);
        }
        // 9.6 prints the depth message before the new state's WMEs and line.
        if level as i64 > self.settings.max_goal_depth {
            let msg = format!(
                "\nGoal stack depth exceeded {} on a no-change impasse.\nSoar appears to be in an infinite loop.  \nContinuing to subgoal may cause Soar to \nexceed the program stack of your system.\n",
                self.settings.max_goal_depth
            );
            self.out(&msg);
            // 9.6 stops the run here without halting the agent: a later `run` goes on
            // deeper, with the same message at each new state (checked on soar-sml 9.6.5).
            self.decider.depth_exceeded = true;
        }
        self.decider.wme_changes += wmes.len() as u64;
        for &w in wmes.iter().rev() {
            if let Some(wme) = self.wm.get(w).copied() {
                self.trace_wme("=>WM: ", &wme);
                self.match_wme_now(w, (wme.id, wme.attr, wme.value), false);
            }
        }
        if self.settings.trace.decisions {
            let what = format!(
                "({} {})",
                if on_operator { "operator" } else { "state" },
                kind.word()
            );
            let line = format!(
                "{}==>S: {} {}",
                self.decision_prefix(level),
                self.symbols.text(s),
                what
            );
            self.out(&line);
        }
        self.decider.goals.push(Goal {
            state: s,
            level,
            operator: None,
            impasse: Some((kind, on_operator)),
            items,
            wmes,
            slot_changed: true,
            made: Vec::new(),
        });
    }

    /// Removes every goal below `gi`, deepest first, with its architecture WMEs; what they
    /// held up goes with the garbage collection.
    pub(crate) fn remove_goals_below(&mut self, gi: usize) {
        while self.decider.goals.len() > gi + 1 {
            let Some(g) = self.decider.goals.pop() else {
                break;
            };
            if self.settings.trace.preferences {
                self.trace_removed_prefs(g.state, &g.made);
            }
            if let Some((_, w)) = g.operator {
                self.remove_wme(w);
            }
            for w in g.wmes {
                self.remove_wme(w);
            }
            if let Some(d) = self.symbols.id_data_mut(g.state) {
                d.is_goal = false;
            }
            // Preferences made for the substate's own objects go with it.
            let gone = self.decider.slots.keys_of(g.state);
            for k in gone {
                if let Some(slot) = self.decider.slots.remove(&k) {
                    for &pid in &slot.prefs {
                        self.decider.free_pref(pid);
                    }
                    for w in slot.wmes.values().rev() {
                        self.remove_wme(w);
                    }
                    self.decider.slots.recycle(slot);
                }
            }
            self.decider.gc_candidates.push(g.state);
            self.decider.gds.retain(|_, goal| *goal != g.state);
        }
        self.collect_garbage();
    }

    /// 9.6's `WARNING: WME added and removed in same phase : (31: S2 ^note hello)`, before
    /// the phase's `=>WM:` lines (at `at` in the output), for each WME it added that is
    /// already gone again (a substate removed in the same phase took it; checked on
    /// soar-sml 9.6.5: agent substate-removed-same-wave).
    fn warn_added_and_removed(&mut self, added: &[crate::wm::Wme], at: usize) {
        let Some(removed) = self.removed_wmes.as_ref() else {
            return;
        };
        let mut text = String::new();
        for wme in added {
            if removed.iter().any(|x| x.timetag == wme.timetag) {
                text.push_str("WARNING: WME added and removed in same phase : ");
                text.push_str(&crate::trace::wme_internal(self, wme));
                text.push('\n');
            }
        }
        if !text.is_empty() && at <= self.output.len() && self.output.is_char_boundary(at) {
            self.output.insert_str(at, &text);
        }
    }

    /// Keeps a substate firing's preference with its goal (a firing's newest first), for
    /// [`Self::trace_removed_prefs`].
    fn note_goal_pref(&mut self, goal: Option<Sym>, pid: PrefId) {
        let Some(gi) = self
            .decider
            .goals
            .iter()
            .position(|g| Some(g.state) == goal)
        else {
            return;
        };
        let p = &self.decider.prefs[pid as usize];
        let what = (p.id, p.attr, p.value);
        self.decider.goals[gi].made.push((pid, what));
        // A long-lived substate keeps only the preferences that still stand (amortized).
        let n = self.decider.goals[gi].made.len();
        if n >= 64 && n.is_power_of_two() {
            let state = self.decider.goals[gi].state;
            let mut made = std::mem::take(&mut self.decider.goals[gi].made);
            made.retain(|&(pid, what)| self.pref_stands(pid, what, state));
            self.decider.goals[gi].made = made;
        }
    }

    /// Whether preference `pid` is still the one a firing of `state` made saying `what`.
    fn pref_stands(&self, pid: PrefId, what: (Sym, Sym, Sym), state: Sym) -> bool {
        let p = &self.decider.prefs[pid as usize];
        p.alive
            && !p.freed
            && (p.id, p.attr, p.value) == what
            && p.inst
                .is_none_or(|i| self.decider.insts[i as usize].goal == Some(state))
    }

    /// 9.6's trace 5 lists the standing preferences of a removed state's firings as
    /// removed (`- (S1 ^r x +) [level 2] (rule)`) before the state's WMEs go: firings
    /// oldest first, each one's preferences newest first, o-supported ones that outlived
    /// their firing too (checked on soar-sml 9.6.5: agents gds, substate-results,
    /// justification-negation).
    fn trace_removed_prefs(&mut self, state: Sym, made: &[(PrefId, (Sym, Sym, Sym))]) {
        let mut seen = FxHashSet::default();
        for &(pid, what) in made {
            if self.pref_stands(pid, what, state) && seen.insert(pid) {
                self.trace_pref('-', pid);
                self.decider.prefs_traced_gone.push(pid);
            }
        }
    }

    /// Removes WMEs no longer linked to a goal or the io link (spec §2). Only identifiers
    /// that lost a link can have become unlinked: each is searched upward for a goal, and
    /// the structure below one that has none goes (cycles included).
    fn collect_garbage(&mut self) {
        self.collect_garbage_traced_at(None);
    }

    /// Garbage collection; the preferences it takes with the slots of unlinked identifiers
    /// are traced as `- pref` lines (`trace -r`) at `at` in the output, where the phase's
    /// `=>WM:` lines start, as 9.6 prints them (checked on soar-sml 9.6.5: agent
    /// support-retraction, an operator elaboration's `^to` on an operator that went), or
    /// where the output is now. Returns how many bytes of text went in at `at`.
    fn collect_garbage_traced_at(&mut self, at: Option<usize>) -> usize {
        let traced_gone = std::mem::take(&mut self.decider.prefs_traced_gone);
        if self.decider.gc_candidates.is_empty() {
            return 0;
        }
        let candidates = std::mem::take(&mut self.decider.gc_candidates);
        // The sets live between calls (emptied), so that a collection allocates nothing.
        let mut gc = std::mem::take(&mut self.decider.gc_scratch);
        gc.roots.extend(self.decider.goals.iter().map(|g| g.state));
        gc.roots.insert(self.top.state);
        let mut garbage: Vec<WmeId> = Vec::new();
        for &c in &candidates {
            if gc.dead.contains(&c) || !self.wm.has_wmes(c) || self.linked(c, &mut gc) {
                continue;
            }
            gc.stack.push(c);
            while let Some(x) = gc.stack.pop() {
                if !gc.dead.insert(x) {
                    continue;
                }
                for w in self.wm.of_id(x) {
                    garbage.push(w);
                    let Some(wme) = self.wm.get(w).copied() else {
                        continue;
                    };
                    for v in [wme.value, wme.attr] {
                        if self.symbols.is_id(v)
                            && !gc.dead.contains(&v)
                            && !self.linked(v, &mut gc)
                        {
                            gc.stack.push(v);
                        }
                    }
                }
            }
        }
        gc.clear();
        self.decider.gc_scratch = gc;
        self.decider.gc_candidates = candidates;
        self.decider.gc_candidates.clear();
        if garbage.is_empty() {
            return 0;
        }
        garbage.sort_by_key(|w| self.wm.get(*w).map(|x| x.timetag));
        // 9.6 lists the removals newest first; they happen oldest first here.
        let mut removed_lines = Vec::new();
        let mut pref_lines = String::new();
        for w in garbage {
            let Some(wme) = self.wm.get(w).copied() else {
                continue;
            };
            if let Some(slot) = self.decider.slots.remove(&(wme.id, wme.attr)) {
                if self.settings.trace.preferences {
                    // Newest first, as 9.6's list of a slot's preferences runs.
                    for &pid in slot.prefs.iter().rev() {
                        if traced_gone.contains(&pid) {
                            continue;
                        }
                        let pref = &self.decider.prefs[pid as usize];
                        pref_lines.push_str("- ");
                        pref_lines.push_str(&crate::trace::pref_trace_text(self, pref));
                        pref_lines.push('\n');
                    }
                }
                for &pid in &slot.prefs {
                    self.decider.free_pref(pid);
                }
                for sw in slot.wmes.values().rev() {
                    if sw != w {
                        self.remove_wme(sw);
                    }
                }
                self.decider.slots.recycle(slot);
            }
            if self.wm.get(w).is_some() {
                removed_lines.push(wme);
                self.remove_wme(w);
            }
        }
        let mut inserted = 0;
        if !pref_lines.is_empty() {
            match at.filter(|&a| a <= self.output.len() && self.output.is_char_boundary(a)) {
                Some(at) => {
                    self.output.insert_str(at, &pref_lines);
                    inserted = pref_lines.len();
                }
                None => {
                    self.fresh_line();
                    self.output.push_str(&pref_lines);
                }
            }
        }
        for wme in removed_lines.iter().rev() {
            self.trace_wme("<=WM: ", wme);
        }
        // What these removals point at was all collected above.
        self.decider.gc_candidates.clear();
        inserted
    }

    /// Is `x` reachable from a goal? An upward search through the WMEs that point at it; a
    /// search that finds no goal proves everything it visited unlinked.
    fn linked(&self, x: Sym, gc: &mut GcScratch) -> bool {
        if let Some(&b) = gc.memo.get(&x) {
            return b;
        }
        if gc.roots.contains(&x) {
            gc.memo.insert(x, true);
            return true;
        }
        // Depth first, each identifier's oldest parent first: a wall pointed at by hundreds
        // of comparison objects is found linked through the `^Wall` WME it was made with,
        // without a look at the others.
        gc.visited.clear();
        gc.path.clear();
        gc.visited.insert(x);
        gc.path.push((x, 0));
        let mut found = false;
        'search: while let Some(&(y, start)) = gc.path.last() {
            let parents = self.wm.parent_wmes(y);
            for (i, &(w, _)) in parents.iter().enumerate().skip(start) {
                let Some(p) = self.wm.get(w).map(|wme| wme.id) else {
                    continue;
                };
                match gc.memo.get(&p) {
                    Some(true) => {
                        found = true;
                        break 'search;
                    }
                    Some(false) => continue,
                    None => {}
                }
                if gc.roots.contains(&p) {
                    found = true;
                    break 'search;
                }
                if gc.visited.insert(p) {
                    if let Some(top) = gc.path.last_mut() {
                        top.1 = i + 1;
                    }
                    gc.path.push((p, 0));
                    continue 'search;
                }
            }
            gc.path.pop();
        }
        if found {
            // Everything on the path hangs off the root found.
            for &(y, _) in &gc.path {
                gc.memo.insert(y, true);
            }
        } else {
            for &v in &gc.visited {
                gc.memo.insert(v, false);
            }
        }
        found
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

    /// A built-in or registered RHS function (spec §1f).
    fn call_rhs(&mut self, name: &str, args: &[Sym]) -> Result<Option<Sym>, String> {
        crate::decide::functions::call(self, name, args)
    }

    /// `init-soar` (spec §2, §3a): working memory, preferences, the goal stack, identifier
    /// counters and timetags start again; rules (and chunks) stay.
    pub fn init_soar(&mut self) {
        // Input changes not applied yet go with the rest of working memory.
        self.inputs.queue.clear();
        let all = self.wm.all();
        for w in all.into_iter().rev() {
            self.remove_wme(w);
        }
        self.matches.clear();
        self.decider = crate::decide::state::DecideState::new();
        self.decider.wm_base = (self.wm.additions(), self.wm.removals());
        self.learn.reset_for_init();
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
    }

    /// How many times each rule has fired (`firing-counts`).
    pub fn firing_count(&self, p: ProdId) -> u64 {
        self.decider
            .firing_counts
            .get(p.0 as usize)
            .copied()
            .unwrap_or(0)
    }
}

/// Slots with more preferences than this get sets for their wanted and rejected values.
const LARGE_SLOT: usize = 16;

/// The values a non-context slot's WMEs should show: each acceptable value not rejected,
/// oldest preference first. Linear in the slot, with sets only for large slots (one slot can
/// hold thousands of values, most hold one).
/// Brings a large non-context slot in line for its touched values alone, as the full pass
/// of `update_slots` would: a value shows as a WME while it has an acceptable and no reject
/// preference; removals go in newest-WME-first order, additions in the order of each
/// value's oldest acceptable preference (a new wall brings a hundred comparisons at once).
fn update_touched_values(
    slot: &Slot,
    prefs: &[Preference],
    touched: &mut Vec<Sym>,
    wm: &crate::wm::WorkingMemory,
    removes: &mut Vec<(WmeId, u64)>,
    adds: &mut Vec<(Sym, Sym, Sym, bool)>,
) {
    touched.sort_unstable();
    touched.dedup();
    let mut gone: Vec<(usize, WmeId)> = Vec::new();
    let mut add: Vec<Sym> = Vec::new();
    for &v in touched.iter() {
        let (mut acceptable, mut rejected) = (false, false);
        for pid in slot.prefs_for(v) {
            match prefs[pid as usize].kind {
                PrefType::Reject => rejected = true,
                PrefType::Acceptable => acceptable = true,
                _ => {}
            }
        }
        let wanted = acceptable && !rejected;
        match (wanted, slot.wmes.position(&(v, false))) {
            (false, Some(pos)) => {
                if let Some(w) = slot.wmes.get(&(v, false)) {
                    gone.push((pos, w));
                }
            }
            (true, None) => add.push(v),
            _ => {}
        }
    }
    gone.sort_unstable_by_key(|g| std::cmp::Reverse(g.0));
    removes.extend(
        gone.iter()
            .map(|&(_, w)| (w, wm.get(w).map_or(0, |x| x.timetag))),
    );
    if add.len() > 1 {
        // `add` is sorted (from `touched`): walk the slot's preferences oldest first.
        let mut done = vec![false; add.len()];
        let mut ordered = Vec::with_capacity(add.len());
        for (&pid, &v) in slot.prefs.iter().zip(slot.values()) {
            if let Ok(i) = add.binary_search(&v) {
                if !done[i] && prefs[pid as usize].kind == PrefType::Acceptable {
                    done[i] = true;
                    ordered.push(v);
                }
            }
        }
        add = ordered;
    }
    for v in add {
        adds.push((slot.key.0, slot.key.1, v, false));
    }
}

fn wanted_values<'a>(slot: &Slot, prefs: &[Preference], out: &'a mut Wanted) -> &'a Wanted {
    out.clear();
    let large = slot.prefs.len() > LARGE_SLOT;
    let rejected = |v: Sym, rejects: &FxHashSet<Sym>| {
        if large {
            rejects.contains(&v)
        } else {
            slot.prefs.iter().any(|&q| {
                let q = &prefs[q as usize];
                q.kind == PrefType::Reject && q.value == v
            })
        }
    };
    let rejects: FxHashSet<Sym> = if large {
        slot.prefs
            .iter()
            .map(|&q| &prefs[q as usize])
            .filter(|q| q.kind == PrefType::Reject)
            .map(|q| q.value)
            .collect()
    } else {
        FxHashSet::default()
    };
    for &pid in &slot.prefs {
        let p = &prefs[pid as usize];
        if p.kind == PrefType::Acceptable && !rejected(p.value, &rejects) {
            out.insert(p.value, large);
        }
    }
    out
}

/// Distinct values in first-seen order; a set beside the list once it is large.
#[derive(Debug, Default)]
struct Wanted {
    list: Vec<Sym>,
    set: FxHashSet<Sym>,
}

impl Wanted {
    fn clear(&mut self) {
        self.list.clear();
        if !self.set.is_empty() {
            self.set = FxHashSet::default();
        }
    }

    fn insert(&mut self, v: Sym, large: bool) {
        let new = if large {
            self.set.insert(v)
        } else {
            !self.list.contains(&v)
        };
        if new {
            self.list.push(v);
        }
    }

    fn contains(&self, v: Sym) -> bool {
        if self.set.is_empty() {
            self.list.contains(&v)
        } else {
            self.set.contains(&v)
        }
    }

    fn list(&self) -> &[Sym] {
        &self.list
    }
}

/// The working sets of one garbage collection, kept between collections for their room.
#[derive(Debug, Default)]
pub(crate) struct GcScratch {
    roots: FxHashSet<Sym>,
    memo: FxHashMap<Sym, bool>,
    dead: FxHashSet<Sym>,
    visited: FxHashSet<Sym>,
    /// The upward search's path: each identifier with the index of its next parent.
    path: Vec<(Sym, usize)>,
    stack: Vec<Sym>,
}

impl GcScratch {
    fn clear(&mut self) {
        self.roots.clear();
        self.memo.clear();
        self.dead.clear();
        self.visited.clear();
        self.path.clear();
        self.stack.clear();
    }
}

/// The buffers of one elaboration cycle, kept between cycles for their room.
#[derive(Debug, Default)]
pub(crate) struct CycleScratch {
    keep: Vec<(ProdId, TokId)>,
    queued: Vec<Queued>,
    retracted_levels: Vec<Option<u32>>,
    levels: Vec<u32>,
    to_fire_insts: Vec<InstId>,
    retracted: Vec<InstId>,
    new_prefs: Vec<PrefId>,
}

/// A match pending at the start of an elaboration cycle (spec §3b).
#[derive(Debug, Clone, Copy)]
struct Queued {
    prod: ProdId,
    tok: TokId,
    /// Its goal's level.
    level: u32,
    o_support: bool,
    fired: bool,
}

/// The buffers of one working-memory phase, kept between phases for their room.
#[derive(Debug, Default)]
pub(crate) struct SlotScratch {
    adds: Vec<(Sym, Sym, Sym, bool)>,
    removes: Vec<(WmeId, u64)>,
    context: Vec<(Sym, Sym)>,
    added: Vec<WmeId>,
    want: Wanted,
}
