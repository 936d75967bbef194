//! Helpers shared by the integration tests.

/// Replaces each `D.DDD` in `line` (whose following text passes `keep`) with `#.###`.
pub fn mask_decimals(line: &str, keep: impl Fn(&str) -> bool) -> String {
    let mut out = String::new();
    let mut rest = line;
    while let Some(i) = rest.find(|c: char| c.is_ascii_digit()) {
        out.push_str(&rest[..i]);
        let tail = &rest[i..];
        let int = tail.bytes().take_while(u8::is_ascii_digit).count();
        let frac = tail[int..]
            .strip_prefix('.')
            .map_or(0, |f| f.bytes().take_while(u8::is_ascii_digit).count());
        let len = if frac > 0 { int + 1 + frac } else { int };
        if frac == 3 && keep(&tail[len..]) {
            out.push_str("#.###");
        } else {
            out.push_str(&tail[..len]);
        }
        rest = &tail[len..];
    }
    out.push_str(rest);
    out
}
