//! The production lexer (spec §1b): a logos enum for raw lexemes plus a thin iterator that
//! classifies constituent runs (variables, integers, identifier-shaped tokens, relations)
//! and joins `1` `.` `5` into the float `1.5` the way Soar's lexer reads numbers.

use crate::source::{Diagnostic, FileId, Span};
use logos::Logos;

/// Raw lexemes. Whitespace and `;` separate; `#` starts a comment to end of line.
#[derive(Logos, Debug, Clone, Copy, PartialEq, Eq)]
#[logos(skip r"[ \t\r\n\x0B\x0C;]+")]
#[logos(skip(r"#[^\n]*", allow_greedy = true))]
enum Raw {
    /// Letters, digits and `$ % & * + - / : < = > ? _ @` (spec §1b constituents).
    #[regex(r"[A-Za-z0-9$%&*+\-/:<=>?_@]+")]
    Constituent,
    #[token(".")]
    Dot,
    #[token("(")]
    LParen,
    #[token(")")]
    RParen,
    #[token("{")]
    LBrace,
    #[token("}")]
    RBrace,
    #[token("^")]
    Caret,
    #[token("!")]
    Bang,
    #[token("~")]
    Tilde,
    #[token(",")]
    Comma,
    /// `|...|` quoted constant; `\` escapes the next character.
    #[regex(r"\|([^|\\]|\\[\s\S])*\|")]
    Pipe,
    /// `"..."` documentation string.
    #[regex(r#""([^"\\]|\\[\s\S])*""#)]
    Quote,
}

/// A classified token, as the grammar sees it.
#[derive(Debug, Clone, PartialEq)]
pub enum Tok {
    Var(String),
    Sym(String),
    /// A letter followed by digits (`p1`, `w2`): a string constant with the letter upper-cased.
    Ident(String),
    Int(i64),
    Float(f64),
    /// `|...|`, already unescaped.
    Quoted(String),
    Doc(String),
    KwState,
    KwImpasse,
    LParen,
    RParen,
    LBrace,
    RBrace,
    Caret,
    Bang,
    Tilde,
    Comma,
    Dot,
    Plus,
    Minus,
    Arrow,
    Lt,
    Gt,
    Eq,
    Le,
    Ge,
    Ne,
    SameType,
    LtLt,
    GtGt,
    Amp,
    At,
}

impl Tok {
    /// How the token reads back, for error messages.
    pub fn describe(&self) -> String {
        match self {
            Tok::Var(s) | Tok::Sym(s) | Tok::Ident(s) => s.clone(),
            Tok::Int(i) => i.to_string(),
            Tok::Float(f) => f.to_string(),
            Tok::Quoted(s) => format!("|{s}|"),
            Tok::Doc(s) => format!("\"{s}\""),
            Tok::KwState => "state".into(),
            Tok::KwImpasse => "impasse".into(),
            other => punct_text(other).to_string(),
        }
    }
}

fn punct_text(t: &Tok) -> &'static str {
    match t {
        Tok::LParen => "(",
        Tok::RParen => ")",
        Tok::LBrace => "{",
        Tok::RBrace => "}",
        Tok::Caret => "^",
        Tok::Bang => "!",
        Tok::Tilde => "~",
        Tok::Comma => ",",
        Tok::Dot => ".",
        Tok::Plus => "+",
        Tok::Minus => "-",
        Tok::Arrow => "-->",
        Tok::Lt => "<",
        Tok::Gt => ">",
        Tok::Eq => "=",
        Tok::Le => "<=",
        Tok::Ge => ">=",
        Tok::Ne => "<>",
        Tok::SameType => "<=>",
        Tok::LtLt => "<<",
        Tok::GtGt => ">>",
        Tok::Amp => "&",
        Tok::At => "@",
        _ => "?",
    }
}

/// A lexing failure: an unexpected character or an unterminated `|` or `"`.
#[derive(Debug, Clone, PartialEq)]
pub struct LexError {
    pub message: String,
    pub start: usize,
    pub end: usize,
}

pub type Spanned = (usize, Tok, usize);

/// Lexes the whole text (offsets relative to `base`) into tokens, or the first lexing error.
/// Warnings such as integer overflow are pushed to `warnings`.
pub fn lex(
    text: &str,
    base: usize,
    file: FileId,
    warnings: &mut Vec<Diagnostic>,
) -> Result<Vec<Spanned>, LexError> {
    let mut raw: Vec<(Raw, usize, usize)> = Vec::new();
    let mut lexer = Raw::lexer(text);
    while let Some(r) = lexer.next() {
        let span = lexer.span();
        match r {
            Ok(t) => raw.push((t, span.start, span.end)),
            Err(()) => return Err(lex_error(text, span.start, base)),
        }
    }
    let mut out = Vec::with_capacity(raw.len());
    let mut i = 0;
    while i < raw.len() {
        let (kind, s, e) = raw[i];
        let at = |k: usize| raw.get(k).copied();
        let adjacent = |a: usize, b: usize| a == b;
        match kind {
            Raw::Constituent => {
                let word = &text[s..e];
                // `1` `.` `5e3` with no gaps is the float `1.5e3`; `5.` alone is a float too.
                if is_int_lexeme(word) {
                    if let Some((Raw::Dot, ds, de)) = at(i + 1) {
                        if adjacent(e, ds) {
                            match at(i + 2) {
                                Some((Raw::Constituent, fs, fe))
                                    if adjacent(de, fs) && is_fraction(&text[fs..fe]) =>
                                {
                                    let lexeme = &text[s..fe];
                                    out.push((base + s, float_tok(lexeme), base + fe));
                                    i += 3;
                                    continue;
                                }
                                Some((Raw::Constituent, fs, _)) if adjacent(de, fs) => {}
                                _ => {
                                    out.push((base + s, float_tok(&text[s..de]), base + de));
                                    i += 2;
                                    continue;
                                }
                            }
                        }
                    }
                }
                out.push((base + s, classify(word, s + base, file, warnings), base + e));
            }
            Raw::Dot => {
                // `.5` after whitespace (not glued to a previous lexeme) is a float.
                let glued_before = i > 0 && raw[i - 1].2 == s;
                if !glued_before {
                    if let Some((Raw::Constituent, fs, fe)) = at(i + 1) {
                        if adjacent(e, fs) && is_fraction(&text[fs..fe]) {
                            out.push((base + s, float_tok(&text[s..fe]), base + fe));
                            i += 2;
                            continue;
                        }
                    }
                }
                out.push((base + s, Tok::Dot, base + e));
            }
            Raw::Pipe => out.push((
                base + s,
                Tok::Quoted(unescape(&text[s + 1..e - 1])),
                base + e,
            )),
            Raw::Quote => out.push((base + s, Tok::Doc(unescape(&text[s + 1..e - 1])), base + e)),
            Raw::LParen => out.push((base + s, Tok::LParen, base + e)),
            Raw::RParen => out.push((base + s, Tok::RParen, base + e)),
            Raw::LBrace => out.push((base + s, Tok::LBrace, base + e)),
            Raw::RBrace => out.push((base + s, Tok::RBrace, base + e)),
            Raw::Caret => out.push((base + s, Tok::Caret, base + e)),
            Raw::Bang => out.push((base + s, Tok::Bang, base + e)),
            Raw::Tilde => out.push((base + s, Tok::Tilde, base + e)),
            Raw::Comma => out.push((base + s, Tok::Comma, base + e)),
        }
        i += 1;
    }
    Ok(out)
}

fn lex_error(text: &str, start: usize, base: usize) -> LexError {
    let rest = &text[start..];
    let (message, len) = match rest.chars().next() {
        Some('|') => ("opening '|' without closing '|'".to_string(), 1),
        Some('"') => ("opening '\"' without closing '\"'".to_string(), 1),
        Some(c) if c.is_control() => (
            format!("unexpected control character (code {})", c as u32),
            c.len_utf8(),
        ),
        Some(c) => (format!("unexpected character '{c}'"), c.len_utf8()),
        None => ("unexpected end of input".to_string(), 0),
    };
    LexError {
        message,
        start: base + start,
        end: base + start + len,
    }
}

fn unescape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    let mut chars = s.chars();
    while let Some(c) = chars.next() {
        if c == '\\' {
            if let Some(n) = chars.next() {
                out.push(n);
            }
        } else {
            out.push(c);
        }
    }
    out
}

/// `[+-]?digits`
pub fn is_int_lexeme(s: &str) -> bool {
    let d = s.strip_prefix(['+', '-']).unwrap_or(s);
    !d.is_empty() && d.bytes().all(|b| b.is_ascii_digit())
}

/// The part of a float after the `.`: `digits*([eE][+-]?digits)?`, at least one digit somewhere.
fn is_fraction(s: &str) -> bool {
    let b = s.as_bytes();
    let mut i = 0;
    while i < b.len() && b[i].is_ascii_digit() {
        i += 1;
    }
    let digits = i;
    if i == b.len() {
        return digits > 0;
    }
    if b[i] != b'e' && b[i] != b'E' {
        return false;
    }
    i += 1;
    if i < b.len() && (b[i] == b'+' || b[i] == b'-') {
        i += 1;
    }
    let exp_start = i;
    while i < b.len() && b[i].is_ascii_digit() {
        i += 1;
    }
    i == b.len() && i > exp_start
}

fn float_tok(lexeme: &str) -> Tok {
    Tok::Float(lexeme.parse::<f64>().unwrap_or(0.0))
}

/// `[A-Za-z][0-9]+`: lexes as an identifier in Soar; a constant with its letter upper-cased
/// inside productions (spec §1b).
pub fn is_identifier_shaped(s: &str) -> bool {
    let b = s.as_bytes();
    b.len() >= 2 && b[0].is_ascii_alphabetic() && b[1..].iter().all(|c| c.is_ascii_digit())
}

/// A variable: `<` ... `>` of at least three characters.
pub fn is_variable(s: &str) -> bool {
    s.len() >= 3 && s.starts_with('<') && s.ends_with('>')
}

fn classify(word: &str, offset: usize, file: FileId, warnings: &mut Vec<Diagnostic>) -> Tok {
    match word {
        "-->" => return Tok::Arrow,
        "-" => return Tok::Minus,
        "+" => return Tok::Plus,
        "<" => return Tok::Lt,
        ">" => return Tok::Gt,
        "=" => return Tok::Eq,
        "<=" => return Tok::Le,
        ">=" => return Tok::Ge,
        "<>" => return Tok::Ne,
        "<=>" => return Tok::SameType,
        "<<" => return Tok::LtLt,
        ">>" => return Tok::GtGt,
        "&" => return Tok::Amp,
        "@" => return Tok::At,
        "state" => return Tok::KwState,
        "impasse" => return Tok::KwImpasse,
        _ => {}
    }
    if is_variable(word) {
        return Tok::Var(word.to_string());
    }
    if is_int_lexeme(word) {
        return match word.parse::<i64>() {
            Ok(v) => Tok::Int(v),
            Err(_) => {
                warnings.push(
                    Diagnostic::warning("bad integer")
                        .at(Span::new(file, offset, offset + word.len()))
                        .with_label("does not fit in 64 bits; Soar reads it as 0"),
                );
                Tok::Int(0)
            }
        };
    }
    if is_identifier_shaped(word) {
        return Tok::Ident(word.to_string());
    }
    Tok::Sym(word.to_string())
}

/// `p1` → `P1`: identifier-shaped lexemes become string constants with the letter upper-cased.
pub fn upcase_identifier(s: &str) -> String {
    s.to_ascii_uppercase()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn toks(s: &str) -> Vec<Tok> {
        lex(s, 0, 0, &mut Vec::new())
            .unwrap()
            .into_iter()
            .map(|t| t.1)
            .collect()
    }

    #[test]
    fn floats_need_a_dot() {
        assert_eq!(toks("1e3"), vec![Tok::Sym("1e3".into())]);
        assert_eq!(toks("1.5e2"), vec![Tok::Float(150.0)]);
        assert_eq!(toks("5."), vec![Tok::Float(5.0)]);
        assert_eq!(toks(" .5"), vec![Tok::Float(0.5)]);
        assert_eq!(toks("-0.5"), vec![Tok::Float(-0.5)]);
    }

    #[test]
    fn integers_as_strtol() {
        assert_eq!(
            toks("+5 007 -7"),
            vec![Tok::Int(5), Tok::Int(7), Tok::Int(-7)]
        );
        let mut w = Vec::new();
        let t = lex("99999999999999999999", 0, 0, &mut w).unwrap();
        assert_eq!(t[0].1, Tok::Int(0));
        assert_eq!(w[0].message, "bad integer");
    }

    #[test]
    fn dot_paths_are_dots() {
        assert_eq!(
            toks("^io.input-link"),
            vec![
                Tok::Caret,
                Tok::Sym("io".into()),
                Tok::Dot,
                Tok::Sym("input-link".into())
            ]
        );
        assert_eq!(toks("abc.def")[1], Tok::Dot);
    }

    #[test]
    fn relations_and_variables() {
        assert_eq!(
            toks("<s> <> <=> << >> <=x -> -->"),
            vec![
                Tok::Var("<s>".into()),
                Tok::Ne,
                Tok::SameType,
                Tok::LtLt,
                Tok::GtGt,
                Tok::Sym("<=x".into()),
                Tok::Sym("->".into()),
                Tok::Arrow
            ]
        );
    }

    #[test]
    fn identifier_shaped() {
        assert_eq!(
            toks("p1 w1b"),
            vec![Tok::Ident("p1".into()), Tok::Sym("w1b".into())]
        );
    }

    #[test]
    fn pipes_and_comments() {
        assert_eq!(
            toks("|a \\| b| # x\n|| ;"),
            vec![Tok::Quoted("a | b".into()), Tok::Quoted("".into())]
        );
    }

    #[test]
    fn unterminated_pipe_is_an_error() {
        let e = lex("^a |abc", 0, 0, &mut Vec::new()).unwrap_err();
        assert_eq!(e.start, 3);
        assert!(e.message.contains("'|'"));
    }
}
