//! A rule's actions made ready for firing: constants interned once, each variable resolved
//! to where the match binds it (token depth and field) or to a slot for the new identifier
//! it makes, so that a firing looks nothing up by name. Built the first time a rule fires
//! and kept by rule id (ids are never reused, so an excised rule's entry is simply never
//! asked for again).

use crate::decide::procedure::PrefType;
use crate::production::{Action, Flags, PrefKind, Production, RhsTerm};
use crate::rete::tests::Field;
use crate::rete::ProdInfo;
use crate::symbols::{Sym, Symbols};

/// One RHS term.
#[derive(Debug)]
pub(crate) enum Term {
    Sym(Sym),
    /// A variable the conditions bind: the match's WME at this token depth, this field.
    Bound(u32, Field),
    /// A variable the conditions do not bind: the new identifier of slot `.0`, made at its
    /// first use in the firing.
    New(usize),
    Call(Call),
}

#[derive(Debug)]
pub(crate) struct Call {
    pub name: String,
    pub args: Vec<Term>,
}

#[derive(Debug)]
pub(crate) enum Act {
    Make {
        id: Term,
        attr: Term,
        value: Term,
        referent: Option<Term>,
        kind: PrefType,
    },
    Call(Call),
}

#[derive(Debug)]
pub(crate) struct CompiledRule {
    /// The rule's actions, in source order (indexes match `Production::actions`).
    pub actions: Vec<Act>,
    /// For each new-identifier slot: the variable's name and the letter of its identifier
    /// (the variable's first letter, `S` read as `I`; `I` when it has none).
    pub new_vars: Vec<(String, char)>,
    /// It makes an acceptable preference for `^operator` (proposals are I-supported: Soar
    /// manual, 2.7.6 "The calculation of o-support").
    pub proposes: bool,
    /// The rule's flags (declared support, its kind for tracing).
    pub flags: Flags,
    /// For each make action: the binding of its id when that is a variable the conditions
    /// bind (for the o-support test of actions on the selected operator).
    pub make_ids: Vec<Option<(u32, Field)>>,
    /// One of its positive conditions can match a `^operator` WME. Without one the rule
    /// cannot test its goal's selected operator and is I-supported, which spares the
    /// support test a walk over the match.
    pub may_test_operator: bool,
    /// Where a match's distinct condition identifiers are read (token depth and field): the
    /// first condition's, and for each later one the binding its identifier is joined on.
    /// The match goal is the lowest goal among them; most rules test a dozen conditions on
    /// a handful of identifiers. Filled in by `AgentCore::compiled_rule`.
    pub id_places: Vec<(u32, Field)>,
}

/// Whether an attribute test can pass on `operator`.
fn may_be_operator(t: &crate::production::Test) -> bool {
    use crate::ast::Constant;
    use crate::production::{Term as CondTerm, Test};
    match t {
        Test::Equal(CondTerm::Const(Constant::Str(s))) => &**s == "operator",
        Test::Equal(CondTerm::Const(_)) => false,
        Test::Disjunction(cs) => cs
            .iter()
            .any(|c| matches!(c, Constant::Str(s) if &**s == "operator")),
        Test::Conjunction(ts) => ts.iter().all(may_be_operator),
        Test::Equal(CondTerm::Var(_)) | Test::Relational(..) => true,
    }
}

pub(crate) fn pref_type(k: PrefKind) -> PrefType {
    match k {
        PrefKind::Acceptable => PrefType::Acceptable,
        PrefKind::Reject => PrefType::Reject,
        PrefKind::Require => PrefType::Require,
        PrefKind::Prohibit => PrefType::Prohibit,
        PrefKind::Best => PrefType::Best,
        PrefKind::Worst => PrefType::Worst,
        PrefKind::Indifferent => PrefType::UnaryIndifferent,
        PrefKind::Better => PrefType::Better,
        PrefKind::Worse => PrefType::Worse,
        PrefKind::BinaryIndifferent => PrefType::BinaryIndifferent,
        PrefKind::NumericIndifferent => PrefType::NumericIndifferent,
    }
}

struct Builder<'a> {
    info: &'a ProdInfo,
    symbols: &'a mut Symbols,
    new_vars: Vec<(String, char)>,
}

impl Builder<'_> {
    fn term(&mut self, t: &RhsTerm) -> Term {
        match t {
            RhsTerm::Const(c) => Term::Sym(self.symbols.constant(c)),
            RhsTerm::Var(v) => {
                if let Some(&(depth, field)) = self.info.bindings.get(v) {
                    return Term::Bound(depth, field);
                }
                if let Some(i) = self.new_vars.iter().position(|(n, _)| n == v) {
                    return Term::New(i);
                }
                let letter = v
                    .chars()
                    .nth(1)
                    .filter(|c| c.is_ascii_alphabetic())
                    .map(|c| c.to_ascii_uppercase())
                    .unwrap_or('I');
                let letter = if letter == 'S' { 'I' } else { letter };
                self.new_vars.push((v.to_string(), letter));
                Term::New(self.new_vars.len() - 1)
            }
            RhsTerm::Call(f) => Term::Call(Call {
                name: f.name.clone(),
                args: f.args.iter().map(|a| self.term(a)).collect(),
            }),
        }
    }
}

/// Compiles a rule's actions against its network bindings. Its constants were interned when
/// the rule was added (in text order), so interning them here creates nothing.
pub(crate) fn compile(prod: &Production, info: &ProdInfo, symbols: &mut Symbols) -> CompiledRule {
    let mut b = Builder {
        info,
        symbols,
        new_vars: Vec::new(),
    };
    let mut actions = Vec::with_capacity(prod.actions.len());
    let mut make_ids = Vec::new();
    let mut proposes = false;
    for a in &prod.actions {
        match a {
            Action::Call(f) => actions.push(Act::Call(Call {
                name: f.name.clone(),
                args: f.args.iter().map(|x| b.term(x)).collect(),
            })),
            Action::Make(m) => {
                proposes |= m.pref == PrefKind::Acceptable
                    && matches!(&m.attr, RhsTerm::Const(crate::ast::Constant::Str(s)) if &**s == "operator");
                make_ids.push(match &m.id {
                    RhsTerm::Var(v) => info.bindings.get(v).copied(),
                    _ => None,
                });
                // Evaluated id, attribute, value, referent: new identifiers are numbered in
                // this order of first use.
                let id = b.term(&m.id);
                let attr = b.term(&m.attr);
                let value = b.term(&m.value);
                let referent = m.referent.as_ref().map(|r| b.term(r));
                actions.push(Act::Make {
                    id,
                    attr,
                    value,
                    referent,
                    kind: pref_type(m.pref),
                });
            }
        }
    }
    let may_test_operator = prod.conditions.iter().any(|c| match c {
        crate::production::Condition::Positive(c) => may_be_operator(&c.attr),
        _ => false,
    });
    CompiledRule {
        actions,
        new_vars: b.new_vars,
        proposes,
        flags: prod.flags.clone(),
        make_ids,
        may_test_operator,
        id_places: Vec::new(),
    }
}
