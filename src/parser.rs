//! The production parser: one entry point, [`parse_production`], over the lalrpop grammar in
//! `grammar/soar.lalrpop`. Grammar errors are translated to Soar's own messages (spec §1g).

use crate::ast::{Pref, RhsValue, ValueItem, ValueMake};
use crate::lexer::{self, Tok};
use crate::source::{Diagnostic, FileId, Span};

lalrpop_util::lalrpop_mod!(
    #[allow(clippy::all, clippy::pedantic, unused)]
    grammar,
    "/soar.rs"
);

/// Parses the inside of an `sp {...}` body. `offset` is the file offset of `text`'s first byte.
/// Warnings (e.g. `bad integer`) go to `warnings`; the first error is returned.
pub fn parse_production(
    text: &str,
    file: FileId,
    offset: usize,
    warnings: &mut Vec<Diagnostic>,
) -> Result<crate::ast::Production, Diagnostic> {
    let tokens = lexer::lex(text, offset, file, warnings).map_err(|e| {
        Diagnostic::error(e.message.clone())
            .at(Span::new(file, e.start, e.end))
            .with_label("here")
    })?;
    let end = offset + text.len();
    if tokens.is_empty() {
        return Err(Diagnostic::error("Expected symbol for production name")
            .at(Span::new(file, offset, end))
            .with_label("the production body is empty"));
    }
    let parser = grammar::ProductionParser::new();
    let token_list = tokens.to_vec();
    parser
        .parse(file, token_list.into_iter().map(Ok::<_, String>))
        .map_err(|e| translate_error(e, &tokens, file, end))
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
            let msg = soar_message(None, &expected, tokens, location);
            Diagnostic::error(msg)
                .at(Span::new(file, end, end))
                .with_label("the production ends here")
                .with_note(expected_note(&expected))
        }
        P::UnrecognizedToken {
            token: (l, tok, r),
            expected,
        } => {
            let msg = soar_message(Some(&tok), &expected, tokens, l);
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

/// Soar's message for a syntax error (spec §1g), chosen from what the grammar expected.
fn soar_message(
    found: Option<&Tok>,
    expected: &[String],
    tokens: &[lexer::Spanned],
    location: usize,
) -> String {
    let has = |t: &str| expected.iter().any(|e| e == t);
    if on_rhs(tokens, location) {
        if has("\"^\"") && has("\")\"") && !has("\"var\"") {
            return "Expected ^ followed by attribute".into();
        }
        if has("\"var\"") && !has("\"(\"") {
            return "Expected variable or identifier for id of make action".into();
        }
        if has("\"var\"") || has("\"sym\"") {
            if found == Some(&Tok::Dot) || found.is_none() || matches!(found, Some(Tok::RParen)) {
                return "Illegal value for RHS value".into();
            }
            return "Illegal value for RHS value".into();
        }
        if has("\"(\"") && !has("\"^\"") {
            return "Expected ( to begin action".into();
        }
        return "Illegal value for RHS value".into();
    }
    if has("\"-->\"") && found.is_none() {
        return "Expected --> in production".into();
    }
    if has("\">>\"") {
        return "Expected constant or >> while reading disjunction test".into();
    }
    if has("\"}\"") && !has("\"^\"") && !has("\"(\"") {
        return "Expected } to end conjunctive condition".into();
    }
    if has("\"-->\"") && !has("\"^\"") {
        return match found {
            Some(Tok::Caret) => "Expected ( to begin condition element".into(),
            _ => "Expected --> in production".into(),
        };
    }
    if has("\"(\"") && !has("\"^\"") && !has("\"var\"") {
        return "Expected ( to begin condition element".into();
    }
    if has("\"^\"") && !has("\"var\"") {
        return "Expected ^ followed by attribute".into();
    }
    if has("\"var\"") {
        return "Expected variable or constant for test".into();
    }
    "Syntax error in production".into()
}

/// Attaches preference symbols to the values they follow (spec §1e). `= > <` take the next
/// item as referent when it is a value; before `,` `)` `^` or another preference they are
/// unary. So `<o1> + = <o2> + =` makes `<o1>` binary-indifferent to `<o2>` (spec §1e pitfall).
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
