//! Compiling a parsed `sp` into a production: dot paths and structured values are flattened
//! into single conditions with placeholder variables, preferences become one action each,
//! and the load-time checks Soar makes are applied (Soar manual, chapter 3, "Production Memory";
//! the messages are 9.6's).

use crate::ast::{self, Constant, Head, Pref, Relation};
use crate::printer::constants::constant_text;
use crate::rhs::table::{self, Use};
use crate::source::{Diagnostic, FileId, PackedSpan, Span};
use rustc_hash::{FxHashMap, FxHashSet};

/// Declared support and other `:flags` (Soar manual, chapter 3, "Production type (optional)").
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Flags {
    pub o_support: bool,
    pub i_support: bool,
    pub chunk: bool,
    pub default: bool,
    pub template: bool,
    pub interrupt: bool,
    pub explain: bool,
    /// A justification: printed, never loaded.
    pub justification: bool,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Production {
    /// (Shared with the symbol table once the rule is loaded: a rule's name is a symbol.)
    pub name: arcstr::ArcStr,
    pub doc: Option<Box<str>>,
    pub flags: Flags,
    /// Shared between a rule and its changed copies (an RL rule with a new value).
    pub conditions: std::sync::Arc<[Condition]>,
    pub actions: Box<[Action]>,
    pub span: Span,
}

impl Production {
    /// Takes the conditions out as a list of their own, moved when nothing else shares
    /// them (a rule being loaded), copied when something does; leaves none behind.
    pub fn take_conditions(&mut self) -> Vec<Condition> {
        let mut shared = std::mem::replace(&mut self.conditions, std::sync::Arc::new([]));
        match std::sync::Arc::get_mut(&mut shared) {
            // (An empty conjunctive negation allocates nothing.)
            Some(own) => own.iter_mut().map(|c| std::mem::replace(c, Condition::Ncc(Vec::new()))).collect(),
            None => shared.to_vec(),
        }
    }

    /// The kind of rule, as the listings of 9.6's commands name it: `chunks`, `defaults`,
    /// `template` or `user` (justifications are never loaded rules).
    pub fn kind_word(&self) -> &'static str {
        if self.flags.chunk {
            "chunks"
        } else if self.flags.default {
            "defaults"
        } else if self.flags.template {
            "template"
        } else {
            "user"
        }
    }

    /// The value of a rule that is an RL rule: a single action, a numeric-indifferent
    /// preference whose value is a number (Soar manual, ch. 5, "RL Rules"). Template rules
    /// and justifications are not RL rules.
    pub fn rl_value(&self) -> Option<f64> {
        if self.flags.template || self.flags.justification {
            return None;
        }
        let [Action::Make(m)] = &*self.actions else {
            return None;
        };
        if m.pref != PrefKind::NumericIndifferent {
            return None;
        }
        match m.referent.as_ref()? {
            RhsTerm::Const(Constant::Int(i)) => Some(*i as f64),
            RhsTerm::Const(Constant::Float(f)) => Some(*f),
            _ => None,
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
pub enum Condition {
    Positive(Cond),
    Negative(Cond),
    Ncc(Vec<Condition>),
}

// A loaded rule keeps its conditions: 100,000 rules of six conditions hold 600,000.
const _: () = assert!(std::mem::size_of::<Condition>() == 64);

/// One `(id ^attr value)` condition after flattening.
#[derive(Debug, Clone, PartialEq)]
pub struct Cond {
    pub id: Test,
    pub attr: Test,
    pub value: Test,
    /// Matches only acceptable-preference WMEs (`+` after the value).
    pub acceptable: bool,
    /// `(state ...)` or `(impasse ...)` put a goal or impasse test on the id.
    pub goal: Head,
    pub span: PackedSpan,
}

/// One field's test. All but the common `Equal` keep their contents boxed: that makes a
/// test 16 bytes instead of 32, and a rule keeps three per condition.
#[derive(Debug, Clone, PartialEq)]
#[allow(clippy::box_collection)] // The boxes keep the enum small (see above).
pub enum Test {
    Equal(Term),
    Relational(Box<RelTest>),
    Disjunction(Box<Vec<Constant>>),
    /// At most one `Equal` inside, always last (as Soar prints it).
    Conjunction(Box<Vec<Test>>),
}

const _: () = assert!(std::mem::size_of::<Test>() == 16);

/// A relational test: its relation and what the field is compared with.
#[derive(Debug, Clone, PartialEq)]
pub struct RelTest {
    pub op: Relation,
    pub term: Term,
}

impl Test {
    /// A test that allocates nothing, left behind when a test is taken out of its place.
    pub fn placeholder() -> Test {
        Test::Equal(Term::Const(Constant::Int(0)))
    }

    pub fn conjunction(tests: Vec<Test>) -> Test {
        Test::Conjunction(Box::new(tests))
    }

    pub fn relational(op: Relation, term: Term) -> Test {
        Test::Relational(Box::new(RelTest { op, term }))
    }
}

#[derive(Debug, Clone, PartialEq)]
pub enum Term {
    /// (Shared text, not a `String`: with it a term is 24 bytes, and a rule keeps a few
    /// dozen of them. A loaded rule's variables share one copy of each name with every
    /// other rule's, see `Rete::share_var_names`.)
    Var(arcstr::ArcStr),
    Const(Constant),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PrefKind {
    Acceptable,
    Reject,
    Require,
    Prohibit,
    Best,
    Worst,
    Indifferent,
    Better,
    Worse,
    BinaryIndifferent,
    NumericIndifferent,
}

impl PrefKind {
    pub fn symbol(self) -> &'static str {
        match self {
            PrefKind::Acceptable => "+",
            PrefKind::Reject => "-",
            PrefKind::Require => "!",
            PrefKind::Prohibit => "~",
            PrefKind::Best | PrefKind::Better => ">",
            PrefKind::Worst | PrefKind::Worse => "<",
            PrefKind::Indifferent | PrefKind::BinaryIndifferent | PrefKind::NumericIndifferent => {
                "="
            }
        }
    }
    pub fn is_binary(self) -> bool {
        matches!(
            self,
            PrefKind::Better
                | PrefKind::Worse
                | PrefKind::BinaryIndifferent
                | PrefKind::NumericIndifferent
        )
    }
}

/// (Both boxed: an action is then 16 bytes, and a rule keeps its list for its lifetime.)
#[derive(Debug, Clone, PartialEq)]
pub enum Action {
    Make(Box<Make>),
    Call(Box<FuncCall>),
}

#[derive(Debug, Clone, PartialEq)]
pub struct Make {
    pub id: RhsTerm,
    pub attr: RhsTerm,
    pub value: RhsTerm,
    pub pref: PrefKind,
    pub referent: Option<RhsTerm>,
    pub span: PackedSpan,
}

#[derive(Debug, Clone, PartialEq)]
pub enum RhsTerm {
    Var(arcstr::ArcStr),
    Const(Constant),
    /// (Boxed: a call is rare, and inline it would double the size of every action.)
    Call(Box<FuncCall>),
}

#[derive(Debug, Clone, PartialEq)]
pub struct FuncCall {
    pub name: String,
    pub args: Vec<RhsTerm>,
    pub span: Span,
}

/// What compiling said besides the result: warnings and informational messages that Soar
/// prints while still adding the rule.
#[derive(Debug, Default)]
pub struct CompileOutput {
    pub warnings: Vec<Diagnostic>,
}

/// Placeholder variables `<s*1>` named after the attribute's first letter, counted per letter.
#[derive(Default)]
struct Placeholders<'a> {
    counters: FxHashMap<char, u32>,
    /// The variables the rule itself names, collected from `source` when the first
    /// placeholder is made (most rules need none).
    used: FxHashSet<&'a str>,
    source: Option<&'a ast::Production>,
    /// The placeholders made so far. Soar names them `<#a*1>` while parsing, so a letter taken
    /// from one is `#`, which is not a letter: the next placeholder is named after `v`.
    generated: FxHashSet<String>,
}

impl Placeholders<'_> {
    fn fresh(&mut self, letter: char) -> String {
        if let Some(p) = self.source.take() {
            collect_vars_ast(p, &mut self.used);
        }
        let letter = letter.to_ascii_lowercase();
        loop {
            let n = self.counters.entry(letter).or_insert(0);
            *n += 1;
            let name = format!("<{letter}*{n}>");
            if !self.used.contains(name.as_str()) && !self.generated.contains(&name) {
                self.generated.insert(name.clone());
                return name;
            }
        }
    }

    /// Soar's `first_letter_from_test`: the letter of the test's equality symbol (a
    /// variable's first letter, a string's first character, `i`/`f` for numbers), or `v`
    /// when that is not a letter.
    fn letter_of(&self, t: &Test) -> char {
        match t {
            Test::Equal(term) => self.letter_of_term(term),
            Test::Conjunction(ts) => ts
                .iter()
                .find_map(|t| match t {
                    Test::Equal(term) => Some(self.letter_of_term(term)),
                    _ => None,
                })
                .unwrap_or('v'),
            _ => 'v',
        }
    }

    fn letter_of_term(&self, term: &Term) -> char {
        match term {
            Term::Var(v) => self.letter_of_var(v),
            Term::Const(c) => letter_of_constant(c)
                .filter(char::is_ascii_alphabetic)
                .unwrap_or('v'),
        }
    }

    fn letter_of_var(&self, v: &str) -> char {
        let c = match v {
            v if self.generated.contains(v) => None,
            v => v.chars().nth(1),
        };
        c.filter(char::is_ascii_alphabetic).unwrap_or('v')
    }

    /// `first_letter_from_rhs_value`: as for tests; a function call gives `v`.
    fn letter_of_rhs(&self, t: &RhsTerm) -> char {
        match t {
            RhsTerm::Var(v) => self.letter_of_var(v),
            RhsTerm::Const(c) => letter_of_constant(c)
                .filter(char::is_ascii_alphabetic)
                .unwrap_or('v'),
            RhsTerm::Call(_) => 'v',
        }
    }
}

fn letter_of_constant(c: &Constant) -> Option<char> {
    match c {
        Constant::Str(s) => s.chars().next(),
        Constant::Int(_) => Some('i'),
        Constant::Float(_) => Some('f'),
    }
}

/// Compiles a parsed production, applying Soar's load-time checks. Errors reject the rule.
pub fn compile(p: &ast::Production, out: &mut CompileOutput) -> Result<Production, Diagnostic> {
    let flags = compile_flags(p)?;
    let mut ph = Placeholders {
        source: Some(p),
        ..Placeholders::default()
    };
    let mut conditions = Vec::new();
    for c in &p.conditions {
        compile_condition(c, &mut ph, &mut conditions, out)?;
    }
    let mut actions = Vec::new();
    for a in &p.actions {
        compile_action(a, &mut ph, &mut actions, out, &p.name)?;
    }
    // Kept for the rule's lifetime: no spare capacity (the reorderer sizes the conditions).
    actions.shrink_to_fit();
    drop_unbound_relational(&mut conditions, &FxHashSet::default(), (&p.name, p.span.file))?;
    let prod = Production {
        name: p.name.as_str().into(),
        doc: p.doc.as_deref().map(Box::from),
        flags,
        conditions: conditions.into(),
        actions: actions.into(),
        span: p.span,
    };
    check_roots(&prod, p, out)?;
    check_grounded(&prod, p)?;
    Ok(prod)
}

/// Only the conditions of a parsed rule, without the checks a loaded rule must pass (for
/// `production find`, which reads a pattern of conditions).
pub fn compile_conditions(p: &ast::Production) -> Result<Vec<Condition>, Diagnostic> {
    let mut ph = Placeholders {
        source: Some(p),
        ..Placeholders::default()
    };
    let mut out = CompileOutput::default();
    let mut conditions = Vec::new();
    for c in &p.conditions {
        compile_condition(c, &mut ph, &mut conditions, &mut out)?;
    }
    Ok(conditions)
}

fn compile_flags(p: &ast::Production) -> Result<Flags, Diagnostic> {
    let mut f = Flags::default();
    for (flag, span) in &p.flags {
        match flag.as_str() {
            ":o-support" => f.o_support = true,
            ":i-support" => f.i_support = true,
            ":chunk" => f.chunk = true,
            ":default" => f.default = true,
            ":template" => f.template = true,
            ":interrupt" => f.interrupt = true,
            ":explain" => f.explain = true,
            other => {
                let mut d = Diagnostic::error("Expected ( to begin condition element")
                    .at(*span)
                    .with_label(format!("`{other}` is not a production flag"));
                d = d.with_note(
                    "the flags are :o-support, :i-support, :chunk, :default, :template, :interrupt and :explain",
                );
                if other == ":no-support" {
                    d = d.with_note(
                        "`:no-support` is a Soar 8 flag that Soar 9.6 no longer accepts; remove it",
                    );
                }
                return Err(d);
            }
        }
    }
    Ok(f)
}

fn collect_vars_ast<'a>(p: &'a ast::Production, used: &mut FxHashSet<&'a str>) {
    fn test<'a>(t: &'a ast::Test, used: &mut FxHashSet<&'a str>) {
        match t {
            ast::Test::Equal(ast::Atom::Var(v), _)
            | ast::Test::Relational(_, ast::Atom::Var(v), _) => {
                used.insert(v);
            }
            ast::Test::Conjunction(ts, _) => ts.iter().for_each(|t| test(t, used)),
            _ => {}
        }
    }
    fn avt<'a>(a: &'a ast::AttrValueTests, used: &mut FxHashSet<&'a str>) {
        a.path.iter().for_each(|t| test(t, used));
        for v in &a.values {
            match v {
                ast::ValueTest::Test { test: t, .. } => test(t, used),
                ast::ValueTest::Structured { tests, .. } => tests.iter().for_each(|a| avt(a, used)),
            }
        }
    }
    fn cond<'a>(c: &'a ast::Condition, used: &mut FxHashSet<&'a str>) {
        match c {
            ast::Condition::Positive(c) | ast::Condition::Negative(c) => {
                if let Some(t) = &c.id_test {
                    test(t, used);
                }
                c.attr_value_tests.iter().for_each(|a| avt(a, used));
            }
            ast::Condition::Ncc(cs, _) => cs.iter().for_each(|c| cond(c, used)),
        }
    }
    fn rhs<'a>(v: &'a ast::RhsValue, used: &mut FxHashSet<&'a str>) {
        match v {
            ast::RhsValue::Var(name, _) => {
                used.insert(name);
            }
            ast::RhsValue::Call(f) => f.args.iter().for_each(|a| rhs(a, used)),
            ast::RhsValue::Const(..) => {}
        }
    }
    p.conditions.iter().for_each(|c| cond(c, used));
    for a in &p.actions {
        match a {
            ast::Action::Make { id, attrs, .. } => {
                rhs(id, used);
                for am in attrs {
                    am.path.iter().for_each(|v| rhs(v, used));
                    for vm in &am.values {
                        rhs(&vm.value, used);
                    }
                }
            }
            ast::Action::Call(f) => f.args.iter().for_each(|a| rhs(a, used)),
        }
    }
}

/// A simple test from the AST, applying 9.6's conjunction rules: one equality test at most
/// (a second is dropped with Soar's message), non-equality tests first.
fn compile_test(t: &ast::Test, out: &mut CompileOutput) -> Test {
    match t {
        ast::Test::Equal(a, _) => Test::Equal(term(a)),
        ast::Test::Relational(r, a, _) => Test::relational(*r, term(a)),
        ast::Test::Disjunction(cs, _) => Test::Disjunction(Box::new(cs.clone())),
        ast::Test::Conjunction(ts, span) => {
            let mut others = Vec::new();
            let mut eq: Option<Term> = None;
            for sub in ts {
                match compile_test(sub, out) {
                    Test::Equal(t) => match &eq {
                        None => eq = Some(t),
                        Some(existing) => {
                            // A constant equality test wins over a variable one.
                            // "constant" when a later constant replaces a variable.
                            let (keep, drop, which) = match (existing, &t) {
                                (Term::Var(_), Term::Const(_)) => {
                                    (t.clone(), existing.clone(), "constant")
                                }
                                _ => (existing.clone(), t.clone(), "existing"),
                            };
                            out.warnings.push(
                                Diagnostic::warning(format!(
                                    "Soar does not support having two equality tests in one conjunctive test!\nIgnoring {} in favor of {which} {}.  Rule semantics may have changed!",
                                    term_text(&drop),
                                    term_text(&keep)
                                ))
                                .at(*span)
                                .with_label("two equality tests"),
                            );
                            eq = Some(keep);
                        }
                    },
                    Test::Conjunction(inner) => others.extend(*inner),
                    other => others.push(other),
                }
            }
            if let Some(e) = eq {
                others.push(Test::Equal(e));
            }
            if others.len() == 1 {
                others.pop().unwrap_or_else(Test::placeholder)
            } else {
                Test::conjunction(others)
            }
        }
    }
}

fn term(a: &ast::Atom) -> Term {
    match a {
        ast::Atom::Var(v) => Term::Var(v.as_str().into()),
        ast::Atom::Const(c) => Term::Const(c.clone()),
    }
}

// ---------------------------------------------------------------------------------- text

// The text of one term, test or action as `print` shows it; the load-time messages below
// quote rules with it, and the printer lays whole rules out from it.

pub fn term_text(t: &Term) -> String {
    match t {
        Term::Var(v) => v.to_string(),
        Term::Const(c) => constant_text(c),
    }
}

pub fn test_text(t: &Test) -> String {
    match t {
        Test::Equal(term) => term_text(term),
        Test::Relational(rt) => format!("{} {}", rt.op.text(), term_text(&rt.term)),
        Test::Disjunction(cs) => {
            let mut s = String::from("<< ");
            for c in cs.iter() {
                s.push_str(&constant_text(c));
                s.push(' ');
            }
            s.push_str(">>");
            s
        }
        Test::Conjunction(ts) => {
            let items: Vec<String> = ts.iter().map(test_text).collect();
            format!("{{ {} }}", items.join(" "))
        }
    }
}

pub fn rhs_term_text(t: &RhsTerm) -> String {
    match t {
        RhsTerm::Var(v) => v.to_string(),
        RhsTerm::Const(c) => constant_text(c),
        RhsTerm::Call(f) => call_text(f),
    }
}

pub fn call_text(f: &FuncCall) -> String {
    // 9.6 prints the function names `+`, `-` and `*` bare but `/` in bars (observed).
    let name = if f.name == "/" {
        "|/|"
    } else {
        f.name.as_str()
    };
    let mut s = format!("({name}");
    for a in &f.args {
        s.push(' ');
        s.push_str(&rhs_term_text(a));
    }
    s.push(')');
    s
}

/// One make action alone, as in Soar's ungrounded-action message: `(<x> ^a 1 +)`.
pub fn make_text(m: &Make) -> String {
    make_text_with(m, rhs_term_text)
}

/// A make action with each term written by `term` (a firing's bindings, say).
pub fn make_text_with(m: &Make, term: impl Fn(&RhsTerm) -> String) -> String {
    let mut s = format!(
        "({} ^{} {} {}",
        term(&m.id),
        term(&m.attr),
        term(&m.value),
        m.pref.symbol()
    );
    if let Some(r) = &m.referent {
        s.push(' ');
        s.push_str(&term(r));
    }
    s.push(')');
    s
}

/// A test with an equality test: a placeholder variable is added when it binds nothing.
fn ensure_equality(t: Test, ph: &mut Placeholders, letter: char) -> Test {
    match t {
        Test::Equal(_) => t,
        Test::Conjunction(mut ts) => {
            if !matches!(ts.last(), Some(Test::Equal(_))) {
                ts.push(Test::Equal(Term::Var(ph.fresh(letter).into())));
            }
            Test::Conjunction(ts)
        }
        other => Test::conjunction(vec![other, Test::Equal(Term::Var(ph.fresh(letter).into()))]),
    }
}

fn compile_condition(
    c: &ast::Condition,
    ph: &mut Placeholders,
    dest: &mut Vec<Condition>,
    out: &mut CompileOutput,
) -> Result<(), Diagnostic> {
    match c {
        ast::Condition::Positive(c) => compile_cond_for_one_id(c, false, ph, dest, out),
        ast::Condition::Negative(c) => {
            let mut inner = Vec::new();
            compile_cond_for_one_id(c, false, ph, &mut inner, out)?;
            dest.extend(negate(inner));
            Ok(())
        }
        ast::Condition::Ncc(cs, _) => {
            let mut inner = Vec::new();
            for c in cs {
                compile_condition(c, ph, &mut inner, out)?;
            }
            dest.extend(negate(inner));
            Ok(())
        }
    }
}

/// Soar's `negate_condition_list`: a single condition toggles between positive and
/// negative (a single conjunctive negation is unwrapped); several become a conjunctive
/// negation. So `-{ (<s> ^a b) }` is the plain negation `-(<s> ^a b)`.
fn negate(mut inner: Vec<Condition>) -> Vec<Condition> {
    if inner.len() == 1 {
        match inner.pop() {
            Some(Condition::Positive(c)) => return vec![Condition::Negative(c)],
            Some(Condition::Negative(c)) => return vec![Condition::Positive(c)],
            Some(Condition::Ncc(cs)) => return cs,
            None => {}
        }
    }
    vec![Condition::Ncc(inner)]
}

fn compile_cond_for_one_id(
    c: &ast::CondForOneId,
    _negated: bool,
    ph: &mut Placeholders,
    dest: &mut Vec<Condition>,
    out: &mut CompileOutput,
) -> Result<(), Diagnostic> {
    if c.head != Head::None && c.attr_value_tests.is_empty() {
        return Err(Diagnostic::error(
            "Error: Expected attribute-value test after state/impasse test. Did you forget to add \"^type state\" or \"^superstate nil\"?",
        )
        .at(c.span)
        .with_label("this condition tests nothing"));
    }
    let id = match &c.id_test {
        Some(t) => {
            let test = compile_test(t, out);
            if let Some(k) = constant_equality(&test) {
                return Err(Diagnostic::error(format!(
                    "Warning: Constant {} in id field test.\n         This will never match.",
                    constant_text(&k)
                ))
                .at(t.span())
                .with_label("identifiers are matched by variables, never by constants"));
            }
            ensure_equality(test, ph, 's')
        }
        // A condition with no id test gets a placeholder named after `s` (parse_cond).
        None => Test::Equal(Term::Var(ph.fresh('s').into())),
    };
    if c.attr_value_tests.is_empty() {
        // `(<x>)` tests that <x> has some attribute: `(<x> ^<a*1> <v*1>)`.
        let attr = Test::Equal(Term::Var(ph.fresh('a').into()));
        let value = Test::Equal(Term::Var(ph.fresh('v').into()));
        dest.push(Condition::Positive(Cond {
            id,
            attr,
            value,
            acceptable: false,
            goal: c.head,
            span: c.span.into(),
        }));
        return Ok(());
    }
    for avt in &c.attr_value_tests {
        compile_attr_value_tests(&id, c.head, avt, ph, dest, out)?;
    }
    Ok(())
}

fn constant_equality(t: &Test) -> Option<Constant> {
    match t {
        Test::Equal(Term::Const(c)) => Some(c.clone()),
        Test::Conjunction(ts) => ts.iter().find_map(constant_equality),
        _ => None,
    }
}

fn compile_attr_value_tests(
    id: &Test,
    head: Head,
    avt: &ast::AttrValueTests,
    ph: &mut Placeholders,
    dest: &mut Vec<Condition>,
    out: &mut CompileOutput,
) -> Result<(), Diagnostic> {
    // Conditions made here go to `local`; a negated chain becomes one negation.
    let mut local = Vec::new();
    let mut cur_id = id.clone();
    let mut goal = head;
    // An attribute test with no equality test gets a placeholder `<a*N>`
    // (parse_attr_value_tests); each path step then links through a placeholder named
    // after the step's attribute.
    let mut attr = ensure_equality(compile_test(&avt.path[0], out), ph, 'a');
    for step in &avt.path[1..] {
        let v = Term::Var(ph.fresh(ph.letter_of(&attr)).into());
        local.push(Condition::Positive(Cond {
            id: cur_id.clone(),
            attr,
            value: Test::Equal(v.clone()),
            acceptable: false,
            goal,
            span: avt.span.into(),
        }));
        cur_id = Test::Equal(v);
        goal = Head::None;
        attr = ensure_equality(compile_test(step, out), ph, 'a');
    }
    let letter = ph.letter_of(&attr);
    let implicit;
    let values: &[ast::ValueTest] = if avt.values.is_empty() {
        implicit = [ast::ValueTest::Test {
            test: ast::Test::Equal(ast::Atom::Var(ph.fresh(letter)), avt.span),
            acceptable: false,
        }];
        &implicit
    } else {
        &avt.values
    };
    // The whole attribute test goes on the first condition, its equality test on the
    // others (fill_in_attr_tests).
    // (Not needed, so not copied, when there is one value.)
    let attr_eq = match &attr {
        _ if values.len() == 1 => Test::placeholder(),
        Test::Conjunction(ts) => ts
            .iter()
            .find(|t| matches!(t, Test::Equal(_)))
            .cloned()
            .unwrap_or_else(|| attr.clone()),
        other => other.clone(),
    };
    let mut first_attr = Some(attr);
    for (k, v) in values.iter().enumerate() {
        let attr = first_attr.take().unwrap_or_else(|| attr_eq.clone());
        // The last condition takes the id test itself.
        let id = if k + 1 == values.len() {
            std::mem::replace(&mut cur_id, Test::placeholder())
        } else {
            cur_id.clone()
        };
        match v {
            ast::ValueTest::Test { test, acceptable } => {
                // A value test that binds nothing gets a placeholder, as Soar prints it.
                let value = ensure_equality(compile_test(test, out), ph, letter);
                local.push(Condition::Positive(Cond {
                    id,
                    attr,
                    value,
                    acceptable: *acceptable,
                    goal,
                    span: avt.span.into(),
                }));
            }
            ast::ValueTest::Structured {
                tests, acceptable, ..
            } => {
                let pv = Term::Var(ph.fresh(letter).into());
                local.push(Condition::Positive(Cond {
                    id,
                    attr,
                    value: Test::Equal(pv.clone()),
                    acceptable: *acceptable,
                    goal,
                    span: avt.span.into(),
                }));
                for inner in tests {
                    compile_attr_value_tests(
                        &Test::Equal(pv.clone()),
                        Head::None,
                        inner,
                        ph,
                        &mut local,
                        out,
                    )?;
                }
            }
        }
    }
    let n = avt.path.len();
    if avt.negated {
        // `-^a v1 v2` negates each value; `-^a.b v` negates the chain as a whole.
        if n == 1
            && local.iter().all(|c| matches!(c, Condition::Positive(_)))
            && !has_structured(values)
        {
            for c in local {
                dest.extend(negate(vec![c]));
            }
        } else {
            dest.extend(negate(local));
        }
    } else {
        dest.extend(local);
    }
    Ok(())
}

fn has_structured(v: &[ast::ValueTest]) -> bool {
    v.iter()
        .any(|v| matches!(v, ast::ValueTest::Structured { .. }))
}

// ------------------------------------------------------------------------------- actions

fn compile_action(
    a: &ast::Action,
    ph: &mut Placeholders,
    dest: &mut Vec<Action>,
    out: &mut CompileOutput,
    rule: &str,
) -> Result<(), Diagnostic> {
    match a {
        ast::Action::Call(f) => {
            let call = compile_call(f, true, out, rule)?;
            dest.push(Action::Call(Box::new(call)));
            Ok(())
        }
        ast::Action::Make { id, attrs, span } => {
            let id_term = rhs_term(id, out, rule)?;
            for am in attrs {
                let mut cur = id_term.clone();
                let n = am.path.len();
                for step in &am.path[..n - 1] {
                    let step_attr = rhs_term(step, out, rule)?;
                    let v = RhsTerm::Var(ph.fresh(ph.letter_of_rhs(&step_attr)).into());
                    dest.push(Action::Make(Box::new(Make {
                        id: cur.clone(),
                        attr: step_attr,
                        value: v.clone(),
                        pref: PrefKind::Acceptable,
                        referent: None,
                        span: am.span.into(),
                    })));
                    cur = v;
                }
                let attr = rhs_term(&am.path[n - 1], out, rule)?;
                let is_operator =
                    matches!(&attr, RhsTerm::Const(Constant::Str(s)) if &**s == "operator");
                for vm in &am.values {
                    let value = rhs_term(&vm.value, out, rule)?;
                    const ACCEPTABLE: &[Pref] = &[Pref::Acceptable];
                    let prefs: &[Pref] = if vm.prefs.is_empty() {
                        ACCEPTABLE
                    } else {
                        &vm.prefs
                    };
                    // Non-operator attributes keep only `-` (one reject per `-`), else one
                    // acceptable; other unary preferences warn each time (the kernel's
                    // `parse_preferences_soar8_non_operator`).
                    let mut rejects = 0usize;
                    for pref in prefs {
                        let (kind, referent) = match pref {
                            Pref::Acceptable => (PrefKind::Acceptable, None),
                            Pref::Reject => (PrefKind::Reject, None),
                            Pref::Require => (PrefKind::Require, None),
                            Pref::Prohibit => (PrefKind::Prohibit, None),
                            Pref::Best => (PrefKind::Best, None),
                            Pref::Worst => (PrefKind::Worst, None),
                            Pref::Indifferent => (PrefKind::Indifferent, None),
                            Pref::Better(r) => (PrefKind::Better, Some(r)),
                            Pref::Worse(r) => (PrefKind::Worse, Some(r)),
                            Pref::BinaryIndifferent(r) => (PrefKind::BinaryIndifferent, Some(r)),
                            Pref::Numeric(r) => (PrefKind::NumericIndifferent, Some(r)),
                        };
                        if !is_operator {
                            if kind.is_binary() {
                                return Err(Diagnostic::error(format!(
                                    "ERROR: Binary preference illegal for non-operator.id = {}\t attr = {}\t value = {}",
                                    rhs_text(&id_term),
                                    rhs_text(&attr),
                                    rhs_text(&value)
                                ))
                                .at(am.span)
                                .with_label("binary preferences are allowed only on ^operator"));
                            }
                            match kind {
                                PrefKind::Acceptable => continue,
                                PrefKind::Reject => rejects += 1,
                                _ => {
                                    out.warnings.push(
                                        Diagnostic::warning(format!(
                                            "WARNING: The only allowable non-operator preference \nis REJECT - .\nIgnoring specified preferences.\nid = {}\t attr = {}\t value = {}",
                                            rhs_text(&id_term),
                                            rhs_text(&attr),
                                            rhs_text(&value)
                                        ))
                                        .at(am.span)
                                        .with_label("only + and - apply to attributes other than ^operator"),
                                    );
                                    continue;
                                }
                            }
                        }
                        let referent = match referent {
                            Some(r) => Some(rhs_term(r, out, rule)?),
                            None => None,
                        };
                        dest.push(Action::Make(Box::new(Make {
                            id: cur.clone(),
                            attr: attr.clone(),
                            value: value.clone(),
                            pref: kind,
                            referent,
                            span: (*span).into(),
                        })));
                    }
                    if !is_operator && rejects == 0 {
                        dest.push(Action::Make(Box::new(Make {
                            id: cur.clone(),
                            attr: attr.clone(),
                            value: value.clone(),
                            pref: PrefKind::Acceptable,
                            referent: None,
                            span: (*span).into(),
                        })));
                    }
                }
            }
            Ok(())
        }
    }
}

fn rhs_term(v: &ast::RhsValue, out: &mut CompileOutput, rule: &str) -> Result<RhsTerm, Diagnostic> {
    Ok(match v {
        ast::RhsValue::Var(name, _) => RhsTerm::Var(name.as_str().into()),
        ast::RhsValue::Const(c, _) => RhsTerm::Const(c.clone()),
        ast::RhsValue::Call(f) => RhsTerm::Call(Box::new(compile_call(f, false, out, rule)?)),
    })
}

/// Checks a call against the built-in table; an unknown name becomes `exec name ...` with
/// Soar's message.
fn compile_call(
    f: &ast::FuncCall,
    standalone: bool,
    out: &mut CompileOutput,
    rule: &str,
) -> Result<FuncCall, Diagnostic> {
    let mut args = Vec::with_capacity(f.args.len() + 1);
    let name = match table::lookup(&f.name) {
        Some(info) => {
            if let Some(n) = info.arity {
                if n != f.args.len() {
                    return Err(Diagnostic::error(format!(
                        "Wrong number of arguments to function {} (expected {})",
                        f.name, n
                    ))
                    .at(f.span)
                    .with_label(format!("{} argument(s) given", f.args.len())));
                }
            }
            match (standalone, info.usage) {
                (true, Use::Value) => {
                    return Err(Diagnostic::error(format!(
                        "Function {} cannot be used as a stand-alone action",
                        f.name
                    ))
                    .at(f.span)
                    .with_label("its value would be thrown away"))
                }
                (false, Use::Standalone) => {
                    return Err(Diagnostic::error(format!(
                        "Function {} can only be used as a stand-alone action",
                        f.name
                    ))
                    .at(f.span)
                    .with_label("it returns no value"))
                }
                _ => {}
            }
            info.name.to_string()
        }
        None => {
            out.warnings.push(
                Diagnostic::warning(format!("Adding exec to RHS function: {}", f.name))
                    .at(f.name_span)
                    .with_label(format!("read as (exec {} ...)", f.name))
                    .with_note(format!("in production {rule}")),
            );
            args.push(RhsTerm::Const(Constant::Str(f.name.as_str().into())));
            "exec".to_string()
        }
    };
    for a in &f.args {
        args.push(rhs_term(a, out, rule)?);
    }
    Ok(FuncCall {
        name,
        args,
        span: f.span,
    })
}

fn rhs_text(t: &RhsTerm) -> String {
    rhs_term_text(t)
}

// --------------------------------------------------------------------------------- checks

fn equality_var(t: &Test) -> Option<&str> {
    match t {
        Test::Equal(Term::Var(v)) => Some(v),
        Test::Conjunction(ts) => ts.iter().find_map(equality_var),
        _ => None,
    }
}

/// Conditions must hang from a state (Soar manual, chapter 3, "The condition side of productions
/// (or LHS)"), as the kernel's reorderer checks it (`collect_root_variables`,
/// `reorder_lhs`): the roots are the variables in the id field of a positive condition that
/// are not the value of another positive condition. A root with no `(state ...)` or
/// `(impasse ...)` test warns; a rule with no root at all must have a positive goal test,
/// or it is rejected. Conjunctive negations are checked the same way, with the outer
/// variables counted bound.
fn check_roots(
    p: &Production,
    ast: &ast::Production,
    out: &mut CompileOutput,
) -> Result<(), Diagnostic> {
    let roots = root_variables(&p.conditions, &FxHashSet::default(), (&p.name, ast.span.file), out);
    if !roots.is_empty() {
        return Ok(());
    }
    let has_goal = p.conditions.iter().any(|c| {
        matches!(c, Condition::Positive(c) if c.goal != Head::None && equality_var(&c.id).is_some())
    });
    if has_goal {
        return Ok(());
    }
    Err(Diagnostic::error(format!(
        "Error: production {} has no positive conditions that reference a goal state.\nDid you forget to add \"^type state\" or \"^superstate nil\"?",
        p.name
    ))
    .at(ast.name_span)
    .with_label("no positive condition of this rule tests a state, so nothing connects it to working memory"))
}

/// The root variables of one condition list (see [`check_roots`]), warning for each root
/// that is not tested as a state or impasse, then recursing into conjunctive negations.
fn root_variables<'a>(
    conds: &'a [Condition],
    outside: &FxHashSet<&'a str>,
    (name, file): (&str, FileId),
    out: &mut CompileOutput,
) -> Vec<&'a str> {
    let positives: Vec<&Cond> = conds
        .iter()
        .filter_map(|c| match c {
            Condition::Positive(c) => Some(c),
            _ => None,
        })
        .collect();
    let mut in_value = Names::for_at_most(positives.len());
    for v in positives.iter().filter_map(|c| equality_var(&c.value)) {
        in_value.insert(v);
    }
    let mut roots: Vec<&str> = Vec::new();
    for c in &positives {
        if let Some(id) = equality_var(&c.id) {
            if !outside.contains(id) && !in_value.contains(id) && !roots.contains(&id) {
                roots.push(id);
            }
        }
    }
    for root in &roots {
        let tested_as_goal = positives
            .iter()
            .any(|c| c.goal != Head::None && equality_var(&c.id) == Some(root));
        if tested_as_goal {
            continue;
        }
        if let Some(c) = positives.iter().find(|c| equality_var(&c.id) == Some(root)) {
            out.warnings.push(
                Diagnostic::warning(format!(
                    "Warning: On the LHS of production {name}, identifier {root} is not connected to any goal or impasse."
                ))
                .at(c.span.in_file(file))
                .with_label("no chain of conditions links this identifier to a state"),
            );
        }
    }
    if !conds.iter().any(|c| matches!(c, Condition::Ncc(_))) {
        return roots;
    }
    let mut bound = outside.clone();
    for c in &positives {
        for t in [&c.id, &c.attr, &c.value] {
            if let Some(v) = equality_var(t) {
                bound.insert(v);
            }
        }
    }
    for c in conds {
        if let Condition::Ncc(inner) = c {
            root_variables(inner, &bound, (name, file), out);
        }
    }
    roots
}

/// As the kernel's reorderer does it: a relational test on a variable that no positive
/// condition binds (at this level or outside it) can never be evaluated. In a positive
/// condition it is dropped silently; in a negated condition it is an error
/// (`check_negative_relational_test_bindings`).
fn drop_unbound_relational(
    conds: &mut [Condition],
    outside: &FxHashSet<String>,
    (name, file): (&str, FileId),
) -> Result<(), Diagnostic> {
    // Most lists have no relational test on a variable: nothing to check, no set to build.
    let relational = |t: &Test| match t {
        Test::Relational(rt) => matches!(rt.term, Term::Var(_)),
        Test::Conjunction(ts) => ts
            .iter()
            .any(|m| matches!(m, Test::Relational(rt) if matches!(rt.term, Term::Var(_)))),
        _ => false,
    };
    let anything = conds.iter().any(|c| match c {
        Condition::Positive(c) | Condition::Negative(c) => {
            relational(&c.id) || relational(&c.attr) || relational(&c.value)
        }
        Condition::Ncc(_) => true,
    });
    if !anything {
        return Ok(());
    }
    let mut bound = outside.clone();
    for c in conds.iter() {
        if let Condition::Positive(c) = c {
            for t in [&c.id, &c.attr, &c.value] {
                if let Some(v) = equality_var(t) {
                    bound.insert(v.to_string());
                }
            }
        }
    }
    let unbound = |t: &Test| matches!(t, Test::Relational(rt) if matches!(&rt.term, Term::Var(v) if !bound.contains(&**v)));
    for c in conds.iter_mut() {
        match c {
            Condition::Positive(c) => {
                for t in [&mut c.id, &mut c.attr, &mut c.value] {
                    if let Test::Conjunction(ts) = t {
                        ts.retain(|m| !unbound(m));
                        if let [only] = ts.as_slice() {
                            *t = only.clone();
                        }
                    }
                }
            }
            Condition::Negative(c) => {
                for t in [&c.id, &c.attr, &c.value] {
                    let members = match t {
                        Test::Conjunction(ts) => ts.as_slice(),
                        other => std::slice::from_ref(other),
                    };
                    if let Some(rel) = members.iter().find(|m| unbound(m)) {
                        return Err(Diagnostic::error(format!(
                            "Error: production {name} has an unbound referent in negated relational test {}.",
                            test_text(rel)
                        ))
                        .at(c.span.in_file(file))
                        .with_label("no positive condition binds this variable")
                        .with_note("Attempted to add an invalid rule:\n      Unbound relational test in negative condition of rule"));
                    }
                }
            }
            Condition::Ncc(inner) => drop_unbound_relational(inner, &bound, (name, file))?,
        }
    }
    Ok(())
}

/// A set of variable names: a list for the few of a typical rule (no hashing, one small
/// allocation), a hash set for many.
pub(crate) enum Names<'a> {
    Few(Vec<&'a str>),
    Many(FxHashSet<&'a str>),
}

impl<'a> Names<'a> {
    /// A set for at most `n` names.
    pub(crate) fn for_at_most(n: usize) -> Self {
        if n <= 32 {
            Names::Few(Vec::with_capacity(n))
        } else {
            Names::Many(FxHashSet::default())
        }
    }

    pub(crate) fn insert(&mut self, v: &'a str) {
        match self {
            Names::Few(l) => {
                if !l.contains(&v) {
                    l.push(v);
                }
            }
            Names::Many(s) => {
                s.insert(v);
            }
        }
    }

    pub(crate) fn contains(&self, v: &str) -> bool {
        match self {
            Names::Few(l) => l.contains(&v),
            Names::Many(s) => s.contains(v),
        }
    }

}

fn bound_names(p: &Production) -> Names<'_> {
    let mut bound = Names::for_at_most(3 * p.conditions.len());
    for c in p.conditions.iter() {
        if let Condition::Positive(c) = c {
            for t in [&c.id, &c.attr, &c.value] {
                if let Some(v) = equality_var(t) {
                    bound.insert(v);
                }
            }
        }
    }
    bound
}

fn term_vars<'a>(t: &'a RhsTerm, in_call: bool, acc: &mut Vec<(&'a str, bool)>) {
    match t {
        RhsTerm::Var(v) => acc.push((v, in_call)),
        RhsTerm::Call(f) => f.args.iter().for_each(|a| term_vars(a, true, acc)),
        RhsTerm::Const(_) => {}
    }
}

/// The variables of an action, each with whether it must be bound before the action can be
/// carried out (an id, a function's argument) or is made by it when unbound.
fn action_vars<'a>(a: &'a Action, acc: &mut Vec<(&'a str, bool)>) {
    match a {
        Action::Make(m) => {
            term_vars(&m.id, true, acc);
            for t in [&m.attr, &m.value].into_iter().chain(m.referent.as_ref()) {
                term_vars(t, false, acc);
            }
        }
        Action::Call(f) => f.args.iter().for_each(|a| term_vars(a, true, acc)),
    }
}

/// RHS action ids and function arguments must be bound on the LHS or be new identifiers
/// made by an action that can itself be carried out (an unbound variable in its attribute,
/// value or referent). As 9.6 orders a rule's actions, an action is placed once what it
/// needs is bound, and then binds all its variables; the actions never placed are
/// ungrounded, so `(<r> ^self <r>)` alone does not ground `<r>`.
fn check_grounded(p: &Production, ast: &ast::Production) -> Result<(), Diagnostic> {
    let bound = bound_names(p);
    let mut new_ids: FxHashSet<&str> = FxHashSet::default();
    let mut placed = vec![false; p.actions.len()];
    let mut vars = Vec::new();
    loop {
        let mut progress = false;
        for (a, done) in p.actions.iter().zip(placed.iter_mut()) {
            if *done {
                continue;
            }
            vars.clear();
            action_vars(a, &mut vars);
            if vars
                .iter()
                .any(|(v, must)| *must && !bound.contains(v) && !new_ids.contains(v))
            {
                continue;
            }
            *done = true;
            progress = true;
            new_ids.extend(vars.iter().map(|(v, _)| *v));
        }
        if !progress {
            break;
        }
    }
    let mut bad: Vec<(String, Span)> = Vec::new();
    let mut seen: FxHashSet<String> = FxHashSet::default();
    for (a, _) in p.actions.iter().zip(&placed).filter(|(_, done)| !**done) {
        // The text only for the message: printing every action of every rule costs.
        let (text, span) = match a {
            Action::Make(m) => (make_text(m), m.span.in_file(p.span.file)),
            Action::Call(f) => (call_text(f), f.span),
        };
        if seen.insert(text.clone()) {
            bad.push((text, span));
        }
    }
    if bad.is_empty() {
        return Ok(());
    }
    let mut msg = String::from(
        "Attempted to add rule with ungrounded action(s).\nThe following RHS actions contain variables that are not tested\nin a positive condition on the LHS: \n",
    );
    for (t, _) in &bad {
        msg.push_str(&format!("\n        {t}\n"));
    }
    let mut d = Diagnostic::error(msg.trim_end().to_string())
        .at(bad[0].1)
        .with_label("uses a variable the conditions never bind");
    for (_, s) in bad.iter().skip(1) {
        d = d.with_secondary(*s, "also ungrounded");
    }
    let _ = ast;
    Ok(()).and(Err(d))
}
