//! The geometry `rules/v2/` calls through `exec`: the rules decide which wall to trust and when
//! to correct, these functions only do the trigonometry (the thesis's "let Java do the math for
//! Soar", §Synchronization). They take numbers and return a float, so a rule reads the result
//! as a number (no `(int ...)`), e.g. `(exec v2-offset <th> <r> <rx> <ry> <e> <mth> <mr>)`.
//!
//! Conventions (`rules/README.md`, section 1.3): a line is `x cos θ + y sin θ = r`, θ in
//! degrees, lengths in mm. The heading error `e` of an observation is how far the believed
//! frame is turned against the map's: a wall seen at `th` on a map whose walls lie at
//! `ref + k·90°` gives `e = th − ref` reduced to [−45°, 45°) (the room's walls meet at right
//! angles; a drift of 45° between two corrections never happens at 2.5 s per extraction).
//!
//! | function | arguments | result |
//! |---|---|---|
//! | `v2-wrap90` | `a ref` | `a − ref` reduced to [−45, 45) |
//! | `v2-offset` | `th r rx ry e mth mr` | the observed line, turned by −e about the robot's `^Ref`, minus the map line, along the map's normal (mm); 10⁶ when not parallel |
//! | `v2-line-th` | `th r rx ry e` | the normal angle of the turned line, [0, 360), r ≥ 0 |
//! | `v2-line-r` | `th r rx ry e` | its distance from the origin, ≥ 0 |
//! | `v2-lo`, `v2-hi` | `rx ry e mth sx sy ex ey` | where the wall's ends, turned by −e about the robot, lie along the map line's direction (−sin, cos): the lower and the higher |
//! | `v2-px`, `v2-py` | `mth mr s` | the point of the map line at `s` along it |
//! | `v2-sense` | `tha thb` | 1 when the normals agree, −1 when they are opposite (parallel walls), 0 otherwise |
//! | `v2-x`, `v2-y`, `v2-th` | `cx cy cth rx ry e d mth gr gth` | the corrected pose: turned by −gth·e about (rx, ry), then moved by −gr·d along the map's normal |
//!
//! Wrong arguments (count or type) give an error message and no value, never a panic.

use rusoar::{Agent, RhsArg, Value};

use super::geom::deg_0_360;

/// What [`offset`] returns for lines that are not parallel.
pub const NOT_PARALLEL: f64 = 1.0e6;

/// Lines whose normals differ by more than this, degrees, are not parallel.
const PARALLEL_DEG: f64 = 10.0;

/// `a − b` reduced to [−45°, 45°).
pub fn wrap90(a: f64, b: f64) -> f64 {
    (a - b + 45.0).rem_euclid(90.0) - 45.0
}

/// `a` reduced to [−180°, 180°).
fn wrap180(a: f64) -> f64 {
    (a + 180.0).rem_euclid(360.0) - 180.0
}

/// The line `(th, r)` turned by `phi_deg` about `(cx, cy)`: its normal angle and signed r.
fn turn_line(th: f64, r: f64, cx: f64, cy: f64, phi_deg: f64) -> (f64, f64) {
    let (s, c) = th.to_radians().sin_cos();
    // The distance from the centre to the line is kept; the normal turns with the plane.
    let from_centre = r - (c * cx + s * cy);
    let th2 = th + phi_deg;
    let (s2, c2) = th2.to_radians().sin_cos();
    (th2, c2 * cx + s2 * cy + from_centre)
}

/// The observed line, turned by −e about the robot, against the map line: the signed distance
/// between them along the map's normal, or [`NOT_PARALLEL`].
pub fn offset(th: f64, r: f64, rx: f64, ry: f64, e: f64, mth: f64, mr: f64) -> f64 {
    let (th2, r2) = turn_line(th, r, rx, ry, -e);
    let diff = wrap180(th2 - mth);
    if diff.abs() <= PARALLEL_DEG {
        r2 - mr
    } else if diff.abs() >= 180.0 - PARALLEL_DEG {
        -r2 - mr
    } else {
        NOT_PARALLEL
    }
}

/// How the normals `tha` and `thb` (degrees) relate: 1 when they agree and −1 when they are
/// opposite, within [`PARALLEL_DEG`] (the two sides of a room), 0 when the lines are not
/// parallel. An offset along one normal is `sense` times the same offset along the other.
pub fn sense(tha: f64, thb: f64) -> f64 {
    let diff = wrap180(thb - tha).abs();
    if diff <= PARALLEL_DEG {
        1.0
    } else if diff >= 180.0 - PARALLEL_DEG {
        -1.0
    } else {
        0.0
    }
}

/// The observed line turned by −e about the robot, as `(θ in [0, 360), r ≥ 0)`.
pub fn turned(th: f64, r: f64, rx: f64, ry: f64, e: f64) -> (f64, f64) {
    let (th2, r2) = turn_line(th, r, rx, ry, -e);
    if r2 < 0.0 {
        (deg_0_360(th2 + 180.0), -r2)
    } else {
        (deg_0_360(th2), r2)
    }
}

/// Where `(px, py)`, turned by −e about `(rx, ry)`, lies along the direction (−sin, cos) of a
/// line with normal angle `mth`.
pub fn along(rx: f64, ry: f64, e: f64, mth: f64, px: f64, py: f64) -> f64 {
    let (s, c) = (-e).to_radians().sin_cos();
    let (dx, dy) = (px - rx, py - ry);
    let (qx, qy) = (rx + c * dx - s * dy, ry + s * dx + c * dy);
    let (ms, mc) = mth.to_radians().sin_cos();
    -ms * qx + mc * qy
}

/// The corrected pose `(x, y, θ)`: the current believed pose `(cx, cy, cth)` turned by −gth·e
/// about `(rx, ry)` (the rules give the robot's own position, so that a heading correction
/// does not move it), then moved by −gr·d along the map line's normal `mth`.
#[allow(clippy::too_many_arguments)]
pub fn corrected(
    cx: f64,
    cy: f64,
    cth: f64,
    rx: f64,
    ry: f64,
    e: f64,
    d: f64,
    mth: f64,
    gr: f64,
    gth: f64,
) -> (f64, f64, f64) {
    let phi = -gth * e;
    let (s, c) = phi.to_radians().sin_cos();
    let (dx, dy) = (cx - rx, cy - ry);
    let (x1, y1) = (rx + c * dx - s * dy, ry + s * dx + c * dy);
    let (ms, mc) = mth.to_radians().sin_cos();
    (x1 - gr * d * mc, y1 - gr * d * ms, deg_0_360(cth + phi))
}

/// The arguments as `N` numbers, or an error naming the function.
fn numbers<const N: usize>(name: &str, args: &[RhsArg]) -> Result<[f64; N], String> {
    let v: Option<Vec<f64>> = args.iter().map(|a| a.as_f64()).collect();
    v.filter(|v| v.iter().all(|x| x.is_finite()))
        .and_then(|v| v.try_into().ok())
        .ok_or_else(|| format!("{name} expects {N} numbers, got {} argument(s)", args.len()))
}

/// The names [`register`] adds.
pub const FUNCTION_NAMES: [&str; 12] = [
    "v2-wrap90",
    "v2-offset",
    "v2-line-th",
    "v2-line-r",
    "v2-lo",
    "v2-hi",
    "v2-px",
    "v2-py",
    "v2-sense",
    "v2-x",
    "v2-y",
    "v2-th",
];

/// Registers the functions of the table above on `agent`.
pub fn register(agent: &mut Agent) {
    agent.register_rhs_function("v2-wrap90", |_, a| {
        let [x, r] = numbers("v2-wrap90", a)?;
        Ok(Value::Float(wrap90(x, r)))
    });
    agent.register_rhs_function("v2-offset", |_, a| {
        let [th, r, rx, ry, e, mth, mr] = numbers("v2-offset", a)?;
        Ok(Value::Float(offset(th, r, rx, ry, e, mth, mr)))
    });
    agent.register_rhs_function("v2-line-th", |_, a| {
        let [th, r, rx, ry, e] = numbers("v2-line-th", a)?;
        Ok(Value::Float(turned(th, r, rx, ry, e).0))
    });
    agent.register_rhs_function("v2-line-r", |_, a| {
        let [th, r, rx, ry, e] = numbers("v2-line-r", a)?;
        Ok(Value::Float(turned(th, r, rx, ry, e).1))
    });
    for (name, high) in [("v2-lo", false), ("v2-hi", true)] {
        agent.register_rhs_function(name, move |_, a| {
            let [rx, ry, e, mth, sx, sy, ex, ey] = numbers(name, a)?;
            let (s1, s2) = (along(rx, ry, e, mth, sx, sy), along(rx, ry, e, mth, ex, ey));
            Ok(Value::Float(if high { s1.max(s2) } else { s1.min(s2) }))
        });
    }
    agent.register_rhs_function("v2-px", |_, a| {
        let [mth, mr, s] = numbers("v2-px", a)?;
        let (sn, cs) = mth.to_radians().sin_cos();
        Ok(Value::Float(mr * cs - s * sn))
    });
    agent.register_rhs_function("v2-py", |_, a| {
        let [mth, mr, s] = numbers("v2-py", a)?;
        let (sn, cs) = mth.to_radians().sin_cos();
        Ok(Value::Float(mr * sn + s * cs))
    });
    agent.register_rhs_function("v2-sense", |_, a| {
        let [tha, thb] = numbers("v2-sense", a)?;
        Ok(Value::Float(sense(tha, thb)))
    });
    for (name, pick) in [("v2-x", 0usize), ("v2-y", 1), ("v2-th", 2)] {
        agent.register_rhs_function(name, move |_, a| {
            let [cx, cy, cth, rx, ry, e, d, mth, gr, gth] = numbers(name, a)?;
            let p = corrected(cx, cy, cth, rx, ry, e, d, mth, gr, gth);
            Ok(Value::Float([p.0, p.1, p.2][pick]))
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap90_reduces_to_the_nearest_right_angle() {
        assert_eq!(wrap90(91.0, 0.0), 1.0);
        assert_eq!(wrap90(359.0, 0.0), -1.0);
        assert_eq!(wrap90(182.0, 3.0), -1.0);
        assert_eq!(wrap90(45.0, 0.0), -45.0);
    }

    #[test]
    fn a_line_seen_turned_about_the_robot_lines_up_with_the_map() {
        // The wall x = 4000; the robot at (1000, 0) believes itself turned by +2°, so it sees
        // the wall turned by +2° about itself.
        let (th, r) = turn_line(0.0, 4000.0, 1000.0, 0.0, 2.0);
        let e = wrap90(th, 0.0);
        assert!((e - 2.0).abs() < 1e-9);
        assert!(offset(th, r, 1000.0, 0.0, e, 0.0, 4000.0).abs() < 1e-6);
        // The same wall from the other side of the origin's normal.
        assert!(offset(th, r, 1000.0, 0.0, e, 180.0, -4000.0).abs() < 1e-6);
        assert_eq!(
            offset(th, r, 1000.0, 0.0, e, 90.0, 3000.0),
            NOT_PARALLEL,
            "perpendicular walls are not compared"
        );
        let (t2, r2) = turned(th, r, 1000.0, 0.0, e);
        assert!(t2.abs() < 1e-9 && (r2 - 4000.0).abs() < 1e-6);
    }

    #[test]
    fn a_correction_moves_the_belief_along_the_normal_and_turns_it() {
        let (x, y, th) = corrected(
            1000.0, 500.0, 10.0, 1000.0, 500.0, 2.0, 100.0, 0.0, 0.5, 1.0,
        );
        assert!((x - 950.0).abs() < 1e-9 && (y - 500.0).abs() < 1e-9);
        assert!((th - 8.0).abs() < 1e-9);
        // Turning about a point behind the robot moves it sideways too.
        let (x, y, _) = corrected(1000.0, 0.0, 0.0, 0.0, 0.0, 90.0, 0.0, 0.0, 0.0, 1.0);
        assert!(x.abs() < 1e-9 && (y + 1000.0).abs() < 1e-9);
    }

    #[test]
    fn sense_tells_the_two_sides_of_a_room() {
        assert_eq!(sense(0.6, 0.6), 1.0);
        assert_eq!(sense(0.6, 180.6), -1.0);
        assert_eq!(sense(359.0, 1.0), 1.0);
        assert_eq!(sense(0.6, 90.6), 0.0);
    }

    #[test]
    fn along_measures_the_wall_direction() {
        // The wall x = 4000 runs along +y.
        assert!((along(0.0, 0.0, 0.0, 0.0, 4000.0, 1200.0) - 1200.0).abs() < 1e-9);
    }

    #[test]
    fn bad_arguments_are_errors() {
        assert!(numbers::<2>("f", &[RhsArg::Int(1)]).is_err());
        assert!(numbers::<1>("f", &[RhsArg::Str("x")]).is_err());
        assert_eq!(numbers::<1>("f", &[RhsArg::Float(2.5)]), Ok([2.5]));
    }
}
