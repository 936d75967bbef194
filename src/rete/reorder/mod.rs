//! Soar 9.6's condition reorderer (`production_reorder.cpp` in the kernel's sources): the
//! order in which a rule's conditions are joined, which is also the order `print` shows
//! them in and the order that decides which of several new matches fires first.
//!
//! The method, as the Soar manual and the kernel's observable behaviour describe it:
//! 1. only the root variables (ids tested but never bound as a value, normally `<s>`) keep
//!    their `state`/`impasse` test; others lose it;
//! 2. positive conditions are *simplified*: every test but the equality test of each field
//!    is set aside, indexed by the symbol of that equality test;
//! 3. conditions are chosen greedily by cost: a condition whose id is unbound costs
//!    [`MAX_COST`]; otherwise 1, times 8 if its attribute is unbound, times 8 if its value is
//!    unbound; a negation or conjunctive negation costs 1 once every variable it shares with
//!    positive conditions is bound. Ties above cost 1 are broken by a one-step look-ahead,
//!    then by the *canonical order*: the condition whose attribute (then value) constant was
//!    created last wins. Ties at cost 1 go to a negation, else by the canonical order. Within
//!    a tie the candidate list runs from the last condition to the first;
//! 4. the set-aside tests are restored on the first condition, in the new order, where they
//!    can be tested: where their own variable is bound and their referent is bound (or
//!    reversed, `<y> > <x>` becoming `<x> < <y>`, where the referent is bound first).
//!
//! Constants are ranked by the order they were created in the agent's symbol table
//! ([`Symbols`] interns the kernel's start-up constants first, `src/initial_symbols.txt`,
//! then each rule's constants in text order), which reproduces the kernel's tie breaks.

mod actions;
mod choose;
mod multi;
mod set_aside;

pub use actions::reorder_actions;

use crate::ast::{Constant, Head};
use crate::production::{Condition, Term, Test};
use crate::symbols::{SymData, Symbols};
use choose::Chooser;
pub use multi::MultiAttributes;
use rustc_hash::FxHashSet;

type Bound = FxHashSet<String>;

/// Reorders a rule's conditions as 9.6 does. `syms` must already hold every constant of the
/// rule (see [`intern_in_text_order`]); an unknown constant ranks as a variable.
#[cfg(test)]
pub fn reorder(conds: &[Condition], syms: &Symbols) -> Vec<Condition> {
    reorder_owned(conds.to_vec(), syms, &MultiAttributes::default())
}

/// [`reorder`], taking the conditions (no copy of them is made).
pub fn reorder_owned(
    mut conds: Vec<Condition>,
    syms: &Symbols,
    multi: &MultiAttributes,
) -> Vec<Condition> {
    let rank = |c: &Constant| syms.find_constant(c).map_or(0, |s| s.0 as u64 + 1);
    let multi = |c: &Constant| multi.count(c, syms);
    let outside = Bound::default();
    let mut roots = root_variables(&conds, &outside);
    if !roots.is_empty() {
        drop_goal_tests_of_non_roots(&mut conds, &roots);
    } else if let Some(v) = conds.iter().find_map(|c| match c {
        Condition::Positive(p) if p.goal != Head::None => equality_var(&p.id),
        _ => None,
    }) {
        roots.push(v.to_string());
    } else {
        // No state is referenced: compile rejects such rules; keep them as written.
        return conds;
    }
    let required = requirements(&conds, &outside);
    reorder_list(conds, required, roots, &outside, &rank, &multi, &mut 0)
}

/// Puts each conjunctive test of a positive condition with its equality test first, the
/// others keeping their order: a learned rule's tests read so in 9.6
/// (`^num3 { <n1> << 2 3 >> }`), where a rule written by hand, reordered, has its equality
/// test last. (Negations keep the tests the learned rule was built with.)
pub fn equality_first(conds: &mut [Condition]) {
    fn field(t: &mut Test) {
        if let Test::Conjunction(ts) = t {
            if let Some(k) = ts.iter().position(|x| matches!(x, Test::Equal(_))) {
                ts[..=k].rotate_right(1);
            }
        }
    }
    for c in conds {
        match c {
            Condition::Positive(p) => {
                field(&mut p.id);
                field(&mut p.attr);
                field(&mut p.value);
            }
            Condition::Negative(_) => {}
            Condition::Ncc(cs) => equality_first(cs),
        }
    }
}

/// Interns the name and the constants of a rule in the order 9.6's parser creates them: the
/// name, then the conditions, then the actions, left to right. Each string constant then
/// shares the symbol table's copy of its text, so that a loaded rule holds no text of its
/// own for the attribute names and values every rule repeats.
pub fn intern_in_text_order(p: &mut crate::production::Production, syms: &mut Symbols) {
    use crate::production::{Action, FuncCall, RhsTerm};
    fn constant(c: &mut Constant, syms: &mut Symbols) {
        let s = syms.constant(c);
        if let (Constant::Str(text), SymData::Str(shared)) = (&mut *c, syms.get(s)) {
            *text = shared.clone();
        }
    }
    fn test(t: &mut Test, syms: &mut Symbols) {
        match t {
            Test::Equal(Term::Const(c)) => constant(c, syms),
            Test::Relational(rt) => {
                if let Term::Const(c) = &mut rt.term {
                    constant(c, syms);
                }
            }
            Test::Disjunction(cs) => cs.iter_mut().for_each(|c| constant(c, syms)),
            Test::Conjunction(ts) => ts.iter_mut().for_each(|t| test(t, syms)),
            _ => {}
        }
    }
    fn cond(c: &mut Condition, syms: &mut Symbols) {
        match c {
            Condition::Positive(p) | Condition::Negative(p) => {
                for t in [&mut p.id, &mut p.attr, &mut p.value] {
                    test(t, syms);
                }
            }
            Condition::Ncc(inner) => inner.iter_mut().for_each(|c| cond(c, syms)),
        }
    }
    fn rhs(t: &mut RhsTerm, syms: &mut Symbols) {
        match t {
            RhsTerm::Const(c) => constant(c, syms),
            RhsTerm::Call(f) => call(f, syms),
            RhsTerm::Var(_) => {}
        }
    }
    fn call(f: &mut FuncCall, syms: &mut Symbols) {
        syms.str(&f.name);
        f.args.iter_mut().for_each(|a| rhs(a, syms));
    }
    // The rule keeps the symbol's text as its name rather than a copy.
    let name = syms.str(&p.name);
    if let SymData::Str(shared) = syms.get(name) {
        p.name = shared.clone();
    }
    std::sync::Arc::make_mut(&mut p.conditions)
        .iter_mut()
        .for_each(|c| cond(c, syms));
    for a in &mut p.actions {
        match a {
            Action::Make(m) => {
                for t in [&mut m.id, &mut m.attr, &mut m.value] {
                    rhs(t, syms);
                }
                if let Some(r) = &mut m.referent {
                    rhs(r, syms);
                }
            }
            Action::Call(f) => call(f, syms),
        }
    }
}

// ------------------------------------------------------------------ variables

fn equality_term(t: &Test) -> Option<&Term> {
    match t {
        Test::Equal(term) => Some(term),
        Test::Conjunction(ts) => ts.iter().find_map(equality_term),
        _ => None,
    }
}

fn equality_var(t: &Test) -> Option<&str> {
    match equality_term(t) {
        Some(Term::Var(v)) => Some(v),
        _ => None,
    }
}

/// Variables a positive condition binds (its equality tests).
fn bound_by(c: &Condition) -> Vec<&str> {
    match c {
        Condition::Positive(p) => [&p.id, &p.attr, &p.value]
            .into_iter()
            .filter_map(|t| equality_var(t))
            .collect(),
        _ => Vec::new(),
    }
}

/// Every variable a condition tests (equality and relational referents), NCCs included.
fn tested_vars<'a>(c: &'a Condition, out: &mut Vec<&'a str>) {
    fn test<'a>(t: &'a Test, out: &mut Vec<&'a str>) {
        match t {
            Test::Equal(Term::Var(v)) => out.push(v),
            Test::Relational(rt) => {
                if let Term::Var(v) = &rt.term {
                    out.push(v);
                }
            }
            Test::Conjunction(ts) => ts.iter().for_each(|t| test(t, out)),
            _ => {}
        }
    }
    match c {
        Condition::Positive(p) | Condition::Negative(p) => {
            for t in [&p.id, &p.attr, &p.value] {
                test(t, out);
            }
        }
        Condition::Ncc(inner) => inner.iter().for_each(|c| tested_vars(c, out)),
    }
}

/// Ids of positive conditions that no positive condition binds as a value, and that are
/// not bound outside, in order of first appearance.
fn root_variables(conds: &[Condition], outside: &Bound) -> Vec<String> {
    let mut values = crate::production::Names::for_at_most(conds.len());
    for c in conds {
        if let Condition::Positive(p) = c {
            if let Some(v) = equality_var(&p.value) {
                values.insert(v);
            }
        }
    }
    let mut roots: Vec<String> = Vec::new();
    for c in conds {
        if let Condition::Positive(p) = c {
            if let Some(v) = equality_var(&p.id) {
                if !values.contains(v) && !outside.contains(v) && !roots.iter().any(|r| r == v) {
                    roots.push(v.to_string());
                }
            }
        }
    }
    roots
}

/// A `state`/`impasse` test stays only on conditions whose id is a root (9.6 keeps the goal
/// test of chunks and rules on their root states only).
fn drop_goal_tests_of_non_roots(conds: &mut [Condition], roots: &[String]) {
    for c in conds.iter_mut() {
        if let Condition::Positive(p) = c {
            if p.goal != Head::None
                && !equality_var(&p.id).is_some_and(|v| roots.iter().any(|r| r == v))
            {
                p.goal = Head::None;
            }
        }
    }
}

/// For each negation or NCC of a list: the variables it tests that positive conditions of
/// this list or of an enclosing one bind. Indexed like the list; NCCs carry their inner
/// lists' requirements along.
#[derive(Debug, Clone, Default)]
pub(super) struct Required {
    vars: Vec<Vec<String>>,
    inner: Vec<Option<Required>>,
}

fn requirements(conds: &[Condition], outside: &Bound) -> Required {
    if conds.iter().all(|c| matches!(c, Condition::Positive(_))) {
        // Nothing to require: the common case, without building the bound set (empty
        // lists stand for "nothing" at every index).
        return Required::default();
    }
    let mut bound = outside.clone();
    for c in conds {
        bound.extend(bound_by(c).into_iter().map(str::to_string));
    }
    let mut req = Required::default();
    for c in conds {
        let mut vars = Vec::new();
        if !matches!(c, Condition::Positive(_)) {
            let mut tested = Vec::new();
            tested_vars(c, &mut tested);
            for v in tested {
                if bound.contains(v) && !vars.iter().any(|x: &String| x == v) {
                    vars.push(v.to_string());
                }
            }
        }
        req.vars.push(vars);
        req.inner.push(match c {
            Condition::Ncc(inner) => Some(requirements(inner, &bound)),
            _ => None,
        });
    }
    req
}

// ------------------------------------------------------------------ one list

fn reorder_list(
    mut conds: Vec<Condition>,
    required: Required,
    roots: Vec<String>,
    outside: &Bound,
    rank: &dyn Fn(&Constant) -> u64,
    multi: &dyn Fn(&Constant) -> u64,
    dummies: &mut usize,
) -> Vec<Condition> {
    let saved = set_aside::simplify(&mut conds, dummies);
    let Required { vars, mut inner } = required;
    // The order first, with the conditions borrowed; an NCC keeps what was bound when it
    // was placed, to order its own conditions with.
    let mut order = Vec::with_capacity(conds.len());
    let mut bound_at_ncc = Vec::new();
    {
        let mut chooser = Chooser::new(&conds, &vars, outside, &roots, rank, multi);
        while let Some(i) = chooser.next() {
            if matches!(conds[i], Condition::Ncc(_)) {
                bound_at_ncc.push(chooser.bound_names(outside));
            }
            chooser.bind(i);
            order.push(i);
        }
    }
    // Exactly sized: the list is kept for the rule's lifetime.
    let mut out = Vec::with_capacity(conds.len());
    let mut bound_at_ncc = bound_at_ncc.into_iter();
    for i in order {
        // (An empty NCC is a placeholder that costs no allocation.)
        let cond = match std::mem::replace(&mut conds[i], Condition::Ncc(Vec::new())) {
            // An NCC's own conditions are ordered when it is placed, with what is bound
            // by then counting as bound outside them.
            Condition::Ncc(mut inner_conds) => {
                let bound = bound_at_ncc.next().unwrap_or_default();
                let inner_roots = root_variables(&inner_conds, &bound);
                // As at the top level, only root ids keep a `state` test: one bound outside
                // the NCC is already tested there (9.6 prints `-{ (<s> ^operator ...) }`).
                drop_goal_tests_of_non_roots(&mut inner_conds, &inner_roots);
                Condition::Ncc(reorder_list(
                    inner_conds,
                    inner.get_mut(i).and_then(Option::take).unwrap_or_default(),
                    inner_roots,
                    &bound,
                    rank,
                    multi,
                    dummies,
                ))
            }
            other => other,
        };
        out.push(cond);
    }
    set_aside::restore(&mut out, outside, saved);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ast::Relation;
    use crate::production::Cond;

    fn var(v: &str) -> Test {
        Test::Equal(Term::Var(v.into()))
    }
    fn attr(a: &str) -> Test {
        Test::Equal(Term::Const(Constant::Str(a.into())))
    }
    fn pos(id: &str, a: Test, v: Test, goal: Head) -> Condition {
        Condition::Positive(Cond {
            id: var(id),
            attr: a,
            value: v,
            acceptable: false,
            goal,
            span: Default::default(),
        })
    }

    #[test]
    fn a_bare_relational_test_moves_to_where_its_referent_is_bound() {
        let mut syms = Symbols::new();
        syms.str("a");
        let conds = vec![
            pos("<s>", var("<at>"), var("<z>"), Head::State),
            pos(
                "<s>",
                attr("a"),
                Test::relational(Relation::Lt, Term::Var("<z>".into())),
                Head::None,
            ),
        ];
        let out = reorder(&conds, &syms);
        let text: Vec<String> = out.iter().map(crate::printer::cond_text).collect();
        assert_eq!(
            text,
            [
                "(state <s> ^a <#dummy 1>)",
                "(<s> ^<at> { > <#dummy 1> <z> })"
            ]
        );
    }
}
