//! Odometry drift: the pose the robot believes, integrated from noisy odometry.
//!
//! The model is Stage 2.0.x's differential-drive error model (Konolige's,
//! `model_position.c`): three biases drawn once per run, uniform in ±MAX/2 with MAX = 0.03
//! (distance), 0.03 (distance into heading) and 0.05 (rotation), so ±1.5 %, ±1.5 % and
//! ±2.5 %; and Gaussian noise with standard deviations of 0.03 m per √m travelled and
//! 0.05 rad per √revolution. For a step that truly moved `odx` metres and turned `oda`
//! radians:
//!
//! ```text
//! da = oda + |oda|·bias_a + |odx|·bias_y + sqrt(|oda|/2π · std_a² + |odx| · std_y²) · N(0,1)
//! dx = odx + |odx|·bias_x + sqrt(|odx|) · std_x · N(0,1)
//! ```
//!
//! One deliberate difference: the translation is applied along the mid-step heading (Stage uses
//! the new heading), the same integration the simulated body uses, so that with zero noise the
//! believed path equals the true path exactly and all drift comes from the model.
//!
//! [`Odometry::set_odometry`] overwrites the believed pose, as the thesis's `setOdometry`
//! output command does on the robot (Stage 2: `stg_model_position_set_odom`). It draws no random
//! numbers, so it cannot change the drift stream.

use std::f64::consts::TAU;

use super::geom::{normalize_angle, Pose};
use super::pioneer::Motion;
use super::rng::Rng;

/// Parameters of the drift model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DriftParams {
    /// Full width of the distance bias draw (bias uniform in ±this/2).
    pub bias_max_x: f64,
    /// Full width of the distance-to-heading bias draw, rad per m.
    pub bias_max_y: f64,
    /// Full width of the rotation bias draw.
    pub bias_max_a: f64,
    /// Distance noise, m per √m travelled.
    pub std_x: f64,
    /// Heading noise from travel, rad per √m travelled.
    pub std_y: f64,
    /// Heading noise from rotation, rad per √revolution.
    pub std_a: f64,
}

impl DriftParams {
    /// Stage 2.0.x defaults (`MAX_X = MAX_Y = 0.03`, `MAX_A = 0.05`,
    /// `ERROR_X = ERROR_Y = 0.03`, `ERROR_A = 0.05`).
    pub const STAGE2: DriftParams = DriftParams {
        bias_max_x: 0.03,
        bias_max_y: 0.03,
        bias_max_a: 0.05,
        std_x: 0.03,
        std_y: 0.03,
        std_a: 0.05,
    };

    /// Perfect odometry: the believed pose follows the true pose exactly.
    pub const NONE: DriftParams = DriftParams {
        bias_max_x: 0.0,
        bias_max_y: 0.0,
        bias_max_a: 0.0,
        std_x: 0.0,
        std_y: 0.0,
        std_a: 0.0,
    };
}

impl Default for DriftParams {
    fn default() -> Self {
        DriftParams::STAGE2
    }
}

/// The biases of one run.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Biases {
    /// Fractional distance bias.
    pub x: f64,
    /// Heading bias per metre travelled, rad/m.
    pub y: f64,
    /// Fractional rotation bias.
    pub a: f64,
}

impl Biases {
    /// Draws the biases of a run, uniform in ±MAX/2 (three draws from `rng`).
    pub fn draw(params: &DriftParams, rng: &mut Rng) -> Self {
        let mut half = |max: f64| rng.range(-max / 2.0, max / 2.0);
        Biases {
            x: half(params.bias_max_x),
            y: half(params.bias_max_y),
            a: half(params.bias_max_a),
        }
    }
}

/// The robot's odometry: drift model, biases and the believed pose.
#[derive(Debug, Clone, PartialEq)]
pub struct Odometry {
    params: DriftParams,
    biases: Biases,
    believed: Pose,
}

impl Odometry {
    /// Odometry starting at `start` with biases drawn from `rng`.
    pub fn new(params: DriftParams, start: Pose, rng: &mut Rng) -> Self {
        let biases = Biases::draw(&params, rng);
        Odometry::with_biases(params, biases, start)
    }

    /// Odometry with given biases.
    pub fn with_biases(params: DriftParams, biases: Biases, start: Pose) -> Self {
        Odometry {
            params,
            biases,
            believed: start,
        }
    }

    /// The model parameters.
    pub fn params(&self) -> &DriftParams {
        &self.params
    }

    /// This run's biases.
    pub fn biases(&self) -> Biases {
        self.biases
    }

    /// The believed pose.
    pub fn believed(&self) -> Pose {
        self.believed
    }

    /// Overwrites the believed pose (the thesis's `setOdometry`). Non-finite values are ignored.
    pub fn set_odometry(&mut self, pose: Pose) {
        if pose.x.is_finite() && pose.y.is_finite() && pose.th.is_finite() {
            self.believed = Pose::new(pose.x, pose.y, normalize_angle(pose.th));
        }
    }

    /// Integrates one step of true motion into the believed pose, with drift. Always draws
    /// exactly two Gaussians from `rng`.
    pub fn update(&mut self, motion: &Motion, rng: &mut Rng) {
        let p = &self.params;
        let b = &self.biases;
        let (odx, oda) = (motion.distance, motion.rotation);
        let (adx, ada) = (odx.abs(), oda.abs());
        let e_heading = rng.gaussian();
        let e_distance = rng.gaussian();
        let da = oda
            + ada * b.a
            + adx * b.y
            + ((ada / TAU) * p.std_a * p.std_a + adx * p.std_y * p.std_y).sqrt() * e_heading;
        let dx = odx + adx * b.x + adx.sqrt() * p.std_x * e_distance;
        let mid = self.believed.th + da / 2.0;
        self.believed.x += dx * mid.cos();
        self.believed.y += dx * mid.sin();
        self.believed.th = normalize_angle(self.believed.th + da);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn straight(step: f64) -> Motion {
        Motion {
            distance: step,
            rotation: 0.0,
            stalled: false,
        }
    }

    struct Stats {
        mean: f64,
        sd: f64,
    }

    fn stats(xs: &[f64]) -> Stats {
        let n = xs.len() as f64;
        let mean = xs.iter().sum::<f64>() / n;
        let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
        Stats {
            mean,
            sd: var.sqrt(),
        }
    }

    /// Drives `steps` steps of `step` metres straight along +x; returns the final believed pose.
    fn drive(odo: &mut Odometry, steps: usize, step: f64, rng: &mut Rng) -> Pose {
        for _ in 0..steps {
            odo.update(&straight(step), rng);
        }
        odo.believed()
    }

    #[test]
    fn no_drift_follows_truth_exactly() {
        let mut rng = Rng::seed_from_u64(1);
        let mut odo = Odometry::new(DriftParams::NONE, Pose::default(), &mut rng);
        let mut truth = crate::pioneer::Pioneer::new(Pose::default());
        truth.set_vel_mm_s(300.0);
        truth.set_rot_vel_deg_s(17.0);
        for _ in 0..500 {
            let m = truth.step(&[], 0.1);
            odo.update(&m, &mut rng);
        }
        let (t, b) = (truth.pose(), odo.believed());
        assert!(t.distance(&b) < 1e-9 && t.heading_error(&b) < 1e-9);
    }

    #[test]
    fn biases_are_uniform_within_bounds() {
        let p = DriftParams::STAGE2;
        let draws: Vec<Biases> = (0..4000)
            .map(|s| Biases::draw(&p, &mut Rng::stream(s, 1)))
            .collect();
        for (get, max) in [
            (&(|b: &Biases| b.x) as &dyn Fn(&Biases) -> f64, p.bias_max_x),
            (&|b: &Biases| b.y, p.bias_max_y),
            (&|b: &Biases| b.a, p.bias_max_a),
        ] {
            let xs: Vec<f64> = draws.iter().map(get).collect();
            assert!(xs.iter().all(|x| x.abs() <= max / 2.0));
            let s = stats(&xs);
            let sd_uniform = max / 12f64.sqrt();
            assert!(s.mean.abs() < 0.05 * max, "mean {}", s.mean);
            assert!((s.sd - sd_uniform).abs() < 0.05 * sd_uniform, "sd {}", s.sd);
        }
    }

    #[test]
    fn bias_only_is_deterministic_drift() {
        // With the noise off, a straight 10 m drive is off by exactly bias_x·10 along track
        // and turns by bias_y·10; a full turn is off by bias_a·2π.
        let params = DriftParams {
            std_x: 0.0,
            std_y: 0.0,
            std_a: 0.0,
            ..DriftParams::STAGE2
        };
        let biases = Biases {
            x: 0.01,
            y: -0.012,
            a: 0.02,
        };
        let mut rng = Rng::seed_from_u64(5);
        let mut odo = Odometry::with_biases(params, biases, Pose::default());
        let end = drive(&mut odo, 100, 0.1, &mut rng);
        assert!((end.th - (-0.12)).abs() < 1e-12);
        // The path is an arc of length 10·1.01 m turning by 0.12 rad: its chord is
        // L·sin(φ/2)/(φ/2).
        let (arc, phi) = (10.0 * 1.01, 0.12f64);
        let chord = arc * (phi / 2.0).sin() / (phi / 2.0);
        let got = end.position().distance(Default::default());
        assert!((got - chord).abs() < 1e-4, "{got} vs {chord}");
        let mut odo = Odometry::with_biases(params, biases, Pose::default());
        for _ in 0..90 {
            odo.update(
                &Motion {
                    distance: 0.0,
                    rotation: TAU / 90.0,
                    stalled: false,
                },
                &mut rng,
            );
        }
        assert!((normalize_angle(odo.believed().th) - 0.02 * TAU).abs() < 1e-9);
    }

    #[test]
    fn straight_drive_along_track_statistics() {
        // Heading drift off (bias_y = std_y = 0): a 10 m drive in 0.1 m steps, 2000 runs with
        // biases drawn per run, ends on the x axis with along-track error of mean 0 and
        // variance D²·MAXx²/12 + D·std_x² (uniform bias plus √m noise).
        let p = DriftParams {
            bias_max_y: 0.0,
            std_y: 0.0,
            ..DriftParams::STAGE2
        };
        let d = 10.0;
        let along: Vec<f64> = (0..2000u64)
            .map(|seed| {
                let mut rng = Rng::stream(seed, 1);
                let mut odo = Odometry::new(p, Pose::default(), &mut rng);
                let end = drive(&mut odo, 100, d / 100.0, &mut rng);
                assert_eq!(end.y, 0.0);
                end.x - d
            })
            .collect();
        let expect = (d * d * p.bias_max_x.powi(2) / 12.0 + d * p.std_x.powi(2)).sqrt();
        let a = stats(&along);
        assert!(a.mean.abs() < 0.1 * expect, "along mean {}", a.mean);
        assert!(
            (a.sd / expect - 1.0).abs() < 0.08,
            "along sd {} vs {expect}",
            a.sd
        );
    }

    #[test]
    fn straight_drive_heading_and_cross_track_statistics() {
        // Full Stage 2 model, 10 m straight, 2000 runs.
        // Heading error:     mean 0, var = D²·MAXy²/12 + D·std_y².
        // Cross-track error: mean 0, var ≈ (D²/2)²·MAXy²/12 + std_y²·D³/3 (small angles).
        let p = DriftParams::STAGE2;
        let d = 10.0;
        let (mut heading, mut cross, mut total) = (vec![], vec![], vec![]);
        for seed in 0..2000u64 {
            let mut rng = Rng::stream(seed, 1);
            let mut odo = Odometry::new(p, Pose::default(), &mut rng);
            let end = drive(&mut odo, 100, d / 100.0, &mut rng);
            cross.push(end.y);
            heading.push(end.th);
            total.push(end.position().distance(Pose::new(d, 0.0, 0.0).position()));
        }
        let expect_heading = (d * d * p.bias_max_y.powi(2) / 12.0 + d * p.std_y.powi(2)).sqrt();
        let expect_cross = ((d * d / 2.0).powi(2) * p.bias_max_y.powi(2) / 12.0
            + p.std_y.powi(2) * d.powi(3) / 3.0)
            .sqrt();
        let (h, c) = (stats(&heading), stats(&cross));
        assert!(
            h.mean.abs() < 0.1 * expect_heading,
            "heading mean {}",
            h.mean
        );
        assert!(c.mean.abs() < 0.1 * expect_cross, "cross mean {}", c.mean);
        let h_ratio = h.sd / expect_heading;
        assert!(
            (h_ratio - 1.0).abs() < 0.08,
            "heading sd {} vs {expect_heading}",
            h.sd
        );
        // The discrete sum over 100 steps gives slightly less than D³/3; allow 10 %.
        let c_ratio = c.sd / expect_cross;
        assert!(
            (c_ratio - 1.0).abs() < 0.10,
            "cross sd {} vs {expect_cross}",
            c.sd
        );
        // The final position error is dominated by cross-track drift (sd ≈ 0.7 m after 10 m),
        // so its mean is about 0.7·√(2/π) ≈ 0.56 m.
        let mean_total = total.iter().sum::<f64>() / total.len() as f64;
        assert!(
            (0.45..0.7).contains(&mean_total),
            "mean final error {mean_total}"
        );
    }

    #[test]
    fn rotation_noise_per_revolution() {
        // Four full turns in place without biases: heading sd = std_a·√4 = 0.1 rad.
        let params = DriftParams {
            bias_max_x: 0.0,
            bias_max_y: 0.0,
            bias_max_a: 0.0,
            ..DriftParams::STAGE2
        };
        let mut errs = vec![];
        for seed in 0..2000u64 {
            let mut rng = Rng::stream(seed, 1);
            let mut odo = Odometry::new(params, Pose::default(), &mut rng);
            for _ in 0..360 {
                odo.update(
                    &Motion {
                        distance: 0.0,
                        rotation: 4.0 * TAU / 360.0,
                        stalled: false,
                    },
                    &mut rng,
                );
            }
            errs.push(normalize_angle(odo.believed().th));
            assert!(odo.believed().position().distance(Default::default()) < 1e-12);
        }
        let s = stats(&errs);
        assert!(s.mean.abs() < 0.01, "mean {}", s.mean);
        assert!((s.sd - 0.1).abs() < 0.008, "sd {}", s.sd);
    }

    #[test]
    fn set_odometry_overwrites_and_ignores_nan() {
        let mut rng = Rng::seed_from_u64(1);
        let mut odo = Odometry::new(DriftParams::STAGE2, Pose::default(), &mut rng);
        odo.set_odometry(Pose::from_mm_deg(1200.0, -300.0, 270.0));
        let b = odo.believed();
        assert!((b.x - 1.2).abs() < 1e-12 && (b.th + PI / 2.0).abs() < 1e-12);
        odo.set_odometry(Pose::new(f64::NAN, 0.0, 0.0));
        assert_eq!(odo.believed(), b);
    }
}
