//! The production parser: one entry point, [`parse_production`], over the lalrpop grammar in
//! `grammar/soar.lalrpop`. Grammar errors are translated to Soar's own messages.
//!
//! Two parsers read that grammar. The hand-written recursive descent in `descent` is the
//! fast path: it builds the tree in less than half the time of the LR state machine, which
//! was a third of the time to load 100,000 rules. It gives up on anything the grammar
//! rejects, and then the lalrpop parser reads the text again, only to give the error:
//! its expected-token sets choose Soar's message and the "expected one of" note, which a
//! second, hand-kept copy would drift from. `tests` checks that both build the same trees.

use crate::ast::{Pref, RhsValue, ValueItem, ValueMake};
use crate::lexer::{self, Tok};
use crate::source::{Diagnostic, FileId, Span};

lalrpop_util::lalrpop_mod!(
    #[allow(clippy::all, clippy::pedantic, unused)]
    grammar,
    "/soar.rs"
);

mod descent;
#[cfg(test)]
mod tests;

/// Parses the inside of an `sp {...}` body. `offset` is the file offset of `text`'s first byte.
/// Warnings (e.g. `bad integer`) go to `warnings`; the first error is returned.
pub fn parse_production(
    text: &str,
    file: FileId,
    offset: usize,
    warnings: &mut Vec<Diagnostic>,
) -> Result<crate::ast::Production, Diagnostic> {
    let before = warnings.len();
    if let Some(p) = descent::parse(lexer::Lexer::new(text, offset, file, warnings), file) {
        return Ok(p);
    }
    // Rejected: the lalrpop pass lexes again and re-reports the warnings up to the error,
    // so the first pass's ones go.
    warnings.truncate(before);
    parse_with_lalrpop(text, file, offset, warnings)
}

/// The LR parser over the same text: the same tree as the fast path, and the diagnostics.
fn parse_with_lalrpop(
    text: &str,
    file: FileId,
    offset: usize,
    warnings: &mut Vec<Diagnostic>,
) -> Result<crate::ast::Production, Diagnostic> {
    let end = offset + text.len();
    // Tokens stream into the parser; a lexing error travels as a grammar "user" error.
    let mut tokens = lexer::Lexer::new(text, offset, file, warnings)
        .map(|t| t.map_err(|e| format!("@{}:{}:{}", e.start, e.end, e.message)))
        .peekable();
    if tokens.peek().is_none() {
        return Err(Diagnostic::error("Expected symbol for production name")
            .at(Span::new(file, offset, end))
            .with_label("the production body is empty"));
    }
    let parser = grammar::ProductionParser::new();
    parser.parse(file, tokens).map(|p| *p).map_err(|e| {
        // Only on the error path: the tokens before the error, to tell which side of
        // `-->` and how deep in parentheses it happened.
        let location = match &e {
            lalrpop_util::ParseError::UnrecognizedToken {
                token: (l, _, _), ..
            } => *l,
            lalrpop_util::ParseError::UnrecognizedEof { .. } => end,
            _ => offset,
        };
        let cut = crate::source::clamp_to_char_boundary(text, location.saturating_sub(offset));
        let mut scratch = Vec::new();
        let before: Vec<lexer::Spanned> =
            lexer::Lexer::new(&text[..cut], offset, file, &mut scratch)
                .map_while(Result::ok)
                .collect();
        translate_error(e, &before, file, end)
    })
}

type LalrError = lalrpop_util::ParseError<usize, Tok, String>;

/// Turns an LR error into Soar's wording, pointing at the offending token.
fn translate_error(
    err: LalrError,
    tokens: &[lexer::Spanned],
    file: FileId,
    end: usize,
) -> Diagnostic {
    use lalrpop_util::ParseError as P;
    match err {
        P::User { error } => {
            // "@start:end:message" from a fallible grammar action.
            let mut parts = error.splitn(4, ':');
            let start = parts
                .next()
                .and_then(|s| s.trim_start_matches('@').parse().ok())
                .unwrap_or(0);
            let stop = parts.next().and_then(|s| s.parse().ok()).unwrap_or(start);
            let msg = parts.collect::<Vec<_>>().join(":");
            Diagnostic::error(msg)
                .at(Span::new(file, start, stop))
                .with_label("here")
        }
        P::UnrecognizedEof { location, expected } => {
            let msg = soar_message(&expected, tokens, location);
            Diagnostic::error(msg)
                .at(Span::new(file, end, end))
                .with_label("the production ends here")
                .with_note(expected_note(&expected))
        }
        P::UnrecognizedToken {
            token: (l, tok, r),
            expected,
        } => {
            let msg = soar_message(&expected, tokens, l);
            Diagnostic::error(msg)
                .at(Span::new(file, l, r))
                .with_label(format!("unexpected `{}`", tok.describe()))
                .with_note(expected_note(&expected))
        }
        P::ExtraToken { token: (l, tok, r) } => {
            Diagnostic::error("Unexpected token after production")
                .at(Span::new(file, l, r))
                .with_label(format!("unexpected `{}`", tok.describe()))
        }
        P::InvalidToken { location } => Diagnostic::error("Invalid token")
            .at(Span::new(file, location, location + 1))
            .with_label("here"),
    }
}

fn expected_note(expected: &[String]) -> String {
    let names: Vec<String> = expected.iter().map(|e| pretty_terminal(e)).collect();
    format!("expected one of: {}", names.join(", "))
}

fn pretty_terminal(t: &str) -> String {
    match t {
        "\"var\"" => "a variable".into(),
        "\"sym\"" => "a symbol".into(),
        "\"ident\"" => "an identifier-shaped constant".into(),
        "\"int\"" => "an integer".into(),
        "\"float\"" => "a float".into(),
        "\"quoted\"" => "a |quoted| constant".into(),
        "\"doc\"" => "a \"documentation\" string".into(),
        other => format!("`{}`", other.trim_matches('"')),
    }
}

/// Which side of `-->` a location is on, found from the token list.
fn on_rhs(tokens: &[lexer::Spanned], location: usize) -> bool {
    tokens
        .iter()
        .any(|(s, t, _)| *t == Tok::Arrow && *s < location)
}

/// Parentheses opened and not yet closed before `location`.
fn paren_depth(tokens: &[lexer::Spanned], location: usize) -> i64 {
    tokens
        .iter()
        .take_while(|(s, _, _)| *s < location)
        .map(|(_, t, _)| match t {
            Tok::LParen => 1,
            Tok::RParen => -1,
            _ => 0,
        })
        .sum()
}

/// The constant right after the `(` of the innermost condition open at `location`, if its
/// id is one (`(stat <s> ...)`).
fn constant_id(tokens: &[lexer::Spanned], location: usize) -> Option<String> {
    let mut open = Vec::new();
    for (i, (s, t, _)) in tokens.iter().enumerate() {
        if *s >= location {
            break;
        }
        match t {
            Tok::LParen => open.push(i),
            Tok::RParen => {
                open.pop();
            }
            _ => {}
        }
    }
    let (_, id, _) = tokens.get(open.last()? + 1)?;
    match id {
        Tok::Sym(_) | Tok::Ident(_) | Tok::Int(_) | Tok::Float(_) | Tok::Quoted(_) => {
            Some(id.describe())
        }
        _ => None,
    }
}

/// Soar's message for a syntax error, chosen from what the grammar expected.
fn soar_message(expected: &[String], tokens: &[lexer::Spanned], location: usize) -> String {
    let has = |t: &str| expected.iter().any(|e| e == t);
    if on_rhs(tokens, location) {
        // After `(<id>`: parse_attr_value_make wants `^`.
        if has("\"^\"") && has("\")\"") && !has("\"var\"") {
            return "Expected ^ in RHS make action".into();
        }
        // Between actions: parse_rhs_action wants `(`.
        if has("\"(\"") && !has("\"^\"") && !has("\"var\"") {
            return "Expected ( to begin RHS action".into();
        }
        // Anything else (a bad id, which Soar reads as a function name, a bad value or
        // attribute, an unclosed action) ends in parse_rhs_value's message.
        return "Illegal value for RHS value".into();
    }
    // Inside `<< ... >>`: parse_disjunction_test.
    if has("\">>\"") {
        return "Expected constant or >> while reading disjunction test".into();
    }
    // Inside a condition group `{ <cond>+ }` (not inside a condition's parentheses, where
    // braces make a conjunctive test) after at least one condition: parse_cond.
    if has("\"}\"") && paren_depth(tokens, location) == 0 {
        return "Expected } to end conjunctive condition".into();
    }
    // After the conditions at top level: parse_production wants the arrow.
    if has("\"-->\"") {
        return "Expected --> in production".into();
    }
    // Where a condition must start (after the name, flags, or a `-`).
    if has("\"(\"") && !has("\"^\"") && !has("\"var\"") {
        return "Expected ( to begin condition element".into();
    }
    // A condition whose id is a constant: Soar rejects it as soon as it has read the id
    // (parse_head_of_cond_for_one_id), whatever follows.
    if let Some(constant) = constant_id(tokens, location) {
        return format!(
            "Warning: Constant {constant} in id field test.\n         This will never match."
        );
    }
    // Inside a condition, where `^attr` must come: parse_attr_value_tests.
    if has("\"^\"") && !has("\"var\"") {
        return "Expected ^ followed by attribute".into();
    }
    // Where a test must come: parse_relational_test.
    if has("\"var\"") {
        return "Expected variable or constant for test".into();
    }
    "Syntax error in production".into()
}

/// Attaches preference symbols to the values they follow (Soar manual, ch. 3, "Shorthand
/// notations for preference creation"). `= > <` take the next item as referent when it is a
/// value; before `,` `)` `^` or another preference they are unary. So `<o1> + = <o2> + =`
/// makes `<o1>` binary-indifferent to `<o2>` (a pitfall).
pub fn attach_preferences(first: RhsValue, rest: Vec<ValueItem>) -> Vec<ValueMake> {
    let mut out = vec![ValueMake {
        value: first,
        prefs: Vec::new(),
    }];
    let mut items = rest.into_iter().peekable();
    while let Some(item) = items.next() {
        let referent = |items: &mut std::iter::Peekable<std::vec::IntoIter<ValueItem>>| {
            if let Some(ValueItem::Value(_)) = items.peek() {
                if let Some(ValueItem::Value(v)) = items.next() {
                    return Some(v);
                }
            }
            None
        };
        let pref = match item {
            ValueItem::Value(v) => {
                out.push(ValueMake {
                    value: v,
                    prefs: Vec::new(),
                });
                continue;
            }
            ValueItem::Comma(_) => continue,
            ValueItem::Plus(_) => Pref::Acceptable,
            ValueItem::Minus(_) => Pref::Reject,
            ValueItem::Bang(_) => Pref::Require,
            ValueItem::Tilde(_) => Pref::Prohibit,
            ValueItem::Gt(_) => referent(&mut items).map_or(Pref::Best, Pref::Better),
            ValueItem::Lt(_) => referent(&mut items).map_or(Pref::Worst, Pref::Worse),
            ValueItem::Eq(_) => match referent(&mut items) {
                None => Pref::Indifferent,
                Some(
                    v @ RhsValue::Const(
                        crate::ast::Constant::Int(_) | crate::ast::Constant::Float(_),
                        _,
                    ),
                ) => Pref::Numeric(v),
                Some(v) => Pref::BinaryIndifferent(v),
            },
        };
        if let Some(last) = out.last_mut() {
            last.prefs.push(pref);
        }
    }
    out
}
