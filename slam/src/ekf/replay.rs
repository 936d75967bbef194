//! The EKF run over a dead-reckoning run (the thesis rules without the SLAM rules): its
//! believed pose is pure odometry, so consecutive believed poses are the odometry increments
//! the agent gets, and the walls the pipeline handed the agent are measured in that same frame.
//! Each wall is turned back into a robot-relative line with the believed pose of the step it
//! was extracted at, and fed to the filter after that step's prediction.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use super::super::fixed::push_fixed;
use super::super::geom::{normalize_angle, Pose};
use super::super::soar_loop::RunResult;
use super::chi2;
use super::filter::{Association, Ekf, Noise};
use super::line::Line;

/// Pose standard deviations the filter starts with (m, m, rad): the odometry starts at the
/// true pose, so only the first step's drift is unknown.
pub const START_SD: [f64; 3] = [0.01, 0.01, 0.01];

/// Walls shorter than this (m) are not given to the filter: a short Hough wall is as often a
/// corner's or a single sonar's echo as a stretch of wall.
pub const MIN_WALL_LENGTH_M: f64 = 1.0;

/// One step of the filter.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct EkfStep {
    pub step: u64,
    pub time_s: f64,
    pub true_pose: Pose,
    /// The filter's pose.
    pub estimate: Pose,
    /// Its standard deviations (m, m, rad).
    pub sd: [f64; 3],
    /// Position error, mm.
    pub pos_err_mm: f64,
    /// Heading error, degrees.
    pub heading_err_deg: f64,
    /// Normalised estimation error squared of the pose (3 degrees of freedom).
    pub nees: f64,
    pub features: usize,
}

/// A whole run of the filter.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct EkfRun {
    pub seed: u64,
    pub steps: Vec<EkfStep>,
    /// The features at the end, with their standard deviations (m, rad).
    pub map: Vec<(Line, (f64, f64))>,
    /// Measurements that updated a feature, started one, or were dropped between the gates.
    pub matched: u64,
    pub started: u64,
    pub rejected: u64,
}

/// Runs the filter over `run`, which must be a run without the SLAM rules (no `setOdometry`).
pub fn replay(run: &RunResult, noise: Noise) -> Result<EkfRun, String> {
    if run.slam {
        return Err(format!(
            "seed {}: the EKF needs a run without the SLAM rules, whose believed pose is pure odometry",
            run.seed
        ));
    }
    let Some(first) = run.steps.first() else {
        return Err(format!("seed {}: the run has no steps", run.seed));
    };
    let mut walls: BTreeMap<i64, Vec<Line>> = BTreeMap::new();
    for w in run
        .stats
        .extracted
        .iter()
        .filter(|w| w.length / 1000.0 >= MIN_WALL_LENGTH_M)
    {
        walls
            .entry(w.time)
            .or_default()
            .push(Line::new(w.line.0 / 1000.0, w.line.1.to_radians()));
    }
    let mut ekf = Ekf::new(first.believed, START_SD, noise);
    let mut out = EkfRun {
        seed: run.seed,
        steps: Vec::with_capacity(run.steps.len()),
        map: Vec::new(),
        matched: 0,
        started: 0,
        rejected: 0,
    };
    let mut prev = first.believed;
    for (k, s) in run.steps.iter().enumerate() {
        let cur = s.believed;
        if k > 0 {
            let rotation = normalize_angle(cur.th - prev.th);
            let mid = prev.th + rotation / 2.0;
            let distance = (cur.x - prev.x) * mid.cos() + (cur.y - prev.y) * mid.sin();
            ekf.predict(distance, rotation);
        }
        prev = cur;
        let upto = s.step as i64;
        let mut seen: Vec<Line> = Vec::new();
        if k == 0 {
            for ws in walls.range(..=upto).map(|(_, ws)| ws) {
                seen.extend(ws);
            }
        } else if let Some(ws) = walls.get(&upto) {
            seen.extend(ws);
        }
        for w in seen {
            match ekf.observe(w.to_robot(cur.x, cur.y, cur.th)) {
                Association::Matched(_) => out.matched += 1,
                Association::New(_) => out.started += 1,
                Association::Rejected => out.rejected += 1,
            }
        }
        let est = ekf.pose();
        let cov = ekf.pose_covariance();
        out.steps.push(EkfStep {
            step: s.step,
            time_s: s.time_s,
            true_pose: s.true_pose,
            estimate: est,
            sd: [cov[(0, 0)].sqrt(), cov[(1, 1)].sqrt(), cov[(2, 2)].sqrt()],
            pos_err_mm: s.true_pose.distance(&est) * 1000.0,
            heading_err_deg: s.true_pose.heading_error(&est).to_degrees(),
            nees: ekf.nees(&s.true_pose),
            features: ekf.features(),
        });
    }
    out.map = (0..ekf.features())
        .map(|i| (ekf.feature(i), ekf.feature_sd(i)))
        .collect();
    Ok(out)
}

/// The two-sided 95 % bounds of the pose NEES at one step averaged over `runs` runs (χ² with
/// 3·runs degrees of freedom, divided by runs).
pub fn nees_bounds(runs: usize) -> (f64, f64) {
    let dof = 3.0 * runs.max(1) as f64;
    let n = runs.max(1) as f64;
    (
        chi2::quantile(dof, 0.025) / n,
        chi2::quantile(dof, 0.975) / n,
    )
}

/// The header of `steps-ekf-<seed>.csv`.
pub const CSV_HEADER: &str = "step,time_s,true_x_mm,true_y_mm,true_th_deg,ekf_x_mm,ekf_y_mm,\
ekf_th_deg,pos_err_mm,heading_err_deg,sd_x_mm,sd_y_mm,sd_th_deg,nees,features";

impl EkfRun {
    /// The steps as CSV ([`CSV_HEADER`]).
    pub fn csv(&self) -> String {
        let mut s = String::with_capacity(128 * (self.steps.len() + 1));
        s.push_str(CSV_HEADER);
        s.push('\n');
        for k in &self.steps {
            let _ = write!(s, "{},", k.step);
            for (v, d) in [
                (k.time_s, 1),
                (k.true_pose.x_mm(), 1),
                (k.true_pose.y_mm(), 1),
                (k.true_pose.th_deg(), 2),
                (k.estimate.x_mm(), 1),
                (k.estimate.y_mm(), 1),
                (k.estimate.th_deg(), 2),
                (k.pos_err_mm, 1),
                (k.heading_err_deg, 2),
                (k.sd[0] * 1000.0, 1),
                (k.sd[1] * 1000.0, 1),
                (k.sd[2].to_degrees(), 2),
                (k.nees, 3),
            ] {
                push_fixed(&mut s, v, d);
                s.push(',');
            }
            let _ = writeln!(s, "{}", k.features);
        }
        s
    }

    /// The features at the end as CSV: r (mm), θ (degrees) and their standard deviations.
    pub fn map_csv(&self) -> String {
        let mut s = String::from("r_mm,th_deg,sd_r_mm,sd_th_deg\n");
        for (l, (sr, st)) in &self.map {
            let _ = writeln!(
                s,
                "{:.1},{:.2},{:.1},{:.2}",
                l.r * 1000.0,
                l.th.to_degrees(),
                sr * 1000.0,
                st.to_degrees()
            );
        }
        s
    }

    /// The share of steps whose NEES lies inside one run's 95 % bounds.
    pub fn nees_in_bounds(&self) -> f64 {
        let (lo, hi) = nees_bounds(1);
        let n = self.steps.len().max(1) as f64;
        self.steps
            .iter()
            .filter(|s| s.nees >= lo && s.nees <= hi)
            .count() as f64
            / n
    }
}

#[cfg(test)]
mod tests {
    use super::super::super::soar_loop::{run, LoopConfig, Outcome};
    use super::super::super::world::World;
    use super::*;

    #[test]
    fn a_run_with_the_slam_rules_is_refused_with_an_error() {
        let cfg = LoopConfig::new(World::empty_room(), 3, true, 5.0);
        let err = replay(&run(&cfg), Noise::STAGE2_HOUGH).unwrap_err();
        assert!(err.contains("without the SLAM rules"), "{err}");
    }

    #[test]
    fn the_filter_beats_dead_reckoning_and_repeats_itself() {
        let cfg = LoopConfig::new(World::empty_room(), 5, false, 120.0);
        let dr = run(&cfg);
        assert_eq!(dr.outcome, Outcome::Completed);
        let a = replay(&dr, Noise::STAGE2_HOUGH).unwrap();
        assert_eq!(a.steps.len(), dr.steps.len());
        assert!(a.started >= 1 && a.matched > a.started, "{a:?}");
        let last = |v: &[f64]| v.iter().rev().take(100).sum::<f64>() / 100.0;
        let ekf: Vec<f64> = a.steps.iter().map(|s| s.pos_err_mm).collect();
        let odo: Vec<f64> = dr.steps.iter().map(|s| s.pos_err_mm).collect();
        assert!(last(&ekf) < last(&odo), "{} vs {}", last(&ekf), last(&odo));
        let b = replay(&dr, Noise::STAGE2_HOUGH).unwrap();
        assert_eq!(a.csv(), b.csv());
        assert_eq!(a.map_csv(), b.map_csv());
    }
}
