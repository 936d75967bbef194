//! Variable names kept by loaded rules: each rule's bindings (where the network binds each
//! of its variables) and the variables of its conditions share one copy of each name, since
//! thousands of rules use the same few.

use super::tests::Field;
use super::Rete;
use crate::production::{Action, Condition, RhsTerm, Term, Test};
use rustc_hash::FxHashMap;
use std::sync::Arc;

/// Variables and where they are bound, sorted by name: kept for every rule, where a hash
/// map would cost several times the memory. The names are shared among all rules
/// ([`VarNames`]): thousands of rules use the same few; and so are whole lists
/// ([`BindingLists`]): rules of one shape bind the same variables in the same places.
#[derive(Debug, Clone)]
pub struct VarBindings(Arc<[Binding]>);

impl Default for VarBindings {
    fn default() -> Self {
        VarBindings(Arc::new([]))
    }
}

/// A variable's name and where it is bound.
type Binding = (arcstr::ArcStr, (u32, Field));

impl VarBindings {
    pub fn get(&self, var: &str) -> Option<&(u32, Field)> {
        self.0
            .binary_search_by(|(k, _)| (**k).cmp(var))
            .ok()
            .map(|i| &self.0[i].1)
    }

    /// The position of a variable among the bindings (name order).
    pub fn index_of(&self, var: &str) -> Option<usize> {
        self.0.binary_search_by(|(k, _)| (**k).cmp(var)).ok()
    }

    /// Each variable (its shared name) with where it is bound, in name order.
    pub fn iter(&self) -> impl Iterator<Item = (&arcstr::ArcStr, (u32, Field))> {
        self.0.iter().map(|(k, b)| (k, *b))
    }


    pub(crate) fn len(&self) -> usize {
        self.0.len()
    }

    pub(super) fn new(
        map: FxHashMap<&str, (u32, Field)>,
        names: &mut VarNames,
        lists: &mut BindingLists,
    ) -> Self {
        let mut v: Vec<_> = map.into_iter().collect();
        v.sort_unstable_by(|a, b| a.0.cmp(b.0));
        let list: Vec<Binding> = v.into_iter().map(|(k, b)| (names.get(k), b)).collect();
        if let Some(shared) = lists.0.get(list.as_slice()) {
            return VarBindings(shared.clone());
        }
        let shared: Arc<[Binding]> = list.into();
        lists.0.insert(shared.clone());
        VarBindings(shared)
    }
}

/// The binding lists of the rules in the network, each stored once (see [`VarBindings`]).
#[derive(Debug, Default)]
pub(crate) struct BindingLists(rustc_hash::FxHashSet<Arc<[Binding]>>);

/// The variable names of the rules in the network, each stored once.
#[derive(Debug, Default)]
pub(crate) struct VarNames(rustc_hash::FxHashSet<arcstr::ArcStr>);

impl VarNames {
    pub(super) fn get(&mut self, name: &str) -> arcstr::ArcStr {
        if let Some(n) = self.0.get(name) {
            return n.clone();
        }
        let n: arcstr::ArcStr = name.into();
        self.0.insert(n.clone());
        n
    }
}

impl Rete {
    /// The variable names loaded rules use, in name order (`debug internal-symbols`).
    pub(crate) fn variable_names(&self) -> Vec<arcstr::ArcStr> {
        let mut names: Vec<_> = self.var_names.0.iter().cloned().collect();
        names.sort_unstable();
        names
    }

    /// Points every variable of these conditions at the network's copy of its name, so that
    /// a loaded rule keeps no name of its own.
    pub fn share_var_names(&mut self, conds: &mut [Condition]) {
        fn test(t: &mut Test, names: &mut VarNames) {
            match t {
                Test::Equal(Term::Var(v)) => *v = names.get(v),
                Test::Relational(rt) => {
                    if let Term::Var(v) = &mut rt.term {
                        *v = names.get(v);
                    }
                }
                Test::Conjunction(ts) => ts.iter_mut().for_each(|t| test(t, names)),
                Test::Equal(Term::Const(_)) | Test::Disjunction(_) => {}
            }
        }
        for c in conds {
            match c {
                Condition::Positive(c) | Condition::Negative(c) => {
                    for t in [&mut c.id, &mut c.attr, &mut c.value] {
                        test(t, &mut self.var_names);
                    }
                }
                Condition::Ncc(inner) => self.share_var_names(inner),
            }
        }
    }

    /// Points every variable of these actions at a shared copy of its name: the
    /// conditions' when they bind it.
    pub fn share_action_var_names(&mut self, actions: &mut [Action]) {
        fn term(t: &mut RhsTerm, rete: &mut Rete) {
            match t {
                RhsTerm::Var(v) => {
                    *v = match rete.var_names.0.get(v.as_str()) {
                        Some(n) => n.clone(),
                        None => rete.action_var_names.get(v),
                    }
                }
                RhsTerm::Call(f) => f.args.iter_mut().for_each(|a| term(a, rete)),
                RhsTerm::Const(_) => {}
            }
        }
        for a in actions {
            match a {
                Action::Make(m) => {
                    for t in [&mut m.id, &mut m.attr, &mut m.value] {
                        term(t, self);
                    }
                    if let Some(r) = &mut m.referent {
                        term(r, self);
                    }
                }
                Action::Call(f) => f.args.iter_mut().for_each(|x| term(x, self)),
            }
        }
    }
}
