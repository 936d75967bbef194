//! `gp`: one `sp` body with `[a b ...]` alternatives stands for one rule per combination
//! (Soar manual, chapter 9, `gp`). The rules are named `NAME*1`, `NAME*2`, ... with the
//! first alternative list varying fastest, as the official kernel numbers them (soar-sml
//! 9.6.5 printed `gen*1` to `gen*8` in that order for three lists of two).

use super::{CmdResult, Ctx, Interpreter};

/// The bodies a `gp` body stands for, in the official kernel's order, or its error text;
/// more than `max` bodies (`soar max-gp`) is an error.
pub(super) fn expand(body: &str, max: usize) -> Result<Vec<String>, String> {
    // The text between the lists, and each list's alternatives.
    let mut pieces: Vec<&str> = Vec::new();
    let mut lists: Vec<Vec<&str>> = Vec::new();
    let bytes = body.as_bytes();
    let (mut start, mut i) = (0, 0);
    while i < bytes.len() {
        match bytes[i] {
            // `|...|` is one constant: brackets inside it are text.
            b'|' => i = skip_pipe(bytes, i),
            b'[' => {
                let close = find_close(bytes, i + 1).map_err(str::to_string)?;
                pieces.push(&body[start..i]);
                let values = alternatives(&body[i + 1..close]);
                if values.is_empty() {
                    return Err("gp can't have empty value collections".into());
                }
                lists.push(values);
                start = close + 1;
                i = close + 1;
            }
            _ => i += 1,
        }
    }
    pieces.push(&body[start..]);
    let total = lists
        .iter()
        .try_fold(1usize, |n, l| n.checked_mul(l.len()))
        .filter(|&n| n <= max)
        .ok_or_else(|| {
            let total = lists.iter().fold(1u128, |n, l| n.saturating_mul(l.len() as u128));
            // 9.6's text, without its space before "exceeded".
            format!("gp-max of {max}exceeded, current production produces {total} productions. You can run 'soar gp-max' to set a higher limit.")
        })?;
    let mut out = Vec::with_capacity(total);
    for n in 0..total {
        let mut text = String::with_capacity(body.len());
        let mut rest = n;
        for (piece, list) in pieces.iter().zip(&lists) {
            text.push_str(piece);
            text.push_str(list[rest % list.len()]);
            rest /= list.len();
        }
        text.push_str(pieces[pieces.len() - 1]);
        out.push(text);
    }
    Ok(out)
}

/// The index just past the `|...|` that starts at `at` (the end, if it never closes).
fn skip_pipe(bytes: &[u8], at: usize) -> usize {
    let mut i = at + 1;
    while i < bytes.len() {
        match bytes[i] {
            b'\\' => i += 2,
            b'|' => return i + 1,
            _ => i += 1,
        }
    }
    bytes.len()
}

/// The `]` that closes a list opened before `from`.
fn find_close(bytes: &[u8], from: usize) -> Result<usize, &'static str> {
    let mut i = from;
    while i < bytes.len() {
        match bytes[i] {
            b'|' => i = skip_pipe(bytes, i),
            b']' => return Ok(i),
            _ => i += 1,
        }
    }
    Err("gp syntax error, unmatched values bracket.")
}

/// A list's alternatives: its words, a `|...|` constant being one word.
fn alternatives(list: &str) -> Vec<&str> {
    let bytes = list.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i].is_ascii_whitespace() {
            i += 1;
            continue;
        }
        let start = i;
        while i < bytes.len() && !bytes[i].is_ascii_whitespace() {
            i = if bytes[i] == b'|' {
                skip_pipe(bytes, i)
            } else {
                i + 1
            };
        }
        out.push(&list[start..i.min(list.len())]);
    }
    out
}

impl Interpreter {
    /// `gp {NAME body}`: each combination becomes `sp {NAME*N body}`, loaded as `sp` loads
    /// it (a `*` each, duplicates ignored with 9.6's message).
    pub(super) fn cmd_gp(&mut self, ctx: &Ctx) -> CmdResult {
        let [_, body] = ctx.cmd.words.as_slice() else {
            return Err(ctx.error("Syntax: gp { production_body }"));
        };
        let max = usize::try_from(self.agent.settings.max_gp).unwrap_or(0);
        let bodies = expand(&body.text, max).map_err(|m| ctx.error(m))?;
        let outer = std::mem::replace(&mut self.in_gp, true);
        let loaded = bodies.iter().enumerate().try_for_each(|(n, b)| {
            // Each rule's name is its body's first word (alternatives in it expanded).
            let b = b.trim_start();
            let name_end = b.find(char::is_whitespace).unwrap_or(b.len());
            let (name, rest) = b.split_at(name_end);
            self.run_text("gp", &format!("sp {{{name}*{}{rest}}}", n + 1))
        });
        self.in_gp = outer;
        loaded.map(|()| String::new())
    }
}

#[cfg(test)]
mod tests {
    use super::expand;

    #[test]
    fn the_first_list_varies_fastest() {
        let out = expand("g (state <s> ^a [b c] ^d [1 2]) --> (<s> ^e [x y])", 20_000).unwrap();
        assert_eq!(out.len(), 8);
        assert_eq!(out[0], "g (state <s> ^a b ^d 1) --> (<s> ^e x)");
        assert_eq!(out[1], "g (state <s> ^a c ^d 1) --> (<s> ^e x)");
        assert_eq!(out[2], "g (state <s> ^a b ^d 2) --> (<s> ^e x)");
        assert_eq!(out[7], "g (state <s> ^a c ^d 2) --> (<s> ^e y)");
    }

    #[test]
    fn pipes_are_one_word_and_hide_brackets() {
        let out = expand("g (state <s> ^a [ |x y| 3.5 ]) --> (write |[not]|)", 20_000).unwrap();
        assert_eq!(
            out,
            [
                "g (state <s> ^a |x y|) --> (write |[not]|)",
                "g (state <s> ^a 3.5) --> (write |[not]|)"
            ]
        );
    }

    /// A name with alternatives and text that is not ASCII: each body is cut at its own
    /// first space.
    #[test]
    fn names_with_alternatives_are_expanded_too() {
        let out = expand("é[a bb] (state <s>) --> (write é)", 20_000).unwrap();
        assert_eq!(out, ["éa (state <s>) --> (write é)", "ébb (state <s>) --> (write é)"]);
    }

    #[test]
    fn bad_lists_are_errors() {
        assert_eq!(
            expand("g (state <s> ^a [b c) --> (<s> ^c d)", 20_000),
            Err("gp syntax error, unmatched values bracket.".to_string())
        );
        assert_eq!(
            expand("g (state <s> ^a []) --> (<s> ^c d)", 20_000),
            Err("gp can't have empty value collections".to_string())
        );
    }

    #[test]
    fn more_rules_than_max_gp_is_an_error() {
        let e = expand("g (state <s> ^a [1 2] ^b [3 4]) --> (<s> ^c d)", 3).unwrap_err();
        assert_eq!(e, "gp-max of 3exceeded, current production produces 4 productions. You can run 'soar gp-max' to set a higher limit.");
        // 2^80 combinations: an error, not an allocation.
        let huge = format!("g (state <s> {}) --> (<s> ^c d)", "^a [1 2] ".repeat(80));
        assert!(expand(&huge, 20_000).unwrap_err().contains("1208925819614629174706176 productions"));
    }
}
