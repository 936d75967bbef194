//! Recording substate firings (Soar manual, ch. 4, "Procedural Knowledge Learning"): a
//! firing below the top state keeps its matched WMEs, the identities of its variables and,
//! for each local WME, the preference that made it. Top-state firings are never backtraced
//! and record nothing (speed).

use super::{Ident, InstTrace, PrefOrigin, TraceCond, TraceNames, TraceVars, VarTable};
use crate::agent::AgentCore;
use crate::decide::procedure::PrefType;
use crate::decide::state::PrefId;
use crate::production::{Action, Condition, Production, RhsTerm, Term, Test};
use crate::rete::{ProdId, TokId};
use crate::symbols::Sym;
use std::sync::Arc;

/// The variable a test binds by equality, if any.
pub(crate) fn equality_var(t: &Test) -> Option<&str> {
    match t {
        Test::Equal(Term::Var(v)) => Some(v),
        Test::Conjunction(ts) => ts.iter().find_map(equality_var),
        _ => None,
    }
}

impl AgentCore {
    /// Records a firing in a substate and gives each preference it made (with the index of
    /// its make action) an origin. `new_ids` holds what each variable the actions make was
    /// bound to, in the order of the compiled rule's list. With `with_osk`, the operator
    /// selection knowledge of the operator slots it tested goes with it.
    pub(crate) fn record_firing(
        &mut self,
        p: ProdId,
        t: TokId,
        prod: &Arc<Production>,
        new_ids: &[Option<Sym>],
        made: &[(PrefId, usize)],
        with_osk: bool,
    ) -> Option<Arc<InstTrace>> {
        let names = self.trace_names(p, prod);
        let table = &names.vars;
        // With learning off, firings get no identities, as in 9.6 (its instantiations
        // carry none then): a justification's conditions are literal, and backtracing
        // has nothing to unify.
        let learning = self.settings.learn != crate::agent::LearnMode::Never;
        let mut slots: Box<[Option<(Ident, Sym)>]> = vec![None; table.names.len()].into();
        // Each binding's identity (0 when unbound), by binding index.
        let mut binding_idents = std::mem::take(&mut self.learn.binding_idents);
        binding_idents.clear();
        if let Some(info) = self.rete.production(p) {
            // Identities are numbered by binding index, then the made variables in name
            // order after the bound ones.
            let n = info.bindings.len() + table.new_in_order.len();
            let first = if learning { self.learn.new_idents(n) } else { 0 };
            let ident = |k: usize| if learning { first + k as u64 } else { 0 };
            let mut bound = 0;
            for (k, (_, (depth, field))) in info.bindings.iter().enumerate() {
                if let Some(s) = self.rete.bound_value(t, depth, field) {
                    slots[table.binding_pos[k] as usize] = Some((ident(k), s));
                    binding_idents.push(ident(k));
                    bound += 1;
                } else {
                    binding_idents.push(0);
                }
            }
            let made_vars = table.new_in_order.iter();
            let present = made_vars.filter_map(|&(j, pos)| Some((new_ids.get(j as usize).copied()??, pos)));
            for (k, (s, pos)) in present.enumerate() {
                slots[pos as usize] = Some((ident(bound + k), s));
            }
        }
        let vars = TraceVars::new(table.clone(), slots);
        let level = self
            .decider
            .inst_by_token
            .get(&(p, t))
            .and_then(|&i| self.decider.insts[i].goal)
            .map_or(0, |g| self.sym_level(g));
        let mut wmes = std::mem::take(&mut self.learn.match_scratch);
        wmes.clear();
        wmes.extend(self.rete.match_row(p, t));
        let positives = prod
            .conditions
            .iter()
            .enumerate()
            .filter(|(_, c)| matches!(c, Condition::Positive(_)));
        let mut conds = Vec::with_capacity(wmes.len());
        for (((ci, c), &w), fields) in positives.zip(wmes.iter()).zip(names.cond_bindings.iter())
        {
            let (Condition::Positive(_), Some(wme)) = (c, self.wm.get(w).copied()) else {
                continue;
            };
            let wme_level = self.symbols.id_data(wme.id).map_or(0, |d| d.level);
            let ident = |b: u32| binding_idents.get(b as usize).copied().unwrap_or(0);
            // Any substate WME may be local to a later episode one level up.
            let support = if wme_level >= 2 {
                self.supporting_origin(&wme)
            } else {
                None
            };
            let ids = fields.map(ident);
            // An impasse's `^item` stands for the acceptable preference it shows, in the
            // state above (9.6 backtraces to `(S1 ^operator O1 +)`, E:look3).
            if let Some(acc) = self.item_preference_wme(&wme) {
                if let Some(aw) = self.wm.get(acc).copied() {
                    conds.push(TraceCond {
                        wme: aw,
                        wme_id: acc,
                        level: self.symbols.id_data(aw.id).map_or(0, |d| d.level),
                        ids: [0, 0, ids[2]],
                        cond: None,
                        support: None,
                        via_item: true,
                        osk: if with_osk { self.prohibit_knowledge_of(&aw, made) } else { None },
                        osk_local: false,
                    });
                }
            }
            let local = if wme_level == level && with_osk {
                self.selection_knowledge_of(&wme)
            } else {
                None
            };
            let osk_local = local.is_some();
            let osk = match local {
                Some(k) => Some(k),
                None if with_osk => self.prohibit_knowledge_of(&wme, made),
                None => None,
            };
            conds.push(TraceCond {
                wme,
                wme_id: w,
                level: wme_level,
                ids,
                cond: Some(ci),
                support,
                via_item: false,
                osk,
                osk_local,
            });
        }
        let trace = Arc::new(InstTrace {
            base: names.base.clone(),
            generation: names.generation,
            level,
            name: names.name.clone(),
            prod: Some(prod.clone()),
            conds,
            vars,
            backtraced: Default::default(),
        });
        for &(pid, ai) in made {
            let Some(pos) = names.vars.action_pos.get(ai) else {
                continue;
            };
            let ids = pos.map(|pos| trace.vars.at(pos).map_or(0, |x| x.0));
            self.decider.prefs[pid].origin = Some(Arc::new(PrefOrigin {
                trace: trace.clone(),
                ids,
                action: Some(ai),
            }));
        }
        self.learn.binding_idents = binding_idents;
        self.learn.match_scratch = wmes;
        Some(trace)
    }

    /// The names and variables a rule's recorded firings share, made once per rule (a
    /// cached entry stands only while the rule it was made for holds the id).
    fn trace_names(&mut self, p: ProdId, prod: &Production) -> Arc<TraceNames> {
        if let Some(n) = self.learn.trace_names.get(&p) {
            if *n.name == *prod.name {
                return n.clone();
            }
        }
        let (base, generation) = super::episode::chunk_base(&prod.name, prod.flags.chunk);
        let new_vars: Vec<String> = self
            .compiled_rule(p)
            .map(|r| r.new_vars.iter().map(|(v, _)| v.clone()).collect())
            .unwrap_or_default();
        let bindings = self.rete.production(p).map(|info| &info.bindings);
        // For each positive condition, the binding index of the variable each field tests
        // for equality (`u32::MAX`: none).
        let index = |t: &Test| {
            equality_var(t)
                .and_then(|v| bindings?.index_of(v))
                .map_or(u32::MAX, |i| i as u32)
        };
        let cond_bindings = prod
            .conditions
            .iter()
            .filter_map(|c| match c {
                Condition::Positive(c) => Some([index(&c.id), index(&c.attr), index(&c.value)]),
                _ => None,
            })
            .collect();
        let binding_names: Vec<Arc<str>> = bindings
            .map(|b| b.iter().map(|(v, _)| Arc::from(v.as_str())).collect())
            .unwrap_or_default();
        let vars = Arc::new(var_table(&binding_names, &new_vars, prod));
        let names = Arc::new(TraceNames {
            name: prod.name.as_str().into(),
            base: base.into(),
            generation,
            cond_bindings,
            vars,
        });
        self.learn.trace_names.insert(p, names.clone());
        names
    }

    /// For the selected operator `(G ^operator O)` of a substate G: the knowledge that
    /// selected it (`chunk add-osk`).
    fn selection_knowledge_of(&self, wme: &crate::wm::Wme) -> Option<super::Osk> {
        if wme.acceptable || wme.attr != self.symbols.known.operator {
            return None;
        }
        let goal = self.decider.goals.iter().find(|g| g.state == wme.id)?;
        match goal.operator {
            Some((o, _)) if o == wme.value => goal.osk.clone(),
            _ => None,
        }
    }

    /// For a WME of a state's operator slot (its selected operator, or a `+` WME): the
    /// origins of the slot's prohibit preferences but those the firing `made`, newest
    /// first. 9.6 backtraces through them whatever the WME's level and the `add-osk`
    /// setting, where the rest of the selection knowledge goes only with the firing's own
    /// state's selected operator. (The top state's firings record nothing: its prohibit
    /// preferences have no origin, see conformance.md.)
    fn prohibit_knowledge_of(
        &self,
        wme: &crate::wm::Wme,
        made: &[(PrefId, usize)],
    ) -> Option<super::Osk> {
        if wme.attr != self.symbols.known.operator || !self.symbols.is_goal(wme.id) {
            return None;
        }
        let slot = self.decider.slots.get(&(wme.id, wme.attr))?;
        let origins: Vec<Arc<PrefOrigin>> = slot
            .prefs
            .iter()
            .rev()
            .filter(|&&pid| !made.iter().any(|m| m.0 == pid))
            .map(|&pid| &self.decider.prefs[pid])
            .filter(|pref| pref.kind == PrefType::Prohibit)
            .filter_map(|pref| pref.origin.clone())
            .collect();
        (!origins.is_empty()).then(|| origins.into())
    }

    /// For `(G ^item X)` of a tie or conflict substate G: the WME `(S ^operator X +)` of
    /// the state above.
    fn item_preference_wme(&self, wme: &crate::wm::Wme) -> Option<crate::wm::WmeId> {
        if self.symbols.known.item != wme.attr || !self.symbols.is_goal(wme.id) {
            return None;
        }
        self.candidate_plus_wme(wme.id, wme.value)
    }

    /// For the substate `goal` of an operator impasse: the `+` WME of the candidate
    /// `value` in the operator slot of the state above.
    pub(crate) fn candidate_plus_wme(&self, goal: Sym, value: Sym) -> Option<crate::wm::WmeId> {
        let gi = self.decider.goals.iter().position(|g| g.state == goal)?;
        let above = self.decider.goals.get(gi.checked_sub(1)?)?.state;
        let op = self.symbols.known.operator;
        let slot = self.decider.slots.get(&(above, op))?;
        slot.wmes.get(&(value, true))
    }

    /// The preference behind a WME of a substate: the oldest acceptable (or require, for an
    /// operator proposal) preference for its value that was recorded.
    pub(crate) fn supporting_origin(&self, wme: &crate::wm::Wme) -> Option<Arc<PrefOrigin>> {
        // A memory's retrieval: the architecture's firing that made it.
        if let Some((_, o)) = self.learn.memory_results.get(&wme.timetag) {
            return Some(o.clone());
        }
        let slot = self.decider.slots.get(&(wme.id, wme.attr))?;
        // A required operator, once selected, rests on its require preference (the
        // candidate 9.6 selects).
        if !wme.acceptable && wme.attr == self.symbols.known.operator {
            let required = slot.prefs_for(wme.value).find_map(|pid| {
                let p = &self.decider.prefs[pid];
                (p.kind == PrefType::Require && p.value == wme.value)
                    .then(|| p.origin.clone())
                    .flatten()
            });
            if required.is_some() {
                return required;
            }
        }
        slot.prefs_for(wme.value).find_map(|pid| {
            let p = &self.decider.prefs[pid];
            let kind_ok = match p.kind {
                PrefType::Acceptable => true,
                PrefType::Require => wme.acceptable,
                _ => false,
            };
            if kind_ok && p.value == wme.value {
                p.origin.clone()
            } else {
                None
            }
        })
    }
}

/// A rule's [`VarTable`]: its bindings' names and the variables its actions make, in name
/// order, with where each binding, made variable and make action's field sits.
fn var_table(bindings: &[Arc<str>], new_vars: &[String], prod: &Production) -> VarTable {
    let mut names: Vec<Arc<str>> = bindings.to_vec();
    names.extend(new_vars.iter().map(|v| Arc::from(v.as_str())));
    names.sort_unstable();
    names.dedup();
    let pos = |v: &str| {
        names
            .binary_search_by(|k| (**k).cmp(v))
            .map_or(u32::MAX, |i| i as u32)
    };
    let binding_pos = bindings.iter().map(|v| pos(v)).collect();
    let mut new_in_order: Vec<(u32, u32)> = (0..new_vars.len() as u32)
        .map(|j| (j, pos(&new_vars[j as usize])))
        .collect();
    new_in_order.sort_by(|a, b| new_vars[a.0 as usize].cmp(&new_vars[b.0 as usize]));
    let term = |t: &RhsTerm| match t {
        RhsTerm::Var(v) => pos(v),
        _ => u32::MAX,
    };
    let action_pos = prod
        .actions
        .iter()
        .map(|a| match a {
            Action::Make(m) => [
                term(&m.id),
                term(&m.attr),
                term(&m.value),
                m.referent.as_ref().map_or(u32::MAX, term),
            ],
            _ => [u32::MAX; 4],
        })
        .collect();
    VarTable {
        names: names.into(),
        binding_pos,
        new_in_order: new_in_order.into(),
        action_pos,
    }
}
