//! `rusoar slam` as independent runs. [`plan`] turns the options into a [`Plan`]: the
//! experiments to make (one, or one per method of a comparison) and a [`RunSpec`] per run,
//! holding everything the run needs. [`run`] carries one out, anywhere: on one of
//! `rusoar slam`'s threads, or in a Ray task of the Python sweep on another machine. An
//! [`Assembly`] takes the [`RunOutput`]s in any order, writes each run's files as it comes
//! in, and once all are in writes the reports. Both ways of running go through these three
//! steps, so the same runs give the same files.
//!
//! Specs and outputs cross process boundaries as bytes ([`RunSpec::to_bytes`],
//! [`RunOutput::to_bytes`]) in postcard's binary form, which keeps every `f64` bit for bit,
//! NaN included: a report assembled from outputs that travelled is the one assembled from
//! outputs that did not.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use serde::{Deserialize, Serialize};

use super::compare::{self, Method, Series};
use super::ekf;
use super::results::{condition_name, Experiment, Options, RunSummary, SlamMode};
use super::soar_loop::{self, LoopConfig, RunResult};
use super::variant::{Ablation, Constants, Variant};
use super::world::World;

/// The stack a run needs: the kernel's matcher and decision procedure recurse deeply on the
/// SLAM rules' substates, more than a default thread (or Python's main thread) has.
pub const RUN_STACK_BYTES: usize = 64 << 20;

/// One run, with all it needs to be carried out in another process: the world itself (not
/// its file), the rules folder as an absolute path (it must exist where the run is carried
/// out), the seed and the condition.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunSpec {
    /// Its place in [`Plan::specs`].
    pub index: usize,
    /// The experiment of [`Plan::parts`] it belongs to.
    pub part: usize,
    pub seed: u64,
    /// With the SLAM rules (`on`) or without (`off`).
    pub slam: bool,
    pub duration_s: f64,
    pub world: World,
    pub rules_dir: PathBuf,
    pub io_log: bool,
    pub ablation: Ablation,
    pub oracle: bool,
    /// The example run (the first seed): it keeps map snapshots and one pipeline output
    /// for the report's figures.
    pub example: bool,
    /// Replay the EKF over this run (runs without the SLAM rules of `--method ekf`).
    pub ekf: bool,
}

/// What one run gives back: its numbers, the files it writes into its experiment's folder,
/// and its EKF replay.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct RunOutput {
    pub index: usize,
    pub part: usize,
    pub summary: RunSummary,
    /// (file name, contents): step CSV, trajectories, map, corrections, I/O log, EKF files.
    pub files: Vec<(String, String)>,
    pub ekf: Option<ekf::EkfRun>,
    /// Why the EKF replay failed, if it did (the experiment then fails).
    pub error: Option<String>,
}

impl RunSpec {
    /// The description as bytes, for another process.
    pub fn to_bytes(&self) -> Vec<u8> {
        // Serialising plain data into a growable buffer cannot fail.
        postcard::to_stdvec(self).unwrap_or_default()
    }

    /// A description from [`RunSpec::to_bytes`]; an error for any other bytes.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, String> {
        postcard::from_bytes(bytes)
            .map_err(|e| format!("not a run description of rusoar slam: {e}"))
    }
}

impl RunOutput {
    /// The result as bytes, for the process that assembles the experiment.
    pub fn to_bytes(&self) -> Vec<u8> {
        postcard::to_stdvec(self).unwrap_or_default()
    }

    /// A result from [`RunOutput::to_bytes`]; an error for any other bytes.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, String> {
        postcard::from_bytes(bytes).map_err(|e| format!("not a run result of rusoar slam: {e}"))
    }
}

/// What a part of the plan is: the whole experiment, or one method's folder of a comparison.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PartKind {
    /// The thesis rules' experiment alone (no v2 or oracle method): its files and reports
    /// go straight into `--out`.
    Single,
    /// The thesis rules' runs of a comparison (`thesis/`, or `dr/` without the thesis
    /// method), which give dead reckoning, the thesis rules and the EKF.
    Thesis,
    /// Rules v2 (`v2/`) or rules v2 against the true map (`oracle/`).
    Rules(Method),
}

/// One experiment of a plan: its options (output folder, conditions, rules) and its runs.
#[derive(Debug, Clone)]
pub struct Part {
    pub kind: PartKind,
    pub opts: Options,
    /// Its runs' places in [`Plan::specs`].
    pub specs: std::ops::Range<usize>,
}

/// Everything `rusoar slam` with these options runs.
#[derive(Debug, Clone)]
pub struct Plan {
    /// The options as given; in a comparison, with the command line quoted without `--out`.
    pub opts: Options,
    pub parts: Vec<Part>,
    pub specs: Vec<RunSpec>,
}

impl Plan {
    /// Whether the plan is a comparison of methods (`comparison.md` and a folder per method).
    pub fn is_comparison(&self) -> bool {
        self.parts.iter().any(|p| p.kind != PartKind::Single)
    }
}

/// Whether `opts` ask for a comparison of methods: with rules v2 or the oracle, each method
/// gets a folder of its own.
pub fn is_comparison(opts: &Options) -> bool {
    opts.methods
        .iter()
        .any(|m| matches!(m, Method::V2 | Method::Oracle))
}

/// The runs of `opts`: every seed of every condition of every experiment.
pub fn plan(opts: &Options) -> Result<Plan, String> {
    let mut opts = opts.clone();
    // A relative rules folder would be read from wherever a run is carried out; the
    // absolute one is the folder meant here.
    opts.rules_dir = std::path::absolute(&opts.rules_dir)
        .map_err(|e| format!("cannot resolve {}: {e}", opts.rules_dir.display()))?;
    let mut parts = Vec::new();
    if is_comparison(&opts) {
        // The reports quote the command without its output folder, so that they do not
        // depend on where they were written.
        opts.command_line = without_out(&opts.command_line);
        let has = |m: Method| opts.methods.contains(&m);
        if has(Method::Dr) || has(Method::Thesis) || has(Method::Ekf) {
            let mut o = opts.clone();
            o.slam = if has(Method::Thesis) {
                SlamMode::Both
            } else {
                SlamMode::Off
            };
            o.out = opts
                .out
                .join(if has(Method::Thesis) { "thesis" } else { "dr" });
            o.oracle = false;
            o.reports = false;
            parts.push((PartKind::Thesis, o));
        }
        for (method, oracle) in [(Method::V2, false), (Method::Oracle, true)] {
            if !has(method) {
                continue;
            }
            let mut o = opts.clone();
            o.slam = SlamMode::On;
            o.ekf = false;
            o.io_log = false;
            o.oracle = oracle;
            o.rules_dir = v2_rules_dir(&opts.rules_dir);
            o.ablation = Ablation::new(
                opts.ablation.drift,
                &[Variant::Tenths],
                Constants::default(),
            )?;
            o.out = opts.out.join(method.name());
            o.reports = false;
            parts.push((PartKind::Rules(method), o));
        }
    } else {
        parts.push((PartKind::Single, opts.clone()));
    }
    let mut specs = Vec::new();
    let parts = parts
        .into_iter()
        .enumerate()
        .map(|(p, (kind, o))| {
            let first = specs.len();
            for seed in o.first_seed..o.first_seed + o.seeds {
                for &slam in o.slam.conditions() {
                    specs.push(RunSpec {
                        index: specs.len(),
                        part: p,
                        seed,
                        slam,
                        duration_s: o.duration_s,
                        world: o.world.clone(),
                        rules_dir: o.rules_dir.clone(),
                        io_log: o.io_log,
                        ablation: o.ablation.clone(),
                        oracle: o.oracle,
                        example: seed == o.first_seed,
                        ekf: o.ekf && !slam,
                    });
                }
            }
            Part {
                kind,
                opts: o,
                specs: first..specs.len(),
            }
        })
        .collect();
    Ok(Plan { opts, parts, specs })
}

/// The rules v2 folder beside the thesis rules.
pub fn v2_rules_dir(thesis_rules: &Path) -> PathBuf {
    thesis_rules.join("v2")
}

/// `command` without its `--out DIR` (or `--out=DIR`).
pub(crate) fn without_out(command: &str) -> String {
    let mut words = command.split(' ');
    let mut kept: Vec<&str> = Vec::new();
    while let Some(w) = words.next() {
        if w == "--out" {
            words.next();
        } else if !w.starts_with("--out=") {
            kept.push(w);
        }
    }
    kept.join(" ")
}

/// Carries out one run. Needs [`RUN_STACK_BYTES`] of stack.
pub fn run(spec: &RunSpec) -> RunOutput {
    let mut cfg = LoopConfig::new(spec.world.clone(), spec.seed, spec.slam, spec.duration_s);
    cfg.rules_dir = spec.rules_dir.clone();
    cfg.io_log = spec.io_log;
    cfg.ablation = spec.ablation.clone();
    cfg.oracle = spec.oracle;
    if spec.example {
        let n = cfg.steps();
        cfg.snapshot_steps = (1..=4).map(|q| (n * q / 4).max(1)).collect();
        cfg.sample_extraction_at = Some(sample_step(&cfg));
    }
    let result = soar_loop::run(&cfg);
    let mut files = run_files(&result);
    let (mut ekf_run, mut error) = (None, None);
    // A run that failed before its first step gives the filter nothing.
    if spec.ekf && !result.steps.is_empty() {
        match ekf::replay(&result, ekf::Noise::STAGE2_HOUGH) {
            Ok(r) => {
                files.extend(ekf_files(&r));
                ekf_run = Some(r);
            }
            Err(e) => error = Some(e),
        }
    }
    RunOutput {
        index: spec.index,
        part: spec.part,
        summary: RunSummary::of(&result, spec.world.run.dt),
        files,
        ekf: ekf_run,
        error,
    }
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

/// A run's step CSV, its TUM trajectories, its final map, its corrections and I/O log.
fn run_files(r: &RunResult) -> Vec<(String, String)> {
    let tag = format!("{}-{}", condition_name(r.slam), r.seed);
    let mut files = vec![
        (format!("steps-{tag}.csv"), r.csv()),
        (
            format!("true-{tag}.tum"),
            tum(r.steps.iter().map(|s| (s.time_s, s.true_pose))),
        ),
        (
            format!("believed-{tag}.tum"),
            tum(r.steps.iter().map(|s| (s.time_s, s.believed))),
        ),
    ];
    let mut map =
        String::from("r_mm,th_deg,start_x_mm,start_y_mm,end_x_mm,end_y_mm,length_mm,time\n");
    for w in &r.memory_walls {
        let _ = writeln!(
            map,
            "{},{},{},{},{},{},{},{}",
            w.r, w.th, w.start.0, w.start.1, w.end.0, w.end.1, w.length, w.time
        );
    }
    files.push((format!("map-{tag}.csv"), map));
    if !r.io_log.is_empty() {
        let mut log = r.io_log.join("\n");
        log.push('\n');
        files.push((format!("io-{tag}.log"), log));
    }
    if r.slam {
        let mut c = String::from(soar_loop::CORRECTIONS_HEADER);
        c.push('\n');
        for k in &r.stats.corrections {
            c.push_str(&k.csv_row());
            c.push('\n');
        }
        files.push((format!("corrections-{tag}.csv"), c));
    }
    files
}

/// An EKF run's step CSV, its TUM trajectories and its final features.
fn ekf_files(r: &ekf::EkfRun) -> Vec<(String, String)> {
    vec![
        (format!("steps-ekf-{}.csv", r.seed), r.csv()),
        (
            format!("true-ekf-{}.tum", r.seed),
            tum(r.steps.iter().map(|s| (s.time_s, s.true_pose))),
        ),
        (
            format!("believed-ekf-{}.tum", r.seed),
            tum(r.steps.iter().map(|s| (s.time_s, s.estimate))),
        ),
        (format!("map-ekf-{}.csv", r.seed), r.map_csv()),
    ]
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

/// Writes `files` into `dir`.
pub fn write_files(dir: &Path, files: &[(String, String)]) -> Result<(), String> {
    for (name, text) in files {
        let p = dir.join(name);
        crate::output_file::write(&p, text)?;
    }
    Ok(())
}

/// What a finished plan made: the experiment, or the comparison's table.
#[derive(Debug)]
pub enum Finished {
    Experiment(Box<Experiment>),
    /// `comparison.md`'s text.
    Comparison(String),
}

/// A plan's outputs as they come in, in any order, and the reports once all are in.
pub struct Assembly {
    plan: Plan,
    summaries: Vec<Option<RunSummary>>,
    /// The EKF replays, by part.
    ekf_runs: Vec<Vec<ekf::EkfRun>>,
    error: Option<String>,
    started: Instant,
}

impl Assembly {
    /// Makes the output folders. The experiment's wall time is counted from here.
    pub fn new(plan: Plan) -> Result<Self, String> {
        for part in &plan.parts {
            std::fs::create_dir_all(&part.opts.out)
                .map_err(|e| format!("cannot create {}: {e}", part.opts.out.display()))?;
        }
        Ok(Assembly {
            summaries: vec![None; plan.specs.len()],
            ekf_runs: vec![Vec::new(); plan.parts.len()],
            plan,
            error: None,
            started: Instant::now(),
        })
    }

    /// The plan whose outputs it takes.
    pub fn plan(&self) -> &Plan {
        &self.plan
    }

    /// How many outputs are in.
    pub fn received(&self) -> usize {
        self.summaries.iter().filter(|s| s.is_some()).count()
    }

    /// The folder a run's files go to.
    pub fn folder(&self, output: &RunOutput) -> Result<&Path, String> {
        self.check(output)?;
        Ok(&self.plan.parts[output.part].opts.out)
    }

    /// An error unless `output` is the result of one of this plan's runs.
    fn check(&self, output: &RunOutput) -> Result<(), String> {
        let spec = self.plan.specs.get(output.index);
        match spec {
            Some(s)
                if s.part == output.part
                    && s.seed == output.summary.seed
                    && s.slam == output.summary.slam =>
            {
                Ok(())
            }
            _ => Err(format!(
                "run {} (seed {}, SLAM {}) is not a run of this experiment's plan",
                output.index,
                output.summary.seed,
                condition_name(output.summary.slam)
            )),
        }
    }

    /// Writes a run's files and keeps its numbers.
    pub fn add(&mut self, output: RunOutput) -> Result<(), String> {
        write_files(self.folder(&output)?, &output.files)?;
        self.keep(output)
    }

    /// Keeps a run's numbers, its files already written (by [`write_files`] into
    /// [`Assembly::folder`]).
    pub fn keep(&mut self, output: RunOutput) -> Result<(), String> {
        self.check(&output)?;
        if self.summaries[output.index].is_some() {
            return Err(format!(
                "run {} (seed {}, SLAM {}) came in twice",
                output.index,
                output.summary.seed,
                condition_name(output.summary.slam)
            ));
        }
        if let Some(e) = output.error {
            self.error.get_or_insert(e);
        }
        if let Some(run) = output.ekf {
            self.ekf_runs[output.part].push(run);
        }
        self.summaries[output.index] = Some(output.summary);
        Ok(())
    }

    /// Records an error that fails the experiment at [`Assembly::finish`] (the first one
    /// is reported).
    pub fn fail(&mut self, error: String) {
        self.error.get_or_insert(error);
    }

    /// Writes the reports: `runs.csv`, `summary.md` and `report.md` of a single experiment,
    /// the EKF's tables, and a comparison's `comparison.md`, `comparison.csv` and figure.
    /// `jobs` is what the reports give as the number of runs carried out at once.
    pub fn finish(self, jobs: usize) -> Result<Finished, String> {
        if let Some(e) = self.error {
            return Err(e);
        }
        let total = self.summaries.len();
        let got = self.received();
        if got != total {
            return Err(format!("only {got} of {total} runs finished"));
        }
        let total_wall_s = self.started.elapsed().as_secs_f64();
        let mut summaries: Vec<Option<RunSummary>> = self.summaries;
        let mut ekf_runs = self.ekf_runs;
        let mut experiments = Vec::new();
        for (p, part) in self.plan.parts.iter().enumerate() {
            let opts = &part.opts;
            let runs: Vec<RunSummary> = summaries[part.specs.clone()]
                .iter_mut()
                .filter_map(Option::take)
                .collect();
            let part_ekf = std::mem::take(&mut ekf_runs[p]);
            let exp = experiment(opts, runs, part_ekf, total_wall_s, jobs)?;
            experiments.push((part.kind, exp));
        }
        if !self.plan.is_comparison() {
            return match experiments.pop() {
                Some((_, exp)) => Ok(Finished::Experiment(Box::new(exp))),
                None => Err("the plan has no experiment".into()),
            };
        }
        comparison(&self.plan.opts, &experiments).map(Finished::Comparison)
    }
}

/// One experiment's [`Experiment`] from its runs, in plan order, with its reports written.
fn experiment(
    opts: &Options,
    runs: Vec<RunSummary>,
    mut ekf_runs: Vec<ekf::EkfRun>,
    total_wall_s: f64,
    jobs: usize,
) -> Result<Experiment, String> {
    let checkpoints: Vec<f64> = [60.0, 300.0, 600.0]
        .into_iter()
        .filter(|t| *t <= opts.duration_s + 1e-9)
        .chain((![60.0, 300.0, 600.0].contains(&opts.duration_s)).then_some(opts.duration_s))
        .collect();
    let mut exp = Experiment {
        runs,
        duration_s: opts.duration_s,
        checkpoints,
        total_wall_s,
        jobs,
        world_label: opts.world_label.clone(),
        noise: opts.world.run.noise,
        world: opts.world.clone(),
        example_seed: opts.first_seed,
        ekf_runs: Vec::new(),
    };
    let write = |name: &str, text: String| -> Result<(), String> {
        crate::output_file::write(&opts.out.join(name), text)
    };
    if opts.reports {
        write("runs.csv", exp.runs_csv())?;
        write("summary.md", exp.summary_md(opts))?;
        super::report::write_report(&exp, opts)?;
    }
    if opts.ekf {
        ekf_runs.sort_by_key(|r| r.seed);
        let mut errors: [ekf::table::ErrorsBySeed; 2] = Default::default();
        for r in &exp.runs {
            errors[usize::from(r.slam)].insert(r.seed, r.pos_err_mm.clone());
        }
        let [dr, thesis] = errors;
        let command = if opts.command_line.is_empty() {
            "rusoar slam --method ekf"
        } else {
            &opts.command_line
        };
        write(
            "ekf.md",
            ekf::table::markdown(&ekf_runs, &dr, &thesis, command),
        )?;
        write("ekf-runs.csv", ekf::table::runs_csv(&ekf_runs, &dr))?;
        exp.ekf_runs = ekf_runs;
    }
    Ok(exp)
}

/// An error naming the first run of `exp` that did not complete: a comparison of methods
/// is only made over complete runs.
fn all_completed(exp: &Experiment, what: &str) -> Result<(), String> {
    match exp.runs.iter().find(|r| !r.outcome.completed()) {
        Some(r) => Err(format!(
            "{what}: seed {} ({}) did not complete: {}",
            r.seed,
            condition_name(r.slam),
            r.outcome
        )),
        None => Ok(()),
    }
}

/// The comparison of the methods' experiments: `comparison.md`, `comparison.csv` and
/// the `fig-compare` figures in `opts.out`. Returns `comparison.md`'s text.
fn comparison(opts: &Options, experiments: &[(PartKind, Experiment)]) -> Result<String, String> {
    let has = |m: Method| opts.methods.contains(&m);
    let world = &opts.world;
    let mut series: Vec<Series> = Vec::new();
    for (kind, exp) in experiments {
        match kind {
            PartKind::Single => {}
            PartKind::Thesis => {
                all_completed(exp, "the thesis rules' runs")?;
                let runs = |slam: bool| -> Vec<&RunSummary> {
                    exp.runs.iter().filter(|r| r.slam == slam).collect()
                };
                series.push(Series::of_runs(Method::Dr, &runs(false), world));
                if has(Method::Thesis) {
                    series.push(Series::of_runs(Method::Thesis, &runs(true), world));
                }
                if has(Method::Ekf) {
                    series.push(Series {
                        method: Method::Ekf,
                        pos: exp
                            .ekf_runs
                            .iter()
                            .map(|r| (r.seed, r.steps.iter().map(|k| k.pos_err_mm).collect()))
                            .collect(),
                        head: exp
                            .ekf_runs
                            .iter()
                            .map(|r| (r.seed, r.steps.iter().map(|k| k.heading_err_deg).collect()))
                            .collect(),
                        rules: None,
                    });
                }
            }
            PartKind::Rules(method) => {
                all_completed(exp, method.label())?;
                let runs: Vec<&RunSummary> = exp.runs.iter().filter(|r| r.slam).collect();
                series.push(Series::of_runs(*method, &runs, world));
            }
        }
    }
    series.sort_by_key(|x| x.method);
    let command = if opts.command_line.is_empty() {
        "rusoar slam --method dr,thesis,v2,ekf,oracle"
    } else {
        &opts.command_line
    };
    let setup = format!(
        "World `{}` ({} sonar), drift `{}`, {} s per run, seeds from {}:",
        opts.world_label,
        opts.world.run.noise,
        opts.ablation.drift,
        opts.duration_s,
        opts.first_seed
    );
    let text = compare::markdown(&series, command, &setup);
    std::fs::create_dir_all(&opts.out)
        .map_err(|e| format!("cannot create {}: {e}", opts.out.display()))?;
    let write = |name: &str, body: String| -> Result<(), String> {
        crate::output_file::write(&opts.out.join(name), body)
    };
    write("comparison.md", text.clone())?;
    write("comparison.csv", compare::csv(&series))?;
    compare::figure(&series, opts.world.run.dt, opts.world.run.noise, &opts.out)?;
    Ok(text)
}

#[cfg(test)]
mod tests {
    use super::super::experiment::{execute, parse_options};
    use super::*;

    fn args(a: &[&str], out: &Path) -> Vec<String> {
        a.iter()
            .map(|s| s.to_string())
            .chain(["--out".to_string(), out.display().to_string()])
            .collect()
    }

    /// Every file under `dir`, by path relative to it, with its contents.
    fn tree(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
        let mut all = Vec::new();
        let mut todo = vec![dir.to_path_buf()];
        while let Some(d) = todo.pop() {
            for e in std::fs::read_dir(&d).unwrap() {
                let p = e.unwrap().path();
                if p.is_dir() {
                    todo.push(p);
                } else {
                    let rel = p.strip_prefix(dir).unwrap().to_path_buf();
                    all.push((rel, std::fs::read(&p).unwrap()));
                }
            }
        }
        all.sort();
        all
    }

    #[test]
    fn runs_carried_out_apart_give_the_threads_files() {
        let base = std::env::temp_dir().join(format!("rusoar-plan-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&base);
        let a = [
            "--seeds",
            "2",
            "--duration",
            "20",
            "--method",
            "dr,thesis,v2,ekf",
            "--io-log",
            "--jobs",
            "2",
        ];
        let threads = base.join("threads");
        let opts = parse_options(&args(&a, &threads)).unwrap();
        let text = match execute(plan(&opts).unwrap(), 2, false).unwrap() {
            Finished::Comparison(t) => t,
            Finished::Experiment(_) => panic!("a comparison was asked for"),
        };
        // The same runs, each through bytes as a Ray task sees them, in reverse order.
        let apart = base.join("apart");
        let plan = plan(&parse_options(&args(&a, &apart)).unwrap()).unwrap();
        assert_eq!(plan.specs.len(), 6, "2 seeds × (off, on, v2)");
        let specs: Vec<Vec<u8>> = plan.specs.iter().map(RunSpec::to_bytes).collect();
        let mut assembly = Assembly::new(plan).unwrap();
        for bytes in specs.iter().rev() {
            let spec = RunSpec::from_bytes(bytes).unwrap();
            let out = RunOutput::from_bytes(&run(&spec).to_bytes()).unwrap();
            assembly.add(out).unwrap();
        }
        match assembly.finish(1).unwrap() {
            Finished::Comparison(t) => assert_eq!(t, text),
            Finished::Experiment(_) => panic!("a comparison was asked for"),
        }
        let (x, y) = (tree(&threads), tree(&apart));
        assert!(x.iter().any(|(p, _)| p.ends_with("thesis/io-on-2.log")));
        assert!(x.iter().any(|(p, _)| p.ends_with("thesis/ekf.md")));
        assert_eq!(
            x.iter().map(|f| &f.0).collect::<Vec<_>>(),
            y.iter().map(|f| &f.0).collect::<Vec<_>>()
        );
        for ((p, a), (_, b)) in x.iter().zip(&y) {
            assert!(a == b, "{} differs", p.display());
        }
        let _ = std::fs::remove_dir_all(&base);
    }

    #[test]
    fn a_failed_run_crosses_as_bytes_with_its_nans() {
        let opts =
            parse_options(&["--seeds".into(), "1".into(), "--slam".into(), "on".into()]).unwrap();
        let mut spec = plan(&opts).unwrap().specs.remove(0);
        spec.rules_dir = PathBuf::from("/nonexistent");
        assert_eq!(RunSpec::from_bytes(&spec.to_bytes()), Ok(spec.clone()));
        let out = run(&spec);
        assert!(!out.summary.outcome.completed() && out.summary.final_mm.is_nan());
        let bytes = out.to_bytes();
        let back = RunOutput::from_bytes(&bytes).unwrap();
        assert!(back.summary.final_mm.is_nan());
        assert_eq!(back.to_bytes(), bytes);
        assert!(RunOutput::from_bytes(&bytes[..bytes.len() / 2]).is_err());
        assert!(RunSpec::from_bytes(b"\xff").is_err());
    }

    #[test]
    fn an_assembly_takes_each_of_its_runs_once() {
        let base = std::env::temp_dir().join(format!("rusoar-plan-once-{}", std::process::id()));
        let a = ["--seeds", "2", "--duration", "1", "--slam", "on"];
        let plan = plan(&parse_options(&args(&a, &base)).unwrap()).unwrap();
        let outputs: Vec<RunOutput> = plan.specs.iter().map(run).collect();
        let mut assembly = Assembly::new(plan.clone()).unwrap();
        assembly.add(outputs[0].clone()).unwrap();
        let twice = assembly.add(outputs[0].clone()).unwrap_err();
        assert!(twice.contains("twice"), "{twice}");
        let mut foreign = outputs[1].clone();
        foreign.summary.seed = 7;
        let e = assembly.add(foreign).unwrap_err();
        assert!(e.contains("not a run of this experiment"), "{e}");
        let e = assembly.finish(1).unwrap_err();
        assert_eq!(e, "only 1 of 2 runs finished");
        let _ = std::fs::remove_dir_all(&base);
    }
}
