//! The EKF over the robot pose, the odometry's biases and the walls: state
//! `[x, y, φ, βx, βy, βa, r₁, θ₁, r₂, θ₂, ...]` (metres, radians), prediction from an odometry
//! increment, and updates from robot-relative line measurements with χ² gating and new-feature
//! initialisation.
//!
//! The biases are Stage 2's run-long drift (`odometry.rs`): a distance βx (fraction of the
//! distance), a heading drift per metre travelled βy (rad/m) and a rotation βa (fraction of the
//! turn). They are states because they are constant over a run: taken as white noise, their
//! effect grows with the square root of the distance in the filter and linearly in truth, and a
//! heading bias of 0.86°/m outruns a filter that believes its heading to within a few degrees;
//! its walls are then rejected by the gate and it never recovers.

use nalgebra::{DMatrix, DVector, Matrix2, Vector2};

use super::super::geom::{normalize_angle, Pose};
use super::chi2;
use super::line::{to_robot_jacobian, to_world_jacobians, Line};

/// The filter's noise model and gates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Noise {
    /// Half-widths of the biases' uniform draws: distance (fraction), heading per metre
    /// travelled (rad/m), rotation (fraction). The bias states start at zero with the draws'
    /// variance, half-width²/3.
    pub bias_x: f64,
    pub bias_y: f64,
    pub bias_a: f64,
    /// Translation noise: variance `std_x²·d` for a step of d metres.
    pub std_x: f64,
    /// Heading noise from rotation: `std_a²·a/2π` for a turn of a radians.
    pub std_a: f64,
    /// Heading noise from travel: `std_y²·d`, rad.
    pub std_y: f64,
    /// Standard deviations of a measured wall: r (m) and θ (rad).
    pub sd_r: f64,
    pub sd_th: f64,
    /// χ² (2 degrees of freedom) probability inside which a measurement updates a feature.
    pub gate_p: f64,
    /// χ² probability beyond which, for every feature, a measurement starts a new feature.
    pub new_p: f64,
}

impl Noise {
    /// The noise model for Stage 2's odometry drift (`odometry::DriftParams::STAGE2`) and the
    /// Hough pipeline's walls: 30 mm and 1°, half the Hough bins, since the pipeline refits
    /// each wall to its returns (the measurement noise was chosen on seeds 101–120:
    /// `docs/slam/ekf-baseline.md`).
    pub const STAGE2_HOUGH: Noise = Noise {
        bias_x: 0.015,
        bias_y: 0.015,
        bias_a: 0.025,
        std_x: 0.03,
        std_a: 0.05,
        std_y: 0.03,
        sd_r: 0.03,
        sd_th: 0.0175,
        gate_p: 0.95,
        new_p: 0.999,
    };
}

/// State entries before the first feature: the pose (x, y, φ) and the biases (βx, βy, βa).
const ROBOT: usize = 6;

/// What became of one measurement.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Association {
    /// It updated feature `i` (0-based).
    Matched(usize),
    /// It started feature `i`.
    New(usize),
    /// Between the two gates: too far for the nearest feature, too near to be a new one.
    Rejected,
}

/// The filter.
#[derive(Debug, Clone)]
pub struct Ekf {
    x: DVector<f64>,
    p: DMatrix<f64>,
    noise: Noise,
    gate: f64,
    new_gate: f64,
}

impl Ekf {
    /// A filter at `start` with the pose standard deviations `sd` (m, m, rad), biases of zero
    /// and no features.
    pub fn new(start: Pose, sd: [f64; 3], noise: Noise) -> Self {
        let x = DVector::from_vec(vec![
            start.x,
            start.y,
            normalize_angle(start.th),
            0.0,
            0.0,
            0.0,
        ]);
        let var = [
            sd[0] * sd[0],
            sd[1] * sd[1],
            sd[2] * sd[2],
            noise.bias_x * noise.bias_x / 3.0,
            noise.bias_y * noise.bias_y / 3.0,
            noise.bias_a * noise.bias_a / 3.0,
        ];
        let p = DMatrix::from_diagonal(&DVector::from_vec(var.to_vec()));
        Ekf {
            x,
            p,
            noise,
            gate: chi2::quantile(2.0, noise.gate_p),
            new_gate: chi2::quantile(2.0, noise.new_p),
        }
    }

    /// The pose estimate.
    pub fn pose(&self) -> Pose {
        Pose::new(self.x[0], self.x[1], self.x[2])
    }

    /// The pose covariance (x, y, φ).
    pub fn pose_covariance(&self) -> nalgebra::Matrix3<f64> {
        self.p.fixed_view::<3, 3>(0, 0).into_owned()
    }

    /// The estimated biases (βx, βy rad/m, βa).
    pub fn biases(&self) -> [f64; 3] {
        [self.x[3], self.x[4], self.x[5]]
    }

    /// The number of wall features.
    pub fn features(&self) -> usize {
        (self.x.len() - ROBOT) / 2
    }

    /// Feature `i` as a world line.
    pub fn feature(&self, i: usize) -> Line {
        Line::new(self.x[ROBOT + 2 * i], self.x[ROBOT + 1 + 2 * i])
    }

    /// Feature `i`'s standard deviations (r m, θ rad).
    pub fn feature_sd(&self, i: usize) -> (f64, f64) {
        let k = ROBOT + 2 * i;
        (self.p[(k, k)].sqrt(), self.p[(k + 1, k + 1)].sqrt())
    }

    /// The normalised estimation error squared of the pose against `truth` (3 degrees of
    /// freedom); infinite if the covariance is singular.
    pub fn nees(&self, truth: &Pose) -> f64 {
        let e = nalgebra::Vector3::new(
            truth.x - self.x[0],
            truth.y - self.x[1],
            normalize_angle(truth.th - self.x[2]),
        );
        match self.pose_covariance().try_inverse() {
            Some(inv) => (e.transpose() * inv * e)[0],
            None => f64::INFINITY,
        }
    }

    /// Moves the pose by an odometry increment: `distance` metres along the mid-step heading and
    /// a turn of `rotation` radians as the odometry measured them, less what the estimated
    /// biases added to them (Stage 2: `dx = odx + |odx|·βx`, `da = oda + |oda|·βa + |odx|·βy`),
    /// integrated as the odometry itself integrates.
    pub fn predict(&mut self, distance: f64, rotation: f64) {
        let n = &self.noise;
        let (dm, am) = (distance.abs(), rotation.abs());
        let var_d = n.std_x * n.std_x * dm;
        let var_a = n.std_a * n.std_a * am / std::f64::consts::TAU + n.std_y * n.std_y * dm;
        let (bx, by, ba) = (self.x[3], self.x[4], self.x[5]);
        let d = distance - dm * bx;
        let a = rotation - am * ba - dm * by;
        let mid = self.x[2] + a / 2.0;
        let (s, c) = mid.sin_cos();
        self.x[0] += d * c;
        self.x[1] += d * s;
        self.x[2] = normalize_angle(self.x[2] + a);
        // ∂(x, y, φ)/∂(x, y, φ, βx, βy, βa); the biases stay.
        let mut f = nalgebra::Matrix6::identity();
        f[(0, 2)] = -d * s;
        f[(1, 2)] = d * c;
        f[(0, 3)] = -dm * c;
        f[(1, 3)] = -dm * s;
        f[(0, 4)] = d * s * dm / 2.0;
        f[(1, 4)] = -d * c * dm / 2.0;
        f[(2, 4)] = -dm;
        f[(0, 5)] = d * s * am / 2.0;
        f[(1, 5)] = -d * c * am / 2.0;
        f[(2, 5)] = -am;
        let g = nalgebra::Matrix3x2::new(c, -d * s / 2.0, s, d * c / 2.0, 0.0, 1.0);
        let q = g * Matrix2::new(var_d, 0.0, 0.0, var_a) * g.transpose();
        let mut prr = f * self.p.fixed_view::<ROBOT, ROBOT>(0, 0) * f.transpose();
        let mut pose = prr.fixed_view_mut::<3, 3>(0, 0);
        pose += q;
        self.p.fixed_view_mut::<ROBOT, ROBOT>(0, 0).copy_from(&prr);
        let m = self.x.len() - ROBOT;
        if m > 0 {
            let prm = f * self.p.view((0, ROBOT), (ROBOT, m));
            self.p.view_mut((0, ROBOT), (ROBOT, m)).copy_from(&prm);
            self.p
                .view_mut((ROBOT, 0), (m, ROBOT))
                .copy_from(&prm.transpose());
        }
    }

    /// The innovation of the robot-relative measurement `z` against feature `i`, its
    /// covariance, and the measurement Jacobian's two column blocks (pose, feature).
    fn innovation(
        &self,
        z: Line,
        i: usize,
    ) -> (
        Vector2<f64>,
        Matrix2<f64>,
        nalgebra::Matrix2x3<f64>,
        Matrix2<f64>,
    ) {
        let k = ROBOT + 2 * i;
        let world = self.feature(i);
        let pred = world.to_robot(self.x[0], self.x[1], self.x[2]);
        let z = z.facing(pred.th);
        let nu = Vector2::new(z.r - pred.r, normalize_angle(z.th - pred.th));
        let j = to_robot_jacobian(world, self.x[0], self.x[1]);
        let hr = nalgebra::Matrix2x3::new(j[0][0], j[0][1], j[0][2], j[1][0], j[1][1], j[1][2]);
        let hm = Matrix2::new(j[0][3], j[0][4], j[1][3], j[1][4]);
        let prr = self.p.fixed_view::<3, 3>(0, 0);
        let prm = self.p.fixed_view::<3, 2>(0, k);
        let pmm = self.p.fixed_view::<2, 2>(k, k);
        let cross = hr * prm * hm.transpose();
        let s = hr * prr * hr.transpose()
            + cross
            + cross.transpose()
            + hm * pmm * hm.transpose()
            + self.measurement_covariance();
        (nu, s, hr, hm)
    }

    fn measurement_covariance(&self) -> Matrix2<f64> {
        Matrix2::new(self.noise.sd_r.powi(2), 0.0, 0.0, self.noise.sd_th.powi(2))
    }

    /// The Mahalanobis distance squared of `z` to feature `i`.
    pub fn distance2(&self, z: Line, i: usize) -> f64 {
        let (nu, s, _, _) = self.innovation(z, i);
        s.try_inverse()
            .map_or(f64::INFINITY, |inv| (nu.transpose() * inv * nu)[0])
    }

    /// Takes one robot-relative wall measurement: updates the nearest feature if it lies inside
    /// the gate, starts a new feature if every feature lies beyond the new-feature gate, and
    /// otherwise drops it.
    pub fn observe(&mut self, z: Line) -> Association {
        let best = (0..self.features())
            .map(|i| (i, self.distance2(z, i)))
            .min_by(|a, b| a.1.total_cmp(&b.1));
        match best {
            Some((i, d2)) if d2 <= self.gate => {
                self.update(z, i);
                Association::Matched(i)
            }
            Some((_, d2)) if d2 <= self.new_gate || !d2.is_finite() => Association::Rejected,
            _ => Association::New(self.add_feature(z)),
        }
    }

    fn update(&mut self, z: Line, i: usize) {
        let k = ROBOT + 2 * i;
        let (nu, s, hr, hm) = self.innovation(z, i);
        let Some(s_inv) = s.try_inverse() else {
            return;
        };
        // P Hᵀ, using H's two non-zero blocks.
        let pht = self.p.columns(0, 3) * hr.transpose() + self.p.columns(k, 2) * hm.transpose();
        let gain = &pht * s_inv;
        self.x += &gain * nu;
        self.x[2] = normalize_angle(self.x[2]);
        for f in 0..self.features() {
            let t = ROBOT + 1 + 2 * f;
            self.x[t] = normalize_angle(self.x[t]);
        }
        self.p -= &gain * pht.transpose();
        let sym = (&self.p + self.p.transpose()) * 0.5;
        self.p = sym;
    }

    fn add_feature(&mut self, z: Line) -> usize {
        let (x, y, phi) = (self.x[0], self.x[1], self.x[2]);
        let world = z.to_world(x, y, phi);
        let (jr, jz) = to_world_jacobians(z, x, y, phi);
        let gr =
            nalgebra::Matrix2x3::new(jr[0][0], jr[0][1], jr[0][2], jr[1][0], jr[1][1], jr[1][2]);
        let gz = Matrix2::new(jz[0][0], jz[0][1], jz[1][0], jz[1][1]);
        let n = self.x.len();
        let cross = gr * self.p.rows(0, 3); // 2 × n
        let pmm = gr * self.p.fixed_view::<3, 3>(0, 0) * gr.transpose()
            + gz * self.measurement_covariance() * gz.transpose();
        let mut x = self.x.clone().resize_vertically(n + 2, 0.0);
        x[n] = world.r;
        x[n + 1] = world.th;
        let mut p = self.p.clone().resize(n + 2, n + 2, 0.0);
        p.view_mut((n, 0), (2, n)).copy_from(&cross);
        p.view_mut((0, n), (n, 2)).copy_from(&cross.transpose());
        p.fixed_view_mut::<2, 2>(n, n).copy_from(&pmm);
        self.x = x;
        self.p = p;
        self.features() - 1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quiet() -> Noise {
        Noise {
            sd_r: 0.02,
            sd_th: 0.01,
            ..Noise::STAGE2_HOUGH
        }
    }

    #[test]
    fn a_static_robot_and_a_known_wall_converge() {
        let truth = Pose::new(0.0, 0.0, 0.0);
        let mut ekf = Ekf::new(Pose::new(0.0, 0.0, 0.0), [0.01, 0.01, 0.01], quiet());
        let wall = Line::new(4.0, 0.0);
        // Noise-free sightings of the wall x = 4 and the wall y = 3.
        let walls = [wall, Line::new(3.0, std::f64::consts::FRAC_PI_2)];
        let mut sds = Vec::new();
        for _ in 0..50 {
            ekf.predict(0.0, 0.0);
            for w in walls {
                let a = ekf.observe(w.to_robot(truth.x, truth.y, truth.th));
                assert!(!matches!(a, Association::Rejected));
            }
            sds.push(ekf.feature_sd(0).0);
        }
        assert_eq!(ekf.features(), 2);
        let f = ekf.feature(0);
        assert!((f.r - 4.0).abs() < 1e-9 && f.th.abs() < 1e-9, "{f:?}");
        assert!(sds.windows(2).all(|w| w[1] <= w[0] + 1e-15));
        assert!(ekf.pose().distance(&truth) < 1e-9);
    }

    #[test]
    fn a_wall_pulls_a_drifted_pose_back() {
        let mut ekf = Ekf::new(Pose::new(0.0, 0.0, 0.0), [1e-4, 1e-4, 1e-4], quiet());
        ekf.observe(Line::new(4.0, 0.0));
        ekf.observe(Line::new(3.0, std::f64::consts::FRAC_PI_2));
        // The odometry says 1 m along x; the robot truly went 0.9 m.
        for _ in 0..10 {
            ekf.predict(0.1, 0.0);
        }
        let before = (ekf.pose().x - 0.9).abs();
        for _ in 0..5 {
            ekf.observe(Line::new(3.1, 0.0));
        }
        assert!(
            (ekf.pose().x - 0.9).abs() < before / 2.0,
            "{:?}",
            ekf.pose()
        );
        assert!(ekf.nees(&Pose::new(0.9, 0.0, 0.0)).is_finite());
    }

    #[test]
    fn a_heading_bias_is_learned_from_a_wall() {
        // The robot drives straight along x beside the wall y = 3 m; its odometry reports a
        // turn of 0.01 rad per metre that never happened (a heading bias βy), for 30 m.
        let noise = quiet();
        let mut ekf = Ekf::new(Pose::new(0.0, 0.0, 0.0), [0.01, 0.01, 0.01], noise);
        let wall = Line::new(3.0, std::f64::consts::FRAC_PI_2);
        let step = 0.03;
        for k in 1..=1000 {
            ekf.predict(step, step * 0.01);
            if k % 25 == 0 {
                let truth = Pose::new(step * k as f64, 0.0, 0.0);
                ekf.observe(wall.to_robot(truth.x, truth.y, truth.th));
            }
        }
        let by = ekf.biases()[1];
        assert!(by > 0.005 && by < 0.015, "βy = {by}");
        assert!(ekf.pose().th.abs() < 0.01, "{:?}", ekf.pose());
    }

    #[test]
    fn angles_wrap_across_pi() {
        // A wall seen at θ just below +π, its feature at just above −π: the same wall.
        let mut ekf = Ekf::new(Pose::new(0.0, 0.0, 3.13), [0.01, 0.01, 0.01], quiet());
        ekf.observe(Line::new(2.0, 0.015));
        let a = ekf.observe(Line::new(2.0, 0.0));
        assert_eq!(a, Association::Matched(0));
        // The heading wraps too.
        ekf.predict(0.0, 0.05);
        assert!(ekf.pose().th < -3.0 && ekf.pose().th > -std::f64::consts::PI);
        assert!(ekf.feature(0).th.abs() <= std::f64::consts::PI);
        // And a measurement in the opposite (r, θ) form still matches.
        let a = ekf.observe(Line::new(-2.0, 0.0 - 0.05 + std::f64::consts::PI));
        assert_eq!(a, Association::Matched(0));
    }

    #[test]
    fn gating_rejects_an_outlier() {
        let mut ekf = Ekf::new(Pose::new(0.0, 0.0, 0.0), [0.01, 0.01, 0.01], quiet());
        for _ in 0..5 {
            ekf.observe(Line::new(4.0, 0.0));
        }
        let pose = ekf.pose();
        let feature = ekf.feature(0);
        // 0.3 m off with σ_r = 0.02 m: far outside the gate. It neither moves the pose nor the
        // feature; it starts a feature of its own.
        let a = ekf.observe(Line::new(4.3, 0.0));
        assert_eq!(a, Association::New(1));
        assert_eq!(ekf.pose(), pose);
        assert_eq!(ekf.feature(0), feature);
        // Between the gates it is dropped.
        let mut ekf = Ekf::new(Pose::new(0.0, 0.0, 0.0), [1e-4, 1e-4, 1e-4], quiet());
        ekf.observe(Line::new(4.0, 0.0));
        // The innovation's σ is about √2 · 0.02 m (the feature's and the measurement's): 3σ off.
        let d = 0.02 * 2f64.sqrt() * 3.0;
        assert_eq!(ekf.observe(Line::new(4.0 + d, 0.0)), Association::Rejected);
        assert_eq!(ekf.features(), 1);
    }

    #[test]
    fn the_same_input_gives_the_same_output() {
        let run = || {
            let mut ekf = Ekf::new(Pose::new(0.1, 0.2, 0.3), [0.01, 0.01, 0.01], quiet());
            for k in 0..100 {
                ekf.predict(0.05, 0.01);
                ekf.observe(Line::new(4.0 - 0.001 * k as f64, 0.02));
            }
            (ekf.pose(), ekf.pose_covariance())
        };
        assert_eq!(run(), run());
    }
}
