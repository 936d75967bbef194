//! The Wall element the pipeline hands to Soar, with the thesis's fields.
//!
//! Thesis, "Hough-Transform Java / Extracting Wall" and "Working Memory Structure": each Wall
//! carries `^R` (integer distance of the line from the origin, mm), `^Th` (angle 0..359 of the
//! line's normal, i.e. the angle between the line and the Y axis), `^Start` and `^End`
//! (`^X ^Y` integers, mm), `^Ref` (`^X ^Y ^Th` of the robot when the wall was generated),
//! `^Length` (float) and `^Time` (integer time of generation).

use super::super::geom::{deg_0_360, Pose};

/// A point in integer millimetres (`^X`, `^Y`).
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Hash, Default, serde::Serialize, serde::Deserialize,
)]
pub struct PointMm {
    /// `^X`, mm.
    pub x: i64,
    /// `^Y`, mm.
    pub y: i64,
}

/// The robot pose a wall was generated from (`^Ref`): mm and degrees 0..359.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Hash, Default, serde::Serialize, serde::Deserialize,
)]
pub struct RefPose {
    /// `^X`, mm.
    pub x: i64,
    /// `^Y`, mm.
    pub y: i64,
    /// `^Th`, degrees 0..359.
    pub th: i64,
}

impl RefPose {
    /// The thesis's integer form of a (believed) pose.
    pub fn from_pose(p: &Pose) -> Self {
        RefPose {
            x: round_i64(p.x_mm()),
            y: round_i64(p.y_mm()),
            th: whole_degree(p.th.to_degrees()),
        }
    }
}

/// A wall element (`^wallData.Wall`).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Wall {
    /// `^R`: distance from the origin to the line, mm, ≥ 0.
    pub r: i64,
    /// `^Th`: direction of the line's normal, degrees 0..359 (`r = x·cos Th + y·sin Th`).
    pub th: i64,
    /// `^Start`: first end point, mm.
    pub start: PointMm,
    /// `^End`: second end point, mm.
    pub end: PointMm,
    /// `^Ref`: the robot's believed pose when the wall was generated.
    pub reference: RefPose,
    /// `^Length`: distance from Start to End, mm.
    pub length: f64,
    /// `^Time`: time of generation (the caller's clock, e.g. the simulation step).
    pub time: i64,
    /// The line before rounding: r in mm (≥ 0) and the normal angle in degrees `[0, 360)`.
    pub line: (f64, f64),
}

impl Wall {
    /// A wall on the line `r = x cos θ + y sin θ` (r mm, θ degrees) between the float end points
    /// `start` and `end` (mm). A negative r is folded to the opposite normal.
    pub fn new(
        r_mm: f64,
        theta_deg: f64,
        start: (f64, f64),
        end: (f64, f64),
        reference: RefPose,
        time: i64,
    ) -> Self {
        let (r_mm, theta_deg) = if r_mm < 0.0 {
            (-r_mm, deg_0_360(theta_deg + 180.0))
        } else {
            (r_mm, deg_0_360(theta_deg))
        };
        let start = PointMm {
            x: round_i64(start.0),
            y: round_i64(start.1),
        };
        let end = PointMm {
            x: round_i64(end.0),
            y: round_i64(end.1),
        };
        Wall {
            r: round_i64(r_mm),
            th: whole_degree(theta_deg),
            start,
            end,
            reference,
            length: length_mm(start, end),
            time,
            line: (r_mm, theta_deg),
        }
    }
}

/// Length of the segment between two integer points, mm (the thesis's `getlength`).
pub fn length_mm(a: PointMm, b: PointMm) -> f64 {
    ((a.x - b.x) as f64).hypot((a.y - b.y) as f64)
}

/// Rounds to the nearest integer, saturating (NaN gives 0).
fn round_i64(v: f64) -> i64 {
    v.round() as i64
}

/// A whole degree in 0..359.
fn whole_degree(deg: f64) -> i64 {
    round_i64(deg_0_360(deg)).rem_euclid(360)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fields_round_and_fold() {
        let w = Wall::new(
            -1234.6,
            359.7,
            (10.4, -3.5),
            (10.4, 2996.5),
            RefPose::from_pose(&Pose::from_mm_deg(100.0, 200.0, -90.0)),
            42,
        );
        assert_eq!(w.r, 1235);
        assert_eq!(w.th, 180);
        assert_eq!(w.start, PointMm { x: 10, y: -4 });
        assert_eq!(w.end, PointMm { x: 10, y: 2997 });
        assert_eq!(w.length, 3001.0);
        assert_eq!(
            w.reference,
            RefPose {
                x: 100,
                y: 200,
                th: 270
            }
        );
        assert_eq!(w.time, 42);
        let w = Wall::new(5.0, 359.7, (0.0, 0.0), (0.0, 0.0), RefPose::default(), 0);
        assert_eq!(w.th, 0);
    }
}
