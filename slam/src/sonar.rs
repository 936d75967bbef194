//! The Pioneer 2-DX sonar ring and its range models.
//!
//! Geometry: the 16 transducer poses of ARIA's `params/p2dx.p` (`SonarUnit n x y heading`):
//! front ring 0–7 at 90, 50, 30, 10, −10, −30, −50, −90°, rear ring 8–15 mirrored;
//! numbering clockwise seen from above.
//!
//! Range model: each transducer casts a few rays spread evenly over its beam cone and
//! reports the nearest echo, clamped to `[0.15, 5] m`, as Stage 2.0.x's `model_ranger.c`
//! does. No echo reads as the maximum range. Three noise presets:
//!
//! - [`NoisePreset::Ideal`]: Stage-like, 3 rays over 15°, no noise (what the thesis saw);
//! - [`NoisePreset::Realistic`]: 7 rays over 25°, Gaussian noise of 1 cm + 1 % of the range,
//!   specular misses at grazing incidence, 7.5 % multipath outliers;
//! - [`NoisePreset::Pessimistic`]: Player AMCL's sonar model level, σ = 0.2 m and 20 % bad
//!   readings, on the realistic geometry.

use std::fmt;
use std::str::FromStr;

use super::geom::{Point, Pose, Segment};
use super::rng::Rng;

/// Number of sonar transducers on a Pioneer 2-DX.
pub const NUM_SONARS: usize = 16;

/// The pose of one sonar transducer on the robot body (x forward, y left).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Transducer {
    /// Forward offset from the centre of rotation, mm.
    pub x_mm: f64,
    /// Leftward offset from the centre of rotation, mm.
    pub y_mm: f64,
    /// Beam axis direction relative to the robot heading, degrees.
    pub heading_deg: f64,
}

impl Transducer {
    const fn new(x_mm: f64, y_mm: f64, heading_deg: f64) -> Self {
        Transducer {
            x_mm,
            y_mm,
            heading_deg,
        }
    }
}

/// ARIA `params/p2dx.p` sonar table, indexed by sonar number.
pub const P2DX_SONARS: [Transducer; NUM_SONARS] = [
    Transducer::new(69.0, 136.0, 90.0),
    Transducer::new(114.0, 119.0, 50.0),
    Transducer::new(148.0, 78.0, 30.0),
    Transducer::new(166.0, 27.0, 10.0),
    Transducer::new(166.0, -27.0, -10.0),
    Transducer::new(148.0, -78.0, -30.0),
    Transducer::new(114.0, -119.0, -50.0),
    Transducer::new(69.0, -136.0, -90.0),
    Transducer::new(-157.0, -136.0, -90.0),
    Transducer::new(-203.0, -119.0, -130.0),
    Transducer::new(-237.0, -78.0, -150.0),
    Transducer::new(-255.0, -27.0, -170.0),
    Transducer::new(-255.0, 27.0, 170.0),
    Transducer::new(-237.0, 78.0, 150.0),
    Transducer::new(-203.0, 119.0, 130.0),
    Transducer::new(-157.0, 136.0, 90.0),
];

/// The sensor-noise presets.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
pub enum NoisePreset {
    /// Stage 2.0.x: 3 rays over 15°, no noise.
    #[default]
    Ideal,
    /// 7 rays over 25°, σ = 1 cm + 1 % of range, specular misses, 7.5 % outliers.
    Realistic,
    /// σ = 0.2 m and 20 % bad readings (Player AMCL sonar model).
    Pessimistic,
}

impl NoisePreset {
    /// All presets, in order.
    pub const ALL: [NoisePreset; 3] = [
        NoisePreset::Ideal,
        NoisePreset::Realistic,
        NoisePreset::Pessimistic,
    ];

    /// The preset's name as written in world files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            NoisePreset::Ideal => "ideal",
            NoisePreset::Realistic => "realistic",
            NoisePreset::Pessimistic => "pessimistic",
        }
    }
}

impl fmt::Display for NoisePreset {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// An unknown noise-preset name.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown noise preset `{0}` (expected ideal, realistic or pessimistic)")]
pub struct UnknownPreset(pub String);

impl FromStr for NoisePreset {
    type Err = UnknownPreset;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        NoisePreset::ALL
            .into_iter()
            .find(|p| p.name().eq_ignore_ascii_case(s.trim()))
            .ok_or_else(|| UnknownPreset(s.to_string()))
    }
}

/// A sonar range model: beam geometry, limits and noise.
#[derive(Debug, Clone, PartialEq)]
pub struct SonarModel {
    /// Shortest reportable range, m (closer echoes read as this).
    pub min_range_m: f64,
    /// Longest range, m; no echo reads as this.
    pub max_range_m: f64,
    /// Rays cast per transducer: the cone is cut into this many equal sectors and one ray runs
    /// along the middle of each (Stage 2.0.x: 15° and 3 rays give −5°, 0°, +5°).
    pub rays: usize,
    /// Full beam cone, degrees.
    pub cone_deg: f64,
    /// Constant part of the Gaussian range noise σ, m.
    pub sigma_const_m: f64,
    /// Proportional part of σ (fraction of the true range).
    pub sigma_prop: f64,
    /// Rays meeting a wall further than this from its normal, in degrees, reflect away
    /// (specular miss). `None` disables specular misses.
    pub max_incidence_deg: Option<f64>,
    /// Probability that a reading is replaced by a uniform random range (multipath,
    /// cross-talk).
    pub outlier_prob: f64,
}

impl SonarModel {
    /// The model of a noise preset.
    pub fn preset(preset: NoisePreset) -> Self {
        match preset {
            // Stage 2.0.x p2dx: `sview [0 5.0 15]`, `sraycount 3` → rays at −5, 0, +5°.
            NoisePreset::Ideal => SonarModel {
                min_range_m: 0.15,
                max_range_m: 5.0,
                rays: 3,
                cone_deg: 15.0,
                sigma_const_m: 0.0,
                sigma_prop: 0.0,
                max_incidence_deg: None,
                outlier_prob: 0.0,
            },
            // Polaroid cone of ~25° (Moravec & Elfes report 30°), 7 rays 3.6° apart.
            // Grazing rays beyond 60° from the normal are lost (Leonard & Durrant-Whyte:
            // smooth walls return only near normal incidence).
            NoisePreset::Realistic => SonarModel {
                min_range_m: 0.15,
                max_range_m: 5.0,
                rays: 7,
                cone_deg: 25.0,
                sigma_const_m: 0.01,
                sigma_prop: 0.01,
                max_incidence_deg: Some(60.0),
                outlier_prob: 0.075,
            },
            // Player AMCL sonar: range_cov 0.2², range_bad 0.2.
            NoisePreset::Pessimistic => SonarModel {
                min_range_m: 0.15,
                max_range_m: 5.0,
                rays: 7,
                cone_deg: 25.0,
                sigma_const_m: 0.2,
                sigma_prop: 0.0,
                max_incidence_deg: Some(60.0),
                outlier_prob: 0.2,
            },
        }
    }

    /// Ray angle offsets from the beam axis, radians.
    fn ray_offsets(&self) -> impl Iterator<Item = f64> + '_ {
        let n = self.rays.max(1);
        let cone = self.cone_deg.to_radians();
        (0..n).map(move |i| -cone / 2.0 + cone * (i as f64 + 0.5) / n as f64)
    }

    /// The noise-free range, in metres, that transducer `t` of a robot at `pose` reports
    /// among `walls` (nearest echo among its rays, within the limits), ignoring specular
    /// misses. `None` when no ray hits within range.
    pub fn geometric_range(&self, walls: &[Segment], pose: &Pose, t: &Transducer) -> Option<f64> {
        self.nearest_echo(walls, pose, t, None)
    }

    fn nearest_echo(
        &self,
        walls: &[Segment],
        pose: &Pose,
        t: &Transducer,
        min_cos_incidence: Option<f64>,
    ) -> Option<f64> {
        let origin = pose.transform(Point::new(t.x_mm / 1000.0, t.y_mm / 1000.0));
        // A transducer pushed through a wall (the robot touching it) hears that wall at once.
        if walls.iter().any(|w| w.crosses(pose.position(), origin)) {
            return Some(self.min_range_m);
        }
        let axis = pose.th + t.heading_deg.to_radians();
        let mut best: Option<f64> = None;
        for offset in self.ray_offsets() {
            let (dy, dx) = (axis + offset).sin_cos();
            for wall in walls {
                if let Some(hit) = wall.ray_hit_dir(origin, dx, dy) {
                    if min_cos_incidence.is_some_and(|c| hit.cos_incidence < c) {
                        continue;
                    }
                    if hit.distance <= self.max_range_m && best.is_none_or(|b| hit.distance < b) {
                        best = Some(hit.distance);
                    }
                }
            }
        }
        best.map(|d| d.max(self.min_range_m))
    }

    /// One reading, in metres, of transducer `t` with noise drawn from `rng`.
    ///
    /// The number of random draws per call is fixed (3 uniforms/normals), so a run's sensing
    /// stream advances identically whatever the readings are.
    pub fn read(&self, walls: &[Segment], pose: &Pose, t: &Transducer, rng: &mut Rng) -> f64 {
        let min_cos = self.max_incidence_deg.map(|d| d.to_radians().cos());
        let noise = rng.gaussian();
        let outlier = rng.chance(self.outlier_prob);
        let random_range = rng.range(self.min_range_m, self.max_range_m);
        if outlier {
            return random_range;
        }
        match self.nearest_echo(walls, pose, t, min_cos) {
            None => self.max_range_m,
            Some(d) => {
                let sigma = self.sigma_const_m + self.sigma_prop * d;
                (d + sigma * noise).clamp(self.min_range_m, self.max_range_m)
            }
        }
    }

    /// All 16 readings of the P2-DX ring, in millimetres.
    pub fn read_ring_mm(&self, walls: &[Segment], pose: &Pose, rng: &mut Rng) -> [f64; NUM_SONARS] {
        let mut out = [0.0; NUM_SONARS];
        for (o, t) in out.iter_mut().zip(P2DX_SONARS.iter()) {
            *o = self.read(walls, pose, t, rng) * 1000.0;
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn room() -> Vec<Segment> {
        vec![
            Segment::new(-4.0, -3.0, 4.0, -3.0),
            Segment::new(4.0, -3.0, 4.0, 3.0),
            Segment::new(4.0, 3.0, -4.0, 3.0),
            Segment::new(-4.0, 3.0, -4.0, -3.0),
        ]
    }

    #[test]
    fn table_matches_aria_p2dx() {
        assert_eq!(P2DX_SONARS[0], Transducer::new(69.0, 136.0, 90.0));
        assert_eq!(P2DX_SONARS[3], Transducer::new(166.0, 27.0, 10.0));
        assert_eq!(P2DX_SONARS[8], Transducer::new(-157.0, -136.0, -90.0));
        // Sonar 15 − i mirrors sonar i front to back: same y, heading reflected about ±90°.
        for i in 0..8 {
            let f = P2DX_SONARS[i];
            let r = P2DX_SONARS[15 - i];
            assert_eq!(f.y_mm, r.y_mm, "sonar {i} vs {}", 15 - i);
            let mirrored = if f.heading_deg.abs() == 90.0 {
                f.heading_deg
            } else {
                f.heading_deg.signum() * (180.0 - f.heading_deg.abs())
            };
            assert_eq!(r.heading_deg, mirrored, "sonar {}", 15 - i);
        }
    }

    #[test]
    fn presets_parse_by_name() {
        for p in NoisePreset::ALL {
            assert_eq!(p.name().parse::<NoisePreset>(), Ok(p));
        }
        assert!("stage".parse::<NoisePreset>().is_err());
    }

    #[test]
    fn ideal_facing_wall_is_exact() {
        // Robot facing +x, 2 m from the wall x = 4: sonar 3 sits at x +166 mm heading 10°,
        // sonar 4 at −10°. Their middle rays make 10° with the normal, but the +5° / −5° edge
        // rays are at 5° and 15°: the nearest echo is along the 5° ray.
        let walls = room();
        let model = SonarModel::preset(NoisePreset::Ideal);
        let mut rng = Rng::seed_from_u64(1);
        for x in [-1.0, 0.0, 1.7] {
            let pose = Pose::new(x, 0.0, 0.0);
            let ranges = model.read_ring_mm(&walls, &pose, &mut rng);
            let t = P2DX_SONARS[3];
            let perpendicular = (4.0 - x) * 1000.0 - t.x_mm;
            let expected = perpendicular / 5f64.to_radians().cos();
            assert!(
                (ranges[3] - expected).abs() < 1.0,
                "{} vs {expected}",
                ranges[3]
            );
            assert!((ranges[4] - expected).abs() < 1.0);
            // Sonar 0 points straight at the wall y = 3 from y = +136 mm: exact.
            let side = 3000.0 - P2DX_SONARS[0].y_mm;
            assert!((ranges[0] - side).abs() < 1.0, "{} vs {side}", ranges[0]);
            assert!((ranges[7] - side).abs() < 1.0);
            assert!((ranges[8] - side).abs() < 1.0);
        }
    }

    #[test]
    fn ideal_head_on_axis_ray_is_exact() {
        // Rotate the robot so sonar 3's axis is normal to the wall x = 4: the middle ray is the
        // nearest echo and equals the perpendicular distance.
        let walls = room();
        let model = SonarModel::preset(NoisePreset::Ideal);
        let mut rng = Rng::seed_from_u64(1);
        let pose = Pose::new(1.0, 0.5, (-10f64).to_radians());
        let t = P2DX_SONARS[3];
        let origin = pose.transform(Point::new(t.x_mm / 1000.0, t.y_mm / 1000.0));
        let expected = (4.0 - origin.x) * 1000.0;
        let got = model.read(&walls, &pose, &t, &mut rng) * 1000.0;
        assert!((got - expected).abs() < 1.0, "{got} vs {expected}");
    }

    #[test]
    fn limits_clamp_and_no_echo_reads_max() {
        let model = SonarModel::preset(NoisePreset::Ideal);
        let mut rng = Rng::seed_from_u64(1);
        // Far wall beyond 5 m: max range.
        let walls = [Segment::new(9.0, -5.0, 9.0, 5.0)];
        let r = model.read(&walls, &Pose::default(), &P2DX_SONARS[3], &mut rng);
        assert_eq!(r, 5.0);
        // Nothing at all: max range.
        assert_eq!(
            model.read(&[], &Pose::default(), &P2DX_SONARS[3], &mut rng),
            5.0
        );
        // A wall 5 cm in front of the transducer: clamped to 0.15 m.
        let walls = [Segment::new(0.22, -5.0, 0.22, 5.0)];
        let r = model.read(&walls, &Pose::default(), &P2DX_SONARS[3], &mut rng);
        assert_eq!(r, 0.15);
        // A transducer through a wall reads the minimum.
        let walls = [Segment::new(-0.2, -5.0, -0.2, 5.0)];
        let r = model.read(&walls, &Pose::default(), &P2DX_SONARS[11], &mut rng);
        assert_eq!(r, 0.15);
    }

    #[test]
    fn realistic_noise_statistics() {
        // Head-on at 2 m: mean ≈ true, σ ≈ 1 cm + 1 % · 2 m = 3 cm, ~7.5 % outliers.
        let walls = room();
        let model = SonarModel::preset(NoisePreset::Realistic);
        let mut rng = Rng::seed_from_u64(9);
        let pose = Pose::new(1.0, 0.5, (-10f64).to_radians());
        let t = P2DX_SONARS[3];
        let truth = model.geometric_range(&walls, &pose, &t).expect("echo");
        let n = 20_000;
        let (mut good, mut sum, mut sq) = (0usize, 0.0, 0.0);
        for _ in 0..n {
            let r = model.read(&walls, &pose, &t, &mut rng);
            let e = r - truth;
            if e.abs() < 0.2 {
                good += 1;
                sum += e;
                sq += e * e;
            }
        }
        let mean = sum / good as f64;
        let sd = (sq / good as f64 - mean * mean).sqrt();
        let sigma = 0.01 + 0.01 * truth;
        assert!(mean.abs() < 0.002, "mean {mean}");
        assert!((sd - sigma).abs() < 0.1 * sigma, "sd {sd} vs {sigma}");
        let bad = 1.0 - good as f64 / n as f64;
        // Outliers are uniform over 0.15–5 m, so ~8 % of them land within ±0.2 m anyway.
        assert!((0.06..0.08).contains(&bad), "bad fraction {bad}");
    }

    #[test]
    fn realistic_specular_miss_at_grazing_incidence() {
        // A single wall seen at 75° from its normal: every ray of the 25° cone is beyond 60°.
        let walls = [Segment::new(0.0, 1.0, 10.0, 1.0)];
        let t = Transducer::new(0.0, 0.0, 15.0);
        let pose = Pose::default();
        let ideal = SonarModel::preset(NoisePreset::Ideal);
        assert!(ideal.geometric_range(&walls, &pose, &t).is_some());
        let mut model = SonarModel::preset(NoisePreset::Realistic);
        model.outlier_prob = 0.0;
        let mut rng = Rng::seed_from_u64(3);
        assert_eq!(model.read(&walls, &pose, &t, &mut rng), model.max_range_m);
    }

    #[test]
    fn pessimistic_bad_fraction() {
        let walls = room();
        let model = SonarModel::preset(NoisePreset::Pessimistic);
        let mut rng = Rng::seed_from_u64(11);
        let pose = Pose::new(1.0, 0.5, (-10f64).to_radians());
        let t = P2DX_SONARS[3];
        let truth = model.geometric_range(&walls, &pose, &t).expect("echo");
        let n = 20_000;
        let far = (0..n)
            .filter(|_| (model.read(&walls, &pose, &t, &mut rng) - truth).abs() > 0.8)
            .count() as f64
            / n as f64;
        // The Gaussian part beyond 4σ is negligible; outliers (20 %, uniform over 0.15–5 m)
        // land beyond ±0.8 m of the 2.8 m truth with probability (4.85 − 1.6)/4.85 = 0.67.
        assert!((0.11..0.16).contains(&far), "far fraction {far}");
    }
}
