//! The Pioneer 2-DX body: differential drive kinematics and collision with walls.
//!
//! Parameters: body radius 0.25 m (ARIA `RobotRadius 250`), cruise 0.3 m/s, in-place turns
//! at 40°/s, time step 0.1 s (Stage's `interval_sim 100`). Commands follow ARIA / the
//! thesis's output-link: set the translational velocity in mm/s, the rotational velocity in
//! °/s, or stop. Commands are clamped to ARIA's `MaxVelocity 2200` mm/s and
//! `MaxRVelocity 500` °/s.
//!
//! Collision: the body is a disc. A motion that would bring the disc closer than its radius to
//! any wall (deeper than it already is) is cut short where it touches, and the step reports a
//! stall, as Stage does; the robot never passes through a wall. Rotation in place is always
//! possible because it does not move the disc.

use super::geom::{clearance, Pose, Segment};

/// Body radius, m (ARIA `RobotRadius 250`).
pub const RADIUS_M: f64 = 0.25;
/// Cruise speed of the experiment, m/s.
pub const CRUISE_SPEED_M_S: f64 = 0.3;
/// In-place turning rate of the experiment, °/s.
pub const TURN_RATE_DEG_S: f64 = 40.0;
/// Simulation time step, s (Stage `interval_sim 100`).
pub const DEFAULT_DT_S: f64 = 0.1;
/// ARIA `MaxVelocity`, mm/s.
pub const MAX_VEL_MM_S: f64 = 2200.0;
/// ARIA `MaxRVelocity`, °/s.
pub const MAX_ROT_VEL_DEG_S: f64 = 500.0;

/// Longest translation integrated in one sub-step, m; well under the radius, so a thin wall
/// can never be jumped over.
const MAX_SUBSTEP_M: f64 = 0.05;
/// Largest rotation integrated in one sub-step, rad.
const MAX_SUBSTEP_RAD: f64 = 0.1;

/// What the body actually did during one step (the input of the odometry model).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Motion {
    /// Signed distance travelled along the path, m (negative when backing up).
    pub distance: f64,
    /// Signed rotation, rad (counter-clockwise positive).
    pub rotation: f64,
    /// Whether a wall cut the translation short.
    pub stalled: bool,
}

/// A simulated Pioneer 2-DX.
#[derive(Debug, Clone, PartialEq)]
pub struct Pioneer {
    pose: Pose,
    vel_m_s: f64,
    rot_rad_s: f64,
    stalled: bool,
}

fn finite_or_zero(v: f64) -> f64 {
    if v.is_finite() {
        v
    } else {
        0.0
    }
}

impl Pioneer {
    /// A stopped robot at `pose` (true pose, world frame).
    pub fn new(pose: Pose) -> Self {
        Pioneer {
            pose,
            vel_m_s: 0.0,
            rot_rad_s: 0.0,
            stalled: false,
        }
    }

    /// The true pose.
    pub fn pose(&self) -> Pose {
        self.pose
    }

    /// Sets the translational velocity, mm/s (clamped to ±2200; NaN counts as 0).
    pub fn set_vel_mm_s(&mut self, v: f64) {
        self.vel_m_s = finite_or_zero(v).clamp(-MAX_VEL_MM_S, MAX_VEL_MM_S) / 1000.0;
    }

    /// Sets the rotational velocity, °/s (clamped to ±500; NaN counts as 0).
    pub fn set_rot_vel_deg_s(&mut self, w: f64) {
        self.rot_rad_s = finite_or_zero(w)
            .clamp(-MAX_ROT_VEL_DEG_S, MAX_ROT_VEL_DEG_S)
            .to_radians();
    }

    /// Stops both translation and rotation.
    pub fn stop(&mut self) {
        self.vel_m_s = 0.0;
        self.rot_rad_s = 0.0;
    }

    /// Commanded translational velocity, mm/s.
    pub fn vel_mm_s(&self) -> f64 {
        self.vel_m_s * 1000.0
    }

    /// Commanded rotational velocity, °/s.
    pub fn rot_vel_deg_s(&self) -> f64 {
        self.rot_rad_s.to_degrees()
    }

    /// Whether the last step was cut short by a wall.
    pub fn stalled(&self) -> bool {
        self.stalled
    }

    /// Advances the body by `dt` seconds under the current command among `walls`.
    /// A non-finite or negative `dt` counts as 0.
    pub fn step(&mut self, walls: &[Segment], dt: f64) -> Motion {
        let dt = finite_or_zero(dt).max(0.0);
        let total_d = self.vel_m_s * dt;
        let total_a = self.rot_rad_s * dt;
        let n = ((total_d.abs() / MAX_SUBSTEP_M).ceil())
            .max((total_a.abs() / MAX_SUBSTEP_RAD).ceil())
            .clamp(1.0, 1.0e6) as usize;
        let (hd, ha) = (total_d / n as f64, total_a / n as f64);
        let mut motion = Motion::default();
        for _ in 0..n {
            let mid = self.pose.th + ha / 2.0;
            let moved = if motion.stalled || hd == 0.0 {
                0.0
            } else {
                self.translate(walls, hd, mid)
            };
            if moved != hd {
                motion.stalled = true;
            }
            motion.distance += moved;
            self.pose.th += ha;
            motion.rotation += ha;
        }
        self.pose.th = super::geom::normalize_angle(self.pose.th);
        self.stalled = motion.stalled;
        motion
    }

    /// Moves `d` metres along heading `th` as far as walls allow; returns the distance moved.
    fn translate(&mut self, walls: &[Segment], d: f64, th: f64) -> f64 {
        let start = self.pose.position();
        let start_clear = clearance(start, walls);
        let (s, c) = th.sin_cos();
        let at = |f: f64| super::geom::Point::new(start.x + f * d * c, start.y + f * d * s);
        let blocked = |f: f64| {
            let cl = clearance(at(f), walls);
            cl < RADIUS_M && cl < start_clear
        };
        let fraction = if !blocked(1.0) {
            1.0
        } else {
            // Largest free fraction, by bisection (the free set near 0 is an interval).
            let (mut lo, mut hi) = (0.0, 1.0);
            for _ in 0..30 {
                let mid = 0.5 * (lo + hi);
                if blocked(mid) {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            lo
        };
        let p = at(fraction);
        self.pose.x = p.x;
        self.pose.y = p.y;
        fraction * d
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn room() -> Vec<Segment> {
        vec![
            Segment::new(-4.0, -3.0, 4.0, -3.0),
            Segment::new(4.0, -3.0, 4.0, 3.0),
            Segment::new(4.0, 3.0, -4.0, 3.0),
            Segment::new(-4.0, 3.0, -4.0, -3.0),
        ]
    }

    #[test]
    fn cruise_straight() {
        let mut p = Pioneer::new(Pose::default());
        p.set_vel_mm_s(CRUISE_SPEED_M_S * 1000.0);
        let mut dist = 0.0;
        for _ in 0..100 {
            dist += p.step(&room(), DEFAULT_DT_S).distance;
        }
        assert!((p.pose().x - 3.0).abs() < 1e-9 && p.pose().y.abs() < 1e-12);
        assert!((dist - 3.0).abs() < 1e-9);
        assert!(!p.stalled());
    }

    #[test]
    fn turn_in_place() {
        let mut p = Pioneer::new(Pose::default());
        p.set_rot_vel_deg_s(TURN_RATE_DEG_S);
        let mut rot = 0.0;
        for _ in 0..45 {
            rot += p.step(&room(), DEFAULT_DT_S).rotation;
        }
        assert!((rot - PI).abs() < 1e-9, "{rot}");
        assert!((p.pose().th.abs() - PI).abs() < 1e-9);
        assert_eq!(p.pose().position(), Pose::default().position());
    }

    #[test]
    fn arc_motion_returns_home() {
        // v = 0.3 m/s, ω = 40°/s: a full circle in 9 s of radius 0.43 m.
        let mut p = Pioneer::new(Pose::default());
        p.set_vel_mm_s(300.0);
        p.set_rot_vel_deg_s(40.0);
        for _ in 0..90 {
            p.step(&room(), DEFAULT_DT_S);
        }
        assert!(p.pose().position().distance(Default::default()) < 1e-9);
    }

    #[test]
    fn wall_stops_the_robot() {
        let walls = room();
        let mut p = Pioneer::new(Pose::new(3.0, 0.0, 0.0));
        p.set_vel_mm_s(2200.0);
        let mut stalled = false;
        for _ in 0..50 {
            stalled |= p.step(&walls, DEFAULT_DT_S).stalled;
        }
        assert!(stalled && p.stalled());
        let gap = 4.0 - p.pose().x;
        assert!(
            (RADIUS_M - 1e-6..RADIUS_M + 1e-3).contains(&gap),
            "gap {gap}"
        );
        // It can turn and drive away.
        p.set_vel_mm_s(-300.0);
        let m = p.step(&walls, DEFAULT_DT_S);
        assert!(!m.stalled && (m.distance + 0.03).abs() < 1e-9);
    }

    #[test]
    fn never_passes_through_a_thin_wall() {
        let walls = [Segment::new(1.0, -1.0, 1.0, 1.0)];
        let mut p = Pioneer::new(Pose::default());
        p.set_vel_mm_s(2200.0);
        for _ in 0..10 {
            p.step(&walls, 1.0); // a huge time step
        }
        assert!(p.pose().x < 1.0 - RADIUS_M + 1e-6);
    }

    #[test]
    fn bad_commands_do_not_panic() {
        let mut p = Pioneer::new(Pose::default());
        p.set_vel_mm_s(f64::NAN);
        p.set_rot_vel_deg_s(f64::INFINITY);
        assert_eq!(p.vel_mm_s(), 0.0);
        assert_eq!(p.rot_vel_deg_s(), 0.0);
        p.set_vel_mm_s(1e12);
        assert_eq!(p.vel_mm_s(), MAX_VEL_MM_S);
        let m = p.step(&room(), f64::NAN);
        assert_eq!(m, Motion::default());
    }
}
