//! One learning episode (Soar manual, ch. 4, "Procedural Knowledge Learning"): a substate
//! firing made results; backtrace them, build a chunk (when learning is on for that state)
//! or a justification, and give the results to that rule's instantiation, whose support
//! they take (Soar manual, ch. 2, "Justifications: Support for results"). A result that is
//! still a result one level up (a level-3 firing returning to the top state) is learned
//! again from that instantiation, as 9.6 does (`chunkx2*...`).

use super::backtrace::Backtrace;
use super::sketch::Body;
use super::{InstTrace, Justification, PrefOrigin, TraceCond};
use crate::agent::{Added, AgentCore, LearnMode};
use crate::decide::procedure::PrefType;
use crate::decide::state::{ImpasseKind, InstId, Instantiation, PrefId};
use crate::production::Production;
use crate::rete::{ProdId, TokId};
use crate::symbols::Sym;
use crate::trace_events::TraceEvent;
use rustc_hash::{FxHashMap, FxHashSet};
use std::sync::Arc;

/// A rule name's base and generation: `chunkx2*foo*t6-2` was learned from a chunk of
/// `foo`; a user rule is its own base.
pub(crate) fn chunk_base(name: &str, is_chunk: bool) -> (String, u32) {
    if !is_chunk {
        return (name.to_string(), 0);
    }
    let (gen, rest) = if let Some(r) = name.strip_prefix("chunk*") {
        (1, r)
    } else if let Some(r) = name.strip_prefix("chunkx") {
        let digits: String = r.chars().take_while(char::is_ascii_digit).collect();
        let g = digits.parse().unwrap_or(2);
        (g, r[digits.len()..].trim_start_matches('*'))
    } else {
        return (name.to_string(), 0);
    };
    // Drop `*t<...>` and an impasse suffix before it.
    let mut parts: Vec<&str> = rest.split('*').collect();
    if parts.last().is_some_and(|p| p.starts_with('t')) {
        parts.pop();
    }
    if parts.last().is_some_and(|p| {
        matches!(
            *p,
            "Tie" | "Conflict" | "Failure" | "OpNoChange"
        )
    }) {
        parts.pop();
    }
    (parts.join("*"), gen)
}

/// The identities of the fields of a chunk's `k`-th action, in a recorded firing of it.
fn action_idents(trace: &InstTrace, prod: &Production, k: usize) -> [super::Ident; 4] {
    let Some(crate::production::Action::Make(m)) = prod.actions.get(k) else {
        return [0; 4];
    };
    let ident = |t: &crate::production::RhsTerm| match t {
        crate::production::RhsTerm::Var(v) => trace.vars.get(v).map_or(0, |x| x.0),
        _ => 0,
    };
    [
        ident(&m.id),
        ident(&m.attr),
        ident(&m.value),
        m.referent.as_ref().map_or(0, ident),
    ]
}

impl AgentCore {
    /// The results among a firing's preferences (Soar manual, ch. 2, "Results"): those for
    /// objects of a higher level, and everything on the substate's objects they link up,
    /// which move up to that level. They come in 9.6's order (its chunker's list of
    /// results): the firing's preferences are looked at newest first, and each result is
    /// followed at once into the substate object its value names, whose slots go newest
    /// first, each slot's preferences newest first then its WMEs' values, then the firing's
    /// own preferences for that object; each result found goes before those found earlier.
    pub(crate) fn find_results(&mut self, made: &[PrefId], level: u32) -> Vec<PrefId> {
        // Most firings make no preference on an object above their state.
        let seeds = made.iter().rev().copied().filter(|&p| {
            let l = self.sym_level(self.decider.prefs[p].id);
            l > 0 && l < level
        });
        let seeds: Vec<PrefId> = seeds.collect();
        if seeds.is_empty() {
            return Vec::new();
        }
        let mut walk = ResultsWalk {
            found: Vec::new(),
            seen: std::mem::take(&mut self.learn.results_seen),
            walked: FxHashSet::default(),
            stack: Vec::new(),
            retrieved_idents: FxHashMap::default(),
        };
        walk.seen.clear();
        for p in seeds {
            let id = self.decider.prefs[p].id;
            if !walk.walked.contains(&id) {
                self.add_result(&mut walk, p, made, level);
            }
        }
        // The objects the results link move up to the level of the object each is put on.
        for &r in &walk.found {
            let p = &self.decider.prefs[r];
            let target = self.sym_level(p.id);
            for x in [Some(p.value), p.referent].into_iter().flatten() {
                self.promote(x, target);
            }
        }
        self.learn.results_seen = walk.seen;
        walk.found.reverse();
        walk.found
    }

    /// One result found (see [`Self::find_results`]), and what it leads to, depth first.
    fn add_result(&mut self, walk: &mut ResultsWalk, first: PrefId, made: &[PrefId], level: u32) {
        walk.stack.push(ResultStep::Pref(first));
        while let Some(step) = walk.stack.pop() {
            match step {
                ResultStep::Pref(r) => {
                    if !self.is_new_result(walk, r) {
                        continue;
                    }
                    walk.found.push(r);
                    walk.seen.insert(r);
                    let p = &self.decider.prefs[r];
                    let ids = p.origin.as_ref().map_or([0; 4], |o| o.ids);
                    let linked = [Some((p.value, ids[2])), p.referent.map(|x| (x, ids[3]))];
                    // The value first, then the referent: pushed last first.
                    for (x, ident) in linked.iter().rev().flatten() {
                        if !self.learn.memory_results.is_empty() {
                            walk.retrieved_idents.entry(*x).or_insert(*ident);
                        }
                        walk.stack.push(ResultStep::Object(*x));
                    }
                }
                ResultStep::Object(x) => {
                    if !self.symbols.is_id(x)
                        || self.sym_level(x) < level
                        || self.symbols.is_goal(x)
                        || !walk.walked.insert(x)
                    {
                        continue;
                    }
                    let steps = self.object_steps(x, made, level, &mut walk.retrieved_idents);
                    // Pushed last first, so that they are taken in order.
                    walk.stack.extend(steps.into_iter().rev());
                }
            }
        }
    }

    /// What 9.6 looks at on an object a result links: each slot, newest first, with its
    /// preferences newest first and then its WMEs' values newest first; a memory's
    /// retrievals on it; the firing's own preferences for it, newest first.
    fn object_steps(
        &mut self,
        x: Sym,
        made: &[PrefId],
        level: u32,
        retrieved_idents: &mut FxHashMap<Sym, super::Ident>,
    ) -> Vec<ResultStep> {
        let mut steps = Vec::new();
        let slots = &self.decider.slots;
        for &attr in slots.attrs_of(x).iter().rev() {
            let Some(slot) = slots.get(&(x, attr)) else {
                continue;
            };
            let prefs = &self.decider.prefs;
            // A retrieval's own preferences come as `retrieved_result_prefs`.
            steps.extend(
                slot.prefs
                    .iter()
                    .rev()
                    .filter(|&&q| !prefs[q].recall)
                    .map(|&q| ResultStep::Pref(q)),
            );
            steps.extend(
                slot.wmes
                    .values()
                    .rev()
                    .filter_map(|w| self.wm.get(w))
                    .map(|w| ResultStep::Object(w.value)),
            );
        }
        // (`retrieved_result_prefs` lists them in the order the learned rule makes them,
        // the reverse of the order they are found in.)
        let retrieved = self.retrieved_result_prefs(x, level, retrieved_idents);
        steps.extend(retrieved.into_iter().rev().map(ResultStep::Pref));
        let prefs = &self.decider.prefs;
        steps.extend(
            made.iter()
                .rev()
                .filter(|&&q| prefs[q].id == x)
                .map(|&q| ResultStep::Pref(q)),
        );
        steps
    }

    /// Whether `r` is a result not yet found: 9.6 takes one preference for each (object,
    /// attribute, value, kind, referent).
    fn is_new_result(&self, walk: &ResultsWalk, r: PrefId) -> bool {
        if walk.seen.contains(&r) {
            return false;
        }
        let prefs = &self.decider.prefs;
        let p = &prefs[r];
        let same = |q: &PrefId| {
            let q = &prefs[*q];
            (q.id, q.attr, q.value, q.kind, q.referent) == (p.id, p.attr, p.value, p.kind, p.referent)
        };
        !walk.found.iter().any(same)
    }

    /// Moves an identifier (and what hangs off it) up to `level`; returns those moved.
    fn promote(&mut self, x: Sym, level: u32) -> Vec<Sym> {
        let mut moved = Vec::new();
        let mut stack = vec![x];
        while let Some(y) = stack.pop() {
            match self.symbols.id_data_mut(y) {
                Some(d) if d.level > level && !d.is_goal => d.level = level,
                _ => continue,
            }
            moved.push(y);
            for w in self.wm.of_id(y) {
                if let Some(wme) = self.wm.get(w) {
                    if self.symbols.is_id(wme.value) {
                        stack.push(wme.value);
                    }
                }
            }
        }
        moved
    }

    /// Learns from the results of a firing at `level` whose trace is `source`.
    pub(crate) fn learn_from_results(
        &mut self,
        results: Vec<PrefId>,
        level: u32,
        source: &InstTrace,
        new_prefs: &mut Vec<PrefId>,
    ) {
        // Backtrace tables are reused from episode to episode: they keep their room.
        let mut bt = self.learn.spare_backtraces.pop().unwrap_or_default();
        self.learn.backtraces_begun += 1;
        bt.reset(level, self.learn.backtraces_begun);
        let retrieved: Vec<PrefId> = results
            .iter()
            .copied()
            .filter(|&r| self.is_retrieved_result(r))
            .collect();
        self.learn_by_backtrace(&mut bt, results, source, new_prefs);
        // What a retrieval made stays as it is: its results served the rule alone.
        for r in retrieved {
            self.decider.free_pref(r);
        }
        bt.reset(0, 0);
        self.learn.spare_backtraces.push(bt);
    }

    fn learn_by_backtrace(
        &mut self,
        bt: &mut Backtrace,
        results: Vec<PrefId>,
        source: &InstTrace,
        new_prefs: &mut Vec<PrefId>,
    ) {
        let level = bt.level;
        let quiescence = self.symbols.str("quiescence");
        let t = self.symbols.str("t");
        for &r in &results {
            if let Some(o) = self.decider.prefs[r].origin.clone() {
                bt.result(&o, self, quiescence, t);
            }
        }
        let bt_text = self
            .settings
            .trace
            .backtracing
            .then(|| self.backtrace_trace(bt, &results));
        if bt.grounds.is_empty() {
            if let Some(text) = bt_text {
                self.output.push_str(&text);
            }
            // No superstate knowledge tested: nothing to learn (9.6 skips it too).
            self.learn.stats.firings_backtraced += bt.firings as u64;
            self.learn.stats.no_grounds += 1;
            return;
        }
        bt.join_same_identifiers(&self.symbols);
        let goal = self
            .decider
            .goals
            .iter()
            .find(|g| g.level == level)
            .map(|g| g.state);
        let want_chunk = match self.settings.learn {
            LearnMode::Always => true,
            LearnMode::Never => false,
            LearnMode::Only => goal.is_some_and(|g| self.learn.force_learn.contains(&g)),
            LearnMode::Except => !goal.is_some_and(|g| self.learn.dont_learn.contains(&g)),
        };
        // `chunk bottom-only`: a state above one that learned a rule learns none.
        let want_chunk = want_chunk
            && !(self.settings.chunk.bottom_only
                && self
                    .decider
                    .goals
                    .iter()
                    .any(|g| g.level == level && g.learned_below));
        // `chunk allow-local-negations off`: reasoning that tested the absence of substate
        // knowledge gives a justification, not a chunk (Soar manual, ch. 4, "Using
        // negated conditions about the substate"; checked on soar-sml 9.6.5: agent
        // learn-local-negation-off).
        let local_negation = self.tests_local_negation(bt);
        let refused = want_chunk && local_negation && !self.settings.chunk.allow_local_negations;
        // A result past `max-chunks` is not analyzed at all (below): 9.6 traces nothing.
        let past_max_chunks = want_chunk
            && !refused
            && !bt.tested_quiescence
            && self.learn.chunks_this_phase >= self.settings.max_chunks;
        if let Some(text) = bt_text.filter(|_| !past_max_chunks) {
            self.output.push_str(&text);
        }
        if refused && self.settings.trace.chunk_warnings {
            let conditions = self.local_negation_texts(bt);
            self.emit(&TraceEvent::LocalNegationRefused {
                conditions: &conditions,
            });
        }
        let want_chunk = want_chunk && !refused;
        let mut chunk: Option<(ProdId, Arc<Production>)> = None;
        let mut duplicate = false;
        // The rule whose firing made the result: max-dupes counts per rule, per phase.
        let dupes_of = source.name.clone();
        let dupes = self
            .learn
            .dupes_this_phase
            .get(&dupes_of)
            .copied()
            .unwrap_or(0);
        if want_chunk && bt.tested_quiescence {
            self.learn.stats.tested_quiescence += 1;
        }
        if want_chunk
            && !bt.tested_quiescence
            && self.learn.chunks_this_phase >= self.settings.max_chunks
        {
            self.learn.stats.max_chunks += 1;
            // 9.6 learns nothing then, not even a justification: the results stay with the
            // substate's firing.
            if self.settings.trace.chunk_warnings {
                self.emit(&TraceEvent::MaxChunksReached);
            }
            return;
        }
        // 9.6 checks max-chunks before it analyzes the substate: a substate skipped for it
        // is neither counted nor backtraced in `chunk stats`.
        self.learn.substates_analyzed += 1;
        self.learn.stats.firings_backtraced += bt.firings as u64;
        if want_chunk && !bt.tested_quiescence {
            if dupes >= self.settings.max_dupes {
                self.learn.stats.max_dupes += 1;
                // This rule's results keep giving rules already known: give up on it for
                // the rest of the phase (its result gets a justification).
            } else {
                let name = self.chunk_name(source, level);
                let prod = self.build_learned_rule(bt, &results, name.clone(), true);
                if bt.tested_ltm {
                    self.learn.stats.ltm_chunks += 1;
                }
                let constraints = super::stats::operational_constraints(&prod);
                self.learn.stats.note_identities(bt);
                // The learned rule's match that its own instantiation takes over below is
                // not queued (9.6 refracts it): its other matches are traced after that.
                let traced = std::mem::replace(&mut self.settings.trace.assertions, false);
                let added = self.add_production(prod);
                self.settings.trace.assertions = traced;
                match added {
                    // A learned rule's conditions are connected to its state.
                    Added::Rejected { .. } => {}
                    Added::Duplicate { .. } => {
                        duplicate = true;
                        // 9.6 makes the rule's instantiation, and counts its constraints,
                        // before it finds the rule known.
                        self.learn.stats.learned_instantiations += 1;
                        self.learn.stats.operational_constraints += constraints;
                        self.learn.duplicates += 1;
                        self.learn.stats.duplicates += 1;
                        *self.learn.dupes_this_phase.entry(dupes_of).or_default() += 1;
                    }
                    _ => {
                        self.learn.chunks_learned += 1;
                        self.learn.chunks_since_init += 1;
                        self.learn.learned_this_run += 1;
                        self.learn.chunks_this_phase += 1;
                        self.learn.stats.operational_constraints += constraints;
                        self.learn.stats.conditions_merged += bt.merged as u64;
                        if local_negation {
                            self.learn.stats.local_negation_chunks += 1;
                        }
                        if let (Some(l), Some(p)) = (self.loaded(&name), self.production_arc(&name))
                        {
                            chunk = Some((l.id, p));
                        }
                        self.learn.explainer.note_learned(&name, &source.name, true);
                        self.print_learned(&name);
                        self.rule_learned_at(level);
                    }
                }
            }
        }
        if duplicate {
            // 9.6 keeps nothing of results whose rule it has already learned: no
            // justification, and the results are not asserted, the rule learned before
            // making them (checked on soar-sml 9.6.5: agent learn-except after
            // `init-soar`, where `preferences` lists only the earlier chunk's).
            new_prefs.retain(|p| !results.contains(p));
            for &r in &results {
                self.decider.free_pref(r);
            }
            return;
        }
        let ground_wmes: Vec<_> = bt.grounds.iter().map(|g| g.cond.wme_id).collect();
        let owner_level = bt.grounds.iter().map(|g| g.cond.level).max().unwrap_or(1);
        let refracted = chunk
            .as_ref()
            .and_then(|(pid, _)| self.take_refracted_match(*pid, &ground_wmes));
        self.trace_queued_matches_now();
        let chunk_match = chunk
            .as_ref()
            .zip(refracted)
            .map(|((p, prod), t)| (*p, t, prod.clone()));
        let (inst_id, o_support, name) = match (&chunk, refracted) {
            (Some((pid, prod)), Some(tok)) => {
                let o = crate::decide::support::match_support(self, *pid, tok).o_support;
                let inst = Instantiation {
                    prod: *pid,
                    token: tok,
                    goal: crate::decide::support::match_goal(self, *pid, tok),
                    o_support: o,
                    prefs: Vec::new(),
                    alive: true,
                    serial: 0,
                    gds_evaluated: false,
                };
                let id = self.decider.alloc_inst(inst);
                self.learn.stats.learned_instantiations += 1;
                self.decider.inst_by_token.insert((*pid, tok), id);
                if self.settings.trace.wme_detail != crate::agent::WmeDetail::None {
                    // What its retraction lists (`trace --timetags`): the WMEs of its match,
                    // those gone by then too, as for a rule's firing.
                    let wmes = self.match_wme_list(*pid, tok);
                    self.decider.traced_match_wmes.insert(id, wmes);
                }
                (id, o, prod.name.to_string())
            }
            _ => {
                // A justification: named unless a chunk was learned (and only failed to
                // match at once).
                let named = chunk.is_none();
                let o = self.justification_support(bt, &results);
                let name = if named {
                    self.justification_name(source, level)
                } else {
                    chunk.as_ref().map(|c| c.1.name.to_string()).unwrap_or_default()
                };
                let id = self.add_justification(bt, &results, &name, named, o);
                // 9.6's explainer records nothing while learning is off.
                if named && self.settings.learn != LearnMode::Never {
                    self.learn.explainer.note_learned(&name, &source.name, false);
                }
                (id, o, name)
            }
        };
        // The results' copies, owned by the learned rule's instantiation (the originals
        // stay with the substate's firing, as 9.6 lists both).
        // An o-supported result outlives the chunk's instantiation under the chunk's name
        // (9.6 names the chunk when an o-reject takes it: agent learn-negation, trace 5).
        let chunk_rule = chunk_match.as_ref().map(|(pid, _, _)| *pid);
        // A chunk's instantiation is recorded like any firing of it (its own variables and
        // tests carry on to a learning episode one level up), but without operator
        // selection knowledge (9.6 builds it from the rule, not from a match); a
        // justification keeps the grounds, a literalized identity becoming a literal.
        let recorded = chunk_match.and_then(|(pid, tok, prod)| {
            let trace = self.record_firing(pid, tok, &prod, &[], &[], false)?;
            Some((trace, prod))
        });
        let trace = match &recorded {
            Some((t, _)) => t.clone(),
            None => Arc::new(InstTrace {
                name: name.as_str().into(),
                prod: None,
                conds: bt
                    .grounds
                    .iter()
                    .map(|g| TraceCond {
                        ids: g.cond.ids.map(|i| {
                            let r = bt.find(i);
                            if bt.literal.contains_key(&r) {
                                0
                            } else {
                                r
                            }
                        }),
                        cond: None,
                        via_item: false,
                        ..g.cond.clone()
                    })
                    .collect(),
                vars: Default::default(),
                base: source.base.clone(),
                generation: source.generation,
                level: self.decider.insts[inst_id]
                    .goal
                    .map_or(0, |g| self.sym_level(g)),
                backtraced: Default::default(),
            }),
        };
        if self.settings.trace.assertions {
            self.decider
                .instantiations_made
                .push((name.clone(), new_prefs.len()));
        }
        // Where each result's action is in the learned rule (see `learned_action_order`),
        // for the recorded firing of a chunk.
        let mut action_of = vec![0; if recorded.is_some() { results.len() } else { 0 }];
        if recorded.is_some() {
            for (j, k) in self.learned_action_order(bt, &results).into_iter().enumerate() {
                action_of[k] = j;
            }
        }
        let mut clones = Vec::with_capacity(results.len());
        for (k, &r) in results.iter().enumerate() {
            if self.is_retrieved_result(r) {
                continue;
            }
            let mut p = self.decider.prefs[r].clone();
            let ids = match &recorded {
                Some((t, prod)) => action_idents(t, prod, action_of[k]),
                None => p
                    .origin
                    .as_ref()
                    .map_or([0; 4], |o| o.ids.map(|i| bt.find(i))),
            };
            // A reject the substate made o-supported stays an o-reject in the copy: 9.6
            // applies it as one (no `+` line), and the learned instantiation keeps nothing
            // of it to retract (checked on soar-sml 9.6.5:
            // tests/commands/agents/o-reject-result.soar, traces 3 and 5, with learning
            // off and under `chunk always`).
            p.o_support = o_support || (p.kind == PrefType::Reject && p.o_support);
            p.inst = Some(inst_id);
            if chunk_rule.is_some() {
                p.rule = chunk_rule;
            }
            p.alive = true;
            p.freed = false;
            p.origin = Some(Arc::new(PrefOrigin {
                trace: trace.clone(),
                ids,
                action: recorded.as_ref().map(|_| action_of[k]),
            }));
            let o_reject = p.kind == PrefType::Reject && p.o_support;
            let pid = self.decider.alloc_pref(p);
            if o_reject {
                self.decider.results_taken_by_o_rejects.push(r);
            }
            self.decider.insts[inst_id].prefs.push(pid);
            new_prefs.push(pid);
            clones.push(pid);
        }
        // The learned rule's instantiation belongs to its match goal: a substate there
        // lists the copies among its firings' preferences when it goes (checked on
        // soar-sml 9.6.5: agent learn-lookahead, trace 5).
        let goal = self.decider.insts[inst_id].goal;
        if goal.is_some_and(|g| self.sym_level(g) >= 2) {
            for &pid in clones.iter().rev() {
                self.note_goal_pref(goal, pid);
            }
        }
        // The learned rule's instantiation is a firing in its own state, which 9.6 learns
        // from in turn (and warns about, when that state keeps from learning).
        if owner_level >= 2 && self.settings.trace.chunk_warnings {
            self.note_state_not_learning(owner_level, &trace.name);
        }
        // Still results one level up: learn again from this instantiation.
        if owner_level >= 2 {
            let again = self.find_results(&clones, owner_level);
            if !again.is_empty() {
                self.learn_from_results(again, owner_level, &trace, new_prefs);
            }
        }
    }

    /// `chunk only` and `chunk except` say, for each firing in a substate that they keep
    /// from learning, that it will not be learned from (9.6 does so whether or not the
    /// firing made results).
    pub(crate) fn note_state_not_learning(&mut self, level: u32, rule: &str) {
        let Some(state) = self
            .decider
            .goals
            .iter()
            .find(|g| g.level == level)
            .map(|g| g.state)
        else {
            return;
        };
        let flagged = match self.settings.learn {
            LearnMode::Only if !self.learn.force_learn.contains(&state) => false,
            LearnMode::Except if self.learn.dont_learn.contains(&state) => true,
            _ => return,
        };
        let state = self.symbols.text(state);
        self.emit(&TraceEvent::NotLearning {
            rule,
            state: &state,
            flagged,
        });
    }

    /// A justification's name: `justify<n>` (odd numbers) with learning off; with learning
    /// on, named like a chunk (`justify*<rule>*t<dc>-<n>`), counted apart from chunks (a
    /// result in a state `chunk only` or `chunk except` keeps from learning, or one that
    /// tested `^quiescence t`).
    fn justification_name(&mut self, source: &InstTrace, level: u32) -> String {
        if self.settings.learn == LearnMode::Never
            || self.settings.chunk.naming_style == crate::learn::settings::NamingStyle::Numbered
        {
            self.learn.justification_counter += 2;
            return format!("justify{}", self.learn.justification_counter - 1);
        }
        let dc = self.decider.d_cycle_count;
        if self.learn.justification_name_dc != dc {
            self.learn.justification_name_dc = dc;
            self.learn.justification_name_count = 0;
        }
        self.learn.justification_name_count += 1;
        let count = self.learn.justification_name_count;
        let name = self.rule_style_name("justify", source, level, count);
        if self.productions_contains(&name) {
            format!("{name}-{}", self.learn.justifications_learned)
        } else {
            name
        }
    }

    /// `chunk*<rule>*[<impasse>*]t[<init+1>-]<dc>-<n>` as the official kernel names chunks.
    /// The impasse is that of the goal the result goes to, when that goal is a substate;
    /// 9.6 calls every no-change `OpNoChange` there, a state no-change too.
    fn chunk_name(&mut self, source: &InstTrace, level: u32) -> String {
        let dc = self.decider.d_cycle_count;
        if self.learn.chunk_name_dc != dc {
            self.learn.chunk_name_dc = dc;
            self.learn.chunk_name_count = 0;
        }
        self.learn.chunk_name_count += 1;
        if self.settings.chunk.naming_style == crate::learn::settings::NamingStyle::Numbered {
            // 9.6 counts two for each name it makes.
            self.learn.chunk_number += 2;
            return format!("chunk{}", self.learn.chunk_number - 1);
        }
        let count = self.learn.chunk_name_count;
        let name = self.rule_style_name("chunk", source, level, count);
        if self.productions_contains(&name) {
            format!("{name}-{}", self.learn.chunks_learned)
        } else {
            name
        }
    }

    /// `<kind>*<rule>*[<impasse>*]t[<init+1>-]<dc>-<count>`, `<kind>x<g>` for a rule
    /// learned from a learned rule of generation `g - 1`.
    fn rule_style_name(&self, kind: &str, source: &InstTrace, level: u32, count: u64) -> String {
        let dc = self.decider.d_cycle_count;
        let prefix = match source.generation {
            0 => kind.to_string(),
            g => format!("{kind}x{}", g + 1),
        };
        let suffix = self
            .decider
            .goals
            .iter()
            .find(|g| g.level + 1 == level)
            .and_then(|g| g.impasse)
            .map(|(kind, _)| match kind {
                ImpasseKind::Tie => "Tie*",
                ImpasseKind::Conflict => "Conflict*",
                ImpasseKind::ConstraintFailure => "Failure*",
                ImpasseKind::NoChange => "OpNoChange*",
            })
            .unwrap_or("");
        let init = if self.learn.init_count > 0 {
            format!("{}-", self.learn.init_count + 1)
        } else {
            String::new()
        };
        format!("{prefix}*{}*{suffix}t{init}{dc}-{count}", source.base)
    }

    fn productions_contains(&self, name: &str) -> bool {
        self.loaded(name).is_some()
    }

    /// The new chunk's match on the very WMEs the result came from: it must not fire (the
    /// results already exist), so it is taken off the match set.
    fn take_refracted_match(&mut self, pid: ProdId, grounds: &[crate::wm::WmeId]) -> Option<TokId> {
        let mut want: Vec<_> = grounds.to_vec();
        want.sort();
        want.dedup();
        self.matches.compact();
        let pos = self.matches.assertions.iter().position(|&(p, t)| {
            if p != pid {
                return false;
            }
            let mut got = self.rete.match_wmes(p, t);
            got.sort();
            got.dedup();
            got == want
        })?;
        let (p, t) = self.matches.assertions.remove(pos);
        self.matches.reindex();
        self.matches.support.remove(&(p, t));
        self.matches.taken(p, t);
        Some(t)
    }

    /// The o-support test (Soar manual, ch. 2, "The calculation of o-support") applied to a
    /// justification's conditions: it tests the selected operator of the lowest goal it
    /// tests, and makes something other than that operator.
    fn justification_support(&mut self, bt: &Backtrace, results: &[PrefId]) -> bool {
        let op = self.symbols.str("operator");
        let lowest = bt
            .grounds
            .iter()
            .map(|g| g.cond.wme.id)
            .filter(|&s| self.symbols.is_goal(s))
            .max_by_key(|&s| self.sym_level(s));
        let Some(goal) = lowest else { return false };
        let Some(selected) = bt
            .grounds
            .iter()
            .find(|g| g.cond.wme.id == goal && g.cond.wme.attr == op && !g.cond.wme.acceptable)
            .map(|g| g.cond.wme.value)
        else {
            return false;
        };
        let prefs: Vec<_> = results
            .iter()
            .map(|&r| self.decider.prefs[r].clone())
            .collect();
        if prefs
            .iter()
            .any(|p| p.attr == op && p.kind == PrefType::Acceptable && self.symbols.is_goal(p.id))
        {
            return false;
        }
        let applies = prefs.iter().any(|p| p.id != selected);
        let elaborates = prefs.iter().any(|p| p.id == selected);
        applies && !elaborates
    }

    /// An instantiation for learned results that the network does not hold: it retracts
    /// when one of its WMEs goes (Soar manual, ch. 2, "Justifications: Support for
    /// results").
    fn add_justification(
        &mut self,
        bt: &Backtrace,
        results: &[PrefId],
        name: &str,
        named: bool,
        o_support: bool,
    ) -> InstId {
        self.learn.next_serial += 1;
        let serial = self.learn.next_serial;
        // Its match goal is the lowest goal among its conditions' identifiers, as for a
        // rule: 9.6 holds justifications in the network (the waterfall retracts them at
        // that goal).
        let goal =
            crate::decide::support::goal_among(self, bt.grounds.iter().map(|g| g.cond.wme.id));
        let inst = Instantiation {
            prod: ProdId(u32::MAX),
            token: TokId::new(0),
            goal,
            o_support,
            prefs: Vec::new(),
            alive: true,
            serial,
            gds_evaluated: false,
        };
        let id = self.decider.alloc_inst(inst);
        self.learn.stats.learned_instantiations += 1;
        if self.settings.trace.wme_detail != crate::agent::WmeDetail::None {
            // What its retraction lists (`trace --timetags`): the WMEs it was built on,
            // newest first, as 9.6 lists a justification's.
            let mut wmes: Vec<crate::wm::Wme> = bt.grounds.iter().map(|g| g.cond.wme).collect();
            wmes.sort_by_key(|w| std::cmp::Reverse(w.timetag));
            wmes.dedup();
            self.decider.traced_match_wmes.insert(id, wmes);
        }
        let mut watched = self.learn.spare_grounds.pop().unwrap_or_default();
        for g in &bt.grounds {
            let key = (g.cond.wme_id, g.cond.wme.timetag);
            if self.wm.get(key.0).is_some_and(|w| w.timetag == key.1) {
                let spare = &mut self.learn.spare_justified;
                let list = self
                    .learn
                    .justified_by_wme
                    .entry(key)
                    .or_insert_with(|| spare.pop().unwrap_or_default());
                if list.last() != Some(&(id, serial)) {
                    list.push((id, serial));
                    watched.push(key);
                }
            } else {
                self.decider
                    .justification_retractions
                    .push((id, serial, usize::MAX));
            }
        }
        self.learn.grounds_of.insert(serial, watched);
        let negations = self.superstate_negations(bt);
        if !negations.is_empty() {
            let list: Vec<_> = negations
                .iter()
                .map(|(n, prod)| (n.trace.clone(), &prod.conditions[n.cond]))
                .collect();
            self.learn.negations.watch(id, serial, &list, &self.symbols);
        }
        if named {
            self.learn
                .justification_names
                .insert(serial, name.to_string());
            self.learn.justifications_learned += 1;
            self.learn.justifications_since_init += 1;
            if self.tests_local_negation(bt) {
                self.learn.stats.local_negation_justifications += 1;
            }
            if bt.tested_ltm {
                self.learn.stats.ltm_justifications += 1;
            }
            // With learning off and no rule text to trace, the justification is kept as its
            // sketch until something shows it.
            let sketched = self.settings.learn == crate::agent::LearnMode::Never
                && self.settings.learning_trace < 2
                && negations.is_empty();
            let body = if sketched {
                Body::Sketch(Arc::new(self.sketch_justification(bt, results, name.to_string())))
            } else {
                Body::Rule(Arc::new(self.build_learned_rule(bt, results, name.to_string(), false)))
            };
            match self.settings.learning_trace {
                0 => {}
                // `trace -L 1` names justifications as it names chunks.
                1 => self.emit(&TraceEvent::LearnedRule { name, text: None }),
                _ => {
                    let text = match &body {
                        Body::Rule(prod) => crate::printer::production_text(prod),
                        Body::Sketch(s) => {
                            crate::printer::production_text(&s.production(&self.symbols))
                        }
                    };
                    self.emit(&TraceEvent::LearnedRule {
                        name,
                        text: Some(&text),
                    });
                }
            }
            self.learn.justifications.push(Justification::new(body, serial));
        }
        id
    }

    /// A rule was learned from the substate below `level`: the states above that substate
    /// learn no more under `bottom-only`, and `chunk interrupt` stops the run after this
    /// phase, with 9.6's notice.
    fn rule_learned_at(&mut self, level: u32) {
        for g in self.decider.goals.iter_mut().filter(|g| g.level < level) {
            g.learned_below = true;
        }
        if self.settings.chunk.interrupt && !self.decider.rhs_interrupted {
            self.decider.rhs_interrupted = true;
            self.emit(&TraceEvent::LearningInterrupt);
        }
    }

    /// `trace -L 1` prints the new rule's name, `-L 2` the rule too.
    fn print_learned(&mut self, name: &str) {
        match self.settings.learning_trace {
            0 => {}
            1 => self.emit(&TraceEvent::LearnedRule { name, text: None }),
            _ => {
                if let Some(p) = self.production(name) {
                    let text = crate::printer::production_text(p);
                    self.emit(&TraceEvent::LearnedRule {
                        name,
                        text: Some(&text),
                    });
                }
            }
        }
    }

    /// A WME was added: the justifications one of whose negations it matches retract
    /// (9.6's rete holds justifications, negations included).
    #[inline]
    pub(crate) fn justification_wme_added(&mut self, w: crate::wm::WmeId) {
        if !self.learn.negations.is_empty() {
            self.check_justification_negations(w);
        }
    }

    /// Whether any live justification has negations to check new WMEs against.
    pub(crate) fn watches_justification_negations(&self) -> bool {
        !self.learn.negations.is_empty()
    }

    /// Each justification a new WME violates retracts where 9.6's rete puts it among the
    /// rules' retractions: its alpha table is reached in order (`Rete::alpha_marks`), and
    /// within one table before the rules' nodes, as the newer node (checked on soar-sml
    /// 9.6.5: agent justification-negation, trace 3).
    #[inline(never)]
    fn check_justification_negations(&mut self, w: crate::wm::WmeId) {
        let Some(new) = self.wm.get(w).copied() else {
            return;
        };
        let insts = &self.decider.insts;
        let hit = self
            .learn
            .negations
            .violated_by(&new, &self.wm, &self.symbols, |i, s| {
                insts
                    .get(i.index())
                    .is_some_and(|x| x.alive && x.serial == s)
            });
        let end = self.matches.retractions.len();
        for (inst, serial, table) in hit {
            let at = self
                .rete
                .alpha_marks
                .iter()
                .find(|&&(t, _)| t >= table)
                .map_or(end, |&(_, n)| n);
            self.decider
                .justification_retractions
                .push((inst, serial, at));
        }
    }

    /// A justification's instantiation lost a WME: its retraction is queued, before the
    /// rules' retractions the same removal made (from `at` on) and the newest
    /// justification first: 9.6's matcher drops the WME's newest matches first, and the
    /// justifications' are newer than the rules' (checked on soar-sml 9.6.5: agent
    /// long/fifteen-puzzle, trace 3, where a move retracts the evaluations' justifications
    /// after the old proposals, oldest first).
    pub(crate) fn justification_wme_removed(
        &mut self,
        w: crate::wm::WmeId,
        timetag: u64,
        at: usize,
    ) {
        // Most removals meet no justification: skip the hash probe then.
        if self.learn.justified_by_wme.is_empty() {
            return;
        }
        if let Some(mut list) = self.learn.justified_by_wme.remove(&(w, timetag)) {
            self.decider
                .justification_retractions
                .extend(list.drain(..).rev().map(|(i, s)| (i, s, at)));
            self.learn.spare_justified.push(list);
        }
    }

    /// A justification retracted. Its i-supported preferences go with it, and so does the
    /// justification; o-supported ones stay in preference memory (Soar manual, ch. 2,
    /// "Justifications: Support for results"), and the justification with them until the
    /// last of them is removed (checked on soar-sml 9.6.5: agent long/fifteen-puzzle, whose
    /// o-supported evaluation results live as long as the selection state).
    pub(crate) fn justification_retracted(&mut self, inst: InstId, serial: u64) {
        // Its WMEs no longer retract it (those that stay would otherwise keep it listed
        // for as long as they last).
        if let Some(mut keys) = self.learn.grounds_of.remove(&serial) {
            for &key in &keys {
                if let Some(list) = self.learn.justified_by_wme.get_mut(&key) {
                    list.retain(|&(_, s)| s != serial);
                    if list.is_empty() {
                        if let Some(list) = self.learn.justified_by_wme.remove(&key) {
                            self.learn.spare_justified.push(list);
                        }
                    }
                }
            }
            keys.clear();
            self.learn.spare_grounds.push(keys);
        }
        let mut held = 0;
        if self.decider.insts[inst].o_support {
            for &pid in &self.decider.insts[inst].prefs {
                let p = &self.decider.prefs[pid];
                if p.o_support && p.alive && !p.freed {
                    self.decider.held_by_justification.insert(pid, serial);
                    held += 1;
                }
            }
        }
        if held == 0 {
            self.forget_justification(serial);
        } else {
            self.learn.held_prefs.insert(serial, held);
        }
    }

    /// Retracted justifications whose last o-supported preference has gone leave the list.
    pub(crate) fn release_justifications(&mut self) {
        if self.decider.released_justification_prefs.is_empty() {
            return;
        }
        let released = std::mem::take(&mut self.decider.released_justification_prefs);
        let mut gone = FxHashSet::default();
        for &serial in &released {
            if let Some(n) = self.learn.held_prefs.get_mut(&serial) {
                *n -= 1;
                if *n == 0 {
                    self.learn.held_prefs.remove(&serial);
                    self.learn.justification_names.remove(&serial);
                    gone.insert(serial);
                }
            }
        }
        if !gone.is_empty() {
            self.learn.justifications.retain(|j| !gone.contains(&j.serial));
        }
        let mut released = released;
        released.clear();
        self.decider.released_justification_prefs = released;
    }

    fn forget_justification(&mut self, serial: u64) {
        self.learn.justification_names.remove(&serial);
        self.learn.justifications.retain(|j| j.serial != serial);
    }
}

/// The state of [`AgentCore::find_results`]' walk.
struct ResultsWalk {
    /// The results in the order found.
    found: Vec<PrefId>,
    seen: FxHashSet<PrefId>,
    /// The objects walked.
    walked: FxHashSet<Sym>,
    stack: Vec<ResultStep>,
    /// The identities of the retrieved objects that results link (see
    /// `retrieved_result_prefs`).
    retrieved_idents: FxHashMap<Sym, super::Ident>,
}

/// A step of the results walk: a preference to take, or an object to look into.
#[derive(Debug, Clone, Copy)]
enum ResultStep {
    Pref(PrefId),
    Object(Sym),
}
