//! The figures and `report.md` of `rusoar slam`: the thesis's experiment (Experiment and
//! Result, Figures 20 and 26–30) answered with numbers over seeds.
//!
//! Written into the experiment's output folder, each figure as SVG and PNG:
//!
//! | file | what | thesis |
//! |---|---|---|
//! | `fig-error` | position error against time, median and 10–90 % band across seeds, SLAM on vs off | Figure 30 |
//! | `fig-heading` | heading error against time, the same way | — |
//! | `fig-error-diff`, `fig-heading-diff` | the paired difference on − off against time, mean with its 95 % bootstrap band | — |
//! | `fig-walls` | walls in memory and walls extracted so far against time, on vs off | Figure 28 (as counts) |
//! | `fig-map` | the example seed: true walls, true and believed paths, and the walls of the map, off and on | Figures 26, 29 |
//! | `fig-map-time` | the example seed with the SLAM rules: the map at four times | Figure 28 |
//! | `fig-hough` | one voted Hough space with its zones, beside the returns and walls | Figures 20–22 |
//! | `fig-corrections` | how much each `setOdometry` changed the position error | — |
//! | `fig-paired` | per seed, RMSE and final error without against with the rules | — |
//!
//! `report.md` puts the setup, the paired numbers and the figures together, and says plainly
//! where the rules do not help. Every number in it is computed from the runs; none is typed in.

pub mod figures;
pub mod mapeval;
pub mod paired;
pub mod pixfont;

use std::fmt::Write as _;
use std::path::Path;

use super::geom::Point;
use super::odometry::DriftParams;
use super::results::{condition_name, Experiment, Options, Pair, RunSummary, SlamMode};
use super::soar_loop::{Correction, MemoryWall};
use super::sonar::SonarModel;
use super::stats::{fmt_band, fmt_mm, p_is, quantile, wilcoxon};
use super::variant::Drift;
use figures::{
    save, Band, BandSeries, HoughFigure, MapFigure, MapPanel, PairedScatter, TimeBands, OFF, ON,
};
use mapeval::{Gate, MapScore};

/// Points per curve in the time figures (a 600-s run has 6000 steps).
const CURVE_POINTS: usize = 600;

/// A figure written to the output folder.
#[derive(Debug, Clone, PartialEq)]
pub struct FigureFile {
    /// File name without extension (`.svg` and `.png` exist).
    pub stem: String,
    /// One line saying what it shows.
    pub caption: String,
}

/// The median and 10–90 % band across `runs` of `value(run, step index)` at every step all
/// runs reached, thinned to about `max_points` points (the last step always kept).
pub fn band_over_time(
    runs: &[&RunSummary],
    max_points: usize,
    value: impl Fn(&RunSummary, usize) -> f64,
) -> Band {
    let n = runs.iter().map(|r| r.pos_err_mm.len()).min().unwrap_or(0);
    let dt = runs.first().map_or(0.1, |r| r.dt);
    let mut band = Band::default();
    if n == 0 {
        return band;
    }
    let stride = n.div_ceil(max_points.max(1)).max(1);
    let mut ks: Vec<usize> = (stride - 1..n).step_by(stride).collect();
    if ks.last() != Some(&(n - 1)) {
        ks.push(n - 1);
    }
    for k in ks {
        let v: Vec<f64> = runs.iter().map(|r| value(r, k)).collect();
        band.t.push((k + 1) as f64 * dt);
        band.median.push(quantile(&v, 0.5));
        band.lo.push(quantile(&v, 0.1));
        band.hi.push(quantile(&v, 0.9));
    }
    band
}

fn segs_of_memory(walls: &[MemoryWall]) -> Vec<(Point, Point)> {
    walls
        .iter()
        .map(|w| {
            (
                Point::new(w.start.0 / 1000.0, w.start.1 / 1000.0),
                Point::new(w.end.0 / 1000.0, w.end.1 / 1000.0),
            )
        })
        .collect()
}

fn segs_of_extracted(r: &RunSummary) -> Vec<(Point, Point)> {
    r.extracted
        .iter()
        .map(|w| {
            (
                Point::new(w.start.x as f64 / 1000.0, w.start.y as f64 / 1000.0),
                Point::new(w.end.x as f64 / 1000.0, w.end.y as f64 / 1000.0),
            )
        })
        .collect()
}

/// The map a run ends with: the walls in memory with the SLAM rules; without them no rule
/// keeps walls, so every wall the pipeline extracted (what the thesis's Figure 26 shows: the
/// walls the agent was given, never merged or removed).
pub fn final_map(r: &RunSummary) -> Vec<(Point, Point)> {
    if r.slam {
        segs_of_memory(&r.memory_walls)
    } else {
        segs_of_extracted(r)
    }
}

/// Map scores of a condition's completed runs.
fn map_scores(exp: &Experiment, slam: bool) -> Vec<MapScore> {
    exp.completed(slam)
        .into_iter()
        .map(|r| mapeval::score(&final_map(r), &exp.world.walls, Gate::default()))
        .collect()
}

/// The map table (markdown) for `summary.md` and `report.md`.
pub fn map_table_md(exp: &Experiment) -> String {
    let mut s = String::new();
    let g = Gate::default();
    let _ = writeln!(
        s,
        "A map wall matches a true wall when its midpoint lies within {:.0} mm of the true \
         wall's line (|Δr|), beside the wall, and its direction is within {:.0}° (Δθ); the rest \
         are phantoms. With the SLAM rules the map is the top state's `^wallData`; without them \
         no rule keeps walls, so the map is every wall the pipeline extracted (the thesis's \
         Figure 26). Medians over seeds, 10–90 % band in brackets; the true room has {} walls.\n",
        g.r_mm,
        g.th_deg,
        exp.world.walls.len()
    );
    let _ = writeln!(
        s,
        "| SLAM | map | walls | matched | phantoms | matched share | true walls found | median \\|Δr\\|, mm | median Δθ, ° |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|");
    for slam in exp.conditions() {
        let sc = map_scores(exp, slam);
        let col = |f: &dyn Fn(&MapScore) -> f64| -> Vec<f64> { sc.iter().map(f).collect() };
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            condition_name(slam),
            if slam {
                "walls in memory"
            } else {
                "all walls extracted"
            },
            fmt_band(&col(&|m| m.walls as f64)),
            fmt_band(&col(&|m| m.matched as f64)),
            fmt_band(&col(&|m| (m.walls - m.matched) as f64)),
            fmt_pct(quantile(&col(&|m| m.matched_share()), 0.5)),
            fmt_band(&col(&|m| m.true_walls_found as f64)),
            fmt_band(&col(&|m| m.median_dr())),
            fmt_1(quantile(&col(&|m| m.median_dth()), 0.5)),
        );
    }
    s
}

fn fmt_pct(v: f64) -> String {
    if v.is_finite() {
        format!("{:.0} %", v * 100.0)
    } else {
        "–".into()
    }
}

fn fmt_1(v: f64) -> String {
    if v.is_finite() {
        format!("{v:.1}")
    } else {
        "–".into()
    }
}

fn fmt_m(mm: f64) -> String {
    if mm.is_finite() {
        format!("{:.2} m", mm / 1000.0)
    } else {
        "–".into()
    }
}

fn fmt_p(p: Option<f64>) -> String {
    p.map_or("–".into(), super::stats::fmt_p)
}

/// The run of the example seed in a condition.
fn example(exp: &Experiment, slam: bool) -> Option<&RunSummary> {
    exp.runs
        .iter()
        .find(|r| r.seed == exp.example_seed && r.slam == slam)
}

/// The seeds both conditions completed: (SLAM on, SLAM off) per seed, in seed order.
fn paired_runs(exp: &Experiment) -> Vec<(&RunSummary, &RunSummary)> {
    let off = exp.completed(false);
    exp.completed(true)
        .into_iter()
        .filter_map(|on| Some((on, *off.iter().find(|r| r.seed == on.seed)?)))
        .collect()
}

/// `fig-error-diff` and `fig-heading-diff`: the paired difference SLAM on − off over time,
/// mean over seeds with its 95 % bootstrap band. Written only when both conditions ran.
fn difference_figures(exp: &Experiment, dir: &Path) -> Result<Vec<FigureFile>, String> {
    let pairs = paired_runs(exp);
    if pairs.is_empty() {
        return Ok(Vec::new());
    }
    let dt = pairs[0].0.dt;
    let metres = |r: &RunSummary| -> Vec<f64> { r.pos_err_mm.iter().map(|e| e / 1000.0).collect() };
    let pos: Vec<(Vec<f64>, Vec<f64>)> = pairs
        .iter()
        .map(|(on, off)| (metres(on), metres(off)))
        .collect();
    let head: Vec<(Vec<f64>, Vec<f64>)> = pairs
        .iter()
        .map(|(on, off)| (on.heading_err_deg.clone(), off.heading_err_deg.clone()))
        .collect();
    let mut out = Vec::new();
    for (stem, title, y, data, caption) in [
        (
            "fig-error-diff",
            "Position error, SLAM on − off, paired",
            "on − off, m",
            &pos,
            "The paired difference in position error, SLAM on − off, against time: mean over seeds with its 95 % bootstrap band (2,000 resamples of the seeds, fixed seed). Above 0 the rules made the error larger.",
        ),
        (
            "fig-heading-diff",
            "Heading error, SLAM on − off, paired",
            "on − off, degrees",
            &head,
            "The paired difference in heading error, SLAM on − off, the same way.",
        ),
    ] {
        let slices: Vec<(&[f64], &[f64])> =
            data.iter().map(|(a, b)| (a.as_slice(), b.as_slice())).collect();
        let band = paired::difference_over_time(&slices, dt, CURVE_POINTS);
        let fig = TimeBands {
            title: format!(
                "{title}: mean of {} seeds, 95 % bootstrap band",
                pairs.len()
            ),
            x_label: "time, s".into(),
            y_label: y.into(),
            series: vec![BandSeries {
                label: "SLAM on − off".into(),
                color: ON,
                band: &band,
                dashed: false,
            }],
            hlines: Vec::new(),
        };
        save(&fig, dir, stem)?;
        out.push(FigureFile {
            stem: stem.into(),
            caption: caption.into(),
        });
    }
    Ok(out)
}

/// Writes every figure into `dir`; returns what was written.
pub fn write_figures(exp: &Experiment, dir: &Path) -> Result<Vec<FigureFile>, String> {
    let mut out = Vec::new();
    let conds = exp.conditions();
    let label = |slam: bool| {
        if slam {
            "SLAM on"
        } else {
            "SLAM off"
        }
    };
    let colour = |slam: bool| if slam { ON } else { OFF };
    let completed: Vec<(bool, Vec<&RunSummary>)> =
        conds.iter().map(|&c| (c, exp.completed(c))).collect();
    let n_seeds = |slam: bool| exp.completed(slam).len();

    // Position and heading error (Figure 30).
    let err: Vec<(bool, Band)> = completed
        .iter()
        .map(|(c, runs)| {
            (
                *c,
                band_over_time(runs, CURVE_POINTS, |r, k| r.pos_err_mm[k] / 1000.0),
            )
        })
        .collect();
    let head: Vec<(bool, Band)> = completed
        .iter()
        .map(|(c, runs)| {
            (
                *c,
                band_over_time(runs, CURVE_POINTS, |r, k| {
                    r.heading_err_deg.get(k).copied().unwrap_or(f64::NAN)
                }),
            )
        })
        .collect();
    let band_label = |c: bool| {
        format!(
            "{}: median of {} seeds (band: 10–90 %)",
            label(c),
            n_seeds(c)
        )
    };
    for (stem, title, y, bands, caption) in [
        (
            "fig-error",
            "Distance between true and believed position (thesis Figure 30)",
            "position error, m",
            &err,
            "Position error against time: median across seeds with the 10–90 % band, without and with the SLAM rules (thesis Figure 30).",
        ),
        (
            "fig-heading",
            "Heading error",
            "heading error, degrees",
            &head,
            "Heading error against time, median and 10–90 % band.",
        ),
    ] {
        let fig = TimeBands {
            title: title.into(),
            x_label: "time, s".into(),
            y_label: y.into(),
            series: bands
                .iter()
                .map(|(c, b)| BandSeries {
                    label: band_label(*c),
                    color: colour(*c),
                    band: b,
                    dashed: false,
                })
                .collect(),
            hlines: Vec::new(),
        };
        save(&fig, dir, stem)?;
        out.push(FigureFile {
            stem: stem.into(),
            caption: caption.into(),
        });
    }

    out.extend(difference_figures(exp, dir)?);

    // Walls over time (Figure 28 as counts).
    let walls: Vec<(bool, Band, Band)> = completed
        .iter()
        .map(|(c, runs)| {
            (
                *c,
                band_over_time(runs, CURVE_POINTS, |r, k| {
                    r.walls_memory.get(k).map_or(f64::NAN, |v| *v as f64)
                }),
                band_over_time(runs, CURVE_POINTS, |r, k| {
                    r.walls_extracted_so_far
                        .get(k)
                        .map_or(f64::NAN, |v| *v as f64)
                }),
            )
        })
        .collect();
    let mut series = Vec::new();
    for (c, mem, ext) in &walls {
        series.push(BandSeries {
            label: format!("{}: walls in memory (^wallData)", label(*c)),
            color: colour(*c),
            band: mem,
            dashed: false,
        });
        series.push(BandSeries {
            label: format!("{}: walls extracted so far", label(*c)),
            color: colour(*c),
            band: ext,
            dashed: true,
        });
    }
    save(
        &TimeBands {
            title: "Walls over time (thesis Figure 28, as counts)".into(),
            x_label: "time, s".into(),
            y_label: "walls".into(),
            series,
            hlines: Vec::new(),
        },
        dir,
        "fig-walls",
    )?;
    out.push(FigureFile {
        stem: "fig-walls".into(),
        caption: "Walls in the agent's memory and walls extracted so far, median and 10–90 % band across seeds. Without the SLAM rules no rule copies walls into memory.".into(),
    });

    // The example seed's maps (Figures 26 and 29).
    let view = figures::view_around(&exp.world.walls, 0.35);
    let panels: Vec<MapPanel<'_>> = conds
        .iter()
        .filter_map(|&c| example(exp, c))
        .map(|r| MapPanel {
            title: if r.slam {
                format!(
                    "SLAM on, seed {}: {} walls in memory after {:.0} s",
                    r.seed,
                    r.memory_walls.len(),
                    r.sim_time_s
                )
            } else {
                format!(
                    "SLAM off, seed {}: all {} walls extracted in {:.0} s",
                    r.seed,
                    r.extracted.len(),
                    r.sim_time_s
                )
            },
            truth: &exp.world.walls,
            true_path: &r.true_path,
            believed_path: &r.believed_path,
            walls: final_map(r),
        })
        .collect();
    if !panels.is_empty() {
        let columns = panels.len();
        save(
            &MapFigure {
                title: format!(
                    "Walls the agent believes in over the true room, seed {} (thesis Figures 26 and 29)",
                    exp.example_seed
                ),
                panels,
                columns,
                walls_label: "walls of the map (believed frame)".into(),
                view,
            },
            dir,
            "fig-map",
        )?;
        out.push(FigureFile {
            stem: "fig-map".into(),
            caption: format!(
                "Seed {} (the first seed, not picked for looks): the true room, the true path, the believed path and the walls of the map at the end, without and with the SLAM rules (thesis Figures 26 and 29). Walls and believed path are in the believed frame; the view is clipped to the room and its surroundings.",
                exp.example_seed
            ),
        });
    }

    // Map snapshots with the SLAM rules (Figure 28).
    if let Some(r) = example(exp, true).filter(|r| !r.map_snapshots.is_empty()) {
        let panels: Vec<MapPanel<'_>> = r
            .map_snapshots
            .iter()
            .map(|(t, walls)| {
                let k = ((t / r.dt).round() as usize).min(r.true_path.len());
                MapPanel {
                    title: format!("t = {t:.0} s: {} walls in memory", walls.len()),
                    truth: &exp.world.walls,
                    true_path: &r.true_path[..k],
                    believed_path: &r.believed_path[..k.min(r.believed_path.len())],
                    walls: segs_of_memory(walls),
                }
            })
            .collect();
        save(
            &MapFigure {
                title: format!(
                    "The map in memory over time, SLAM on, seed {} (thesis Figure 28)",
                    r.seed
                ),
                panels,
                columns: 2,
                walls_label: "walls in memory".into(),
                view,
            },
            dir,
            "fig-map-time",
        )?;
        out.push(FigureFile {
            stem: "fig-map-time".into(),
            caption: format!(
                "Seed {} with the SLAM rules: the walls in memory and the paths so far at four times (thesis Figure 28).",
                r.seed
            ),
        });
    }

    // One Hough space (Figure 20).
    let sample = conds
        .iter()
        .rev()
        .filter_map(|&c| example(exp, c))
        .find_map(|r| r.sample_extraction.as_ref().map(|s| (r, s)));
    if let Some((r, (t, ex))) = sample {
        save(
            &HoughFigure {
                title: format!(
                    "One extraction: seed {}, SLAM {}, t = {t:.1} s (thesis Figures 20-22)",
                    r.seed,
                    condition_name(r.slam)
                ),
                extraction: ex,
                k: exp.world.pipeline.k,
                truth: &exp.world.walls,
            },
            dir,
            "fig-hough",
        )?;
        out.push(FigureFile {
            stem: "fig-hough".into(),
            caption: format!(
                "Left: the voted Hough space of one extraction (seed {}, t = {t:.1} s; darker = more votes, red circles = centres of the zones above k = {}), thesis Figures 20 and 21. Right: the sonar returns of the scan window in the believed frame, those kept by the noise filter, and the walls extracted (red), thesis Figure 22; the dashed grey lines are the true walls.",
                r.seed, exp.world.pipeline.k
            ),
        });
    }

    // Corrections.
    let corr: Vec<&Correction> = exp
        .completed(true)
        .into_iter()
        .flat_map(|r| r.correction_log.iter())
        .collect();
    if !corr.is_empty() {
        let d: Vec<f64> = corr
            .iter()
            .map(|c| c.err_after_mm - c.err_before_mm)
            .collect();
        let lo = quantile(&d, 0.0);
        let hi = quantile(&d, 1.0);
        let width = nice_bin((hi - lo) / 40.0);
        let first = (lo / width).floor() as i64;
        let last = (hi / width).floor() as i64;
        let mut bars: Vec<(f64, f64, u32, bool)> = (first..=last)
            .flat_map(|b| {
                let x0 = b as f64 * width;
                [(x0, x0 + width, 0, false), (x0, x0 + width, 0, true)]
            })
            .collect();
        for v in &d {
            let b = ((v / width).floor() as i64 - first) as usize;
            let hurt = *v > 0.0;
            if let Some(bar) = bars.get_mut(2 * b + usize::from(hurt)) {
                bar.2 += 1;
            }
        }
        let helped = d.iter().filter(|v| **v < 0.0).count();
        save(
            &figures::Histogram {
                title: format!(
                    "{} setOdometry corrections over {} runs: {} brought the belief closer",
                    d.len(),
                    exp.completed(true).len(),
                    helped
                ),
                x_label: "change of the position error by the correction, mm".into(),
                y_label: "corrections".into(),
                bars,
                labels: [
                    ("closer to the truth".into(), RGBColorExt::GOOD),
                    ("further from the truth".into(), OFF),
                ],
            },
            dir,
            "fig-corrections",
        )?;
        out.push(FigureFile {
            stem: "fig-corrections".into(),
            caption: "Every `setOdometry` the SLAM rules made, over all seeds: the position error just after minus just before (negative: the correction helped).".into(),
        });
    }

    // Per-seed pairs.
    let rmse = exp.paired(|r| r.rmse_mm / 1000.0);
    if !rmse.is_empty() {
        let last = exp.checkpoints.last().copied().unwrap_or(exp.duration_s);
        let fin = exp.paired(|r| r.err_at(last).unwrap_or(f64::NAN) / 1000.0);
        save(
            &PairedScatter {
                title: "Per seed, without (x) and with (y) the SLAM rules".into(),
                panels: vec![
                    ("RMSE".into(), "m".into(), rmse),
                    (format!("error at {last:.0} s"), "m".into(), fin),
                ],
            },
            dir,
            "fig-paired",
        )?;
        out.push(FigureFile {
            stem: "fig-paired".into(),
            caption:
                "One point per seed: below the diagonal the SLAM rules gave the smaller error."
                    .into(),
        });
    }
    Ok(out)
}

/// Colours beyond the two conditions.
struct RGBColorExt;

impl RGBColorExt {
    const GOOD: plotters::style::RGBColor = plotters::style::RGBColor(60, 150, 70);
}

/// A bin width of 1, 2 or 5 times a power of ten, at least `w` (and at least 1).
fn nice_bin(w: f64) -> f64 {
    if !w.is_finite() || w <= 1.0 {
        return 1.0;
    }
    let p = 10f64.powf(w.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * p)
        .find(|b| *b >= w)
        .unwrap_or(10.0 * p)
}

/// The `rusoar slam` command line that repeats this experiment.
fn command_line(opts: &Options) -> String {
    let slam = match opts.slam {
        SlamMode::On => "on",
        SlamMode::Off => "off",
        SlamMode::Both => "both",
    };
    format!(
        "cargo run --release -- slam --seeds {} --first-seed {} --duration {} --world {} --noise {} --slam {slam} --out {}",
        opts.seeds,
        opts.first_seed,
        opts.duration_s,
        opts.world_label,
        opts.world.run.noise,
        opts.out.display()
    )
}

/// Paired statistics of one measure.
struct PairStats {
    n: usize,
    better: usize,
    worse: usize,
    median_off: f64,
    median_on: f64,
    median_diff: f64,
    p: Option<f64>,
}

fn pair_stats(pairs: &[Pair]) -> PairStats {
    let pairs: Vec<&Pair> = pairs
        .iter()
        .filter(|(_, a, b)| a.is_finite() && b.is_finite())
        .collect();
    let diffs: Vec<f64> = pairs.iter().map(|(_, off, on)| on - off).collect();
    PairStats {
        n: pairs.len(),
        better: diffs.iter().filter(|d| **d < 0.0).count(),
        worse: diffs.iter().filter(|d| **d > 0.0).count(),
        median_off: quantile(&pairs.iter().map(|p| p.1).collect::<Vec<_>>(), 0.5),
        median_on: quantile(&pairs.iter().map(|p| p.2).collect::<Vec<_>>(), 0.5),
        median_diff: quantile(&diffs, 0.5),
        p: wilcoxon(&diffs).map(|(_, _, p)| p),
    }
}

/// The smallest two-sided p the exact signed-rank test can give with `n` pairs.
fn min_p(n: usize) -> f64 {
    (2.0 / 2f64.powi(n.min(1000) as i32)).min(1.0)
}

/// A plain sentence on a paired comparison where smaller is better.
fn verdict(s: &PairStats) -> String {
    if s.n == 0 {
        return "cannot be compared (no seed completed in both conditions)".into();
    }
    let dir = if s.better == s.n {
        "lower with the SLAM rules in every seed".to_string()
    } else if s.worse == s.n {
        "higher with the SLAM rules in every seed".to_string()
    } else if s.better > s.worse {
        format!("lower with the SLAM rules in {} of {} seeds", s.better, s.n)
    } else if s.worse > s.better {
        format!("higher with the SLAM rules in {} of {} seeds", s.worse, s.n)
    } else {
        format!(
            "lower with the SLAM rules in {} and higher in {} of {} seeds: no consistent difference",
            s.better, s.worse, s.n
        )
    };
    let sig = match s.p {
        Some(p) if p < 0.05 => format!("significant at 5 % (Wilcoxon {})", p_is(p)),
        Some(p) if min_p(s.n) >= 0.05 => format!(
            "Wilcoxon {}; with {} seeds no result can reach p < 0.05 (the smallest possible p is {:.3})",
            p_is(p),
            s.n,
            min_p(s.n)
        ),
        Some(p) => format!("not significant at 5 % (Wilcoxon {})", p_is(p)),
        None => "no non-zero difference to test".into(),
    };
    format!("{dir}; {sig}")
}

/// Checkpoints at which most paired seeds have a lower (`lower`) or higher error with the rules.
fn checkpoints_where(exp: &Experiment, lower: bool) -> Vec<f64> {
    exp.checkpoints
        .iter()
        .copied()
        .filter(|&t| {
            let st = pair_stats(&exp.paired(|r| r.err_at(t).unwrap_or(f64::NAN)));
            if lower {
                st.better * 2 > st.n
            } else {
                st.worse * 2 > st.n
            }
        })
        .collect()
}

/// The corrections made in one time window, summed up.
#[derive(Debug, Clone, PartialEq)]
struct Window {
    from: f64,
    to: f64,
    n: usize,
    helped: usize,
    helped_head: usize,
    /// Sum of the changes of the position error, mm.
    sum_pos_mm: f64,
    /// Sum of the changes of the heading error, degrees.
    sum_head_deg: f64,
    median_jump_mm: f64,
}

/// The corrections of `corr` split at the checkpoints.
fn windows(corr: &[&Correction], checkpoints: &[f64]) -> Vec<Window> {
    let mut edges = vec![0.0];
    edges.extend(checkpoints.iter().copied());
    edges
        .windows(2)
        .map(|e| {
            let inside: Vec<&&Correction> = corr
                .iter()
                .filter(|c| c.time_s > e[0] && c.time_s <= e[1])
                .collect();
            Window {
                from: e[0],
                to: e[1],
                n: inside.len(),
                helped: inside.iter().filter(|c| c.helped()).count(),
                helped_head: inside.iter().filter(|c| c.helped_heading()).count(),
                sum_pos_mm: inside
                    .iter()
                    .map(|c| c.err_after_mm - c.err_before_mm)
                    .sum(),
                sum_head_deg: inside
                    .iter()
                    .map(|c| c.head_after_deg - c.head_before_deg)
                    .sum(),
                median_jump_mm: quantile(
                    &inside.iter().map(|c| c.jump_mm).collect::<Vec<_>>(),
                    0.5,
                ),
            }
        })
        .collect()
}

/// `report.md`.
pub fn report_md(exp: &Experiment, opts: &Options, figs: &[FigureFile]) -> String {
    let mut s = String::new();
    let conds = exp.conditions();
    let both = conds.len() == 2;
    let full = opts.seeds >= 20 && opts.duration_s >= 600.0;
    let _ = writeln!(
        s,
        "# Soar-SLAM: the thesis's experiment, repeated over seeds\n"
    );
    let _ = writeln!(s, "Produced by\n\n```sh\n{}\n```\n", command_line(opts));
    if !full {
        let _ = writeln!(
            s,
            "**A reduced run**: {} seed(s) × {} s. The full experiment is 20 seeds × 600 s \
             (`cargo run --release -- slam`); read the numbers below as a first look, not as the \
             answer.\n",
            opts.seeds, exp.duration_s
        );
    }

    // Setup.
    let _ = writeln!(s, "## Setup\n");
    let w = &exp.world;
    let (x0, x1, y0, y1) = figures::view_around(&w.walls, 0.0);
    let _ = writeln!(
        s,
        "- **World** `{}`: {} wall segments spanning {:.1} m × {:.1} m; the robot starts at \
         ({:.2}, {:.2}) m facing {:.0}°.",
        exp.world_label,
        w.walls.len(),
        x1 - x0,
        y1 - y0,
        w.start.x,
        w.start.y,
        w.start.th.to_degrees()
    );
    let _ = writeln!(
        s,
        "- **Robot**: simulated Pioneer 2-DX, time step {} s; one Soar decision per step. The \
         moving rules drive it on sonar alone (forward; turn right when a wall blocks the front).",
        w.run.dt
    );
    let m = SonarModel::preset(exp.noise);
    let noise = if m.sigma_const_m == 0.0 && m.sigma_prop == 0.0 {
        "no range noise".to_string()
    } else {
        format!(
            "Gaussian range noise σ = {:.0} mm + {:.1} % of range",
            m.sigma_const_m * 1000.0,
            m.sigma_prop * 100.0
        )
    };
    let misses = match m.max_incidence_deg {
        Some(a) => format!("specular misses beyond {a:.0}° incidence"),
        None => "no specular misses".into(),
    };
    let outliers = if m.outlier_prob > 0.0 {
        format!("{:.1} % outliers", m.outlier_prob * 100.0)
    } else {
        "no outliers".into()
    };
    let _ = writeln!(
        s,
        "- **Sonar** (`{}` preset): 16 transducers, {} ray(s) over a {:.0}° cone, range \
         {:.2}–{:.1} m, {noise}, {misses}, {outliers}.",
        exp.noise, m.rays, m.cone_deg, m.min_range_m, m.max_range_m,
    );
    let d = DriftParams::STAGE2;
    if opts.ablation.drift == Drift::None {
        let _ = writeln!(
            s,
            "- **Odometry drift**: none (`--drift none`, the control): the believed pose follows \
             the true pose exactly until `setOdometry` overwrites it, so every error comes from \
             the rules."
        );
    } else {
        let _ = writeln!(
            s,
            "- **Odometry drift** (Stage 2.0.x model): biases drawn once per run, uniform in \
         ±{:.1} % on distance, ±{:.1} % distance-to-heading, ±{:.1} % on rotation; noise \
         {:.2} m per √m travelled and {:.2} rad per √revolution. The robot believes the pose it \
         integrates; `setOdometry` overwrites it.",
            d.bias_max_x * 50.0,
            d.bias_max_y * 50.0,
            d.bias_max_a * 50.0,
            d.std_x,
            d.std_a
        );
    }
    let p = &w.pipeline;
    let _ = writeln!(
        s,
        "- **Pipeline**: Hough transform over the last {} scans every {} steps, θ step {}°, r bin \
         {:.0} mm, critical value k = {}, `{}` voting.",
        p.scan_window, p.extract_every, p.theta_step_deg, p.r_bin_mm, p.k, p.vote_mode
    );
    let prods = |slam: bool| {
        exp.runs
            .iter()
            .find(|r| r.slam == slam)
            .map_or(0, |r| r.productions)
    };
    let _ = writeln!(
        s,
        "- **Rules**: SLAM `on` loads `rules/robotagent.soar` unmodified ({} productions); `off` \
         leaves out its line `source slam.soar` ({} productions). The thesis rules are not tuned.",
        prods(true),
        prods(false)
    );
    if !opts.ablation.variants.is_empty() || opts.ablation.constants.any() {
        let mut parts: Vec<String> = opts
            .ablation
            .variants
            .iter()
            .map(|v| format!("`{v}` ({})", v.describe()))
            .collect();
        if opts.ablation.constants.any() {
            let (r, th, o) = opts.ablation.constants.values();
            parts.push(format!(
                "constants r-tolerance {r} mm, th-tolerance {th}°, overlap {o} %"
            ));
        }
        let _ = writeln!(
            s,
            "- **Ablation** `{}`, not the thesis's setup: {} (`rules/README.md`, section 6). The \
             productions above count the variant rules.",
            opts.ablation.label(),
            parts.join("; ")
        );
    }
    let _ = writeln!(
        s,
        "- **Seeds** {}–{} ({} per condition), {} simulated seconds each, paired by seed: a seed \
         gives the same odometry biases, sonar noise and start in both conditions. {}\n",
        opts.first_seed,
        opts.first_seed + opts.seeds - 1,
        opts.seeds,
        exp.duration_s,
        exp.true_paths_note().unwrap_or_default()
    );

    let failed: Vec<&RunSummary> = exp.runs.iter().filter(|r| !r.outcome.completed()).collect();
    if !failed.is_empty() {
        let _ = writeln!(
            s,
            "**{} run(s) did not complete** and are left out of every number below:\n",
            failed.len()
        );
        for r in failed {
            let _ = writeln!(
                s,
                "- seed {} SLAM {}: {}",
                r.seed,
                condition_name(r.slam),
                r.outcome
            );
        }
        let _ = writeln!(s);
    }

    // The answer.
    let _ = writeln!(s, "## The answer\n");
    if !both {
        let _ = writeln!(
            s,
            "Only SLAM `{}` was run, so the thesis's comparison cannot be made; the numbers below \
             describe that condition alone.\n",
            conds.first().map_or("–", |c| condition_name(*c))
        );
    } else if exp.paired(|r| r.rmse_mm).is_empty() {
        let _ = writeln!(
            s,
            "No seed completed in both conditions, so the thesis's comparison cannot be made.\n"
        );
    } else {
        let _ = writeln!(
            s,
            "The thesis (Figure 30) claims that with its SLAM rules the distance between the true \
             and the believed position stays smaller. Here, paired by seed:\n"
        );
        for &t in &exp.checkpoints {
            let st = pair_stats(&exp.paired(|r| r.err_at(t).unwrap_or(f64::NAN)));
            let _ = writeln!(
                s,
                "- **At {t:.0} s** the position error is {}. Median {} without, {} with the rules \
                 (median paired difference {} mm).",
                verdict(&st),
                fmt_m(st.median_off),
                fmt_m(st.median_on),
                fmt_mm(st.median_diff)
            );
        }
        let st = pair_stats(&exp.paired(|r| r.rmse_mm));
        let _ = writeln!(
            s,
            "- **Over the whole run** (RMSE of the position error) it is {}. Median {} without, \
             {} with.",
            verdict(&st),
            fmt_m(st.median_off),
            fmt_m(st.median_on)
        );
        let st = pair_stats(&exp.paired(|r| r.rmse_heading_deg));
        let _ = writeln!(
            s,
            "- **Heading** (RMSE of the heading error) is {}. Median {}° without, {}° with.",
            verdict(&st),
            fmt_1(st.median_off),
            fmt_1(st.median_on)
        );
        let on_mem = quantile(&exp.column(true, |r| r.final_walls as f64), 0.5);
        let off_ext = quantile(&exp.column(false, |r| r.extracted.len() as f64), 0.5);
        let on_ext = quantile(&exp.column(true, |r| r.extracted.len() as f64), 0.5);
        let _ = writeln!(
            s,
            "- **Walls** (the thesis compares Figures 26 and 29): with the rules the agent ends \
             with a median of {} walls in memory, for a room of {} walls, after the pipeline \
             gave it {}. Without them no rule keeps walls; the agent was given a median of {} \
             walls, which is the unmerged map of the thesis's Figure 26. So the wall count is {} \
             with the rules.\n",
            fmt_mm(on_mem),
            w.walls.len(),
            fmt_mm(on_ext),
            fmt_mm(off_ext),
            if on_mem < off_ext {
                "lower"
            } else if on_mem > off_ext {
                "higher"
            } else {
                "the same"
            }
        );
        let helps_at = checkpoints_where(exp, true);
        let hurts_at = checkpoints_where(exp, false);
        let list = |v: &[f64]| {
            v.iter()
                .map(|t| format!("{t:.0} s"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let _ = write!(s, "**In short:** ");
        if hurts_at.is_empty() && helps_at.len() == exp.checkpoints.len() {
            let _ = writeln!(
                s,
                "in this run the thesis's claim holds: the rules lower the position error in \
                 most seeds at every checkpoint ({}).\n",
                list(&helps_at)
            );
        } else {
            if !helps_at.is_empty() {
                let _ = write!(
                    s,
                    "the rules lower the position error in most seeds at {}. ",
                    list(&helps_at)
                );
            }
            if !hurts_at.is_empty() {
                let _ = write!(
                    s,
                    "They do **not** help at {}: there the error is higher with the rules in most \
                     seeds. ",
                    list(&hurts_at)
                );
            }
            let _ = writeln!(
                s,
                "The thesis's claim holds here only where stated; we did not tune the rules.\n"
            );
        }
    }

    // Tables.
    let _ = writeln!(s, "## Position error\n");
    let _ = writeln!(
        s,
        "Medians over seeds with the 10–90 % band in brackets, mm; paired columns compare the \
         same seed (on − off).\n"
    );
    let _ = writeln!(
        s,
        "| time | SLAM off | SLAM on | seeds lower with SLAM | median paired difference | Wilcoxon p |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|");
    let col_at = |slam: bool, t: f64| -> Vec<f64> {
        exp.completed(slam)
            .iter()
            .filter_map(|r| r.err_at(t))
            .collect()
    };
    // (row name, off values, on values, pairs)
    type Row = (String, Vec<f64>, Vec<f64>, Vec<Pair>);
    let mut rows: Vec<Row> = exp
        .checkpoints
        .iter()
        .map(|&t| {
            (
                format!("{t:.0} s"),
                col_at(false, t),
                col_at(true, t),
                exp.paired(|r| r.err_at(t).unwrap_or(f64::NAN)),
            )
        })
        .collect();
    rows.push((
        "RMSE".into(),
        exp.column(false, |r| r.rmse_mm),
        exp.column(true, |r| r.rmse_mm),
        exp.paired(|r| r.rmse_mm),
    ));
    rows.push((
        "max".into(),
        exp.column(false, |r| r.max_mm),
        exp.column(true, |r| r.max_mm),
        exp.paired(|r| r.max_mm),
    ));
    for (name, off, on, pairs) in rows {
        let st = pair_stats(&pairs);
        let _ = writeln!(
            s,
            "| {name} | {} | {} | {} | {} | {} |",
            fmt_band(&off),
            fmt_band(&on),
            if st.n == 0 {
                "–".to_string()
            } else {
                format!("{} of {}", st.better, st.n)
            },
            fmt_mm(st.median_diff),
            fmt_p(st.p)
        );
    }
    let _ = writeln!(s);

    let _ = writeln!(s, "## The map\n");
    s.push_str(&map_table_md(exp));
    let _ = writeln!(s);

    // Corrections.
    let on_runs = exp.completed(true);
    if !on_runs.is_empty() && on_runs.iter().all(|r| r.correction_log.is_empty()) {
        let _ = writeln!(
            s,
            "## Corrections\n\nThe SLAM rules made no `setOdometry` correction in {} run(s).\n",
            on_runs.len()
        );
    } else if !on_runs.is_empty() {
        let all: Vec<&Correction> = on_runs
            .iter()
            .flat_map(|r| r.correction_log.iter())
            .collect();
        let helped = all.iter().filter(|c| c.helped()).count();
        let helped_head = all.iter().filter(|c| c.helped_heading()).count();
        let change: Vec<f64> = all
            .iter()
            .map(|c| c.err_after_mm - c.err_before_mm)
            .collect();
        let head_change: Vec<f64> = all
            .iter()
            .map(|c| c.head_after_deg - c.head_before_deg)
            .collect();
        let share = |k: usize| {
            fmt_pct(if all.is_empty() {
                f64::NAN
            } else {
                k as f64 / all.len() as f64
            })
        };
        let _ = writeln!(s, "## Corrections\n");
        let _ =
            writeln!(
            s,
            "The SLAM rules reset the odometry (`setOdometry`) {} times over {} runs (median {} \
             per run; median jump {} mm and {:.1}°).\n",
            all.len(),
            on_runs.len(),
            fmt_mm(quantile(
                &on_runs.iter().map(|r| r.correction_log.len() as f64).collect::<Vec<_>>(),
                0.5
            )),
            fmt_mm(quantile(&all.iter().map(|c| c.jump_mm).collect::<Vec<_>>(), 0.5)),
            quantile(&all.iter().map(|c| c.turn_deg).collect::<Vec<_>>(), 0.5),
        );
        let _ = writeln!(
            s,
            "- position: {helped} of them ({}) brought the believed position closer to the true \
             one; median change of the position error {} mm (negative = better), sum over all \
             corrections {} mm;",
            share(helped),
            fmt_mm(quantile(&change, 0.5)),
            fmt_mm(change.iter().sum::<f64>()),
        );
        let _ = writeln!(
            s,
            "- heading: {helped_head} ({}) brought the believed heading closer; median change \
             of the heading error {:.2}°, sum {:.1}°.\n",
            share(helped_head),
            quantile(&head_change, 0.5),
            head_change.iter().sum::<f64>(),
        );
        let win = windows(&all, &exp.checkpoints);
        let _ = writeln!(
            s,
            "| corrections made | count | position closer | sum of position changes, mm | heading closer | sum of heading changes, ° | median jump, mm |"
        );
        let _ = writeln!(s, "|---|---|---|---|---|---|---|");
        for w in &win {
            let pct = |k: usize| {
                fmt_pct(if w.n == 0 {
                    f64::NAN
                } else {
                    k as f64 / w.n as f64
                })
            };
            let _ = writeln!(
                s,
                "| {:.0}–{:.0} s | {} | {} | {} | {} | {:.1} | {} |",
                w.from,
                w.to,
                w.n,
                pct(w.helped),
                fmt_mm(w.sum_pos_mm),
                pct(w.helped_head),
                w.sum_head_deg,
                fmt_mm(w.median_jump_mm)
            );
        }
        let _ = writeln!(s);
        let hurts_at = checkpoints_where(exp, false);
        if both && !hurts_at.is_empty() {
            let phantoms = quantile(
                &map_scores(exp, true)
                    .iter()
                    .map(|m| 1.0 - m.matched_share())
                    .collect::<Vec<_>>(),
                0.5,
            );
            let last = win.iter().rev().find(|w| w.n > 0);
            let first = win.iter().find(|w| w.n > 0);
            let _ = writeln!(
                s,
                "### Why the rules do not help at {}
",
                {
                    hurts_at
                        .iter()
                        .map(|t| format!("{t:.0} s"))
                        .collect::<Vec<_>>()
                        .join(" and ")
                }
            );
            if let (Some(f), Some(l)) = (first, last) {
                let _ = writeln!(
                    s,
                    "The numbers above: in {:.0}–{:.0} s, {} of the {} corrections moved the \
                     believed position closer to the truth (a coin flip gives 50 %), and \
                     together they moved it {} mm {}; the corrections grow (median jump {} mm \
                     in {:.0}–{:.0} s, {} mm in {:.0}–{:.0} s), while the map fills with walls \
                     that match no true wall ({} of the walls in memory at the end, median over \
                     seeds).\n",
                    l.from,
                    l.to,
                    l.helped,
                    l.n,
                    fmt_mm(l.sum_pos_mm.abs()),
                    if l.sum_pos_mm > 0.0 {
                        "further away"
                    } else {
                        "closer"
                    },
                    fmt_mm(f.median_jump_mm),
                    f.from,
                    f.to,
                    fmt_mm(l.median_jump_mm),
                    l.from,
                    l.to,
                    fmt_pct(phantoms)
                );
            }
            let _ = writeln!(
                s,
                "Our reading, from the rules (`rules/README.md`): a correction compares a newly \
                 extracted wall with a remembered wall of an earlier time (hypothesis 2), trusts \
                 the earlier one, and moves the believed pose by their difference. A remembered \
                 wall was placed with the believed pose of its time, so it is only as right as \
                 the belief was then; once the belief has drifted, and once earlier corrections \
                 have moved it, the map holds displaced copies of the walls, and a correction \
                 against one of them is as likely to pull the belief away from the truth as \
                 towards it: the corrections become a random walk whose steps grow with the \
                 map's spread. The printed correction also moves the robot along its heading \
                 plus the walls' angle difference, not along the wall's normal (`rules/README.md`, \
                 section 5), which puts part of every correction in the wrong direction.\n"
            );
            let helps_at = checkpoints_where(exp, true);
            if let Some(f) = first.filter(|f| f.sum_head_deg < 0.0 && !helps_at.is_empty()) {
                let _ = writeln!(
                    s,
                    "Early on the rules do help (at {}): in {:.0}–{:.0} s the heading corrections \
                     reduce the heading error on net (sum {:.1}°), and a smaller heading error \
                     slows the growth of the position error, while the remembered walls are still \
                     near the true ones.\n",
                    helps_at
                        .iter()
                        .map(|t| format!("{t:.0} s"))
                        .collect::<Vec<_>>()
                        .join(", "),
                    f.from,
                    f.to,
                    f.sum_head_deg
                );
            }
        }
    }

    // Figures.
    let _ = writeln!(s, "## Figures\n");
    let _ = writeln!(
        s,
        "Each figure is written as SVG and as PNG (same name) into this folder.\n"
    );
    for f in figs {
        let _ = writeln!(
            s,
            "### `{}`\n\n{}\n\n![{}]({}.svg)\n\n[PNG]({}.png)\n",
            f.stem, f.caption, f.stem, f.stem, f.stem
        );
    }

    // Per seed.
    let _ = writeln!(s, "## Per seed\n");
    let _ = write!(s, "| seed |");
    for t in &exp.checkpoints {
        let _ = write!(s, " off at {t:.0} s | on at {t:.0} s |");
    }
    let _ = writeln!(
        s,
        " RMSE off | RMSE on | walls in memory (on) | corrections | helped |"
    );
    let _ = write!(s, "|---|");
    for _ in &exp.checkpoints {
        let _ = write!(s, "---|---|");
    }
    let _ = writeln!(s, "---|---|---|---|---|");
    for seed in opts.first_seed..opts.first_seed + opts.seeds {
        let run = |slam: bool| {
            exp.runs
                .iter()
                .find(|r| r.seed == seed && r.slam == slam && r.outcome.completed())
        };
        let (off, on) = (run(false), run(true));
        let _ = write!(s, "| {seed} |");
        for &t in &exp.checkpoints {
            let v =
                |r: Option<&RunSummary>| fmt_mm(r.and_then(|r| r.err_at(t)).unwrap_or(f64::NAN));
            let _ = write!(s, " {} | {} |", v(off), v(on));
        }
        let _ = writeln!(
            s,
            " {} | {} | {} | {} | {} |",
            fmt_mm(off.map_or(f64::NAN, |r| r.rmse_mm)),
            fmt_mm(on.map_or(f64::NAN, |r| r.rmse_mm)),
            on.map_or("–".into(), |r| r.final_walls.to_string()),
            on.map_or("–".into(), |r| r.correction_log.len().to_string()),
            on.map_or("–".into(), |r| r
                .correction_log
                .iter()
                .filter(|c| c.helped())
                .count()
                .to_string()),
        );
    }
    let _ = writeln!(s);

    // Timing.
    let _ = writeln!(s, "## Speed\n");
    for &slam in &conds {
        let wt = exp.column(slam, |r| r.wall_time_s);
        if wt.is_empty() {
            continue;
        }
        let _ = writeln!(
            s,
            "- SLAM {}: {:.2} s of wall time per run (median; max {:.2} s), {:.0}× real time.",
            condition_name(slam),
            quantile(&wt, 0.5),
            quantile(&wt, 1.0),
            exp.duration_s / quantile(&wt, 0.5)
        );
    }
    let _ = writeln!(
        s,
        "- The whole experiment: {:.1} s on {} thread(s).\n",
        exp.total_wall_s, exp.jobs
    );
    let _ = writeln!(
        s,
        "Data: `runs.csv` (one row per run), `steps-<on|off>-<seed>.csv` (per step), \
         `true-…`/`believed-….tum` (trajectories), `map-…csv` (the final map), \
         `corrections-on-<seed>.csv`, and `summary.md`."
    );
    s
}

/// Writes the figures and `report.md` into the experiment's output folder.
pub fn write_report(exp: &Experiment, opts: &Options) -> Result<Vec<FigureFile>, String> {
    let figs = write_figures(exp, &opts.out)?;
    let path = opts.out.join("report.md");
    crate::output_file::write(&path, report_md(exp, opts, &figs))?;
    Ok(figs)
}

#[cfg(test)]
mod tests {
    use super::*;

    use super::super::geom::Pose;
    use super::super::soar_loop::{Outcome, RunResult, RunStats, StepRecord};

    /// A made-up run whose position error at step k (from 0) is `slope · (k + 1)` mm.
    fn fake_run(seed: u64, slam: bool, steps: usize, slope: f64) -> RunSummary {
        let steps: Vec<StepRecord> = (0..steps)
            .map(|k| StepRecord {
                step: k as u64 + 1,
                time_s: (k + 1) as f64 * 0.1,
                true_pose: Pose::default(),
                believed: Pose::default(),
                pos_err_mm: slope * (k + 1) as f64,
                heading_err_deg: 0.0,
                walls_memory: k,
                walls_input: 0,
                walls_extracted: 2 * k as u64,
                corrections: 0,
                wm_size: 0,
                operators: String::new(),
            })
            .collect();
        let r = RunResult {
            seed,
            slam,
            outcome: Outcome::Completed,
            steps,
            stats: RunStats::default(),
            memory_walls: Vec::new(),
            productions: 0,
            load_log: String::new(),
            wall_time: std::time::Duration::ZERO,
            map_snapshots: Vec::new(),
            sample_extraction: None,
            io_log: Vec::new(),
        };
        RunSummary::of(&r, 0.1)
    }

    #[test]
    fn bands_are_quantiles_across_runs_at_each_kept_step() {
        let runs: Vec<RunSummary> = (1..=5).map(|s| fake_run(s, true, 100, s as f64)).collect();
        let refs: Vec<&RunSummary> = runs.iter().collect();
        let b = band_over_time(&refs, 10, |r, k| r.pos_err_mm[k]);
        assert_eq!(b.t.len(), 10);
        // Every 10th step, the last one kept: steps 10, 20, ... 100.
        assert!((b.t[0] - 1.0).abs() < 1e-9 && (b.t[9] - 10.0).abs() < 1e-9);
        // At step 100 the errors are 100, 200, ..., 500: median 300, 10 % 140, 90 % 460.
        assert!((b.median[9] - 300.0).abs() < 1e-9);
        assert!((b.lo[9] - 140.0).abs() < 1e-9 && (b.hi[9] - 460.0).abs() < 1e-9);
        // Runs of different lengths: only the steps all reached.
        let mut short = runs.clone();
        short.push(fake_run(9, true, 35, 1.0));
        let refs: Vec<&RunSummary> = short.iter().collect();
        let b = band_over_time(&refs, 1000, |r, k| r.walls_memory[k] as f64);
        assert_eq!(b.t.len(), 35);
        assert_eq!(b.median[34], 34.0);
        assert_eq!(
            band_over_time(&[], 10, |r, k| r.pos_err_mm[k]),
            Band::default()
        );
    }

    /// The numbers in a markdown table cell like `1467 [1311–1622]` or `2 of 3`.
    fn numbers(cell: &str) -> Vec<f64> {
        cell.split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-'))
            .filter_map(|t| t.parse::<f64>().ok())
            .collect()
    }

    /// A small real run (3 seeds × 12 s, both conditions): every figure is written in both
    /// formats and decodes, and the report's numbers agree with the per-step CSV files.
    #[test]
    fn a_small_run_writes_figures_and_a_consistent_report() {
        use super::super::experiment::{parse_options, run_experiment};
        let dir = std::env::temp_dir().join(format!("rusoar-report-test-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let args: Vec<String> = ["--seeds", "3", "--duration", "12", "--out"]
            .iter()
            .map(|s| s.to_string())
            .chain([dir.display().to_string()])
            .collect();
        let mut opts = parse_options(&args).unwrap();
        opts.jobs = 2;
        let exp = run_experiment(&opts, false).unwrap();
        assert!(exp.runs.iter().all(|r| r.outcome.completed()));
        for stem in [
            "fig-error",
            "fig-heading",
            "fig-walls",
            "fig-map",
            "fig-map-time",
            "fig-hough",
            "fig-paired",
        ] {
            let svg = std::fs::read_to_string(dir.join(format!("{stem}.svg"))).unwrap();
            assert!(
                svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"),
                "{stem}"
            );
            assert!(svg.len() > 2000, "{stem}.svg is nearly empty");
            let png = std::fs::read(dir.join(format!("{stem}.png"))).unwrap();
            let mut reader = png::Decoder::new(std::io::Cursor::new(png))
                .read_info()
                .unwrap();
            let mut buf = vec![0; reader.output_buffer_size().unwrap()];
            let info = reader.next_frame(&mut buf).unwrap();
            assert!(info.width >= 800 && info.height >= 400, "{stem}");
            // Not blank: some dark pixels (axes, text) and some coloured ones (data).
            let px = &buf[..info.buffer_size()];
            assert!(
                px.chunks(3).filter(|p| p.iter().all(|c| *c < 80)).count() > 500,
                "{stem}"
            );
            assert!(
                px.chunks(3)
                    .any(|p| (p[0] as i32 - p[2] as i32).abs() > 100),
                "{stem} has no colour"
            );
        }
        let report = std::fs::read_to_string(dir.join("report.md")).unwrap();
        assert!(report.contains("**A reduced run**"));
        assert!(
            !report.contains("     "),
            "a string literal kept its indentation"
        );
        assert!(report.contains("--seeds 3 --first-seed 1 --duration 12"));
        for stem in ["fig-error", "fig-map", "fig-hough"] {
            assert!(report.contains(&format!("![{stem}]({stem}.svg)")), "{stem}");
        }

        // Position error at 12 s, recomputed from the step files.
        let err_at_end = |slam: &str, seed: u64| -> f64 {
            let text =
                std::fs::read_to_string(dir.join(format!("steps-{slam}-{seed}.csv"))).unwrap();
            let mut lines = text.lines();
            let header: Vec<&str> = lines.next().unwrap().split(',').collect();
            let col = header.iter().position(|h| *h == "pos_err_mm").unwrap();
            let last = lines.last().unwrap();
            assert!(last.starts_with("120,12.0,"), "{last}");
            last.split(',').nth(col).unwrap().parse().unwrap()
        };
        let off: Vec<f64> = (1..=3).map(|s| err_at_end("off", s)).collect();
        let on: Vec<f64> = (1..=3).map(|s| err_at_end("on", s)).collect();
        let row = report
            .lines()
            .find(|l| l.starts_with("| 12 s |"))
            .expect("no row for 12 s");
        let cells: Vec<&str> = row.split('|').map(str::trim).collect();
        for (cell, v) in [(cells[2], &off), (cells[3], &on)] {
            let got = numbers(cell);
            let want = [quantile(v, 0.5), quantile(v, 0.1), quantile(v, 0.9)];
            assert_eq!(got.len(), 3, "{cell}");
            for (g, w) in got.iter().zip(want) {
                assert!((g - w).abs() <= 1.0, "{row}: {g} vs {w}");
            }
        }
        let better = off.iter().zip(&on).filter(|(a, b)| b < a).count();
        assert_eq!(numbers(cells[4]), vec![better as f64, 3.0], "{row}");

        // Corrections: the report's count is the number of rows in the correction files.
        let rows: usize = (1..=3)
            .map(|s| {
                let t =
                    std::fs::read_to_string(dir.join(format!("corrections-on-{s}.csv"))).unwrap();
                t.lines().count() - 1
            })
            .sum();
        assert!(
            report.contains(&format!("(`setOdometry`) {rows} times over 3 runs")),
            "{rows}"
        );
        // Walls in memory per seed: as in runs.csv.
        let runs = std::fs::read_to_string(dir.join("runs.csv")).unwrap();
        for line in runs.lines().skip(1).filter(|l| l.starts_with("on,")) {
            let f: Vec<&str> = line.split(',').collect();
            let (seed, walls) = (f[1], f[10]);
            let per_seed = report
                .lines()
                .find(|l| l.starts_with(&format!("| {seed} |")))
                .unwrap();
            let c: Vec<&str> = per_seed.split('|').map(str::trim).collect();
            assert_eq!(c[6], walls, "{per_seed}");
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn corrections_are_summed_per_window_between_checkpoints() {
        let c = |t: f64, before: f64, after: f64, hb: f64, ha: f64| Correction {
            step: (t * 10.0) as u64,
            time_s: t,
            jump_mm: (after - before).abs(),
            turn_deg: (ha - hb).abs(),
            err_before_mm: before,
            err_after_mm: after,
            head_before_deg: hb,
            head_after_deg: ha,
            by: Default::default(),
        };
        let all = [
            c(10.0, 100.0, 50.0, 5.0, 4.0),
            c(60.0, 100.0, 120.0, 5.0, 6.0),
            c(61.0, 300.0, 100.0, 2.0, 1.0),
            c(500.0, 0.0, 10.0, 1.0, 1.0),
        ];
        let refs: Vec<&Correction> = all.iter().collect();
        let w = windows(&refs, &[60.0, 300.0, 600.0]);
        assert_eq!(w.len(), 3);
        assert_eq!((w[0].from, w[0].to, w[0].n, w[0].helped), (0.0, 60.0, 2, 1));
        assert_eq!((w[0].sum_pos_mm, w[0].sum_head_deg), (-30.0, 0.0));
        assert_eq!((w[1].n, w[1].helped, w[1].helped_head), (1, 1, 1));
        assert_eq!((w[2].n, w[2].helped, w[2].sum_pos_mm), (1, 0, 10.0));
        assert_eq!(w[0].median_jump_mm, 35.0);
    }

    /// Runs that fail (here: no rules) still give a report and figures, saying what happened,
    /// with no NaN in the text.
    #[test]
    fn failed_runs_give_a_plain_report() {
        use super::super::experiment::{parse_options, run_experiment};
        let dir = std::env::temp_dir().join(format!("rusoar-report-fail-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let args: Vec<String> = [
            "--seeds",
            "1",
            "--duration",
            "1",
            "--rules",
            "/nonexistent",
            "--slam",
            "both",
            "--out",
        ]
        .iter()
        .map(|s| s.to_string())
        .chain([dir.display().to_string()])
        .collect();
        let exp = run_experiment(&parse_options(&args).unwrap(), false).unwrap();
        assert!(exp.runs.iter().all(|r| !r.outcome.completed()));
        let report = std::fs::read_to_string(dir.join("report.md")).unwrap();
        assert!(report.contains("**2 run(s) did not complete**"), "{report}");
        assert!(report.contains("robotagent.soar"));
        assert!(report.contains("No seed completed in both conditions"));
        assert!(
            !report.contains("NaN") && !report.contains("inf"),
            "{report}"
        );
        assert!(dir.join("fig-error.svg").is_file() && dir.join("fig-error.png").is_file());
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn bin_widths_are_round() {
        assert_eq!(nice_bin(0.3), 1.0);
        assert_eq!(nice_bin(13.0), 20.0);
        assert_eq!(nice_bin(41.0), 50.0);
        assert_eq!(nice_bin(60.0), 100.0);
        assert_eq!(nice_bin(f64::NAN), 1.0);
    }

    #[test]
    fn verdicts_say_what_the_pairs_say() {
        let st = pair_stats(&[(1, 10.0, 5.0), (2, 10.0, 4.0), (3, 10.0, 20.0)]);
        assert_eq!((st.n, st.better, st.worse), (3, 2, 1));
        let v = verdict(&st);
        assert!(
            v.starts_with("lower with the SLAM rules in 2 of 3 seeds"),
            "{v}"
        );
        assert!(v.contains("smallest possible p is 0.250"), "{v}");
        let st = pair_stats(&[(1, 1.0, 2.0), (2, 1.0, 3.0)]);
        assert!(verdict(&st).starts_with("higher with the SLAM rules in every seed"));
        let pairs: Vec<Pair> = (0..8).map(|i| (i, 10.0, 1.0 + i as f64)).collect();
        assert!(verdict(&pair_stats(&pairs)).contains("significant at 5 %"));
        assert!(verdict(&pair_stats(&[])).contains("cannot be compared"));
        assert!((min_p(3) - 0.25).abs() < 1e-12);
    }
}
