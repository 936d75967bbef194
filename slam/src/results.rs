//! The experiment as data: what `rusoar slam` was asked to do ([`Options`]) and what it
//! produced (a [`RunSummary`] per run, the [`Experiment`] holding them all), with the ways the
//! summary and the report read it (by condition, paired by seed). Running the experiment
//! and writing its files is [`super::experiment`]'s job; its figures and `report.md` are
//! [`super::report`]'s.

use std::collections::BTreeMap;
use std::path::PathBuf;

use super::geom::Point;
use super::pipeline::{Extraction, Wall};
use super::soar_loop::{Correction, MemoryWall, Outcome, RunResult, StepRecord};
use super::sonar::NoisePreset;
use super::world::World;

/// Which conditions to run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SlamMode {
    On,
    Off,
    Both,
}

impl SlamMode {
    /// The SLAM switch of each condition to run, off first.
    pub fn conditions(self) -> &'static [bool] {
        match self {
            SlamMode::On => &[true],
            SlamMode::Off => &[false],
            SlamMode::Both => &[false, true],
        }
    }
}

/// The name of a condition in file names and tables.
pub fn condition_name(slam: bool) -> &'static str {
    if slam {
        "on"
    } else {
        "off"
    }
}

/// The experiment's settings.
#[derive(Debug, Clone)]
pub struct Options {
    /// Seeds `first_seed .. first_seed + seeds`.
    pub seeds: u64,
    pub first_seed: u64,
    /// Simulated seconds per run.
    pub duration_s: f64,
    pub slam: SlamMode,
    /// The world, with `--noise` applied.
    pub world: World,
    /// What `--world` said (a built-in name or a file).
    pub world_label: String,
    pub out: PathBuf,
    pub jobs: usize,
    pub rules_dir: PathBuf,
    /// Write each run's input-link and output-link traffic (`io-<on|off>-<seed>.log`).
    pub io_log: bool,
    /// Drift model, rule variants and constants (`--drift`, `--variant`, the constants).
    pub ablation: super::variant::Ablation,
    /// Also run the EKF SLAM over each run without the SLAM rules (`--method ekf`).
    pub ekf: bool,
    /// The command line, as the EKF's table quotes it.
    pub command_line: String,
    /// `--method`, in the order of [`super::method::Method::NAMES`].
    pub methods: Vec<super::method::Method>,
    /// Put the true walls on the input-link and load `oracle.soar` (`--method oracle`).
    pub oracle: bool,
    /// Write `runs.csv`, `summary.md` and `report.md` (they quote wall-clock times, so a
    /// comparison, which must repeat byte for byte, leaves them out of its method folders).
    pub reports: bool,
}

/// The numbers of one run, kept after its steps are written out.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct RunSummary {
    pub seed: u64,
    pub slam: bool,
    pub outcome: Outcome,
    /// Loop wall-clock time, s.
    pub wall_time_s: f64,
    /// Simulated time reached, s.
    pub sim_time_s: f64,
    pub steps: usize,
    /// Time step, s.
    pub dt: f64,
    /// Position error (mm) at each step, for checkpoints.
    pub pos_err_mm: Vec<f64>,
    pub rmse_mm: f64,
    pub max_mm: f64,
    pub final_mm: f64,
    pub final_heading_deg: f64,
    pub rmse_heading_deg: f64,
    pub final_walls: usize,
    pub max_walls: usize,
    pub corrections: u64,
    pub decisions: u64,
    pub firings: u64,
    pub operators: BTreeMap<String, u64>,
    pub walls_extracted: u64,
    pub walls_copied: u64,
    pub walls_expired: u64,
    /// Walls still on the input-link, uncopied, at the end.
    pub final_input_walls: usize,
    pub messages: Vec<String>,
    pub message_count: u64,
    pub bad_commands: Vec<String>,
    pub productions: usize,
    /// Heading error (degrees) at each step.
    pub heading_err_deg: Vec<f64>,
    /// Walls in memory (the top state's `^wallData`) at each step.
    pub walls_memory: Vec<u32>,
    /// Walls extracted so far, at each step.
    pub walls_extracted_so_far: Vec<u32>,
    /// True and believed position at each step, m.
    pub true_path: Vec<Point>,
    pub believed_path: Vec<Point>,
    /// The map in memory at the end.
    pub memory_walls: Vec<MemoryWall>,
    /// Every wall the pipeline extracted.
    pub extracted: Vec<Wall>,
    /// Every `setOdometry` carried out.
    pub correction_log: Vec<Correction>,
    /// The map in memory at chosen times (example seed only).
    pub map_snapshots: Vec<(f64, Vec<MemoryWall>)>,
    /// One whole pipeline output (example seed only).
    pub sample_extraction: Option<(f64, Box<Extraction>)>,
}

impl RunSummary {
    /// Summarises a finished run.
    pub fn of(r: &RunResult, dt: f64) -> Self {
        let n = r.steps.len();
        let errs: Vec<f64> = r.steps.iter().map(|s| s.pos_err_mm).collect();
        let rms = |v: &mut dyn Iterator<Item = f64>| -> f64 {
            let (sum, count) = v.fold((0.0, 0usize), |(s, c), x| (s + x * x, c + 1));
            if count == 0 {
                f64::NAN
            } else {
                (sum / count as f64).sqrt()
            }
        };
        let last: Option<&StepRecord> = r.steps.last();
        RunSummary {
            seed: r.seed,
            slam: r.slam,
            outcome: r.outcome.clone(),
            wall_time_s: r.wall_time.as_secs_f64(),
            sim_time_s: last.map_or(0.0, |s| s.time_s),
            steps: n,
            dt,
            rmse_mm: rms(&mut errs.iter().copied()),
            max_mm: errs.iter().copied().fold(f64::NAN, f64::max),
            final_mm: last.map_or(f64::NAN, |s| s.pos_err_mm),
            final_heading_deg: last.map_or(f64::NAN, |s| s.heading_err_deg),
            rmse_heading_deg: rms(&mut r.steps.iter().map(|s| s.heading_err_deg)),
            final_walls: last.map_or(0, |s| s.walls_memory),
            max_walls: r.steps.iter().map(|s| s.walls_memory).max().unwrap_or(0),
            corrections: last.map_or(0, |s| s.corrections),
            decisions: r.stats.decisions,
            firings: r.stats.firings,
            operators: r.stats.operators.clone(),
            walls_extracted: r.stats.walls_extracted,
            walls_copied: r.stats.walls_copied,
            walls_expired: r.stats.walls_expired,
            final_input_walls: last.map_or(0, |s| s.walls_input),
            messages: r.stats.messages.clone(),
            message_count: r.stats.message_count,
            bad_commands: r.stats.bad_commands.clone(),
            productions: r.productions,
            pos_err_mm: errs,
            heading_err_deg: r.steps.iter().map(|s| s.heading_err_deg).collect(),
            walls_memory: r.steps.iter().map(|s| s.walls_memory as u32).collect(),
            walls_extracted_so_far: r.steps.iter().map(|s| s.walls_extracted as u32).collect(),
            true_path: r.steps.iter().map(|s| s.true_pose.position()).collect(),
            believed_path: r.steps.iter().map(|s| s.believed.position()).collect(),
            memory_walls: r.memory_walls.clone(),
            extracted: r.stats.extracted.clone(),
            correction_log: r.stats.corrections.clone(),
            map_snapshots: r.map_snapshots.clone(),
            sample_extraction: r.sample_extraction.clone(),
        }
    }

    /// The position error at simulated time `t` (the step ending nearest `t`), if reached.
    pub fn err_at(&self, t: f64) -> Option<f64> {
        if self.dt.is_nan() || self.dt <= 0.0 || t <= 0.0 {
            return None;
        }
        let k = (t / self.dt).round() as usize;
        if k == 0 || k > self.pos_err_mm.len() {
            return None;
        }
        Some(self.pos_err_mm[k - 1])
    }
}

/// A seed's value of a measure without and with the SLAM rules: (seed, off, on).
pub(crate) type Pair = (u64, f64, f64);

/// Everything the experiment produced.
#[derive(Debug, Clone)]
pub struct Experiment {
    pub runs: Vec<RunSummary>,
    pub duration_s: f64,
    pub checkpoints: Vec<f64>,
    pub total_wall_s: f64,
    pub jobs: usize,
    pub world_label: String,
    pub noise: NoisePreset,
    /// The world the runs drove in (its walls are the ground truth of the map figures).
    pub world: World,
    /// The seed whose maps, snapshots and Hough space are plotted (the first seed).
    pub example_seed: u64,
    /// The EKF runs (`--method ekf`), by seed.
    pub ekf_runs: Vec<super::ekf::EkfRun>,
}

impl Experiment {
    /// Whether each seed's true path came out the same with and without the SLAM rules, as
    /// a sentence for the reports (`None` unless both conditions ran).
    pub(crate) fn true_paths_note(&self) -> Option<String> {
        let mut pairs = 0;
        let mut same = 0;
        for on in self.runs.iter().filter(|r| r.slam) {
            let Some(off) = self.runs.iter().find(|r| !r.slam && r.seed == on.seed) else {
                continue;
            };
            pairs += 1;
            same += usize::from(on.true_path == off.true_path);
        }
        if pairs == 0 {
            return None;
        }
        Some(if same == pairs {
            format!(
                "The true path of each seed is the same in both conditions ({same} of {pairs} \
                 seeds): the moving rules react only to the sonar, and a motion operator they \
                 propose replaces a selected SLAM operator at once, as 9.6's consistency check \
                 does; only the believed pose differs."
            )
        } else {
            format!(
                "The true path of {same} of {pairs} seeds is the same in both conditions; in the \
                 others the paths part where a SLAM operator holds the top state when the \
                 moving rules want to move or turn."
            )
        })
    }

    pub(crate) fn conditions(&self) -> Vec<bool> {
        let mut c: Vec<bool> = self.runs.iter().map(|r| r.slam).collect();
        c.sort();
        c.dedup();
        c
    }

    /// Completed runs of a condition.
    pub(crate) fn completed(&self, slam: bool) -> Vec<&RunSummary> {
        self.runs
            .iter()
            .filter(|r| r.slam == slam && r.outcome.completed())
            .collect()
    }

    pub(crate) fn column(&self, slam: bool, f: impl Fn(&RunSummary) -> f64) -> Vec<f64> {
        self.completed(slam).into_iter().map(f).collect()
    }

    /// Seeds completed in both conditions, with (off, on) values.
    pub(crate) fn paired(&self, f: impl Fn(&RunSummary) -> f64) -> Vec<Pair> {
        let off: BTreeMap<u64, f64> = self
            .completed(false)
            .into_iter()
            .map(|r| (r.seed, f(r)))
            .collect();
        self.completed(true)
            .into_iter()
            .filter_map(|r| off.get(&r.seed).map(|o| (r.seed, *o, f(r))))
            .collect()
    }
}
