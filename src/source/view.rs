//! The files one diagnostic shows, as codespan reads them. A packed file is shown through
//! the whole lines its labels are on, unpacked for the rendering alone, with their own
//! line numbers: a diagnostic in a large rule file unpacks a block or two, not the file.

use super::packed::Lines;
use super::{clamp_to_char_boundary, Diagnostic, FileId, FileText, SourceMap, Span};
use codespan_reporting::files::{self as cs_files, Files};
use std::ops::Range;

/// A packed file's lines that a diagnostic shows, with where each of them starts in `text`.
struct Part {
    file: FileId,
    lines: Lines,
    starts: Vec<usize>,
}

pub(super) struct View<'a> {
    map: &'a SourceMap,
    parts: Vec<Part>,
}

impl<'a> View<'a> {
    /// The files `diag` points into.
    pub fn new(map: &'a SourceMap, diag: &Diagnostic) -> Self {
        let spans = diag.span.iter().chain(diag.secondary.iter().map(|(s, _)| s));
        // Each packed file's bytes that the labels cover, from the first to the last.
        let mut covered: Vec<(FileId, usize, usize)> = Vec::new();
        for s in spans {
            let Ok(FileText::Packed(_)) = map.get(s.file).map(|f| &f.text) else {
                continue;
            };
            let end = s.end.max(s.start);
            match covered.iter_mut().find(|c| c.0 == s.file) {
                Some(c) => *c = (c.0, c.1.min(s.start), c.2.max(end)),
                None => covered.push((s.file, s.start, end)),
            }
        }
        let parts = covered
            .into_iter()
            .filter_map(|(file, start, end)| {
                let Ok(FileText::Packed(p)) = map.get(file).map(|f| &f.text) else {
                    return None;
                };
                let lines = p.lines(start, end);
                let starts = cs_files::line_starts(&lines.text).collect();
                Some(Part {
                    file,
                    lines,
                    starts,
                })
            })
            .collect();
        View { map, parts }
    }

    fn part(&self, file: FileId) -> Option<&Part> {
        self.parts.iter().find(|p| p.file == file)
    }

    /// A span as a byte range of the text shown for its file, cut to character boundaries.
    pub fn range(&self, span: Span) -> Range<usize> {
        match self.part(span.file) {
            Some(p) => {
                let local = |o: usize| {
                    let o = o.min(p.lines.start + p.lines.text.len());
                    clamp_to_char_boundary(&p.lines.text, o.saturating_sub(p.lines.start))
                };
                let start = local(span.start);
                let end = local(span.end.max(p.lines.start + start));
                start..end
            }
            None => {
                let text = self.map.text(span.file);
                let start = clamp_to_char_boundary(text, span.start);
                let end = clamp_to_char_boundary(text, span.end.max(start));
                start..end
            }
        }
    }
}

impl<'a> Files<'a> for View<'a> {
    type FileId = FileId;
    type Name = &'a str;
    type Source = &'a str;

    fn name(&'a self, id: FileId) -> Result<&'a str, cs_files::Error> {
        Files::name(self.map, id)
    }

    fn source(&'a self, id: FileId) -> Result<&'a str, cs_files::Error> {
        match self.part(id) {
            Some(p) => Ok(&p.lines.text),
            None => self.map.source(id),
        }
    }

    fn line_index(&'a self, id: FileId, byte_index: usize) -> Result<usize, cs_files::Error> {
        match self.part(id) {
            Some(p) => Ok(p.lines.first_line
                + p.starts
                    .binary_search(&byte_index)
                    .unwrap_or_else(|next| next - 1)),
            None => self.map.line_index(id, byte_index),
        }
    }

    fn line_range(&'a self, id: FileId, line: usize) -> Result<Range<usize>, cs_files::Error> {
        let Some(p) = self.part(id) else {
            return self.map.line_range(id, line);
        };
        let start = |i: usize| match p.starts.get(i) {
            Some(&s) => Ok(s),
            None if i == p.starts.len() => Ok(p.lines.text.len()),
            None => Err(cs_files::Error::LineTooLarge {
                given: i + p.lines.first_line,
                max: p.starts.len() + p.lines.first_line - 1,
            }),
        };
        let i = line
            .checked_sub(p.lines.first_line)
            .ok_or(cs_files::Error::LineTooLarge {
                given: line,
                max: p.lines.first_line,
            })?;
        Ok(start(i)?..start(i + 1)?)
    }
}

#[cfg(test)]
mod tests {
    use crate::source::{Diagnostic, SourceMap, Span};
    use proptest::prelude::*;

    fn texts() -> impl Strategy<Value = String> {
        proptest::collection::vec(
            prop_oneof![Just("\n"), Just("é"), Just("\t"), Just("ab"), Just("sp {x}"), Just("  ")],
            0..50,
        )
        .prop_map(|v| v.concat())
    }

    /// The same text in a map that keeps it as it is and in one that packs it.
    fn maps(text: &str, block: usize) -> (SourceMap, SourceMap) {
        let mut plain = SourceMap::new();
        let mut packed = SourceMap::packing(0, block);
        for m in [&mut plain, &mut packed] {
            m.add("small", "echo x\n");
            m.add("file.soar", text);
        }
        (plain, packed)
    }

    proptest! {
        /// A diagnostic in a packed text renders as in the text itself.
        #[test]
        fn renders_as_the_whole_text(
            text in texts(),
            block in 1usize..16,
            a in 0usize..200, b in 0usize..200, c in 0usize..200, d in 0usize..200,
            other in any::<bool>(),
        ) {
            let (plain, packed) = maps(&text, block);
            let mut diag = Diagnostic::error("bad").at(Span::new(1, a, b)).with_label("here");
            if other {
                diag = diag.with_secondary(Span::new(1, c, d), "and here")
                    .with_secondary(Span::new(0, 0, 4), "elsewhere");
            }
            prop_assert_eq!(packed.render(&diag), plain.render(&diag));
            prop_assert_eq!(packed.line_col(1, a), plain.line_col(1, a));
            prop_assert_eq!(packed.snippet(Span::new(1, a, b)), plain.snippet(Span::new(1, a, b)));
            prop_assert_eq!(packed.text(1), plain.text(1));
        }
    }
}
