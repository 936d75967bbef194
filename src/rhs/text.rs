//! Symbol texts as 9.6 prints them, C conversions (`strtol`, `strtod`, `%f`), and the
//! string functions.

use super::{fresh, RhsContext};
use crate::symbols::{Sym, SymData, Symbols};

pub use crate::printer::constants::{c_fixed, c_general};

/// 9.6's `Symbol::to_string()`, as `write`, `concat`, `exec`, `strlen` see a symbol:
/// strings without bars, floats with 6 decimals, identifiers as `S1`.
pub fn value_text(symbols: &Symbols, s: Sym) -> String {
    match symbols.get(s) {
        SymData::Str(x) => x.to_string(),
        SymData::Int(i) => i.to_string(),
        SymData::Float(f) => c_fixed(*f, 6),
        SymData::Id(d) => format!("{}{}", d.letter as char, d.number),
    }
}

/// [`value_text`] appended to `out` (no string of its own: `exec` joins many).
pub fn push_value_text(symbols: &Symbols, s: Sym, out: &mut String) {
    use std::fmt::Write;
    match symbols.get(s) {
        SymData::Str(x) => out.push_str(x),
        SymData::Int(i) => {
            let _ = write!(out, "{i}");
        }
        SymData::Float(f) if f.is_finite() => {
            let _ = write!(out, "{f:.6}");
        }
        SymData::Float(f) => out.push_str(&c_fixed(*f, 6)),
        SymData::Id(d) => {
            let _ = write!(out, "{}{}", d.letter as char, d.number);
        }
    }
}

/// 9.6's `%y`: rereadable (strings get bars when they would read back as something else).
pub(super) fn rereadable_text(symbols: &Symbols, s: Sym) -> String {
    match symbols.get(s) {
        SymData::Str(x) => crate::printer::rereadable(x),
        _ => value_text(symbols, s),
    }
}

/// C's `isspace` in the C locale.
fn c_space(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\n' | 0x0b | 0x0c | b'\r')
}

/// `errno == ERANGE` from a C conversion.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Erange;

/// `strtol(s, NULL, 10)` on 64-bit Linux: leading white space, a sign, decimal digits.
/// `Err(Erange)` when out of range; no digits give `Ok(0)` without an error.
pub fn c_strtol(s: &str) -> Result<i64, Erange> {
    let b = s.as_bytes();
    let mut i = 0;
    while i < b.len() && c_space(b[i]) {
        i += 1;
    }
    let neg = match b.get(i) {
        Some(b'-') => {
            i += 1;
            true
        }
        Some(b'+') => {
            i += 1;
            false
        }
        _ => false,
    };
    let mut v: i128 = 0;
    let mut overflow = false;
    while i < b.len() && b[i].is_ascii_digit() {
        if !overflow {
            v = v * 10 + i128::from(b[i] - b'0');
            if v > i128::from(i64::MAX) + 1 {
                overflow = true;
            }
        }
        i += 1;
    }
    let v = if neg { -v } else { v };
    if overflow || v > i128::from(i64::MAX) || v < i128::from(i64::MIN) {
        return Err(Erange);
    }
    Ok(v as i64)
}

/// `strtod(s, NULL)` as glibc: leading white space, a sign, then `inf`/`infinity`, `nan`
/// (optionally `nan(...)`), a hexadecimal float (`0x1.8p3`) or a decimal one; the longest
/// valid prefix counts and no prefix gives 0. The flag is `errno == ERANGE`: the value
/// overflowed to infinity, or a non-zero number came out zero or subnormal.
pub fn c_strtod(s: &str) -> (f64, bool) {
    let b = s.as_bytes();
    let mut i = 0;
    while i < b.len() && c_space(b[i]) {
        i += 1;
    }
    let neg = match b.get(i) {
        Some(b'-') => {
            i += 1;
            true
        }
        Some(b'+') => {
            i += 1;
            false
        }
        _ => false,
    };
    let sign = |v: f64| if neg { -v } else { v };
    let rest = &b[i..];
    let lower: Vec<u8> = rest
        .iter()
        .take(8)
        .map(|c| c.to_ascii_lowercase())
        .collect();
    if lower.starts_with(b"inf") {
        return (sign(f64::INFINITY), false);
    }
    if lower.starts_with(b"nan") {
        return (sign(f64::NAN), false);
    }
    if lower.len() >= 2
        && &lower[..2] == b"0x"
        && rest.get(2).is_some_and(|c| {
            c.is_ascii_hexdigit() || (*c == b'.' && rest.get(3).is_some_and(u8::is_ascii_hexdigit))
        })
    {
        let (v, nonzero) = hex_float(&rest[2..]);
        return (sign(v), range_error(v, nonzero));
    }
    // Decimal: digits [. digits] [e [sign] digits], at least one mantissa digit.
    let mut j = 0;
    let mut int_digits = String::new();
    while j < rest.len() && rest[j].is_ascii_digit() {
        int_digits.push(rest[j] as char);
        j += 1;
    }
    let mut frac_digits = String::new();
    if j < rest.len() && rest[j] == b'.' {
        let mut k = j + 1;
        while k < rest.len() && rest[k].is_ascii_digit() {
            frac_digits.push(rest[k] as char);
            k += 1;
        }
        if !int_digits.is_empty() || !frac_digits.is_empty() {
            j = k;
        }
    }
    if int_digits.is_empty() && frac_digits.is_empty() {
        return (0.0, false);
    }
    let mut exp = String::new();
    if j < rest.len() && (rest[j] == b'e' || rest[j] == b'E') {
        let mut k = j + 1;
        let mut e = String::new();
        if k < rest.len() && (rest[k] == b'+' || rest[k] == b'-') {
            e.push(rest[k] as char);
            k += 1;
        }
        let start = k;
        while k < rest.len() && rest[k].is_ascii_digit() {
            e.push(rest[k] as char);
            k += 1;
        }
        if k > start {
            exp = e;
        }
    }
    let nonzero = int_digits
        .bytes()
        .chain(frac_digits.bytes())
        .any(|c| c != b'0');
    // Very long exponents: clamp, keeping the sign (Rust's parser needs a sane exponent).
    let exp = clamp_exponent(&exp);
    let text = format!(
        "{}.{}e{}",
        if int_digits.is_empty() {
            "0"
        } else {
            &int_digits
        },
        if frac_digits.is_empty() {
            "0"
        } else {
            &frac_digits
        },
        if exp.is_empty() { "0" } else { &exp }
    );
    let v = text.parse::<f64>().unwrap_or(0.0);
    (sign(v), range_error(v, nonzero))
}

fn clamp_exponent(exp: &str) -> String {
    let (neg, digits) = match exp.as_bytes().first() {
        Some(b'-') => (true, &exp[1..]),
        Some(b'+') => (false, &exp[1..]),
        _ => (false, exp),
    };
    let digits = digits.trim_start_matches('0');
    if digits.len() > 6 {
        return if neg {
            "-999999".into()
        } else {
            "999999".into()
        };
    }
    if digits.is_empty() {
        return String::new();
    }
    format!("{}{digits}", if neg { "-" } else { "" })
}

fn range_error(v: f64, nonzero: bool) -> bool {
    v.is_infinite() || (nonzero && (v == 0.0 || v.abs() < f64::MIN_POSITIVE))
}

/// The part of a hexadecimal float after `0x`: hex digits, `.`, hex digits, `p` exponent.
fn hex_float(b: &[u8]) -> (f64, bool) {
    let mut mant: u64 = 0;
    let mut exp2: i64 = 0;
    let mut nonzero = false;
    let mut sticky = false;
    let mut i = 0;
    let mut seen_point = false;
    while i < b.len() {
        let c = b[i];
        if c == b'.' && !seen_point {
            seen_point = true;
        } else if let Some(d) = (c as char).to_digit(16) {
            if d != 0 {
                nonzero = true;
            }
            if mant >> 60 == 0 {
                mant = (mant << 4) | u64::from(d);
                if seen_point {
                    exp2 -= 4;
                }
            } else {
                sticky |= d != 0;
                if !seen_point {
                    exp2 += 4;
                }
            }
        } else {
            break;
        }
        i += 1;
    }
    if i < b.len() && (b[i] == b'p' || b[i] == b'P') {
        let mut k = i + 1;
        let mut eneg = false;
        if k < b.len() && (b[k] == b'+' || b[k] == b'-') {
            eneg = b[k] == b'-';
            k += 1;
        }
        let start = k;
        let mut e: i64 = 0;
        while k < b.len() && b[k].is_ascii_digit() {
            e = (e * 10 + i64::from(b[k] - b'0')).min(1 << 20);
            k += 1;
        }
        if k > start {
            exp2 += if eneg { -e } else { e };
        }
    }
    if sticky {
        mant |= 1;
    }
    let v = (mant as f64) * 2f64.powi(exp2.clamp(-2200, 2200) as i32);
    (v, nonzero)
}

/// `timestamp`: `YYYY-MM-DD HH:MM:SS.mmm` (UTC here; 9.6 uses local time).
pub(super) fn timestamp_now() -> String {
    let now = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .unwrap_or_default();
    timestamp_text(now.as_secs(), now.subsec_millis())
}

pub(super) fn timestamp_text(secs: u64, millis: u32) -> String {
    let days = (secs / 86_400) as i64;
    let rem = secs % 86_400;
    // Civil date from days since 1970-01-01 (Howard Hinnant's algorithm).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}-{m:02}-{d:02} {:02}:{:02}:{:02}.{millis:03}",
        rem / 3600,
        (rem / 60) % 60,
        rem % 60
    )
}

pub(super) fn trim_capitalize(
    is_trim: bool,
    args: &[Sym],
    ctx: &mut RhsContext,
) -> Result<Option<Sym>, String> {
    let (quoted, plain) = if is_trim {
        ("'trim'", "'trim' function")
    } else {
        ("'capitalize-symbol'", "capitalize-symbol function")
    };
    let Some(&sym) = args.first() else {
        return fresh(
            ctx,
            &format!("Error: {quoted} function called with no arguments."),
        );
    };
    let s = match ctx.symbols.get(sym) {
        SymData::Str(s) => s.to_string(),
        _ => {
            let msg = format!("Error: non-symbol ({}) passed to {plain}.", ctx.y(sym));
            return fresh(ctx, &msg);
        }
    };
    if args.len() > 1 {
        return fresh(ctx, &format!("Error: {quoted} takes exactly 1 argument."));
    }
    let out = if is_trim {
        s.trim_matches([' ', '\t', '\n']).to_string()
    } else {
        let mut b = s.into_bytes();
        if let Some(c) = b.first_mut() {
            *c = c.to_ascii_uppercase();
        }
        String::from_utf8(b).unwrap_or_default()
    };
    Ok(Some(ctx.symbols.str(&out)))
}

/// `accept`: reads lines from standard input until one holds a symbol, and returns that
/// first symbol (9.6's text-input rules, [`accept_symbol`]). At end of input it fails
/// silently, as 9.6 does. Like 9.6 it blocks while waiting for a line.
pub(super) fn accept(ctx: &mut RhsContext) -> Result<Option<Sym>, String> {
    let stdin = std::io::stdin();
    loop {
        let mut line = String::new();
        match stdin.read_line(&mut line) {
            Ok(0) | Err(_) => return Err(String::new()),
            Ok(_) => {}
        }
        match accept_symbol(&line) {
            Some(Accepted::Int(i)) => return Ok(Some(ctx.symbols.int(i))),
            Some(Accepted::Float(f)) => return Ok(Some(ctx.symbols.float(f))),
            Some(Accepted::Str(s)) => return Ok(Some(ctx.symbols.str(&s))),
            Some(Accepted::BadInt) => {
                ctx.output
                    .push_str("Text Input Error: bad integer (probably too large)\n");
            }
            None => {}
        }
    }
}

#[derive(Debug, PartialEq)]
pub(super) enum Accepted {
    Int(i64),
    Float(f64),
    Str(String),
    /// 9.6 prints `Text Input Error: bad integer (probably too large)` and reads on.
    BadInt,
}

/// The first symbol of a line of text input (9.6 `get_next_io_symbol_from_text_input_line`):
/// white space other than newline is skipped; a run of constituents (letters, digits,
/// `+-._`) is an integer, a float or a string; any other character is a one-character
/// string (`|`, `<`, `(`). `None` when the line holds nothing.
pub(super) fn accept_symbol(line: &str) -> Option<Accepted> {
    let b = line.as_bytes();
    let mut i = 0;
    while i < b.len() && b[i] != b'\n' && c_space(b[i]) {
        i += 1;
    }
    if i >= b.len() || b[i] == b'\n' || b[i] == 0 {
        return None;
    }
    let constituent = |c: u8| c.is_ascii_alphanumeric() || b"+-._".contains(&c);
    if !constituent(b[i]) {
        // A single (possibly multi-byte) character.
        let ch = line[i..].chars().next()?;
        return Some(Accepted::Str(ch.to_string()));
    }
    let start = i;
    while i < b.len() && constituent(b[i]) {
        i += 1;
    }
    let word = &line[start..i];
    if crate::lexer::is_int_lexeme(word) {
        return Some(match c_strtol(word) {
            Ok(v) => Accepted::Int(v),
            Err(Erange) => Accepted::BadInt,
        });
    }
    if is_float_lexeme(word) {
        return Some(Accepted::Float(c_strtod(word).0));
    }
    Some(Accepted::Str(word.to_string()))
}

/// Soar's float lexeme: `[+-]? digits* . digits* ([eE][+-]?digits)?` with a digit.
fn is_float_lexeme(s: &str) -> bool {
    let d = s.strip_prefix(['+', '-']).unwrap_or(s);
    let Some((int, frac)) = d.split_once('.') else {
        return false;
    };
    if !int.bytes().all(|c| c.is_ascii_digit()) {
        return false;
    }
    let (frac, exp) = match frac.find(['e', 'E']) {
        Some(k) => (&frac[..k], Some(&frac[k + 1..])),
        None => (frac, None),
    };
    if !frac.bytes().all(|c| c.is_ascii_digit()) || (int.is_empty() && frac.is_empty()) {
        return false;
    }
    match exp {
        None => true,
        Some(e) => {
            let e = e.strip_prefix(['+', '-']).unwrap_or(e);
            !e.is_empty() && e.bytes().all(|c| c.is_ascii_digit())
        }
    }
}
