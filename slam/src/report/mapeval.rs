//! Scoring a wall map against the true walls: how many walls the map holds against the
//! room's 4, and the r and θ errors (|Δr|, |Δθ|) of each wall that matches a true wall.
//!
//! A map wall is a segment in the believed frame, which starts as the true frame (the believed
//! pose starts at the true start pose), so a wall recorded while the belief was off shows up as
//! displaced. Each map wall is compared with each true wall `a → b` in the true wall's own normal
//! form (unit direction u, normal n):
//!
//! - Δθ: the angle between the two lines, degrees in [0, 90];
//! - Δr: the signed offset of the map wall's midpoint from the true line, `n · (m − a)`, mm;
//!   for a parallel wall it is exactly the difference of the two lines' r;
//! - the midpoint must also lie beside the true segment: its position along u within the
//!   segment, give or take [`Gate::beside_m`].
//!
//! A map wall **matches** the true wall with the smallest `|Δr| / 100 mm + Δθ / 5°` among those
//! within the gate (`|Δr|` ≤ [`Gate::r_mm`], Δθ ≤ [`Gate::th_deg`]). Unmatched walls are
//! phantoms: misplaced copies of a wall or echoes.

use super::super::geom::{Point, Segment};
use super::super::stats::quantile;

/// How close a map wall must be to a true wall to count as that wall.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gate {
    /// Largest |Δr|, mm.
    pub r_mm: f64,
    /// Largest Δθ, degrees.
    pub th_deg: f64,
    /// How far beyond the true segment's ends the midpoint may lie, m.
    pub beside_m: f64,
}

impl Default for Gate {
    /// 300 mm and 10°: three times the pipeline's support band (100 mm) and the rules'
    /// `^th-tolerance` of 15° lowered to what the pipeline reaches on clean data (< 1°) with
    /// room for drift; 0.5 m beyond the ends (a robot length).
    fn default() -> Self {
        Gate {
            r_mm: 300.0,
            th_deg: 10.0,
            beside_m: 0.5,
        }
    }
}

/// Δr (mm, signed) and Δθ (degrees) of the map wall p–q against the true wall `t`, if the
/// midpoint lies beside `t`.
pub fn compare(p: Point, q: Point, t: &Segment, beside_m: f64) -> Option<(f64, f64)> {
    if ![p.x, p.y, q.x, q.y].iter().all(|c| c.is_finite()) {
        return None;
    }
    let len = t.length();
    if len <= 0.0 {
        return None;
    }
    let u = ((t.b.x - t.a.x) / len, (t.b.y - t.a.y) / len);
    let n = (-u.1, u.0);
    let m = ((p.x + q.x) / 2.0 - t.a.x, (p.y + q.y) / 2.0 - t.a.y);
    let along = m.0 * u.0 + m.1 * u.1;
    if along < -beside_m || along > len + beside_m {
        return None;
    }
    let dr = (m.0 * n.0 + m.1 * n.1) * 1000.0;
    let (dx, dy) = (q.x - p.x, q.y - p.y);
    let dl = dx.hypot(dy);
    let dth = if dl > 0.0 {
        let c = ((dx * u.0 + dy * u.1) / dl).abs().min(1.0);
        c.acos().to_degrees()
    } else {
        90.0
    };
    Some((dr, dth))
}

/// How a map compares with the true walls.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MapScore {
    /// Walls in the map.
    pub walls: usize,
    /// Map walls matching a true wall.
    pub matched: usize,
    /// True walls matched by at least one map wall.
    pub true_walls_found: usize,
    /// True walls.
    pub true_walls: usize,
    /// |Δr| of each matched wall, mm.
    pub abs_dr_mm: Vec<f64>,
    /// Δθ of each matched wall, degrees.
    pub dth_deg: Vec<f64>,
}

impl MapScore {
    /// Median |Δr| of the matched walls, mm (NaN without any).
    pub fn median_dr(&self) -> f64 {
        quantile(&self.abs_dr_mm, 0.5)
    }

    /// Median Δθ of the matched walls, degrees (NaN without any).
    pub fn median_dth(&self) -> f64 {
        quantile(&self.dth_deg, 0.5)
    }

    /// Share of map walls that match a true wall (NaN for an empty map).
    pub fn matched_share(&self) -> f64 {
        if self.walls == 0 {
            f64::NAN
        } else {
            self.matched as f64 / self.walls as f64
        }
    }
}

/// Scores the map walls (segments, m) against the true walls.
pub fn score(walls: &[(Point, Point)], truth: &[Segment], gate: Gate) -> MapScore {
    let mut s = MapScore {
        walls: walls.len(),
        true_walls: truth.len(),
        ..MapScore::default()
    };
    let mut found = vec![false; truth.len()];
    for &(p, q) in walls {
        let best = truth
            .iter()
            .enumerate()
            .filter_map(|(i, t)| compare(p, q, t, gate.beside_m).map(|(dr, dth)| (i, dr, dth)))
            .filter(|(_, dr, dth)| dr.abs() <= gate.r_mm && *dth <= gate.th_deg)
            .min_by(|a, b| {
                let cost = |x: &(usize, f64, f64)| x.1.abs() / 100.0 + x.2 / 5.0;
                cost(a).total_cmp(&cost(b))
            });
        if let Some((i, dr, dth)) = best {
            s.matched += 1;
            found[i] = true;
            s.abs_dr_mm.push(dr.abs());
            s.dth_deg.push(dth);
        }
    }
    s.true_walls_found = found.iter().filter(|f| **f).count();
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn room() -> Vec<Segment> {
        vec![
            Segment::new(-4.0, -3.0, 4.0, -3.0),
            Segment::new(4.0, -3.0, 4.0, 3.0),
            Segment::new(4.0, 3.0, -4.0, 3.0),
            Segment::new(-4.0, 3.0, -4.0, -3.0),
        ]
    }

    #[test]
    fn a_wall_parallel_to_a_true_wall_has_its_offset_as_dr() {
        let t = Segment::new(4.0, -3.0, 4.0, 3.0);
        let (dr, dth) = compare(Point::new(3.9, -1.0), Point::new(3.9, 1.0), &t, 0.5).unwrap();
        assert!(
            (dr.abs() - 100.0).abs() < 1e-9 && dth.abs() < 1e-9,
            "{dr} {dth}"
        );
        // Reversed direction: the same line.
        let (dr2, dth2) = compare(Point::new(3.9, 1.0), Point::new(3.9, -1.0), &t, 0.5).unwrap();
        assert!((dr - dr2).abs() < 1e-9 && dth2.abs() < 1e-9);
        // Tilted by 5°.
        let a = 5f64.to_radians();
        let (_, dth) = compare(
            Point::new(4.0 - a.sin(), -a.cos()),
            Point::new(4.0 + a.sin(), a.cos()),
            &t,
            0.5,
        )
        .unwrap();
        assert!((dth - 5.0).abs() < 1e-9, "{dth}");
        // Beyond the end of the true wall.
        assert!(compare(Point::new(3.9, 5.0), Point::new(3.9, 6.0), &t, 0.5).is_none());
        assert!(compare(Point::new(f64::NAN, 0.0), Point::new(3.9, 6.0), &t, 0.5).is_none());
    }

    #[test]
    fn a_map_scores_matches_phantoms_and_coverage() {
        let walls = vec![
            // Right wall, 50 mm inside, 1° off.
            (
                Point::new(3.95 - 1f64.to_radians().tan(), -1.0),
                Point::new(3.95 + 1f64.to_radians().tan(), 1.0),
            ),
            // Top wall, exact.
            (Point::new(-2.0, 3.0), Point::new(2.0, 3.0)),
            // A phantom in the middle of the room.
            (Point::new(0.0, 0.0), Point::new(1.0, 0.5)),
            // A copy of the right wall 1 m off: a phantom too.
            (Point::new(3.0, -1.0), Point::new(3.0, 1.0)),
        ];
        let s = score(&walls, &room(), Gate::default());
        assert_eq!(
            (s.walls, s.matched, s.true_walls_found, s.true_walls),
            (4, 2, 2, 4)
        );
        assert!((s.matched_share() - 0.5).abs() < 1e-12);
        let mut dr = s.abs_dr_mm.clone();
        dr.sort_by(f64::total_cmp);
        assert!(dr[0] < 1e-9 && (dr[1] - 50.0).abs() < 1e-6, "{dr:?}");
        assert!((s.dth_deg.iter().copied().fold(0.0, f64::max) - 1.0).abs() < 1e-9);
        assert!(score(&[], &room(), Gate::default())
            .matched_share()
            .is_nan());
    }
}
