//! Steps 2 and 4 of the reorderer (see `mod.rs`): setting aside every test of a positive
//! condition but its equality tests, and putting them back on the first condition of the
//! new order that can test them.

use super::{equality_term, equality_var, Bound};
use crate::ast::{Head, Relation};
use crate::production::{Condition, Term, Test};
use rustc_hash::FxHashMap;

/// The tests set aside from one condition list, in 9.6's list order (each new one goes on
/// the front), found by the term they are indexed by and by their referent.
#[derive(Debug, Default)]
pub(super) struct SetAside {
    tests: Vec<Option<(Term, Test)>>,
    /// `state`/`impasse` tests by the id variable they were on: restored to the first
    /// condition on that id (copies are one test, as 9.6 adds a test only once).
    /// (A list: a rule tests one or two states.)
    goals: Vec<(String, Head)>,
    by_term: FxHashMap<String, Vec<usize>>,
}

fn key(t: &Term) -> String {
    match t {
        Term::Var(v) => v.to_string(),
        Term::Const(c) => format!("#{c:?}"),
    }
}

impl SetAside {
    fn push(&mut self, index: Term, test: Test) {
        self.tests.push(Some((index, test)));
    }

    /// Turns push order into 9.6's order (newest first) and indexes the tests.
    fn finish(&mut self) {
        self.tests.reverse();
        for (slot, t) in self.tests.iter().enumerate() {
            let Some((index, test)) = t else { continue };
            self.by_term.entry(key(index)).or_default().push(slot);
            if let Test::Relational(rt) = test {
                if rt.term != *index {
                    self.by_term.entry(key(&rt.term)).or_default().push(slot);
                }
            }
        }
    }
}

/// Splits a field's test into its equality test and the tests set aside. A field with no
/// equality test (compile always gives one; generated rules may not) gets a dummy variable,
/// as 9.6 does, so that its tests can move to where their referents are bound.
fn simplify_field(field: &mut Test, saved: &mut SetAside, dummies: &mut usize) {
    if matches!(field, Test::Equal(_)) {
        return;
    }
    let parts: Vec<Test> = match std::mem::replace(field, Test::placeholder()) {
        Test::Conjunction(parts) => *parts,
        other => vec![other],
    };
    let eq = parts
        .iter()
        .find_map(|p| match p {
            Test::Equal(term) => Some(term.clone()),
            _ => None,
        })
        .unwrap_or_else(|| {
            *dummies += 1;
            // Not a name a rule can write: it cannot clash with the rule's variables.
            Term::Var(format!("<#dummy {dummies}>").into())
        });
    for p in parts {
        if !matches!(p, Test::Equal(_)) {
            saved.push(eq.clone(), p);
        }
    }
    *field = Test::Equal(eq);
}

/// Leaves each positive condition with its equality tests only.
pub(super) fn simplify(conds: &mut [Condition], dummies: &mut usize) -> SetAside {
    let mut saved = SetAside::default();
    for c in conds.iter_mut() {
        if let Condition::Positive(p) = c {
            simplify_field(&mut p.id, &mut saved, dummies);
            if p.goal != Head::None {
                if let Some(v) = equality_var(&p.id) {
                    if !saved.goals.iter().any(|(g, _)| g == v) {
                        saved.goals.push((v.to_string(), p.goal));
                    }
                }
                p.goal = Head::None;
            }
            simplify_field(&mut p.attr, &mut saved, dummies);
            simplify_field(&mut p.value, &mut saved, dummies);
        }
    }
    saved.finish();
    saved
}

fn reversed(r: Relation) -> Relation {
    match r {
        Relation::Lt => Relation::Gt,
        Relation::Gt => Relation::Lt,
        Relation::Le => Relation::Ge,
        Relation::Ge => Relation::Le,
        other => other,
    }
}

fn is_bound(t: &Term, bound: &Bound) -> bool {
    match t {
        Term::Const(_) => true,
        Term::Var(v) => bound.contains(&**v),
    }
}

/// Adds a restored test to a field: at the front of its conjunction, unless it is there.
fn add_test(field: &mut Test, t: Test) {
    match field {
        Test::Conjunction(parts) => {
            if !parts.contains(&t) {
                parts.insert(0, t);
            }
        }
        other => {
            if *other != t {
                let eq = std::mem::replace(other, Test::placeholder());
                *other = Test::conjunction(vec![t, eq]);
            }
        }
    }
}

/// Restores to one field what can go there, in list order: tests indexed by the field's
/// equality term whose referent is bound, and relational tests whose referent is this term
/// and whose own term is bound, turned round.
fn restore_field(field: &mut Test, bound: &Bound, saved: &mut SetAside) {
    let Some(eq) = equality_term(field).cloned() else {
        return;
    };
    let Some(slots) = saved.by_term.get(&key(&eq)) else {
        return;
    };
    let mut slots = slots.clone();
    slots.sort_unstable();
    slots.dedup();
    for slot in slots {
        let Some((index, test)) = &saved.tests[slot] else {
            continue;
        };
        let restored = match test {
            Test::Relational(rt) => {
                let referent = &rt.term;
                if *index == eq {
                    (is_bound(referent, bound) || *referent == *index)
                        .then(|| Test::relational(rt.op, referent.clone()))
                } else if *referent == eq {
                    (is_bound(index, bound) || *index == *referent)
                        .then(|| Test::relational(reversed(rt.op), index.clone()))
                } else {
                    None
                }
            }
            other => (*index == eq).then(|| other.clone()),
        };
        if let Some(t) = restored {
            add_test(field, t);
            saved.tests[slot] = None;
        }
    }
}

/// Puts the set-aside tests back on the first reordered condition that can test them;
/// tests whose referent is never bound are dropped (compile has already warned).
pub(super) fn restore(conds: &mut [Condition], outside: &Bound, mut saved: SetAside) {
    if saved.tests.is_empty() && saved.goals.is_empty() {
        return;
    }
    let only_goals = saved.tests.is_empty();
    let mut bound = outside.clone();
    for c in conds.iter_mut() {
        let Condition::Positive(p) = c else { continue };
        if let Some(v) = equality_var(&p.id) {
            if let Some(k) = saved.goals.iter().position(|(g, _)| g == v) {
                p.goal = saved.goals.swap_remove(k).1;
            }
        }
        if only_goals {
            continue;
        }
        for field in [&mut p.id, &mut p.attr, &mut p.value] {
            restore_field(field, &bound, &mut saved);
            if let Some(v) = equality_var(field) {
                bound.insert(v.to_string());
            }
        }
    }
}
