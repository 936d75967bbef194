//! `rusoar slam --method dr,thesis,v2,ekf,oracle`: every localisation method over the same
//! seeds, one table (`comparison.md`, `comparison.csv`) and its figures (`fig-compare`: the
//! position error with lines at the targets; `fig-compare-heading`: the heading error;
//! `fig-compare-diff`: each method's paired difference from dead reckoning with its 95 %
//! bootstrap band, [`super::report::paired`]; each as `.svg` and `.png`). Each method's series is the position error (mm) and heading error (degrees) of
//! every step of every seed; the seeds pair the methods: the same seed gives the same true
//! path, odometry biases and sonar readings.
//!
//! Statistics: medians and 90 % quantiles over all steps of all seeds (the targets of
//! rules v2 are stated that way), the median over seeds of the error at the end with a
//! distribution-free 95 % confidence interval (order statistics of the binomial, Conover,
//! *Practical Nonparametric Statistics*, §3.2), and the exact two-sided Wilcoxon
//! signed-rank test of each method against dead reckoning on the per-seed median error.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use plotters::style::RGBColor;

use super::ekf::table::ErrorsBySeed;
use super::geom::Point;
pub use super::method::Method;
use super::report::figures::{save, Band, BandSeries, HLine, TimeBands};
use super::report::mapeval::{score, Gate};
use super::report::paired::difference_over_time;
use super::results::RunSummary;
use super::sonar::NoisePreset;
use super::stats::{p_is, quantile, wilcoxon};
use super::world::World;

/// A method's colour in the figure.
fn colour(m: Method) -> RGBColor {
    match m {
        Method::Dr => RGBColor(205, 65, 40),
        Method::Thesis => RGBColor(150, 90, 170),
        Method::V2 => RGBColor(35, 95, 200),
        Method::Ekf => RGBColor(60, 150, 70),
        Method::Oracle => RGBColor(120, 120, 120),
    }
}

/// What a Soar method's runs say beyond the errors: corrections and the map.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RuleFigures {
    /// `setOdometry` corrections over all seeds.
    pub corrections: usize,
    /// Those that brought the believed position closer to the true one.
    pub helped_position: usize,
    /// Those that brought the believed heading closer.
    pub helped_heading: usize,
    /// Those that brought either closer without taking the other further (a heading-only
    /// correction turns the pose about the robot and barely moves it).
    pub helped: usize,
    /// Walls in the map at the end, per seed.
    pub walls: Vec<usize>,
    /// Map walls within 100 mm and 2° of a true wall, over all seeds.
    pub walls_close: usize,
}

/// One method's errors, by seed.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    pub method: Method,
    pub pos: ErrorsBySeed,
    pub head: ErrorsBySeed,
    /// `None` for dead reckoning and the EKF.
    pub rules: Option<RuleFigures>,
}

impl Series {
    /// A Soar condition's runs (all with the same `slam` flag) as a series.
    pub fn of_runs(method: Method, runs: &[&RunSummary], world: &World) -> Self {
        let pos = runs
            .iter()
            .map(|r| (r.seed, r.pos_err_mm.clone()))
            .collect();
        let head = runs
            .iter()
            .map(|r| (r.seed, r.heading_err_deg.clone()))
            .collect();
        let rules = (method != Method::Dr).then(|| {
            let mut f = RuleFigures::default();
            let gate = Gate {
                r_mm: 100.0,
                th_deg: 2.0,
                beside_m: 0.5,
            };
            for r in runs {
                for c in &r.correction_log {
                    f.corrections += 1;
                    let pos = c.err_after_mm < c.err_before_mm;
                    let head = c.head_after_deg < c.head_before_deg;
                    f.helped_position += usize::from(pos);
                    f.helped_heading += usize::from(head);
                    let pos_kept = c.err_after_mm <= c.err_before_mm + 1.0;
                    let head_kept = c.head_after_deg <= c.head_before_deg + 0.05;
                    f.helped += usize::from((pos && head_kept) || (head && pos_kept));
                }
                let walls: Vec<(Point, Point)> = r
                    .memory_walls
                    .iter()
                    .map(|w| {
                        (
                            Point::new(w.start.0 / 1000.0, w.start.1 / 1000.0),
                            Point::new(w.end.0 / 1000.0, w.end.1 / 1000.0),
                        )
                    })
                    .collect();
                f.walls.push(walls.len());
                f.walls_close += score(&walls, &world.walls, gate).matched;
            }
            f
        });
        Series {
            method,
            pos,
            head,
            rules,
        }
    }

    fn pooled(e: &ErrorsBySeed) -> Vec<f64> {
        e.values().flatten().copied().collect()
    }

    fn finals(&self) -> Vec<f64> {
        self.pos
            .values()
            .filter_map(|v| v.last().copied())
            .collect()
    }

    fn per_seed_median(&self) -> BTreeMap<u64, f64> {
        self.pos
            .iter()
            .map(|(s, v)| (*s, quantile(v, 0.5)))
            .collect()
    }
}

/// The distribution-free 95 % confidence interval of the median of `v`: the order statistics
/// `(k, n + 1 − k)` with k the largest for which P(Binomial(n, ½) < k) ≤ 2.5 %.
pub fn median_ci(v: &[f64]) -> Option<(f64, f64)> {
    let mut s: Vec<f64> = v.iter().copied().filter(|x| !x.is_nan()).collect();
    s.sort_by(f64::total_cmp);
    let n = s.len();
    // P(B < k) for B ~ Binomial(n, 1/2), summed term by term.
    let mut k = 0usize;
    let mut below = 0.0;
    let mut term = 0.5f64.powi(n as i32);
    for j in 0..n {
        if below + term > 0.025 {
            break;
        }
        below += term;
        k = j + 1;
        term *= (n - j) as f64 / (j + 1) as f64;
    }
    (k >= 1 && k <= n + 1 - k).then(|| (s[k - 1], s[n - k]))
}

/// The targets rules v2 is held to (empty room, `ideal` sonar, 600 s, over all steps).
pub mod targets {
    /// Median position error, mm.
    pub const MEDIAN_MM: f64 = 300.0;
    /// 90th percentile of the position error, mm.
    pub const P90_MM: f64 = 600.0;
    /// Median heading error, degrees.
    pub const HEADING_DEG: f64 = 3.0;
    /// Dead reckoning's error at the end over this method's, medians over seeds.
    pub const FACTOR_BELOW_DR: f64 = 5.0;
    /// Share of corrections that bring the belief closer.
    pub const HELPED: f64 = 0.8;
    /// Walls in the map at the end.
    pub const WALLS: (usize, usize) = (4, 6);
    /// Share of map walls within 100 mm and 2° of a true wall.
    pub const CLOSE: f64 = 0.9;
    /// Median position error with the `realistic` sonar, mm.
    pub const REALISTIC_MEDIAN_MM: f64 = 500.0;
}

/// The targets that apply with sonar `noise`, as lines on the position figure (m) and on the
/// heading figure (degrees). The targets are stated for the `ideal` sonar, with one more for
/// the `realistic` one; the `pessimistic` sonar has none.
fn target_lines(noise: NoisePreset) -> (Vec<HLine>, Vec<HLine>) {
    use targets::*;
    let line = |label: String, value: f64, color: RGBColor| HLine {
        label,
        value,
        color,
    };
    let dark = RGBColor(40, 40, 40);
    let light = RGBColor(150, 150, 150);
    match noise {
        NoisePreset::Ideal => (
            vec![
                line(
                    format!("target: median ≤ {:.1} m", MEDIAN_MM / 1000.0),
                    MEDIAN_MM / 1000.0,
                    dark,
                ),
                line(
                    format!("target: 90 % ≤ {:.1} m", P90_MM / 1000.0),
                    P90_MM / 1000.0,
                    light,
                ),
            ],
            vec![line(
                format!("target: median ≤ {HEADING_DEG:.0}°"),
                HEADING_DEG,
                dark,
            )],
        ),
        NoisePreset::Realistic => (
            vec![line(
                format!(
                    "target (realistic sonar): median ≤ {:.1} m",
                    REALISTIC_MEDIAN_MM / 1000.0
                ),
                REALISTIC_MEDIAN_MM / 1000.0,
                dark,
            )],
            Vec::new(),
        ),
        NoisePreset::Pessimistic => (Vec::new(), Vec::new()),
    }
}

fn met(ok: bool) -> &'static str {
    if ok {
        "met"
    } else {
        "not met"
    }
}

/// `comparison.md`: the table, the paired tests against dead reckoning, the targets of rules
/// v2 when it ran, and the figure. `command` is the command line that made the runs.
pub fn markdown(series: &[Series], command: &str, setup: &str) -> String {
    let mut s = String::from("# Localisation methods, paired by seed\n\n");
    let seeds = series.first().map_or(0, |x| x.pos.len());
    let _ = writeln!(s, "{setup} {seeds} seed(s). Produced by `{command}`.\n");
    s.push_str(
        "Position error over all steps of all seeds (median and 90 %), heading error over all \
         steps (median), the error at the end (median over seeds, with its 95 % confidence \
         interval), and the per-seed median error against dead reckoning's (seeds lower, exact \
         Wilcoxon signed-rank p, two-sided).\n\n",
    );
    s.push_str(
        "| method | median error | 90 % | heading median | error at the end [95 % CI] | × below dead reckoning at the end | seeds lower than DR | p |\n\
         |---|---|---|---|---|---|---|---|\n",
    );
    let dr = series.iter().find(|x| x.method == Method::Dr);
    let dr_final = dr.map(|d| quantile(&d.finals(), 0.5));
    let dr_medians = dr.map(Series::per_seed_median);
    for x in series {
        let pos = Series::pooled(&x.pos);
        let head = Series::pooled(&x.head);
        let finals = x.finals();
        let fin = quantile(&finals, 0.5);
        let ci = median_ci(&finals).map_or("–".into(), |(a, b)| format!("{a:.0}–{b:.0}"));
        let factor = match dr_final {
            Some(d) if x.method != Method::Dr && fin > 0.0 => format!("{:.1}", d / fin),
            _ => "–".into(),
        };
        let (lower, p) = match (&dr_medians, x.method) {
            (Some(d), m) if m != Method::Dr => {
                let mine = x.per_seed_median();
                let diffs: Vec<f64> = mine
                    .iter()
                    .filter_map(|(seed, v)| Some(v - d.get(seed)?))
                    .collect();
                let lower = diffs.iter().filter(|v| **v < 0.0).count();
                (
                    format!("{lower} of {}", diffs.len()),
                    wilcoxon(&diffs).map_or("–".into(), |(_, _, p)| p_is(p)),
                )
            }
            _ => ("–".into(), "–".into()),
        };
        let _ = writeln!(
            s,
            "| {} | {:.0} mm | {:.0} mm | {:.2}° | {fin:.0} mm [{ci}] | {factor} | {lower} | {p} |",
            x.method.label(),
            quantile(&pos, 0.5),
            quantile(&pos, 0.9),
            quantile(&head, 0.5),
        );
    }
    let with_rules: Vec<&Series> = series.iter().filter(|x| x.rules.is_some()).collect();
    if !with_rules.is_empty() {
        s.push_str(
            "\n| rules | corrections | moved the position closer | moved the heading closer | \
             moved the belief closer | walls at the end, median [range] | walls within 100 mm \
             and 2° of a true wall |\n|---|---|---|---|---|---|---|\n",
        );
        for x in &with_rules {
            let Some(f) = &x.rules else { continue };
            let share = |k: usize| 100.0 * k as f64 / f.corrections.max(1) as f64;
            let walls: Vec<f64> = f.walls.iter().map(|w| *w as f64).collect();
            let total: usize = f.walls.iter().sum();
            let _ = writeln!(
                s,
                "| {} | {} | {:.0} % | {:.0} % | {:.0} % | {:.0} [{}–{}] | {:.0} % |",
                x.method.label(),
                f.corrections,
                share(f.helped_position),
                share(f.helped_heading),
                share(f.helped),
                quantile(&walls, 0.5),
                f.walls.iter().min().unwrap_or(&0),
                f.walls.iter().max().unwrap_or(&0),
                100.0 * f.walls_close as f64 / total.max(1) as f64
            );
        }
        s.push_str(
            "\nA correction moved the belief closer when it brought the position or the heading \
             closer without taking the other more than 1 mm or 0.05° further.\n",
        );
    }
    if let Some(v2) = series.iter().find(|x| x.method == Method::V2) {
        s.push_str(&targets_md(v2, dr_final));
    }
    s.push_str(FIGURES_MD);
    s
}

/// The figures under `comparison.md`.
const FIGURES_MD: &str = "
![Position error against time, median and 10–90 % band over seeds, per method; dashed: the targets that apply](fig-compare.svg)

![Each method's position error minus dead reckoning's on the same seed, mean over seeds with its 95 % bootstrap band](fig-compare-diff.svg)

![Heading error against time, median and 10–90 % band over seeds, per method; dashed: the target, where one applies](fig-compare-heading.svg)

The difference from dead reckoning is taken seed by seed; its band is the 95 % percentile \
bootstrap interval of the mean over seeds (2,000 resamples of the seeds, drawn with a fixed \
seed, so the figure repeats byte for byte). Below 0 the method is closer to the truth than \
dead reckoning.
";

/// Rules v2 against its targets.
fn targets_md(v2: &Series, dr_final: Option<f64>) -> String {
    use targets::*;
    let pos = Series::pooled(&v2.pos);
    let head = Series::pooled(&v2.head);
    let (med, p90, hmed) = (
        quantile(&pos, 0.5),
        quantile(&pos, 0.9),
        quantile(&head, 0.5),
    );
    let fin = quantile(&v2.finals(), 0.5);
    let mut s =
        String::from("\n## Rules v2 against its targets\n\n| target | value | |\n|---|---|---|\n");
    let mut row = |name: String, value: String, ok: bool| {
        let _ = writeln!(s, "| {name} | {value} | {} |", met(ok));
    };
    row(
        format!("median position error ≤ {MEDIAN_MM:.0} mm"),
        format!("{med:.0} mm"),
        med <= MEDIAN_MM,
    );
    row(
        format!("90 % ≤ {P90_MM:.0} mm"),
        format!("{p90:.0} mm"),
        p90 <= P90_MM,
    );
    row(
        format!("median heading error ≤ {HEADING_DEG:.0}°"),
        format!("{hmed:.2}°"),
        hmed <= HEADING_DEG,
    );
    if let Some(d) = dr_final {
        row(
            format!("{FACTOR_BELOW_DR:.0}× below dead reckoning at the end"),
            format!("{:.1}×", d / fin),
            d >= FACTOR_BELOW_DR * fin,
        );
    }
    if let Some(f) = &v2.rules {
        let helped = f.helped as f64 / f.corrections.max(1) as f64;
        row(
            format!(
                "≥ {:.0} % of corrections move the belief closer",
                100.0 * HELPED
            ),
            format!("{:.0} %", 100.0 * helped),
            helped >= HELPED,
        );
        let in_range = f
            .walls
            .iter()
            .filter(|w| (WALLS.0..=WALLS.1).contains(*w))
            .count();
        row(
            format!("the map ends with {}–{} walls", WALLS.0, WALLS.1),
            format!("{in_range} of {} seeds", f.walls.len()),
            in_range == f.walls.len(),
        );
        let total: usize = f.walls.iter().sum();
        let close = f.walls_close as f64 / total.max(1) as f64;
        row(
            format!(
                "≥ {:.0} % of map walls within 100 mm and 2° of a true wall",
                100.0 * CLOSE
            ),
            format!("{:.0} %", 100.0 * close),
            close >= CLOSE,
        );
    }
    s
}

/// `comparison.csv`: one row per method and seed.
pub fn csv(series: &[Series]) -> String {
    let mut s = String::from("method,seed,median_mm,p90_mm,final_mm,heading_median_deg\n");
    for x in series {
        for (seed, v) in &x.pos {
            let h = x.head.get(seed).map_or(f64::NAN, |h| quantile(h, 0.5));
            let _ = writeln!(
                s,
                "{},{seed},{:.1},{:.1},{:.1},{:.3}",
                x.method.name(),
                quantile(v, 0.5),
                quantile(v, 0.9),
                v.last().copied().unwrap_or(f64::NAN),
                h
            );
        }
    }
    s
}

/// The median and 10–90 % band across seeds of `e`, every `every` steps of `dt` seconds.
fn band(e: &ErrorsBySeed, dt: f64, every: usize) -> Band {
    let n = e.values().map(Vec::len).min().unwrap_or(0);
    let mut b = Band {
        t: Vec::new(),
        median: Vec::new(),
        lo: Vec::new(),
        hi: Vec::new(),
    };
    for k in (every.max(1) - 1..n).step_by(every.max(1)) {
        let v: Vec<f64> = e.values().map(|x| x[k]).collect();
        b.t.push((k + 1) as f64 * dt);
        b.median.push(quantile(&v, 0.5));
        if e.len() > 1 {
            b.lo.push(quantile(&v, 0.1));
            b.hi.push(quantile(&v, 0.9));
        }
    }
    b
}

/// `fig-compare`, `fig-compare-heading` and, with dead reckoning among the methods,
/// `fig-compare-diff` (each `.svg` and `.png`), with lines at the targets that apply with sonar
/// `noise`.
pub fn figure(
    series: &[Series],
    dt: f64,
    noise: NoisePreset,
    dir: &std::path::Path,
) -> Result<(), String> {
    let metres = |e: &ErrorsBySeed| -> ErrorsBySeed {
        e.iter()
            .map(|(s, v)| (*s, v.iter().map(|e| e / 1000.0).collect()))
            .collect()
    };
    let pos: Vec<(Method, ErrorsBySeed)> =
        series.iter().map(|x| (x.method, metres(&x.pos))).collect();
    let (pos_targets, head_targets) = target_lines(noise);
    let pos_bands: Vec<(Method, Band)> = pos.iter().map(|(m, e)| (*m, band(e, dt, 10))).collect();
    let head_bands: Vec<(Method, Band)> = series
        .iter()
        .map(|x| (x.method, band(&x.head, dt, 10)))
        .collect();
    let fig = TimeBands {
        title: "Position error of each localisation method (paired by seed)".into(),
        x_label: "time, s".into(),
        y_label: "position error, m".into(),
        series: lines(&pos_bands),
        hlines: pos_targets,
    };
    save(&fig, dir, "fig-compare")?;
    let fig = TimeBands {
        title: "Heading error of each localisation method (paired by seed)".into(),
        x_label: "time, s".into(),
        y_label: "heading error, degrees".into(),
        series: lines(&head_bands),
        hlines: head_targets,
    };
    save(&fig, dir, "fig-compare-heading")?;
    let Some((_, dr)) = pos.iter().find(|(m, _)| *m == Method::Dr) else {
        return Ok(());
    };
    let diffs: Vec<(Method, Band)> = pos
        .iter()
        .filter(|(m, _)| *m != Method::Dr)
        .map(|(m, e)| {
            // Only the seeds both ran are paired.
            let pairs: Vec<(&[f64], &[f64])> = e
                .iter()
                .filter_map(|(s, v)| Some((v.as_slice(), dr.get(s)?.as_slice())))
                .collect();
            (*m, difference_over_time(&pairs, dt, DIFF_POINTS))
        })
        .collect();
    if diffs.is_empty() {
        return Ok(());
    }
    let seeds = dr.len();
    let fig = TimeBands {
        title: format!(
            "Position error minus dead reckoning's: mean of {seeds} seeds, 95 % bootstrap band"
        ),
        x_label: "time, s".into(),
        y_label: "method − dead reckoning, m".into(),
        series: lines(&diffs),
        hlines: Vec::new(),
    };
    save(&fig, dir, "fig-compare-diff").map(|_| ())
}

/// One line with its band per method.
fn lines(bands: &[(Method, Band)]) -> Vec<BandSeries<'_>> {
    bands
        .iter()
        .map(|(m, b)| BandSeries {
            label: m.label().into(),
            color: colour(*m),
            band: b,
            dashed: false,
        })
        .collect()
}

/// Points per curve of `fig-compare-diff`: as many as `fig-compare` draws (one per 10 steps of
/// a 600-s run).
const DIFF_POINTS: usize = 600;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_median_interval_of_twenty_values_is_the_sixth_and_fifteenth() {
        let v: Vec<f64> = (1..=20).map(f64::from).collect();
        assert_eq!(median_ci(&v), Some((6.0, 15.0)));
        assert_eq!(median_ci(&[1.0, 2.0]), None);
    }
}
