//! Backtracing through a memory retrieval (Soar manual, ch. 4, "Procedural Knowledge
//! Learning"): 9.6 makes the WMEs a semantic memory command retrieves in a substate
//! through instantiations of the architecture's own, named "Architecture", whose conditions
//! are the command's: the link to the memory, its command and result WMEs, the command and
//! the cue's WMEs. One instantiation makes what goes on the result link (`^retrieved`,
//! `^success`, ...), another, with the same conditions, the retrieved objects' WMEs
//! (checked with `trace --backtracing` on soar-sml 9.6.5). Backtracing goes on through the
//! cue into the firings that built it, so a chunk tests what the cue came from.

use super::{Ident, InstTrace, PrefOrigin, TraceCond, TraceVars};
use crate::agent::AgentCore;
use crate::decide::procedure::PrefType;
use crate::decide::state::{PrefId, Preference};
use crate::symbols::Sym;
use crate::wm::{Wme, WmeId};
use rustc_hash::{FxHashMap, FxHashSet};
use std::sync::Arc;

/// The architecture's instantiations' name, as `trace --backtracing` prints it.
const ARCHITECTURE: &str = "Architecture";

/// The command attributes whose value is a cue, whose WMEs the conditions include.
const CUES: [&str; 3] = ["query", "neg-query", "math-query"];

/// Whether a firing is the architecture's, behind a memory's retrieval.
pub(crate) fn is_retrieval(trace: &InstTrace) -> bool {
    trace.prod.is_none() && &*trace.name == ARCHITECTURE
}

impl AgentCore {
    /// The conditions of the architecture's firing that makes a command's results: the
    /// link, command and result WMEs of `(state, link, command, result)`, then the
    /// command's WMEs and each cue's, each in timetag order (soar-sml 9.6.5, both
    /// memories).
    pub(crate) fn memory_command_conditions(&self, (state, link, cmd, res): (Sym, Sym, Sym, Sym)) -> Vec<WmeId> {
        let mut conditions: Vec<WmeId> = [(state, link), (link, cmd), (link, res)]
            .into_iter()
            .filter_map(|(id, value)| self.wme_linking(id, value))
            .collect();
        let by_timetag = |id: Sym| {
            let mut ws: Vec<(Wme, WmeId)> = self
                .wm
                .of_id(id)
                .filter_map(|x| self.wm.get(x).map(|w| (*w, x)))
                .collect();
            ws.sort_unstable_by_key(|(w, _)| w.timetag);
            ws
        };
        let command = by_timetag(cmd);
        conditions.extend(command.iter().map(|&(_, x)| x));
        let cues = CUES.map(|a| self.symbols.find_str(a));
        for (w, _) in &command {
            if cues.contains(&Some(w.attr)) && self.symbols.is_id(w.value) {
                conditions.extend(by_timetag(w.value).into_iter().map(|(_, x)| x));
            }
        }
        conditions
    }

    /// Gives the WMEs a command on `link` (of a state at `level`) just made their origins:
    /// `results` are the new WMEs, `conditions` the command's WMEs in order.
    pub(crate) fn note_memory_results(
        &mut self,
        level: u32,
        res: Sym,
        results: &[WmeId],
        conditions: &[WmeId],
    ) {
        // `chunk stats` counts the instantiations at any level (one for what goes on the
        // result link, one for the retrieved objects' WMEs).
        let on_link_made = results
            .iter()
            .filter(|&&w| self.wm.get(w).is_some_and(|x| x.id == res))
            .count();
        self.learn.stats.retrieval_instantiations +=
            u64::from(on_link_made > 0) + u64::from(on_link_made < results.len());
        // The origins of results that left working memory some other way (with their
        // substate) go now, so that a long run keeps only the live ones and the firings
        // they hold.
        if !self.learn.memory_results.is_empty() {
            let wm = &self.wm;
            self.learn
                .memory_results
                .retain(|&t, (w, _)| wm.get(*w).is_some_and(|x| x.timetag == t));
        }
        // Top-state firings are never backtraced.
        if level < 2 || results.is_empty() {
            return;
        }
        // Each identifier the conditions test has an identity of its own, shared by the
        // conditions that test it (9.6 variablizes identifiers); constants have none, so a
        // cue's constant stays in the chunk as a literal. With learning off, as for rules'
        // firings, nothing has an identity.
        let mut idents: FxHashMap<Sym, Ident> = Default::default();
        let mut fields = Vec::with_capacity(conditions.len());
        for &w in conditions {
            if let Some(wme) = self.wm.get(w).copied() {
                let ids = [
                    self.retrieval_ident(&mut idents, wme.id),
                    self.retrieval_ident(&mut idents, wme.attr),
                    self.retrieval_ident(&mut idents, wme.value),
                ];
                fields.push((w, wme, ids));
            }
        }
        let conds: Vec<TraceCond> = fields
            .into_iter()
            .map(|(w, wme, ids)| {
                let wme_level = self.symbols.id_data(wme.id).map_or(0, |d| d.level);
                let support = if wme_level >= 2 {
                    self.supporting_origin(&wme)
                } else {
                    None
                };
                TraceCond {
                    wme,
                    wme_id: w,
                    level: wme_level,
                    ids,
                    cond: None,
                    support,
                    via_item: false,
                    osk: None,
                    osk_local: false,
                }
            })
            .collect();
        let instantiation = || {
            Arc::new(PrefOrigin {
                trace: Arc::new(InstTrace {
                    name: ARCHITECTURE.into(),
                    prod: None,
                    conds: conds.clone(),
                    vars: TraceVars::new(Arc::default(), Box::default()),
                    base: ARCHITECTURE.into(),
                    generation: 0,
                    level,
                    backtraced: Default::default(),
                }),
                ids: [0; 4],
                action: None,
            })
        };
        let (on_link, below) = (instantiation(), instantiation());
        for &w in results {
            if let Some(wme) = self.wm.get(w).copied() {
                let origin = if wme.id == res { &on_link } else { &below };
                self.learn.memory_results.insert(wme.timetag, (w, origin.clone()));
            }
        }
    }

    /// The WMEs a memory retrieval in the substate at `level` put on `id`, as results: 9.6
    /// makes them through preferences of its architecture instantiation, so a result that
    /// links the retrieved object brings its WMEs along (`(<a1> ^color red ^name alpha)`
    /// in the chunk; checked on soar-sml 9.6.5). Here they are preferences
    /// made for the learned rule's actions alone: the WMEs stay as the memory made them,
    /// and the learned rule's instantiation takes no copy of them. `idents` holds the
    /// identity of each retrieved object a result links, so that the rule's actions name
    /// it with one variable; an object they link in turn gets an identity of its own.
    pub(crate) fn retrieved_result_prefs(
        &mut self,
        id: Sym,
        level: u32,
        idents: &mut FxHashMap<Sym, Ident>,
    ) -> Vec<PrefId> {
        if self.learn.memory_results.is_empty() {
            return Vec::new();
        }
        let mut retrieved: Vec<(Wme, Arc<PrefOrigin>)> = self
            .wm
            .of_id(id)
            .filter_map(|w| {
                let wme = self.wm.get(w)?;
                let (_, origin) = self.learn.memory_results.get(&wme.timetag)?;
                (origin.trace.level == level).then(|| (*wme, origin.clone()))
            })
            .collect();
        // 9.6 walks the object's slots newest first, and a slot's preferences oldest first
        // (a slot is as old as its attribute's first WME).
        let mut slot_age: FxHashMap<Sym, u64> = FxHashMap::default();
        for w in self.wm.of_id(id) {
            if let Some(wme) = self.wm.get(w) {
                let age = slot_age.entry(wme.attr).or_insert(wme.timetag);
                *age = (*age).min(wme.timetag);
            }
        }
        retrieved.sort_by_key(|(w, _)| (std::cmp::Reverse(slot_age[&w.attr]), w.timetag));
        retrieved
            .into_iter()
            .map(|(w, origin)| {
                let ids = [
                    self.retrieval_ident(idents, w.id),
                    0,
                    self.retrieval_ident(idents, w.value),
                    0,
                ];
                let origin = Arc::new(PrefOrigin {
                    trace: origin.trace.clone(),
                    ids,
                    action: None,
                });
                self.decider.alloc_pref(Preference {
                    kind: PrefType::Acceptable,
                    id: w.id,
                    attr: w.attr,
                    value: w.value,
                    referent: None,
                    number: None,
                    o_support: false,
                    inst: None,
                    rule: None,
                    alive: true,
                    freed: false,
                    origin: Some(origin),
                    matched: None,
                    recall: false,
                    links_filed: false,
                })
            })
            .collect()
    }

    /// The long-term identifiers' short-term instances among a learned rule's results, in
    /// the order 9.6's `chunk add-ltm-links` links them: 9.6 gathers results depth first
    /// (an object's slots oldest first, a slot's preferences newest first), each at the
    /// head of its list, and takes each instance the first time that list names it.
    pub(crate) fn ltm_instances_in_results(&self, results: &[PrefId]) -> Vec<Sym> {
        let prefs = &self.decider.prefs;
        let values = |r: PrefId| [Some(prefs[r].value), prefs[r].referent].into_iter().flatten();
        // An object's results, in the order 9.6 walks them.
        let mut on: FxHashMap<Sym, Vec<PrefId>> = FxHashMap::default();
        for &r in results {
            on.entry(prefs[r].id).or_default().push(r);
        }
        for list in on.values_mut() {
            let retrieved: Vec<PrefId> = list.iter().copied().filter(|&r| self.is_retrieved_result(r)).collect();
            if retrieved.len() > 1 {
                // `retrieved_result_prefs` gave them slots newest first, each oldest first.
                let mut slots: Vec<Vec<PrefId>> = Vec::new();
                for r in retrieved {
                    match slots.last_mut() {
                        Some(s) if prefs[s[0]].attr == prefs[r].attr => s.push(r),
                        _ => slots.push(vec![r]),
                    }
                }
                list.retain(|&r| !self.is_retrieved_result(r));
                for mut s in slots.into_iter().rev() {
                    s.reverse();
                    list.extend(s);
                }
            }
        }
        let linked: FxHashSet<Sym> = results.iter().flat_map(|&r| values(r)).collect();
        let mut found = Vec::with_capacity(results.len());
        let mut walked: FxHashSet<Sym> = FxHashSet::default();
        let mut stack: Vec<PrefId> = results
            .iter()
            .copied()
            .filter(|&r| !linked.contains(&prefs[r].id))
            .rev()
            .collect();
        while let Some(r) = stack.pop() {
            found.push(r);
            for v in values(r) {
                if walked.insert(v) {
                    if let Some(list) = on.get(&v) {
                        stack.extend(list.iter().rev());
                    }
                }
            }
        }
        let mut instances = Vec::new();
        for &r in found.iter().rev() {
            let p = &prefs[r];
            for s in [Some(p.id), Some(p.attr), Some(p.value), p.referent].into_iter().flatten() {
                if self.symbols.lti(s).is_some() && !instances.contains(&s) {
                    instances.push(s);
                }
            }
        }
        instances
    }

    /// The identity of a symbol in the architecture's firing behind a retrieval: each
    /// identifier has one of its own, kept in `idents` so that every field naming it shares
    /// it; constants have none, and with learning off, as for rules' firings, nothing has.
    fn retrieval_ident(&mut self, idents: &mut FxHashMap<Sym, Ident>, s: Sym) -> Ident {
        if self.settings.learn == crate::agent::LearnMode::Never || !self.symbols.is_id(s) {
            return 0;
        }
        *idents.entry(s).or_insert_with(|| self.learn.new_idents(1))
    }

    /// Whether a result is one of `retrieved_result_prefs`.
    pub(crate) fn is_retrieved_result(&self, r: PrefId) -> bool {
        let p = &self.decider.prefs[r];
        p.inst.is_none() && p.origin.as_ref().is_some_and(|o| is_retrieval(&o.trace))
    }

    /// The results of a command that went: they no longer need their origins.
    pub(crate) fn forget_memory_results(&mut self, timetags: impl IntoIterator<Item = u64>) {
        if self.learn.memory_results.is_empty() {
            return;
        }
        for t in timetags {
            self.learn.memory_results.remove(&t);
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::commands::Interpreter;

    /// Each decision an operator meets a no-change impasse whose substate queries semantic
    /// memory, and the substate goes with the next decision. The retrievals' origins go with
    /// their WMEs: however long the run, only the live substate's are kept.
    #[test]
    fn the_origins_of_retrievals_go_with_their_substates() {
        let mut i = Interpreter::new();
        i.run_text(
            "t",
            "smem --enable
             smem --add {(<x> ^name alpha ^color red)}
             sp {init :o-support (state <s> ^superstate nil -^count) --> (<s> ^count 0)}
             sp {propose (state <s> ^superstate nil ^count <c>) --> (<s> ^operator <o> +) (<o> ^name go ^n <c>)}
             sp {query (state <s> ^superstate <ss> ^smem.command <c>) (<ss> ^operator.name go)
                --> (<c> ^query <q>) (<q> ^name alpha)}
             sp {count (state <s> ^superstate <ss> ^smem.result.retrieved <r>)
                (<ss> ^operator <o> ^count <c>) (<o> ^name go)
                --> (<ss> ^count <c> - (+ <c> 1))}
             watch 0",
        )
        .unwrap();
        i.run_text("t", "run 40").unwrap();
        let kept = i.agent.learn.memory_results.len();
        assert!(kept > 0, "the live substate's retrieval has its origins");
        i.run_text("t", "run 400").unwrap();
        assert!(
            i.agent.learn.memory_results.len() <= kept,
            "{} origins kept after 440 decisions, {kept} after 40",
            i.agent.learn.memory_results.len()
        );
    }
}
