//! A justification made with learning off, kept as symbols until something shows it.
//! Such a justification tests the matched symbols themselves (no variables, no extra
//! tests) and is shown only by `print` and the retraction trace, while a run makes one for
//! nearly every result: writing each out as rule text at once would cost more than the
//! backtrace that found it. The text, when asked for, is the one the rule builder writes.
//! (A justification with superstate negations is written out at once.)

use crate::ast::{Constant, Head};
use crate::production::{
    Action, Cond, Condition, Flags, Make, PrefKind, Production, RhsTerm, Term, Test,
};
use crate::source::PackedSpan;
use crate::symbols::{Sym, SymData, Symbols};
use crate::wm::Wme;
use std::sync::Arc;

/// The parts of a justification, as the builder found them.
#[derive(Debug)]
pub(crate) struct Sketch {
    pub name: String,
    /// Each condition's WME, whether it marks its identifier as a state (the first test of
    /// each state), and the span of the rule condition it came from; in the rule's order.
    pub conditions: Vec<(Wme, bool, PackedSpan)>,
    /// Each result: its preference kind, id, attribute, value and referent, and the span of
    /// the action that made it.
    pub actions: Vec<(PrefKind, [Sym; 3], Option<Sym>, PackedSpan)>,
}

impl Sketch {
    /// The justification as a rule.
    pub fn production(&self, symbols: &Symbols) -> Production {
        let test = |s: Sym| Test::Equal(term(symbols, s));
        let conditions: Vec<Condition> = self
            .conditions
            .iter()
            .map(|&(w, state, span)| {
                Condition::Positive(Cond {
                    id: test(w.id),
                    attr: test(w.attr),
                    value: test(w.value),
                    acceptable: w.acceptable,
                    goal: if state { Head::State } else { Head::None },
                    span,
                })
            })
            .collect();
        let rhs = |s: Sym| match term(symbols, s) {
            Term::Var(v) => RhsTerm::Var(v),
            Term::Const(c) => RhsTerm::Const(c),
        };
        let actions = self
            .actions
            .iter()
            .map(|&(pref, [id, attr, value], referent, span)| {
                Action::Make(Box::new(Make {
                    id: rhs(id),
                    attr: rhs(attr),
                    value: rhs(value),
                    pref,
                    referent: referent.map(rhs),
                    span,
                }))
            })
            .collect();
        Production {
            name: self.name.as_str().into(),
            doc: None,
            flags: Flags {
                justification: true,
                ..Flags::default()
            },
            conditions: conditions.into(),
            actions,
            span: Default::default(),
        }
    }
}

/// A symbol as a justification writes it: an identifier by its bare name (`S1`), a
/// constant as itself.
fn term(symbols: &Symbols, s: Sym) -> Term {
    match symbols.get(s) {
        SymData::Id(_) => Term::Var(symbols.text(s).into()),
        SymData::Str(x) => Term::Const(Constant::Str(x.clone())),
        SymData::Int(i) => Term::Const(Constant::Int(*i)),
        SymData::Float(f) => Term::Const(Constant::Float(*f)),
    }
}

/// A justification's body: written out, or kept as its sketch.
#[derive(Debug, Clone)]
pub(crate) enum Body {
    Rule(Arc<Production>),
    Sketch(Arc<Sketch>),
}
