//! The tests a join node makes (Soar manual, ch. 3, "Predicates for values"): equality and
//! the relational tests between a field of the new WME and a bound variable or a constant,
//! disjunctions, and goal/impasse tests.

use crate::ast::Relation;
use crate::symbols::{Sym, Symbols};
use std::cmp::Ordering;

/// A field of a WME.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Field {
    Id,
    Attr,
    Value,
}

/// What a field is compared with: a field of the WME at token depth `depth`, or a constant.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Operand {
    Bound { depth: u32, field: Field },
    Const(Sym),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Op {
    Eq,
    Rel(Relation),
}

#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum JoinTest {
    /// `field op operand`.
    Compare {
        field: Field,
        op: Op,
        operand: Operand,
    },
    /// `<< a b c >>` on a field: membership by identity.
    Disjunction { field: Field, items: Vec<Sym> },
    /// `(state <s> ...)`: the id is a goal in the stack.
    IsGoal,
    /// `(impasse <i> ...)`.
    IsImpasse,
}

/// `a op b` with Soar's semantics.
pub fn relation_holds(symbols: &Symbols, op: Op, a: Sym, b: Sym) -> bool {
    match op {
        Op::Eq => a == b,
        Op::Rel(Relation::Ne) => a != b,
        Op::Rel(Relation::SameType) => symbols.same_type(a, b),
        Op::Rel(r) => {
            let ord = symbols.compare(a, b);
            match r {
                Relation::Lt => ord == Ordering::Less,
                Relation::Le => ord != Ordering::Greater,
                Relation::Gt => ord == Ordering::Greater,
                Relation::Ge => ord != Ordering::Less,
                // Handled above.
                Relation::Ne | Relation::SameType => false,
            }
        }
    }
}
