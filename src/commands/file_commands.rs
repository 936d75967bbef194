//! The commands of a registered text, one at a time. A packed text (a large file, see
//! `source/packed.rs`) is read through a window of a few unpacked blocks: its commands
//! are the ones the whole text gives, and it is never unpacked whole.

use super::tokenizer::{Command, Tokenizer};
use crate::source::{Diagnostic, FileId, FileText, PackedText};

pub(crate) struct FileCommands {
    file: FileId,
    text: FileText,
    /// File offset of the first NUL byte, where the commands end (as in `Tokenizer::new`).
    nul_at: Option<usize>,
    /// Where the commands end: the text's end or its first NUL byte.
    end: usize,
    /// File offset where the next command is looked for.
    pos: usize,
    failed: bool,
    /// A packed text's unpacked blocks from file offset `base` on (cut at `end`), and
    /// the next block to unpack.
    window: String,
    base: usize,
    next_block: usize,
}

impl FileCommands {
    pub fn new(file: FileId, text: FileText) -> Self {
        let (nul_at, len) = match &text {
            FileText::Plain(t) => (t.find('\0'), t.len()),
            FileText::Packed(p) => (p.first_nul(), p.len()),
        };
        FileCommands {
            file,
            text,
            nul_at,
            end: nul_at.unwrap_or(len),
            pos: 0,
            failed: false,
            window: String::new(),
            base: 0,
            next_block: 0,
        }
    }

    /// Where the next command is looked for, where the commands end, and whether the text
    /// is a large one (packed).
    pub fn progress(&self) -> (usize, usize, bool) {
        (self.pos, self.end, matches!(self.text, FileText::Packed(_)))
    }

    fn next_packed(&mut self, packed: &PackedText) -> Option<Result<Command, Diagnostic>> {
        let mut more = 1;
        loop {
            let complete = self.base + self.window.len() >= self.end
                || self.next_block >= packed.block_count();
            let mut t = Tokenizer::resume(
                &self.window,
                self.file,
                self.base,
                self.pos - self.base,
                self.nul_at,
            );
            let command = t.next_command();
            // A command that reaches the window's end (or the byte before it, which the
            // tokenizer may have looked past) may go on in the next block: read it again
            // with more text.
            if !complete && t.pos() + 1 >= self.window.len() {
                self.unpack_more(packed, more);
                more *= 2;
                continue;
            }
            self.pos = self.base + t.pos();
            self.failed = t.failed();
            self.drop_read_text();
            return command;
        }
    }

    /// Appends `n` more blocks to the window.
    fn unpack_more(&mut self, packed: &PackedText, n: usize) {
        for _ in 0..n {
            if self.next_block >= packed.block_count() {
                break;
            }
            packed.unpack_block(self.next_block, &mut self.window);
            self.next_block += 1;
        }
        if self.base + self.window.len() > self.end {
            self.window.truncate(self.end - self.base);
        }
    }

    /// Drops the window's text before the next command, once it is a block's worth.
    fn drop_read_text(&mut self) {
        let read = self.pos - self.base;
        if read >= crate::source::PACKED_BLOCK.min(self.window.len())
            && self.window.is_char_boundary(read)
        {
            self.window.drain(..read);
            self.base = self.pos;
        }
    }
}

impl Iterator for FileCommands {
    type Item = Result<Command, Diagnostic>;
    fn next(&mut self) -> Option<Self::Item> {
        if self.failed {
            return None;
        }
        match self.text.clone() {
            FileText::Plain(text) => {
                let mut t = Tokenizer::resume(&text[..self.end], self.file, 0, self.pos, self.nul_at);
                let command = t.next_command();
                self.pos = t.pos();
                self.failed = t.failed();
                command
            }
            FileText::Packed(packed) => self.next_packed(&packed),
        }
    }
}

/// The commands of a text kept as it is, for the tests.
#[cfg(test)]
pub(crate) fn plain(file: FileId, text: &str) -> FileCommands {
    FileCommands::new(file, FileText::Plain(std::sync::Arc::new(text.to_string())))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::sync::Arc;

    fn texts() -> impl Strategy<Value = String> {
        proptest::collection::vec(
            prop_oneof![
                Just("\n"),
                Just(";"),
                Just(" "),
                Just("{"),
                Just("}"),
                Just("\""),
                Just("|"),
                Just("\\"),
                Just("\\\n"),
                Just("#"),
                Just("\0"),
                Just("é"),
                Just("sp"),
                Just("echo"),
                Just("ab"),
            ],
            0..60,
        )
        .prop_map(|v| v.concat())
    }

    proptest! {
        /// The window gives what the whole text gives, at any block size.
        #[test]
        fn packed_commands_are_the_text_commands(text in texts(), block in 1usize..12) {
            let whole: Vec<_> = plain(3, &text).collect();
            let packed = PackedText::pack(&text, block);
            let windowed: Vec<_> = FileCommands::new(3, FileText::Packed(Arc::new(packed))).collect();
            prop_assert_eq!(windowed, whole.clone());
            let tokenizer: Vec<_> = Tokenizer::new(&text, 3).collect();
            prop_assert_eq!(whole, tokenizer);
        }
    }
}

#[cfg(test)]
mod large_file_tests {
    use crate::commands::Interpreter;
    use crate::source::SourceMap;

    /// A file of more than a megabyte (so kept packed) with a warning in the middle, a
    /// duplicate, and a failing rule near the end.
    fn large_file() -> String {
        let mut text = String::new();
        for i in 0..8000 {
            text.push_str(&format!(
                "sp {{gen*{i}\n   (state <s> ^superstate nil ^task <t>)\n   (<t> ^name task-{} ^step <st>)\n   (<st> ^kind k{i} ^value <v>)\n-->\n   (<s> ^result r{i})}}\n",
                i % 100
            ));
            if i == 3500 {
                text.push_str("sp {unconnected (<x> ^a b) --> (<x> ^c d)}\n");
                text.push_str("sp {gen*dup (state <s> ^superstate nil ^task <t>) (<t> ^name task-0 ^step <st>) (<st> ^kind k0 ^value <v>) --> (<s> ^result r0)}\n");
            }
        }
        text.push_str("echo é\nsp {bad (state <s> ^a <b> --> (<s> ^c d)}\necho never\n");
        assert!(text.len() >= crate::source::PACK_AT);
        text
    }

    fn run(sources: SourceMap, text: &str, path: &std::path::Path) -> String {
        let mut it = Interpreter::new();
        it.sources = sources;
        let failed = it.run_text_keep_going("<text>", text);
        let mut out = format!("{failed} failed\n{}", it.take_output());
        let r = it.run_text("-c", &format!("source {{{}}}", path.display()));
        out.push_str(&format!("{r:?}\n{}", it.take_output()));
        out
    }

    #[test]
    fn a_packed_file_runs_and_reports_as_a_plain_one() {
        let text = large_file();
        let path = std::env::temp_dir().join(format!("rusoar-large-{}.soar", std::process::id()));
        std::fs::write(&path, &text).unwrap();
        let packed = run(SourceMap::new(), &text, &path);
        let plain = run(SourceMap::packing(usize::MAX, 1), &text, &path);
        std::fs::remove_file(&path).ok();
        assert_eq!(packed, plain);
        assert!(packed.contains("not connected"), "{packed}");
        assert!(packed.contains("duplicate"), "{packed}");
        assert!(packed.contains("Ignoring production bad"), "{packed}");
    }
}
