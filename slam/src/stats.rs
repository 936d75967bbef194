//! The statistics over seeds: quantiles, the median with its 10–90 % band, the Wilcoxon
//! signed-rank test of paired differences, and how the tables print them.

/// The `q`-quantile (0..1) of `v` with linear interpolation; NaN for no values.
pub fn quantile(v: &[f64], q: f64) -> f64 {
    let mut s: Vec<f64> = v.iter().copied().filter(|x| x.is_finite()).collect();
    if s.is_empty() {
        return f64::NAN;
    }
    s.sort_by(f64::total_cmp);
    let pos = q.clamp(0.0, 1.0) * (s.len() - 1) as f64;
    let (lo, hi) = (pos.floor() as usize, pos.ceil() as usize);
    s[lo] + (s[hi] - s[lo]) * (pos - lo as f64)
}

/// Median and 10–90 % band.
pub(crate) fn band(v: &[f64]) -> (f64, f64, f64) {
    (quantile(v, 0.5), quantile(v, 0.1), quantile(v, 0.9))
}

/// Two-sided Wilcoxon signed-rank test of paired differences (zeros dropped, tied ranks
/// averaged), with the exact null distribution of the rank sum given those ranks. Returns
/// (n used, W+, p), or `None` without non-zero differences.
pub fn wilcoxon(diffs: &[f64]) -> Option<(usize, f64, f64)> {
    let d: Vec<f64> = diffs
        .iter()
        .copied()
        .filter(|x| x.is_finite() && *x != 0.0)
        .collect();
    let n = d.len();
    if n == 0 {
        return None;
    }
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| d[a].abs().total_cmp(&d[b].abs()));
    // Doubled ranks, so that averaged ties stay integers.
    let mut rank2 = vec![0usize; n];
    let mut i = 0;
    while i < n {
        let mut j = i;
        while j + 1 < n && d[order[j + 1]].abs() == d[order[i]].abs() {
            j += 1;
        }
        let r2 = i + j + 2; // (i+1 + j+1), i.e. twice the average rank
        for &k in &order[i..=j] {
            rank2[k] = r2;
        }
        i = j + 1;
    }
    let w2: usize = (0..n).filter(|&k| d[k] > 0.0).map(|k| rank2[k]).sum();
    let max: usize = rank2.iter().sum();
    let mut dist = vec![0.0f64; max + 1];
    dist[0] = 1.0;
    let mut reach = 0;
    for &r in &rank2 {
        for s in (0..=reach).rev() {
            let p = dist[s] * 0.5;
            dist[s] = p;
            dist[s + r] += p;
        }
        reach += r;
    }
    let low: f64 = dist[..=w2].iter().sum();
    let high: f64 = dist[w2..].iter().sum();
    Some((n, w2 as f64 / 2.0, (2.0 * low.min(high)).min(1.0)))
}

/// A p-value as a report prints it: three decimals, or `< 0.001` (never `0.000`).
pub fn fmt_p(p: f64) -> String {
    if p < 0.001 {
        "< 0.001".into()
    } else {
        format!("{p:.3}")
    }
}

/// `p = 0.040` or `p < 0.001`.
pub fn p_is(p: f64) -> String {
    let t = fmt_p(p);
    if t.starts_with('<') {
        format!("p {t}")
    } else {
        format!("p = {t}")
    }
}

pub(crate) fn fmt_mm(v: f64) -> String {
    if v.is_finite() {
        format!("{v:.0}")
    } else {
        "–".into()
    }
}

pub(crate) fn fmt_band(v: &[f64]) -> String {
    if v.is_empty() {
        return "–".into();
    }
    let (m, lo, hi) = band(v);
    format!("{} [{}–{}]", fmt_mm(m), fmt_mm(lo), fmt_mm(hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_p_values_print_as_a_bound() {
        assert_eq!(fmt_p(0.0004), "< 0.001");
        assert_eq!(fmt_p(0.001), "0.001");
        assert_eq!(p_is(0.0), "p < 0.001");
        assert_eq!(p_is(0.0404), "p = 0.040");
    }

    #[test]
    fn quantiles_interpolate() {
        let v = [5.0, 1.0, 3.0, 2.0, 4.0];
        assert_eq!(quantile(&v, 0.5), 3.0);
        assert_eq!(quantile(&v, 0.0), 1.0);
        assert_eq!(quantile(&v, 1.0), 5.0);
        assert!((quantile(&v, 0.1) - 1.4).abs() < 1e-12);
        assert!(quantile(&[], 0.5).is_nan());
        assert_eq!(quantile(&[f64::NAN, 2.0], 0.5), 2.0);
    }

    #[test]
    fn wilcoxon_matches_the_exact_tables() {
        // All 6 differences negative: W+ = 0, p = 2 / 2^6.
        let (n, w, p) = wilcoxon(&[-1.0, -2.0, -3.0, -4.0, -5.0, -6.0]).unwrap();
        assert_eq!((n, w), (6, 0.0));
        assert!((p - 2.0 / 64.0).abs() < 1e-12);
        // Symmetric data: p = 1.
        let (_, _, p) = wilcoxon(&[-1.0, 1.0, -2.0, 2.0]).unwrap();
        assert!((p - 1.0).abs() < 1e-12);
        // n = 10, W+ = 8 (ranks 1, 3, 4 positive): scipy.stats.wilcoxon gives p = 0.048828125.
        let d = [1.0, -2.0, 3.0, 4.0, -5.0, -6.0, -7.0, -8.0, -9.0, -10.0];
        let (_, w, p) = wilcoxon(&d).unwrap();
        assert_eq!(w, 8.0);
        assert!((p - 0.048828125).abs() < 1e-9, "{p}");
        // Zeros dropped; ties averaged.
        let (n, w, _) = wilcoxon(&[0.0, 1.0, -1.0, 2.0]).unwrap();
        assert_eq!((n, w), (3, 4.5));
        assert!(wilcoxon(&[0.0, 0.0]).is_none());
    }
}
