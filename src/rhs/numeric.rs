//! The numeric fast path of `exec` for registered functions that read their argument string
//! as comma-separated numbers (the thesis's `getlength`, `checkwallrelation`, ...).
//!
//! `exec` hands a registered function the text of its arguments, concatenated (Soar manual,
//! ch. 3, "User-defined functions and interface commands as RHS actions"):
//! `(exec f <x>|, |<y>)` gives `"3000, -1.500000"`. A function that only splits that text
//! on commas and parses each field as a number can also register a numeric form, which gets
//! those numbers directly, without the text being printed and read back. Both forms must
//! compute the same thing; [`numbers`] yields exactly the numbers the text form would read,
//! or `None` when the arguments are not of that shape, and then the text form runs.

use crate::symbols::{Sym, SymData, Symbols};

/// A function's numeric form: the numbers its argument string holds, in order, to its
/// result; `None` lets the text form answer (a wrong count of numbers, say, whose error
/// message quotes the text).
pub type NumericRhsFn = Box<dyn FnMut(&[f64]) -> Option<String>>;

/// The numbers of `args` when they alternate number, separator, number, ..., where a
/// separator is a string of spaces and tabs around exactly one comma: then the text form's
/// fields are exactly these numbers as printed. An integer reads back as itself (to the
/// nearest double, as `as f64` rounds); a float is printed with six decimals, so it reads
/// back as the double nearest to it rounded to six decimals, which is computed here unless
/// it lies too near a rounding tie or is too large to tell (then `None`, and the text form
/// decides).
pub fn numbers(symbols: &Symbols, args: &[Sym], out: &mut Vec<f64>) -> Option<()> {
    out.clear();
    if args.is_empty() || args.len().is_multiple_of(2) {
        return None;
    }
    // The separators of one call are nearly always one constant: its text is checked once.
    let mut last_separator = Sym(u32::MAX);
    for (i, &a) in args.iter().enumerate() {
        match (i % 2, symbols.get(a)) {
            (0, SymData::Int(n)) => out.push(*n as f64),
            (0, SymData::Float(f)) => out.push(six_decimals(*f)?),
            (1, SymData::Str(_)) if a == last_separator => {}
            (1, SymData::Str(s)) if is_separator(s) => last_separator = a,
            _ => return None,
        }
    }
    Some(())
}

/// `f` printed with `{:.6}` and read back, when that can be told without printing it.
fn six_decimals(f: f64) -> Option<f64> {
    let scaled = f * 1e6;
    // Below 2^40 the product's rounding error (under 2^-12) cannot move it across a tie
    // that lies further than 1e-3 away.
    if !scaled.is_finite() || scaled.abs() >= (1u64 << 40) as f64 {
        return None;
    }
    let k = scaled.round();
    if ((scaled - k).abs() - 0.5).abs() < 1e-3 {
        return None;
    }
    // k and 1e6 are exact, so the quotient is the double nearest to k / 10^6, as parsing
    // the six-decimal text gives.
    Some(k / 1e6)
}

fn is_separator(s: &str) -> bool {
    s.bytes().filter(|&b| b == b',').count() == 1
        && s.bytes().all(|b| matches!(b, b',' | b' ' | b'\t'))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What the text form reads: print with exec's float format, then parse.
    fn via_text(f: f64) -> f64 {
        format!("{f:.6}").parse().unwrap()
    }

    #[test]
    fn floats_read_back_as_their_six_decimal_text() {
        let mut state = 0x9e3779b97f4a7c15u64;
        let mut fast = 0;
        for _ in 0..200_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let mag = [1.0, 1e3, 1e5, 1e-3][(state % 4) as usize];
            let f = ((state >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * mag;
            if let Some(g) = six_decimals(f) {
                assert_eq!(g.to_bits(), via_text(f).to_bits(), "{f:e}");
                fast += 1;
            }
        }
        // Only values next to a rounding tie go the slow way (about 0.2 % of them).
        assert!(fast > 199_000, "fast path taken for {fast} of 200,000");
        for f in [
            0.0, -0.0, 1.5, -2.25, 3025.0, 1e-7, -1e-7, 0.0000005, 123456.789,
        ] {
            if let Some(g) = six_decimals(f) {
                assert_eq!(g.to_bits(), via_text(f).to_bits(), "{f:e}");
            }
        }
        assert_eq!(six_decimals(1e300), None);
        assert_eq!(six_decimals(f64::NAN), None);
    }

    #[test]
    fn only_number_separator_sequences_take_the_fast_path() {
        let mut s = Symbols::new();
        let (a, b) = (s.int(3000), s.float(-1.5));
        let (sep, bare, word) = (s.str(", "), s.str(""), s.str("x"));
        let mut out = Vec::new();
        assert!(numbers(&s, &[a, sep, b], &mut out).is_some());
        assert_eq!(out, vec![3000.0, -1.5]);
        // "3000-1.500000" is one field, not two numbers.
        assert!(numbers(&s, &[a, bare, b], &mut out).is_none());
        assert!(numbers(&s, &[a, b], &mut out).is_none());
        assert!(numbers(&s, &[word], &mut out).is_none());
        assert!(numbers(&s, &[], &mut out).is_none());
        let two = s.str(",,");
        assert!(numbers(&s, &[a, two, b], &mut out).is_none());
    }
}
