//! The paired difference of two conditions over time, with a 95 % confidence band.
//!
//! At each kept step, every seed gives one difference (condition A − condition B on the same
//! seed, so the same true path, odometry biases and sonar readings). The line is the mean of
//! those differences over seeds, and the band is its 95 % percentile bootstrap interval
//! (Efron & Tibshirani, *An Introduction to the Bootstrap*, §13.3): the seeds are resampled
//! with replacement [`RESAMPLES`] times. The mean is drawn, not the median, because its
//! bootstrap interval is smooth at 20 seeds, where the median's jumps between order
//! statistics.
//!
//! The resampling must not make the figures differ from run to run, so the resamples come from
//! a generator with a fixed seed ([`BOOTSTRAP_SEED`]), and they are drawn once and used at every
//! step: the band then moves only where the data move.

use super::super::rng::Rng;
use super::super::stats::quantile;
use super::figures::Band;

/// Bootstrap resamples of the seeds.
pub const RESAMPLES: usize = 2000;

/// The bootstrap generator's seed; any fixed value does, it only has to be the same every run.
pub const BOOTSTRAP_SEED: u64 = 20_070_101;

/// The seeds' indices of every resample: `RESAMPLES` rows of `n` indices below `n`.
fn resamples(n: usize) -> Vec<Vec<usize>> {
    let mut rng = Rng::seed_from_u64(BOOTSTRAP_SEED);
    (0..RESAMPLES)
        .map(|_| (0..n).map(|_| rng.below(n as u64) as usize).collect())
        .collect()
}

/// The mean of `d` and its 95 % percentile bootstrap interval over the resamples `rs`.
fn mean_with_interval(d: &[f64], rs: &[Vec<usize>]) -> (f64, f64, f64) {
    let n = d.len() as f64;
    let mean = d.iter().sum::<f64>() / n;
    let means: Vec<f64> = rs
        .iter()
        .map(|r| r.iter().map(|&i| d[i]).sum::<f64>() / n)
        .collect();
    (mean, quantile(&means, 0.025), quantile(&means, 0.975))
}

/// The paired difference `a − b` over time. `pairs` holds, per seed, the two conditions'
/// values at every step; `dt` is the step in seconds. The steps every seed reached in both
/// conditions are kept, thinned to about `max_points` (the last always kept). A step where a
/// seed's value is not finite is left out. With fewer than two seeds the band is empty.
pub fn difference_over_time(pairs: &[(&[f64], &[f64])], dt: f64, max_points: usize) -> Band {
    let n = pairs
        .iter()
        .map(|(a, b)| a.len().min(b.len()))
        .min()
        .unwrap_or(0);
    let mut band = Band::default();
    if n == 0 {
        return band;
    }
    let rs = resamples(pairs.len());
    let stride = n.div_ceil(max_points.max(1)).max(1);
    let mut ks: Vec<usize> = (stride - 1..n).step_by(stride).collect();
    if ks.last() != Some(&(n - 1)) {
        ks.push(n - 1);
    }
    let mut d = Vec::with_capacity(pairs.len());
    for k in ks {
        d.clear();
        d.extend(pairs.iter().map(|(a, b)| a[k] - b[k]));
        if !d.iter().all(|v| v.is_finite()) {
            continue;
        }
        let (mean, lo, hi) = mean_with_interval(&d, &rs);
        band.t.push((k + 1) as f64 * dt);
        band.median.push(mean);
        if pairs.len() > 1 {
            band.lo.push(lo);
            band.hi.push(hi);
        }
    }
    band
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_constant_difference_has_a_band_of_zero_width() {
        let a: Vec<Vec<f64>> = (0..5).map(|s| vec![s as f64 + 2.0; 30]).collect();
        let b: Vec<Vec<f64>> = (0..5).map(|s| vec![s as f64; 30]).collect();
        let pairs: Vec<(&[f64], &[f64])> = a
            .iter()
            .zip(&b)
            .map(|(x, y)| (x.as_slice(), y.as_slice()))
            .collect();
        let band = difference_over_time(&pairs, 0.1, 10);
        assert_eq!(band.t.len(), 10);
        assert!((band.t[9] - 3.0).abs() < 1e-12);
        assert!(band.median.iter().all(|m| *m == 2.0));
        assert!(band.lo.iter().chain(&band.hi).all(|v| *v == 2.0));
    }

    #[test]
    fn the_band_holds_the_mean_and_repeats_exactly() {
        let a: Vec<Vec<f64>> = (0..20).map(|s| vec![(s * s % 7) as f64; 4]).collect();
        let b: Vec<Vec<f64>> = (0..20).map(|_| vec![1.0; 4]).collect();
        let pairs: Vec<(&[f64], &[f64])> = a
            .iter()
            .zip(&b)
            .map(|(x, y)| (x.as_slice(), y.as_slice()))
            .collect();
        let one = difference_over_time(&pairs, 1.0, 100);
        let two = difference_over_time(&pairs, 1.0, 100);
        assert_eq!(one, two);
        for k in 0..one.t.len() {
            assert!(one.lo[k] < one.median[k] && one.median[k] < one.hi[k]);
        }
    }

    #[test]
    fn no_steps_give_an_empty_band() {
        assert!(difference_over_time(&[], 0.1, 10).t.is_empty());
        let empty: [f64; 0] = [];
        assert!(difference_over_time(&[(&empty, &empty)], 0.1, 10)
            .t
            .is_empty());
    }
}
