//! A large text kept compressed, in blocks that unpack on their own. A sourced file's text
//! stays for the diagnostics that point into it, yet once its commands have run only a few
//! lines of it are ever read again (the ones a diagnostic shows); a rule file of 100,000
//! rules is 16 MB of text and about 1.2 MB packed.

/// Bytes of text a block holds, about: a block ends after the last line end that fits.
pub(crate) const BLOCK: usize = 64 << 10;

/// The compression level (1, the fastest: 16 MB of rules pack in about 30 ms).
const LEVEL: u8 = 1;

/// One block: where its text starts in the whole, and its text compressed.
#[derive(Debug)]
struct Block {
    start: usize,
    /// The line ends before it and in it, so that a line number is known without
    /// unpacking.
    lines_before: usize,
    lines: usize,
    /// Whether it starts a line (the text's start, or just after a line end).
    starts_line: bool,
    packed: Box<[u8]>,
}

/// A text in compressed blocks, each of whole characters.
#[derive(Debug)]
pub(crate) struct PackedText {
    len: usize,
    /// The offset of the first NUL byte, where a text's commands end.
    first_nul: Option<usize>,
    blocks: Vec<Block>,
}

/// Whole lines of a packed text, unpacked: `text` starts at byte `start` of the whole,
/// which is the start of line `first_line` (0-based).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Lines {
    pub start: usize,
    pub first_line: usize,
    pub text: String,
}

/// Packs a text given piece by piece (a file as it is read), so that the whole text is
/// never in memory at once.
pub(crate) struct Packer {
    block: usize,
    /// Text not yet packed: less than two blocks' worth between calls.
    pending: String,
    /// Whether the text packed so far ends a line.
    after_line_end: bool,
    text: PackedText,
}

impl Packer {
    /// A packer for blocks of about `block` bytes.
    pub fn new(block: usize) -> Self {
        Packer {
            block: block.max(1),
            pending: String::new(),
            after_line_end: true,
            text: PackedText {
                len: 0,
                first_nul: None,
                blocks: Vec::new(),
            },
        }
    }

    /// Appends `piece` to the text.
    pub fn push(&mut self, piece: &str) {
        if self.text.first_nul.is_none() {
            if let Some(n) = piece.find('\0') {
                self.text.first_nul = Some(self.text.len + self.pending.len() + n);
            }
        }
        self.pending.push_str(piece);
        let mut start = 0;
        while self.pending.len() - start > 2 * self.block {
            let end = block_end(&self.pending, start, self.block);
            self.pack_block(start, end);
            start = end;
        }
        self.pending.drain(..start);
    }

    /// The text packed.
    pub fn finish(mut self) -> PackedText {
        let mut start = 0;
        while start < self.pending.len() {
            let end = block_end(&self.pending, start, self.block);
            self.pack_block(start, end);
            start = end;
        }
        self.text
    }

    /// Packs `pending[start..end]` as the next block.
    fn pack_block(&mut self, start: usize, end: usize) {
        let piece = &self.pending[start..end];
        let lines_before = self
            .text
            .blocks
            .last()
            .map_or(0, |b| b.lines_before + b.lines);
        self.text.blocks.push(Block {
            start: self.text.len,
            lines_before,
            lines: piece.bytes().filter(|&b| b == b'\n').count(),
            starts_line: self.after_line_end,
            packed: miniz_oxide::deflate::compress_to_vec(piece.as_bytes(), LEVEL).into(),
        });
        self.after_line_end = piece.ends_with('\n');
        self.text.len += piece.len();
    }
}

impl PackedText {
    /// Packs `text` in blocks of about `block` bytes.
    pub fn pack(text: &str, block: usize) -> PackedText {
        let mut p = Packer::new(block);
        p.push(text);
        p.finish()
    }

    /// The length of the whole text in bytes.
    pub fn len(&self) -> usize {
        self.len
    }

    /// The offset of the first NUL byte, if there is one.
    pub fn first_nul(&self) -> Option<usize> {
        self.first_nul
    }

    /// The bytes the text takes packed (for the tests and `stats`).
    #[cfg(test)]
    pub fn packed_len(&self) -> usize {
        self.blocks.iter().map(|b| b.packed.len()).sum()
    }

    /// How many blocks there are.
    pub fn block_count(&self) -> usize {
        self.blocks.len()
    }

    /// Where block `i` starts in the whole text (the text's length past the last block).
    pub fn block_start(&self, i: usize) -> usize {
        self.blocks.get(i).map_or(self.len, |b| b.start)
    }

    /// Appends block `i`'s text to `out`.
    pub fn unpack_block(&self, i: usize, out: &mut String) {
        let Some(b) = self.blocks.get(i) else {
            return;
        };
        // The blocks are this module's own output, so neither step fails; were one to, the
        // text would read as blanks rather than stop the kernel.
        let bytes = miniz_oxide::inflate::decompress_to_vec(&b.packed).unwrap_or_default();
        match String::from_utf8(bytes) {
            Ok(s) if s.len() == self.block_start(i + 1) - b.start => out.push_str(&s),
            _ => out.extend(std::iter::repeat_n(' ', self.block_start(i + 1) - b.start)),
        }
    }

    /// The whole text.
    pub fn unpack(&self) -> String {
        let mut out = String::with_capacity(self.len);
        for i in 0..self.blocks.len() {
            self.unpack_block(i, &mut out);
        }
        out
    }

    /// The block holding byte `offset` (the last block for the text's end).
    fn block_of(&self, offset: usize) -> usize {
        self.blocks
            .partition_point(|b| b.start <= offset)
            .saturating_sub(1)
    }

    /// The whole lines that hold bytes `start..end` (both clamped to the text).
    pub fn lines(&self, start: usize, end: usize) -> Lines {
        if self.blocks.is_empty() {
            return Lines {
                start: 0,
                first_line: 0,
                text: String::new(),
            };
        }
        let start = start.min(self.len);
        let end = end.clamp(start, self.len);
        let mut first = self.block_of(start);
        while first > 0 && !self.blocks[first].starts_line {
            first -= 1;
        }
        let mut last = self.block_of(end);
        while last + 1 < self.blocks.len() && !self.blocks[last + 1].starts_line {
            last += 1;
        }
        let mut text = String::with_capacity(self.block_start(last + 1) - self.blocks[first].start);
        for i in first..=last {
            self.unpack_block(i, &mut text);
        }
        Lines {
            start: self.blocks[first].start,
            first_line: self.blocks[first].lines_before,
            text,
        }
    }
}

/// Where a block that starts at `start` ends: after the last line end within `block` bytes
/// if there is one in its second half, else at the last character boundary within them
/// (or after one character, if that is longer).
fn block_end(text: &str, start: usize, block: usize) -> usize {
    let limit = start.saturating_add(block);
    if limit >= text.len() {
        return text.len();
    }
    let half = start + block / 2;
    if let Some(nl) = text.as_bytes()[half..limit].iter().rposition(|&b| b == b'\n') {
        return half + nl + 1;
    }
    let mut end = limit;
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    if end > start {
        return end;
    }
    let mut end = limit + 1;
    while !text.is_char_boundary(end) {
        end += 1;
    }
    end
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn texts() -> impl Strategy<Value = String> {
        proptest::collection::vec(
            prop_oneof![
                Just("\n".to_string()),
                Just("é".to_string()),
                Just("日本".to_string()),
                Just("\0".to_string()),
                "[a-z {}\\\\]{0,12}",
            ],
            0..40,
        )
        .prop_map(|v| v.concat())
    }

    proptest! {
        #[test]
        fn unpacks_to_the_text(text in texts(), block in 1usize..20, cuts in proptest::collection::vec(0usize..400, 0..6)) {
            let p = PackedText::pack(&text, block);
            prop_assert_eq!(p.unpack(), text.clone());
            prop_assert_eq!(p.len(), text.len());
            prop_assert_eq!(p.first_nul(), text.find('\0'));
            // Given in pieces, the same text.
            let mut packer = Packer::new(block);
            let mut at = 0;
            for c in cuts {
                let mut c = c.min(text.len());
                while !text.is_char_boundary(c) {
                    c -= 1;
                }
                if c > at {
                    packer.push(&text[at..c]);
                    at = c;
                }
            }
            packer.push(&text[at..]);
            let q = packer.finish();
            prop_assert_eq!(q.unpack(), text.clone());
            prop_assert_eq!(q.first_nul(), text.find('\0'));
            let lines = q.lines(0, text.len());
            prop_assert_eq!(lines.first_line, 0);
        }

        #[test]
        fn lines_are_whole_and_in_place(text in texts(), block in 1usize..20, a in 0usize..300, b in 0usize..300) {
            let p = PackedText::pack(&text, block);
            let (start, end) = (a.min(b), a.max(b));
            let l = p.lines(start, end);
            let (s, e) = (start.min(text.len()), end.clamp(start.min(text.len()), text.len()));
            // It covers the bytes, starts a line and ends one (or the text).
            prop_assert!(l.start <= s && e <= l.start + l.text.len());
            prop_assert_eq!(&text[l.start..l.start + l.text.len()], l.text.as_str());
            prop_assert!(l.start == 0 || text.as_bytes()[l.start - 1] == b'\n');
            let after = l.start + l.text.len();
            prop_assert!(after == text.len() || text.as_bytes()[after - 1] == b'\n');
            prop_assert_eq!(l.first_line, text[..l.start].matches('\n').count());
        }
    }

    #[test]
    fn rule_text_packs_small() {
        let text: String = (0..2000)
            .map(|i| format!("sp {{r*{i}\n   (state <s> ^superstate nil)\n-->\n   (<s> ^a {i})}}\n"))
            .collect();
        let p = PackedText::pack(&text, BLOCK);
        assert!(p.packed_len() * 5 < text.len(), "{} of {}", p.packed_len(), text.len());
        assert_eq!(p.unpack(), text);
    }
}
