//! `rusoar slam`: the thesis's experiment (issue 6, item 8), repeated over many seeds. The
//! robot wanders a room for `--duration` simulated seconds, driven by the thesis rules with
//! the SLAM rules (`on`) and without them (`off`), paired by seed, and the gap between its
//! true and believed position is measured.
//!
//! Written to `--out` (default `slam-out/`):
//!
//! - `steps-<on|off>-<seed>.csv`: one row per 0.1-s step ([`soar_loop::CSV_HEADER`]);
//! - `true-<on|off>-<seed>.tum`, `believed-<on|off>-<seed>.tum`: trajectories in TUM format
//!   (`t x y z qx qy qz qw`, metres), for the usual trajectory tools;
//! - `map-<on|off>-<seed>.csv`: the walls in the agent's memory at the end;
//! - `runs.csv`: one row per run with its summary numbers;
//! - `corrections-on-<seed>.csv`: every `setOdometry` of a SLAM-on run, with the position and
//!   heading error just before and after it;
//! - `summary.md`: per condition the median and 10–90 % band of the position error at 60, 300
//!   and 600 s, RMSE, maximum and final error, heading error, walls in memory, corrections,
//!   the map against the true walls, and the paired comparison (seeds improved, Wilcoxon
//!   signed-rank p-value);
//! - `io-<on|off>-<seed>.log` with `--io-log`: the run's input-link and output-link traffic
//!   ([`super::io_log`]), which `scripts/slam_oracle.py` replays in the official kernel;
//! - `fig-*.svg` and `fig-*.png`, and `report.md` putting numbers and figures together (see
//!   [`super::report`]).
//!
//! Runs go in parallel over `--jobs` threads (default: all cores), each with its own agent.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::Instant;

use clap::parser::ValueSource;
use clap::{value_parser, Arg, ArgAction, ArgMatches, Command};

use super::geom::Point;
use super::pipeline::{Extraction, Wall};
use super::soar_loop::{self, Correction, LoopConfig, MemoryWall, Outcome, RunResult, StepRecord};
use super::sonar::NoisePreset;
use super::world::{World, BUILTIN_WORLDS};

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
}

fn command() -> Command {
    Command::new("rusoar slam")
        .about(
            "Soar-SLAM experiment: the thesis rules drive a simulated Pioneer around a room, \
             with and without the SLAM rules, over many seeds",
        )
        .arg(
            Arg::new("seeds")
                .long("seeds")
                .value_name("N")
                .value_parser(value_parser!(u64).range(1..=100_000))
                .default_value("20")
                .help("Number of seeds (runs per condition)"),
        )
        .arg(
            Arg::new("first-seed")
                .long("first-seed")
                .value_name("S")
                .value_parser(value_parser!(u64))
                .default_value("1")
                .help("First seed; the seeds are S, S+1, ..."),
        )
        .arg(
            Arg::new("duration")
                .long("duration")
                .value_name("SECONDS")
                .value_parser(parse_duration)
                .default_value("600")
                .help("Simulated seconds per run"),
        )
        .arg(
            Arg::new("slam")
                .long("slam")
                .value_name("on|off|both")
                .value_parser(["on", "off", "both"])
                .default_value("both")
                .help("Run with the SLAM rules, without them, or both (paired by seed)"),
        )
        .arg(
            Arg::new("noise")
                .long("noise")
                .value_name("PRESET")
                .value_parser(["ideal", "realistic", "pessimistic"])
                .help("Sonar noise preset (default: the world's, `ideal` for the built-ins)"),
        )
        .arg(
            Arg::new("world")
                .long("world")
                .value_name("FILE")
                .default_value("empty-room")
                .help("World file (TOML), or a built-in world: empty-room, box-partition"),
        )
        .arg(
            Arg::new("out")
                .long("out")
                .value_name("DIR")
                .value_parser(value_parser!(PathBuf))
                .default_value("slam-out")
                .help("Output folder"),
        )
        .arg(
            Arg::new("quick")
                .long("quick")
                .action(ArgAction::SetTrue)
                .help("A small run for a first look: 2 seeds × 60 s (unless --seeds/--duration say otherwise)"),
        )
        .arg(
            Arg::new("jobs")
                .long("jobs")
                .short('j')
                .value_name("N")
                .value_parser(value_parser!(u64).range(1..=1024))
                .help("Runs in parallel (default: the number of cores)"),
        )
        .arg(
            Arg::new("io-log")
                .long("io-log")
                .action(ArgAction::SetTrue)
                .help(
                    "Also write io-<on|off>-<seed>.log: each run's input-link and output-link \
                     traffic, for replaying it in the official kernel (scripts/slam_oracle.py)",
                ),
        )
        .arg(
            Arg::new("rules")
                .long("rules")
                .value_name("DIR")
                .value_parser(value_parser!(PathBuf))
                .help("Folder with robotagent.soar (default: this source tree's rules/)"),
        )
}

fn parse_duration(s: &str) -> Result<f64, String> {
    let v: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("`{s}` is not a number of seconds"))?;
    if v.is_finite() && v > 0.0 && v <= 1.0e6 {
        Ok(v)
    } else {
        Err(format!(
            "the duration must be between 0 and 1e6 seconds, not {s}"
        ))
    }
}

/// Reads the options from the arguments after `slam`.
pub fn parse_options(args: &[String]) -> Result<Options, clap::Error> {
    let m = command().try_get_matches_from(
        std::iter::once("rusoar slam".to_string()).chain(args.iter().cloned()),
    )?;
    options_from(&m).map_err(|e| command().error(clap::error::ErrorKind::InvalidValue, e))
}

fn options_from(m: &ArgMatches) -> Result<Options, String> {
    let quick = m.get_flag("quick");
    let given = |id: &str| m.value_source(id) == Some(ValueSource::CommandLine);
    let mut seeds = *m.get_one::<u64>("seeds").unwrap_or(&20);
    let mut duration_s = *m.get_one::<f64>("duration").unwrap_or(&600.0);
    if quick {
        if !given("seeds") {
            seeds = 2;
        }
        if !given("duration") {
            duration_s = 60.0;
        }
    }
    let slam = match m.get_one::<String>("slam").map(String::as_str) {
        Some("on") => SlamMode::On,
        Some("off") => SlamMode::Off,
        _ => SlamMode::Both,
    };
    let world_label = m
        .get_one::<String>("world")
        .cloned()
        .unwrap_or_else(|| "empty-room".into());
    let mut world = match World::builtin(&world_label) {
        Some(w) => w,
        None => {
            let path = Path::new(&world_label);
            if !path.exists() && !world_label.contains(['/', '.']) {
                return Err(format!(
                    "no world file `{world_label}` and no built-in world of that name (built-ins: {})",
                    BUILTIN_WORLDS.join(", ")
                ));
            }
            World::load(path).map_err(|e| e.to_string())?
        }
    };
    if let Some(n) = m.get_one::<String>("noise") {
        world.run.noise = n.parse::<NoisePreset>().map_err(|e| e.to_string())?;
    }
    let jobs = m
        .get_one::<u64>("jobs")
        .map(|j| *j as usize)
        .unwrap_or_else(|| {
            std::thread::available_parallelism()
                .map(|n| n.get())
                .unwrap_or(1)
        });
    Ok(Options {
        seeds,
        first_seed: *m.get_one::<u64>("first-seed").unwrap_or(&1),
        duration_s,
        slam,
        world,
        world_label,
        out: m
            .get_one::<PathBuf>("out")
            .cloned()
            .unwrap_or_else(|| PathBuf::from("slam-out")),
        jobs: jobs.max(1),
        rules_dir: m
            .get_one::<PathBuf>("rules")
            .cloned()
            .unwrap_or_else(soar_loop::default_rules_dir),
        io_log: m.get_flag("io-log"),
    })
}

/// `rusoar slam ARGS...`.
pub fn main(args: &[String]) -> ExitCode {
    let opts = match parse_options(args) {
        Ok(o) => o,
        Err(e) => {
            let _ = e.print();
            return if e.use_stderr() {
                ExitCode::from(2)
            } else {
                ExitCode::SUCCESS
            };
        }
    };
    match run_experiment(&opts, true) {
        Ok(exp) => {
            print!("{}", exp.table());
            println!("Wrote {}", opts.out.display());
            if exp.runs.iter().all(|r| r.outcome.completed()) {
                ExitCode::SUCCESS
            } else {
                eprintln!("Some runs did not complete; see summary.md.");
                ExitCode::FAILURE
            }
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// The numbers of one run, kept after its steps are written out.
#[derive(Debug, Clone)]
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
}

/// Runs every seed of every condition, writing the per-run files and `summary.md` into
/// `opts.out`. With `progress`, prints a line per finished run to stderr.
pub fn run_experiment(opts: &Options, progress: bool) -> Result<Experiment, String> {
    std::fs::create_dir_all(&opts.out)
        .map_err(|e| format!("cannot create {}: {e}", opts.out.display()))?;
    let jobs: Vec<(u64, bool)> = (opts.first_seed..opts.first_seed + opts.seeds)
        .flat_map(|seed| opts.slam.conditions().iter().map(move |&s| (seed, s)))
        .collect();
    let total = jobs.len();
    // The long runs (SLAM on) start first and the short ones fill in after them, so that
    // no thread is left with a long run at the end; results keep the jobs' order.
    let mut order: Vec<usize> = (0..total).collect();
    order.sort_by_key(|&i| !jobs[i].1);
    let next = AtomicUsize::new(0);
    let done = AtomicUsize::new(0);
    let results: Mutex<Vec<Option<RunSummary>>> = Mutex::new(vec![None; total]);
    let write_error: Mutex<Option<String>> = Mutex::new(None);
    let started = Instant::now();
    let threads = opts.jobs.min(total).max(1);
    if progress {
        eprintln!(
            "rusoar slam: {} seed(s) × {} condition(s), {} s each, world {} ({} sonar), {} thread(s)",
            opts.seeds,
            opts.slam.conditions().len(),
            opts.duration_s,
            opts.world_label,
            opts.world.run.noise,
            threads
        );
    }
    std::thread::scope(|scope| {
        for _ in 0..threads {
            let worker = || {
                while let Some(&i) = order.get(next.fetch_add(1, Ordering::SeqCst)) {
                    let (seed, slam) = jobs[i];
                    let mut cfg = LoopConfig::new(opts.world.clone(), seed, slam, opts.duration_s);
                    cfg.rules_dir = opts.rules_dir.clone();
                    cfg.io_log = opts.io_log;
                    if seed == opts.first_seed {
                        let n = cfg.steps();
                        cfg.snapshot_steps = (1..=4).map(|q| (n * q / 4).max(1)).collect();
                        cfg.sample_extraction_at = Some(sample_step(&cfg));
                    }
                    let result = soar_loop::run(&cfg);
                    let summary = RunSummary::of(&result, opts.world.run.dt);
                    if let Err(e) = write_run(&opts.out, &result) {
                        let mut w = write_error.lock().unwrap_or_else(|p| p.into_inner());
                        w.get_or_insert(e);
                    }
                    let k = done.fetch_add(1, Ordering::SeqCst) + 1;
                    if progress {
                        eprintln!("{}", progress_line(k, total, &summary));
                    }
                    let mut r = results.lock().unwrap_or_else(|p| p.into_inner());
                    r[i] = Some(summary);
                }
            };
            let spawned = std::thread::Builder::new()
                .name("slam-run".into())
                .stack_size(64 << 20)
                .spawn_scoped(scope, worker);
            if let Err(e) = spawned {
                let mut w = write_error.lock().unwrap_or_else(|p| p.into_inner());
                w.get_or_insert(format!("cannot start a worker thread: {e}"));
            }
        }
    });
    if let Some(e) = write_error.into_inner().unwrap_or_else(|p| p.into_inner()) {
        return Err(e);
    }
    let runs: Vec<RunSummary> = results
        .into_inner()
        .unwrap_or_else(|p| p.into_inner())
        .into_iter()
        .flatten()
        .collect();
    if runs.len() != total {
        return Err(format!("only {} of {total} runs finished", runs.len()));
    }
    let checkpoints: Vec<f64> = [60.0, 300.0, 600.0]
        .into_iter()
        .filter(|t| *t <= opts.duration_s + 1e-9)
        .chain((![60.0, 300.0, 600.0].contains(&opts.duration_s)).then_some(opts.duration_s))
        .collect();
    let exp = Experiment {
        runs,
        duration_s: opts.duration_s,
        checkpoints,
        total_wall_s: started.elapsed().as_secs_f64(),
        jobs: threads,
        world_label: opts.world_label.clone(),
        noise: opts.world.run.noise,
        world: opts.world.clone(),
        example_seed: opts.first_seed,
    };
    let write = |name: &str, text: String| -> Result<(), String> {
        let p = opts.out.join(name);
        std::fs::write(&p, text).map_err(|e| format!("cannot write {}: {e}", p.display()))
    };
    write("runs.csv", exp.runs_csv())?;
    write("summary.md", exp.summary_md(opts))?;
    super::report::write_report(&exp, opts)?;
    Ok(exp)
}

/// The step from which the example run keeps one pipeline output for the Hough figure: 30 s in,
/// or half-way through a shorter run (a full scan window has been seen by then).
fn sample_step(cfg: &LoopConfig) -> u64 {
    let dt = cfg.world.run.dt;
    let at_30s = if dt > 0.0 {
        (30.0 / dt).round() as u64
    } else {
        1
    };
    at_30s.min(cfg.steps() / 2).max(1)
}

fn progress_line(k: usize, total: usize, s: &RunSummary) -> String {
    let status = match &s.outcome {
        Outcome::Completed => String::new(),
        o => format!(" — {o}"),
    };
    format!(
        "[{k:>3}/{total}] seed {:>3} SLAM {:<3}: {:>5.0} s simulated in {:.2} s wall; final error {:.0} mm, {} walls, {} corrections{status}",
        s.seed,
        condition_name(s.slam),
        s.sim_time_s,
        s.wall_time_s,
        s.final_mm,
        s.final_walls,
        s.corrections
    )
}

/// Writes a run's step CSV, its TUM trajectories and its final map.
fn write_run(out: &Path, r: &RunResult) -> Result<(), String> {
    let tag = format!("{}-{}", condition_name(r.slam), r.seed);
    let write = |name: String, text: String| -> Result<(), String> {
        let p = out.join(name);
        std::fs::write(&p, text).map_err(|e| format!("cannot write {}: {e}", p.display()))
    };
    write(format!("steps-{tag}.csv"), r.csv())?;
    write(
        format!("true-{tag}.tum"),
        tum(r.steps.iter().map(|s| (s.time_s, s.true_pose))),
    )?;
    write(
        format!("believed-{tag}.tum"),
        tum(r.steps.iter().map(|s| (s.time_s, s.believed))),
    )?;
    let mut map =
        String::from("r_mm,th_deg,start_x_mm,start_y_mm,end_x_mm,end_y_mm,length_mm,time\n");
    for w in &r.memory_walls {
        let _ = writeln!(
            map,
            "{},{},{},{},{},{},{},{}",
            w.r, w.th, w.start.0, w.start.1, w.end.0, w.end.1, w.length, w.time
        );
    }
    write(format!("map-{tag}.csv"), map)?;
    if !r.io_log.is_empty() {
        let mut log = r.io_log.join("\n");
        log.push('\n');
        write(format!("io-{tag}.log"), log)?;
    }
    if r.slam {
        let mut c = String::from(soar_loop::CORRECTIONS_HEADER);
        c.push('\n');
        for k in &r.stats.corrections {
            c.push_str(&k.csv_row());
            c.push('\n');
        }
        write(format!("corrections-{tag}.csv"), c)?;
    }
    Ok(())
}

/// A trajectory in TUM format: `t x y z qx qy qz qw`, metres, a yaw-only quaternion.
pub fn tum(poses: impl Iterator<Item = (f64, super::geom::Pose)>) -> String {
    let mut s = String::from("# t x y z qx qy qz qw\n");
    for (t, p) in poses {
        let (sz, cz) = (p.th / 2.0).sin_cos();
        let _ = writeln!(s, "{t:.1} {:.4} {:.4} 0 0 0 {sz:.6} {cz:.6}", p.x, p.y);
    }
    s
}

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

    /// The short table printed at the end.
    pub fn table(&self) -> String {
        let mut s = String::new();
        let cps: Vec<String> = self
            .checkpoints
            .iter()
            .map(|t| format!("err@{t:.0}s"))
            .collect();
        let _ = writeln!(
            s,
            "\nposition error, mm: median [10–90 %] over seeds ({} world, {} sonar)",
            self.world_label, self.noise
        );
        let _ = write!(s, "{:<5} {:>5}", "SLAM", "runs");
        for c in &cps {
            let _ = write!(s, " {c:>18}");
        }
        let _ = writeln!(
            s,
            " {:>18} {:>7} {:>6} {:>6} {:>8}",
            "RMSE", "final", "walls", "corr.", "wall s"
        );
        for slam in self.conditions() {
            let runs = self.completed(slam);
            let all = self.runs.iter().filter(|r| r.slam == slam).count();
            let _ = write!(
                s,
                "{:<5} {:>5}",
                condition_name(slam),
                format!("{}/{}", runs.len(), all)
            );
            for &t in &self.checkpoints {
                let v: Vec<f64> = runs.iter().filter_map(|r| r.err_at(t)).collect();
                let _ = write!(s, " {:>18}", fmt_band(&v));
            }
            let _ = writeln!(
                s,
                " {:>18} {:>7} {:>6} {:>6} {:>8.2}",
                fmt_band(&self.column(slam, |r| r.rmse_mm)),
                fmt_mm(quantile(&self.column(slam, |r| r.final_mm), 0.5)),
                fmt_mm(quantile(&self.column(slam, |r| r.final_walls as f64), 0.5)),
                fmt_mm(quantile(&self.column(slam, |r| r.corrections as f64), 0.5)),
                quantile(&self.column(slam, |r| r.wall_time_s), 0.5),
            );
        }
        let pairs = self.paired(|r| r.final_mm);
        if !pairs.is_empty() {
            let better = pairs.iter().filter(|(_, off, on)| on < off).count();
            let _ = writeln!(
                s,
                "SLAM on has the lower final error in {better} of {} seeds{}",
                pairs.len(),
                match wilcoxon(&pairs.iter().map(|(_, o, n)| n - o).collect::<Vec<_>>()) {
                    Some((_, _, p)) => format!(" (Wilcoxon p = {p:.3})"),
                    None => String::new(),
                }
            );
        }
        let walls: Vec<f64> = self.runs.iter().map(|r| r.wall_time_s).collect();
        let _ = writeln!(
            s,
            "wall time per run: median {:.2} s, max {:.2} s; total {:.1} s on {} thread(s)",
            quantile(&walls, 0.5),
            walls.iter().copied().fold(0.0, f64::max),
            self.total_wall_s,
            self.jobs
        );
        s
    }

    /// `runs.csv`: one row per run.
    pub fn runs_csv(&self) -> String {
        let mut s = String::from(
            "slam,seed,outcome,sim_time_s,wall_time_s,rmse_mm,max_mm,final_mm,final_heading_deg,\
             rmse_heading_deg,final_walls,max_walls,corrections,decisions,firings,\
             walls_extracted,walls_copied,walls_expired,final_input_walls,messages\n",
        );
        for r in &self.runs {
            let _ = writeln!(
                s,
                "{},{},{},{:.1},{:.3},{:.1},{:.1},{:.1},{:.3},{:.3},{},{},{},{},{},{},{},{},{},{}",
                condition_name(r.slam),
                r.seed,
                match r.outcome {
                    Outcome::Completed => "completed",
                    Outcome::Halted { .. } => "halted",
                    Outcome::Failed(_) => "failed",
                },
                r.sim_time_s,
                r.wall_time_s,
                r.rmse_mm,
                r.max_mm,
                r.final_mm,
                r.final_heading_deg,
                r.rmse_heading_deg,
                r.final_walls,
                r.max_walls,
                r.corrections,
                r.decisions,
                r.firings,
                r.walls_extracted,
                r.walls_copied,
                r.walls_expired,
                r.final_input_walls,
                r.message_count
            );
        }
        s
    }

    /// `summary.md`.
    pub fn summary_md(&self, opts: &Options) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "# Soar-SLAM experiment\n");
        let _ = writeln!(
            s,
            "World `{}` ({} sonar), {} seed(s) from {}, {} simulated seconds per run, time step \
             {} s. SLAM `on` loads `rules/robotagent.soar` as it is; `off` leaves out its line \
             `source slam.soar`. Paired by seed: the same seed gives the same odometry biases, \
             sonar noise and start in both conditions. {}\n",
            self.world_label,
            self.noise,
            opts.seeds,
            opts.first_seed,
            self.duration_s,
            opts.world.run.dt,
            self.true_paths_note().unwrap_or_default()
        );
        let _ = writeln!(
            s,
            "Numbers are medians over seeds with the 10–90 % band in brackets; errors in mm, \
             headings in degrees.\n"
        );
        let _ = writeln!(s, "## Position error\n");
        let _ = write!(s, "| SLAM | runs |");
        for t in &self.checkpoints {
            let _ = write!(s, " at {t:.0} s |");
        }
        let _ = writeln!(s, " RMSE | max | final | final heading |");
        let _ = write!(s, "|---|---|");
        for _ in &self.checkpoints {
            let _ = write!(s, "---|");
        }
        let _ = writeln!(s, "---|---|---|---|");
        for slam in self.conditions() {
            let runs = self.completed(slam);
            let all = self.runs.iter().filter(|r| r.slam == slam).count();
            let _ = write!(s, "| {} | {}/{} |", condition_name(slam), runs.len(), all);
            for &t in &self.checkpoints {
                let v: Vec<f64> = runs.iter().filter_map(|r| r.err_at(t)).collect();
                let _ = write!(s, " {} |", fmt_band(&v));
            }
            let heading = self.column(slam, |r| r.final_heading_deg);
            let (hm, hlo, hhi) = band(&heading);
            let _ = writeln!(
                s,
                " {} | {} | {} | {hm:.1} [{hlo:.1}–{hhi:.1}] |",
                fmt_band(&self.column(slam, |r| r.rmse_mm)),
                fmt_band(&self.column(slam, |r| r.max_mm)),
                fmt_band(&self.column(slam, |r| r.final_mm)),
            );
        }
        let _ = writeln!(s, "\n## Map and agent\n");
        let _ = writeln!(
            s,
            "| SLAM | walls in memory at the end | max walls | corrections (setOdometry) | walls extracted | copied | expired uncopied | left on the input-link | decisions | firings | wall time per run, s |"
        );
        let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|---|");
        for slam in self.conditions() {
            let c = |f: &dyn Fn(&RunSummary) -> f64| fmt_band(&self.column(slam, f));
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {:.2} [{:.2}–{:.2}] |",
                condition_name(slam),
                c(&|r| r.final_walls as f64),
                c(&|r| r.max_walls as f64),
                c(&|r| r.corrections as f64),
                c(&|r| r.walls_extracted as f64),
                c(&|r| r.walls_copied as f64),
                c(&|r| r.walls_expired as f64),
                c(&|r| r.final_input_walls as f64),
                c(&|r| r.decisions as f64),
                c(&|r| r.firings as f64),
                quantile(&self.column(slam, |r| r.wall_time_s), 0.5),
                quantile(&self.column(slam, |r| r.wall_time_s), 0.1),
                quantile(&self.column(slam, |r| r.wall_time_s), 0.9),
            );
        }
        let _ = writeln!(s, "\n### The map against the true walls\n");
        s.push_str(&super::report::map_table_md(self));
        let _ = writeln!(s, "\nOperator selections, median per run:\n");
        let mut names: Vec<&String> = self.runs.iter().flat_map(|r| r.operators.keys()).collect();
        names.sort();
        names.dedup();
        let _ = write!(s, "| SLAM |");
        for n in &names {
            let _ = write!(s, " {n} |");
        }
        let _ = writeln!(s);
        let _ = write!(s, "|---|");
        for _ in &names {
            let _ = write!(s, "---|");
        }
        let _ = writeln!(s);
        for slam in self.conditions() {
            let _ = write!(s, "| {} |", condition_name(slam));
            for n in &names {
                let v = self.column(slam, |r| r.operators.get(*n).copied().unwrap_or(0) as f64);
                let _ = write!(s, " {} |", fmt_mm(quantile(&v, 0.5)));
            }
            let _ = writeln!(s);
        }
        let pairs_final = self.paired(|r| r.final_mm);
        if !pairs_final.is_empty() {
            let _ = writeln!(s, "\n## Paired comparison (SLAM on − off, same seed)\n");
            let _ = writeln!(
                s,
                "| measure | seeds improved | median difference | Wilcoxon signed-rank p (two-sided) |"
            );
            let _ = writeln!(s, "|---|---|---|---|");
            let mut measures: Vec<(String, Vec<Pair>)> = Vec::new();
            for &t in &self.checkpoints {
                measures.push((
                    format!("error at {t:.0} s"),
                    self.paired(|r| r.err_at(t).unwrap_or(f64::NAN)),
                ));
            }
            measures.push(("RMSE".into(), self.paired(|r| r.rmse_mm)));
            measures.push(("max error".into(), self.paired(|r| r.max_mm)));
            measures.push(("final error".into(), pairs_final.clone()));
            for (name, pairs) in &measures {
                let diffs: Vec<f64> = pairs.iter().map(|(_, off, on)| on - off).collect();
                let better = diffs.iter().filter(|d| **d < 0.0).count();
                let p = wilcoxon(&diffs).map_or("–".to_string(), |(_, _, p)| format!("{p:.4}"));
                let _ = writeln!(
                    s,
                    "| {name} | {better} of {} | {} mm | {p} |",
                    pairs.len(),
                    fmt_mm(quantile(&diffs, 0.5))
                );
            }
        }
        let _ = writeln!(s, "\n## Runs\n");
        let _ = writeln!(
            s,
            "| seed | SLAM | outcome | final error | RMSE | max | walls | corrections | wall time, s |"
        );
        let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|");
        let mut runs: Vec<&RunSummary> = self.runs.iter().collect();
        runs.sort_by_key(|r| (r.seed, r.slam));
        for r in runs {
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {} | {} | {} | {:.2} |",
                r.seed,
                condition_name(r.slam),
                match &r.outcome {
                    Outcome::Completed => "completed".to_string(),
                    o => o.to_string().replace('|', "/"),
                },
                fmt_mm(r.final_mm),
                fmt_mm(r.rmse_mm),
                fmt_mm(r.max_mm),
                r.final_walls,
                r.corrections,
                r.wall_time_s
            );
        }
        let noisy: Vec<&RunSummary> = self
            .runs
            .iter()
            .filter(|r| r.message_count > 0 || !r.bad_commands.is_empty())
            .collect();
        if !noisy.is_empty() {
            let _ = writeln!(s, "\n## Messages from the agent\n");
            for r in noisy {
                let _ = writeln!(
                    s,
                    "- seed {} SLAM {}: {} message line(s){}{}",
                    r.seed,
                    condition_name(r.slam),
                    r.message_count,
                    r.messages
                        .first()
                        .map_or(String::new(), |m| format!(", first: `{m}`")),
                    if r.bad_commands.is_empty() {
                        String::new()
                    } else {
                        format!("; bad commands: {}", r.bad_commands.join("; "))
                    }
                );
            }
        }
        let walls: Vec<f64> = self.runs.iter().map(|r| r.wall_time_s).collect();
        let _ = writeln!(
            s,
            "\nWall time: {:.1} s in total on {} thread(s); per run median {:.2} s, max {:.2} s.",
            self.total_wall_s,
            self.jobs,
            quantile(&walls, 0.5),
            walls.iter().copied().fold(0.0, f64::max)
        );
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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

    #[test]
    fn tum_lines_have_a_yaw_quaternion() {
        use super::super::geom::Pose;
        let t = tum([(0.1, Pose::new(1.0, -2.0, std::f64::consts::PI))].into_iter());
        assert_eq!(
            t.lines().nth(1),
            Some("0.1 1.0000 -2.0000 0 0 0 1.000000 0.000000")
        );
    }

    #[test]
    fn options_parse_with_quick_defaults() {
        let args = |a: &[&str]| -> Vec<String> { a.iter().map(|s| s.to_string()).collect() };
        let o = parse_options(&args(&[])).unwrap();
        assert_eq!((o.seeds, o.duration_s, o.slam), (20, 600.0, SlamMode::Both));
        assert_eq!(o.out, PathBuf::from("slam-out"));
        let o = parse_options(&args(&["--quick"])).unwrap();
        assert_eq!((o.seeds, o.duration_s), (2, 60.0));
        let o = parse_options(&args(&["--quick", "--seeds", "5", "--slam", "on"])).unwrap();
        assert_eq!((o.seeds, o.duration_s, o.slam), (5, 60.0, SlamMode::On));
        let o =
            parse_options(&args(&["--noise", "realistic", "--world", "box-partition"])).unwrap();
        assert_eq!(o.world.run.noise, NoisePreset::Realistic);
        assert_eq!(o.world.name, "box-partition");
        assert!(parse_options(&args(&["--slam", "maybe"])).is_err());
        assert!(parse_options(&args(&["--duration", "-3"])).is_err());
        assert!(parse_options(&args(&["--world", "nowhere"])).is_err());
        let e = parse_options(&args(&["--world", "/nonexistent/w.toml"])).unwrap_err();
        assert!(e.to_string().contains("w.toml"), "{e}");
    }

    #[test]
    fn a_tiny_experiment_writes_its_files() {
        let dir = std::env::temp_dir().join(format!("rusoar-slam-test-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let mut opts = parse_options(&[
            "--seeds".into(),
            "2".into(),
            "--duration".into(),
            "5".into(),
            "--out".into(),
            dir.display().to_string(),
        ])
        .unwrap();
        opts.jobs = 2;
        let exp = run_experiment(&opts, false).unwrap();
        assert_eq!(exp.runs.len(), 4);
        assert!(exp
            .runs
            .iter()
            .all(|r| r.outcome.completed() && r.steps == 50));
        for f in [
            "steps-on-1.csv",
            "steps-off-2.csv",
            "true-on-1.tum",
            "believed-off-1.tum",
            "map-on-2.csv",
            "runs.csv",
            "summary.md",
        ] {
            assert!(dir.join(f).is_file(), "{f} missing");
        }
        let steps = std::fs::read_to_string(dir.join("steps-on-1.csv")).unwrap();
        assert_eq!(steps.lines().count(), 51);
        assert!(steps.starts_with(soar_loop::CSV_HEADER));
        let summary = std::fs::read_to_string(dir.join("summary.md")).unwrap();
        assert!(summary.contains("Paired comparison") && summary.contains("at 5 s"));
        assert_eq!(exp.checkpoints, vec![5.0]);
        let _ = std::fs::remove_dir_all(&dir);
    }
}
