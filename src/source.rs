//! Files, spans and diagnostics. Every error and warning the kernel reports carries a
//! [`Span`] into a file registered here, and renders with a caret under the text (codespan).

use codespan_reporting::diagnostic::{Diagnostic as CsDiagnostic, Label};
use codespan_reporting::files::SimpleFiles;
use codespan_reporting::term::{self, termcolor::NoColor};

/// Index of a file in a [`SourceMap`].
pub type FileId = usize;

/// A byte range in one file. Small and `Copy`, attached to every AST node.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Span {
    pub file: FileId,
    pub start: usize,
    pub end: usize,
}

impl Span {
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

/// A registered text, shared (running a file's commands needs it while the map grows).
#[derive(Clone, Default)]
struct Text(std::sync::Arc<String>);

impl AsRef<str> for Text {
    fn as_ref(&self) -> &str {
        &self.0
    }
}

/// All text the kernel has read: sourced files, `-c` commands, REPL lines.
#[derive(Default)]
pub struct SourceMap {
    files: SimpleFiles<String, Text>,
}

impl SourceMap {
    pub fn new() -> Self {
        Self::default()
    }
    /// Registers a text under a display name and returns its id.
    pub fn add(&mut self, name: impl Into<String>, text: impl Into<String>) -> FileId {
        self.files
            .add(name.into(), Text(std::sync::Arc::new(text.into())))
    }
    pub fn text(&self, file: FileId) -> &str {
        self.files
            .get(file)
            .map(|f| f.source().as_ref())
            .unwrap_or("")
    }
    /// The text itself, shared, not copied.
    pub fn shared_text(&self, file: FileId) -> std::sync::Arc<String> {
        self.files
            .get(file)
            .map(|f| f.source().0.clone())
            .unwrap_or_default()
    }
    pub fn name(&self, file: FileId) -> &str {
        self.files
            .get(file)
            .map(|f| f.name().as_str())
            .unwrap_or("<unknown>")
    }
    /// 1-based line and column of a byte offset.
    pub fn line_col(&self, file: FileId, offset: usize) -> (usize, usize) {
        let text = self.text(file);
        let offset = clamp_to_char_boundary(text, offset);
        let before = &text[..offset];
        let line = before.matches('\n').count() + 1;
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
        let mut labels = Vec::new();
        if let Some(span) = diag.span {
            let text = self.text(span.file);
            let start = clamp_to_char_boundary(text, span.start);
            let end = clamp_to_char_boundary(text, span.end.max(start));
            labels.push(Label::primary(span.file, start..end).with_message(&diag.label));
        }
        for (span, msg) in &diag.secondary {
            let text = self.text(span.file);
            let start = clamp_to_char_boundary(text, span.start);
            let end = clamp_to_char_boundary(text, span.end.max(start));
            labels.push(Label::secondary(span.file, start..end).with_message(msg));
        }
        cs = cs.with_labels(labels).with_notes(diag.notes.clone());
        let mut buf = NoColor::new(Vec::new());
        let config = term::Config::default();
        if term::emit_to_write_style(&mut buf, &config, &self.files, &cs).is_err() {
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

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Severity {
    Error,
    Warning,
    Note,
}

impl Severity {
    pub fn word(self) -> &'static str {
        match self {
            Severity::Error => "error",
            Severity::Warning => "warning",
            Severity::Note => "note",
        }
    }
}

/// A located message. `message` is Soar's own wording where Soar has one (spec §1g), so that
/// users searching for the official text find it.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagnostic {
    pub severity: Severity,
    pub message: String,
    pub span: Option<Span>,
    pub label: String,
    pub secondary: Vec<(Span, String)>,
    pub notes: Vec<String>,
}

impl Diagnostic {
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
    pub fn warning(message: impl Into<String>) -> Self {
        Diagnostic {
            severity: Severity::Warning,
            ..Diagnostic::error(message)
        }
    }
    pub fn at(mut self, span: Span) -> Self {
        self.span = Some(span);
        self
    }
    pub fn with_label(mut self, label: impl Into<String>) -> Self {
        self.label = label.into();
        self
    }
    pub fn with_note(mut self, note: impl Into<String>) -> Self {
        self.notes.push(note.into());
        self
    }
    pub fn with_secondary(mut self, span: Span, label: impl Into<String>) -> Self {
        self.secondary.push((span, label.into()));
        self
    }
    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }
}
