//! Plane geometry shared by the simulator and the pipeline: poses, points, wall segments,
//! ray–segment intersection (the sonar rays are cast with it) and point–segment distance
//! (the Pioneer's collision test).
//!
//! Simulator units are metres and radians, x forward / y left as in ARIA (`params/p2dx.p`)
//! and Stage. The thesis's units (mm and degrees 0–359) are produced by the conversion
//! helpers on [`Pose`].

use std::f64::consts::{PI, TAU};

/// A point in the plane.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct Point {
    /// x coordinate.
    pub x: f64,
    /// y coordinate.
    pub y: f64,
}

impl Point {
    /// A point from its coordinates.
    pub const fn new(x: f64, y: f64) -> Self {
        Point { x, y }
    }

    /// Euclidean distance to `other`.
    pub fn distance(self, other: Point) -> f64 {
        (self.x - other.x).hypot(self.y - other.y)
    }
}

/// A robot pose: position in metres and heading in radians (counter-clockwise from +x).
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct Pose {
    /// x in metres.
    pub x: f64,
    /// y in metres.
    pub y: f64,
    /// Heading in radians.
    pub th: f64,
}

impl Pose {
    /// A pose from metres and radians.
    pub const fn new(x: f64, y: f64, th: f64) -> Self {
        Pose { x, y, th }
    }

    /// A pose from the thesis's units: millimetres and degrees.
    pub fn from_mm_deg(x_mm: f64, y_mm: f64, th_deg: f64) -> Self {
        Pose::new(x_mm / 1000.0, y_mm / 1000.0, th_deg.to_radians())
    }

    /// x in millimetres.
    pub fn x_mm(&self) -> f64 {
        self.x * 1000.0
    }

    /// y in millimetres.
    pub fn y_mm(&self) -> f64 {
        self.y * 1000.0
    }

    /// Heading in degrees, normalised to `[0, 360)`.
    pub fn th_deg(&self) -> f64 {
        deg_0_360(self.th.to_degrees())
    }

    /// The position as a point.
    pub fn position(&self) -> Point {
        Point::new(self.x, self.y)
    }

    /// Maps a point given in this pose's body frame (x forward, y left) to the parent frame.
    pub fn transform(&self, local: Point) -> Point {
        let (s, c) = self.th.sin_cos();
        Point::new(
            self.x + c * local.x - s * local.y,
            self.y + s * local.x + c * local.y,
        )
    }

    /// Distance between the positions of two poses.
    pub fn distance(&self, other: &Pose) -> f64 {
        self.position().distance(other.position())
    }

    /// Absolute heading difference in radians, in `[0, π]`.
    pub fn heading_error(&self, other: &Pose) -> f64 {
        normalize_angle(self.th - other.th).abs()
    }
}

/// Normalises an angle in radians to `(-π, π]`.
pub fn normalize_angle(a: f64) -> f64 {
    if !a.is_finite() {
        return a;
    }
    let mut r = a.rem_euclid(TAU);
    if r > PI {
        r -= TAU;
    }
    r
}

/// Normalises an angle in degrees to `[0, 360)`.
pub fn deg_0_360(d: f64) -> f64 {
    if !d.is_finite() {
        return d;
    }
    let r = d.rem_euclid(360.0);
    // rem_euclid can return 360.0 for tiny negative inputs through rounding.
    if r >= 360.0 {
        0.0
    } else {
        r
    }
}

/// A straight wall segment between two points.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Segment {
    /// First end point.
    pub a: Point,
    /// Second end point.
    pub b: Point,
}

impl Segment {
    /// A segment from its end coordinates.
    pub const fn new(x1: f64, y1: f64, x2: f64, y2: f64) -> Self {
        Segment {
            a: Point::new(x1, y1),
            b: Point::new(x2, y2),
        }
    }

    /// Length of the segment.
    pub fn length(&self) -> f64 {
        self.a.distance(self.b)
    }

    /// Shortest distance from `p` to the segment.
    pub fn distance_to(&self, p: Point) -> f64 {
        let (dx, dy) = (self.b.x - self.a.x, self.b.y - self.a.y);
        let len2 = dx * dx + dy * dy;
        let t = if len2 > 0.0 {
            (((p.x - self.a.x) * dx + (p.y - self.a.y) * dy) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        p.distance(Point::new(self.a.x + t * dx, self.a.y + t * dy))
    }

    /// Where the ray `origin + t·(cos angle, sin angle)`, `t ≥ 0`, first meets the segment:
    /// the distance `t` and the cosine of the incidence angle (between the ray and the wall's
    /// normal; 1 for a head-on hit, near 0 at grazing incidence).
    pub fn ray_hit(&self, origin: Point, angle: f64) -> Option<RayHit> {
        let (dy, dx) = angle.sin_cos();
        self.ray_hit_dir(origin, dx, dy)
    }

    /// [`Segment::ray_hit`] with the ray's unit direction `(dx, dy)` given.
    pub fn ray_hit_dir(&self, origin: Point, dx: f64, dy: f64) -> Option<RayHit> {
        let (ex, ey) = (self.b.x - self.a.x, self.b.y - self.a.y);
        let denom = dx * ey - dy * ex;
        let len2 = ex * ex + ey * ey;
        if len2 == 0.0 || denom * denom < 1e-24 * len2 {
            return None; // parallel (or degenerate): no single hit point
        }
        let (wx, wy) = (self.a.x - origin.x, self.a.y - origin.y);
        let t = (wx * ey - wy * ex) / denom;
        let u = (wx * dy - wy * dx) / denom;
        if t < 0.0 || !(0.0..=1.0).contains(&u) {
            return None;
        }
        Some(RayHit {
            distance: t,
            cos_incidence: denom.abs() / len2.sqrt(),
        })
    }

    /// Whether the closed segment from `p` to `q` crosses or touches this segment.
    pub fn crosses(&self, p: Point, q: Point) -> bool {
        fn orient(a: Point, b: Point, c: Point) -> f64 {
            (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)
        }
        let d1 = orient(self.a, self.b, p);
        let d2 = orient(self.a, self.b, q);
        let d3 = orient(p, q, self.a);
        let d4 = orient(p, q, self.b);
        if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
            && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
        {
            return true;
        }
        if d1 != 0.0 && d2 != 0.0 && d3 != 0.0 && d4 != 0.0 {
            return false;
        }
        // Touching or collinear cases.
        let pq = Segment { a: p, b: q };
        self.distance_to(p) == 0.0
            || self.distance_to(q) == 0.0
            || pq.distance_to(self.a) == 0.0
            || pq.distance_to(self.b) == 0.0
    }
}

/// The result of [`Segment::ray_hit`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RayHit {
    /// Distance from the ray origin to the hit point.
    pub distance: f64,
    /// |cos| of the angle between the ray and the wall normal.
    pub cos_incidence: f64,
}

/// Distance from `p` to the nearest of `walls` (infinity when there are none).
pub fn clearance(p: Point, walls: &[Segment]) -> f64 {
    walls
        .iter()
        .map(|w| w.distance_to(p))
        .fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn angles_normalise() {
        assert!((normalize_angle(3.0 * PI) - PI).abs() < 1e-12);
        assert!((normalize_angle(-PI / 2.0) + PI / 2.0).abs() < 1e-12);
        assert_eq!(deg_0_360(-90.0), 270.0);
        assert_eq!(deg_0_360(720.0), 0.0);
        assert_eq!(deg_0_360(-1e-17), 0.0);
    }

    #[test]
    fn ray_hits_wall_head_on() {
        let wall = Segment::new(2.0, -1.0, 2.0, 1.0);
        let hit = wall.ray_hit(Point::new(0.0, 0.0), 0.0).expect("hit");
        assert!((hit.distance - 2.0).abs() < 1e-12);
        assert!((hit.cos_incidence - 1.0).abs() < 1e-12);
        // 45 degrees: distance 2·√2, incidence cos = cos 45°.
        let hit = wall.ray_hit(Point::new(0.0, -1.0), PI / 4.0).expect("hit");
        assert!((hit.distance - 2.0 * 2f64.sqrt()).abs() < 1e-12);
        assert!((hit.cos_incidence - (PI / 4.0).cos()).abs() < 1e-12);
        // Away from the wall, parallel, or past its end: no hit.
        assert!(wall.ray_hit(Point::new(0.0, 0.0), PI).is_none());
        assert!(wall.ray_hit(Point::new(0.0, 0.0), PI / 2.0).is_none());
        assert!(wall.ray_hit(Point::new(0.0, 0.0), 1.2).is_none());
    }

    #[test]
    fn segment_distance_and_crossing() {
        let wall = Segment::new(0.0, 0.0, 4.0, 0.0);
        assert!((wall.distance_to(Point::new(2.0, 1.5)) - 1.5).abs() < 1e-12);
        assert!((wall.distance_to(Point::new(7.0, 4.0)) - 5.0).abs() < 1e-12);
        assert!(wall.crosses(Point::new(1.0, -1.0), Point::new(1.0, 1.0)));
        assert!(!wall.crosses(Point::new(1.0, 0.5), Point::new(1.0, 1.0)));
        assert!(wall.crosses(Point::new(1.0, 0.0), Point::new(1.0, 1.0)));
    }

    #[test]
    fn pose_units_and_transform() {
        let p = Pose::from_mm_deg(1500.0, -200.0, 450.0);
        assert!((p.x - 1.5).abs() < 1e-12 && (p.y + 0.2).abs() < 1e-12);
        assert!((p.th_deg() - 90.0).abs() < 1e-9);
        let q = p.transform(Point::new(1.0, 0.0));
        assert!((q.x - 1.5).abs() < 1e-12 && (q.y - 0.8).abs() < 1e-12);
    }
}
