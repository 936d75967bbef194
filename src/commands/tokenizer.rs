//! The command tokenizer: how a `.soar` file or a typed line splits into commands and words
//! (as Soar's `shared/tokenizer.h` does it). Tcl-like but not Tcl: `#` starts a comment
//! anywhere (also inside braces, not inside `|...|`), braces nest, there is no `$` or `[`
//! substitution.

use crate::source::{Diagnostic, FileId, Span};

/// How a word was written. Braced words keep their inner text verbatim (only comments and
/// backslash-newlines are blanked, byte for byte, so offsets still point into the file).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WordKind {
    /// A plain word, up to white space or `;`.
    Bare,
    /// `{...}`: the text between the braces.
    Braced,
    /// `"..."`: the text between the quotes.
    Quoted,
}

/// One word of a command.
#[derive(Debug, Clone, PartialEq)]
pub struct Word {
    /// The word's text (without its braces or quotes).
    pub text: String,
    /// Where the word is, braces or quotes included.
    pub span: Span,
    /// How it was written.
    pub kind: WordKind,
}

impl Word {
    /// File offset of the first byte of `text`: inside the braces for a braced word.
    pub fn content_offset(&self) -> usize {
        match self.kind {
            WordKind::Braced => self.span.start + 1,
            _ => self.span.start,
        }
    }
}

/// One command: its words and the span from its first to its last word.
#[derive(Debug, Clone, PartialEq)]
pub struct Command {
    /// The words, the command's name first.
    pub words: Vec<Word>,
    /// From the first word's start to the last word's end.
    pub span: Span,
}

/// Splits text into commands lazily, so that commands before a tokenizing error still run,
/// as they do in Soar.
pub struct Tokenizer<'a> {
    text: &'a str,
    bytes: &'a [u8],
    pos: usize,
    file: FileId,
    /// Where `text` starts in the file (spans are file offsets).
    base: usize,
    failed: bool,
    /// File offset of the first NUL byte: Soar's tokenizer reads a C string, so the text
    /// ends there.
    nul_at: Option<usize>,
}

impl<'a> Tokenizer<'a> {
    /// Commands of `text`, whose spans name `file`.
    pub fn new(text: &'a str, file: FileId) -> Self {
        let nul_at = text.find('\0');
        Tokenizer::resume(&text[..nul_at.unwrap_or(text.len())], file, 0, 0, nul_at)
    }

    /// Commands of a piece of a file from `pos` on: `text` starts at file offset `base` and
    /// ends at the file's end or first NUL byte (`nul_at`), or earlier, where its reader
    /// then gives it more and starts again (see `file_commands.rs`).
    pub(crate) fn resume(
        text: &'a str,
        file: FileId,
        base: usize,
        pos: usize,
        nul_at: Option<usize>,
    ) -> Self {
        Tokenizer {
            text,
            bytes: text.as_bytes(),
            pos,
            file,
            base,
            failed: false,
            nul_at,
        }
    }

    /// Where in `text` the next command is looked for.
    pub(crate) fn pos(&self) -> usize {
        self.pos
    }

    /// Whether tokenizing stopped at an error.
    pub(crate) fn failed(&self) -> bool {
        self.failed
    }

    /// An end-of-text error, pointing also at the NUL byte that ended the text early.
    fn at_eof(&self, d: Diagnostic) -> Diagnostic {
        match self.nul_at {
            Some(n) => d.with_secondary(
                Span::new(self.file, n, n + 1),
                "the text ends at this NUL byte",
            ),
            None => d,
        }
    }

    fn span(&self, start: usize, end: usize) -> Span {
        Span::new(self.file, self.base + start, self.base + end)
    }

    fn peek(&self) -> Option<u8> {
        self.bytes.get(self.pos).copied()
    }

    fn skip_comment(&mut self) {
        while let Some(c) = self.peek() {
            if c == b'\n' {
                break;
            }
            self.pos += 1;
        }
    }

    /// Skips blanks inside a command; stops at a command end (newline, `;`) or a word.
    fn skip_blanks(&mut self) {
        while let Some(c) = self.peek() {
            match c {
                b' ' | b'\t' | b'\r' | b'\x0b' | b'\x0c' => self.pos += 1,
                b'#' => self.skip_comment(),
                _ => break,
            }
        }
    }

    fn read_braced(&mut self) -> Result<Word, Diagnostic> {
        let open = self.pos;
        self.pos += 1;
        let mut out = Vec::with_capacity(256);
        let mut depth = 1usize;
        let mut in_pipe = false;
        while let Some(c) = self.peek() {
            match c {
                b'|' => {
                    in_pipe = !in_pipe;
                    out.push(c);
                    self.pos += 1;
                }
                b'\\' => {
                    let next = self.bytes.get(self.pos + 1).copied();
                    if next == Some(b'\n') {
                        // Only backslash-newline is substituted inside braces; blank it.
                        out.extend_from_slice(b"  ");
                        self.pos += 2;
                    } else {
                        // `\x` is kept verbatim and the escaped character is not structural.
                        out.push(c);
                        self.pos += 1;
                        if let Some(n) = next {
                            let len = utf8_len(n);
                            out.extend_from_slice(&self.bytes[self.pos..self.pos + len]);
                            self.pos += len;
                        }
                    }
                }
                b'#' if !in_pipe => {
                    let start = self.pos;
                    self.skip_comment();
                    out.extend(std::iter::repeat_n(b' ', self.pos - start));
                }
                b'{' if !in_pipe => {
                    depth += 1;
                    out.push(c);
                    self.pos += 1;
                }
                b'}' if !in_pipe => {
                    depth -= 1;
                    self.pos += 1;
                    if depth == 0 {
                        // Whole characters of the text, and blanks: valid UTF-8, not copied.
                        let text = String::from_utf8(out)
                            .unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned());
                        return Ok(Word {
                            text,
                            span: self.span(open, self.pos),
                            kind: WordKind::Braced,
                        });
                    }
                    out.push(c);
                }
                _ => {
                    // This byte (in a `|...|`, `#`, `{` and `}` come here too) and the run
                    // up to the next byte that matters, copied at once.
                    let rest = &self.bytes[self.pos..];
                    let run = 1 + rest[1..]
                        .iter()
                        .position(|b| matches!(b, b'|' | b'\\' | b'#' | b'{' | b'}'))
                        .unwrap_or(rest.len() - 1);
                    out.extend_from_slice(&rest[..run]);
                    self.pos += run;
                }
            }
        }
        let mut d = Diagnostic::error("unexpected eof, unmatched opening brace")
            .at(self.span(open, open + 1))
            .with_label("this brace is never closed");
        d = self.at_eof(d);
        if in_pipe {
            d = d.with_note(
                "a `|` inside the braces opened a quoted constant that is never closed, \
                 so the closing brace was read as part of it",
            );
        }
        Err(d)
    }

    fn read_quoted(&mut self) -> Result<Word, Diagnostic> {
        let open = self.pos;
        self.pos += 1;
        let mut out = String::new();
        while self.pos < self.bytes.len() {
            let c = self.bytes[self.pos];
            match c {
                b'"' => {
                    self.pos += 1;
                    return Ok(Word {
                        text: out,
                        span: self.span(open, self.pos),
                        kind: WordKind::Quoted,
                    });
                }
                b'\\' => self.read_escape(&mut out),
                _ => self.push_char(&mut out),
            }
        }
        Err(self.at_eof(
            Diagnostic::error("unexpected eof")
                .at(self.span(open, open + 1))
                .with_label("this quote is never closed"),
        ))
    }

    /// Appends the (possibly multi-byte) character at `pos`.
    fn push_char(&mut self, out: &mut String) {
        let rest = &self.text[self.pos..];
        if let Some(ch) = rest.chars().next() {
            out.push(ch);
            self.pos += ch.len_utf8();
        } else {
            self.pos += 1;
        }
    }

    /// Backslash escapes outside braces.
    fn read_escape(&mut self, out: &mut String) {
        self.pos += 1;
        let Some(c) = self.peek() else {
            out.push('\\');
            return;
        };
        let mapped = match c {
            b'n' => Some('\n'),
            b't' => Some('\t'),
            b'r' => Some('\r'),
            b'a' => Some('\x07'),
            b'b' => Some('\x08'),
            b'f' => Some('\x0c'),
            b'v' => Some('\x0b'),
            b'\n' => {
                self.pos += 1;
                while matches!(self.peek(), Some(b' ' | b'\t')) {
                    self.pos += 1;
                }
                out.push(' ');
                return;
            }
            _ => None,
        };
        match mapped {
            Some(ch) => {
                out.push(ch);
                self.pos += 1;
            }
            None => self.push_char(out),
        }
    }

    fn read_bare(&mut self) -> Result<Word, Diagnostic> {
        let start = self.pos;
        let mut out = String::new();
        if self.peek() == Some(b'|') {
            // A word starting with `|` keeps its pipes and runs to the closing pipe.
            out.push('|');
            self.pos += 1;
            loop {
                match self.peek() {
                    None => {
                        return Err(self.at_eof(
                            Diagnostic::error("unexpected eof")
                                .at(self.span(start, start + 1))
                                .with_label("this `|` is never closed"),
                        ))
                    }
                    Some(b'|') => {
                        out.push('|');
                        self.pos += 1;
                        break;
                    }
                    Some(b'\\') => {
                        out.push('\\');
                        self.pos += 1;
                        if self.pos < self.bytes.len() {
                            self.push_char(&mut out);
                        }
                    }
                    Some(_) => self.push_char(&mut out),
                }
            }
        }
        while let Some(c) = self.peek() {
            match c {
                b' ' | b'\t' | b'\r' | b'\n' | b';' | b'\x0b' | b'\x0c' | b'#' => break,
                // Backslash-newline is one space that swallows the following blanks and
                // continues the word: `echo a \<newline>  b` prints `a  b`, as in Soar.
                b'\\' => self.read_escape(&mut out),
                _ => self.push_char(&mut out),
            }
        }
        Ok(Word {
            text: out,
            span: self.span(start, self.pos),
            kind: WordKind::Bare,
        })
    }

    pub(crate) fn next_command(&mut self) -> Option<Result<Command, Diagnostic>> {
        // Skip empty commands: blank lines, `;`, comments.
        loop {
            self.skip_blanks();
            match self.peek() {
                Some(b'\n' | b';') => self.pos += 1,
                None => {
                    let n = self.nul_at?;
                    self.failed = true;
                    return Some(Err(Diagnostic::error("unexpected NUL byte")
                        .at(Span::new(self.file, n, n + 1))
                        .with_label("Soar reads no further than this NUL byte")
                        .with_note("the rest of the text is ignored")));
                }
                _ => break,
            }
        }
        let mut words = Vec::new();
        loop {
            self.skip_blanks();
            let word = match self.peek() {
                None | Some(b'\n' | b';') => break,
                Some(b'{') => self.read_braced(),
                Some(b'"') => self.read_quoted(),
                Some(_) => self.read_bare(),
            };
            match word {
                Ok(w) => words.push(w),
                Err(d) => {
                    self.failed = true;
                    return Some(Err(d));
                }
            }
        }
        let first = words.first()?.span;
        let last = words.last().map(|w| w.span).unwrap_or(first);
        Some(Ok(Command {
            words,
            span: first.to(last),
        }))
    }
}

impl Iterator for Tokenizer<'_> {
    type Item = Result<Command, Diagnostic>;
    fn next(&mut self) -> Option<Self::Item> {
        if self.failed {
            return None;
        }
        self.next_command()
    }
}

fn utf8_len(first: u8) -> usize {
    match first {
        0x00..=0x7f => 1,
        0xc0..=0xdf => 2,
        0xe0..=0xef => 3,
        0xf0..=0xf7 => 4,
        _ => 1,
    }
}

/// Tokenizes a whole text, stopping at the first error.
pub fn tokenize(text: &str, file: FileId) -> Result<Vec<Command>, Diagnostic> {
    Tokenizer::new(text, file).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn words(text: &str) -> Vec<Vec<String>> {
        tokenize(text, 0)
            .unwrap()
            .into_iter()
            .map(|c| c.words.into_iter().map(|w| w.text).collect())
            .collect()
    }

    #[test]
    fn splits_on_newline_and_semicolon() {
        assert_eq!(
            words("a b\nc; d e"),
            vec![vec!["a", "b"], vec!["c"], vec!["d", "e"]]
        );
    }

    #[test]
    fn braces_nest_and_drop_outer() {
        assert_eq!(words("sp {a {b} c}"), vec![vec!["sp", "a {b} c"]]);
    }

    #[test]
    fn braces_and_hashes_inside_pipes_are_text() {
        assert_eq!(words("sp {a |{#}| b}"), vec![vec!["sp", "a |{#}| b"]]);
    }

    #[test]
    fn newline_and_semicolon_inside_braces_do_not_end_command() {
        assert_eq!(words("x {a;\nb}"), vec![vec!["x", "a;\nb"]]);
    }

    #[test]
    fn hash_comments_anywhere_even_in_braces() {
        let w = words("sp {a # c }\n b}");
        // The `}` on the comment line is commented out too, as in Soar.
        assert_eq!(w[0][1], "a      \n b");
        assert_eq!(words("echo a # comment"), vec![vec!["echo", "a"]]);
    }

    #[test]
    fn hash_inside_pipes_in_braces_is_literal() {
        assert_eq!(words("x {|a # }|}"), vec![vec!["x", "|a # }|"]]);
    }

    #[test]
    fn quotes_process_escapes() {
        assert_eq!(words("echo \"a\\tb c\""), vec![vec!["echo", "a\tb c"]]);
    }

    #[test]
    fn pipe_word_keeps_pipes() {
        assert_eq!(words("echo |x y| z"), vec![vec!["echo", "|x y|", "z"]]);
    }

    #[test]
    fn backslash_newline_continues_command() {
        // The backslash-newline becomes a space that starts (or continues) a word.
        assert_eq!(
            words("echo a \\\n   b\nc"),
            vec![vec!["echo", "a", " b"], vec!["c"]]
        );
        assert_eq!(words("echo a\\\n   b"), vec![vec!["echo", "a b"]]);
    }

    #[test]
    fn unmatched_brace_is_located() {
        let e = tokenize("echo x\nsp {a (b", 0).unwrap_err();
        assert_eq!(e.message, "unexpected eof, unmatched opening brace");
        assert_eq!(e.span.unwrap().start, 10);
        let e = tokenize("sp {a |b}", 0).unwrap_err();
        assert!(e.notes[0].contains('|'));
    }

    #[test]
    fn commands_before_an_error_still_come_out() {
        let mut t = Tokenizer::new("echo ok\nsp {x", 0);
        assert!(t.next().unwrap().is_ok());
        assert!(t.next().unwrap().is_err());
        assert!(t.next().is_none());
    }

    #[test]
    fn nul_byte_ends_the_text() {
        let mut t = Tokenizer::new("echo a\n\0echo b", 0);
        assert!(t.next().unwrap().is_ok());
        let e = t.next().unwrap().unwrap_err();
        assert_eq!(e.message, "unexpected NUL byte");
        assert_eq!(e.span.unwrap().start, 7);
        assert!(t.next().is_none());
        let e = tokenize("sp {a \0 }", 0).unwrap_err();
        assert_eq!(e.message, "unexpected eof, unmatched opening brace");
        assert_eq!(e.secondary[0].0.start, 6);
    }

    #[test]
    fn braced_content_keeps_file_offsets() {
        let text = "sp {ab # x\n cd}";
        let c = &tokenize(text, 0).unwrap()[0];
        let w = &c.words[1];
        assert_eq!(w.text.len(), w.span.end - w.span.start - 2);
        let off = w.content_offset() + w.text.find("cd").unwrap();
        assert_eq!(&text[off..off + 2], "cd");
    }
}
