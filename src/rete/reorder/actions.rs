//! The order of a rule's actions, which 9.6 settles as it loads the rule: an action can run
//! once the variables of its identifier (and of any function call in it) are bound, by the
//! conditions or by an action before it. Again and again the first such action in the list
//! is taken and its variables become bound, so an action that makes an identifier comes
//! before the actions on that identifier, and those come right after it.
//!
//! The order decides which of a firing's new identifiers is made first (their numbers), the
//! order its preferences are asserted in (their WMEs' timetags), the order of a result's
//! preferences in what a substate learns, and how `print` lists the actions (checked on
//! soar-sml 9.6.5: test agent `action-order`).

use crate::production::{Action, Condition, RhsTerm};
use rustc_hash::FxHashSet;

/// Puts `actions` in the order 9.6 runs them, given the rule's `conditions` (the variables
/// their positive conditions bind start bound). Actions that never become runnable (an
/// identifier no condition or action binds) follow in their own order.
pub fn reorder_actions(conditions: &[Condition], actions: &mut Box<[Action]>) {
    if actions.len() < 2 {
        return;
    }
    let bound: FxHashSet<&str> = conditions
        .iter()
        .flat_map(|c| super::bound_by(c))
        .collect();
    let mut remaining: Vec<Option<Action>> = std::mem::take(actions)
        .into_vec()
        .into_iter()
        .map(Some)
        .collect();
    let mut ordered = Vec::with_capacity(remaining.len());
    // The variables each taken action binds, owned: the actions move as they are taken.
    let mut newly_bound: Vec<arcstr::ArcStr> = Vec::new();
    let mut taken = 0;
    while taken < remaining.len() {
        let next = remaining.iter().position(|a| {
            a.as_ref()
                .is_some_and(|a| runnable(a, &bound, &newly_bound))
        });
        let Some(i) = next else {
            break;
        };
        let Some(action) = remaining[i].take() else {
            break;
        };
        for_each_var(&action, &mut |v| {
            if !bound.contains(v.as_str()) && !newly_bound.iter().any(|n| n == v) {
                newly_bound.push(v.clone());
            }
        });
        ordered.push(action);
        taken += 1;
    }
    ordered.extend(remaining.into_iter().flatten());
    *actions = ordered.into_boxed_slice();
}

/// Whether every variable `action` needs bound is: its identifier's, and those of any
/// function call in it (a plain variable elsewhere makes a new identifier).
fn runnable(action: &Action, bound: &FxHashSet<&str>, newly_bound: &[arcstr::ArcStr]) -> bool {
    let is_bound = |v: &arcstr::ArcStr| bound.contains(v.as_str()) || newly_bound.contains(v);
    let all_bound = |t: &RhsTerm| {
        let mut ok = true;
        term_vars(t, &mut |v| ok &= is_bound(v));
        ok
    };
    match action {
        Action::Make(m) => {
            let calls = [Some(&m.attr), Some(&m.value), m.referent.as_ref()];
            all_bound(&m.id)
                && calls
                    .into_iter()
                    .flatten()
                    .all(|t| !matches!(t, RhsTerm::Call(_)) || all_bound(t))
        }
        Action::Call(f) => f.args.iter().all(all_bound),
    }
}

fn for_each_var(action: &Action, f: &mut impl FnMut(&arcstr::ArcStr)) {
    match action {
        Action::Make(m) => {
            for t in [&m.id, &m.attr, &m.value].into_iter().chain(m.referent.as_ref()) {
                term_vars(t, f);
            }
        }
        Action::Call(c) => c.args.iter().for_each(|t| term_vars(t, f)),
    }
}

fn term_vars(t: &RhsTerm, f: &mut impl FnMut(&arcstr::ArcStr)) {
    match t {
        RhsTerm::Var(v) => f(v),
        RhsTerm::Call(c) => c.args.iter().for_each(|a| term_vars(a, f)),
        RhsTerm::Const(_) => {}
    }
}
