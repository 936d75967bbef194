//! Files, spans and diagnostics. Every error and warning the kernel reports carries a
//! [`Span`] into a file registered here, and renders with a caret under the text (codespan).

use codespan_reporting::diagnostic::{Diagnostic as CsDiagnostic, Label};
use codespan_reporting::files::{self as cs_files, Files};
use codespan_reporting::term::{self, termcolor::NoColor};
use std::ops::Range;
use std::sync::{Arc, OnceLock};

/// Index of a file in a [`SourceMap`].
pub type FileId = usize;

/// A byte range in one file. Small and `Copy`, attached to every AST node.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Span {
    /// The text the span is in.
    pub file: FileId,
    /// The first byte.
    pub start: usize,
    /// One past the last byte.
    pub end: usize,
}

impl Span {
    /// The bytes `start..end` of `file`.
    pub fn new(file: FileId, start: usize, end: usize) -> Self {
        Span { file, start, end }
    }
    /// The smallest span covering both.
    pub fn to(self, other: Span) -> Span {
        Span {
            file: self.file,
            start: self.start.min(other.start),
            end: self.end.max(other.end),
        }
    }
}

/// A place in a rule's text in 6 bytes, for the parts of a loaded rule that keep one (each
/// of its conditions and actions): 100,000 rules keep about 700,000, and in 6 bytes a
/// condition fits in 56 with its tests. The file is the rule's own, so it is not kept.
/// Offsets past 4 GiB and lengths past 64 KiB saturate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct PackedSpan {
    /// The start's low and high halves, and the length.
    start_len: [u16; 3],
}

impl From<Span> for PackedSpan {
    fn from(s: Span) -> Self {
        let start = u32::try_from(s.start).unwrap_or(u32::MAX);
        let len = u16::try_from(s.end.saturating_sub(s.start)).unwrap_or(u16::MAX);
        PackedSpan {
            start_len: [start as u16, (start >> 16) as u16, len],
        }
    }
}

impl PackedSpan {
    /// The span in `file`.
    pub fn in_file(self, file: FileId) -> Span {
        let [lo, hi, len] = self.start_len.map(usize::from);
        let start = hi << 16 | lo;
        Span::new(file, start, start + len)
    }
}

mod packed;
mod read;
mod view;

pub(crate) use packed::{PackedText, BLOCK as PACKED_BLOCK};

/// The text of a registered file: as it is, or packed when it is large (see
/// `packed.rs`). Shared either way: running a file's commands needs it while the map grows.
#[derive(Clone)]
pub(crate) enum FileText {
    Plain(Arc<String>),
    Packed(Arc<PackedText>),
}

/// A registered text. Its line starts are found only when a diagnostic is rendered in it:
/// most sourced files never need them, and for a large rule file they are megabytes.
struct SourceFile {
    name: String,
    text: FileText,
    /// A packed text unpacked whole, for the callers that ask for all of it (`text`).
    unpacked: OnceLock<String>,
    line_starts: OnceLock<Vec<usize>>,
}

impl SourceFile {
    fn text(&self) -> &str {
        match &self.text {
            FileText::Plain(t) => t,
            FileText::Packed(p) => self.unpacked.get_or_init(|| p.unpack()),
        }
    }

    fn len(&self) -> usize {
        match &self.text {
            FileText::Plain(t) => t.len(),
            FileText::Packed(p) => p.len(),
        }
    }

    fn line_starts(&self) -> &[usize] {
        self.line_starts
            .get_or_init(|| cs_files::line_starts(self.text()).collect())
    }

    /// The start of line `i`, or the end of the text for the line after the last.
    fn line_start(&self, i: usize) -> Result<usize, cs_files::Error> {
        let starts = self.line_starts();
        match starts.get(i) {
            Some(&s) => Ok(s),
            None if i == starts.len() => Ok(self.len()),
            None => Err(cs_files::Error::LineTooLarge {
                given: i,
                max: starts.len() - 1,
            }),
        }
    }
}

/// Texts of at least this many bytes are kept packed (a rule file of about 6,000 rules).
pub(crate) const PACK_AT: usize = 1 << 20;

/// All text the kernel has read: sourced files, `-c` commands, REPL lines.
pub struct SourceMap {
    files: Vec<SourceFile>,
    /// Texts this long or longer are packed, in blocks of `block` bytes.
    pack_at: usize,
    block: usize,
}

impl Default for SourceMap {
    fn default() -> Self {
        SourceMap {
            files: Vec::new(),
            pack_at: PACK_AT,
            block: packed::BLOCK,
        }
    }
}

impl<'a> Files<'a> for SourceMap {
    type FileId = FileId;
    type Name = &'a str;
    type Source = &'a str;

    fn name(&'a self, id: FileId) -> Result<&'a str, cs_files::Error> {
        self.get(id).map(|f| f.name.as_str())
    }

    fn source(&'a self, id: FileId) -> Result<&'a str, cs_files::Error> {
        self.get(id).map(|f| f.text())
    }

    fn line_index(&'a self, id: FileId, byte_index: usize) -> Result<usize, cs_files::Error> {
        let starts = self.get(id)?.line_starts();
        Ok(starts
            .binary_search(&byte_index)
            .unwrap_or_else(|next| next - 1))
    }

    fn line_range(&'a self, id: FileId, line: usize) -> Result<Range<usize>, cs_files::Error> {
        let f = self.get(id)?;
        Ok(f.line_start(line)?..f.line_start(line + 1)?)
    }
}

impl SourceMap {
    /// An empty map.
    pub fn new() -> Self {
        Self::default()
    }
    /// An empty map that packs texts of `pack_at` bytes or more in blocks of `block`
    /// bytes (the tests pack small texts in small blocks).
    #[cfg(test)]
    pub(crate) fn packing(pack_at: usize, block: usize) -> Self {
        SourceMap {
            files: Vec::new(),
            pack_at,
            block,
        }
    }
    fn get(&self, file: FileId) -> Result<&SourceFile, cs_files::Error> {
        self.files.get(file).ok_or(cs_files::Error::FileMissing)
    }
    /// Registers a text under a display name and returns its id.
    pub fn add(&mut self, name: impl Into<String>, text: impl Into<String>) -> FileId {
        let text: String = text.into();
        let text = if text.len() >= self.pack_at {
            FileText::Packed(Arc::new(PackedText::pack(&text, self.block)))
        } else {
            FileText::Plain(Arc::new(text))
        };
        self.push_file(name.into(), text)
    }
    fn push_file(&mut self, name: String, text: FileText) -> FileId {
        self.files.push(SourceFile {
            name,
            text,
            unpacked: OnceLock::new(),
            line_starts: OnceLock::new(),
        });
        self.files.len() - 1
    }
    /// The text registered as `file` (empty for an unknown id). A packed text is unpacked
    /// for it, and kept so.
    pub fn text(&self, file: FileId) -> &str {
        self.get(file).map(|f| f.text()).unwrap_or("")
    }
    /// The text of `file` as it is kept, shared (empty for an unknown id).
    pub(crate) fn file_text(&self, file: FileId) -> FileText {
        self.get(file)
            .map(|f| f.text.clone())
            .unwrap_or_else(|_| FileText::Plain(Arc::default()))
    }
    /// The text under a span (empty where there is none).
    pub fn snippet(&self, span: Span) -> String {
        match self.get(span.file).map(|f| &f.text) {
            Ok(FileText::Plain(t)) => t.get(span.start..span.end).unwrap_or_default().to_string(),
            Ok(FileText::Packed(p)) => {
                let lines = p.lines(span.start, span.end);
                let at = |o: usize| o.checked_sub(lines.start);
                match (at(span.start), at(span.end)) {
                    (Some(a), Some(b)) => lines.text.get(a..b).unwrap_or_default().to_string(),
                    _ => String::new(),
                }
            }
            Err(_) => String::new(),
        }
    }
    /// The display name of `file`.
    pub fn name(&self, file: FileId) -> &str {
        self.get(file)
            .map(|f| f.name.as_str())
            .unwrap_or("<unknown>")
    }
    /// 1-based line and column of a byte offset.
    pub fn line_col(&self, file: FileId, offset: usize) -> (usize, usize) {
        let (text, offset, lines_before) = match self.get(file).map(|f| &f.text) {
            Ok(FileText::Packed(p)) => {
                let lines = p.lines(offset, offset);
                let local = offset.min(p.len()) - lines.start;
                (std::borrow::Cow::Owned(lines.text), local, lines.first_line)
            }
            _ => (std::borrow::Cow::Borrowed(self.text(file)), offset, 0),
        };
        let offset = clamp_to_char_boundary(&text, offset);
        let before = &text[..offset];
        let line = lines_before + before.matches('\n').count() + 1;
        let col = before
            .rsplit('\n')
            .next()
            .map(|s| s.chars().count())
            .unwrap_or(0)
            + 1;
        (line, col)
    }
    /// Renders a diagnostic as plain text (no colour), as snapshots and logs want it.
    pub fn render(&self, diag: &Diagnostic) -> String {
        let mut cs = match diag.severity {
            Severity::Error => CsDiagnostic::error(),
            Severity::Warning => CsDiagnostic::warning(),
            Severity::Note => CsDiagnostic::note(),
        }
        .with_message(&diag.message);
        let view = view::View::new(self, diag);
        let mut labels = Vec::new();
        if let Some(span) = diag.span {
            labels.push(Label::primary(span.file, view.range(span)).with_message(&diag.label));
        }
        for (span, msg) in &diag.secondary {
            labels.push(Label::secondary(span.file, view.range(*span)).with_message(msg));
        }
        cs = cs.with_labels(labels).with_notes(diag.notes.clone());
        let mut buf = NoColor::new(Vec::new());
        let config = term::Config::default();
        if term::emit_to_write_style(&mut buf, &config, &view, &cs).is_err() {
            return format!("{}: {}", diag.severity.word(), diag.message);
        }
        String::from_utf8_lossy(&buf.into_inner()).into_owned()
    }
}

/// Largest char boundary not after `offset`, so slicing never panics on odd input.
pub fn clamp_to_char_boundary(text: &str, offset: usize) -> usize {
    let mut o = offset.min(text.len());
    while o > 0 && !text.is_char_boundary(o) {
        o -= 1;
    }
    o
}

/// How serious a diagnostic is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Severity {
    /// The command failed.
    Error,
    /// The command went on.
    Warning,
    /// Extra information.
    Note,
}

impl Severity {
    /// The word that starts a rendered diagnostic.
    pub fn word(self) -> &'static str {
        match self {
            Severity::Error => "error",
            Severity::Warning => "warning",
            Severity::Note => "note",
        }
    }
}

/// A located message. `message` is Soar's own wording where Soar has one, so that
/// users searching for the official text find it.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagnostic {
    /// Error, warning or note.
    pub severity: Severity,
    /// The message.
    pub message: String,
    /// Where it is, if in a text.
    pub span: Option<Span>,
    /// The label under the caret.
    pub label: String,
    /// Other places worth showing, each with its label.
    pub secondary: Vec<(Span, String)>,
    /// Notes printed after the source excerpt.
    pub notes: Vec<String>,
}

impl Diagnostic {
    /// An error with `message` and no location yet.
    pub fn error(message: impl Into<String>) -> Self {
        Diagnostic {
            severity: Severity::Error,
            message: message.into(),
            span: None,
            label: String::new(),
            secondary: Vec::new(),
            notes: Vec::new(),
        }
    }
    /// A warning with `message` and no location yet.
    pub fn warning(message: impl Into<String>) -> Self {
        Diagnostic {
            severity: Severity::Warning,
            ..Diagnostic::error(message)
        }
    }
    /// Located at `span`.
    pub fn at(mut self, span: Span) -> Self {
        self.span = Some(span);
        self
    }
    /// With a label under the caret.
    pub fn with_label(mut self, label: impl Into<String>) -> Self {
        self.label = label.into();
        self
    }
    /// With a note after the excerpt.
    pub fn with_note(mut self, note: impl Into<String>) -> Self {
        self.notes.push(note.into());
        self
    }
    /// With another place to show.
    pub fn with_secondary(mut self, span: Span, label: impl Into<String>) -> Self {
        self.secondary.push((span, label.into()));
        self
    }
    /// Whether it is an error.
    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }
}
