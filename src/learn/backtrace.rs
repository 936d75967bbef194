//! Backtracing (Soar manual, ch. 4, "Procedural Knowledge Learning"): from each result,
//! through the firings that made the local WMEs it tested, to the superstate WMEs
//! ("grounds") the reasoning depended on. Identities are joined where a condition tested
//! what an action made, and a literal tested on such a WME fixes the identity to that
//! literal (EBC's constraint propagation).

use super::{Ident, InstTrace, PrefOrigin, TraceCond};
use crate::agent::AgentCore;
use crate::symbols::Sym;
use rustc_hash::{FxHashMap, FxHashSet};
use std::sync::atomic::Ordering::Relaxed;
use std::sync::Arc;

/// A superstate WME the result depended on, with the identities its tests had.
#[derive(Debug, Clone)]
pub struct Ground {
    pub cond: TraceCond,
    pub trace: Arc<InstTrace>,
}

/// A relational test a local condition made on something that came from elsewhere: it
/// constrains that identity wherever the chunk tests it (EBC's constraint propagation).
#[derive(Debug, Clone)]
pub struct Constraint {
    pub ident: Ident,
    pub test: crate::production::Test,
    pub trace: Arc<InstTrace>,
}

/// What the backtrace goes through next: a firing, or an impasse's `^item`, whose
/// architecture instantiation tested the acceptable preference WME it stands for.
#[derive(Debug)]
enum Pending {
    Firing(Arc<InstTrace>),
    Item(TraceCond, Arc<InstTrace>),
}

/// A negated condition (or conjunctive negation) of a backtraced firing.
#[derive(Debug, Clone)]
pub struct Negation {
    pub trace: Arc<InstTrace>,
    pub cond: usize,
}

#[derive(Debug, Default)]
pub struct Backtrace {
    /// The learning goal's level: WMEs whose id is above it are grounds.
    pub level: u32,
    pub grounds: Vec<Ground>,
    /// The tests of a ground WME after its first, merged into it, each with the number of
    /// grounds found before it: a justification built with learning on lists them all.
    pub merged_grounds: Vec<(usize, Ground)>,
    ground_at: FxHashMap<u64, usize>,
    pub negations: Vec<Negation>,
    pub constraints: Vec<Constraint>,
    parent: FxHashMap<Ident, Ident>,
    pub literal: FxHashMap<Ident, Sym>,
    /// This backtrace's number: a firing marked with it has been gone through.
    number: u64,
    /// Firings waiting to be gone through (kept for its room).
    stack: Vec<Pending>,
    /// Firings backtraced (for `chunk stats`), and the impasse items gone through (9.6
    /// backtraces each through an instantiation of its own).
    pub firings: usize,
    items: FxHashSet<u64>,
    /// The variables of the firings backtraced: the identities the episode worked with.
    pub identities: usize,
    /// Fields where a condition met the action that made its WME: with an identity on
    /// both sides, and with a literal tested on the condition's side.
    pub propagations: usize,
    pub propagations_blocked: usize,
    /// Unions of two identity sets.
    pub joins: usize,
    /// Conditions that tested a WME another condition had already given to the rule
    /// (they become one condition).
    pub merged: usize,
    /// Relational tests on local conditions whose value a rule made as a literal.
    pub literal_constraints: usize,
    /// A local WME `^quiescence t` was tested (9.6 then learns no chunk).
    pub tested_quiescence: bool,
    /// The reasoning went through a memory's retrieval (`chunk stats` counts it).
    pub tested_ltm: bool,
}

impl Backtrace {
    /// Empties the tables for an episode at `level`, numbered `number`, keeping their room.
    pub fn reset(&mut self, level: u32, number: u64) {
        self.level = level;
        self.grounds.clear();
        self.merged_grounds.clear();
        self.ground_at.clear();
        self.negations.clear();
        self.constraints.clear();
        self.parent.clear();
        self.literal.clear();
        self.number = number;
        self.stack.clear();
        self.firings = 0;
        self.items.clear();
        self.identities = 0;
        self.propagations = 0;
        self.propagations_blocked = 0;
        self.joins = 0;
        self.merged = 0;
        self.tested_quiescence = false;
        self.tested_ltm = false;
        self.literal_constraints = 0;
    }

    /// The representative of an identity's joined set.
    pub fn find(&self, mut i: Ident) -> Ident {
        while let Some(&p) = self.parent.get(&i) {
            if p == i {
                break;
            }
            i = p;
        }
        i
    }

    pub fn join(&mut self, a: Ident, b: Ident) {
        if a == 0 || b == 0 {
            return;
        }
        let (ra, rb) = (self.find(a), self.find(b));
        if ra == rb {
            return;
        }
        // The older identity stays the representative (stable variable names).
        let (keep, gone) = if ra < rb { (ra, rb) } else { (rb, ra) };
        self.parent.insert(gone, keep);
        self.joins += 1;
        if let Some(l) = self.literal.remove(&gone) {
            self.literal.entry(keep).or_insert(l);
        }
    }

    /// Backtraces a result preference through the firing that made it.
    pub fn result(&mut self, origin: &PrefOrigin, agent: &AgentCore, quiescence: Sym, t: Sym) {
        self.firing(&origin.trace, agent, quiescence, t);
    }

    fn firing(&mut self, trace: &Arc<InstTrace>, agent: &AgentCore, quiescence: Sym, t: Sym) {
        let mut stack = std::mem::take(&mut self.stack);
        stack.push(Pending::Firing(trace.clone()));
        // The local WMEs are gone through last found first, as 9.6 takes them off the
        // head of its list of locals: the grounds come in the order 9.6 finds them.
        while let Some(next) = stack.pop() {
            let trace = match next {
                Pending::Firing(trace) => trace,
                Pending::Item(c, trace) => {
                    self.add_ground(&c, &trace, agent);
                    continue;
                }
            };
            if trace.backtraced.swap(self.number, Relaxed) == self.number {
                continue;
            }
            self.firings += 1;
            self.identities += trace.vars.len();
            self.tested_ltm |= super::memory_results::is_retrieval(&trace);
            for c in &trace.conds {
                if c.via_item && self.items.insert(c.wme.timetag) {
                    self.firings += 1;
                }
                if c.level > 0 && c.level < self.level {
                    if c.via_item {
                        stack.push(Pending::Item(c.clone(), trace.clone()));
                    } else {
                        self.add_ground(c, &trace, agent);
                    }
                    // The prohibit preferences of a higher state's operator slot that
                    // this firing tested are backtraced too (their firings' conditions
                    // come in as they are: a top-state firing's with its identifiers).
                    self.push_osk(c, &mut stack);
                    continue;
                }
                if c.wme.attr == quiescence && c.wme.value == t {
                    self.tested_quiescence = true;
                }
                if let Some(origin) = &c.support {
                    // Without identities (learning off) there is nothing to propagate.
                    if c.ids != [0; 3] || origin.ids[..3] != [0; 3] {
                        self.propagate(&trace, c, origin, &agent.symbols);
                    }
                    // A firing already gone through would be passed over when popped.
                    if origin.trace.backtraced.load(Relaxed) != self.number {
                        stack.push(Pending::Firing(origin.trace.clone()));
                    }
                    // The knowledge that selected a tested operator goes with its
                    // proposal, without joining identities (`chunk add-osk`).
                    self.push_osk(c, &mut stack);
                }
            }
            if let Some(prod) = &trace.prod {
                for (i, c) in prod.conditions.iter().enumerate() {
                    if !matches!(c, crate::production::Condition::Positive(_)) {
                        self.negations.push(Negation {
                            trace: trace.clone(),
                            cond: i,
                        });
                    }
                }
            }
        }
        self.stack = stack;
    }

    /// The firings behind condition `c`'s operator selection knowledge, to be backtraced.
    fn push_osk(&self, c: &TraceCond, stack: &mut Vec<Pending>) {
        if let Some(osk) = &c.osk {
            for o in osk.iter() {
                if o.trace.backtraced.load(Relaxed) != self.number {
                    stack.push(Pending::Firing(o.trace.clone()));
                }
            }
        }
    }

    /// Where a local condition met the action that made its WME: identities on both
    /// sides join, and a literal tested on what was made from a variable fixes it.
    fn propagate(
        &mut self,
        trace: &Arc<InstTrace>,
        c: &TraceCond,
        origin: &PrefOrigin,
        symbols: &crate::symbols::Symbols,
    ) {
        let fields = [c.wme.id, c.wme.attr, c.wme.value];
        for ((&tested, &made), field) in c.ids.iter().zip(&origin.ids).zip(fields) {
            match (tested, made) {
                (0, 0) => {}
                // A literal tested on what was made from a variable: the chunk can only
                // fire for that literal.
                (0, made) => {
                    self.propagations_blocked += 1;
                    let r = self.find(made);
                    self.literal.entry(r).or_insert(field);
                }
                // A variable tested on what was made from a literal (or a function's
                // value): that identity is the literal (9.6 literalizes it, checked on
                // soar-sml 9.6.5).
                (tested, 0) => {
                    self.propagations += 1;
                    if !symbols.is_id(field) {
                        let r = self.find(tested);
                        self.literal.entry(r).or_insert(field);
                    }
                }
                (tested, made) => {
                    self.propagations += 1;
                    self.join(tested, made)
                }
            }
        }
        self.local_constraints(trace, c, origin);
    }

    /// The relational tests of a local condition, on fields made from an identity.
    fn local_constraints(&mut self, trace: &Arc<InstTrace>, c: &TraceCond, origin: &PrefOrigin) {
        let Some(crate::production::Condition::Positive(cond)) = c
            .cond
            .and_then(|ci| trace.prod.as_ref()?.conditions.get(ci))
        else {
            return;
        };
        for (t, &made) in [&cond.id, &cond.attr, &cond.value]
            .into_iter()
            .zip(&origin.ids)
        {
            if matches!(t, crate::production::Test::Equal(_)) {
                continue;
            }
            let mut tests = Vec::new();
            relational_parts(t, &mut tests);
            if made == 0 {
                // Tested on a literal the rule made: detected (9.6 counts it), but the
                // literal meets it, so nothing is left to enforce.
                self.literal_constraints += tests.len();
                continue;
            }
            for test in tests {
                self.constraints.push(Constraint {
                    ident: made,
                    test,
                    trace: trace.clone(),
                });
            }
        }
    }

    /// Identifiers are always variables, and one identifier is one variable: identities
    /// that matched the same identifier are joined (so the conditions stay connected).
    /// The conditions of a superstate's firing that operator selection knowledge brought
    /// in keep their own identities: 9.6 gives that state's firings identities of their
    /// own, and the chunk tests them with variables of their own.
    pub fn join_same_identifiers(&mut self, symbols: &crate::symbols::Symbols) {
        let mut first: FxHashMap<Sym, Ident> = FxHashMap::default();
        let mut pairs = Vec::new();
        let level = self.level;
        for g in self.grounds.iter().filter(|g| g.trace.level >= level) {
            let w = g.cond.wme;
            for (s, i) in [w.id, w.attr, w.value].into_iter().zip(g.cond.ids) {
                if i != 0 && symbols.is_id(s) {
                    match first.get(&s) {
                        Some(&f) => pairs.push((f, i)),
                        None => {
                            first.insert(s, i);
                        }
                    }
                }
            }
        }
        for (a, b) in pairs {
            self.join(a, b);
        }
    }

    /// A superstate WME: the same WME tested twice joins the identities of both tests.
    fn add_ground(&mut self, c: &TraceCond, trace: &Arc<InstTrace>, agent: &AgentCore) {
        let symbols = &agent.symbols;
        let first = self.ground_at.get(&c.wme.timetag).copied();
        // A WME that is no singleton may be tested by several conditions of the chunk,
        // each with its own identities (9.6; equal ones merge when the rule is built).
        if let Some(g) = first.filter(|_| agent.is_singleton(&c.wme)) {
            self.merged += 1;
            // Only a justification built with learning on lists them (see `merged_grounds`).
            if agent.settings.learn != crate::agent::LearnMode::Never {
                self.merged_grounds.push((
                    self.grounds.len(),
                    Ground {
                        cond: c.clone(),
                        trace: trace.clone(),
                    },
                ));
            }
            let ids = self.grounds[g].cond.ids;
            for (a, b) in ids.into_iter().zip(c.ids) {
                self.join(a, b);
            }
            // A value one test names by a literal is that literal in the other too (9.6
            // unifies the values of two conditions on one singleton WME).
            let value = c.wme.value;
            if let (0, i) | (i, 0) = (ids[2], c.ids[2]) {
                if i != 0 && !symbols.is_id(value) {
                    let r = self.find(i);
                    self.literal.entry(r).or_insert(value);
                }
            }
            return;
        }
        if first.is_none() {
            self.ground_at.insert(c.wme.timetag, self.grounds.len());
        }
        self.grounds.push(Ground {
            cond: c.clone(),
            trace: trace.clone(),
        });
    }
}

/// The relational and disjunction tests inside a test.
fn relational_parts(t: &crate::production::Test, out: &mut Vec<crate::production::Test>) {
    use crate::production::Test;
    match t {
        Test::Relational(..) | Test::Disjunction(_) => out.push(t.clone()),
        Test::Conjunction(ts) => ts.iter().for_each(|x| relational_parts(x, out)),
        Test::Equal(_) => {}
    }
}
