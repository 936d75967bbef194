//! The Rust functions the Soar-SLAM rules call through `exec` (the contract is
//! `rules/README.md`, section 1.6; "let Java do the math for Soar" in the thesis's
//! §Synchronization).
//!
//! A rule writes `(exec f a1 |, | a2 |, | ...)`; Soar concatenates the arguments' texts with no
//! separator, so each function receives **one string** such as `3000, -895, 3000, 1105`
//! (integers as `123`, floats with six decimals as `3025.000000`). Every function here splits
//! it on `,`, trims each field and parses it as a float, and returns a string, which Soar turns
//! into a string symbol (the rules wrap numeric results in `(int ...)`, which truncates).
//!
//! | function | arguments | result |
//! |---|---|---|
//! | [`getlength`] | `x1, y1, x2, y2` | Euclidean length, mm, `"2000.000"` |
//! | [`checkwallrelation`] | `rx, ry, rth, sx, sy, ex, ey` | `front`, `left`, `right`, `back` or `none` |
//! | [`getwalldistance`] | `rx, ry, rth, i, sx, sy, ex, ey` | range sonar `i` would read, mm, `"1234.500"`, or `"-1"` |
//!
//! Malformed arguments (wrong count, a field that is not a finite number, a sonar index outside
//! 0..15) never panic: `getlength` returns an `Error: ...` string (which `(int ...)` reads as
//! 0), `checkwallrelation` returns `none` and `getwalldistance` returns `-1`, the values for
//! which the rules do nothing.
//!
//! [`register`] puts all three on an agent under the names the rules use.

use rusoar::Agent;

use super::fixed::fixed;
use super::sonar::{Transducer, P2DX_SONARS};

/// The names the rules call, in the order of the table above.
pub const FUNCTION_NAMES: [&str; 3] = ["getlength", "checkwallrelation", "getwalldistance"];

/// Registers [`getlength`], [`checkwallrelation`] and [`getwalldistance`] (with the Pioneer
/// 2-DX sonar table, the one the simulator reads with) on `agent`.
pub fn register(agent: &mut Agent) {
    register_with(agent, &[0.0]);
}

/// [`register`], with `getwalldistance` casting one ray per entry of `rays_deg` (offsets from
/// the transducer's axis, degrees) and returning the nearest hit: `[0.0]` is the thesis's
/// central ray, [`cone_rays`] the simulated sonar's cone (the `cone` variant).
pub fn register_with(agent: &mut Agent, rays_deg: &[f64]) {
    let rays: Vec<f64> = if rays_deg.is_empty() {
        vec![0.0]
    } else {
        rays_deg.to_vec()
    };
    let text_rays = rays.clone();
    agent.register_sml_rhs_function("getlength", |_, args| getlength(args));
    agent.register_sml_rhs_function("checkwallrelation", |_, args| checkwallrelation(args));
    agent.register_sml_rhs_function("getwalldistance", move |_, args| {
        getwalldistance_rays(parse_n::<8>(args), &P2DX_SONARS, &text_rays)
    });
    // The same functions on the numbers themselves, which `exec` passes when the rules
    // separate their numeric arguments with commas, as the thesis's rules do (no printing
    // and reading back of 360,000 argument strings in a 600-s run).
    agent.register_sml_rhs_numeric_form("getlength", |n| Some(getlength_of(n.try_into().ok()?)));
    agent.register_sml_rhs_numeric_form("checkwallrelation", |n| {
        Some(checkwallrelation_of(n.try_into().ok()))
    });
    agent.register_sml_rhs_numeric_form("getwalldistance", move |n| {
        Some(getwalldistance_rays(n.try_into().ok(), &P2DX_SONARS, &rays))
    });
}

/// The ray offsets, degrees from the axis, of a sonar whose `cone_deg` cone is cut into `rays`
/// equal sectors with one ray along the middle of each (the simulator's sonar model).
pub fn cone_rays(rays: usize, cone_deg: f64) -> Vec<f64> {
    let n = rays.max(1);
    (0..n)
        .map(|i| -cone_deg / 2.0 + cone_deg * (i as f64 + 0.5) / n as f64)
        .collect()
}

/// Splits an `exec` argument string on `,` and parses each trimmed field as a finite float.
/// `None` when a field is empty, not a number or not finite.
pub fn parse_args(args: &str) -> Option<Vec<f64>> {
    args.split(',')
        .map(|f| f.trim().parse::<f64>().ok().filter(|v| v.is_finite()))
        .collect()
}

/// Exactly `n` numbers, or `None`.
fn parse_n<const N: usize>(args: &str) -> Option<[f64; N]> {
    parse_args(args)?.try_into().ok()
}

/// `getlength`: `x1, y1, x2, y2` (mm) → the distance between the two points, mm, with three
/// decimals (`"2000.000"`).
pub fn getlength(args: &str) -> String {
    match parse_n::<4>(args) {
        Some(n) => getlength_of(n),
        None => format!("Error: getlength expects \"x1, y1, x2, y2\", got \"{args}\""),
    }
}

/// [`getlength`] on its numbers.
fn getlength_of([x1, y1, x2, y2]: [f64; 4]) -> String {
    fixed((x2 - x1).hypot(y2 - y1), 3)
}

/// Where a robot sees a wall (`checkwallrelation`'s result).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Relation {
    Front,
    Left,
    Right,
    Back,
    None,
}

impl Relation {
    /// The word the rules compare with.
    pub fn word(self) -> &'static str {
        match self {
            Relation::Front => "front",
            Relation::Left => "left",
            Relation::Right => "right",
            Relation::Back => "back",
            Relation::None => "none",
        }
    }
}

/// The relation of the wall `(sx, sy)–(ex, ey)` to a robot at `(rx, ry)` heading `rth_deg`
/// (`rules/README.md`, section 1.6): F is the foot of the perpendicular from the robot to
/// the wall's line; `None` for a zero-length wall, when F lies outside the segment (t < 0
/// or t > 1 along Start→End) or when F is the robot's position; otherwise the bearing b =
/// atan2(F − robot) − rth, normalised to [−180, 180), gives `Front` for −45 ≤ b ≤ 45,
/// `Left` for 45 < b < 135, `Right` for −135 < b < −45 and `Back` otherwise.
pub fn wall_relation(rx: f64, ry: f64, rth_deg: f64, s: (f64, f64), e: (f64, f64)) -> Relation {
    let (dx, dy) = (e.0 - s.0, e.1 - s.1);
    let len2 = dx * dx + dy * dy;
    if len2 == 0.0 {
        return Relation::None;
    }
    let t = ((rx - s.0) * dx + (ry - s.1) * dy) / len2;
    if !(0.0..=1.0).contains(&t) {
        return Relation::None;
    }
    let (fx, fy) = (s.0 + t * dx - rx, s.1 + t * dy - ry);
    // F = robot, up to rounding of the foot's coordinates (inputs are mm).
    if fx.hypot(fy) < 1e-9 {
        return Relation::None;
    }
    let b = (fy.atan2(fx).to_degrees() - rth_deg + 180.0).rem_euclid(360.0) - 180.0;
    if (-45.0..=45.0).contains(&b) {
        Relation::Front
    } else if b > 45.0 && b < 135.0 {
        Relation::Left
    } else if b > -135.0 && b < -45.0 {
        Relation::Right
    } else {
        Relation::Back
    }
}

/// `checkwallrelation`: `rx, ry, rth, sx, sy, ex, ey` → `front`, `left`, `right`, `back` or
/// `none` (see [`wall_relation`]). Malformed arguments give `none`.
pub fn checkwallrelation(args: &str) -> String {
    checkwallrelation_of(parse_n::<7>(args))
}

/// [`checkwallrelation`] on its numbers (`None`: not seven of them).
fn checkwallrelation_of(n: Option<[f64; 7]>) -> String {
    match n {
        Some([rx, ry, rth, sx, sy, ex, ey]) => wall_relation(rx, ry, rth, (sx, sy), (ex, ey))
            .word()
            .to_string(),
        None => Relation::None.word().to_string(),
    }
}

/// The range transducer `t` would read, mm, if the segment `(sx, sy)–(ex, ey)` were the
/// only wall, for a robot at `(rx, ry)` heading `rth_deg` (`rules/README.md`, section 1.6):
/// the transducer sits at P = robot + Rot(rth)·(x, y) and looks along rth + its heading;
/// the result is the distance t ≥ 0 along that ray to the segment (ends included), not
/// clipped to the sonar's range. `None` when the ray is parallel to the segment, misses it
/// or hits it only behind P.
pub fn sonar_distance(
    rx: f64,
    ry: f64,
    rth_deg: f64,
    t: &Transducer,
    s: (f64, f64),
    e: (f64, f64),
) -> Option<f64> {
    let (sin_r, cos_r) = rth_deg.to_radians().sin_cos();
    let px = rx + cos_r * t.x_mm - sin_r * t.y_mm;
    let py = ry + sin_r * t.x_mm + cos_r * t.y_mm;
    let (dy, dx) = (rth_deg + t.heading_deg).to_radians().sin_cos();
    let (ex, ey) = (e.0 - s.0, e.1 - s.1);
    // Solve P + t·d = S + u·(E − S).
    let denom = dx * ey - dy * ex;
    let len = ex.hypot(ey);
    if len == 0.0 || denom.abs() <= 1e-12 * len {
        return None;
    }
    let (wx, wy) = (s.0 - px, s.1 - py);
    let dist = (wx * ey - wy * ex) / denom;
    let u = (wx * dy - wy * dx) / denom;
    // A hit exactly on an end point may come out a rounding error outside [0, 1].
    let slack = 1e-9;
    if dist < 0.0 || u < -slack || u > 1.0 + slack {
        return None;
    }
    Some(dist)
}

/// `getwalldistance`: `rx, ry, rth, i, sx, sy, ex, ey` → the range sonar `i` of the Pioneer
/// 2-DX ring would read off the wall, mm with three decimals, or `-1` (see
/// [`sonar_distance`]). A malformed call (including an index that is not one of 0..15) gives
/// `-1` too.
pub fn getwalldistance(args: &str) -> String {
    getwalldistance_with(args, &P2DX_SONARS)
}

/// [`getwalldistance`] for another transducer table.
pub fn getwalldistance_with(args: &str, sonars: &[Transducer]) -> String {
    getwalldistance_of(parse_n::<8>(args), sonars)
}

/// [`getwalldistance_with`] on its numbers (`None`: not eight of them).
fn getwalldistance_of(n: Option<[f64; 8]>, sonars: &[Transducer]) -> String {
    getwalldistance_rays(n, sonars, &[0.0])
}

/// [`getwalldistance_of`] over several rays (offsets from the axis, degrees): the nearest hit.
fn getwalldistance_rays(n: Option<[f64; 8]>, sonars: &[Transducer], rays_deg: &[f64]) -> String {
    let Some([rx, ry, rth, i, sx, sy, ex, ey]) = n else {
        return "-1".to_string();
    };
    if i.fract() != 0.0 || i < 0.0 {
        return "-1".to_string();
    }
    let Some(t) = sonars.get(i as usize) else {
        return "-1".to_string();
    };
    let nearest = rays_deg
        .iter()
        .filter_map(|off| {
            let ray = Transducer {
                heading_deg: t.heading_deg + off,
                ..*t
            };
            sonar_distance(rx, ry, rth, &ray, (sx, sy), (ex, ey))
        })
        .min_by(f64::total_cmp);
    match nearest {
        Some(d) => fixed(d, 3),
        None => "-1".to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rusoar::RunUnit;

    #[test]
    fn parses_soar_argument_strings() {
        assert_eq!(
            parse_args("3000, -895, 3000, 1105"),
            Some(vec![3000.0, -895.0, 3000.0, 1105.0])
        );
        assert_eq!(
            parse_args("3025.000000, -1.500000"),
            Some(vec![3025.0, -1.5])
        );
        assert_eq!(parse_args("1, x"), None);
        assert_eq!(parse_args("1,,2"), None);
        assert_eq!(parse_args("1, inf"), None);
        assert_eq!(parse_args(""), None);
    }

    #[test]
    fn getlength_is_euclidean_with_three_decimals() {
        assert_eq!(getlength("3025, -900, 3025, 1100"), "2000.000");
        assert_eq!(getlength("0, 0, 3, 4"), "5.000");
        assert_eq!(getlength("0.500000, 0, 0, 0"), "0.500");
        assert_eq!(getlength("1, 1, 1, 1"), "0.000");
        assert!(getlength("1, 2, 3").starts_with("Error: getlength"));
        assert!(getlength("a, b, c, d").starts_with("Error: getlength"));
    }

    #[test]
    fn checkwallrelation_follows_the_contract() {
        // The wall x = 3000 from y = -895 to 1105 (README smoke-run string).
        assert_eq!(
            checkwallrelation("0, 0, 0, 3000, -895, 3000, 1105"),
            "front"
        );
        assert_eq!(
            checkwallrelation("0, 0, 90, 3000, -895, 3000, 1105"),
            "right"
        );
        assert_eq!(
            checkwallrelation("0, 0, 270, 3000, -895, 3000, 1105"),
            "left"
        );
        assert_eq!(
            checkwallrelation("0, 0, 180, 3000, -895, 3000, 1105"),
            "back"
        );
        assert_eq!(
            checkwallrelation("0, 0, -90, 3000, -895, 3000, 1105"),
            "left"
        );
        assert_eq!(
            checkwallrelation("0, 0, 450, 3000, -895, 3000, 1105"),
            "right"
        );
        // Boundaries: b = 45 is front, b = 135 is back, b = -135 is back, b = -45 is front.
        assert_eq!(
            checkwallrelation("0, 0, -45, 3000, -895, 3000, 1105"),
            "front"
        );
        assert_eq!(
            checkwallrelation("0, 0, 45, 3000, -895, 3000, 1105"),
            "front"
        );
        assert_eq!(
            checkwallrelation("0, 0, -135, 3000, -895, 3000, 1105"),
            "back"
        );
        assert_eq!(
            checkwallrelation("0, 0, 135, 3000, -895, 3000, 1105"),
            "back"
        );
        assert_eq!(
            checkwallrelation("0, 0, 44, 3000, -895, 3000, 1105"),
            "front"
        );
        assert_eq!(
            checkwallrelation("0, 0, 46, 3000, -895, 3000, 1105"),
            "right"
        );
        // Foot outside the segment (t > 1 and t < 0), zero length, robot on the wall.
        assert_eq!(
            checkwallrelation("0, 2000, 0, 3000, -895, 3000, 1105"),
            "none"
        );
        assert_eq!(
            checkwallrelation("0, -1000, 0, 3000, -895, 3000, 1105"),
            "none"
        );
        assert_eq!(checkwallrelation("0, 0, 0, 3000, 5, 3000, 5"), "none");
        assert_eq!(
            checkwallrelation("3000, 0, 0, 3000, -895, 3000, 1105"),
            "none"
        );
        // Ends included: the foot on Start or End still counts.
        assert_eq!(
            checkwallrelation("0, -895, 0, 3000, -895, 3000, 1105"),
            "front"
        );
        assert_eq!(
            checkwallrelation("0, 1105, 0, 3000, -895, 3000, 1105"),
            "front"
        );
        // A tilted wall, floats in Soar's text form.
        assert_eq!(
            checkwallrelation("0.000000, 0.000000, 0, -2000.000000, 2000, 2000, 0"),
            "left"
        );
        // Malformed.
        assert_eq!(checkwallrelation("0, 0, 0, 3000, -895, 3000"), "none");
        assert_eq!(checkwallrelation("0, 0, 0, 3000, -895, 3000, y"), "none");
    }

    #[test]
    fn getwalldistance_casts_the_transducer_ray() {
        // README smoke-run string: sonar 3 (166, 27, +10°) of a robot at the origin facing +x
        // towards the wall x = 3200 (y from -800 to 1200): the ray starts at (166, 27) and
        // runs (3200 - 166) / cos 10° to the wall.
        let want = (3200.0 - 166.0) / 10f64.to_radians().cos();
        let got: f64 = getwalldistance("0, 0, 0, 3, 3200, -800, 3200, 1200")
            .parse()
            .unwrap();
        assert!((got - want).abs() < 1e-3, "{got} vs {want}");
        // The same with the robot turned: facing +y at (1000, -500), wall y = 2000.
        // Sonar 0 sits at robot + Rot(90°)(69, 136) = (864, -431) and looks at 180°: it misses
        // this wall (parallel). Sonar 3 sits at (973, -334) and looks at 100°.
        assert_eq!(
            getwalldistance("1000, -500, 90, 0, -5000, 2000, 5000, 2000"),
            "-1"
        );
        let want = (2000.0 - (-500.0 + 166.0)) / 10f64.to_radians().cos();
        let got: f64 = getwalldistance("1000, -500, 90, 3, -5000, 2000, 5000, 2000")
            .parse()
            .unwrap();
        assert!((got - want).abs() < 1e-3, "{got} vs {want}");
        // Sonar 8 (-157, -136, -90°) at the origin looks at -y: the wall y = -1136 is 1000 away.
        assert_eq!(
            getwalldistance("0, 0, 0, 8, -500, -1136, 500, -1136"),
            "1000.000"
        );
        // Ends included: a wall ending exactly where the ray hits it.
        assert_eq!(
            getwalldistance("0, 0, 0, 8, -157, -1136, 500, -1136"),
            "1000.000"
        );
        // Misses the segment (beside it, beyond its end), hit only behind the transducer,
        // parallel.
        assert_eq!(getwalldistance("0, 0, 0, 8, 500, -1136, 900, -1136"), "-1");
        assert_eq!(getwalldistance("0, 0, 0, 3, 0, 1000, 3000, 1000"), "-1");
        assert_eq!(getwalldistance("0, 0, 0, 0, -500, -1136, 500, -1136"), "-1");
        assert_eq!(getwalldistance("0, 0, 0, 0, 500, -1000, 500, 1000"), "-1");
        // Not clipped to the sonar's 5 m range.
        assert_eq!(
            getwalldistance("0, 0, 0, 8, -500, -9136, 500, -9136"),
            "9000.000"
        );
        // Bad index, bad count, zero-length wall.
        assert_eq!(
            getwalldistance("0, 0, 0, 16, -500, -1136, 500, -1136"),
            "-1"
        );
        assert_eq!(
            getwalldistance("0, 0, 0, -1, -500, -1136, 500, -1136"),
            "-1"
        );
        assert_eq!(
            getwalldistance("0, 0, 0, 2.5, -500, -1136, 500, -1136"),
            "-1"
        );
        assert_eq!(getwalldistance("0, 0, 0, 8, -500, -1136, 500"), "-1");
        assert_eq!(getwalldistance("0, 0, 0, 8, 0, -1136, 0, -1136"), "-1");
    }

    /// The functions as the rules reach them: registered on an agent and called through
    /// `exec` with `|, |` between the arguments; `(int ...)` truncates the string result.
    #[test]
    fn rules_call_them_through_exec() {
        let mut agent = Agent::new("t");
        register(&mut agent);
        for name in FUNCTION_NAMES {
            assert!(agent.has_rhs_function(name), "{name}");
        }
        agent
            .execute(
                "sp {t (state <s> ^superstate nil) -->
                   (<s> ^len (int (exec getlength 3025 |, | -900 |, | 3025.000000 |, | 1100))
                        ^rel (exec checkwallrelation 0 |, | 0 |, | 0 |, | 3000 |, | -895 |, | 3000 |, | 1105)
                        ^dist (int (exec getwalldistance 0 |, | 0 |, | 0 |, | 8 |, | -500 |, | -1136.5 |, | 500 |, | -1136.5))
                        ^miss (int (exec getwalldistance 0 |, | 0 |, | 0 |, | 0 |, | -500 |, | -1136 |, | 500 |, | -1136)))}",
            )
            .unwrap();
        agent.set_trace_level(0);
        agent.run(1, RunUnit::Decisions).unwrap();
        let a = &agent;
        let value = |attr: &str| -> String {
            a.children(a.top_state())
                .iter()
                .find(|w| a.text(w.attr) == attr)
                .map(|w| a.text(w.value))
                .unwrap_or_default()
        };
        assert_eq!(value("len"), "2000");
        assert_eq!(value("rel"), "front");
        assert_eq!(value("dist"), "1000");
        assert_eq!(value("miss"), "-1");
    }
}
