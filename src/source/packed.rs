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
    /// The line ends before it, so that a line number is known without unpacking.
    lines_before: usize,
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

impl PackedText {
    /// Packs `text` in blocks of about `block` bytes.
    pub fn pack(text: &str, block: usize) -> PackedText {
        let block = block.max(1);
        let mut blocks = Vec::with_capacity(text.len() / block + 1);
        let (mut start, mut lines) = (0, 0);
        while start < text.len() {
            let end = block_end(text, start, block);
            let piece = &text[start..end];
            blocks.push(Block {
                start,
                lines_before: lines,
                starts_line: start == 0 || text.as_bytes()[start - 1] == b'\n',
                packed: miniz_oxide::deflate::compress_to_vec(piece.as_bytes(), LEVEL).into(),
            });
            lines += piece.bytes().filter(|&b| b == b'\n').count();
            start = end;
        }
        PackedText {
            len: text.len(),
            first_nul: text.find('\0'),
            blocks,
        }
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
                "[a-z {}\\\\]{0,12}",
            ],
            0..40,
        )
        .prop_map(|v| v.concat())
    }

    proptest! {
        #[test]
        fn unpacks_to_the_text(text in texts(), block in 1usize..20) {
            let p = PackedText::pack(&text, block);
            prop_assert_eq!(p.unpack(), text.clone());
            prop_assert_eq!(p.len(), text.len());
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
