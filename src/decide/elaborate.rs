//! One elaboration cycle (Soar manual, chapter 2, "Soar's Execution Cycle: Without Substates", and
//! 2.7.8 "Soar's Cycle: With Substates"): the pending matches of one support type fire at the
//! highest goal with activity and then at each lower one (the "waterfall"), the active goal's
//! retractions follow, and the working-memory phase makes the changes together. Also the
//! support of new matches, decided as they are queued.

use super::compiled::{Act, Term};
use super::scratch::Queued;
use super::state::{InstId, Phase};
use crate::agent::AgentCore;
use crate::rete::{ProdId, TokId};
use crate::trace_events::TraceEvent;

impl AgentCore {
    /// Decides the support of the matches made since the last call, as 9.6's matcher does
    /// when it queues them, with its warning for rules that both elaborate and apply the
    /// operator (observed on 9.6).
    pub(crate) fn classify_new_matches(&mut self) {
        self.matches.compact();
        let at = self.decider.queued_matches_at;
        let mut queued = String::new();
        let n = self.matches.assertions.len();
        for i in 0..n {
            let key = self.matches.assertions[i];
            if self.matches.support.contains_key(&key) {
                continue;
            }
            self.compiled_rule(key.0);
            let s = crate::decide::support::match_support(self, key.0, key.1);
            if s.mixed && self.settings.warnings {
                let mut out = std::mem::take(&mut self.output);
                let rule = self.production_name(key.0);
                self.write_event(&mut out, &TraceEvent::MixedOperatorElaborations { rule });
                self.output = out;
            }
            if self.settings.trace.assertions {
                self.trace_queued_match(&mut queued, at, key.0, s.o_support);
            }
            self.matches.support.insert(key, s.o_support);
        }
        if !queued.is_empty() {
            match at.filter(|&a| a <= self.output.len()) {
                Some(a) => {
                    self.output.insert_str(a, &queued);
                    self.decider.queued_matches_at = Some(a + queued.len());
                }
                None => self.output.push_str(&queued),
            }
        }
    }

    /// With `trace --assertions`, the matches a WME change just made are classified at
    /// once, as 9.6's matcher queues them, so that each gets its `RETE: putting` line
    /// even when it goes again before the phase ends.
    #[inline]
    pub(crate) fn trace_queued_matches_now(&mut self) {
        if self.settings.trace.assertions && self.matches.has_assertions() {
            self.classify_new_matches();
        }
    }

    /// Marks where the print stream stands as the place of the `RETE: putting` lines of
    /// the matches the changes about to be traced make, unless a place is marked already:
    /// 9.6 changes the matcher for a whole batch of changes before it traces them.
    pub(crate) fn mark_queued_matches(&mut self) {
        if self.settings.trace.assertions && self.decider.queued_matches_at.is_none() {
            self.decider.queued_matches_at = Some(self.output.len());
        }
    }

    /// Ends the batch of changes [`Self::mark_queued_matches`] began: the `RETE: putting`
    /// lines that follow go where the print stream stands.
    pub(crate) fn end_queued_matches(&mut self) {
        self.decider.queued_matches_at = None;
    }

    /// `RETE: putting [rule] into ms_o_assertions` (`trace --assertions`) into `queued`,
    /// the lines that go at `at` in the print stream (at its end when `None`): 9.6 prints
    /// them as the matcher queues the match, before the phase's `=>WM:` lines.
    fn trace_queued_match(&self, queued: &mut String, at: Option<usize>, p: ProdId, o: bool) {
        // Whether the stream stands at a line's start where the lines go.
        let line_start = match at.filter(|&a| a <= self.output.len()) {
            _ if !queued.is_empty() => false,
            Some(0) => self.output_line_start,
            Some(a) => self.output.as_bytes()[a - 1] == b'\n',
            None => self.at_line_start(),
        };
        let event = TraceEvent::MatchQueued {
            rule: self.production_name(p),
            o_support: o,
        };
        self.trace_text.write(queued, line_start, &self.symbols, &event);
    }

    /// One elaboration cycle: the pending matches of one support type fire at the active
    /// goal and then at each lower goal with activity, the active goal's retractions
    /// follow, then the working-memory changes happen together.
    pub(super) fn elaboration_cycle(&mut self) -> bool {
        self.decider.e_cycles += 1;
        self.decider.e_cycles_this_phase += 1;
        let apply = self.decider.phase == Some(Phase::Apply);
        let retractions = std::mem::take(&mut self.matches.retractions);
        self.matches.compact();
        // Working-memory activation counts the WMEs of every match about to fire.
        if self.wma.on() {
            self.wma_tested_in_prods();
        }
        let mut pending = std::mem::take(&mut self.matches.assertions);
        let mut sc = std::mem::take(&mut self.decider.cycle_scratch);
        // Token ids are reused: resolve retractions to their instantiations before new
        // matches (possibly on a reused id) fire. Those a higher goal kept waiting in
        // earlier cycles come first (they are older).
        let mut retracted = std::mem::take(&mut sc.retracted);
        retracted.append(&mut self.decider.waiting_retractions);
        retracted.retain(|&i| self.decider.insts[i].alive);
        // Justifications that lost a WME retract with them, each in its place among the
        // rules' retractions (see `justification_wme_added`).
        let mut justified = std::mem::take(&mut self.decider.justification_retractions);
        if justified.is_empty() {
            retracted.extend(
                retractions
                    .iter()
                    .filter_map(|k| self.decider.inst_by_token.remove(k)),
            );
        } else {
            self.merge_justification_retractions(
                &retractions,
                &mut justified,
                &mut retracted,
                &mut sc.pending_retractions,
            );
        }
        justified.clear();
        self.decider.justification_retractions = justified;
        let mut retractions = retractions;
        retractions.clear();
        if self.matches.retractions.is_empty() {
            self.matches.retractions = retractions;
        }
        // The waterfall: the pending matches by goal level, newest first (the order 9.6
        // fires them in), with their support.
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
            self.decider.insts[i]
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
        // The firing type: IE before PE. In the apply phase PE only when the active goal
        // has no i-activity, where retractions count too (consistency.cpp
        // `i_activity_at_goal`); IE when only retractions of goals that are gone are left.
        let o_support = match (apply, top) {
            (true, Some(g)) => {
                !queued.iter().any(|q| q.level == g && !q.o_support)
                    && !retracted_levels.contains(&Some(g))
            }
            _ => false,
        };
        self.decider.pe_cycles += u64::from(o_support);
        self.decider.last_wave_o_support = o_support;
        if apply && self.settings.trace.phases {
            self.emit(&TraceEvent::FiringProductions {
                o_support,
                depth: top.unwrap_or(0),
            });
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
        // Past the preference ceiling the rest of the cycle's matches wait: one cycle of a
        // rule that joins a state's WMEs with themselves can make a hundred thousand.
        let mut over_ceiling = None;
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
                if self.preferences_over_ceiling() {
                    over_ceiling = Some(self.decider.live_prefs() as u64);
                    break;
                }
            }
            if exist && l > next_change {
                next_change = l;
            }
            // New preferences go in before the retractions are processed (9.6 prints the
            // `+` lines before `Retracting`), which sets the order slots change in.
            self.assert_preferences(&new_prefs);
            new_prefs.clear();
            if over_ceiling.is_some() {
                break;
            }
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
        // blocks-world matches 9.6 at trace 4 and 5).
        if self.settings.trace.preferences || self.settings.trace.any_firings() {
            for &inst in now.iter().rev() {
                self.trace_retraction(inst);
            }
        }
        for &inst in now.iter().rev() {
            self.retract(inst);
        }
        if apply && self.settings.trace.phases {
            self.emit(&TraceEvent::ChangeWorkingMemory { o_support });
        }
        now.clear();
        retracted.clear();
        sc.to_fire_insts = now;
        sc.retracted = retracted;
        sc.new_prefs = new_prefs;
        self.decider.cycle_scratch = sc;
        // Firings past the preference ceiling stop before their changes reach the matcher,
        // where one cycle's worth can exhaust memory; the slots keep their changes for the
        // run that goes on.
        if let Some(count) = over_ceiling {
            // The cycle's retractions may have brought the count down again: the run stops
            // all the same, or it would go on a firing a cycle.
            self.preference_ceiling_reached(count);
            return true;
        }
        if self.preferences_over_ceiling() {
            self.ceiling_reached();
            return true;
        }
        self.update_slots();
        // Semantic memory stores what the rules asked it to store, at once.
        self.smem_after_elaboration((apply && self.settings.trace.phases).then_some(o_support));
        true
    }

    /// The rules' retractions (`retractions`, as the matcher reported them) with the
    /// justifications' (`justified`), as instantiations in the order of
    /// [`Self::pending_retractions`], after those already in `retracted`.
    fn merge_justification_retractions(
        &mut self,
        retractions: &[(ProdId, TokId)],
        justified: &mut [(InstId, u64, usize)],
        retracted: &mut Vec<InstId>,
        order: &mut Vec<PendingRetraction>,
    ) {
        self.pending_retractions(retractions.len(), justified, order);
        for &pending in order.iter() {
            match pending {
                PendingRetraction::Justification(i) => {
                    if !retracted.contains(&i) {
                        retracted.push(i);
                    }
                }
                PendingRetraction::Rule(at) => {
                    if let Some(i) = self.decider.inst_by_token.remove(&retractions[at]) {
                        retracted.push(i);
                    }
                }
            }
        }
    }

    /// The order the next elaboration cycle takes its retractions in: the `rules` the
    /// matcher reported (by their place in `MatchSet::retractions`), with each
    /// justification that lost a WME (`justified`: its instantiation, the serial it was
    /// made with, and the place it goes before, past the end for after them all) in its
    /// place, once, while its instantiation is still the one recorded. `justified` is
    /// sorted here by its places; `order` receives the result.
    pub(crate) fn pending_retractions(
        &self,
        rules: usize,
        justified: &mut [(InstId, u64, usize)],
        order: &mut Vec<PendingRetraction>,
    ) {
        justified.sort_by_key(|&(_, _, at)| at.min(rules));
        order.clear();
        let mut next = justified.iter().peekable();
        for at in 0..=rules {
            while let Some(&(i, serial, _)) = next.next_if(|j| j.2.min(rules) <= at) {
                let inst = &self.decider.insts[i];
                let listed = order.contains(&PendingRetraction::Justification(i));
                if inst.alive && inst.serial == serial && !listed {
                    order.push(PendingRetraction::Justification(i));
                }
            }
            if at < rules {
                order.push(PendingRetraction::Rule(at));
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
        let mut waits = None;
        for action in rule.actions.iter() {
            let Act::Make { id, .. } = action else {
                continue;
            };
            let sym = match id {
                Term::Sym(s) => Some(*s),
                Term::Bound(depth, field) => self.rete.field_at(&wmes, *depth, *field),
                _ => None,
            };
            let level = sym.and_then(|s| Some((s, self.symbols.id_data(s)?.level)));
            if let Some((s, l)) = level.filter(|&(_, l)| l <= change_level) {
                waits = Some((s, l));
                break;
            }
        }
        self.decider.rhs_wmes = wmes;
        // 9.6 tries the firing and aborts it, saying so (checked on soar-sml 9.6.5).
        if let Some((id, level)) = waits {
            if self.settings.trace.waterfall {
                self.emit(&crate::trace_events::TraceEvent::WaterfallAbort {
                    id,
                    level,
                    change_level,
                });
            }
        }
        waits.is_some()
    }
}

/// A retraction the next elaboration cycle takes (see `AgentCore::pending_retractions`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum PendingRetraction {
    /// The rule retraction at this place in `MatchSet::retractions`.
    Rule(usize),
    /// A justification's instantiation.
    Justification(InstId),
}
