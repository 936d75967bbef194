//! Settings of the sonar-to-walls pipeline, with the reasons for each default.
//!
//! The thesis's "Hough-Transform Java" section names the knobs (the filter's vote
//! threshold, the critical value k, θ from 0 to 359 in 1° steps) but gives no numbers
//! besides the θ grid. The defaults were chosen on the simulator and are justified one by
//! one below. Every field can be set in the `[pipeline]` table of a world file.
//!
//! Measured with the defaults (`settings_sweep` in `tests/robot_pipeline.rs`, ignored by default:
//! wander in the empty 8 × 6 m room with perfect odometry, 4 seeds × 300 s, 480 extractions; a
//! wall is "right" when it is within 200 mm and 5° of a true wall):
//!
//! | vote mode | sonar | walls | right | mean \|Δr\| | mean \|Δθ\| |
//! |---|---|---|---|---|---|
//! | `arcs` (default) | `ideal` | 741 | 99 % | 9 mm | 0.17° |
//! | `arcs` | `realistic` | 280 | 99 % | 24 mm | 0.90° |
//! | `arcs` | `pessimistic` | 0 | – | – | – |
//! | `points` (thesis) | `ideal` | 2223 | 84 % | 55 mm | 1.15° |
//! | `points` | `realistic` | 2484 | 45 % | 54 mm | 1.80° |
//! | `points` | `pessimistic` | 142 | 44 % | 70 mm | 2.72° |
//!
//! With the `pessimistic` preset (σ = 0.2 m, 20 % bad readings) wider bins and a lower k do not
//! rescue `arcs` mode either (r bin 200 mm, support 400 mm, k 10–30: 17–45 % right walls): that
//! noise level is beyond this pipeline.

use std::fmt;
use std::str::FromStr;

/// What votes in the Hough space (see the `hough` module).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
pub enum VoteMode {
    /// The thesis: every filtered return's position votes along its whole sinusoid.
    Points,
    /// Tardós et al. (the thesis's reference \[3\]): every filtered return votes for the lines
    /// tangent to its visible arc.
    #[default]
    Arcs,
}

impl VoteMode {
    /// The name used in world files.
    pub fn name(self) -> &'static str {
        match self {
            VoteMode::Points => "points",
            VoteMode::Arcs => "arcs",
        }
    }
}

impl fmt::Display for VoteMode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for VoteMode {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim() {
            "points" => Ok(VoteMode::Points),
            "arcs" => Ok(VoteMode::Arcs),
            other => Err(format!(
                "unknown vote mode `{other}` (expected points or arcs)"
            )),
        }
    }
}

/// Pipeline settings.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Settings {
    /// What votes in the Hough space. Default `arcs`: a sonar return only says that the nearest
    /// surface in its cone is at that range, so a wall is tangent to the visible arcs of the
    /// returns that see it head-on; voting those tangents gives walls about 6 times more
    /// accurate, with far fewer spurious ones, than voting the return positions on the beam
    /// axis (`points`, the thesis's equation (1) applied to the converted pixels), whose returns
    /// from beams meeting a wall obliquely sit short of the wall (see the table above).
    pub vote_mode: VoteMode,
    /// Critical value k of the wall extractor: a Hough cell belongs to a zone when it holds
    /// **more than** k votes. Default 30: with a 50-scan window a wall seen head-on gives peaks of
    /// 40–200 votes, while corner echoes and beam-edge returns from a robot turning near a wall
    /// make short, tilted phantom walls whose peaks rarely reach 30. At k = 12 only 69 % of the
    /// walls were right (`ideal`, min length 300 mm), at 20 93 %, at 30 99 %.
    pub k: u32,
    /// Hough r bin, mm. Default 50 mm. Finer bins split a wall's votes between neighbours
    /// under range noise; coarser bins merge parallel walls closer than a robot width.
    pub r_bin_mm: f64,
    /// Hough θ step, degrees. Default 1°: the thesis's "θ varies from 0 to 359" in whole degrees.
    pub theta_step_deg: u32,
    /// Number of most recent scans (one per simulator step) pooled for one extraction.
    /// Default 50 scans = 5 s at 10 Hz = 1.5 m of travel at cruise speed: enough returns to
    /// outline the walls around the robot, short enough that odometry drift within the window
    /// (a few centimetres) stays below the r bin. k scales with it: with 30 scans and k = 30 the
    /// walls are all right but 2.6 times fewer; with 100 scans only 84 % are right.
    pub scan_window: usize,
    /// Run an extraction every this many steps. Default 25 (every 2.5 s): each scan takes part
    /// in two extractions, walls come out while they are still near the robot (0.75 m of travel
    /// apart), and the pipeline costs about 0.15–0.25 s per 600-second run.
    pub extract_every: usize,
    /// Noise filter: keep a return whose vote-space cell holds more than this many votes.
    /// Default 2: a return's own visible arc always gives its cell one vote, so at least two
    /// other arcs must agree; isolated multipath returns are dropped.
    pub filter_k: u32,
    /// Noise filter: vote-space cell size, mm. Default 100 mm, twice the r bin: the filter only
    /// has to tell "near a solid line of returns" from "alone", not locate the wall.
    pub filter_cell_mm: f64,
    /// Visibility angle β of a return's visible arc, degrees, used by the noise filter, by `arcs`
    /// voting and by the tangent refinement. Default 25°, the sonar cone of the `realistic`
    /// preset (Moravec & Elfes report about 30° for the Polaroid transducer; Stage 2 uses 15°,
    /// and a wider β than the real cone only costs a slight outward bias of at most
    /// 1 − cos(β/2 − 5°) ≈ 0.9 % of the range there).
    pub beam_deg: f64,
    /// Converter: returns at or below this, in mm, are dropped. Default 150 mm, the sonar's
    /// minimum range: such readings mean "something is touching the robot", not a wall position.
    pub min_range_mm: f64,
    /// Converter: returns at or beyond this, in mm, are dropped. Default 4900 mm, just under the
    /// 5 m maximum range, which is what a transducer reports when it hears no echo.
    pub max_range_mm: f64,
    /// Extractor: a return supports a line when it lies within this distance of it (`points`),
    /// or when its visible arc touches it within this distance (`arcs`), mm. Default 100 mm,
    /// two r bins: 2.5 σ of the `realistic` range noise at 3 m.
    pub support_mm: f64,
    /// Extractor: supporting returns further apart than this along the line, mm, split the line
    /// into separate walls. Default 700 mm: wider than the gaps the sonar ring leaves on a wall
    /// 3–4 m away in one window, narrower than a doorway (~0.8 m).
    pub gap_mm: f64,
    /// Extractor: a wall needs at least this many supporting returns not already used by a
    /// stronger wall. Default 8: fewer returns cannot fix both a direction and an extent.
    pub min_points: usize,
    /// Extractor: walls shorter than this, mm, are dropped. Default 500 mm: the phantom walls of
    /// corner echoes are mostly 300–500 mm long (raising it from 300 to 500 mm took the right
    /// share from 87 % to 93 % at k = 20), while a wall seen for 5 s is longer.
    pub min_length_mm: f64,
    /// Extractor: refit each wall to its supporting returns (see the `fit` module). Default on:
    /// the zone centre alone is quantised to one r bin (±25 mm) and 1°; the refit reaches
    /// millimetres and hundredths of a degree on clean data. Off gives the thesis's plain zone
    /// centre.
    pub refine: bool,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            vote_mode: VoteMode::Arcs,
            k: 30,
            r_bin_mm: 50.0,
            theta_step_deg: 1,
            scan_window: 50,
            extract_every: 25,
            filter_k: 2,
            filter_cell_mm: 100.0,
            beam_deg: 25.0,
            min_range_mm: 150.0,
            max_range_mm: 4900.0,
            support_mm: 100.0,
            gap_mm: 700.0,
            min_points: 8,
            min_length_mm: 500.0,
            refine: true,
        }
    }
}
