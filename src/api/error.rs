//! The error of the public API: a standard error that renders itself.

use crate::io::IoError;
use crate::source::{Diagnostic, Severity, SourceMap};

/// What went wrong in a call to the kernel.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum Error {
    /// A command or a rule was rejected (a syntax error, a bad option, a file that cannot
    /// be read, ...). `Display` shows Soar's message with the file, line and a caret under
    /// the offending text.
    #[error("{}", rendered.trim_end())]
    Command {
        /// Whether it is an error or a warning (a warning is printed, never returned).
        severity: Severity,
        /// The message alone, without its location.
        message: String,
        /// Where it happened, when it is in a text the agent read.
        location: Option<Location>,
        /// The message as a terminal shows it.
        rendered: String,
    },
    /// A misuse of the input or output link.
    #[error(transparent)]
    Io(#[from] IoError),
}

/// A place in a text the agent read: a file, a `-c` argument or a string passed to
/// [`crate::Agent::source_text`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// The name the text was read under (a path, or a name such as `<stdin>`).
    pub name: String,
    /// The line, from 1.
    pub line: usize,
    /// The column, from 1.
    pub column: usize,
}

impl Error {
    /// A diagnostic made into an error, rendered with the texts it points into.
    pub(crate) fn from_diagnostic(d: &Diagnostic, sources: &SourceMap) -> Self {
        let location = d.span.map(|s| {
            let (line, column) = sources.line_col(s.file, s.start);
            Location {
                name: sources.name(s.file).to_string(),
                line,
                column,
            }
        });
        Error::Command {
            severity: d.severity,
            message: d.message.clone(),
            location,
            rendered: sources.render(d),
        }
    }

    /// The message alone, without its location.
    pub fn message(&self) -> String {
        match self {
            Error::Command { message, .. } => message.clone(),
            Error::Io(e) => e.to_string(),
        }
    }

    /// The error as a terminal shows it: for a command's error, Soar's message with the
    /// file, line and a caret under the offending text, ending in a newline.
    pub fn render(&self) -> String {
        match self {
            Error::Command { rendered, .. } => rendered.clone(),
            Error::Io(e) => format!("error: {e}\n"),
        }
    }

    /// Whether this is a warning (printed by a command that went on) and not an error.
    pub fn is_warning(&self) -> bool {
        matches!(
            self,
            Error::Command {
                severity: Severity::Warning | Severity::Note,
                ..
            }
        )
    }

    /// Where the error is, when it is in a text the agent read.
    pub fn location(&self) -> Option<&Location> {
        match self {
            Error::Command { location, .. } => location.as_ref(),
            Error::Io(_) => None,
        }
    }
}

/// Something the agent printed: text as Soar prints it, or a located message (a warning, or
/// an error reported without stopping the command that met it).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Printed {
    /// Text: trace output, `write` output, command results.
    Text(String),
    /// A located message (rendered with its file, line and caret by `Display`).
    Diagnostic(Error),
}

impl std::fmt::Display for Printed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Printed::Text(t) => f.write_str(t),
            Printed::Diagnostic(Error::Command { rendered, .. }) => f.write_str(rendered),
            Printed::Diagnostic(e) => writeln!(f, "{e}"),
        }
    }
}

impl Printed {
    /// A printed event of the command language as the API gives it.
    pub(crate) fn from_event(e: &crate::commands::Event, sources: &SourceMap) -> Self {
        match e {
            crate::commands::Event::Text(t) => Printed::Text(t.clone()),
            crate::commands::Event::Diag(d) => {
                Printed::Diagnostic(Error::from_diagnostic(d, sources))
            }
        }
    }
}
