//! Firing and retraction: a match fires as an instantiation, whose actions make preferences
//! (and call RHS functions); a retracted instantiation takes its i-supported preferences out
//! of their slots (Soar manual, chapter 2, "Production Actions and Persistence"). A rule's actions
//! are compiled at its first firing.

use super::compiled::{self, Act, CompiledRule, Term};
use super::procedure::PrefType;
use super::state::{InstId, Instantiation, PrefId, Preference};
use crate::agent::AgentCore;
use crate::rete::{ProdId, TokId};
use crate::symbols::{Sym, SymData};
use crate::trace_events::TraceEvent;
use crate::wm::WmeId;
use std::rc::Rc;

impl AgentCore {
    pub(crate) fn fire(
        &mut self,
        p: ProdId,
        t: TokId,
        o_support: bool,
        new_prefs: &mut Vec<PrefId>,
    ) {
        let Some(rule) = self.compiled_rule(p) else {
            return;
        };
        self.decider.firings += 1;
        let counts = &mut self.decider.firing_counts;
        if counts.len() <= p.0 as usize {
            counts.resize(p.0 as usize + 1, 0);
        }
        counts[p.0 as usize] += 1;
        self.send_rule_event(p, false);
        if self.settings.trace.assertions {
            self.trace_new_match(p, t, new_prefs.len());
        }
        let mut traced_wmes = Vec::new();
        let traced = self.settings.trace.firings_of(&rule.flags)
            || (!self.watched_rules.is_empty() && self.watched_rules.contains(self.production_name(p)));
        if traced {
            let mut out = std::mem::take(&mut self.output);
            let event = crate::trace_events::TraceEvent::Firing {
                rule: self.production_name(p),
            };
            self.write_event(&mut out, &event);
            self.output = out;
            traced_wmes = self.trace_match_wmes(p, t);
        }
        // A template's match makes an RL rule instead of preferences (Soar manual, ch. 5,
        // "Rule Templates").
        if rule.flags.template {
            self.rl_template_fired(p, t, o_support, new_prefs);
            return;
        }
        let mut wmes = std::mem::take(&mut self.decider.rhs_wmes);
        let mut args = std::mem::take(&mut self.decider.rhs_args);
        self.rete.token_wmes(t, &mut wmes);
        // The match goal (the lowest goal it tests), from the WMEs the actions read anyway.
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
            gds_evaluated: false,
        };
        if rule.flags.i_support {
            inst.o_support = false;
        }
        // An o-supported preference outlives its firing's match: keep what the match held
        // (a substate firing's record keeps it already). So does an i-supported one while
        // activation is on: a reference to its WME goes to what the firing matched, also
        // once the match is gone (see `wma_pref_conditions`).
        // (Gathered in a buffer kept for its room: one allocation, the record's own.)
        let kept = if inst.o_support { level < 2 } else { self.wma.on() };
        let matched: Option<std::sync::Arc<[crate::wm::Wme]>> = kept
            .then(|| {
                let mut held = std::mem::take(&mut self.decider.matched_scratch);
                held.clear();
                held.extend(self.rete.match_row(p, t).filter_map(|w| self.wm.get(w).copied()));
                let record = std::sync::Arc::from(held.as_slice());
                self.decider.matched_scratch = held;
                record
            });
        // The slot is taken now: the preferences name it.
        let inst_id = self.decider.alloc_inst(inst.clone());
        if !traced_wmes.is_empty() {
            self.decider.traced_match_wmes.insert(inst_id, traced_wmes);
        }
        let mut new_ids = std::mem::take(&mut self.decider.rhs_new_ids);
        new_ids.clear();
        new_ids.resize(rule.new_vars.len(), None);
        // Substate firings are recorded for backtracing: each preference with its action.
        let mut made = std::mem::take(&mut self.decider.rhs_made);
        made.clear();
        // New identifiers a failed action would have linked (see below).
        let mut unlinked_new: Vec<usize> = Vec::new();
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
                    // The identifier first: an action whose identifier is not one stops
                    // there, before its other terms make anything (as 9.6 does).
                    let Some(id_sym) =
                        self.term_value(&rule, &wmes, id, level, &mut new_ids, &mut args)
                    else {
                        continue;
                    };
                    if !self.symbols.is_id(id_sym) {
                        self.report_non_identifier(action, id_sym);
                        // The objects it would have linked stay, unlinked (as in 9.6); a
                        // new one is noted if a later action makes it.
                        for t in [attr, value].into_iter().chain(referent) {
                            match t {
                                Term::Bound(depth, field) => {
                                    match self.rete.field_at(&wmes, *depth, *field) {
                                        Some(x) if self.symbols.is_id(x) => {
                                            self.wm.note_failed_link(x)
                                        }
                                        _ => {}
                                    }
                                }
                                Term::New(slot) => unlinked_new.push(*slot),
                                _ => {}
                            }
                        }
                        continue;
                    }
                    let id = id_sym;
                    // A new identifier made here takes the level of the object it is put
                    // on, as 9.6 makes it: one a substate puts on its superstate is the
                    // superstate's from the start.
                    let on = self.sym_level(id);
                    let attr = self.term_value(&rule, &wmes, attr, on, &mut new_ids, &mut args);
                    let value = self.term_value(&rule, &wmes, value, on, &mut new_ids, &mut args);
                    let referent = match referent {
                        Some(r) => {
                            match self.term_value(&rule, &wmes, r, on, &mut new_ids, &mut args) {
                                Some(x) => Some(x),
                                None => continue,
                            }
                        }
                        None => None,
                    };
                    let (Some(attr), Some(value)) = (attr, value) else {
                        continue;
                    };
                    // A binary indifferent preference whose referent is a number is a
                    // numeric one (`= <v>` with <v> bound to a number, as 9.6 reads it).
                    let kind = match (*kind, referent.map(|r| self.symbols.get(r))) {
                        (
                            PrefType::BinaryIndifferent,
                            Some(SymData::Int(_) | SymData::Float(_)),
                        ) => PrefType::NumericIndifferent,
                        (kind, _) => kind,
                    };
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
                        matched: matched.clone(),
                        recall: false,
                        links_filed: false,
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
        for slot in unlinked_new {
            if let Some(x) = new_ids.get(slot).copied().flatten() {
                self.wm.note_failed_link(x);
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
        let mut own_prefs = std::mem::take(&mut self.decider.rhs_own_prefs);
        own_prefs.clear();
        if traced || level >= 2 {
            own_prefs.extend_from_slice(&inst.prefs);
        }
        self.decider.insts[inst_id] = inst;
        if level >= 2 && self.wma.on() {
            self.wma_hold_firing(inst_id);
        }
        if traced {
            self.trace_instantiation_prefs(&own_prefs);
        }
        // Results of a substate firing are learned from at once (Soar manual, chapter 2,
        // "Results"): a justification or a chunk takes them over.
        if level >= 2 && self.settings.trace.chunk_warnings {
            let rule = self.production_name(p).to_string();
            self.note_state_not_learning(level, &rule);
        }
        if level >= 2 {
            let recorded = match self.production_by_id(p) {
                Some(prod) => self.record_firing(p, t, &prod, &new_ids, &made, true),
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
        self.decider.rhs_made = made;
        self.decider.rhs_own_prefs = own_prefs;
    }

    /// `New match of rule in state S1 (level 1).  Creating instantiation.` (`trace
    /// --assertions`), and the instantiation noted for its `asserting` line; its
    /// preferences start at `first` among the new ones.
    fn trace_new_match(&mut self, p: ProdId, t: TokId, first: usize) {
        let state = crate::decide::support::match_goal(self, p, t);
        let level = state
            .and_then(|g| self.symbols.id_data(g))
            .map_or(1, |d| d.level);
        let rule = self.production_name(p).to_string();
        self.emit(&TraceEvent::NewMatch {
            rule: &rule,
            state,
            level,
        });
        self.decider.instantiations_made.push((rule, first));
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
    /// identifier at its first use, shared by all its uses (its letter is the variable's
    /// first, `S` read as `I`; Soar manual, chapter 3, "The action side of productions (or
    /// RHS)").
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

    pub(super) fn retract(&mut self, inst_id: InstId) {
        self.send_rule_event(self.decider.insts[inst_id].prod, true);
        self.apoptosis_note_retraction(self.decider.insts[inst_id].prod);
        let serial = self.decider.insts[inst_id].serial;
        if serial != 0 {
            self.justification_retracted(inst_id, serial);
        }
        let inst = &mut self.decider.insts[inst_id];
        inst.alive = false;
        let mut prefs = std::mem::take(&mut inst.prefs);
        // Newest first, as 9.6's list of an instantiation's preferences runs.
        for &pid in prefs.iter().rev() {
            let pref = &mut self.decider.prefs[pid];
            pref.inst = None;
            // O-supported preferences outlive their instantiation (Soar manual, chapter 2,
            // "Production Actions and Persistence").
            if pref.o_support || !pref.alive {
                continue;
            }
            let key = (pref.id, pref.attr);
            let value = pref.value;
            if let Some(slot) = self.decider.slots.id_of(&key) {
                self.decider.slots.slot_mut(slot).remove(pid, value);
                self.pref_link_removed(pid);
                self.mark_changed(key, Some(slot));
                self.decider.slots.drop_if_empty(slot);
            } else {
                self.mark_changed(key, None);
            }
            self.decider.free_pref(pid);
        }
        prefs.clear();
        self.decider.insts[inst_id].prefs = prefs;
        self.decider.free_inst(inst_id);
    }

    /// 9.6's error for a make action whose identifier evaluated to `id`, not an identifier:
    /// the action as 9.6 prints it, a variable the conditions bind as `[RETE-loc]` and one
    /// they do not as `<unbound-variable>`.
    fn report_non_identifier(&mut self, action: &Act, id: Sym) {
        let Act::Make {
            id: id_term,
            attr,
            value,
            referent,
            kind,
        } = action
        else {
            return;
        };
        let mut line = String::from("Error: RHS of action           (");
        self.push_term_text(id_term, &mut line);
        line.push_str(" ^");
        self.push_term_text(attr, &mut line);
        line.push(' ');
        self.push_term_text(value, &mut line);
        line.push(' ');
        line.push(crate::trace_text::pref_type_char(*kind));
        if let Some(r) = referent {
            line.push(' ');
            self.push_term_text(r, &mut line);
        }
        line.push_str(") makes a preference for ");
        line.push_str(&self.symbols.text(id));
        line.push_str(" (not an identifier)\n");
        self.output.push_str(&line);
    }

    fn push_term_text(&self, t: &Term, out: &mut String) {
        match t {
            Term::Sym(s) => out.push_str(&self.symbols.text(*s)),
            Term::Bound(..) => out.push_str("[RETE-loc]"),
            Term::New(_) => out.push_str("<unbound-variable>"),
            Term::Call(c) => {
                out.push('(');
                out.push_str(&c.name);
                for a in &c.args {
                    out.push(' ');
                    self.push_term_text(a, out);
                }
                out.push(')');
            }
        }
    }

    /// A built-in or registered RHS function (Soar manual, chapter 3, "Right-hand side
    /// Functions").
    fn call_rhs(&mut self, name: &str, args: &[Sym]) -> Result<Option<Sym>, String> {
        crate::decide::functions::call(self, name, args)
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
