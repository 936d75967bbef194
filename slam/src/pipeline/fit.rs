//! Line fitting for the wall extractor: least squares on return positions, and the tangent fit
//! to the returns' visible arcs.
//!
//! The thesis takes a wall's (r, θ) from the middle of its Hough zone, which is quantised to the
//! bins (±25 mm, ±0.5°). These fits refine it (`Settings::refine`):
//!
//! - [`robust_fit`]: total least squares through the supporting returns' positions, with one
//!   round of outlier trimming (so that a neighbouring wall's returns near a corner do not tilt
//!   the line);
//! - [`tangent_fit`]: the line tangent to the visible arcs of the returns that face it. A sonar
//!   reports the distance to the nearest surface in its cone; for a flat wall whose normal lies
//!   inside the cone that is the perpendicular distance from the transducer (thesis Figure 17:
//!   the object lies somewhere on the return's *visible line*, and a wall seen head-on is tangent
//!   to it). Positions placed on the beam axis are biased towards the robot when the beam meets
//!   the wall obliquely, by up to 1 − cos(β/2) of the range; the tangent estimate is not.

use std::f64::consts::{PI, TAU};
use std::sync::LazyLock;

use super::convert::SonarPoint;

/// A refit further than this from the line it starts from, in degrees, is rejected (the returns
/// are then too bunched to fix a direction).
pub const MAX_TURN_DEG: f64 = 3.0;

/// Signed smallest difference `a − b` between two angles, radians, in `(−π, π]`.
pub fn angle_diff(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(TAU);
    if d > PI {
        d - TAU
    } else {
        d
    }
}

/// Total-least-squares line through `pts`: `(r, θ)` with `r = x cos θ + y sin θ ≥ 0`, θ in
/// radians `[0, 2π)`. `None` for fewer than two distinct points.
pub fn fit_line(pts: &[(f64, f64)]) -> Option<(f64, f64)> {
    if pts.len() < 2 {
        return None;
    }
    let n = pts.len() as f64;
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let (mut sxx, mut syy, mut sxy) = (0.0, 0.0, 0.0);
    for &(x, y) in pts {
        sxx += (x - mx) * (x - mx);
        syy += (y - my) * (y - my);
        sxy += (x - mx) * (y - my);
    }
    // (Also rejects NaN input.)
    if (sxx + syy).partial_cmp(&1e-9) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    let direction = 0.5 * (2.0 * sxy).atan2(sxx - syy);
    let normal = direction + PI / 2.0;
    let r = mx * normal.cos() + my * normal.sin();
    let (r, normal) = if r < 0.0 {
        (-r, normal + PI)
    } else {
        (r, normal)
    };
    Some((r, normal.rem_euclid(TAU)))
}

/// Whether two lines are within `MAX_TURN_DEG` of each other in direction (either normal).
fn close_direction(a: f64, b: f64) -> bool {
    let limit = MAX_TURN_DEG.to_radians();
    angle_diff(a, b).abs() <= limit || angle_diff(a, b + PI).abs() <= limit
}

/// [`fit_line`] unless it turns the line `(r, th)` by more than [`MAX_TURN_DEG`]; then only r
/// is re-estimated (mean signed distance along the normal θ).
fn guarded_fit(pts: &[(f64, f64)], r: f64, th: f64) -> (f64, f64) {
    match fit_line(pts) {
        Some((r2, th2)) if close_direction(th2, th) => (r2, th2),
        _ if !pts.is_empty() => {
            let (c, s) = (th.cos(), th.sin());
            let mean = pts.iter().map(|p| p.0 * c + p.1 * s).sum::<f64>() / pts.len() as f64;
            (mean, th)
        }
        _ => (r, th),
    }
}

/// The trimming limit for residuals: 2.5 robust standard deviations (1.4826 × the median
/// absolute residual, which outliers cannot inflate), and at least `floor`.
fn trim_limit(residuals: impl Iterator<Item = f64>, floor: f64) -> f64 {
    let mut abs: Vec<f64> = residuals.map(f64::abs).collect();
    if abs.is_empty() {
        return floor;
    }
    let mid = abs.len() / 2;
    let (_, median, _) = abs.select_nth_unstable_by(mid, f64::total_cmp);
    (2.5 * 1.4826 * *median).max(floor)
}

/// Total least squares near the line `(r, th)`, with trimming: points further from the current
/// fit than `trim_limit` (2.5 robust standard deviations, at least `floor`) are left out and the fit repeated, up to three times.
pub fn robust_fit(pts: &[(f64, f64)], r: f64, th: f64, floor: f64) -> (f64, f64) {
    let (mut r1, mut th1) = guarded_fit(pts, r, th);
    let mut kept = pts.len();
    for _ in 0..3 {
        let residual = |p: &(f64, f64)| p.0 * th1.cos() + p.1 * th1.sin() - r1;
        let limit = trim_limit(pts.iter().map(residual), floor);
        let inliers: Vec<(f64, f64)> = pts
            .iter()
            .copied()
            .filter(|p| residual(p).abs() <= limit)
            .collect();
        if inliers.len() < 2 || inliers.len() == kept {
            break;
        }
        kept = inliers.len();
        (r1, th1) = guarded_fit(&inliers, r, th);
    }
    (r1, th1)
}

/// A line `r = x cos θ + y sin θ` with its normal's cosine and sine.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Line {
    /// Distance parameter, mm (may be negative before [`Line::normalised`]).
    pub r: f64,
    /// Normal direction, radians.
    pub th: f64,
    c: f64,
    s: f64,
}

impl Line {
    /// The line `r = x cos th + y sin th`.
    pub fn new(r: f64, th: f64) -> Self {
        let (s, c) = th.sin_cos();
        Line { r, th, c, s }
    }

    /// The same line with r ≥ 0 and θ in `[0, 2π)`.
    pub fn normalised(self) -> Self {
        let (r, th) = normalise(self.r, self.th);
        Line::new(r, th)
    }

    /// Signed distance of `(x, y)` from the line, along the normal.
    pub fn distance(&self, x: f64, y: f64) -> f64 {
        x * self.c + y * self.s - self.r
    }

    /// Position of `(x, y)` along the line's direction `(−sin θ, cos θ)`.
    pub fn along(&self, x: f64, y: f64) -> f64 {
        -x * self.s + y * self.c
    }

    /// The point of the line at position `t` along it.
    pub fn point(&self, t: f64) -> (f64, f64) {
        (self.r * self.c - t * self.s, self.r * self.s + t * self.c)
    }
}

/// A sonar return prepared for fitting: position, transducer position, unit beam direction and
/// range (mm).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    /// Return position x.
    pub x: f64,
    /// Return position y.
    pub y: f64,
    /// Transducer x.
    pub sx: f64,
    /// Transducer y.
    pub sy: f64,
    /// Beam direction, cosine.
    pub hx: f64,
    /// Beam direction, sine.
    pub hy: f64,
    /// Range.
    pub range: f64,
}

impl From<&SonarPoint> for Ray {
    fn from(p: &SonarPoint) -> Self {
        let (hy, hx) = p.heading.sin_cos();
        Ray {
            x: p.x,
            y: p.y,
            sx: p.sensor_x,
            sy: p.sensor_y,
            hx,
            hy,
            range: p.range,
        }
    }
}

impl Ray {
    /// How this return sees `line`: `Some(sign)` when the line's normal, pointing from the
    /// transducer towards the line, lies inside the beam cone (`cos_half` = cosine of its
    /// half-width); `sign` = +1 when that normal is `+n(θ)`, −1 when it is `−n(θ)`. `None` when
    /// the beam meets the line obliquely.
    pub fn facing(&self, line: &Line, cos_half: f64) -> Option<f64> {
        let sign = if self.sx * line.c + self.sy * line.s <= line.r {
            1.0
        } else {
            -1.0
        };
        (sign * (self.hx * line.c + self.hy * line.s) >= cos_half).then_some(sign)
    }

    /// The r of the line with `line`'s normal that is tangent to this return's visible arc.
    pub fn tangent_r(&self, sign: f64, line: &Line) -> f64 {
        self.sx * line.c + self.sy * line.s + sign * self.range
    }

    /// Where this facing return touches a line with `line`'s normal: the foot of the
    /// perpendicular from its transducer.
    pub fn contact(&self, sign: f64, line: &Line) -> (f64, f64) {
        (
            self.sx + sign * self.range * line.c,
            self.sy + sign * self.range * line.s,
        )
    }
}

/// The line near the direction `th0` of `from` that best agrees with the tangent r of the facing returns
/// `set`: `r_i(θ) = sx_i cos θ + sy_i sin θ + sign_i·range_i` is linear in (cos θ, sin θ), so its
/// variance over the set is a quadratic form in them, evaluated from six moments for every θ
/// within [`MAX_TURN_DEG`] of `th0` in 0.05° steps. θ stays `th0` when the transducers are too
/// bunched along the line (under 300 mm apart, or fewer than 3) to observe it.
fn best_tangent_line(set: &[(Ray, f64)], from: &Line) -> Line {
    let th0 = from.th;
    let n = set.len().max(1) as f64;
    let z = |(p, sign): &(Ray, f64)| sign * p.range;
    let mx = set.iter().map(|(p, _)| p.sx).sum::<f64>() / n;
    let my = set.iter().map(|(p, _)| p.sy).sum::<f64>() / n;
    let mz = set.iter().map(z).sum::<f64>() / n;
    // `from` holds th0's sine and cosine already.
    let line0 = Line { r: 0.0, ..*from };
    let along = set.iter().map(|(p, _)| line0.along(p.sx, p.sy));
    let spread =
        along.clone().fold(f64::NEG_INFINITY, f64::max) - along.fold(f64::INFINITY, f64::min);
    let observable = spread >= 300.0;
    let th = if set.len() < 3 || !observable {
        th0
    } else {
        let (mut cxx, mut cyy, mut czz, mut cxy, mut cxz, mut cyz) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
        for e in set {
            let (dx, dy, dz) = (e.0.sx - mx, e.0.sy - my, z(e) - mz);
            cxx += dx * dx;
            cyy += dy * dy;
            czz += dz * dz;
            cxy += dx * dy;
            cxz += dx * dz;
            cyz += dy * dz;
        }
        let var = |c: f64, s: f64| {
            c * c * cxx + s * s * cyy + czz + 2.0 * (c * s * cxy + c * cxz + s * cyz)
        };
        // Scan θ = th0 − max_turn … th0 + max_turn, rotating (cos, sin) step by step.
        let steps = SCAN_STEPS;
        let step = MAX_TURN_DEG.to_radians() / steps as f64;
        let (ds, dc) = *STEP_TRIG;
        let (mut s, mut c) = (th0 - step * steps as f64).sin_cos();
        let (mut best, mut best_var) = (th0, f64::INFINITY);
        for i in -steps..=steps {
            let v = var(c, s);
            if v < best_var {
                (best, best_var) = (th0 + step * i as f64, v);
            }
            (c, s) = (c * dc - s * ds, s * dc + c * ds);
        }
        best
    };
    let (s, c) = if th.to_bits() == th0.to_bits() {
        (from.s, from.c)
    } else {
        th.sin_cos()
    };
    Line {
        r: mx * c + my * s + mz,
        th,
        c,
        s,
    }
}

/// [`best_tangent_line`] scans this many θ steps either side of its start.
const SCAN_STEPS: i32 = 60;

/// Sine and cosine of that θ step, computed once.
static STEP_TRIG: LazyLock<(f64, f64)> =
    LazyLock::new(|| (MAX_TURN_DEG.to_radians() / SCAN_STEPS as f64).sin_cos());

/// The line near `line0` tangent to the visible arcs of the returns of `rays` that face it
/// (`cos_half` = cosine of the beam's half-width), after one round of trimming (tangent r
/// further than `trim_limit` (2.5 robust standard deviations, at least `floor`) from the line's). `None` when no return faces the line.
pub fn tangent_fit(rays: &[Ray], line0: &Line, cos_half: f64, floor: f64) -> Option<Line> {
    let mut set: Vec<(Ray, f64)> = rays
        .iter()
        .filter_map(|p| p.facing(line0, cos_half).map(|s| (*p, s)))
        .collect();
    if set.is_empty() {
        return None;
    }
    let line1 = best_tangent_line(&set, line0);
    let limit = trim_limit(
        set.iter().map(|(p, s)| p.tangent_r(*s, &line1) - line1.r),
        floor,
    );
    set.retain(|(p, s)| (p.tangent_r(*s, &line1) - line1.r).abs() <= limit);
    if set.is_empty() {
        return Some(line1.normalised());
    }
    Some(best_tangent_line(&set, &line1).normalised())
}

/// Folds a line to r ≥ 0 and θ in `[0, 2π)`.
pub fn normalise(r: f64, th: f64) -> (f64, f64) {
    if r < 0.0 {
        (-r, (th + PI).rem_euclid(TAU))
    } else {
        (r, th.rem_euclid(TAU))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A return from a transducer at `sensor` looking along `heading_deg`, with `range`.
    fn ret(sensor: (f64, f64), heading_deg: f64, range: f64) -> SonarPoint {
        let h = heading_deg.to_radians();
        SonarPoint {
            x: sensor.0 + range * h.cos(),
            y: sensor.1 + range * h.sin(),
            sensor_x: sensor.0,
            sensor_y: sensor.1,
            heading: h,
            range,
        }
    }

    #[test]
    fn fit_line_recovers_lines() {
        let (r, th) = fit_line(&[(1000.0, -500.0), (1000.0, 0.0), (1000.0, 800.0)]).expect("fit");
        assert!((r - 1000.0).abs() < 1e-9 && angle_diff(th, 0.0).abs() < 1e-12);
        let (r, th) = fit_line(&[(-3.0, -2000.0), (5.0, -2000.0)]).expect("fit");
        assert!((r - 2000.0).abs() < 1e-9 && angle_diff(th, 1.5 * PI).abs() < 1e-12);
        assert!(fit_line(&[(1.0, 1.0), (1.0, 1.0)]).is_none());
        assert!(fit_line(&[(1.0, 1.0)]).is_none());
    }

    #[test]
    fn robust_fit_ignores_a_corner() {
        // The wall x = 2000 with a few returns of the perpendicular wall y = 1000 near the corner.
        let mut pts: Vec<(f64, f64)> = (0..40).map(|i| (2000.0, i as f64 * 25.0)).collect();
        pts.extend([(1950.0, 1000.0), (1920.0, 1000.0), (1960.0, 1000.0)]);
        let (r, th) = robust_fit(&pts, 1990.0, 0.01, 25.0);
        assert!(
            (r - 2000.0).abs() < 0.5 && angle_diff(th, 0.0).abs() < 1e-3,
            "{r} {th}"
        );
        // A bunched cluster cannot turn the line by more than MAX_TURN_DEG.
        let (_, th) = robust_fit(
            &[(0.0, 1000.0), (10.0, 1003.0), (20.0, 990.0)],
            1000.0,
            PI / 2.0,
            25.0,
        );
        assert!(angle_diff(th, PI / 2.0).abs() <= MAX_TURN_DEG.to_radians() + 1e-12);
    }

    #[test]
    fn facing_depends_on_the_beam_cone() {
        let cos_half = 12.5f64.to_radians().cos();
        let wall = Line::new(2000.0, 0.0);
        // Wall x = 2000; a transducer at the origin looking at 10° faces it, at 20° it does not.
        let ray = |s, h, r| Ray::from(&ret(s, h, r));
        assert_eq!(
            ray((0.0, 0.0), 10.0, 2031.0).facing(&wall, cos_half),
            Some(1.0)
        );
        assert_eq!(ray((0.0, 0.0), 20.0, 2050.0).facing(&wall, cos_half), None);
        // From beyond the wall, looking back (−x), the normal is −n.
        assert_eq!(
            ray((3000.0, 0.0), 175.0, 1000.0).facing(&wall, cos_half),
            Some(-1.0)
        );
    }

    #[test]
    fn line_helpers() {
        let l = Line::new(-5.0, 0.5).normalised();
        assert!((l.r - 5.0).abs() < 1e-12 && (l.th - (0.5 + PI)).abs() < 1e-12);
        let l = Line::new(1000.0, PI / 2.0);
        assert!((l.distance(30.0, 1200.0) - 200.0).abs() < 1e-9);
        assert!((l.along(30.0, 1200.0) + 30.0).abs() < 1e-9);
        let (x, y) = l.point(-30.0);
        assert!((x - 30.0).abs() < 1e-9 && (y - 1000.0).abs() < 1e-9);
    }

    #[test]
    fn tangent_fit_removes_oblique_bias() {
        // A robot driving along y = 0 sees the wall y = 1500 with a side sonar (90°, head-on)
        // and a 50° sonar whose nearest echo comes through its cone edge at 62.5°: its range is
        // 1500 / sin 62.5°, and placed on the axis the return sits 1500·sin50/sin62.5 ≈ 1296 mm
        // from the robot's line: 204 mm short of the wall.
        let mut pts = Vec::new();
        for i in 0..30 {
            let x = i as f64 * 100.0;
            pts.push(ret((x, 0.0), 90.0, 1500.0));
            pts.push(ret((x, 0.0), 50.0, 1500.0 / 62.5f64.to_radians().sin()));
        }
        let xy: Vec<(f64, f64)> = pts.iter().map(|p| (p.x, p.y)).collect();
        let (r_pts, _) = robust_fit(&xy, 1450.0, PI / 2.0, 25.0);
        assert!(r_pts < 1450.0, "axis positions are biased: {r_pts}");
        let rays: Vec<Ray> = pts.iter().map(Ray::from).collect();
        let cos_half = 12.5f64.to_radians().cos();
        let fit =
            tangent_fit(&rays, &Line::new(1450.0, PI / 2.0 + 0.02), cos_half, 25.0).expect("fit");
        assert!((fit.r - 1500.0).abs() < 0.5, "r {}", fit.r);
        assert!(
            angle_diff(fit.th, PI / 2.0).abs() < 0.06f64.to_radians(),
            "θ {}",
            fit.th.to_degrees()
        );
        let (cx, cy) = rays[0].contact(1.0, &fit);
        assert!(cx.abs() < 5.0 && (cy - 1500.0).abs() < 0.5);
    }

    #[test]
    fn tangent_fit_needs_facing_returns() {
        let rays = [Ray::from(&ret((0.0, 0.0), 50.0, 2000.0))];
        let cos_half = 12.5f64.to_radians().cos();
        assert!(tangent_fit(&rays, &Line::new(1500.0, PI / 2.0), cos_half, 25.0).is_none());
    }
}
