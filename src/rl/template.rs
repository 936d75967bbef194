//! RL templates (Soar manual, ch. 5, "Rule Templates"): a `:template` rule's match makes no
//! preference; it makes an RL rule for that match's values, named `rl*<template>*<n>`, which
//! joins the rule memory while the agent runs and fires at once. The new rule's
//! conditions are the match's working-memory elements, each identifier a variable named by
//! its letter and counted per letter (`<s1>`, `<o1>`), each constant itself; a negated
//! condition keeps its tests with the values the match bound. Its action is the template's,
//! with the same values. A match whose rule is already loaded (the same conditions and
//! action, whatever the value learned) adds nothing and takes no number; the shapes of
//! the matches that made rules are remembered, so that such a match costs no rule build.
//!
//! 9.6 makes templates' rules whether learning is on or off, and the numbers go on across
//! `init-soar`. In episodes after the first, 9.6 sometimes makes, for a match whose rule is
//! loaded, a malformed rule whose state and operator share one variable (observed; it never
//! matches); rusoar adds nothing then. A template with a negated condition that tests a
//! bound variable crashes 9.6; rusoar makes the rule with the negation testing the values.

use crate::agent::{Added, AgentCore};
use crate::ast::Constant;
use crate::decide::state::PrefId;
use crate::production::{
    Action, Cond, Condition, Flags, FuncCall, Make, Production, RhsTerm, Term, Test,
};
use crate::rete::{ProdId, TokId};
use crate::symbols::{Sym, SymData};
use rustc_hash::FxHashMap;

/// The symbols a template's variables were bound to, and the variables that stand for
/// identifiers in the new rule.
#[derive(Default)]
struct Binder {
    bound: FxHashMap<arcstr::ArcStr, Sym>,
    names: FxHashMap<Sym, arcstr::ArcStr>,
    counters: FxHashMap<char, u32>,
}

impl Binder {
    /// The new rule's term for a symbol of the match.
    fn term(&mut self, agent: &AgentCore, s: Sym) -> Term {
        match agent.symbols.get(s) {
            SymData::Id(d) => {
                if let Some(n) = self.names.get(&s) {
                    return Term::Var(n.clone());
                }
                let letter = (d.letter as char).to_ascii_lowercase();
                let n = self.counters.entry(letter).or_insert(0);
                *n += 1;
                let name: arcstr::ArcStr = format!("<{letter}{n}>").into();
                self.names.insert(s, name.clone());
                Term::Var(name)
            }
            SymData::Str(x) => Term::Const(Constant::Str(x.clone())),
            SymData::Int(i) => Term::Const(Constant::Int(*i)),
            SymData::Float(f) => Term::Const(Constant::Float(*f)),
        }
    }

    /// A template term with the match's values: a bound variable becomes its value's term.
    fn subst(&mut self, agent: &AgentCore, t: &Term) -> Term {
        match t {
            Term::Var(v) => match self.bound.get(v) {
                Some(&s) => self.term(agent, s),
                None => t.clone(),
            },
            Term::Const(_) => t.clone(),
        }
    }

    fn subst_test(&mut self, agent: &AgentCore, t: &Test) -> Test {
        match t {
            Test::Equal(x) => Test::Equal(self.subst(agent, x)),
            Test::Relational(rt) => Test::relational(rt.op, self.subst(agent, &rt.term)),
            Test::Disjunction(_) => t.clone(),
            Test::Conjunction(ts) => {
                Test::conjunction(ts.iter().map(|x| self.subst_test(agent, x)).collect())
            }
        }
    }

    fn subst_condition(&mut self, agent: &AgentCore, c: &Condition) -> Condition {
        let cond = |b: &mut Self, c: &Cond| Cond {
            id: b.subst_test(agent, &c.id),
            attr: b.subst_test(agent, &c.attr),
            value: b.subst_test(agent, &c.value),
            ..c.clone()
        };
        match c {
            Condition::Positive(c) => Condition::Positive(cond(self, c)),
            Condition::Negative(c) => Condition::Negative(cond(self, c)),
            Condition::Ncc(cs) => {
                Condition::Ncc(cs.iter().map(|c| self.subst_condition(agent, c)).collect())
            }
        }
    }

    fn subst_rhs(&mut self, agent: &AgentCore, t: &RhsTerm) -> RhsTerm {
        match t {
            RhsTerm::Var(v) => match self.bound.get(v.as_str()) {
                Some(&s) => match self.term(agent, s) {
                    Term::Var(n) => RhsTerm::Var(n.clone()),
                    Term::Const(c) => RhsTerm::Const(c),
                },
                None => t.clone(),
            },
            RhsTerm::Const(_) => t.clone(),
            RhsTerm::Call(f) => RhsTerm::Call(Box::new(FuncCall {
                name: f.name.clone(),
                args: f.args.iter().map(|a| self.subst_rhs(agent, a)).collect(),
                ..(**f).clone()
            })),
        }
    }
}

/// The variables a field's test binds by equality.
fn equality_vars(t: &Test, out: &mut Vec<arcstr::ArcStr>) {
    match t {
        Test::Equal(Term::Var(v)) => out.push(v.clone()),
        Test::Conjunction(ts) => ts.iter().for_each(|x| equality_vars(x, out)),
        _ => {}
    }
}

impl AgentCore {
    /// A template rule matched (`p` at token `t`): its RL rule for the match's values joins
    /// the rule memory, and its matches fire now, in this elaboration cycle (observed on
    /// 9.6: `Firing rl*<template>*<n>` follows the template's firing).
    pub(crate) fn rl_template_fired(
        &mut self,
        p: ProdId,
        t: TokId,
        o_support: bool,
        new_prefs: &mut Vec<PrefId>,
    ) {
        // A match shaped like one that already made a rule makes the same rule, which is
        // loaded: a duplicate, known without building it (and, as most matches are, without
        // allocating).
        let mut shape = (p, std::mem::take(&mut self.rl.shape_scratch));
        self.match_shape(p, t, &mut shape.1);
        if self.rl.template_rules.contains_key(&shape) {
            self.rl.shape_scratch = shape.1;
            return;
        }
        let Some(template) = self.production_by_id(p) else {
            return;
        };
        let wmes: Vec<_> = self
            .rete
            .match_wmes(p, t)
            .into_iter()
            .map(|w| self.wm.get(w).copied())
            .collect();
        let mut b = Binder::default();
        let mut conditions = Vec::new();
        let positives = template
            .conditions
            .iter()
            .filter_map(|c| match c {
                Condition::Positive(c) => Some(c),
                _ => None,
            })
            .zip(&wmes);
        for (c, w) in positives {
            let Some(w) = w else { return };
            for (test, s) in [(&c.id, w.id), (&c.attr, w.attr), (&c.value, w.value)] {
                let mut vars = Vec::new();
                equality_vars(test, &mut vars);
                for v in vars {
                    b.bound.insert(v, s);
                }
            }
        }
        for c in template.conditions.iter() {
            let made = match c {
                Condition::Positive(c) => {
                    let Some(Some(w)) = wmes.get(conditions_positive_index(&conditions)) else {
                        return;
                    };
                    Condition::Positive(Cond {
                        id: Test::Equal(b.term(self, w.id)),
                        attr: Test::Equal(b.term(self, w.attr)),
                        value: Test::Equal(b.term(self, w.value)),
                        acceptable: c.acceptable,
                        goal: c.goal,
                        span: c.span,
                    })
                }
                other => b.subst_condition(self, other),
            };
            conditions.push(made);
        }
        let actions = template
            .actions
            .iter()
            .map(|a| match a {
                Action::Make(m) => Action::Make(Box::new(Make {
                    id: b.subst_rhs(self, &m.id),
                    attr: b.subst_rhs(self, &m.attr),
                    value: b.subst_rhs(self, &m.value),
                    pref: m.pref,
                    referent: m.referent.as_ref().map(|r| b.subst_rhs(self, r)),
                    span: m.span,
                })),
                other => other.clone(),
            })
            .collect();
        let mut n = self.rl.template_count + 1;
        let name = loop {
            let name = format!("rl*{}*{n}", template.name);
            if self.loaded(&name).is_none() {
                break name;
            }
            n += 1;
        };
        let rule = Production {
            name: name.as_str().into(),
            doc: None,
            flags: Flags::default(),
            conditions: conditions.into(),
            actions,
            // Made, not sourced: `print --filename` names no file (`_unknown_`).
            span: crate::source::Span::default(),
        };
        // A template's rule is a duplicate whatever its twin learned, even with `chunk-stop off`
        // (observed on 9.6).
        if !matches!(self.add_production_by_value(rule, false), Added::New) {
            return;
        }
        self.rl.template_count = n;
        let Some(id) = self.loaded(&name).map(|l| l.id) else {
            return;
        };
        self.rl.template_rules.insert(shape, id);
        // The new rule's matches leave the queue and fire now.
        self.matches.compact();
        let mine: Vec<TokId> = self
            .matches
            .assertions
            .iter()
            .filter(|m| m.0 == id)
            .map(|m| m.1)
            .collect();
        if mine.is_empty() {
            return;
        }
        self.matches.assertions.retain(|m| m.0 != id);
        self.matches.reindex();
        for tok in mine {
            self.matches.taken(id, tok);
            self.matches.support.remove(&(id, tok));
            self.fire(id, tok, o_support, new_prefs);
        }
    }
}

impl AgentCore {
    /// What a template's rule is made from: each field of the matched WMEs, a constant as
    /// itself and an identifier by its letter and the place it first appeared (the rule
    /// names identifiers' variables by letter, in order).
    fn match_shape(&mut self, p: ProdId, t: TokId, shape: &mut Vec<u64>) {
        shape.clear();
        let mut firsts = std::mem::take(&mut self.rl.shape_ids);
        firsts.clear();
        let positives = self.rete.production(p).map_or(0, |info| info.positives as usize);
        let mut filled = 0;
        for w in self.rete.match_row(p, t) {
            filled += 1;
            let Some(w) = self.wm.get(w) else {
                shape.push(u64::MAX);
                continue;
            };
            for s in [w.id, w.attr, w.value] {
                let code = match self.symbols.get(s) {
                    SymData::Id(d) => {
                        let place = firsts.iter().position(|f| *f == s).unwrap_or_else(|| {
                            firsts.push(s);
                            firsts.len() - 1
                        });
                        1 << 63 | u64::from(d.letter) << 32 | place as u64
                    }
                    _ => u64::from(s.0),
                };
                shape.push(code);
            }
        }
        // A match short of WMEs (never a complete one) is marked as `match_wmes` pads it.
        shape.extend(std::iter::repeat_n(u64::MAX, positives.saturating_sub(filled)));
        self.rl.shape_ids = firsts;
    }
}

/// How many positive conditions a condition list holds: the index of the next one's WME.
fn conditions_positive_index(conditions: &[Condition]) -> usize {
    conditions
        .iter()
        .filter(|c| matches!(c, Condition::Positive(_)))
        .count()
}
