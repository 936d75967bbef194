//! The syntax tree of one `sp` production, as written (Soar manual, ch. 3, "Production
//! Memory"). Dot paths and structured values are kept as written here; `production::compile`
//! flattens them.

use crate::source::Span;

#[derive(Debug, Clone, PartialEq)]
pub struct Production {
    pub name: String,
    pub name_span: Span,
    pub doc: Option<String>,
    pub flags: Vec<(String, Span)>,
    pub conditions: Vec<Condition>,
    pub arrow: Span,
    pub actions: Vec<Action>,
    pub span: Span,
}

#[derive(Debug, Clone, PartialEq)]
pub enum Condition {
    Positive(CondForOneId),
    Negative(CondForOneId),
    /// `-{ ... }`: true iff the conjunction has no match.
    Ncc(Vec<Condition>, Span),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Head {
    None,
    State,
    Impasse,
}

#[derive(Debug, Clone, PartialEq)]
pub struct CondForOneId {
    pub head: Head,
    pub id_test: Option<Test>,
    pub attr_value_tests: Vec<AttrValueTests>,
    pub span: Span,
}

/// `[-]^a.b.c v1 v2 ...`
#[derive(Debug, Clone, PartialEq)]
pub struct AttrValueTests {
    pub negated: bool,
    pub path: Vec<Test>,
    pub values: Vec<ValueTest>,
    pub span: Span,
}

#[derive(Debug, Clone, PartialEq)]
pub enum ValueTest {
    Test {
        test: Test,
        acceptable: bool,
    },
    /// `^Start (^X <x> ^Y <y>)`: a condition on a new placeholder id.
    Structured {
        tests: Vec<AttrValueTests>,
        acceptable: bool,
        span: Span,
    },
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Relation {
    Ne,
    Lt,
    Le,
    Gt,
    Ge,
    SameType,
}

impl Relation {
    pub fn text(self) -> &'static str {
        match self {
            Relation::Ne => "<>",
            Relation::Lt => "<",
            Relation::Le => "<=",
            Relation::Gt => ">",
            Relation::Ge => ">=",
            Relation::SameType => "<=>",
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
pub enum Test {
    /// A bare atom, or `= atom`.
    Equal(Atom, Span),
    Relational(Relation, Atom, Span),
    Disjunction(Vec<Constant>, Span),
    Conjunction(Vec<Test>, Span),
}

impl Test {
    pub fn span(&self) -> Span {
        match self {
            Test::Equal(_, s)
            | Test::Relational(_, _, s)
            | Test::Disjunction(_, s)
            | Test::Conjunction(_, s) => *s,
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
pub enum Atom {
    Var(String),
    Const(Constant),
}

/// A constant symbol. Identifier-shaped lexemes are already upper-cased strings here.
/// (Shared text: a loaded rule's strings share the symbol table's copy, see
/// `rete::reorder::intern_in_text_order`; 100,000 rules repeat their attribute names a
/// million times.)
#[derive(Debug, Clone, PartialEq)]
pub enum Constant {
    Str(arcstr::ArcStr),
    Int(i64),
    Float(f64),
}

#[derive(Debug, Clone, PartialEq)]
pub enum Action {
    Make {
        id: RhsValue,
        attrs: Vec<AttrMake>,
        span: Span,
    },
    Call(FuncCall),
}

#[derive(Debug, Clone, PartialEq)]
pub struct AttrMake {
    pub path: Vec<RhsValue>,
    pub values: Vec<ValueMake>,
    pub span: Span,
}

#[derive(Debug, Clone, PartialEq)]
pub struct ValueMake {
    pub value: RhsValue,
    pub prefs: Vec<Pref>,
}

#[derive(Debug, Clone, PartialEq)]
pub enum RhsValue {
    Var(String, Span),
    Const(Constant, Span),
    /// (Boxed: inline, a call would triple the size of every value.)
    Call(Box<FuncCall>),
}


#[derive(Debug, Clone, PartialEq)]
pub struct FuncCall {
    pub name: String,
    pub name_span: Span,
    pub args: Vec<RhsValue>,
    pub span: Span,
}

/// Preferences after a value (Soar manual, ch. 3, "The syntax of preferences").
#[derive(Debug, Clone, PartialEq)]
pub enum Pref {
    Acceptable,
    Reject,
    Require,
    Prohibit,
    Best,
    Worst,
    Indifferent,
    Better(RhsValue),
    Worse(RhsValue),
    BinaryIndifferent(RhsValue),
    /// `= <number>`: numeric indifferent.
    Numeric(RhsValue),
}

/// One item of a value list before preferences are attached to values (see `grammar/`).
#[derive(Debug, Clone, PartialEq)]
pub enum ValueItem {
    Value(RhsValue),
    Plus(Span),
    Minus(Span),
    Bang(Span),
    Tilde(Span),
    Gt(Span),
    Lt(Span),
    Eq(Span),
    Comma(Span),
}
