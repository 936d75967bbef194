//! A learned rule's variable names in 9.6's order. A chunk's variables are numbered per
//! letter in the order its conditions are joined (after reordering), each named where its
//! equality test first comes: after the attribute it is the value of (`^to <t1>`), or,
//! first met as an identifier, after its own letter (`(<s1> ^name ...)`). Variables of
//! negations and of the actions alone follow, in the order the rule was built with them.
//! (Checked on soar-sml 9.6.5: a value first tested under `^to` in join order is `<t1>`
//! even where the dependency analysis met it under `^dead-end` first.)

use crate::ast::Constant;
use crate::production::{Action, Condition, RhsTerm, Term, Test};
use rustc_hash::FxHashMap;

/// Renames the variables of `conds` and `actions` (a learned rule before reordering).
/// `ordered`: the same conditions in join order; `own`: the own letter of each variable
/// that stands for an identifier; `created`: every variable in the order it was made.
pub(super) fn rename_in_join_order(
    conds: &mut [Condition],
    actions: &mut [Action],
    ordered: &[Condition],
    own: &FxHashMap<String, char>,
    created: &[String],
) {
    let mut names = Names::default();
    for c in ordered {
        let Condition::Positive(x) = c else { continue };
        let attr_letter = match &x.attr {
            Test::Equal(Term::Const(Constant::Str(a))) => a.chars().next(),
            _ => None,
        }
        .filter(char::is_ascii_alphabetic)
        .map(|l| l.to_ascii_lowercase());
        for (t, under) in [(&x.id, None), (&x.attr, None), (&x.value, attr_letter)] {
            if let Some(v) = equality_var(t) {
                let letter = under.or_else(|| own.get(v).copied()).unwrap_or_else(|| letter_of(v));
                names.name(v, letter);
            }
        }
    }
    for v in created {
        names.name(v, letter_of(v));
    }
    for c in conds.iter_mut() {
        rename_condition(c, &names.map);
    }
    for a in actions.iter_mut() {
        match a {
            Action::Make(m) => {
                for t in [&mut m.id, &mut m.attr, &mut m.value] {
                    rename_rhs(t, &names.map);
                }
                if let Some(r) = m.referent.as_mut() {
                    rename_rhs(r, &names.map);
                }
            }
            Action::Call(f) => f.args.iter_mut().for_each(|t| rename_rhs(t, &names.map)),
        }
    }
}

/// New names, numbered per letter.
#[derive(Default)]
struct Names {
    map: FxHashMap<String, arcstr::ArcStr>,
    counters: FxHashMap<char, u32>,
}

impl Names {
    fn name(&mut self, old: &str, letter: char) {
        if self.map.contains_key(old) {
            return;
        }
        let n = self.counters.entry(letter).or_insert(0);
        *n += 1;
        self.map
            .insert(old.to_string(), format!("<{letter}{n}>").into());
    }
}

/// The letter a variable was named by (`<t1>`: `t`).
fn letter_of(var: &str) -> char {
    var.chars().nth(1).unwrap_or('v')
}

/// The variable of a field's equality test, if it has one.
fn equality_var(t: &Test) -> Option<&str> {
    match t {
        Test::Equal(Term::Var(v)) => Some(v),
        Test::Conjunction(ts) => ts.iter().find_map(|x| match x {
            Test::Equal(Term::Var(v)) => Some(&**v),
            _ => None,
        }),
        _ => None,
    }
}

fn rename_condition(c: &mut Condition, map: &FxHashMap<String, arcstr::ArcStr>) {
    match c {
        Condition::Positive(x) | Condition::Negative(x) => {
            for t in [&mut x.id, &mut x.attr, &mut x.value] {
                rename_test(t, map);
            }
        }
        Condition::Ncc(inner) => inner.iter_mut().for_each(|c| rename_condition(c, map)),
    }
}

fn rename_test(t: &mut Test, map: &FxHashMap<String, arcstr::ArcStr>) {
    match t {
        Test::Equal(term) => rename_term(term, map),
        Test::Relational(rt) => rename_term(&mut rt.term, map),
        Test::Conjunction(ts) => ts.iter_mut().for_each(|t| rename_test(t, map)),
        Test::Disjunction(_) => {}
    }
}

fn rename_term(t: &mut Term, map: &FxHashMap<String, arcstr::ArcStr>) {
    if let Term::Var(v) = t {
        if let Some(n) = map.get(&**v) {
            *v = n.clone();
        }
    }
}

fn rename_rhs(t: &mut RhsTerm, map: &FxHashMap<String, arcstr::ArcStr>) {
    match t {
        RhsTerm::Var(v) => {
            if let Some(n) = map.get(&**v) {
                *v = n.clone();
            }
        }
        RhsTerm::Call(f) => f.args.iter_mut().for_each(|t| rename_rhs(t, map)),
        RhsTerm::Const(_) => {}
    }
}
