//! Step 3 of the pipeline: the Hough transform with voting.
//!
//! Thesis, "Hough-Transform Java / Hough transforming", equation (1): every pixel (x, y) becomes
//! the sinusoid `r = x·cos θ + y·sin θ`, θ from 0 to 359; the Hough space "also acts like a vote
//! space": each pixel adds one vote to the cell its curve passes through at every θ (Figure 20).
//!
//! The accumulator covers θ = 0, s, 2s, … < 360° (s = `theta_step_deg`, 1° by default) and r in
//! bins of `r_bin_mm` from two bins below zero up to the farthest point. With θ over the full
//! circle every line has a representation with r ≥ 0, so negative r is not needed except near
//! r = 0, where a line through the origin must not lose its peak to the bin edge.
//! The accumulator is kept whole in [`Accumulator`] so that it can be plotted (Figure 20).
//!
//! Two ways of voting ([`VoteMode`]):
//! - `points` (the thesis): each return's position votes along its whole sinusoid;
//! - `arcs` (Tardós et al. 2002, the thesis's reference \[3\], whose figures the noise-filter
//!   section reuses): each return votes only for the lines tangent to its visible arc, i.e. at
//!   each θ inside its beam cone for the arc point whose tangent has normal θ:
//!   `r = x_s cos θ + y_s sin θ + range` — equation (1) applied to the points of the visible
//!   line. Returns of a wall seen head-on then agree exactly on the wall's (r, θ), while returns
//!   of beams meeting it obliquely (placed short of the wall on the beam axis) do not vote for it.

use super::convert::SonarPoint;
use super::pool::{self, Bands, Pool};
use super::settings::VoteMode;
use super::Settings;

thread_local! {
    static FREE: Pool = const { Pool::new(Vec::new()) };
}

/// Largest accumulator, in cells; beyond it the r bin is widened (only for absurd inputs).
const MAX_CELLS: usize = 1 << 21;

/// The voted Hough space.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Accumulator {
    theta_step_deg: u32,
    n_theta: usize,
    r_bin_mm: f64,
    r_min_mm: f64,
    n_r: usize,
    votes: Vec<u32>,
    /// The r bins of each θ column that hold votes.
    bands: Bands,
}

impl Drop for Accumulator {
    fn drop(&mut self) {
        let mut votes = std::mem::take(&mut self.votes);
        self.bands.zero(&mut votes, self.n_r);
        pool::give(&FREE, votes);
    }
}

impl Accumulator {
    /// An empty accumulator for r up to `r_max` mm (see [`Accumulator::vote`] for the steps).
    fn empty(r_max: f64, theta_step_deg: u32, r_bin_mm: f64) -> Self {
        let step = (1..=theta_step_deg.clamp(1, 90))
            .rev()
            .find(|s| 360 % s == 0)
            .unwrap_or(1);
        let n_theta = 360usize.div_ceil(step as usize);
        let mut bin = if r_bin_mm.is_finite() && r_bin_mm > 0.0 {
            r_bin_mm
        } else {
            50.0
        };
        let r_max = if r_max.is_finite() {
            r_max.max(0.0)
        } else {
            0.0
        };
        // Rows in floating point so that a huge r_max cannot overflow.
        let rows = |bin: f64| (r_max / bin).floor() + 3.0;
        while rows(bin) * n_theta as f64 > MAX_CELLS as f64 {
            bin *= 2.0;
        }
        let n_r = rows(bin) as usize;
        Accumulator {
            theta_step_deg: step,
            n_theta,
            r_bin_mm: bin,
            r_min_mm: -2.0 * bin,
            n_r,
            votes: pool::take(&FREE, n_theta * n_r),
            bands: Bands::new(n_theta),
        }
    }

    /// (cos θ, sin θ) of every column.
    fn trig(&self) -> Vec<(f64, f64)> {
        (0..self.n_theta)
            .map(|t| {
                let (s, c) = self.theta_deg(t).to_radians().sin_cos();
                (c, s)
            })
            .collect()
    }

    /// Adds one vote at column `t` for r (folding a negative r beyond the accumulator to the
    /// opposite column).
    fn add(&mut self, t: usize, r: f64) {
        let (t, r) = if r < self.r_min_mm {
            ((t + self.n_theta / 2) % self.n_theta, -r)
        } else {
            (t, r)
        };
        let f = (r - self.r_min_mm) * (1.0 / self.r_bin_mm);
        if f >= 0.0 && f < self.n_r as f64 {
            self.bump(t, f as usize);
        }
    }

    /// One more vote in cell (t, ri).
    #[inline]
    fn bump(&mut self, t: usize, ri: usize) {
        self.votes[t * self.n_r + ri] += 1;
        self.bands.note(t, ri);
    }

    /// Votes `points` (x, y in mm) into a new accumulator with θ steps of `theta_step_deg`
    /// degrees (clamped to 1..=90, then lowered to a divisor of 360 so that the θ axis wraps
    /// evenly) and r bins of `r_bin_mm` (≤ 0 or non-finite means 50 mm).
    pub fn vote(points: &[(f64, f64)], theta_step_deg: u32, r_bin_mm: f64) -> Self {
        let points: Vec<(f64, f64)> = points
            .iter()
            .copied()
            .filter(|(x, y)| x.is_finite() && y.is_finite())
            .collect();
        let r_max = points.iter().map(|(x, y)| x.hypot(*y)).fold(0.0, f64::max);
        let mut acc = Accumulator::empty(r_max, theta_step_deg, r_bin_mm);
        let trig = acc.trig();
        let (n_r, r_min, inv) = (acc.n_r, acc.r_min_mm, 1.0 / acc.r_bin_mm);
        for (t, &(c, s)) in trig.iter().enumerate() {
            for &(x, y) in &points {
                let f = (x * c + y * s - r_min) * inv;
                if f >= 0.0 && f < n_r as f64 {
                    acc.bump(t, f as usize);
                }
            }
        }
        acc
    }

    /// Votes the visible arcs of `returns` (beam cone `beam_deg`): each return votes once at
    /// every θ column inside its cone, for `r = x_s cos θ + y_s sin θ + range`.
    pub fn vote_arcs(
        returns: &[SonarPoint],
        theta_step_deg: u32,
        r_bin_mm: f64,
        beam_deg: f64,
    ) -> Self {
        let returns: Vec<&SonarPoint> = returns
            .iter()
            .filter(|p| {
                p.sensor_x.is_finite()
                    && p.sensor_y.is_finite()
                    && p.range.is_finite()
                    && p.heading.is_finite()
            })
            .collect();
        let r_max = returns
            .iter()
            .map(|p| p.sensor_x.hypot(p.sensor_y) + p.range)
            .fold(0.0, f64::max);
        let mut acc = Accumulator::empty(r_max, theta_step_deg, r_bin_mm);
        let trig = acc.trig();
        let half = beam_deg.clamp(0.0, 360.0) / 2.0;
        let step = acc.theta_step_deg as f64;
        for p in returns {
            let axis = p.heading.to_degrees().rem_euclid(360.0);
            let first = ((axis - half) / step).ceil() as i64;
            let last = ((axis + half) / step).floor() as i64;
            for i in first..=last.min(first + acc.n_theta as i64 - 1) {
                let t = i.rem_euclid(acc.n_theta as i64) as usize;
                let (c, s) = trig[t];
                acc.add(t, p.sensor_x * c + p.sensor_y * s + p.range);
            }
        }
        acc
    }

    /// The r bin holding `r_mm`, if inside the accumulator.
    pub fn bin_of(&self, r_mm: f64) -> Option<usize> {
        let f = (r_mm - self.r_min_mm) / self.r_bin_mm;
        (f >= 0.0 && f < self.n_r as f64).then_some(f as usize)
    }

    /// θ of column `t`, degrees.
    pub fn theta_deg(&self, t: usize) -> f64 {
        (t as u32 * self.theta_step_deg) as f64
    }

    /// Centre of r bin `ri`, mm.
    pub fn r_mm(&self, ri: usize) -> f64 {
        self.r_min_mm + (ri as f64 + 0.5) * self.r_bin_mm
    }

    /// Votes in cell (θ column `t`, r bin `ri`); 0 outside.
    pub fn get(&self, t: usize, ri: usize) -> u32 {
        if t < self.n_theta && ri < self.n_r {
            self.votes[t * self.n_r + ri]
        } else {
            0
        }
    }

    /// The r bins of column `t` that may hold votes (all others hold none).
    pub fn voted_bins(&self, t: usize) -> std::ops::Range<usize> {
        self.bands.get(t)
    }

    /// Number of θ columns.
    pub fn n_theta(&self) -> usize {
        self.n_theta
    }

    /// Number of r bins.
    pub fn n_r(&self) -> usize {
        self.n_r
    }

    /// θ step, degrees.
    pub fn theta_step_deg(&self) -> u32 {
        self.theta_step_deg
    }

    /// r bin size, mm.
    pub fn r_bin_mm(&self) -> f64 {
        self.r_bin_mm
    }

    /// Lower edge of the first r bin, mm.
    pub fn r_min_mm(&self) -> f64 {
        self.r_min_mm
    }

    /// All votes, θ-major (`votes[t * n_r + ri]`), for plotting.
    pub fn votes(&self) -> &[u32] {
        &self.votes
    }

    /// The largest vote count (0 when empty).
    pub fn max_votes(&self) -> u32 {
        self.votes.iter().copied().max().unwrap_or(0)
    }
}

/// The Hough transform of the filtered returns, with the settings' vote mode, θ step, r bin
/// and (for arcs) beam width.
pub fn hough(points: &[SonarPoint], settings: &Settings) -> Accumulator {
    match settings.vote_mode {
        VoteMode::Points => {
            let xy: Vec<(f64, f64)> = points.iter().map(|p| (p.x, p.y)).collect();
            Accumulator::vote(&xy, settings.theta_step_deg, settings.r_bin_mm)
        }
        VoteMode::Arcs => Accumulator::vote_arcs(
            points,
            settings.theta_step_deg,
            settings.r_bin_mm,
            settings.beam_deg,
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn single_point_draws_a_sinusoid() {
        let acc = Accumulator::vote(&[(1000.0, 0.0)], 1, 50.0);
        assert_eq!(acc.n_theta(), 360);
        // r = 1000·cos θ: at θ = 0 in the bin of 1000, at 60° in the bin of 500; negative r
        // (θ in 90..270 except near the ends) falls outside.
        assert_eq!(acc.get(0, acc.bin_of(1000.0).expect("bin")), 1);
        assert_eq!(acc.get(60, acc.bin_of(500.0).expect("bin")), 1);
        assert_eq!(
            acc.votes().iter().sum::<u32>(),
            (0..360)
                .filter(|t| (*t as f64).to_radians().cos() * 1000.0 >= -100.0)
                .count() as u32
        );
    }

    #[test]
    fn collinear_points_peak_at_their_line() {
        // Points on the line x cos 30° + y sin 30° = 1500.
        let th = 30f64.to_radians();
        let pts: Vec<(f64, f64)> = (-10..=10)
            .map(|i| {
                let t = i as f64 * 100.0;
                (
                    1500.0 * th.cos() - t * th.sin(),
                    1500.0 * th.sin() + t * th.cos(),
                )
            })
            .collect();
        let acc = Accumulator::vote(&pts, 1, 50.0);
        assert_eq!(acc.max_votes(), 21);
        let ri = acc.bin_of(1500.0).expect("bin");
        assert_eq!(acc.get(30, ri), 21);
        assert!((acc.r_mm(ri) - 1500.0).abs() <= 25.0);
        // Two degrees off, the votes spread over several bins.
        assert!((0..acc.n_r()).all(|r| acc.get(32, r) < 21));
    }

    #[test]
    fn coarse_theta_step() {
        let acc = Accumulator::vote(&[(0.0, 800.0)], 5, 50.0);
        assert_eq!(acc.n_theta(), 72);
        assert_eq!(Accumulator::vote(&[], 7, 50.0).theta_step_deg(), 6);
        assert_eq!(acc.theta_deg(18), 90.0);
        assert_eq!(acc.get(18, acc.bin_of(800.0).expect("bin")), 1);
    }

    #[test]
    fn arcs_of_a_wall_agree_on_its_line() {
        // Transducers along y = 0 looking at 90° ± 30° see the wall y = 1500; only the head-on
        // ones (cone 25°) report 1500 and vote for it; the 30°-off ones report the cone-edge
        // distance 1500 / cos 17.5° and their arcs never reach θ = 90°.
        let mut returns = Vec::new();
        for i in 0..20 {
            let x = i as f64 * 100.0;
            for (heading, range) in [(90.0, 1500.0), (120.0, 1500.0 / 17.5f64.to_radians().cos())] {
                let h = f64::to_radians(heading);
                returns.push(SonarPoint {
                    x: x + range * h.cos(),
                    y: range * h.sin(),
                    sensor_x: x,
                    sensor_y: 0.0,
                    heading: h,
                    range,
                });
            }
        }
        let acc = Accumulator::vote_arcs(&returns, 1, 50.0, 25.0);
        let ri = acc.bin_of(1500.0).expect("bin");
        assert_eq!(acc.get(90, ri), 20);
        assert_eq!(acc.max_votes(), 20);
        // Each return votes once per degree of its cone.
        assert_eq!(acc.votes().iter().sum::<u32>(), 40 * 25);
    }

    #[test]
    fn arcs_fold_negative_r() {
        // A transducer at (−3000, 0) looking −x at a wall 1000 mm away: the wall x = −4000 has
        // normal 180° and r = 4000.
        let p = SonarPoint {
            x: -4000.0,
            y: 0.0,
            sensor_x: -3000.0,
            sensor_y: 0.0,
            heading: std::f64::consts::PI,
            range: 1000.0,
        };
        let acc = Accumulator::vote_arcs(&[p], 1, 50.0, 10.0);
        assert_eq!(acc.get(180, acc.bin_of(4000.0).expect("bin")), 1);
    }

    #[test]
    fn degenerate_inputs() {
        let acc = Accumulator::vote(&[], 0, f64::NAN);
        assert_eq!(acc.max_votes(), 0);
        assert_eq!(acc.theta_step_deg(), 1);
        assert_eq!(acc.r_bin_mm(), 50.0);
        let acc = Accumulator::vote(&[(f64::NAN, 1.0), (1e15, 0.0)], 1, 1.0);
        assert!(acc.votes().len() <= MAX_CELLS);
        let acc = Accumulator::vote(&[(1e300, 1e300)], 1, 1.0);
        assert!(acc.votes().len() <= MAX_CELLS);
        let far = SonarPoint {
            x: 1e300,
            y: 0.0,
            sensor_x: 1e300,
            sensor_y: 0.0,
            heading: 1e300,
            range: 1000.0,
        };
        let acc = Accumulator::vote_arcs(&[far], 1, 50.0, 25.0);
        assert!(acc.votes().len() <= MAX_CELLS);
    }
}
