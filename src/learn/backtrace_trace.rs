//! `trace --backtracing`: chunking's dependency analysis as 9.6 prints it (Soar manual,
//! ch. 4, "Procedural Knowledge Learning"; the text checked on soar-sml 9.6.5). It walks the
//! same firings the backtrace did, in 9.6's order: each result through the firing that made
//! it, then the local WMEs one at a time, newest found first, each through the firing that
//! made it. The superstate WMEs found ("grounds") and the local WMEs still to go are listed
//! after each firing; a firing's negated conditions are listed with it, and those on the
//! superstate are moved to the grounds at the end.
//!
//! The walk is its own: it prints and changes nothing the rule is built from.

use std::fmt::Write;
use std::sync::Arc;

use rustc_hash::{FxHashMap, FxHashSet};

use super::backtrace::{Backtrace, Negation};
use super::{InstTrace, Osk, PrefOrigin};
use crate::agent::AgentCore;
use crate::decide::ids::PrefId;
use crate::production::{Action, Condition, PrefKind, RhsTerm};
use crate::trace_text::{pref_text, wme_text};
use crate::wm::Wme;

/// A local WME waiting its turn.
struct Local {
    wme: Wme,
    /// The preference that made it, to go on through.
    support: Option<Arc<PrefOrigin>>,
    /// For an impasse's `^item`: the acceptable preference WME it stands for (9.6 makes the
    /// item by an instantiation of its own, "Architecture", that tested that WME).
    item_of: Option<Wme>,
}

struct Walk<'a> {
    agent: &'a AgentCore,
    bt: &'a Backtrace,
    out: String,
    /// In the order found: 9.6 lists them newest first.
    grounds: Vec<Wme>,
    ground_seen: FxHashSet<u64>,
    /// A stack: the top is the head of 9.6's list.
    locals: Vec<Local>,
    /// Firings gone through, by address; the `^item` WMEs gone through, by timetag.
    done: FxHashSet<*const InstTrace>,
    items_done: FxHashSet<u64>,
    negations: Vec<Negation>,
    /// The firings that proposed a selected operator, with the operator's selection
    /// knowledge: 9.6 goes through the knowledge again with the proposal.
    proposals: FxHashMap<*const InstTrace, Osk>,
}

impl AgentCore {
    /// The text of `trace --backtracing` for a learning episode whose results are
    /// `results`, backtraced into `bt`.
    pub(crate) fn backtrace_trace(&self, bt: &Backtrace, results: &[PrefId]) -> String {
        let mut walk = Walk {
            agent: self,
            bt,
            out: String::new(),
            grounds: Vec::new(),
            ground_seen: FxHashSet::default(),
            locals: Vec::new(),
            done: FxHashSet::default(),
            items_done: FxHashSet::default(),
            negations: Vec::new(),
            proposals: self.selected_operator_proposals(),
        };
        for &r in results {
            let pref = &self.decider.prefs[r];
            let Some(origin) = pref.origin.clone() else {
                continue;
            };
            walk.out.push_str("\nFor result preference ");
            pref_text(&mut walk.out, &self.symbols, pref, origin.trace.level, None);
            walk.out.push('\n');
            walk.through(&origin.trace, " ...");
        }
        walk.out.push_str("\n\n*** Tracing Locals ***\n\n");
        while let Some(local) = walk.locals.pop() {
            walk.out.push_str("For local ");
            wme_text(&mut walk.out, &self.symbols, &local.wme);
            walk.out.push('\n');
            if let Some(acceptable) = local.item_of {
                walk.through_item(&local.wme, acceptable);
            } else if let Some(origin) = &local.support {
                walk.through(&origin.trace, " ...");
            } else {
                walk.out.push_str(" ...no trace, can't BT\n");
                continue;
            }
            walk.out.push('\n');
        }
        walk.out.push_str("\n*** Adding Grounded Negated Conditions ***\n");
        for n in &walk.negations {
            if let Some((level, c)) = self.literal_negation(bt, n) {
                if level != u32::MAX && level < bt.level {
                    let _ = write!(walk.out, "\n-->Moving to grounds: {}", negation_text(&c));
                }
            }
        }
        walk.out
    }

    /// The firing behind each selected operator that has selection knowledge.
    fn selected_operator_proposals(&self) -> FxHashMap<*const InstTrace, Osk> {
        let mut out = FxHashMap::default();
        for g in &self.decider.goals {
            let (Some((_, w)), Some(osk)) = (g.operator, &g.osk) else {
                continue;
            };
            let wme = self.wm.get(w).copied();
            if let Some(origin) = wme.and_then(|w| self.supporting_origin(&w)) {
                out.insert(Arc::as_ptr(&origin.trace), osk.clone());
            }
        }
        out
    }
}

impl Walk<'_> {
    /// Through one firing: its operator's selection knowledge first, then its conditions,
    /// then the lists. `lead` starts the heading (9.6 indents all but the knowledge's).
    fn through(&mut self, trace: &Arc<InstTrace>, lead: &str) {
        let _ = writeln!(self.out, "{lead} BT through instantiation of {}", trace.name);
        if !self.done.insert(Arc::as_ptr(trace)) {
            self.out.push_str("(We already backtraced through this instantiation.)\n");
            return;
        }
        let add_osk = self.agent.settings.chunk.add_osk;
        // A firing that tested a selected operator goes through the prohibit preferences
        // behind the selection, then (with `add-osk`) all of the knowledge, the prohibit
        // preferences again among it; the firing that proposed it, through the knowledge.
        // A test of another state's operator slot brings its prohibit preferences alone.
        // 9.6 lists each condition's, the last condition's first.
        let mut passes: Vec<Arc<PrefOrigin>> = Vec::new();
        for c in trace.conds.iter().rev() {
            let Some(osk) = &c.osk else { continue };
            let prohibits = osk.iter().filter(|o| pref_kind(o) == Some(PrefKind::Prohibit));
            let all = osk.iter().filter(|_| add_osk && c.osk_local);
            passes.extend(prohibits.chain(all).cloned());
        }
        if !passes.is_empty() {
            self.through_knowledge(&passes);
        }
        if let Some(osk) = self.proposals.get(&Arc::as_ptr(trace)).filter(|_| add_osk) {
            let osk = osk.clone();
            self.through_knowledge(&osk);
        }
        let mut item_of = None;
        for c in &trace.conds {
            if c.via_item {
                item_of = Some(c.wme);
                continue;
            }
            if c.level > 0 && c.level < self.bt.level {
                self.ground(c.wme);
            } else {
                self.locals.push(Local {
                    wme: c.wme,
                    support: c.support.clone(),
                    item_of,
                });
            }
            item_of = None;
        }
        let mut negated = String::new();
        let mut found = Vec::new();
        if let Some(prod) = &trace.prod {
            // Listed last condition first, as 9.6 gathers them (at the head of a list).
            for (i, c) in prod.conditions.iter().enumerate().rev() {
                if matches!(c, Condition::Positive(_)) {
                    continue;
                }
                let n = Negation {
                    trace: trace.clone(),
                    cond: i,
                };
                if let Some((_, c)) = self.agent.literal_negation(self.bt, &n) {
                    negated.push_str(&negation_text(&c));
                }
                found.push(n);
            }
        }
        // Each firing's block goes in front of those found before.
        self.negations.splice(0..0, found);
        self.lists(&negated);
    }

    fn through_knowledge(&mut self, prefs: &[Arc<PrefOrigin>]) {
        for o in prefs {
            let _ = writeln!(
                self.out,
                "     Tracing through OSK preference: {} [level {}]",
                made_pref_text(self.agent, o),
                o.trace.level
            );
            self.through(&o.trace, "...");
        }
    }

    /// Through the architecture's instantiation of an impasse's `^item`: it tested the
    /// acceptable preference WME above and the substate's `^superstate`.
    fn through_item(&mut self, item: &Wme, acceptable: Wme) {
        self.out
            .push_str(" ... BT through instantiation of Architecture\n");
        if !self.items_done.insert(item.timetag) {
            self.out.push_str("(We already backtraced through this instantiation.)\n");
            return;
        }
        self.ground(acceptable);
        let agent = self.agent;
        let superstate = agent
            .wm
            .of_id(item.id)
            .filter_map(|w| agent.wm.get(w).copied())
            .find(|w| w.attr == agent.symbols.known.superstate);
        if let Some(wme) = superstate {
            self.locals.push(Local {
                wme,
                support: None,
                item_of: None,
            });
        }
        self.lists("");
    }

    /// A superstate WME. With learning on, 9.6 lists one for each condition that tested
    /// it (each condition has identities of its own); with learning off, each WME once.
    fn ground(&mut self, w: Wme) {
        let learning = self.agent.settings.learn != crate::agent::LearnMode::Never;
        if self.ground_seen.insert(w.timetag) || learning {
            self.grounds.push(w);
        }
    }

    /// The grounds and the locals so far, newest first, and a firing's negated conditions.
    fn lists(&mut self, negated: &str) {
        let symbols = &self.agent.symbols;
        self.out.push_str("  -->Grounds:\n");
        for w in self.grounds.iter().rev() {
            self.out.push_str("     ");
            wme_text(&mut self.out, symbols, w);
            self.out.push('\n');
        }
        self.out.push_str("\n  -->Locals:\n");
        for l in self.locals.iter().rev() {
            self.out.push_str("     ");
            wme_text(&mut self.out, symbols, &l.wme);
            self.out.push('\n');
        }
        let _ = writeln!(self.out, "\n  -->Negated:\n{negated}");
    }
}

/// A negated condition as 9.6 lists it: ` (S1 -^blocked <b*1>)`, or a conjunctive
/// negation `-{ (S3 ^evaluation <x>)` with its other conditions on lines of their own.
fn negation_text(c: &Condition) -> String {
    match c {
        Condition::Ncc(inner) => {
            let parts: Vec<String> = inner
                .iter()
                .map(|x| crate::printer::cond_text_with(x, false))
                .collect();
            format!("-{{ {}}}", parts.join("\n   "))
        }
        c => format!(" {}", crate::printer::cond_text_with(c, false)),
    }
}

/// The make action behind a preference.
fn made_action(origin: &PrefOrigin) -> Option<&crate::production::Make> {
    match origin.trace.prod.as_ref()?.actions.get(origin.action?)? {
        Action::Make(m) => Some(m),
        Action::Call(_) => None,
    }
}

fn pref_kind(origin: &PrefOrigin) -> Option<PrefKind> {
    made_action(origin).map(|m| m.pref)
}

/// A preference of the selection knowledge, `(S2 ^operator B1 > A1)`, as its firing made
/// it: the make action with the firing's bindings.
fn made_pref_text(agent: &AgentCore, origin: &PrefOrigin) -> String {
    let Some(m) = made_action(origin) else {
        return String::from("(?)");
    };
    let term = |t: &RhsTerm| match t {
        RhsTerm::Var(v) => origin
            .trace
            .vars
            .get(v)
            .map_or_else(|| v.to_string(), |&(_, s)| agent.symbols.text(s)),
        RhsTerm::Const(c) => agent.symbols.find_constant(c).map_or_else(
            || crate::printer::constants::constant_text(c),
            |s| agent.symbols.text(s),
        ),
        RhsTerm::Call(_) => String::from("?"),
    };
    crate::production::make_text_with(m, term)
}
