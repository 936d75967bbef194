//! Building the learned rule from a backtrace (Soar manual, ch. 4, "Procedural Knowledge
//! Learning"): its conditions are the grounds (plus the negations on superstate objects the
//! reasoning used), its actions the results. A chunk gets one variable per joined identity,
//! named after the attribute it first sits under in join order (`<o1>` for `^operator`,
//! see `var_order.rs`), counted per letter; literals stay literals. A justification keeps
//! the symbols themselves.

use super::backtrace::Backtrace;
use super::record::equality_var;
use super::{Ident, InstTrace};
use crate::agent::AgentCore;
use crate::ast::{Constant, Head};
use crate::decide::procedure::PrefType;
use crate::decide::state::PrefId;
use crate::production::{
    Action, Cond, Condition, Flags, FuncCall, Make, PrefKind, Production, RhsTerm, Term, Test,
};
use crate::symbols::{Sym, SymData};
use rustc_hash::{FxHashMap, FxHashSet};
use std::sync::Arc;

fn pref_kind(t: PrefType) -> PrefKind {
    match t {
        PrefType::Acceptable => PrefKind::Acceptable,
        PrefType::Reject => PrefKind::Reject,
        PrefType::Require => PrefKind::Require,
        PrefType::Prohibit => PrefKind::Prohibit,
        PrefType::Best => PrefKind::Best,
        PrefType::Worst => PrefKind::Worst,
        PrefType::UnaryIndifferent => PrefKind::Indifferent,
        PrefType::Better => PrefKind::Better,
        PrefType::Worse => PrefKind::Worse,
        PrefType::BinaryIndifferent => PrefKind::BinaryIndifferent,
        PrefType::NumericIndifferent => PrefKind::NumericIndifferent,
    }
}

/// Variable names for a chunk: one per identity set, `<letter><n>` counted per letter.
#[derive(Default)]
struct Namer {
    variablize: bool,
    by_ident: FxHashMap<Ident, String>,
    by_sym: FxHashMap<Sym, String>,
    counters: FxHashMap<char, u32>,
    /// Every name made, in order, and the own letter of those that stand for an
    /// identifier: the names are given again in join order once the rule is built.
    created: Vec<String>,
    own: FxHashMap<String, char>,
}

impl Namer {
    fn fresh(&mut self, letter: char) -> String {
        let n = self.counters.entry(letter).or_insert(0);
        *n += 1;
        let name = format!("<{letter}{n}>");
        self.created.push(name.clone());
        name
    }

    /// A new name for `sym`, noting an identifier's own letter.
    fn fresh_for(&mut self, agent: &AgentCore, sym: Sym, under: Option<Sym>) -> String {
        let n = self.fresh(letter_for(agent, sym, under));
        if let SymData::Id(d) = agent.symbols.get(sym) {
            self.own.insert(n.clone(), (d.letter as char).to_ascii_lowercase());
        }
        n
    }
}

/// The letter a variable is named by: the attribute's first letter for a value, the
/// identifier's own letter otherwise.
fn letter_for(agent: &AgentCore, sym: Sym, under: Option<Sym>) -> char {
    if let Some(SymData::Str(s)) = under.map(|a| agent.symbols.get(a)) {
        if let Some(c) = s.chars().next().filter(char::is_ascii_alphabetic) {
            return c.to_ascii_lowercase();
        }
    }
    match agent.symbols.get(sym) {
        SymData::Id(d) => (d.letter as char).to_ascii_lowercase(),
        _ => 'v',
    }
}

fn constant_of(agent: &AgentCore, s: Sym) -> Constant {
    match agent.symbols.get(s) {
        SymData::Str(x) => Constant::Str(x.clone()),
        SymData::Int(i) => Constant::Int(*i),
        SymData::Float(f) => Constant::Float(*f),
        SymData::Id(_) => Constant::Str(agent.symbols.text(s).into()),
    }
}

struct Builder<'a> {
    agent: &'a AgentCore,
    bt: &'a Backtrace,
    namer: Namer,
    /// Identity sets that some positive condition binds (only these may appear elsewhere).
    bound: FxHashSet<Ident>,
    /// The identity set each identifier of the conditions has (an action naming the same
    /// identifier through another identity gets the same variable).
    ground_ids: FxHashMap<Sym, Ident>,
    /// The rule's relational tests and RHS function calls are carried over: always for a
    /// chunk, for a justification only with learning on (9.6 builds it as it builds a
    /// chunk then, without variables).
    keep_tests: bool,
    /// A justification's identifiers by name, each named once per rule.
    id_names: FxHashMap<Sym, arcstr::ArcStr>,
}

impl Builder<'_> {
    /// The term for a symbol seen with an identity.
    fn term(&mut self, sym: Sym, ident: Ident, under: Option<Sym>) -> Term {
        let is_id = self.agent.symbols.is_id(sym);
        if !self.namer.variablize {
            return if is_id {
                // Justifications print their identifiers bare (`(state S1 ^operator O1)`).
                let symbols = &self.agent.symbols;
                let name = self
                    .id_names
                    .entry(sym)
                    .or_insert_with(|| symbols.text(sym).into());
                Term::Var(name.clone())
            } else {
                Term::Const(constant_of(self.agent, sym))
            };
        }
        let mut root = self.bt.find(ident);
        if is_id && !self.bound.contains(&root) {
            if let Some(&r) = self.ground_ids.get(&sym) {
                root = r;
            } else if let Some(n) = self.namer.by_sym.get(&sym) {
                // An identifier the conditions test without an identity (one a tie's
                // ^item led to): its variable there.
                return Term::Var(n.as_str().into());
            }
        }
        if root != 0 {
            if let Some(&l) = self.bt.literal.get(&root) {
                return Term::Const(constant_of(self.agent, l));
            }
            if let Some(n) = self.namer.by_ident.get(&root) {
                return Term::Var(n.as_str().into());
            }
            let n = self.namer.fresh_for(self.agent, sym, under);
            self.namer.by_ident.insert(root, n.clone());
            return Term::Var(n.into());
        }
        if is_id {
            if let Some(n) = self.namer.by_sym.get(&sym) {
                return Term::Var(n.as_str().into());
            }
            let n = self.namer.fresh_for(self.agent, sym, under);
            self.namer.by_sym.insert(sym, n.clone());
            return Term::Var(n.into());
        }
        Term::Const(constant_of(self.agent, sym))
    }

    /// A variable of a rule's test, as the chunk names it; `None` when the chunk cannot
    /// test it (its identity is not bound by the chunk's conditions, nor is its identifier
    /// one the conditions match: `(<ss> -^prefix object)` where `<ss>` came through the
    /// substate's `^superstate` is kept on the state the chunk tests).
    fn var_term(&mut self, trace: &InstTrace, v: &str) -> Option<Term> {
        let &(ident, sym) = trace.vars.get(v)?;
        if !self.namer.variablize {
            return Some(self.term(sym, ident, None));
        }
        let root = self.bt.find(ident);
        if self.bt.literal.contains_key(&root)
            || self.bound.contains(&root)
            || self.ground_ids.contains_key(&sym)
        {
            return Some(self.term(sym, ident, None));
        }
        if self.agent.symbols.is_id(sym) {
            None
        } else {
            Some(Term::Const(constant_of(self.agent, sym)))
        }
    }

    /// The non-equality tests of a rule's test, carried over to the chunk.
    fn extra_tests(&mut self, trace: &InstTrace, t: &Test, out: &mut Vec<Test>) {
        match t {
            Test::Relational(rt) => match &rt.term {
                Term::Var(v) => {
                    if let Some(term) = self.var_term(trace, v) {
                        out.push(Test::relational(rt.op, term));
                    }
                }
                Term::Const(_) => out.push(t.clone()),
            },
            Test::Disjunction(_) => out.push(t.clone()),
            Test::Conjunction(ts) => ts.iter().for_each(|x| self.extra_tests(trace, x, out)),
            Test::Equal(_) => {}
        }
    }

    /// A field's equality test with the other tests on it: the equality comes first, as
    /// 9.6 prints a chunk's conjunctive tests (`^num3 { <n1> << 2 3 >> }`); a
    /// justification's comes last (`^num3 { << 2 3 >> 2 }`).
    fn field_test(&mut self, main: Term, extra: Vec<Test>) -> Test {
        if extra.is_empty() {
            Test::Equal(main)
        } else if !self.namer.variablize {
            let mut ts = extra;
            ts.push(Test::Equal(main));
            Test::conjunction(ts)
        } else {
            let mut ts = Vec::with_capacity(extra.len() + 1);
            ts.push(Test::Equal(main));
            ts.extend(extra);
            Test::conjunction(ts)
        }
    }

    /// A negated condition of a backtraced firing, translated; `None` when it tests
    /// something the chunk cannot name (local structure).
    fn negation(
        &mut self,
        trace: &InstTrace,
        c: &Condition,
        locals: &mut FxHashMap<String, String>,
    ) -> Option<Condition> {
        match c {
            Condition::Positive(x) | Condition::Negative(x) => {
                // A local value is named after its attribute, as in positive conditions.
                let under = match &x.attr {
                    Test::Equal(Term::Const(Constant::Str(a))) => a.chars().next(),
                    _ => None,
                }
                .filter(char::is_ascii_alphabetic);
                let mut fields = Vec::with_capacity(3);
                for (t, hint) in [(&x.id, None), (&x.attr, None), (&x.value, under)] {
                    fields.push(self.negated_test(trace, t, hint, locals)?);
                }
                let value = fields.pop()?;
                let attr = fields.pop()?;
                let id = fields.pop()?;
                let cond = Cond {
                    id,
                    attr,
                    value,
                    acceptable: x.acceptable,
                    goal: Head::None,
                    span: x.span,
                };
                Some(match c {
                    Condition::Positive(_) => Condition::Positive(cond),
                    _ => Condition::Negative(cond),
                })
            }
            Condition::Ncc(cs) => {
                let mut out = Vec::with_capacity(cs.len());
                for x in cs {
                    out.push(self.negation(trace, x, locals)?);
                }
                Some(Condition::Ncc(out))
            }
        }
    }

    /// A test of a negated condition; a variable local to it is named after `hint` (its
    /// attribute's first letter) if given, else after the rule's variable.
    fn negated_test(
        &mut self,
        trace: &InstTrace,
        t: &Test,
        hint: Option<char>,
        locals: &mut FxHashMap<String, String>,
    ) -> Option<Test> {
        let term = |b: &mut Self, term: &Term, locals: &mut FxHashMap<String, String>| match term {
            Term::Var(v) if trace.vars.contains_key(v) => b.var_term(trace, v),
            // A justification keeps the rule's own names for them (`-^t-done <t*1>`).
            Term::Var(v) if !b.namer.variablize => Some(Term::Var(v.clone())),
            Term::Var(v) => Some(Term::Var(match locals.get(&**v) {
                Some(n) => n.as_str().into(),
                None => {
                    let letter = hint
                        .or_else(|| v.chars().nth(1))
                        .filter(char::is_ascii_alphabetic)
                        .unwrap_or('v');
                    let n = b.namer.fresh(letter.to_ascii_lowercase());
                    locals.insert(v.to_string(), n.clone());
                    n.into()
                }
            })),
            Term::Const(c) => Some(Term::Const(c.clone())),
        };
        Some(match t {
            Test::Equal(x) => Test::Equal(term(self, x, locals)?),
            Test::Relational(rt) => Test::relational(rt.op, term(self, &rt.term, locals)?),
            Test::Disjunction(cs) => Test::Disjunction(cs.clone()),
            Test::Conjunction(ts) => {
                let mut out = Vec::with_capacity(ts.len());
                for x in ts.iter() {
                    out.push(self.negated_test(trace, x, hint, locals)?);
                }
                // An equality on a variable of the negation's own goes first (9.6:
                // `-^c { <c1> << x y >> }`); one the chunk binds elsewhere stays where the
                // rule has it (`-^w { <> 5 <a1> }`).
                let local = ts.iter().position(|x| {
                    matches!(x, Test::Equal(Term::Var(v)) if !trace.vars.contains_key(v))
                });
                if let Some(k) = local.filter(|_| self.namer.variablize) {
                    out[..=k].rotate_right(1);
                }
                Test::conjunction(out)
            }
        })
    }

    /// An action's term: a function call of the original action is rebuilt over the
    /// chunk's variables; anything else is the symbol the result holds.
    fn action_term(
        &mut self,
        trace: Option<&InstTrace>,
        orig: Option<&RhsTerm>,
        sym: Sym,
        ident: Ident,
        under: Option<Sym>,
    ) -> RhsTerm {
        // (A justification keeps the call too, over the symbols, `(+ 5 1)`, when
        // learning is on.)
        if let (Some(trace), Some(RhsTerm::Call(f)), true) = (trace, orig, self.keep_tests) {
            if let Some(call) = self.call(trace, f) {
                return RhsTerm::Call(Box::new(call));
            }
        }
        match self.term(sym, ident, under) {
            Term::Var(v) => RhsTerm::Var(v),
            Term::Const(c) => RhsTerm::Const(c),
        }
    }

    fn call(&mut self, trace: &InstTrace, f: &FuncCall) -> Option<FuncCall> {
        let mut args = Vec::with_capacity(f.args.len());
        for a in &f.args {
            args.push(match a {
                RhsTerm::Var(v) => match self.var_term(trace, v)? {
                    Term::Var(x) => RhsTerm::Var(x),
                    Term::Const(c) => RhsTerm::Const(c),
                },
                RhsTerm::Const(c) => RhsTerm::Const(c.clone()),
                RhsTerm::Call(g) => RhsTerm::Call(Box::new(self.call(trace, g)?)),
            });
        }
        Some(FuncCall {
            name: f.name.clone(),
            args,
            span: f.span,
        })
    }
}

impl AgentCore {
    /// The negations of a backtrace that belong to a learned rule or justification: those
    /// about superstate objects, with the rule each is a condition of.
    pub(crate) fn superstate_negations<'b>(
        &self,
        bt: &'b Backtrace,
    ) -> Vec<(&'b super::backtrace::Negation, Arc<Production>)> {
        let mut out = Vec::new();
        for n in &bt.negations {
            let Some((id_level, prod)) = self.negation_level(n) else {
                continue;
            };
            if id_level != 0 && id_level < bt.level {
                out.push((n, prod));
            }
        }
        // 9.6 gathers them front first: the learned rule lists them last found first,
        // which decides the order among negations that become testable together.
        out.reverse();
        out
    }

    /// The level of the identifier a negated condition of a backtraced firing tests
    /// (`u32::MAX` when it names none), with the rule it belongs to.
    fn negation_level(&self, n: &super::backtrace::Negation) -> Option<(u32, Arc<Production>)> {
        let prod = n.trace.prod.clone()?;
        let c = prod.conditions.get(n.cond)?;
        let first = match c {
            Condition::Negative(x) | Condition::Positive(x) => Some(x),
            Condition::Ncc(cs) => cs.iter().find_map(|x| match x {
                Condition::Positive(x) | Condition::Negative(x) => Some(x),
                _ => None,
            }),
        };
        let id_level = first
            .and_then(|x| equality_var(&x.id))
            .and_then(|v| n.trace.vars.get(v))
            .and_then(|&(_, s)| self.symbols.id_data(s))
            .map_or(u32::MAX, |d| d.level);
        Some((id_level, prod))
    }

    /// Whether the reasoning behind a result tested the absence of something in the
    /// substate (Soar manual, ch. 4, "Using negated conditions about the substate"): a
    /// chunk cannot carry such a test, so it may be wrong when that knowledge changes.
    pub(crate) fn tests_local_negation(&self, bt: &Backtrace) -> bool {
        bt.negations.iter().any(|n| {
            self.negation_level(n)
                .is_some_and(|(l, _)| l != u32::MAX && l >= bt.level)
        })
    }

    /// The negations about the substate that a backtrace's reasoning tested, as 9.6's
    /// warning shows them: over the symbols matched, a variable of the negation's own
    /// kept (`(S2 -^blocker <b*1>)`).
    pub(crate) fn local_negation_texts(&self, bt: &Backtrace) -> Vec<String> {
        bt.negations
            .iter()
            .filter_map(|n| self.literal_negation(bt, n))
            .filter(|&(level, _)| level != u32::MAX && level >= bt.level)
            .map(|(_, c)| crate::printer::cond_text_with(&c, false))
            .collect()
    }

    /// A negated condition of a backtraced firing over the symbols it matched (a variable
    /// of the negation's own kept), with the level of the identifier it tests (`u32::MAX`
    /// when it names none).
    pub(crate) fn literal_negation(
        &self,
        bt: &Backtrace,
        n: &super::backtrace::Negation,
    ) -> Option<(u32, Condition)> {
        let (level, prod) = self.negation_level(n)?;
        let mut b = Builder {
            agent: self,
            bt,
            namer: Namer::default(),
            bound: FxHashSet::default(),
            ground_ids: FxHashMap::default(),
            keep_tests: true,
            id_names: FxHashMap::default(),
        };
        let mut locals = FxHashMap::default();
        let c = b.negation(&n.trace, prod.conditions.get(n.cond)?, &mut locals)?;
        Some((level, c))
    }

    /// The rule a backtrace gives: a chunk (`variablize`) or a justification.
    /// A justification made with learning off, as its sketch: the conditions in 9.6's order
    /// (last found first, each state marked on its first condition) and the results, as
    /// [`AgentCore::build_learned_rule`] writes them then. (Superstate negations are
    /// written out at once by the builder: callers with any build the rule instead.)
    pub(crate) fn sketch_justification(
        &self,
        bt: &Backtrace,
        results: &[PrefId],
        name: String,
    ) -> super::sketch::Sketch {
        let ordered = self.results_in_action_order(bt, results);
        let results = ordered.as_slice();
        let mut marked: FxHashSet<Sym> = FxHashSet::default();
        let conditions = bt
            .grounds
            .iter()
            .rev()
            .map(|g| {
                let w = g.cond.wme;
                let span = g
                    .cond
                    .cond
                    .and_then(|ci| match g.trace.prod.as_ref()?.conditions.get(ci)? {
                        Condition::Positive(c) => Some(c.span),
                        _ => None,
                    })
                    .unwrap_or_default();
                let state = self.symbols.is_goal(w.id) && marked.insert(w.id);
                (w, state, span)
            })
            .collect();
        let actions = results
            .iter()
            .map(|&r| {
                let p = &self.decider.prefs[r];
                let span = p
                    .origin
                    .as_ref()
                    .and_then(|o| match o.trace.prod.as_ref()?.actions.get(o.action?)? {
                        Action::Make(m) => Some(m.span),
                        _ => None,
                    })
                    .unwrap_or_default();
                (pref_kind(p.kind), [p.id, p.attr, p.value], p.referent, span)
            })
            .collect();
        super::sketch::Sketch {
            name,
            conditions,
            actions,
        }
    }

    /// A learned rule's results in the order of its actions (see `learned_action_order`).
    fn results_in_action_order(&self, bt: &Backtrace, results: &[PrefId]) -> Vec<PrefId> {
        self.learned_action_order(bt, results)
            .into_iter()
            .map(|k| results[k])
            .collect()
    }

    /// The order of a learned rule's actions, as indexes into its `results`: 9.6 orders a
    /// learned rule's actions as it orders any rule's when it loads it (see
    /// `rete::reorder::reorder_actions`): again and again the first result whose object the
    /// conditions test, or an action taken before names, goes next. So the result on the
    /// superstate comes before the results on the objects it links.
    pub(crate) fn learned_action_order(&self, bt: &Backtrace, results: &[PrefId]) -> Vec<usize> {
        let mut order: Vec<usize> = (0..results.len()).collect();
        if results.len() < 2 {
            return order;
        }
        order.clear();
        let prefs = &self.decider.prefs;
        let tested = |s: Sym| {
            bt.grounds
                .iter()
                .any(|g| g.cond.wme.id == s || g.cond.wme.attr == s || g.cond.wme.value == s)
        };
        // What the actions taken so far name (a rule makes few results).
        let mut named: Vec<Sym> = Vec::new();
        let mut taken = vec![false; results.len()];
        while let Some(k) = (0..results.len()).find(|&k| {
            let id = prefs[results[k]].id;
            !taken[k] && (named.contains(&id) || tested(id))
        }) {
            taken[k] = true;
            order.push(k);
            let p = &prefs[results[k]];
            named.extend([Some(p.attr), Some(p.value), p.referent].into_iter().flatten());
        }
        order.extend((0..results.len()).filter(|&k| !taken[k]));
        order
    }

    pub(crate) fn build_learned_rule(
        &self,
        bt: &Backtrace,
        results: &[PrefId],
        name: String,
        variablize: bool,
    ) -> Production {
        let ordered = self.results_in_action_order(bt, results);
        let results = ordered.as_slice();
        let mut b = Builder {
            agent: self,
            bt,
            namer: Namer {
                variablize,
                ..Namer::default()
            },
            bound: FxHashSet::default(),
            ground_ids: FxHashMap::default(),
            keep_tests: variablize || self.settings.learn != crate::agent::LearnMode::Never,
            id_names: FxHashMap::default(),
        };
        // Which identities and identifiers the conditions bind: only a chunk's variables
        // need them.
        for g in bt.grounds.iter().filter(|_| variablize) {
            let w = g.cond.wme;
            for (&i, s) in g.cond.ids.iter().zip([w.id, w.attr, w.value]) {
                if i != 0 {
                    b.bound.insert(bt.find(i));
                    if self.symbols.is_id(s) {
                        b.ground_ids.entry(s).or_insert(bt.find(i));
                    }
                }
            }
        }
        // Variables are named where they are first tested for equality (9.6: `^to <t1>`,
        // even when a relational test elsewhere names it first), here in the grounds'
        // order, and again in join order once the rule is built. A justification has none.
        for g in bt.grounds.iter().filter(|_| variablize) {
            let w = g.cond.wme;
            b.term(w.id, g.cond.ids[0], None);
            b.term(w.attr, g.cond.ids[1], None);
            b.term(w.value, g.cond.ids[2], Some(w.attr));
        }
        let mut constrained: FxHashSet<Ident> = FxHashSet::default();
        // A justification built with learning on tests a WME once for each condition
        // behind it that tested it, as 9.6 lists it (`^flag on ^flag on`).
        let all_tests = !variablize && b.keep_tests && !bt.merged_grounds.is_empty();
        let grounds: Vec<&super::backtrace::Ground> = if all_tests {
            let mut merged = bt.merged_grounds.iter().peekable();
            let mut out = Vec::with_capacity(bt.grounds.len() + bt.merged_grounds.len());
            for (i, g) in bt.grounds.iter().enumerate() {
                while let Some((_, m)) = merged.next_if(|(at, _)| *at <= i) {
                    out.push(m);
                }
                out.push(g);
            }
            out.extend(merged.map(|(_, m)| m));
            out
        } else {
            bt.grounds.iter().collect()
        };
        let mut conditions = Vec::new();
        // The identifiers marked as states, by the term that tests them (one state can
        // be tested through two variables, see `join_same_identifiers`).
        let mut goal_tested: Vec<Term> = Vec::new();
        for &g in &grounds {
            let w = g.cond.wme;
            let orig =
                g.cond
                    .cond
                    .and_then(|ci| match g.trace.prod.as_ref()?.conditions.get(ci)? {
                        Condition::Positive(c) => Some(c),
                        _ => None,
                    });
            let id = b.term(w.id, g.cond.ids[0], None);
            let attr = b.term(w.attr, g.cond.ids[1], None);
            let value = b.term(w.value, g.cond.ids[2], Some(w.attr));
            let mut tests = [Vec::new(), Vec::new(), Vec::new()];
            // With learning off, a justification tests the symbols themselves, nothing more.
            if let Some(o) = orig.filter(|_| b.keep_tests) {
                for (k, t) in [&o.id, &o.attr, &o.value].into_iter().enumerate() {
                    b.extra_tests(&g.trace, t, &mut tests[k]);
                }
            }
            for (k, &i) in g.cond.ids.iter().enumerate() {
                let root = bt.find(i);
                if !b.keep_tests || i == 0 || !constrained.insert(root) {
                    continue;
                }
                for c in bt.constraints.iter().filter(|c| bt.find(c.ident) == root) {
                    b.extra_tests(&c.trace, &c.test, &mut tests[k]);
                }
            }
            // A literalized field needs no other test (9.6 drops them).
            for (k, &i) in g.cond.ids.iter().enumerate() {
                if i != 0 && bt.literal.contains_key(&bt.find(i)) {
                    tests[k].clear();
                }
                let mut seen = Vec::new();
                tests[k].retain(|t| {
                    let new = !seen.contains(t);
                    seen.push(t.clone());
                    new
                });
            }
            let [ti, ta, tv] = tests;
            // 9.6 marks the state the rule will match in (the learning goal's superstate).
            let goal = if self.symbols.is_goal(w.id)
                && self.sym_level(w.id) + 1 == bt.level
                && !goal_tested.contains(&id)
            {
                goal_tested.push(id.clone());
                Head::State
            } else {
                Head::None
            };
            let cond = Cond {
                id: b.field_test(id, ti),
                attr: b.field_test(attr, ta),
                value: b.field_test(value, tv),
                acceptable: w.acceptable,
                goal,
                span: orig.map(|o| o.span).unwrap_or_default(),
            };
            // Two conditions of a chunk on one WME that came out the same are one (9.6
            // merges them).
            let same = |c: &Condition| {
                matches!(c, Condition::Positive(x) if x.id == cond.id && x.attr == cond.attr
                    && x.value == cond.value && x.acceptable == cond.acceptable)
            };
            if variablize && conditions.iter().any(same) {
                continue;
            }
            conditions.push(Condition::Positive(cond));
        }
        if !variablize {
            // A justification is not reordered: 9.6 lists its conditions last found first,
            // and marks each state it tests (`(state S1 ^superstate nil)`,
            // `(state S2 ^superstate S1)`) on the first condition of it.
            conditions.reverse();
            let mut marked: FxHashSet<Sym> = FxHashSet::default();
            for (c, g) in conditions.iter_mut().zip(grounds.iter().rev()) {
                if let Condition::Positive(c) = c {
                    let id = g.cond.wme.id;
                    c.goal = if self.symbols.is_goal(id) && marked.insert(id) {
                        Head::State
                    } else {
                        Head::None
                    };
                }
            }
        }
        for (n, prod) in self.superstate_negations(bt) {
            let c = &prod.conditions[n.cond];
            let mut locals = FxHashMap::default();
            if let Some(t) = b.negation(&n.trace, c, &mut locals) {
                if !conditions.contains(&t) {
                    conditions.push(t);
                }
            }
        }
        let mut actions = Vec::new();
        // The identities of the long-term identifiers' instances among the results.
        let mut instance_idents: FxHashMap<Sym, Ident> = FxHashMap::default();
        for &r in results {
            let p = &self.decider.prefs[r];
            let origin = p.origin.as_ref();
            let ids = origin.as_ref().map_or([0; 4], |o| o.ids);
            let links = variablize && self.settings.chunk.add_ltm_links;
            for (s, i) in [(p.id, ids[0]), (p.value, ids[2])].into_iter().filter(|_| links) {
                if self.symbols.lti(s).is_some() {
                    instance_idents.entry(s).or_insert(i);
                }
            }
            let make = origin.as_ref().and_then(|o| {
                let prod = o.trace.prod.as_ref()?;
                match prod.actions.get(o.action?)? {
                    Action::Make(m) => Some(m.clone()),
                    _ => None,
                }
            });
            let trace = origin.as_ref().map(|o| &*o.trace);
            let id = b.action_term(trace, make.as_ref().map(|m| &m.id), p.id, ids[0], None);
            let attr = b.action_term(trace, make.as_ref().map(|m| &m.attr), p.attr, ids[1], None);
            let value = b.action_term(
                trace,
                make.as_ref().map(|m| &m.value),
                p.value,
                ids[2],
                Some(p.attr),
            );
            let referent = p.referent.map(|s| {
                b.action_term(
                    trace,
                    make.as_ref().and_then(|m| m.referent.as_ref()),
                    s,
                    ids[3],
                    None,
                )
            });
            actions.push(Action::Make(Box::new(Make {
                id,
                attr,
                value,
                pref: pref_kind(p.kind),
                referent,
                span: make.map(|m| m.span).unwrap_or_default(),
            })));
        }
        // `chunk add-ltm-links`: each instance the rule makes anew is linked to its
        // long-term identifier, as the memory's retrieval linked it.
        if variablize && self.settings.chunk.add_ltm_links {
            for s in self.ltm_instances_in_results(results) {
                let (Some(&ident), Some(lti)) = (instance_idents.get(&s), self.symbols.lti(s)) else {
                    continue;
                };
                if b.ground_ids.contains_key(&s) || b.bound.contains(&bt.find(ident)) {
                    continue;
                }
                let var = match b.term(s, ident, None) {
                    Term::Var(v) => RhsTerm::Var(v),
                    Term::Const(_) => continue,
                };
                actions.push(Action::Call(Box::new(FuncCall {
                    name: "link-stm-to-ltm".into(),
                    args: vec![var, RhsTerm::Const(Constant::Int(lti))],
                    span: Default::default(),
                })));
            }
        }
        if variablize {
            let ordered = crate::rete::reorder::reorder_owned(
                conditions.clone(),
                &self.symbols,
                &self.multi_attributes,
            );
            super::var_order::rename_in_join_order(
                &mut conditions,
                &mut actions,
                &ordered,
                &b.namer.own,
                &b.namer.created,
            );
        }
        Production {
            name: name.into(),
            doc: None,
            flags: Flags {
                chunk: variablize,
                justification: !variablize,
                ..Flags::default()
            },
            conditions: conditions.into(),
            actions: actions.into(),
            span: Default::default(),
        }
    }
}
