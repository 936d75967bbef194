//! Soar's text as tools read it: the command tokenizer (words, braces, quotes, `#`
//! comments), and located diagnostics with the source map that renders them. The kernel
//! reads every file and command line through these; a tool that reads Soar's command
//! syntax (a test runner, an editor) can use them too.

pub use crate::commands::tokenizer::{tokenize, Command, Tokenizer, Word, WordKind};
pub use crate::source::{Diagnostic, FileId, Severity, SourceMap, Span};
