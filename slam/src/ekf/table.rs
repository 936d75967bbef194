//! `ekf.md` and `ekf-runs.csv`: the EKF beside dead reckoning (and the thesis rules when they
//! ran), paired by seed, over all steps of all runs, with the NEES consistency test.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use super::super::stats::{p_is, quantile, wilcoxon};
use super::replay::{nees_bounds, EkfRun};

/// The targets the EKF is held to: the median position error over all steps
/// (mm), and the share of steps whose NEES lies inside its 95 % bounds.
pub const TARGET_MEDIAN_MM: f64 = 150.0;
pub const TARGET_NEES_SHARE: f64 = 0.8;

/// The position errors (mm) of every step of one method's runs, by seed.
pub type ErrorsBySeed = BTreeMap<u64, Vec<f64>>;

/// The consistency figures of a set of EKF runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Consistency {
    /// Share of (run, step) pairs whose NEES lies inside one run's 95 % bounds.
    pub per_run: f64,
    /// Share of steps whose NEES averaged over the runs lies inside that average's 95 % bounds.
    pub averaged: f64,
    /// Median NEES over all runs and steps (3 for a consistent filter).
    pub median: f64,
}

/// The NEES test over `runs`, step by step (steps beyond the shortest run are left out of the
/// averaged test).
pub fn consistency(runs: &[EkfRun]) -> Consistency {
    let (lo1, hi1) = nees_bounds(1);
    let all: Vec<f64> = runs
        .iter()
        .flat_map(|r| r.steps.iter().map(|s| s.nees))
        .collect();
    let inside = all.iter().filter(|n| **n >= lo1 && **n <= hi1).count();
    let steps = runs.iter().map(|r| r.steps.len()).min().unwrap_or(0);
    let (lo, hi) = nees_bounds(runs.len());
    let averaged_inside = (0..steps)
        .filter(|&k| {
            let m = runs.iter().map(|r| r.steps[k].nees).sum::<f64>() / runs.len() as f64;
            m >= lo && m <= hi
        })
        .count();
    Consistency {
        per_run: inside as f64 / all.len().max(1) as f64,
        averaged: averaged_inside as f64 / steps.max(1) as f64,
        median: quantile(&all, 0.5),
    }
}

fn pooled(errors: &ErrorsBySeed) -> Vec<f64> {
    errors.values().flatten().copied().collect()
}

fn met(ok: bool) -> &'static str {
    if ok {
        "met"
    } else {
        "not met"
    }
}

/// `ekf.md`: `command` is the command line that produced the runs.
pub fn markdown(
    runs: &[EkfRun],
    dr: &ErrorsBySeed,
    thesis: &ErrorsBySeed,
    command: &str,
) -> String {
    let mut s = String::from("# EKF SLAM on the Hough walls\n\n");
    let ekf: ErrorsBySeed = runs
        .iter()
        .map(|r| (r.seed, r.steps.iter().map(|k| k.pos_err_mm).collect()))
        .collect();
    let heading: Vec<f64> = runs
        .iter()
        .flat_map(|r| r.steps.iter().map(|k| k.heading_err_deg))
        .collect();
    let c = consistency(runs);
    let _ = writeln!(
        s,
        "{} seed(s), paired by seed. Produced by `{command}`.\n",
        runs.len()
    );
    s.push_str("| position error over all steps | median | 90 % |\n|---|---|---|\n");
    let mut rows = vec![("dead reckoning", dr)];
    if !thesis.is_empty() {
        rows.push(("thesis rules", thesis));
    }
    rows.push(("EKF", &ekf));
    for (name, e) in &rows {
        let v = pooled(e);
        let _ = writeln!(
            s,
            "| {name} | {:.0} mm | {:.0} mm |",
            quantile(&v, 0.5),
            quantile(&v, 0.9)
        );
    }
    let med = quantile(&pooled(&ekf), 0.5);
    let (lo1, hi1) = nees_bounds(1);
    let (lo, hi) = nees_bounds(runs.len());
    let _ = writeln!(
        s,
        "\nEKF heading error over all steps: median {:.2}°, 90 % {:.2}°.\n",
        quantile(&heading, 0.5),
        quantile(&heading, 0.9)
    );
    let _ = writeln!(
        s,
        "Pose NEES (3 degrees of freedom): median {:.2}; inside one run's 95 % bounds \
         [{lo1:.3}, {hi1:.3}] on {:.1} % of (run, step) pairs; the average over the {} runs \
         inside its 95 % bounds [{lo:.3}, {hi:.3}] on {:.1} % of steps.\n",
        c.median,
        100.0 * c.per_run,
        runs.len(),
        100.0 * c.averaged
    );
    let _ = writeln!(
        s,
        "Targets: median ≤ {TARGET_MEDIAN_MM:.0} mm: {} ({med:.0} mm); NEES inside its bounds on \
         ≥ {:.0} % of steps: {} per run, {} averaged over runs.\n",
        met(med <= TARGET_MEDIAN_MM),
        100.0 * TARGET_NEES_SHARE,
        met(c.per_run >= TARGET_NEES_SHARE),
        met(c.averaged >= TARGET_NEES_SHARE)
    );
    let diffs: Vec<f64> = runs
        .iter()
        .filter_map(|r| {
            let d = dr.get(&r.seed)?;
            Some(quantile(&ekf[&r.seed], 0.5) - quantile(d, 0.5))
        })
        .collect();
    if let Some((n, _, p)) = wilcoxon(&diffs) {
        let lower = diffs.iter().filter(|d| **d < 0.0).count();
        let _ = writeln!(
            s,
            "Per-seed median error lower with the EKF than with dead reckoning in {lower} of {n} \
             seeds (Wilcoxon {}).\n",
            p_is(p)
        );
    }
    s.push_str(
        "| seed | DR median | EKF median | EKF final | NEES in bounds | features | matched | started | dropped |\n\
         |---|---|---|---|---|---|---|---|---|\n",
    );
    for r in runs {
        let e = &ekf[&r.seed];
        let d = dr.get(&r.seed).map_or(f64::NAN, |d| quantile(d, 0.5));
        let _ = writeln!(
            s,
            "| {} | {d:.0} mm | {:.0} mm | {:.0} mm | {:.1} % | {} | {} | {} | {} |",
            r.seed,
            quantile(e, 0.5),
            e.last().copied().unwrap_or(f64::NAN),
            100.0 * r.nees_in_bounds(),
            r.map.len(),
            r.matched,
            r.started,
            r.rejected
        );
    }
    s
}

/// `ekf-runs.csv`: one row per EKF run.
pub fn runs_csv(runs: &[EkfRun], dr: &ErrorsBySeed) -> String {
    let mut s = String::from(
        "seed,dr_median_mm,ekf_median_mm,ekf_p90_mm,ekf_final_mm,nees_median,nees_in_bounds,features,matched,started,dropped\n",
    );
    for r in runs {
        let e: Vec<f64> = r.steps.iter().map(|k| k.pos_err_mm).collect();
        let nees: Vec<f64> = r.steps.iter().map(|k| k.nees).collect();
        let _ = writeln!(
            s,
            "{},{:.1},{:.1},{:.1},{:.1},{:.3},{:.4},{},{},{},{}",
            r.seed,
            dr.get(&r.seed).map_or(f64::NAN, |d| quantile(d, 0.5)),
            quantile(&e, 0.5),
            quantile(&e, 0.9),
            e.last().copied().unwrap_or(f64::NAN),
            quantile(&nees, 0.5),
            r.nees_in_bounds(),
            r.map.len(),
            r.matched,
            r.started,
            r.rejected
        );
    }
    s
}
