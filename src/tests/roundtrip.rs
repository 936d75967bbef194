//! Round trip of productions through the printer: generated Soar source is parsed and
//! compiled (P1), printed with `production_text`, and the printed text is parsed and
//! compiled again (P2). The printer groups conditions on one identifier (as Soar's `print`
//! does), so P2 must equal P1 *regrouped*, every span ignored; after that first regrouping
//! the round trip must be exact: `text(P2) == text(P1)` and P3 == P2. The printed text and
//! the generated source must also load to the same rules through the real `sp` command
//! (`Interpreter::run_text`), which adds the command tokenizer to the path.
//!
//! The generator builds a plain-data description of a rule with proptest combinators (no
//! filtering), then renders it as text, so a failure shrinks to a small rule. Variables that
//! must be bound (relational referents, RHS ids and function arguments) are indices that are
//! resolved against the variables the conditions actually bind, which keeps every rule valid
//! (a goal test, grounded actions, only `+`/`-` on attributes other than `^operator`).
//!
//! `PROPTEST_CASES=N` changes the case count (2,000 by default). Known printer bugs are kept
//! as `#[ignore]`d tests at the end of the file.

use crate::ast::Head;
use crate::commands::Interpreter;
use crate::parser::parse_production;
use crate::printer::production_text;
use crate::production::{self, Action, CompileOutput, Condition, FuncCall, Production, RhsTerm};
use crate::rete::reorder;
use crate::source::Span;
use proptest::collection::vec;
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::{Config, TestCaseError, TestRunner};

// ------------------------------------------------------------------ the rule description

/// Variables the conditions may bind. `<s>` (index 0) is the state of the first condition;
/// `<a*1>` has the shape of a placeholder variable on purpose.
const VARS: &[&str] = &[
    "<s>", "<o>", "<x>", "<y>", "<w1>", "<th>", "<a*1>", "<v-2>", "<Big>", "<io>",
];
/// Variables that appear only on the RHS, as values: new identifiers.
const NEW_VARS: &[&str] = &["<n>", "<new>", "<m*1>"];
const FLAGS: &[&str] = &[
    ":o-support",
    ":i-support",
    ":chunk",
    ":default",
    ":template",
    ":interrupt",
    ":explain",
];
/// Generate `-(state <x> ...)`? Off until the printer keeps the goal test of a negated
/// condition (see `negated_condition_keeps_its_state_test` below).
const NEGATED_GOAL_TESTS: bool = true;
const RELATIONS: &[&str] = &["<>", "<", "<=", ">", ">=", "<=>"];
/// Symbols that lex as symbols but look odd (the printer must bar some of them).
const ODD_SYMBOLS: &[&str] = &[
    "1e3",
    "1a",
    "*",
    "a1b",
    "ab-c",
    "gp*test*1",
    "x>",
    "<x",
    "a1-",
    "z9-",
    "-a",
    "+a",
    "$",
    "%x",
    "?",
    ":",
    "/",
    "1e-3",
    "a:b",
    "_",
    "@x",
    "state",
    "impasse",
    "Start",
    "nil",
];
/// Value functions: name, exact arity (None: any), fewest arguments.
const VALUE_FUNCS: &[(&str, Option<usize>, usize)] = &[
    ("+", None, 1),
    ("-", None, 1),
    ("*", None, 1),
    ("/", None, 1),
    ("min", None, 1),
    ("max", None, 1),
    ("concat", None, 1),
    ("int", Some(1), 1),
    ("float", Some(1), 1),
    ("abs", Some(1), 1),
    ("sqrt", Some(1), 1),
    ("div", Some(2), 2),
    ("mod", Some(2), 2),
    ("atan2", Some(2), 2),
    ("crlf", Some(0), 0),
    ("exec", None, 1),
    // Unknown: Soar rewrites it to `(exec my-fn ...)`.
    ("my-fn", None, 0),
];
/// Stand-alone functions.
const ACTION_FUNCS: &[(&str, Option<usize>, usize)] = &[
    ("write", None, 1),
    ("halt", Some(0), 0),
    ("interrupt", Some(0), 0),
    ("exec", None, 1),
    ("cmd", None, 1),
    ("log", None, 1),
    ("my-action", None, 0),
];

#[derive(Debug, Clone)]
enum Const {
    /// Lexes as a symbol when written bare.
    Sym(String),
    /// `p1`: read as the string `P1`.
    Ident(char, u32),
    /// The integer, written with a leading `+` when the flag is set and it is not negative.
    Int(i64, bool),
    /// n / 10^k written in one of several float spellings.
    Float(i64, u32, u8),
    /// `|...|`, possibly empty, with anything inside.
    Quoted(String),
}

#[derive(Debug, Clone)]
enum Atom {
    /// A variable from `VARS`; binds it in a positive condition.
    Var(u8),
    Const(Const),
}

/// A variable that must already be bound (resolved against the bound list) or a constant.
#[derive(Debug, Clone)]
enum RefAtom {
    Ref(u8),
    Const(Const),
}

#[derive(Debug, Clone)]
enum Simple {
    /// `x`, or `= x` when the flag is set.
    Eq(Atom, bool),
    Rel(u8, RefAtom),
    Disj(Vec<Const>),
}

#[derive(Debug, Clone)]
enum TestSpec {
    Simple(Simple),
    /// `{ rel... [eq] }`: non-equality tests and at most one equality test.
    Conj(Vec<Simple>, Option<Atom>),
}

#[derive(Debug, Clone)]
enum PathElem {
    Sym(String),
    Quoted(String),
    Ident(char, u32),
    Var(u8),
}

#[derive(Debug, Clone)]
enum ValueSpec {
    Test(TestSpec, bool),
    /// `^a (^b ...)`, optionally followed by `+`.
    Struct(Vec<AvtSpec>, bool),
}

/// `[-]^p1.p2.last v1 v2 ...`
#[derive(Debug, Clone)]
struct AvtSpec {
    negated: bool,
    prefix: Vec<PathElem>,
    last: TestSpec,
    values: Vec<ValueSpec>,
}

#[derive(Debug, Clone)]
enum IdSpec {
    Var(u8),
    /// `{ <> <ref> <var> }`
    Conj(Vec<(u8, u8)>, u8),
}

#[derive(Debug, Clone)]
enum CondSpec {
    Positive(u8, IdSpec, Vec<AvtSpec>),
    Negative(u8, IdSpec, Vec<AvtSpec>),
    Ncc(Vec<CondSpec>),
}

#[derive(Debug, Clone)]
struct Call {
    func: u8,
    args: Vec<Arg>,
}

#[derive(Debug, Clone)]
enum Arg {
    Ref(u8),
    Const(Const),
    Call(Call),
}

#[derive(Debug, Clone)]
enum RhsVal {
    Ref(u8),
    /// A new identifier from `NEW_VARS`.
    New(u8),
    Const(Const),
    Call(Call),
}

#[derive(Debug, Clone)]
enum PrefSpec {
    Plus,
    Minus,
    Bang,
    Tilde,
    Gt,
    Lt,
    Eq,
    Better(RhsVal),
    Worse(RhsVal),
    BinEq(RhsVal),
    Numeric(Const),
}

#[derive(Debug, Clone)]
enum MakeAttr {
    Operator,
    Const(Const),
    Ref(u8),
    Call(Call),
}

#[derive(Debug, Clone)]
struct AttrMakeSpec {
    prefix: Vec<PathElem>,
    last: MakeAttr,
    values: Vec<(RhsVal, Vec<PrefSpec>)>,
    commas: bool,
}

#[derive(Debug, Clone)]
enum ActionSpec {
    Make(RhsId, Vec<AttrMakeSpec>),
    Call(Call),
}

#[derive(Debug, Clone)]
enum RhsId {
    Ref(u8),
    /// A new identifier made by this rule; falls back to `<s>` when no make creates it.
    New(u8),
}

#[derive(Debug, Clone)]
enum NameSpec {
    Sym(String),
    Quoted(String),
}

#[derive(Debug, Clone)]
struct RuleSpec {
    name: NameSpec,
    doc: Option<String>,
    flags: Vec<u8>,
    /// The attribute tests of `(state <s> ...)`.
    first: Vec<AvtSpec>,
    conds: Vec<CondSpec>,
    actions: Vec<ActionSpec>,
    /// 0: single spaces; otherwise seeds the choice of whitespace, `;` and `#` comments.
    layout: u32,
}

// ---------------------------------------------------------------------------- strategies

fn symbol() -> impl Strategy<Value = String> {
    prop_oneof![
        4 => "[a-z][a-z]{0,5}([*-][a-zA-Z0-9]{1,4}){0,3}",
        1 => "[A-Z][a-zA-Z]{0,6}",
        1 => proptest::sample::select(ODD_SYMBOLS).prop_map(str::to_string),
    ]
}

fn quoted_text() -> impl Strategy<Value = String> {
    prop_oneof![
        1 => Just(String::new()),
        4 => "[ a-zA-Z0-9|\\\\#{}().^\"'<>=*+,;~!-]{0,10}",
        1 => proptest::sample::select(&["P1", "p1", "123", "1.5", "<x>", "a b", "é ü", "state", "-", "a.b"][..])
            .prop_map(str::to_string),
    ]
}

fn constant() -> impl Strategy<Value = Const> {
    prop_oneof![
        5 => symbol().prop_map(Const::Sym),
        2 => (proptest::char::range('a', 'z'), 0u32..1000).prop_map(|(c, n)| Const::Ident(c, n)),
        3 => prop_oneof![4 => -1000i64..1000, 1 => any::<i64>()].prop_flat_map(|i| (Just(i), any::<bool>()))
            .prop_map(|(i, plus)| Const::Int(i, plus)),
        2 => (-10_000_000i64..10_000_000, 0u32..7, 0u8..4).prop_map(|(n, k, f)| Const::Float(n, k, f)),
        2 => quoted_text().prop_map(Const::Quoted),
    ]
}

fn number() -> impl Strategy<Value = Const> {
    prop_oneof![
        (-100i64..100).prop_map(|i| Const::Int(i, false)),
        (0i64..1000, 0u32..4, 0u8..4).prop_map(|(n, k, f)| Const::Float(n, k, f)),
    ]
}

fn var() -> impl Strategy<Value = u8> {
    0..VARS.len() as u8
}

fn atom() -> impl Strategy<Value = Atom> {
    prop_oneof![3 => var().prop_map(Atom::Var), 2 => constant().prop_map(Atom::Const)]
}

fn ref_atom() -> impl Strategy<Value = RefAtom> {
    prop_oneof![
        any::<u8>().prop_map(RefAtom::Ref),
        constant().prop_map(RefAtom::Const)
    ]
}

fn non_eq_simple() -> impl Strategy<Value = Simple> {
    prop_oneof![
        3 => (0..RELATIONS.len() as u8, ref_atom()).prop_map(|(r, a)| Simple::Rel(r, a)),
        1 => vec(constant(), 1..4).prop_map(Simple::Disj),
    ]
}

fn test_spec() -> impl Strategy<Value = TestSpec> {
    prop_oneof![
        6 => (atom(), prop::bool::weighted(0.2)).prop_map(|(a, e)| TestSpec::Simple(Simple::Eq(a, e))),
        2 => non_eq_simple().prop_map(TestSpec::Simple),
        2 => (vec(non_eq_simple(), 1..3), proptest::option::of(atom()))
            .prop_map(|(ts, eq)| TestSpec::Conj(ts, eq)),
    ]
}

fn attr_test() -> impl Strategy<Value = TestSpec> {
    prop_oneof![
        8 => symbol().prop_map(|s| TestSpec::Simple(Simple::Eq(Atom::Const(Const::Sym(s)), false))),
        1 => test_spec(),
    ]
}

fn path_elem() -> impl Strategy<Value = PathElem> {
    prop_oneof![
        6 => symbol().prop_map(PathElem::Sym),
        1 => "[a-z ]{1,5}".prop_map(PathElem::Quoted),
        1 => (proptest::char::range('a', 'z'), 0u32..50).prop_map(|(c, n)| PathElem::Ident(c, n)),
        1 => var().prop_map(PathElem::Var),
    ]
}

fn avt_with(values: BoxedStrategy<ValueSpec>) -> impl Strategy<Value = AvtSpec> {
    (
        prop::bool::weighted(0.2),
        prop_oneof![3 => vec(path_elem(), 0..1), 1 => vec(path_elem(), 1..3)],
        attr_test(),
        vec(values, 0..3),
    )
        .prop_map(|(negated, prefix, last, values)| AvtSpec {
            negated,
            prefix,
            last,
            values,
        })
}

fn avt() -> BoxedStrategy<AvtSpec> {
    let plain = (test_spec(), prop::bool::weighted(0.1))
        .prop_map(|(t, a)| ValueSpec::Test(t, a))
        .boxed();
    avt_with(plain)
        .prop_recursive(2, 8, 3, |inner| {
            let values = prop_oneof![
                4 => (test_spec(), prop::bool::weighted(0.1)).prop_map(|(t, a)| ValueSpec::Test(t, a)),
                1 => (vec(inner, 1..3), prop::bool::weighted(0.2)).prop_map(|(a, acc)| ValueSpec::Struct(a, acc)),
            ]
            .boxed();
            avt_with(values)
        })
        .boxed()
}

fn id_spec() -> impl Strategy<Value = IdSpec> {
    prop_oneof![
        6 => var().prop_map(IdSpec::Var),
        1 => (vec((0..RELATIONS.len() as u8, any::<u8>()), 1..3), var())
            .prop_map(|(rels, v)| IdSpec::Conj(rels, v)),
    ]
}

fn head() -> impl Strategy<Value = u8> {
    prop_oneof![8 => Just(0u8), 1 => Just(1u8), 1 => Just(2u8)]
}

fn cond() -> impl Strategy<Value = CondSpec> {
    let leaf = prop_oneof![
        3 => (head(), id_spec(), vec(avt(), 1..4)).prop_map(|(h, id, a)| CondSpec::Positive(h, id, a)),
        1 => (head(), id_spec(), vec(avt(), 1..3)).prop_map(|(h, id, a)| CondSpec::Negative(h, id, a)),
    ];
    leaf.prop_recursive(2, 8, 3, |inner| {
        prop_oneof![
            3 => inner.clone(),
            1 => vec(inner, 1..4).prop_map(CondSpec::Ncc),
        ]
    })
}

fn call(table: &'static [(&'static str, Option<usize>, usize)]) -> impl Strategy<Value = Call> {
    let leaf_arg = prop_oneof![
        2 => any::<u8>().prop_map(Arg::Ref),
        2 => constant().prop_map(Arg::Const),
    ];
    let value_call = (0..VALUE_FUNCS.len() as u8, vec(leaf_arg.clone(), 0..4))
        .prop_map(|(func, args)| Call { func, args });
    let nested = value_call.prop_recursive(2, 8, 3, |inner| {
        (
            0..VALUE_FUNCS.len() as u8,
            vec(
                prop_oneof![
                    2 => any::<u8>().prop_map(Arg::Ref),
                    2 => constant().prop_map(Arg::Const),
                    1 => inner.prop_map(Arg::Call),
                ],
                0..4,
            ),
        )
            .prop_map(|(func, args)| Call { func, args })
    });
    let arg = prop_oneof![
        3 => leaf_arg,
        1 => nested.prop_map(Arg::Call),
    ];
    (0..table.len() as u8, vec(arg, 0..4)).prop_map(|(func, args)| Call { func, args })
}

fn rhs_val() -> impl Strategy<Value = RhsVal> {
    prop_oneof![
        3 => any::<u8>().prop_map(RhsVal::Ref),
        2 => (0..NEW_VARS.len() as u8).prop_map(RhsVal::New),
        3 => constant().prop_map(RhsVal::Const),
        1 => call(VALUE_FUNCS).prop_map(RhsVal::Call),
    ]
}

fn pref() -> impl Strategy<Value = PrefSpec> {
    prop_oneof![
        3 => Just(PrefSpec::Plus),
        2 => Just(PrefSpec::Minus),
        1 => Just(PrefSpec::Bang),
        1 => Just(PrefSpec::Tilde),
        1 => Just(PrefSpec::Gt),
        1 => Just(PrefSpec::Lt),
        1 => Just(PrefSpec::Eq),
        1 => rhs_val().prop_map(PrefSpec::Better),
        1 => rhs_val().prop_map(PrefSpec::Worse),
        1 => rhs_val().prop_map(PrefSpec::BinEq),
        1 => number().prop_map(PrefSpec::Numeric),
    ]
}

fn make_attr() -> impl Strategy<Value = MakeAttr> {
    prop_oneof![
        3 => Just(MakeAttr::Operator),
        5 => symbol().prop_map(|s| MakeAttr::Const(Const::Sym(s))),
        1 => constant().prop_map(MakeAttr::Const),
        1 => any::<u8>().prop_map(MakeAttr::Ref),
        1 => call(VALUE_FUNCS).prop_map(MakeAttr::Call),
    ]
}

fn attr_make() -> impl Strategy<Value = AttrMakeSpec> {
    (
        prop_oneof![4 => vec(path_elem(), 0..1), 1 => vec(path_elem(), 1..3)],
        make_attr(),
        vec((rhs_val(), vec(pref(), 0..3)), 1..4),
        prop::bool::weighted(0.2),
    )
        .prop_map(|(prefix, last, values, commas)| AttrMakeSpec {
            prefix,
            last,
            values,
            commas,
        })
}

fn action() -> impl Strategy<Value = ActionSpec> {
    let id = prop_oneof![
        4 => any::<u8>().prop_map(RhsId::Ref),
        1 => (0..NEW_VARS.len() as u8).prop_map(RhsId::New),
    ];
    prop_oneof![
        4 => (id, vec(attr_make(), 1..4)).prop_map(|(id, a)| ActionSpec::Make(id, a)),
        1 => call(ACTION_FUNCS).prop_map(ActionSpec::Call),
    ]
}

fn rule() -> impl Strategy<Value = RuleSpec> {
    let name = prop_oneof![
        6 => "[a-z]{1,6}([*-][a-z0-9]{1,5}){0,3}".prop_map(NameSpec::Sym),
        1 => symbol().prop_map(NameSpec::Sym),
        1 => "[a-z][a-z ]{0,8}".prop_map(NameSpec::Quoted),
    ];
    (
        name,
        proptest::option::weighted(
            0.3,
            "[ a-zA-Z0-9.,:'()*<>=^+-]{0,20}|[a-z]{1,3}(\\\\|\")[a-z]{0,3}",
        ),
        prop_oneof![3 => vec(0..FLAGS.len() as u8, 0..1), 1 => vec(0..FLAGS.len() as u8, 1..4)],
        vec(avt(), 1..4),
        vec(cond(), 0..5),
        vec(action(), 0..5),
        prop_oneof![1 => Just(0u32), 3 => any::<u32>()],
    )
        .prop_map(
            |(name, doc, flags, first, conds, actions, layout)| RuleSpec {
                name,
                doc,
                flags,
                first,
                conds,
                actions,
                layout,
            },
        )
}

// ------------------------------------------------------------------------------ rendering

/// Renders a rule description as the inside of `sp {...}`.
fn render(spec: &RuleSpec) -> String {
    let mut bound = vec!["<s>"];
    for a in &spec.first {
        bind_avt(a, &mut bound);
    }
    for c in &spec.conds {
        bind_cond(c, &mut bound);
    }
    // A new identifier is made by an action whose own id is grounded (bound, or made by
    // another such action), so `made` grows until no action adds to it.
    let mut made: Vec<u8> = Vec::new();
    loop {
        let before = made.len();
        add_made(spec, &mut made);
        if made.len() == before {
            break;
        }
    }
    let mut r = Renderer {
        out: String::new(),
        bound,
        made,
        rng: u64::from(spec.layout),
    };
    r.rule(spec);
    r.out
}

/// The new identifiers the make actions whose ids are grounded by `made` create.
fn add_made(spec: &RuleSpec, made: &mut Vec<u8>) {
    for a in &spec.actions {
        if let ActionSpec::Make(id, attrs) = a {
            if let RhsId::New(k) = id {
                if !made.contains(k) {
                    continue;
                }
            }
            for am in attrs {
                // Referents are rendered only on ^operator (other attributes take + and -).
                let operator = matches!(am.last, MakeAttr::Operator);
                for (v, prefs) in &am.values {
                    let referents = prefs.iter().filter_map(|p| match p {
                        PrefSpec::Better(r) | PrefSpec::Worse(r) | PrefSpec::BinEq(r)
                            if operator =>
                        {
                            Some(r)
                        }
                        _ => None,
                    });
                    for r in std::iter::once(v).chain(referents) {
                        if let RhsVal::New(k) = r {
                            if !made.contains(k) {
                                made.push(*k);
                            }
                        }
                    }
                }
            }
        }
    }
}

fn bind_atom(a: &Atom, bound: &mut Vec<&'static str>) {
    if let Atom::Var(v) = a {
        let name = VARS[*v as usize % VARS.len()];
        if !bound.contains(&name) {
            bound.push(name);
        }
    }
}

fn bind_test(t: &TestSpec, bound: &mut Vec<&'static str>) {
    match t {
        TestSpec::Simple(Simple::Eq(a, _)) => bind_atom(a, bound),
        TestSpec::Conj(_, Some(a)) => bind_atom(a, bound),
        _ => {}
    }
}

fn bind_avt(a: &AvtSpec, bound: &mut Vec<&'static str>) {
    if a.negated {
        return;
    }
    for p in &a.prefix {
        if let PathElem::Var(v) = p {
            bind_atom(&Atom::Var(*v), bound);
        }
    }
    bind_test(&a.last, bound);
    for v in &a.values {
        match v {
            ValueSpec::Test(t, _) => bind_test(t, bound),
            ValueSpec::Struct(inner, _) => inner.iter().for_each(|a| bind_avt(a, bound)),
        }
    }
}

fn bind_cond(c: &CondSpec, bound: &mut Vec<&'static str>) {
    if let CondSpec::Positive(_, id, avts) = c {
        // The id is bound only by a condition that some non-negated test makes.
        if avts.iter().any(|a| !a.negated) {
            match id {
                IdSpec::Var(v) | IdSpec::Conj(_, v) => bind_atom(&Atom::Var(*v), bound),
            }
        }
        avts.iter().for_each(|a| bind_avt(a, bound));
    }
}

struct Renderer {
    out: String,
    bound: Vec<&'static str>,
    made: Vec<u8>,
    rng: u64,
}

impl Renderer {
    /// Whitespace between two tokens: one space in layout 0, else a deterministic mix.
    fn ws(&mut self) {
        if self.rng == 0 {
            self.out.push(' ');
            return;
        }
        self.rng = self
            .rng
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        let pick = (self.rng >> 33) % 16;
        self.out.push_str(match pick {
            0..=9 => " ",
            10 => "\n    ",
            11 => "\t",
            12 => " ; ",
            13 => "  # a comment (with ^odd <text>)\n  ",
            14 => "\n",
            _ => "   ",
        });
    }

    fn tok(&mut self, s: &str) {
        self.ws();
        self.out.push_str(s);
    }

    fn rule(&mut self, spec: &RuleSpec) {
        let name = match &spec.name {
            NameSpec::Sym(s) => s.clone(),
            NameSpec::Quoted(s) => quote(s),
        };
        self.out.push_str(&name);
        if let Some(doc) = &spec.doc {
            let escaped = doc.replace('\\', "\\\\").replace('"', "\\\"");
            self.tok(&format!("\"{escaped}\""));
        }
        for f in &spec.flags {
            self.tok(FLAGS[*f as usize % FLAGS.len()]);
        }
        // The goal test: the first attribute test is never negated.
        self.tok("(state");
        self.tok("<s>");
        for (i, a) in spec.first.iter().enumerate() {
            let mut a = a.clone();
            if i == 0 {
                a.negated = false;
            }
            self.avt(&a);
        }
        self.tok(")");
        for c in &spec.conds {
            self.cond(c, false);
        }
        self.tok("-->");
        for a in &spec.actions {
            self.action(a);
        }
        self.ws();
    }

    fn reference(&self, i: u8) -> &'static str {
        self.bound[i as usize % self.bound.len()]
    }

    fn constant(&mut self, c: &Const) {
        let text = const_text(c);
        self.tok(&text);
    }

    fn atom(&mut self, a: &Atom) {
        match a {
            Atom::Var(v) => self.tok(VARS[*v as usize % VARS.len()]),
            Atom::Const(c) => self.constant(c),
        }
    }

    fn simple(&mut self, s: &Simple) {
        match s {
            Simple::Eq(a, explicit) => {
                if *explicit {
                    self.tok("=");
                }
                self.atom(a);
            }
            Simple::Rel(r, a) => {
                self.tok(RELATIONS[*r as usize % RELATIONS.len()]);
                match a {
                    RefAtom::Ref(i) => {
                        let v = self.reference(*i);
                        self.tok(v);
                    }
                    RefAtom::Const(c) => self.constant(c),
                }
            }
            Simple::Disj(cs) => {
                self.tok("<<");
                for c in cs {
                    self.constant(c);
                }
                self.tok(">>");
            }
        }
    }

    fn test(&mut self, t: &TestSpec) {
        match t {
            TestSpec::Simple(s) => self.simple(s),
            TestSpec::Conj(ts, eq) => {
                self.tok("{");
                for s in ts {
                    self.simple(s);
                }
                if let Some(a) = eq {
                    self.atom(a);
                }
                self.tok("}");
            }
        }
    }

    fn avt(&mut self, a: &AvtSpec) {
        self.tok(if a.negated { "-^" } else { "^" });
        // The path is glued: `^a.b.c`.
        for p in &a.prefix {
            let text = match p {
                PathElem::Sym(s) => s.clone(),
                PathElem::Quoted(s) => quote(s),
                PathElem::Ident(c, n) => format!("{c}{n}"),
                PathElem::Var(v) => VARS[*v as usize % VARS.len()].to_string(),
            };
            self.out.push_str(&text);
            self.out.push('.');
        }
        {
            // Glue the attribute to `^` or the last dot: render it and trim its leading
            // whitespace (a float `.5` would read as a dot after `^`, so write `0.5`).
            let start = self.out.len();
            self.test(&a.last);
            let rendered = self.out.split_off(start);
            let trimmed = rendered.trim_start();
            if trimmed.starts_with('.') {
                self.out.push('0');
            }
            self.out.push_str(trimmed);
        }
        for v in &a.values {
            match v {
                ValueSpec::Test(t, acc) => {
                    self.test(t);
                    if *acc {
                        self.tok("+");
                    }
                }
                ValueSpec::Struct(inner, acc) => {
                    self.tok("(");
                    for i in inner {
                        self.avt(i);
                    }
                    self.tok(")");
                    if *acc {
                        self.tok("+");
                    }
                }
            }
        }
    }

    fn id(&mut self, id: &IdSpec) {
        match id {
            IdSpec::Var(v) => self.tok(VARS[*v as usize % VARS.len()]),
            IdSpec::Conj(rels, v) => {
                self.tok("{");
                for (r, i) in rels {
                    self.tok(RELATIONS[*r as usize % RELATIONS.len()]);
                    let v = self.reference(*i);
                    self.tok(v);
                }
                self.tok(VARS[*v as usize % VARS.len()]);
                self.tok("}");
            }
        }
    }

    /// `in_negation`: inside `-{...}`, where a lone condition may become a negated one.
    fn cond(&mut self, c: &CondSpec, in_negation: bool) {
        match c {
            CondSpec::Positive(h, id, avts) | CondSpec::Negative(h, id, avts) => {
                let negated = matches!(c, CondSpec::Negative(..));
                self.tok(if negated { "-(" } else { "(" });
                let head = if (negated || in_negation) && !NEGATED_GOAL_TESTS {
                    0
                } else {
                    h % 3
                };
                match head {
                    1 => self.tok("state"),
                    2 => self.tok("impasse"),
                    _ => {}
                }
                self.id(id);
                for (i, a) in avts.iter().enumerate() {
                    if i == 0 && head != 0 && !NEGATED_GOAL_TESTS {
                        // `(state <x> -^a)` alone is a negated goal test too.
                        let mut a = a.clone();
                        a.negated = false;
                        self.avt(&a);
                    } else {
                        self.avt(a);
                    }
                }
                self.tok(")");
            }
            CondSpec::Ncc(cs) => {
                self.tok("-{");
                for c in cs {
                    self.cond(c, true);
                }
                self.tok("}");
            }
        }
    }

    fn call(&mut self, c: &Call, table: &[(&str, Option<usize>, usize)]) {
        let (name, arity, min) = table[c.func as usize % table.len()];
        let mut args = c.args.clone();
        let want = arity.unwrap_or(args.len().max(min));
        args.truncate(want);
        while args.len() < want {
            args.push(Arg::Const(Const::Int(args.len() as i64 + 1, false)));
        }
        self.tok("(");
        self.out.push_str(name);
        for a in &args {
            match a {
                Arg::Ref(i) => {
                    let v = self.reference(*i);
                    self.tok(v);
                }
                Arg::Const(k) => self.constant(k),
                Arg::Call(inner) => self.call(inner, VALUE_FUNCS),
            }
        }
        self.tok(")");
    }

    fn rhs_val(&mut self, v: &RhsVal) {
        match v {
            RhsVal::Ref(i) => {
                let v = self.reference(*i);
                self.tok(v);
            }
            RhsVal::New(k) => self.tok(NEW_VARS[*k as usize % NEW_VARS.len()]),
            RhsVal::Const(c) => self.constant(c),
            RhsVal::Call(c) => self.call(c, VALUE_FUNCS),
        }
    }

    fn action(&mut self, a: &ActionSpec) {
        match a {
            ActionSpec::Call(c) => self.call(c, ACTION_FUNCS),
            ActionSpec::Make(id, attrs) => {
                self.tok("(");
                match id {
                    RhsId::Ref(i) => {
                        let v = self.reference(*i);
                        self.out.push_str(v);
                    }
                    RhsId::New(k) if self.made.contains(k) => {
                        self.out.push_str(NEW_VARS[*k as usize % NEW_VARS.len()])
                    }
                    RhsId::New(_) => self.out.push_str("<s>"),
                }
                for am in attrs {
                    self.attr_make(am);
                }
                self.tok(")");
            }
        }
    }

    fn attr_make(&mut self, am: &AttrMakeSpec) {
        self.tok("^");
        for p in &am.prefix {
            let text = match p {
                PathElem::Sym(s) => s.clone(),
                PathElem::Quoted(s) => quote(s),
                PathElem::Ident(c, n) => format!("{c}{n}"),
                PathElem::Var(i) => self.reference(*i).to_string(),
            };
            self.out.push_str(&text);
            self.out.push('.');
        }
        let start = self.out.len();
        let is_operator = match &am.last {
            MakeAttr::Operator => {
                self.tok("operator");
                true
            }
            MakeAttr::Const(c) => {
                self.constant(c);
                false
            }
            MakeAttr::Ref(i) => {
                let v = self.reference(*i);
                self.tok(v);
                false
            }
            MakeAttr::Call(c) => {
                self.call(c, VALUE_FUNCS);
                false
            }
        };
        // The attribute follows `^` (or the last `.`) directly.
        let rendered = self.out.split_off(start);
        let trimmed = rendered.trim_start();
        if trimmed.starts_with('.') {
            self.out.push('0');
        }
        self.out.push_str(trimmed);
        for (i, (v, prefs)) in am.values.iter().enumerate() {
            if i > 0 && am.commas {
                self.tok(",");
            }
            self.rhs_val(v);
            let mut last_unary_binary_symbol = false;
            for p in prefs {
                let p = if is_operator {
                    p.clone()
                } else {
                    // Only + and - are allowed on other attributes, as in Soar.
                    match p {
                        PrefSpec::Minus | PrefSpec::Tilde | PrefSpec::Lt | PrefSpec::Worse(_) => {
                            PrefSpec::Minus
                        }
                        _ => PrefSpec::Plus,
                    }
                };
                last_unary_binary_symbol = matches!(p, PrefSpec::Gt | PrefSpec::Lt | PrefSpec::Eq);
                match &p {
                    PrefSpec::Plus => self.tok("+"),
                    PrefSpec::Minus => self.tok("-"),
                    PrefSpec::Bang => self.tok("!"),
                    PrefSpec::Tilde => self.tok("~"),
                    PrefSpec::Gt => self.tok(">"),
                    PrefSpec::Lt => self.tok("<"),
                    PrefSpec::Eq => self.tok("="),
                    PrefSpec::Better(r) => {
                        self.tok(">");
                        self.rhs_val(r);
                    }
                    PrefSpec::Worse(r) => {
                        self.tok("<");
                        self.rhs_val(r);
                    }
                    PrefSpec::BinEq(r) => {
                        self.tok("=");
                        self.rhs_val(r);
                    }
                    PrefSpec::Numeric(n) => {
                        self.tok("=");
                        self.constant(n);
                    }
                }
            }
            // `<o1> = <o2>` would make `=` binary: a comma keeps it unary.
            if last_unary_binary_symbol && i + 1 < am.values.len() && !am.commas {
                self.tok(",");
            }
        }
    }
}

fn quote(s: &str) -> String {
    let mut out = String::from("|");
    for c in s.chars() {
        if c == '|' || c == '\\' {
            out.push('\\');
        }
        out.push(c);
    }
    out.push('|');
    out
}

fn const_text(c: &Const) -> String {
    match c {
        Const::Sym(s) => s.clone(),
        Const::Ident(c, n) => format!("{c}{n}"),
        Const::Int(i, plus) => {
            if *plus && *i >= 0 {
                format!("+{i}")
            } else {
                i.to_string()
            }
        }
        Const::Float(n, k, form) => float_text(*n, *k, *form),
        Const::Quoted(s) => quote(s),
    }
}

/// n / 10^k as `12.34`, `.5` / `5.`, or `1.234e1`: always with a `.`, so it lexes as a float.
fn float_text(n: i64, k: u32, form: u8) -> String {
    let sign = if n < 0 { "-" } else { "" };
    let digits = n.unsigned_abs().to_string();
    let k = k as usize;
    let padded = if digits.len() <= k {
        format!("{}{digits}", "0".repeat(k + 1 - digits.len()))
    } else {
        digits.clone()
    };
    let (int_part, frac) = padded.split_at(padded.len() - k);
    match form {
        // `.5`: only for a positive value below 1 (the lexer reads `-.5` as `-` `.5`).
        1 if int_part == "0" && !frac.is_empty() && n > 0 => format!(".{frac}"),
        // `5.`
        2 if frac.is_empty() => format!("{sign}{int_part}."),
        3 => {
            // d.ddd e(len-1-k)
            let exp = digits.len() as i64 - 1 - k as i64;
            format!("{sign}{}.{}e{exp}", &digits[..1], &digits[1..])
        }
        _ => format!(
            "{sign}{int_part}.{}",
            if frac.is_empty() { "0" } else { frac }
        ),
    }
}

// ------------------------------------------------------------------------- normalising

fn zero_call(f: &mut FuncCall) {
    f.span = Span::default();
    f.args.iter_mut().for_each(zero_term);
}

fn zero_term(t: &mut RhsTerm) {
    if let RhsTerm::Call(f) = t {
        zero_call(f);
    }
}

fn zero_conds(cs: &mut [Condition]) {
    for c in cs {
        match c {
            Condition::Positive(c) | Condition::Negative(c) => c.span = Default::default(),
            Condition::Ncc(inner) => zero_conds(inner),
        }
    }
}

/// The production with every `Span` zeroed.
fn strip(p: &Production) -> Production {
    let mut p = p.clone();
    p.span = Span::default();
    zero_conds(std::sync::Arc::make_mut(&mut p.conditions));
    for a in &mut p.actions {
        match a {
            Action::Make(m) => {
                m.span = Default::default();
                zero_term(&mut m.id);
                zero_term(&mut m.attr);
                zero_term(&mut m.value);
                if let Some(r) = &mut m.referent {
                    zero_term(r);
                }
            }
            Action::Call(f) => zero_call(f),
        }
    }
    p
}

/// The condition order `print` produces (as Soar's `print_condition_list`): at each level,
/// conditions with the same id test gather at the place of the first one, and a
/// `state`/`impasse` test on a positive condition of the group applies to all of them (it
/// tests the identifier, so it is the same test). A negated condition whose goal test no
/// positive condition on its id repeats must keep it, in a group of its own,
/// `(state <x> -^a v)` (the printer does not do this yet: `NEGATED_GOAL_TESTS`). Conjunctive
/// negations stay in place.
/// Make actions as the printer groups them: each with every later one on the same id, at
/// the place of the first (9.6's order); function calls stay where they are.
fn regroup_actions(actions: &[Action]) -> Vec<Action> {
    let mut taken = vec![false; actions.len()];
    let mut out = Vec::new();
    for i in 0..actions.len() {
        if taken[i] {
            continue;
        }
        match &actions[i] {
            Action::Make(m) => {
                for (j, a) in actions.iter().enumerate().skip(i) {
                    if let Action::Make(mm) = a {
                        if !taken[j] && mm.id == m.id {
                            taken[j] = true;
                            out.push(a.clone());
                        }
                    }
                }
            }
            other => out.push(other.clone()),
        }
    }
    out
}

fn regroup(conds: &[Condition]) -> Vec<Condition> {
    enum Item {
        /// The id test, the negated goal test it keeps (or `None`), the members.
        Group(production::Test, Head, Vec<Condition>),
        Ncc(Vec<Condition>),
    }
    let mut items: Vec<Item> = Vec::new();
    for c in conds {
        let (cc, negated) = match c {
            Condition::Ncc(inner) => {
                items.push(Item::Ncc(regroup(inner)));
                continue;
            }
            Condition::Positive(cc) => (cc, false),
            Condition::Negative(cc) => (cc, true),
        };
        let own = negated
            && cc.goal != Head::None
            && !conds
                .iter()
                .any(|o| matches!(o, Condition::Positive(p) if p.id == cc.id && p.goal == cc.goal));
        let key = if own { cc.goal } else { Head::None };
        let found = items.iter_mut().find_map(|it| match it {
            Item::Group(id, k, g) if *id == cc.id && *k == key => Some(g),
            _ => None,
        });
        match found {
            Some(g) => g.push(c.clone()),
            None => items.push(Item::Group(cc.id.clone(), key, vec![c.clone()])),
        }
    }
    let mut out = Vec::new();
    for it in items {
        match it {
            Item::Ncc(inner) => out.push(Condition::Ncc(inner)),
            Item::Group(_, key, mut g) => {
                let goal = g
                    .iter()
                    .find_map(|c| match c {
                        Condition::Positive(c) if c.goal != Head::None => Some(c.goal),
                        _ => None,
                    })
                    .unwrap_or(key);
                for c in &mut g {
                    if let Condition::Positive(c) | Condition::Negative(c) = c {
                        c.goal = goal;
                    }
                }
                out.extend(g);
            }
        }
    }
    out
}

// ----------------------------------------------------------------------------- the check

fn compile_body(body: &str) -> Result<Production, String> {
    let mut warnings = Vec::new();
    let ast = parse_production(body, 0, 0, &mut warnings)
        .map_err(|d| format!("parse error: {}", d.message))?;
    let mut out = CompileOutput::default();
    production::compile(&ast, &mut out).map_err(|d| format!("compile error: {}", d.message))
}

/// `sp {BODY}\n` → `BODY`.
fn body_of(printed: &str) -> &str {
    printed
        .strip_prefix("sp {")
        .and_then(|s| s.strip_suffix("}\n"))
        .unwrap_or_else(|| panic!("production_text should be `sp {{...}}\\n`: {printed:?}"))
}

/// Loads `text` (commands) into a fresh interpreter and returns the one rule it stored.
fn load(text: &str, name: &str) -> Result<Production, String> {
    let mut it = Interpreter::new();
    it.run_text("roundtrip", text).map_err(|d| {
        format!(
            "`sp` failed: {}\n{}",
            d.message,
            it.sources.render(&d).trim_end()
        )
    })?;
    it.agent
        .production(name)
        .cloned()
        .ok_or_else(|| format!("`sp` did not store a rule named {name:?}"))
}

/// A compiled rule as a fresh agent stores it: its conditions in the reorderer's order
/// ranked by a fresh symbol table.
fn as_loaded(p: &Production) -> Production {
    let mut syms = crate::symbols::Symbols::new();
    reorder::intern_in_text_order(&mut p.clone(), &mut syms);
    let mut conditions = reorder::reorder(&p.conditions, &syms);
    if p.flags.chunk || p.flags.justification {
        reorder::equality_first(&mut conditions);
    }
    let mut actions = p.actions.clone();
    if !(p.flags.chunk || p.flags.justification) {
        reorder::reorder_actions(&p.conditions, &mut actions);
    }
    Production {
        conditions: conditions.into(),
        actions,
        ..p.clone()
    }
}

/// The round trip; returns a description of the first difference.
fn round_trip(src: &str) -> Result<(), String> {
    let p1 = compile_body(src).map_err(|e| format!("generated rule rejected: {e}"))?;
    if p1.conditions.is_empty() || p1.name.is_empty() {
        return Err("generated rule compiled to nothing".into());
    }
    let t1 = production_text(&p1);
    let p2 = compile_body(body_of(&t1)).map_err(|e| format!("printed rule rejected: {e}"))?;
    let t2 = production_text(&p2);
    if t1 != t2 {
        return Err(format!(
            "printing changed on the second round:\n--- first\n{t1}--- second\n{t2}"
        ));
    }
    let (g1, s2) = (strip(&p1), strip(&p2));
    let expected = Production {
        conditions: regroup(&g1.conditions).into(),
        actions: regroup_actions(&g1.actions).into(),
        ..g1
    };
    if s2 != expected {
        return Err(format!(
            "the reparsed rule differs from the original (regrouped):\nprinted:\n{t1}\noriginal (regrouped):\n  {:?} {:?} {:?}\n  {:?}\n  {:?}\nreparsed:\n  {:?} {:?} {:?}\n  {:?}\n  {:?}",
            expected.name, expected.doc, expected.flags, expected.conditions, expected.actions,
            s2.name, s2.doc, s2.flags, s2.conditions, s2.actions
        ));
    }
    let p3 = compile_body(body_of(&t2)).map_err(|e| format!("reprinted rule rejected: {e}"))?;
    if strip(&p3) != s2 {
        return Err(format!(
            "the third parse differs from the second:\nprinted:\n{t2}"
        ));
    }
    // The real `sp` path, printed text and generated source alike.
    let loaded = load(&t1, &p1.name)?;
    if strip(&loaded) != strip(&as_loaded(&p2)) {
        return Err(format!(
            "`sp` stored a different rule for the printed text:\n{t1}"
        ));
    }
    let loaded = load(&format!("sp {{{src}}}\n"), &p1.name)?;
    if strip(&loaded) != strip(&as_loaded(&p1)) {
        return Err(
            "`sp {...}` of the generated source stored a different rule than parse_production"
                .into(),
        );
    }
    Ok(())
}

fn cases() -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(2000)
}

/// Runs `f` on a thread with a large stack: the nested strategies recurse deeply, and in a
/// debug build their frames overflow the 2 MB of a test thread.
fn with_big_stack(f: impl FnOnce() + Send + 'static) {
    let thread = std::thread::Builder::new()
        .stack_size(256 << 20)
        .spawn(f)
        .expect("spawn a test thread");
    if let Err(panic) = thread.join() {
        std::panic::resume_unwind(panic);
    }
}

#[test]
fn generated_rules_survive_print_and_reparse() {
    with_big_stack(|| {
        let mut runner = TestRunner::new(Config {
            cases: cases(),
            // Failures are reported with the shrunk rule; regressions live below as fixed tests.
            failure_persistence: None,
            ..Config::default()
        });
        let result = runner.run(&rule(), |spec| {
            let src = render(&spec);
            round_trip(&src).map_err(|e| {
                TestCaseError::fail(format!("{e}\n--- generated source\nsp {{{src}}}"))
            })
        });
        if let Err(e) = result {
            panic!("{e}");
        }
    });
}

/// The generator really produces every construct the round trip is meant to cover.
#[test]
fn generator_covers_every_feature() {
    with_big_stack(generator_coverage);
}

fn generator_coverage() {
    let mut runner = TestRunner::deterministic();
    let strategy = rule();
    let mut all = String::new();
    for _ in 0..600 {
        let spec = strategy.new_tree(&mut runner).expect("generate").current();
        all.push_str(&render(&spec));
        all.push('\n');
    }
    for needle in [
        "(state <s>",
        "impasse <",
        "-(",
        "-^",
        "-{",
        "<<",
        ">>",
        "<=>",
        " <> ",
        " <= ",
        " >= ",
        "{ ",
        " + ",
        "||",
        "|P1|",
        "\"",
        ":o-support",
        ":interrupt",
        "^operator",
        " ! ",
        " ~ ",
        "(+ ",
        "(write",
        "(halt",
        "(crlf",
        "(my-fn",
        "# a comment",
        " ; ",
        "e-",
    ] {
        assert!(
            all.contains(needle),
            "no generated rule contains {needle:?}"
        );
    }
    // Dot paths, floats in every spelling, structured values, numeric indifference.
    let words = |l: &str| {
        l.split([' ', '\t', '\n'])
            .map(str::to_string)
            .collect::<Vec<_>>()
    };
    type Check = (&'static str, fn(&[String]) -> bool);
    let checks: [Check; 5] = [
        ("a dot path", |ws| {
            ws.iter().any(|w| {
                w.starts_with('^')
                    && w.len() > 3
                    && w[1..].split('.').filter(|p| !p.is_empty()).count() > 1
            })
        }),
        ("a float written .5", |ws| {
            ws.iter()
                .any(|w| w.starts_with('.') && w[1..].starts_with(|c: char| c.is_ascii_digit()))
        }),
        ("a float written 5.", |ws| {
            ws.iter().any(|w| {
                let w = w.trim_start_matches('-');
                w.len() > 1
                    && w.ends_with('.')
                    && w[..w.len() - 1].bytes().all(|b| b.is_ascii_digit())
            })
        }),
        ("a structured value", |ws| {
            ws.windows(2).any(|p| p[0].starts_with('^') && p[1] == "(")
        }),
        ("a numeric indifferent", |ws| {
            ws.windows(3)
                .any(|p| p[0] == "=" && p[1].parse::<f64>().is_ok() && !p[1].starts_with('<'))
                && ws.iter().any(|w| w == "^operator")
        }),
    ];
    let all_words = words(&all);
    for (what, check) in checks {
        assert!(check(&all_words), "no generated rule contains {what}");
    }
}

// ------------------------------------------------------------------ fixed regression cases

fn assert_round_trip(src: &str) {
    if let Err(e) = round_trip(src) {
        panic!("{e}\n--- source\nsp {{{src}}}");
    }
}

#[test]
fn thesis_style_rule() {
    assert_round_trip(
        "robot*propose*copy-wall
            \"Copy a wall from the input link\"
            :o-support
            (state <s> ^io.input-link.wallData <source> ^Start (^X <sx> ^Y <sy>))
            (<source> ^Wall <w1> <w2> -^Copied true)
            (<w1> ^th { <th1> >= 0.5 } ^id <i1>)
            (<w2> ^th { <th2> <> <th1> >= <th1> } ^id { <> <i1> <i2> })
            -{ (<s> ^done <d>) (<d> ^wall <w1>) }
          -->
            (<s> ^operator <o> + =, <o2> > <o> ^operator <o> = 0.5)
            (<o> ^name copy-wall ^wall <w1> ^dist (int (/ (+ <sx> <sy>) 2)))
            (<source> ^Wall <w1> - <w2> -)
            (write |Copied wall | <w1> (crlf))
            (halt)",
    );
}

#[test]
fn every_constant_kind() {
    assert_round_trip(
        "a*b-c (state <s> ^type state ^v p1 ^k2 1e3 ^i -7 +5 007 ^f 1.5 .25 5. 1.5e2 -0.5
            ^q |a b| || |P1| |123| |1.5| |<x>| |a\\|b\\\\c| |é|
            ^d << a |b c| 1 2.5 P1 >> ^r { < 3 > <s> <= 2.0 >= -1 <=> x <> |y| })
         --> (<s> ^out |a b| || p1 1e3 -7 2.5 |<x>| state impasse)",
    );
}

#[test]
fn every_preference_form() {
    assert_round_trip(
        "prefs (state <s> ^operator <o> + ^operator <p> +) -->
            (<s> ^operator <o> + ^operator <o> - ^operator <o> ! ^operator <o> ~
                 ^operator <o> > ^operator <o> < ^operator <o> =
                 ^operator <o> > <p> ^operator <o> < <p> ^operator <o> = <p>
                 ^operator <o> = 0.5 ^operator <p> = 3)
            (<s> ^remove <o> - ^add <p> + ^both <o> + -)",
    );
}

#[test]
fn negations_and_paths() {
    assert_round_trip(
        "neg*paths (state <s> ^a.b.c <x> -^d.e 1 -^f (^g <y>) -^h 1 2)
            -(<x> ^z.q 1)
            -(<x> -^k 2)
            -{ (<x> ^m <m>) -{ (<m> ^n 1) } }
            (impasse <i> ^attribute operator)
          --> (<s> ^new.deep.path <n> ^(concat a b) (+ (* 2 <x>) 1)) (<n> ^made yes)",
    );
}

#[test]
fn structured_value_with_acceptable() {
    assert_round_trip("sv (state <s> ^operator (^name go ^arg <a>) + ^x <a>) --> (<s> ^ok <a>)");
}

#[test]
fn placeholder_shaped_user_variables() {
    // `<a*1>` is also the first placeholder for `^a`: the compiler must not reuse it.
    assert_round_trip("ph (state <s> ^a.b <a*1> ^a <q> ^a < 5) (<a*1> ^c 1) --> (<s> ^a.b <m*1>)");
}

#[test]
fn relational_only_id_test() {
    assert_round_trip("rid (state <s> ^x <x>) ({ <> <s> <y> } ^v <x>) --> (<s> ^ok 1)");
}

#[test]
fn all_flags_and_a_doc_with_escapes() {
    assert_round_trip(
        "flags \"a \\\"doc\\\" with \\\\ and spaces\" :o-support :i-support :chunk :default
            :template :interrupt :explain (state <s> ^a 1) --> (write |done|)",
    );
}

// Known round-trip bugs, kept as ignored tests until `src/printer.rs` is fixed (then remove
// the `ignore` and set `NEGATED_GOAL_TESTS` to true).

/// A negated condition with a `state` test on an id that no positive condition tests as a
/// state prints as `(<x> -^b 1)`: the goal test is lost, so the reparsed rule differs.
#[test]
fn negated_condition_keeps_its_state_test() {
    assert_round_trip("a (state <s> ^a <x>) -(state <x> ^b 1) -->");
    assert_round_trip("a (state <s> ^a <x>) (state <x> -^b 1) -->");
    assert_round_trip("a (state <s> ^a <x>) (<x> ^c 1) -{ (impasse <x> ^b 1) } -->");
}

/// `(s1 ^a b)`: an identifier-shaped RHS id prints as `(|S1| ^a b)`, which the grammar
/// rejects (`Illegal value for RHS value`).
#[test]
fn identifier_shaped_rhs_id() {
    assert_round_trip("a (state <s> ^a <x>) --> (s1 ^a b)");
}
