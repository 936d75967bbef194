//! The thesis's sonar-to-walls pipeline ("Hough-Transform Java"), in four pure steps:
//!
//! 1. [`convert`]: sonar data converter (ranges → x, y points in the believed frame, mm);
//! 2. [`filter`]: noise filter (visible lines voted into a vote space, keep points with more
//!    than k votes);
//! 3. [`hough`]: Hough transform `r = x cos θ + y sin θ`, θ = 0..359 in 1° steps, voting;
//! 4. [`zones`] and [`extract`]: wall extraction (zones above the critical value k, their
//!    centres, start and end points) into [`Wall`] elements, with the line fits of [`fit`].
//!
//! [`run`] chains them over a window of recent scans ([`ScanWindow`]); [`Settings`] holds every
//! knob, with the reason for each default.
//!
//! Two deliberate departures from the thesis, both switchable in [`Settings`]: by default the
//! Hough votes come from the returns' visible arcs (`VoteMode::Arcs`, Tardós et al. 2002, the
//! thesis's reference \[3\]) rather than from the points alone (`VoteMode::Points`), and each
//! wall's line is refitted to its returns (`refine`). The table in [`settings`] shows why.
//!
//! All scans in a window are pooled in the believed frame of their own time. When the believed
//! pose is reset (`setOdometry`), older scans are in the old frame: a caller that wants walls in
//! the new frame only should [`ScanWindow::clear`] the window then.

pub mod convert;
pub mod extract;
pub mod filter;
pub mod fit;
pub mod hough;
mod pool;
pub mod settings;
pub mod wall;
pub mod zones;

use std::collections::VecDeque;

use super::geom::Pose;
use super::sonar::{Transducer, NUM_SONARS};

pub use convert::SonarPoint;
pub use filter::VoteSpace;
pub use hough::Accumulator;
pub use settings::{Settings, VoteMode};
pub use wall::{PointMm, RefPose, Wall};
pub use zones::{Peak, Zone};

/// One sonar scan: the 16 ranges (mm) and the pose the robot believed it had when taking them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scan {
    /// Ranges, mm, by sonar number.
    pub ranges_mm: [f64; NUM_SONARS],
    /// Believed robot pose at scan time.
    pub pose: Pose,
}

/// The most recent scans, oldest first, up to a capacity (`Settings::scan_window`).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ScanWindow {
    capacity: usize,
    scans: VecDeque<Scan>,
}

impl ScanWindow {
    /// An empty window keeping at most `capacity` scans (at least one).
    pub fn new(capacity: usize) -> Self {
        ScanWindow {
            capacity: capacity.max(1),
            scans: VecDeque::new(),
        }
    }

    /// Adds a scan, dropping the oldest when full.
    pub fn push(&mut self, scan: Scan) {
        if self.scans.len() == self.capacity {
            self.scans.pop_front();
        }
        self.scans.push_back(scan);
    }

    /// Forgets all scans (e.g. after the believed pose was reset).
    pub fn clear(&mut self) {
        self.scans.clear();
    }

    /// Number of scans held.
    pub fn len(&self) -> usize {
        self.scans.len()
    }

    /// Whether the window is empty.
    pub fn is_empty(&self) -> bool {
        self.scans.is_empty()
    }

    /// The scans, oldest first.
    pub fn scans(&self) -> impl Iterator<Item = &Scan> {
        self.scans.iter()
    }

    /// The newest scan.
    pub fn latest(&self) -> Option<&Scan> {
        self.scans.back()
    }
}

/// Everything one pass of the pipeline produced, for the input-link and for plots.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Extraction {
    /// All converted returns (Figure 15).
    pub points: Vec<SonarPoint>,
    /// The noise filter's vote space (Figure 18).
    pub vote_space: VoteSpace,
    /// The returns that passed the noise filter (Figure 19).
    pub filtered: Vec<SonarPoint>,
    /// The voted Hough space (Figure 20).
    pub accumulator: Accumulator,
    /// Its zones above k (Figure 21).
    pub zones: Vec<Zone>,
    /// The extracted walls (Figure 22).
    pub walls: Vec<Wall>,
}

/// Runs the four steps over `scans` (all scans are pooled in the believed frame). The walls'
/// `^Ref` is the believed pose of the last scan and their `^Time` is `time`.
pub fn run<'a>(
    scans: impl IntoIterator<Item = &'a Scan>,
    transducers: &[Transducer],
    settings: &Settings,
    time: i64,
) -> Extraction {
    let mut points = Vec::new();
    let mut last_pose = None;
    for scan in scans {
        points.extend(convert::convert(
            &scan.ranges_mm,
            transducers,
            &scan.pose,
            settings,
        ));
        last_pose = Some(scan.pose);
    }
    let reference = RefPose::from_pose(&last_pose.unwrap_or_default());
    let vote_space = filter::vote_space(&points, settings);
    let filtered = filter::noise_filter(&points, &vote_space, settings);
    let accumulator = hough::hough(&filtered, settings);
    let zones = zones::find_zones(&accumulator, settings.k);
    let walls = extract::extract_walls(&filtered, &zones, settings, reference, time);
    Extraction {
        points,
        vote_space,
        filtered,
        accumulator,
        zones,
        walls,
    }
}

#[cfg(test)]
mod tests {
    use super::super::sonar::P2DX_SONARS;
    use super::*;

    #[test]
    fn window_keeps_the_latest_scans() {
        let mut w = ScanWindow::new(3);
        for i in 0..5 {
            w.push(Scan {
                ranges_mm: [i as f64; NUM_SONARS],
                pose: Pose::default(),
            });
        }
        assert_eq!(w.len(), 3);
        let firsts: Vec<f64> = w.scans().map(|s| s.ranges_mm[0]).collect();
        assert_eq!(firsts, vec![2.0, 3.0, 4.0]);
        assert_eq!(w.latest().map(|s| s.ranges_mm[0]), Some(4.0));
        w.clear();
        assert!(w.is_empty());
    }

    /// Scans of a noise-free sonar ring (25 rays over its 25° cone, so that each reading is the
    /// nearest echo in the cone) taken at 60 poses around a loop inside a 4 × 4 m room centred on
    /// the origin.
    fn square_room_scans() -> Vec<Scan> {
        use super::super::geom::Segment;
        use super::super::rng::Rng;
        use super::super::sonar::{NoisePreset, SonarModel};
        let walls = [
            Segment::new(-2.0, -2.0, 2.0, -2.0),
            Segment::new(2.0, -2.0, 2.0, 2.0),
            Segment::new(2.0, 2.0, -2.0, 2.0),
            Segment::new(-2.0, 2.0, -2.0, -2.0),
        ];
        let model = SonarModel {
            rays: 25,
            cone_deg: 25.0,
            ..SonarModel::preset(NoisePreset::Ideal)
        };
        let mut rng = Rng::seed_from_u64(0);
        (0..60)
            .map(|i| {
                let a = i as f64 * std::f64::consts::TAU / 60.0;
                let pose = Pose::new(0.9 * a.cos(), 0.6 * a.sin(), a + 1.3);
                Scan {
                    ranges_mm: model.read_ring_mm(&walls, &pose, &mut rng),
                    pose,
                }
            })
            .collect()
    }

    #[test]
    fn square_room_end_to_end_within_2cm_and_1deg() {
        let scans = square_room_scans();
        for mode in [VoteMode::Arcs, VoteMode::Points] {
            let settings = Settings {
                vote_mode: mode,
                ..Settings::default()
            };
            let out = run(&scans, &P2DX_SONARS, &settings, 3);
            assert_eq!(out.points.len(), 60 * 16, "every reading is an echo");
            assert!(
                out.filtered.len() > 900,
                "{mode}: {} kept",
                out.filtered.len()
            );
            assert_eq!(out.walls.len(), 4, "{mode}: {:#?}", out.walls);
            let mut worst = (0.0f64, 0.0f64);
            for th in [0.0, 90.0, 180.0, 270.0] {
                let w = out
                    .walls
                    .iter()
                    .find(|w| (w.line.1 - th).abs() < 5.0 || (w.line.1 - th - 360.0).abs() < 5.0)
                    .expect("wall");
                let dth = (w.line.1 - th).abs().min((w.line.1 - th - 360.0).abs());
                worst = (worst.0.max((w.line.0 - 2000.0).abs()), worst.1.max(dth));
                assert_eq!(w.time, 3);
                assert_eq!(w.reference, RefPose::from_pose(&scans[59].pose));
            }
            eprintln!(
                "end to end ({mode}): worst Δr {:.1} mm, Δθ {:.2}°",
                worst.0, worst.1
            );
            assert!(worst.0 < 20.0 && worst.1 < 1.0, "{mode}: {worst:?}");
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(32))]

        /// Whatever the readings and poses (NaN, infinities, huge values), the pipeline returns
        /// without panicking.
        #[test]
        fn pipeline_never_panics(
            ranges in proptest::collection::vec(
                proptest::prop_oneof![
                    0.0f64..6000.0,
                    proptest::prelude::Just(f64::NAN),
                    proptest::prelude::Just(f64::INFINITY),
                    proptest::prelude::Just(-1.0e300),
                ],
                NUM_SONARS * 3,
            ),
            poses in proptest::collection::vec(
                (-1.0e6f64..1.0e6, -1.0e6f64..1.0e6, -100.0f64..100.0),
                3,
            ),
            k in 0u32..40,
            mode in proptest::prelude::any::<bool>(),
        ) {
            let scans: Vec<Scan> = poses
                .iter()
                .enumerate()
                .map(|(i, &(x, y, th))| {
                    let mut r = [0.0; NUM_SONARS];
                    r.copy_from_slice(&ranges[i * NUM_SONARS..(i + 1) * NUM_SONARS]);
                    Scan { ranges_mm: r, pose: Pose::new(x, y, th) }
                })
                .collect();
            let settings = Settings {
                k,
                vote_mode: if mode { VoteMode::Arcs } else { VoteMode::Points },
                ..Settings::default()
            };
            let out = run(&scans, &P2DX_SONARS, &settings, 0);
            proptest::prop_assert!(out.walls.iter().all(|w| (0..360).contains(&w.th) && w.r >= 0));
        }
    }

    #[test]
    fn empty_input_gives_no_walls() {
        let out = run(&[], &P2DX_SONARS, &Settings::default(), 0);
        assert!(out.points.is_empty() && out.walls.is_empty());
    }
}
