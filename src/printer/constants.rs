//! Constants as Soar prints them: a string in `|...|` when the lexer would not read it back as
//! itself, a float with six decimals; and numbers as C's `%f` and `%g` print them. The
//! lowest part of printing: symbols, the production types' text, the trace and `print` all
//! use it.

use crate::ast::Constant;
use crate::lexer::{is_identifier_shaped, is_int_lexeme, is_variable};

fn is_constituent(c: char) -> bool {
    c.is_ascii_alphanumeric() || "$%&*+-/:<=>?_@".contains(c)
}

/// Would the lexer read `s` back as something other than this string constant? This is the
/// kernel's `determine_possible_symbol_types_for_string`: a string is rereadable when it is
/// all alphanumeric, longer than the longest special lexeme (3, `<=>`), or `*`; and it must
/// not read as a number, a variable or an identifier. Observed on the official kernel:
/// `a1`, `a*b`, `a-b`, `z9-`, `-a`, `*a`, `1.5`, `+`, `a b`, `x/y` need bars; `a1b`, `ab-c`,
/// `1e5`, `1a`, `*`, `x/y:z`, `a-b-c`, `-abc`, `1-23` do not.
fn needs_bars(s: &str) -> bool {
    if s.is_empty() || !s.chars().all(is_constituent) {
        return true;
    }
    if is_int_lexeme(s) || is_variable(s) || looks_like_float(s) || is_identifier_shaped(s) {
        return true;
    }
    let rereadable = s.bytes().all(|b| b.is_ascii_alphanumeric()) || s.len() > 3 || s == "*";
    !rereadable
}

fn looks_like_float(s: &str) -> bool {
    s.contains('.') && s.parse::<f64>().is_ok()
}

/// A string constant as Soar prints it: with `|...|` when it would not read back as itself.
pub fn rereadable(s: &str) -> String {
    if needs_bars(s) {
        let mut out = String::with_capacity(s.len() + 2);
        out.push('|');
        for c in s.chars() {
            if c == '|' || c == '\\' {
                out.push('\\');
            }
            out.push(c);
        }
        out.push('|');
        out
    } else {
        s.to_string()
    }
}

/// C's `std::fixed` with `prec` decimals, including glibc's `nan`, `-nan`, `inf`, `-inf`.
pub fn c_fixed(f: f64, prec: usize) -> String {
    if f.is_nan() {
        return if f.is_sign_negative() { "-nan" } else { "nan" }.to_string();
    }
    if f.is_infinite() {
        return if f < 0.0 { "-inf" } else { "inf" }.to_string();
    }
    format!("{f:.prec$}")
}

/// C's `%.{prec}g`: `prec` significant digits, trailing zeros dropped, an exponent when
/// it is below -4 or at least `prec` (as a C++ stream prints a double with that precision).
pub fn c_general(f: f64, prec: usize) -> String {
    if !f.is_finite() {
        return c_fixed(f, 0);
    }
    if f == 0.0 {
        return if f.is_sign_negative() { "-0" } else { "0" }.to_string();
    }
    let prec = prec.max(1);
    let sci = format!("{f:.*e}", prec - 1);
    let (mantissa, exp) = sci.split_once('e').unwrap_or((&sci, "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    let trim = |s: &str| -> String {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s.to_string()
        }
    };
    if exp < -4 || exp >= prec as i32 {
        let sign = if exp < 0 { '-' } else { '+' };
        format!("{}e{sign}{:02}", trim(mantissa), exp.abs())
    } else {
        let decimals = (prec as i32 - 1 - exp).max(0) as usize;
        trim(&format!("{f:.decimals$}"))
    }
}

/// Floats print with 6 decimals as `std::fixed` does.
pub fn float_text(f: f64) -> String {
    format!("{f:.6}")
}

pub fn constant_text(c: &Constant) -> String {
    match c {
        Constant::Str(s) => rereadable(s),
        Constant::Int(i) => i.to_string(),
        Constant::Float(f) => float_text(*f),
    }
}

/// [`constant_text`] appended to `out`, without a string of its own for the common case.
pub fn push_constant_text(c: &Constant, out: &mut String) {
    use std::fmt::Write;
    match c {
        Constant::Str(s) if !needs_bars(s) => out.push_str(s),
        Constant::Int(i) => {
            let _ = write!(out, "{i}");
        }
        _ => out.push_str(&constant_text(c)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bars_as_the_official_kernel_prints_them() {
        for s in [
            "a*b", "a-b", "z9-", "a1-", "-a", "*a", "1.5", "+", "a b", "", "P1", "123", "<x>",
            "a.b", "x/y", "a_b", "<<>>",
        ] {
            assert!(rereadable(s).starts_with('|'), "{s} should have bars");
        }
        for s in [
            "a1b",
            "ab-c",
            "x/y:z",
            "a-b-c",
            "-abc",
            "1-23",
            "1e5",
            "1a",
            "*",
            "a",
            "gp*test*1",
            "propose*init",
            "wall01",
            "w1b",
        ] {
            assert_eq!(rereadable(s), s, "{s} should print bare");
        }
    }

    #[test]
    fn floats_have_six_decimals() {
        assert_eq!(float_text(2.5), "2.500000");
        assert_eq!(float_text(150.0), "150.000000");
    }
}
