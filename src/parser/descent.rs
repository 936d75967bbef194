//! The fast path of [`super::parse_production`]: a recursive-descent reading of
//! `grammar/soar.lalrpop`, one method per nonterminal, one token of lookahead.
//!
//! It only has to be right on well-formed rules: on anything the grammar rejects (or a
//! lexing error) it gives up with `None`, and the lalrpop parser reads the text again to
//! produce the diagnostic. So it must never accept what the grammar rejects, and must
//! build the same tree, spans included: a span runs from the start of its first token to
//! the end of its last one (lalrpop's `@L` ... `@R`).
//!
//! Recursion (function calls, structured values, condition groups) goes one level per `(`
//! or `{`, which the lexer caps at `lexer::MAX_NESTING`.

use crate::ast::{
    Action, Atom, AttrMake, AttrValueTests, CondForOneId, Condition, Constant, FuncCall, Head,
    Production, Relation, RhsValue, Test, ValueItem, ValueTest,
};
use crate::lexer::{upcase_identifier, Lexer, Tok};
use crate::source::{FileId, Span};

/// Parses an `sp` body, or `None` if the grammar would not accept it.
pub(super) fn parse(lexer: Lexer<'_, '_>, file: FileId) -> Option<Production> {
    let mut p = Parser::new(lexer, file);
    let prod = p.production()?;
    // A lexing error ends the token stream early; what came before may have parsed.
    (!p.lex_failed).then_some(prod)
}

/// `None`: the grammar rejects the input here.
type R<T> = Option<T>;

struct Parser<'a, 'w> {
    lexer: Lexer<'a, 'w>,
    file: FileId,
    /// The lookahead token and its span; `None` at the end of the input.
    tok: Option<Tok>,
    start: usize,
    end: usize,
    /// End of the last token consumed: where a span that ends "here" ends.
    prev_end: usize,
    lex_failed: bool,
}

impl<'a, 'w> Parser<'a, 'w> {
    fn new(lexer: Lexer<'a, 'w>, file: FileId) -> Self {
        let mut p = Parser {
            lexer,
            file,
            tok: None,
            start: 0,
            end: 0,
            prev_end: 0,
            lex_failed: false,
        };
        p.advance();
        p
    }

    fn advance(&mut self) {
        self.tok = match self.lexer.next() {
            Some(Ok((s, t, e))) => {
                self.start = s;
                self.end = e;
                Some(t)
            }
            Some(Err(_)) => {
                self.lex_failed = true;
                None
            }
            None => None,
        };
    }

    fn peek(&self) -> Option<&Tok> {
        self.tok.as_ref()
    }

    /// Consumes the lookahead token (`None` at the end), returning it with its start.
    fn bump(&mut self) -> R<(usize, Tok)> {
        let t = self.tok.take()?;
        let start = self.start;
        self.prev_end = self.end;
        self.advance();
        Some((start, t))
    }

    /// Consumes `want` (a token without payload) or rejects; returns its start.
    fn expect(&mut self, want: &Tok) -> R<usize> {
        if self.tok.as_ref() == Some(want) {
            self.bump().map(|(s, _)| s)
        } else {
            None
        }
    }

    fn eat(&mut self, want: &Tok) -> bool {
        self.tok.as_ref() == Some(want) && self.bump().is_some()
    }

    /// From `start` to the end of the last token consumed.
    fn span(&self, start: usize) -> Span {
        Span::new(self.file, start, self.prev_end)
    }

    // ------------------------------------------------------------------ production

    fn production(&mut self) -> R<Production> {
        let l = self.start;
        let (name, name_span) = self.prod_name()?;
        let doc = match self.peek() {
            Some(Tok::Doc(_)) => match self.bump()? {
                (_, Tok::Doc(d)) => Some(d),
                _ => None,
            },
            _ => None,
        };
        let mut flags = Vec::new();
        while let Some(Tok::Sym(_)) = self.peek() {
            if let (s, Tok::Sym(f)) = self.bump()? {
                flags.push((f, self.span(s)));
            }
        }
        let conditions = self.conditions()?;
        let al = self.expect(&Tok::Arrow)?;
        let arrow = self.span(al);
        let mut actions = Vec::new();
        while self.peek().is_some() {
            actions.push(self.action()?);
        }
        Some(Production {
            name,
            name_span,
            doc,
            flags,
            conditions,
            arrow,
            actions,
            span: self.span(l),
        })
    }

    /// Symbols, |quoted| names and the keywords; other tokens get the grammar's own
    /// message, so they are left to it.
    fn prod_name(&mut self) -> R<(String, Span)> {
        let (s, t) = self.bump()?;
        let name = match t {
            Tok::Sym(s) | Tok::Quoted(s) => s,
            Tok::KwState => "state".to_string(),
            Tok::KwImpasse => "impasse".to_string(),
            _ => return None,
        };
        Some((name, self.span(s)))
    }

    // ------------------------------------------------------------------ conditions

    /// `CondItem+`, flattening brace groups into the list.
    fn conditions(&mut self) -> R<Vec<Condition>> {
        let mut out = Vec::new();
        loop {
            match self.peek() {
                Some(Tok::LParen) => out.push(Condition::Positive(self.cond_for_one_id()?)),
                Some(Tok::Minus) => {
                    let (l, _) = self.bump()?;
                    match self.peek() {
                        Some(Tok::LParen) => {
                            out.push(Condition::Negative(self.cond_for_one_id()?));
                        }
                        Some(Tok::LBrace) => {
                            let cs = self.brace_group()?;
                            out.push(Condition::Ncc(cs, self.span(l)));
                        }
                        _ => return None,
                    }
                }
                Some(Tok::LBrace) => out.extend(self.brace_group()?),
                _ => break,
            }
        }
        // Every item holds at least one condition, so an empty list means no items.
        (!out.is_empty()).then_some(out)
    }

    /// `{ <cond>+ }`
    fn brace_group(&mut self) -> R<Vec<Condition>> {
        self.expect(&Tok::LBrace)?;
        let cs = self.conditions()?;
        self.expect(&Tok::RBrace)?;
        Some(cs)
    }

    fn cond_for_one_id(&mut self) -> R<CondForOneId> {
        let l = self.expect(&Tok::LParen)?;
        // Right after `(`, `state` and `impasse` are always the head keywords.
        let head = match self.peek() {
            Some(Tok::KwState) => Head::State,
            Some(Tok::KwImpasse) => Head::Impasse,
            _ => Head::None,
        };
        if head != Head::None {
            self.bump()?;
        }
        let id_test = match self.peek() {
            Some(Tok::KwState | Tok::KwImpasse) => return None,
            Some(t) if starts_test(t) => Some(self.test()?),
            _ => None,
        };
        let attr_value_tests = self.attr_value_tests_list()?;
        self.expect(&Tok::RParen)?;
        Some(CondForOneId {
            head,
            id_test,
            attr_value_tests,
            span: self.span(l),
        })
    }

    /// `AttrValueTests*`
    fn attr_value_tests_list(&mut self) -> R<Vec<AttrValueTests>> {
        let mut out = Vec::new();
        while let Some(Tok::Minus | Tok::Caret) = self.peek() {
            out.push(self.attr_value_tests()?);
        }
        Some(out)
    }

    /// `[-]^a.b.c v1 v2 ...`
    fn attr_value_tests(&mut self) -> R<AttrValueTests> {
        let l = self.start;
        let negated = self.eat(&Tok::Minus);
        self.expect(&Tok::Caret)?;
        let mut path = vec![self.test()?];
        while self.eat(&Tok::Dot) {
            path.push(self.test()?);
        }
        let mut values = Vec::new();
        loop {
            match self.peek() {
                Some(Tok::LParen) => {
                    let vl = self.start;
                    self.bump()?;
                    let tests = self.attr_value_tests_list()?;
                    if tests.is_empty() {
                        return None;
                    }
                    self.expect(&Tok::RParen)?;
                    let span = self.span(vl);
                    let acceptable = self.eat(&Tok::Plus);
                    values.push(ValueTest::Structured {
                        tests,
                        acceptable,
                        span,
                    });
                }
                Some(t) if starts_test(t) => {
                    let test = self.test()?;
                    let acceptable = self.eat(&Tok::Plus);
                    values.push(ValueTest::Test { test, acceptable });
                }
                _ => break,
            }
        }
        Some(AttrValueTests {
            negated,
            path,
            values,
            span: self.span(l),
        })
    }

    /// `SimpleTest` or `{ SimpleTest+ }`.
    fn test(&mut self) -> R<Test> {
        if self.peek() != Some(&Tok::LBrace) {
            return self.simple_test();
        }
        let (l, _) = self.bump()?;
        let mut tests = Vec::new();
        while self.peek() != Some(&Tok::RBrace) {
            tests.push(self.simple_test()?);
        }
        if tests.is_empty() {
            return None;
        }
        self.bump()?;
        Some(Test::Conjunction(tests, self.span(l)))
    }

    fn simple_test(&mut self) -> R<Test> {
        let (l, t) = self.bump()?;
        Some(match t {
            Tok::Eq => Test::Equal(self.atom()?, self.span(l)),
            Tok::LtLt => {
                let mut cs = Vec::new();
                loop {
                    match self.bump()? {
                        (_, Tok::GtGt) => break,
                        (_, t) => cs.push(constant(t)?),
                    }
                }
                Test::Disjunction(cs, self.span(l))
            }
            t => match relation(&t) {
                Some(op) => Test::Relational(op, self.atom()?, self.span(l)),
                None => Test::Equal(atom(t)?, self.span(l)),
            },
        })
    }

    fn atom(&mut self) -> R<Atom> {
        atom(self.bump()?.1)
    }

    // ------------------------------------------------------------------ actions

    fn action(&mut self) -> R<Action> {
        let l = self.expect(&Tok::LParen)?;
        match self.peek() {
            Some(Tok::Var(_) | Tok::Ident(_)) => {}
            _ => return Some(Action::Call(self.call_after_paren(l)?)),
        }
        let id = match self.bump()? {
            (s, Tok::Var(v)) => RhsValue::Var(v, self.span(s)),
            (s, Tok::Ident(i)) => {
                RhsValue::Const(Constant::Str(upcase_identifier(&i).into()), self.span(s))
            }
            _ => return None,
        };
        let mut attrs = Vec::new();
        while self.peek() == Some(&Tok::Caret) {
            attrs.push(self.attr_make()?);
        }
        self.expect(&Tok::RParen)?;
        Some(Action::Make {
            id,
            attrs,
            span: self.span(l),
        })
    }

    /// `^a.b value prefs...`
    fn attr_make(&mut self) -> R<AttrMake> {
        let l = self.expect(&Tok::Caret)?;
        let mut path = vec![self.rhs_value()?];
        while self.eat(&Tok::Dot) {
            path.push(self.rhs_value()?);
        }
        let first = self.rhs_value()?;
        let mut rest = Vec::new();
        loop {
            let item = match self.peek() {
                Some(t) if starts_rhs_value(t) => ValueItem::Value(self.rhs_value()?),
                Some(t) => {
                    let Some(make) = pref_item(t) else { break };
                    let (s, _) = self.bump()?;
                    make(self.span(s))
                }
                None => break,
            };
            rest.push(item);
        }
        Some(AttrMake {
            path,
            values: super::attach_preferences(first, rest),
            span: self.span(l),
        })
    }

    fn rhs_value(&mut self) -> R<RhsValue> {
        let (s, t) = self.bump()?;
        Some(match t {
            Tok::LParen => RhsValue::Call(Box::new(self.call_after_paren(s)?)),
            Tok::Var(v) => RhsValue::Var(v, self.span(s)),
            t => RhsValue::Const(constant(t)?, self.span(s)),
        })
    }

    /// A function call whose `(` (at `l`) is consumed: `name args... )`.
    fn call_after_paren(&mut self, l: usize) -> R<FuncCall> {
        let (nl, t) = self.bump()?;
        let name = match t {
            Tok::Sym(s) | Tok::Quoted(s) => s,
            Tok::Plus => "+".to_string(),
            Tok::Minus => "-".to_string(),
            _ => return None,
        };
        let name_span = self.span(nl);
        let mut args = Vec::new();
        while self.peek().is_some_and(starts_rhs_value) {
            args.push(self.rhs_value()?);
        }
        self.expect(&Tok::RParen)?;
        Some(FuncCall {
            name,
            name_span,
            args,
            span: self.span(l),
        })
    }
}

/// Tokens that begin a `Test`.
fn starts_test(t: &Tok) -> bool {
    is_atom(t) || relation(t).is_some() || matches!(t, Tok::Eq | Tok::LtLt | Tok::LBrace)
}

/// Tokens that begin an `RhsValue`.
fn starts_rhs_value(t: &Tok) -> bool {
    is_atom(t) || *t == Tok::LParen
}

fn is_atom(t: &Tok) -> bool {
    matches!(
        t,
        Tok::Var(_)
            | Tok::Sym(_)
            | Tok::Ident(_)
            | Tok::Quoted(_)
            | Tok::Int(_)
            | Tok::Float(_)
            | Tok::KwState
            | Tok::KwImpasse
    )
}

fn relation(t: &Tok) -> Option<Relation> {
    Some(match t {
        Tok::Ne => Relation::Ne,
        Tok::Lt => Relation::Lt,
        Tok::Le => Relation::Le,
        Tok::Gt => Relation::Gt,
        Tok::Ge => Relation::Ge,
        Tok::SameType => Relation::SameType,
        _ => return None,
    })
}

fn atom(t: Tok) -> R<Atom> {
    match t {
        Tok::Var(v) => Some(Atom::Var(v)),
        t => constant(t).map(Atom::Const),
    }
}

/// `Constant`: identifier-shaped lexemes are upper-cased, keywords are plain strings.
fn constant(t: Tok) -> R<Constant> {
    Some(match t {
        Tok::Sym(s) | Tok::Quoted(s) => Constant::Str(s.into()),
        Tok::Ident(s) => Constant::Str(upcase_identifier(&s).into()),
        Tok::Int(i) => Constant::Int(i),
        Tok::Float(f) => Constant::Float(f),
        Tok::KwState => Constant::Str("state".into()),
        Tok::KwImpasse => Constant::Str("impasse".into()),
        _ => return None,
    })
}

/// The preference items of a value list (`ValueItem` minus values).
fn pref_item(t: &Tok) -> Option<fn(Span) -> ValueItem> {
    Some(match t {
        Tok::Plus => ValueItem::Plus,
        Tok::Minus => ValueItem::Minus,
        Tok::Bang => ValueItem::Bang,
        Tok::Tilde => ValueItem::Tilde,
        Tok::Gt => ValueItem::Gt,
        Tok::Lt => ValueItem::Lt,
        Tok::Eq => ValueItem::Eq,
        Tok::Comma => ValueItem::Comma,
        _ => return None,
    })
}
