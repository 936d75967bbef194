//! The production lexer (Soar's `parsing/lexer.cpp`): a logos enum for raw lexemes plus a
//! thin iterator that classifies constituent runs (variables, integers, identifier-shaped
//! tokens, relations) and joins `1` `.` `5` into the float `1.5` the way Soar's lexer reads
//! numbers.

use crate::source::{Diagnostic, FileId, Span};
use logos::Logos;

/// Raw lexemes. Whitespace and `;` separate; `#` starts a comment to end of line.
#[derive(Logos, Debug, Clone, Copy, PartialEq, Eq)]
#[logos(skip r"[ \t\r\n\x0B\x0C;]+")]
#[logos(skip(r"#[^\n]*", allow_greedy = true))]
enum Raw {
    /// Letters, digits and `$ % & * + - / : < = > ? _ @` (Soar manual, ch. 3, "Symbols").
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

/// A lexing failure: an unterminated `|` or `"`, or parentheses and braces nested too deep.
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
    Lexer::new(text, base, file, warnings).collect()
}

/// At most this many "unknown character" warnings per production; binary junk would
/// otherwise make one per run.
const MAX_UNKNOWN_WARNINGS: usize = 5;

/// Parentheses and braces may nest this deep. Real rules nest a few levels; the limit keeps
/// the recursive passes over the syntax tree (compiling, printing, dropping it) within the
/// stack, whatever the input.
pub const MAX_NESTING: usize = 200;

/// The production lexer as a lazy iterator, as Soar's lexer is: the parser pulls tokens one
/// at a time, so a production that goes wrong early is not lexed to its end (a 10 MB body
/// costs nothing past its first error). Warnings go to the borrowed vector as tokens are read.
pub struct Lexer<'a, 'w> {
    text: &'a str,
    base: usize,
    file: FileId,
    warnings: &'w mut Vec<Diagnostic>,
    raw: logos::Lexer<'a, Raw>,
    /// Raw tokens read ahead (at most two are needed to join `1` `.` `5`).
    ahead: std::collections::VecDeque<(Raw, usize, usize)>,
    /// End of the raw token consumed last, to tell a glued `.` from a `.5` float.
    prev_end: Option<usize>,
    /// A run of unknown characters not yet reported, and how many runs were.
    unknown: Option<(usize, usize)>,
    unknown_runs: usize,
    /// An unterminated `|` or `"`, reported once the tokens before it are out.
    fatal: Option<LexError>,
    depth: usize,
    done: bool,
}

impl<'a, 'w> Lexer<'a, 'w> {
    pub fn new(
        text: &'a str,
        base: usize,
        file: FileId,
        warnings: &'w mut Vec<Diagnostic>,
    ) -> Self {
        Lexer {
            text,
            base,
            file,
            warnings,
            raw: Raw::lexer(text),
            ahead: std::collections::VecDeque::new(),
            prev_end: None,
            unknown: None,
            unknown_runs: 0,
            fatal: None,
            depth: 0,
            done: false,
        }
    }

    /// Reads raw tokens until `n` are buffered (or the input or a fatal error ends them).
    fn fill(&mut self, n: usize) {
        while self.ahead.len() < n && self.fatal.is_none() {
            let Some(r) = self.raw.next() else {
                self.flush_unknown();
                return;
            };
            let span = self.raw.span();
            match r {
                Ok(t) => {
                    self.flush_unknown();
                    self.ahead.push_back((t, span.start, span.end));
                }
                Err(()) if self.text[span.start..].starts_with(['|', '"']) => {
                    self.flush_unknown();
                    self.fatal = Some(lex_error(self.text, span.start, self.base));
                }
                // Soar's lexer skips characters it does not know (`lex_unknown`).
                Err(()) => match &mut self.unknown {
                    Some(run) if run.1 == span.start => run.1 = span.end,
                    _ => {
                        self.flush_unknown();
                        self.unknown = Some((span.start, span.end));
                    }
                },
            }
        }
    }

    /// Characters that are neither constituents, whitespace nor punctuation are separators
    /// to Soar (`b\x02c` reads as `b c`); we skip them too, with a warning.
    fn flush_unknown(&mut self) {
        let Some((s, e)) = self.unknown.take() else {
            return;
        };
        self.unknown_runs += 1;
        if self.unknown_runs > MAX_UNKNOWN_WARNINGS {
            return;
        }
        let run = &self.text[s..e];
        let shown: String = run.chars().take(8).flat_map(char::escape_debug).collect();
        let more = if run.chars().count() > 8 { "..." } else { "" };
        let mut d = Diagnostic::warning(format!(
            "Ignoring unknown character{} \"{shown}{more}\" in production",
            if run.chars().count() == 1 { "" } else { "s" }
        ))
        .at(Span::new(self.file, self.base + s, self.base + e))
        .with_label("Soar's lexer skips this, as if it were a space");
        if run.contains('\u{fffd}') {
            d = d.with_note("U+FFFD stands for bytes that are not valid UTF-8");
        }
        if self.unknown_runs == MAX_UNKNOWN_WARNINGS {
            d = d.with_note("further unknown characters in this production are skipped silently");
        }
        self.warnings.push(d);
    }

    fn pop(&mut self) -> Option<(Raw, usize, usize)> {
        let t = self.ahead.pop_front();
        if let Some((_, _, e)) = t {
            self.prev_end = Some(e);
        }
        t
    }

    fn tok(&self, s: usize, t: Tok, e: usize) -> Spanned {
        (self.base + s, t, self.base + e)
    }

    fn next_token(&mut self) -> Option<Result<Spanned, LexError>> {
        self.fill(1);
        let prev_end = self.prev_end;
        let Some((kind, s, e)) = self.pop() else {
            return self.fatal.take().map(Err);
        };
        let text = self.text;
        Some(Ok(match kind {
            Raw::Constituent => {
                let word = &text[s..e];
                // `1` `.` `5e3` with no gaps is the float `1.5e3`; `5.` alone is a float too.
                if is_int_lexeme(word) {
                    self.fill(2);
                    if let Some(&(Raw::Dot, ds, de)) = self.ahead.front() {
                        if e == ds {
                            self.fill(2);
                            match self.ahead.get(1).copied() {
                                Some((Raw::Constituent, fs, fe))
                                    if de == fs && is_fraction(&text[fs..fe]) =>
                                {
                                    self.pop();
                                    self.pop();
                                    return Some(Ok(self.tok(s, float_tok(&text[s..fe]), fe)));
                                }
                                Some((Raw::Constituent, fs, _)) if de == fs => {}
                                _ => {
                                    self.pop();
                                    return Some(Ok(self.tok(s, float_tok(&text[s..de]), de)));
                                }
                            }
                        }
                    }
                }
                let t = classify(word, s + self.base, self.file, self.warnings);
                self.tok(s, t, e)
            }
            Raw::Dot => {
                // `.5` after whitespace (not glued to a previous lexeme) is a float.
                if prev_end != Some(s) {
                    self.fill(1);
                    if let Some(&(Raw::Constituent, fs, fe)) = self.ahead.front() {
                        if e == fs && is_fraction(&text[fs..fe]) {
                            self.pop();
                            return Some(Ok(self.tok(s, float_tok(&text[s..fe]), fe)));
                        }
                    }
                }
                self.tok(s, Tok::Dot, e)
            }
            Raw::Pipe => self.tok(s, Tok::Quoted(unescape(&text[s + 1..e - 1])), e),
            Raw::Quote => self.tok(s, Tok::Doc(unescape(&text[s + 1..e - 1])), e),
            Raw::LParen | Raw::LBrace => {
                self.depth += 1;
                if self.depth > MAX_NESTING {
                    return Some(Err(LexError {
                        message: format!(
                            "production nested too deeply (more than {MAX_NESTING} levels of ( and {{)"
                        ),
                        start: self.base + s,
                        end: self.base + e,
                    }));
                }
                let t = if kind == Raw::LParen {
                    Tok::LParen
                } else {
                    Tok::LBrace
                };
                self.tok(s, t, e)
            }
            Raw::RParen | Raw::RBrace => {
                self.depth = self.depth.saturating_sub(1);
                let t = if kind == Raw::RParen {
                    Tok::RParen
                } else {
                    Tok::RBrace
                };
                self.tok(s, t, e)
            }
            Raw::Caret => self.tok(s, Tok::Caret, e),
            Raw::Bang => self.tok(s, Tok::Bang, e),
            Raw::Tilde => self.tok(s, Tok::Tilde, e),
            Raw::Comma => self.tok(s, Tok::Comma, e),
        }))
    }
}

impl Iterator for Lexer<'_, '_> {
    type Item = Result<Spanned, LexError>;
    fn next(&mut self) -> Option<Self::Item> {
        if self.done {
            return None;
        }
        let item = self.next_token();
        if !matches!(item, Some(Ok(_))) {
            self.done = true;
        }
        item
    }
}

fn lex_error(text: &str, start: usize, base: usize) -> LexError {
    let rest = &text[start..];
    let (message, len) = match rest.chars().next() {
        Some('|') => ("Error:  opening '|' without closing '|'".to_string(), 1),
        Some('"') => ("Error:  opening '\"' without closing '\"'".to_string(), 1),
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

/// A float constant; `-0.0` reads as `0.0`, as Soar keeps no negative zero (its floats
/// print, compare and compute as `0.000000`).
fn float_tok(lexeme: &str) -> Tok {
    Tok::Float(lexeme.parse::<f64>().unwrap_or(0.0) + 0.0)
}

/// Whether `c` is one of Soar's symbol constituents (the `Constituent` lexeme above).
pub fn is_constituent(c: char) -> bool {
    c.is_ascii_alphanumeric() || "$%&*+-/:<=>?_@".contains(c)
}

/// `[A-Za-z][0-9]+`: lexes as an identifier in Soar; a constant with its letter upper-cased
/// inside productions, as Soar's parser makes it.
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
                    Diagnostic::warning("Error: bad integer (probably too large)")
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
    if word.starts_with('<') || word.ends_with('>') {
        // Probably a mistyped variable; Soar warns about it the same way.
        warnings.push(
            Diagnostic::warning(format!("Warning: Suspicious string constant \"{word}\""))
                .at(Span::new(file, offset, offset + word.len()))
                .with_label("a string constant, not a variable: variables are <name>"),
        );
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
        assert!(matches!(toks("-0.0")[..], [Tok::Float(f)] if f.is_sign_positive()));
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
        assert_eq!(w[0].message, "Error: bad integer (probably too large)");
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
    fn unknown_characters_are_skipped_as_separators() {
        let mut w = Vec::new();
        let t: Vec<Tok> = lex("b\u{2}c `d", 0, 0, &mut w)
            .unwrap()
            .into_iter()
            .map(|t| t.1)
            .collect();
        assert_eq!(
            t,
            vec![
                Tok::Sym("b".into()),
                Tok::Sym("c".into()),
                Tok::Sym("d".into())
            ]
        );
        assert_eq!(w.len(), 2);
        assert_eq!(w[1].span.map(|s| s.start), Some(4));
    }

    #[test]
    fn unterminated_pipe_is_an_error() {
        let e = lex("^a |abc", 0, 0, &mut Vec::new()).unwrap_err();
        assert_eq!(e.start, 3);
        assert!(e.message.contains("'|'"));
    }
}
