//! `rusoar slam`: the thesis's experiment, repeated over many seeds. The robot wanders a
//! room for `--duration` simulated seconds, driven by the thesis rules with the SLAM rules
//! (`on`) and without them (`off`), paired by seed, and the gap between its true and
//! believed position is measured.
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
//! They are planned, carried out and assembled into these files by [`super::plan`], the code
//! the Python sweep's Ray tasks use too. What they produce is data of [`super::results`];
//! the statistics are [`super::stats`]'s.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

use clap::parser::ValueSource;
use clap::{value_parser, Arg, ArgAction, ArgMatches, Command};

use super::compare::Method;
use super::plan::{self, Assembly, Finished, Plan, RunSpec};
pub use super::plan::{tum, v2_rules_dir};
use super::results::{condition_name, Experiment, Options, Pair, RunSummary, SlamMode};
use super::soar_loop::{self, Outcome};
use super::sonar::NoisePreset;
use super::stats::{band, fmt_band, fmt_mm, fmt_p, p_is, quantile, wilcoxon};
use super::variant::{parse_constant, Ablation, Constants, Drift, Variant};
use super::world::{World, BUILTIN_WORLDS};

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
            Arg::new("method")
                .long("method")
                .value_name("dr|thesis|v2|ekf|oracle")
                .action(ArgAction::Append)
                .value_delimiter(',')
                .value_parser(Method::NAMES)
                .help(
                    "Localisation methods, repeatable: thesis (the conditions --slam picks), dr \
                     (dead reckoning: the run without the SLAM rules), ekf (an EKF SLAM over the \
                     same odometry and Hough walls, written to ekf.md), v2 (rules/v2), oracle \
                     (rules v2 against the true map); with v2 or oracle every method runs over \
                     the same seeds into its own folder and comparison.md compares them; \
                     default thesis",
                ),
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
                .help("World file (TOML), or a built-in world: empty-room, box-partition, l-room, box-room"),
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
            Arg::new("drift")
                .long("drift")
                .value_name("stage|none")
                .value_parser(Drift::NAMES)
                .default_value("stage")
                .help(
                    "Odometry drift: Stage 2's model, or none (the control: with perfect \
                     odometry every error comes from the rules)",
                ),
        )
        .arg(
            Arg::new("variant")
                .long("variant")
                .value_name("NAME")
                .action(ArgAction::Append)
                .value_delimiter(',')
                .value_parser(|s: &str| s.parse::<Variant>())
                .help(
                    "An ablation of the SLAM rules, never the default (repeatable): h2-only, \
                     crp2-only, nearest-wall, cone, wrap, tenths (rules/README.md, section 6)",
                ),
        )
        .arg(
            Arg::new("r-tolerance")
                .long("r-tolerance")
                .value_name("MM")
                .value_parser(|s: &str| parse_constant(s, "--r-tolerance", 0.0, 100_000.0))
                .help("Override ^r-tolerance (mm; 500 in Elaborate.soar)"),
        )
        .arg(
            Arg::new("th-tolerance")
                .long("th-tolerance")
                .value_name("DEG")
                .value_parser(|s: &str| parse_constant(s, "--th-tolerance", 0.0, 360.0))
                .help("Override ^th-tolerance (degrees; 15 in Elaborate.soar)"),
        )
        .arg(
            Arg::new("overlap")
                .long("overlap")
                .value_name("PCT")
                .value_parser(|s: &str| parse_constant(s, "--overlap", 0.0, 100.0))
                .help("Override ^overlap-factor (percent of the shorter wall; 50 in Elaborate.soar)"),
        )
        .arg(
            Arg::new("rules")
                .long("rules")
                .value_name("DIR")
                .value_parser(value_parser!(PathBuf))
                .help(
                    "Folder with robotagent.soar (default: this source tree's rules/); without \
                     --method, its rules run with and without SLAM (--rules rules/v2: rules v2)",
                ),
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
    let mut opts =
        options_from(&m).map_err(|e| command().error(clap::error::ErrorKind::InvalidValue, e))?;
    opts.command_line = std::iter::once("rusoar slam")
        .chain(args.iter().map(String::as_str))
        .collect::<Vec<_>>()
        .join(" ");
    Ok(opts)
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
    // Without --method the full comparison runs, unless an option of the thesis rules' own
    // experiment (--slam, an ablation, a constant, a rules folder) asks for that experiment
    // alone.
    let classic = [
        "slam",
        "variant",
        "r-tolerance",
        "th-tolerance",
        "overlap",
        "rules",
    ]
    .iter()
    .any(|id| given(id));
    let methods: Vec<&str> = m
        .get_many::<String>("method")
        .map(|v| v.map(String::as_str).collect())
        .unwrap_or_else(|| {
            if classic {
                vec!["thesis"]
            } else {
                Method::NAMES.to_vec()
            }
        });
    let mut parsed: Vec<Method> = methods
        .iter()
        .map(|m| m.parse::<Method>())
        .collect::<Result<_, _>>()?;
    parsed.sort();
    parsed.dedup();
    let thesis = methods.contains(&"thesis");
    let ekf = methods.contains(&"ekf");
    let needs_off = ekf || methods.contains(&"dr");
    let slam = match (thesis, m.get_one::<String>("slam").map(String::as_str)) {
        (false, _) | (true, Some("off")) => SlamMode::Off,
        (true, Some("on")) if !needs_off => SlamMode::On,
        _ => SlamMode::Both,
    };
    if !thesis && given("slam") {
        return Err("--slam chooses the thesis rules' conditions; add --method thesis".into());
    }
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
    let drift = m
        .get_one::<String>("drift")
        .map_or(Ok(Drift::Stage), |d| d.parse::<Drift>())?;
    let variants: Vec<Variant> = m
        .get_many::<Variant>("variant")
        .map(|v| v.copied().collect())
        .unwrap_or_default();
    let constants = Constants {
        r_tolerance: m.get_one::<f64>("r-tolerance").copied(),
        th_tolerance: m.get_one::<f64>("th-tolerance").copied(),
        overlap: m.get_one::<f64>("overlap").copied(),
    };
    let rules_dir = m
        .get_one::<PathBuf>("rules")
        .cloned()
        .unwrap_or_else(soar_loop::default_rules_dir);
    // Rules v2 (a folder with `oracle.soar` beside `robotagent.soar`) read the heading and
    // the walls' angles in tenths of a degree (rules/v2/README.md).
    let mut variants = variants;
    if rules_dir.join("oracle.soar").is_file() && !variants.contains(&Variant::Tenths) {
        variants.push(Variant::Tenths);
    }
    let ablation = Ablation::new(drift, &variants, constants)?;
    let io_log = m.get_flag("io-log");
    if io_log && (!ablation.variants.is_empty() || constants.any()) {
        return Err(format!(
            "--io-log replays the thesis rules in the official kernel, so it cannot be combined \
             with --variant or a constant override (here: {})",
            ablation.label()
        ));
    }
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
        rules_dir,
        io_log,
        ablation,
        ekf,
        command_line: String::new(),
        oracle: false,
        methods: parsed,
        reports: true,
    })
}

/// `rusoar slam ARGS...`.
pub fn main(args: &[String]) -> ExitCode {
    ExitCode::from(status(args))
}

/// `rusoar slam ARGS...`, giving its exit status: 0, 1 when a run or the experiment failed,
/// 2 for bad options.
pub fn status(args: &[String]) -> u8 {
    let opts = match parse_options(args) {
        Ok(o) => o,
        Err(e) => {
            let _ = e.print();
            return if e.use_stderr() { 2 } else { 0 };
        }
    };
    let finished = plan::plan(&opts).and_then(|p| execute(p, opts.jobs, true));
    match finished {
        Ok(Finished::Comparison(text)) => {
            print!("{text}");
            println!("Wrote {}", opts.out.display());
            0
        }
        Ok(Finished::Experiment(exp)) => {
            print!("{}", exp.table());
            println!("Wrote {}", opts.out.display());
            if exp.runs.iter().all(|r| r.outcome.completed()) {
                0
            } else {
                eprintln!("Some runs did not complete; see summary.md.");
                1
            }
        }
        Err(e) => {
            eprintln!("error: {e}");
            1
        }
    }
}

/// Carries out `plan`'s runs on up to `jobs` threads, each run with its own agent, writing
/// each run's files as it finishes and then the reports. With `progress`, prints a line per
/// finished run to stderr.
pub fn execute(plan: Plan, jobs: usize, progress: bool) -> Result<Finished, String> {
    let assembly = Assembly::new(plan)?;
    let specs: Vec<RunSpec> = assembly.plan().specs.clone();
    let total = specs.len();
    // The long runs (SLAM on) start first and the short ones fill in after them, so that
    // no thread is left with a long run at the end.
    let mut order: Vec<usize> = (0..total).collect();
    order.sort_by_key(|&i| !specs[i].slam);
    let threads = jobs.min(total).max(1);
    if progress {
        for part in &assembly.plan().parts {
            let o = &part.opts;
            eprintln!(
                "rusoar slam: {} seed(s) × {} condition(s), {} s each, world {} ({} sonar), drift {}, rules {}, {} thread(s)",
                o.seeds,
                o.slam.conditions().len(),
                o.duration_s,
                o.world_label,
                o.world.run.noise,
                o.ablation.drift,
                o.ablation.label(),
                threads
            );
        }
    }
    let next = AtomicUsize::new(0);
    let done = AtomicUsize::new(0);
    let assembly = Mutex::new(assembly);
    std::thread::scope(|scope| {
        for _ in 0..threads {
            let worker = || {
                while let Some(&i) = order.get(next.fetch_add(1, Ordering::SeqCst)) {
                    let output = plan::run(&specs[i]);
                    let k = done.fetch_add(1, Ordering::SeqCst) + 1;
                    if progress {
                        eprintln!("{}", progress_line(k, total, &output.summary));
                    }
                    // Files are written outside the lock, so that threads do not queue
                    // behind one another's writes.
                    let folder = assembly
                        .lock()
                        .unwrap_or_else(|p| p.into_inner())
                        .folder(&output)
                        .map(Path::to_path_buf);
                    let written = folder.and_then(|dir| plan::write_files(&dir, &output.files));
                    let mut a = assembly.lock().unwrap_or_else(|p| p.into_inner());
                    if let Err(e) = written.and_then(|()| a.keep(output)) {
                        a.fail(e);
                    }
                }
            };
            let spawned = std::thread::Builder::new()
                .name("slam-run".into())
                .stack_size(plan::RUN_STACK_BYTES)
                .spawn_scoped(scope, worker);
            if let Err(e) = spawned {
                let mut a = assembly.lock().unwrap_or_else(|p| p.into_inner());
                a.fail(format!("cannot start a worker thread: {e}"));
            }
        }
    });
    assembly
        .into_inner()
        .unwrap_or_else(|p| p.into_inner())
        .finish(threads)
}

/// Runs every seed of every condition of the thesis rules' experiment, writing the per-run
/// files and the reports into `opts.out`. With `progress`, prints a line per finished run
/// to stderr.
pub fn run_experiment(opts: &Options, progress: bool) -> Result<Experiment, String> {
    let mut single = opts.clone();
    single
        .methods
        .retain(|m| !matches!(m, Method::V2 | Method::Oracle));
    match execute(plan::plan(&single)?, opts.jobs, progress)? {
        Finished::Experiment(exp) => Ok(*exp),
        Finished::Comparison(_) => Err("a single experiment was planned as a comparison".into()),
    }
}

/// Every method of `opts.methods` over the same seeds, each Soar rule set into its own
/// folder under `opts.out` (`thesis/`, `v2/`, `oracle/`; dead reckoning and the EKF come from
/// the runs without the SLAM rules, in `thesis/` or `dr/`), then `comparison.md`,
/// `comparison.csv` and `fig-compare` in `opts.out`. Returns the table it printed.
pub fn run_comparison(opts: &Options, progress: bool) -> Result<String, String> {
    if !plan::is_comparison(opts) {
        return Err("a comparison needs the v2 or oracle method".into());
    }
    match execute(plan::plan(opts)?, opts.jobs, progress)? {
        Finished::Comparison(text) => Ok(text),
        Finished::Experiment(_) => Err("a comparison was planned as a single experiment".into()),
    }
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

impl Experiment {
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
                    Some((_, _, p)) => format!(" (Wilcoxon {})", p_is(p)),
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
            "Odometry drift `{}`; SLAM rules `{}`.\n",
            opts.ablation.drift,
            opts.ablation.label()
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
                let p = wilcoxon(&diffs).map_or("–".to_string(), |(_, _, p)| fmt_p(p));
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
    fn the_quoted_command_leaves_out_the_output_folder() {
        assert_eq!(
            plan::without_out("rusoar slam --seeds 2 --out /tmp/x --quick"),
            "rusoar slam --seeds 2 --quick"
        );
        assert_eq!(plan::without_out("rusoar slam --out=/tmp/x"), "rusoar slam");
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
        assert!(o.ekf, "the default is the full comparison");
        assert_eq!(o.methods.len(), Method::NAMES.len());
        let o = parse_options(&args(&["--slam", "both"])).unwrap();
        assert!(!o.ekf && o.methods == [Method::Thesis]);
        let o = parse_options(&args(&["--quick"])).unwrap();
        assert_eq!((o.seeds, o.duration_s), (2, 60.0));
        let o = parse_options(&args(&["--method", "ekf"])).unwrap();
        assert!(o.ekf && o.slam == SlamMode::Off);
        assert_eq!(o.command_line, "rusoar slam --method ekf");
        let o = parse_options(&args(&["--method", "dr"])).unwrap();
        assert!(!o.ekf && o.slam == SlamMode::Off);
        let o = parse_options(&args(&["--method", "thesis,ekf", "--slam", "on"])).unwrap();
        assert!(o.ekf && o.slam == SlamMode::Both);
        let o = parse_options(&args(&["--quick", "--seeds", "5", "--slam", "on"])).unwrap();
        assert_eq!((o.seeds, o.duration_s, o.slam), (5, 60.0, SlamMode::On));
        let o =
            parse_options(&args(&["--noise", "realistic", "--world", "box-partition"])).unwrap();
        assert_eq!(o.world.run.noise, NoisePreset::Realistic);
        assert_eq!(o.world.name, "box-partition");
        assert!(parse_options(&args(&["--slam", "maybe"])).is_err());
        assert!(parse_options(&args(&["--method", "kalman"])).is_err());
        assert!(parse_options(&args(&["--method", "ekf", "--slam", "on"])).is_err());
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
