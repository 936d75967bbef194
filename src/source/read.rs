//! Reading a file into the source map: a large one is packed as it is read, so that its
//! whole text is never in memory at once (at 100,000 rules that would be 16 MB freed just
//! as the rules start to fill memory, which the allocator need not hand back at once).
//! Bytes that are not UTF-8 read as U+FFFD, as `String::from_utf8_lossy` reads them.

use super::packed::Packer;
use super::{FileId, FileText, SourceMap};
use std::io::Read;
use std::path::Path;
use std::sync::Arc;

/// Bytes read at a time.
const CHUNK: usize = 64 << 10;

impl SourceMap {
    /// Reads the file at `path` and registers its text under `name`.
    pub(crate) fn read_file(&mut self, name: String, path: &Path) -> std::io::Result<FileId> {
        let mut file = std::fs::File::open(path)?;
        let size = file.metadata().map_or(0, |m| m.len());
        if size < self.pack_at as u64 {
            let mut bytes = Vec::new();
            file.read_to_end(&mut bytes)?;
            let text = String::from_utf8(bytes)
                .unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned());
            return Ok(self.add(name, text));
        }
        let mut packer = Packer::new(self.block);
        let mut buf = vec![0u8; CHUNK];
        // The bytes of a character cut at the end of the last chunk.
        let mut carry: Vec<u8> = Vec::new();
        let mut text = String::with_capacity(CHUNK);
        loop {
            let n = match file.read(&mut buf) {
                Ok(n) => n,
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
                Err(e) => return Err(e),
            };
            if n == 0 {
                break;
            }
            carry.extend_from_slice(&buf[..n]);
            text.clear();
            let kept = decode(&carry, &mut text);
            packer.push(&text);
            carry.drain(..carry.len() - kept);
        }
        if !carry.is_empty() {
            packer.push(&String::from_utf8_lossy(&carry));
        }
        Ok(self.push_file(name, FileText::Packed(Arc::new(packer.finish()))))
    }
}

/// Appends the text of `bytes` to `out`, U+FFFD for each invalid sequence; a sequence cut
/// short by the end of `bytes` is left out. Returns how many bytes were left out.
fn decode(bytes: &[u8], out: &mut String) -> usize {
    let mut rest = bytes;
    loop {
        match std::str::from_utf8(rest) {
            Ok(s) => {
                out.push_str(s);
                return 0;
            }
            Err(e) => {
                let (valid, after) = rest.split_at(e.valid_up_to());
                out.push_str(std::str::from_utf8(valid).unwrap_or_default());
                match e.error_len() {
                    None => return after.len(),
                    Some(bad) => {
                        out.push(char::REPLACEMENT_CHARACTER);
                        rest = &after[bad..];
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// Read in chunks, bytes decode as they do whole.
        #[test]
        fn decodes_in_pieces_as_whole(bytes in proptest::collection::vec(prop_oneof![
            Just(0xe6u8), Just(0x97), Just(0xa5), Just(0xc3), Just(0xa9), Just(0xff), Just(b'a'), Just(b'\n')
        ], 0..80), cut in 1usize..7) {
            let mut out = String::new();
            let mut carry = Vec::new();
            for piece in bytes.chunks(cut) {
                carry.extend_from_slice(piece);
                let kept = decode(&carry, &mut out);
                carry.drain(..carry.len() - kept);
            }
            out.push_str(&String::from_utf8_lossy(&carry));
            prop_assert_eq!(out, String::from_utf8_lossy(&bytes).into_owned());
        }
    }

    #[test]
    fn a_large_file_reads_as_its_text() {
        let text: String = (0..3000).map(|i| format!("echo {i} é\n")).collect();
        let path = std::env::temp_dir().join(format!("rusoar-read-{}.soar", std::process::id()));
        std::fs::write(&path, &text).unwrap();
        let mut map = SourceMap::packing(1000, 256);
        let id = map.read_file("f".into(), &path).unwrap();
        std::fs::remove_file(&path).ok();
        assert!(matches!(map.file_text(id), FileText::Packed(_)));
        assert_eq!(map.text(id), text);
    }
}
