//! Line features in the (r, θ) form `r = x cos θ + y sin θ`: the wall seen from the robot, and
//! the wall in the world, with the Jacobians the filter needs.
//!
//! A line has two (r, θ) forms, `(r, θ)` and `(−r, θ + π)`. The world form keeps r ≥ 0; a
//! measurement is compared with a prediction in whichever of its two forms has the nearer angle,
//! so a wall passing close to the robot or the origin never flips sides between steps.

use super::super::geom::normalize_angle;

/// A line `r = x cos θ + y sin θ`: r in metres, θ in radians.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Line {
    pub r: f64,
    pub th: f64,
}

impl Line {
    pub const fn new(r: f64, th: f64) -> Self {
        Line { r, th }
    }

    /// The same line with r ≥ 0 and θ in `(−π, π]`.
    pub fn canonical(self) -> Line {
        if self.r < 0.0 {
            Line::new(-self.r, normalize_angle(self.th + std::f64::consts::PI))
        } else {
            Line::new(self.r, normalize_angle(self.th))
        }
    }

    /// The form of this line whose angle is within π/2 of `th`.
    pub fn facing(self, th: f64) -> Line {
        if normalize_angle(self.th - th).abs() > std::f64::consts::FRAC_PI_2 {
            Line::new(-self.r, normalize_angle(self.th + std::f64::consts::PI))
        } else {
            Line::new(self.r, normalize_angle(self.th))
        }
    }

    /// The world line seen from a robot at (x, y, φ): r − x cos θ − y sin θ, θ − φ.
    pub fn to_robot(self, x: f64, y: f64, phi: f64) -> Line {
        let (s, c) = self.th.sin_cos();
        Line::new(self.r - x * c - y * s, normalize_angle(self.th - phi))
    }

    /// The robot-relative line in the world, for a robot at (x, y, φ); canonical.
    pub fn to_world(self, x: f64, y: f64, phi: f64) -> Line {
        let th = normalize_angle(self.th + phi);
        let (s, c) = th.sin_cos();
        Line::new(self.r + x * c + y * s, th).canonical()
    }
}

/// Jacobian of [`Line::to_robot`] with respect to the robot (x, y, φ) and the world line
/// (r, θ): rows (r, θ) of the robot-relative line; columns x, y, φ, r, θ.
pub fn to_robot_jacobian(world: Line, x: f64, y: f64) -> [[f64; 5]; 2] {
    let (s, c) = world.th.sin_cos();
    [
        [-c, -s, 0.0, 1.0, x * s - y * c],
        [0.0, 0.0, -1.0, 0.0, 1.0],
    ]
}

/// Jacobians of [`Line::to_world`] for the robot-relative line `rel` seen from (x, y, φ): with
/// respect to the robot (x, y, φ) and to the measured (r, θ). Both follow the canonical form's
/// sign.
pub fn to_world_jacobians(rel: Line, x: f64, y: f64, phi: f64) -> ([[f64; 3]; 2], [[f64; 2]; 2]) {
    let th = normalize_angle(rel.th + phi);
    let (s, c) = th.sin_cos();
    let d_th = -x * s + y * c;
    let sign = if rel.r + x * c + y * s < 0.0 {
        -1.0
    } else {
        1.0
    };
    (
        [[sign * c, sign * s, sign * d_th], [0.0, 0.0, 1.0]],
        [[sign, sign * d_th], [0.0, 1.0]],
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn canonical_folds_negative_r_and_wraps() {
        let l = Line::new(-2.0, 0.25).canonical();
        assert!((l.r - 2.0).abs() < 1e-12);
        assert!((l.th - (0.25 - PI)).abs() < 1e-12);
        let l = Line::new(1.0, 3.0 * PI).canonical();
        assert!((l.th - PI).abs() < 1e-12);
    }

    #[test]
    fn facing_picks_the_form_with_the_nearer_angle() {
        // The wall x = 4 seen at θ = 359° and at θ = 1°: the same line, one degree apart.
        let a = Line::new(4.0, (-1.0f64).to_radians());
        let b = Line::new(4.0, 1.0f64.to_radians()).facing(a.th);
        assert!((normalize_angle(b.th - a.th) - 2.0f64.to_radians()).abs() < 1e-12);
        let flipped = Line::new(-4.0, PI - 0.01).facing(0.0);
        assert!((flipped.r - 4.0).abs() < 1e-12 && (flipped.th + 0.01).abs() < 1e-12);
    }

    #[test]
    fn robot_and_world_round_trip() {
        let w = Line::new(3.0, 1.2);
        let (x, y, phi) = (0.4, -0.7, 2.9);
        let back = w.to_robot(x, y, phi).to_world(x, y, phi);
        assert!((back.r - w.r).abs() < 1e-12 && normalize_angle(back.th - w.th).abs() < 1e-12);
    }

    #[test]
    fn jacobians_match_finite_differences() {
        let w = Line::new(3.0, 1.2);
        let (x, y, phi) = (0.4, -0.7, 2.9);
        let j = to_robot_jacobian(w, x, y);
        let h = 1e-6;
        let f = |v: [f64; 5]| Line::new(v[3], v[4]).to_robot(v[0], v[1], v[2]);
        let base = [x, y, phi, w.r, w.th];
        for k in 0..5 {
            let mut p = base;
            p[k] += h;
            let (a, b) = (f(p), f(base));
            assert!(((a.r - b.r) / h - j[0][k]).abs() < 1e-5, "dr/d{k}");
            assert!(
                (normalize_angle(a.th - b.th) / h - j[1][k]).abs() < 1e-5,
                "dθ/d{k}"
            );
        }
        let rel = Line::new(1.5, 0.3);
        let (jr, jz) = to_world_jacobians(rel, x, y, phi);
        let g = |v: [f64; 5]| Line::new(v[3], v[4]).to_world(v[0], v[1], v[2]);
        let base = [x, y, phi, rel.r, rel.th];
        for k in 0..5 {
            let mut p = base;
            p[k] += h;
            let (a, b) = (g(p), g(base));
            let (er, et) = if k < 3 {
                (jr[0][k], jr[1][k])
            } else {
                (jz[0][k - 3], jz[1][k - 3])
            };
            assert!(((a.r - b.r) / h - er).abs() < 1e-5, "dρ/d{k}");
            assert!(
                (normalize_angle(a.th - b.th) / h - et).abs() < 1e-5,
                "dα/d{k}"
            );
        }
    }
}
