//! Fixed-decimal printing of floats and integers for the per-step records and the `exec`
//! results, byte for byte what `format!("{v:.N}")` and `format!("{n}")` print, without the
//! formatting machinery (a run prints about a million such numbers).

use std::fmt::Write;

/// Largest number of decimals [`push_fixed`] handles itself.
const MAX_DECIMALS: usize = 3;
const POW10: [u64; MAX_DECIMALS + 1] = [1, 10, 100, 1000];

/// Appends `v` with `decimals` decimals, as `write!(out, "{v:.decimals$}")` does.
///
/// `{:.N}` prints the exact binary value rounded to N decimals (ties to even). Here
/// `scaled = v·10^N` is computed in one rounding, off the exact product by at most
/// 2^40·2^-53 = 2^-13 when |scaled| < 2^40; so unless `scaled` lies within 10^-3 of a
/// rounding tie, the exact product rounds to the same integer as `scaled`, which is then
/// printed with integer arithmetic. Other values (near ties, huge, NaN, infinite) and
/// more than [`MAX_DECIMALS`] decimals go to `format!`.
pub fn push_fixed(out: &mut String, v: f64, decimals: usize) {
    if decimals <= MAX_DECIMALS {
        let p = POW10[decimals];
        let scaled = v * p as f64;
        if scaled.abs() < (1u64 << 40) as f64 {
            let k = scaled.round();
            if ((scaled - k).abs() - 0.5).abs() >= 1e-3 {
                // `{:.N}` keeps the sign of negative values, -0.0 and those rounding to 0.
                if v.is_sign_negative() {
                    out.push('-');
                }
                let n = k.abs() as u64;
                push_u64(out, n / p);
                if decimals > 0 {
                    out.push('.');
                    let frac = n % p;
                    for d in (0..decimals).rev() {
                        out.push(char::from(b'0' + (frac / POW10[d] % 10) as u8));
                    }
                }
                return;
            }
        }
    }
    let _ = write!(out, "{v:.decimals$}");
}

/// `v` with `decimals` decimals (see [`push_fixed`]).
pub fn fixed(v: f64, decimals: usize) -> String {
    let mut s = String::with_capacity(24);
    push_fixed(&mut s, v, decimals);
    s
}

/// Appends `n` in decimal, as `write!(out, "{n}")` does.
pub fn push_u64(out: &mut String, mut n: u64) {
    let mut buf = [0u8; 20];
    let mut i = buf.len();
    loop {
        i -= 1;
        buf[i] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    // Only ASCII digits were written.
    out.extend(buf[i..].iter().map(|&b| char::from(b)));
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(v: f64, decimals: usize) -> bool {
        let want = format!("{v:.decimals$}");
        let got = fixed(v, decimals);
        assert_eq!(got, want, "{v:e} with {decimals} decimals");
        // Whether the fast path could answer (format! answers the rest).
        let scaled = v * POW10[decimals] as f64;
        scaled.abs() < (1u64 << 40) as f64 && ((scaled - scaled.round()).abs() - 0.5).abs() >= 1e-3
    }

    #[test]
    fn matches_format_on_random_values() {
        let mut state = 0x2545f4914f6cdd1du64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        // Fast-path count and total among moderate uniform values, where nearly all are fast.
        let (mut fast, mut total) = (0, 0);
        for _ in 0..400_000 {
            let bits = next();
            let decimals = (bits % 4) as usize;
            let class = (bits >> 2) % 6;
            let moderate = class <= 2 && (bits >> 5) % 8 <= 4;
            let v = match class {
                // Uniform in a few magnitudes, both signs.
                0..=2 => {
                    let mag = [1.0, 1e3, 1e4, 1e6, 1e-3, 1e9, 1e12, 1e15][(bits >> 5) as usize % 8];
                    ((next() >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * mag
                }
                // Exact and near ties: (m + 1/2) / 10^N, nudged by a few ulps.
                3 | 4 => {
                    let m = (next() % 20_000_000) as f64 - 10_000_000.0;
                    let tie = (m + 0.5) / POW10[decimals] as f64;
                    let ulps = (next() % 7) as i64 - 3;
                    f64::from_bits((tie.to_bits() as i64 + ulps) as u64)
                }
                // Any bit pattern (NaN, infinities, subnormals, huge).
                _ => f64::from_bits(next()),
            };
            let was_fast = check(v, decimals);
            if moderate {
                total += 1;
                fast += usize::from(was_fast);
            }
        }
        // Only values within 10^-3 of a tie go the slow way (about 0.2 % of them).
        assert!(fast * 100 > total * 99, "fast path for {fast} of {total}");
    }

    #[test]
    fn matches_format_on_edge_values() {
        let edges = [
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.5,
            2.5,
            0.05,
            0.15,
            0.25,
            0.0625,
            0.0005,
            -0.0004,
            -0.00049,
            1e-300,
            -1e-300,
            f64::MIN_POSITIVE,
            5e-324,
            -5e-324,
            999.9995,
            999.9994,
            9.95,
            99.95,
            1234.5,
            (1u64 << 40) as f64 / 1000.0,
            (1u64 << 40) as f64,
            1e300,
            -1e300,
            f64::MAX,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ];
        for v in edges {
            for decimals in 0..=5 {
                let _ = check_any(v, decimals);
            }
        }
        assert!(check(2000.0, 3) && check(-895.26, 1) && check(-0.0, 2));
    }

    fn check_any(v: f64, decimals: usize) -> String {
        let got = fixed(v, decimals);
        assert_eq!(got, format!("{v:.decimals$}"), "{v:e} with {decimals}");
        got
    }

    #[test]
    fn integers_match_display() {
        for n in [0, 1, 9, 10, 99, 100, 12345, u32::MAX as u64, u64::MAX] {
            let mut s = String::new();
            push_u64(&mut s, n);
            assert_eq!(s, n.to_string());
        }
    }
}
