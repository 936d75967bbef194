//! Arithmetic, conversions, the TacAir/Quake helpers and random numbers
//! (9.6 `rhs_functions_math.cpp`), with its overflow behaviour (wrapping) and messages.

use super::text::{c_strtod, c_strtol};
use super::{arity_error, RhsContext};
use crate::symbols::{Sym, SymData};

#[derive(Clone, Copy)]
enum Num {
    I(i64),
    F(f64),
}

impl Num {
    fn f(self) -> f64 {
        match self {
            Num::I(i) => i as f64,
            Num::F(f) => f,
        }
    }

    /// `int` for an int, the C cast of a float.
    fn i(self) -> i64 {
        match self {
            Num::I(i) => i,
            Num::F(f) => f64_to_i64(f),
        }
    }
}

/// `static_cast<int64_t>(double)` as x86-64 does it: truncation, and `i64::MIN` for NaN and
/// values out of range.
pub(super) fn f64_to_i64(f: f64) -> i64 {
    if !(-9_223_372_036_854_775_808.0..9_223_372_036_854_775_808.0).contains(&f) {
        i64::MIN
    } else {
        f as i64
    }
}

fn num(ctx: &RhsContext, s: Sym) -> Option<Num> {
    match ctx.symbols.get(s) {
        SymData::Int(i) => Some(Num::I(*i)),
        SymData::Float(f) => Some(Num::F(*f)),
        _ => None,
    }
}

/// All arguments as numbers, or 9.6's `non-number` error naming the first that is not.
fn nums(ctx: &RhsContext, args: &[Sym], msg: &str) -> Result<Vec<Num>, String> {
    args.iter()
        .map(|a| num(ctx, *a).ok_or_else(|| msg.replace("{}", &ctx.y(*a))))
        .collect()
}

fn out(ctx: &mut RhsContext, n: Num) -> Sym {
    match n {
        Num::I(i) => ctx.symbols.int(i),
        Num::F(f) => ctx.symbols.float(f),
    }
}

/// `+` and `*`: ints accumulate as ints until the first float; from there on a double.
fn accumulate(args: &[Sym], ctx: &mut RhsContext, times: bool) -> Result<Sym, String> {
    let mut i: i64 = i64::from(times);
    let mut f: Option<f64> = None;
    for &a in args {
        let Some(n) = num(ctx, a) else {
            let op = if times { '*' } else { '+' };
            return Err(format!(
                "Error: non-number ({}) passed to {op} function",
                ctx.y(a)
            ));
        };
        f = match (f, n) {
            (None, Num::I(x)) => {
                i = if times {
                    i.wrapping_mul(x)
                } else {
                    i.wrapping_add(x)
                };
                None
            }
            (None, Num::F(x)) => Some(if times { x * i as f64 } else { x + i as f64 }),
            (Some(acc), n) => Some(if times { acc * n.f() } else { acc + n.f() }),
        };
    }
    Ok(out(ctx, f.map_or(Num::I(i), Num::F)))
}

pub(super) fn plus(args: &[Sym], ctx: &mut RhsContext) -> Result<Sym, String> {
    accumulate(args, ctx, false)
}

pub(super) fn times(args: &[Sym], ctx: &mut RhsContext) -> Result<Sym, String> {
    accumulate(args, ctx, true)
}

pub(super) fn minus(args: &[Sym], ctx: &mut RhsContext) -> Result<Sym, String> {
    if args.is_empty() {
        return Err("Error: '-' function called with no arguments".into());
    }
    let ns = nums(ctx, args, "Error: non-number ({}) passed to - function")?;
    if ns.len() == 1 {
        let r = match ns[0] {
            Num::I(i) => Num::I(i.wrapping_neg()),
            Num::F(f) => Num::F(-f),
        };
        return Ok(out(ctx, r));
    }
    let mut i: i64 = 0;
    let mut f: Option<f64> = None;
    match ns[0] {
        Num::I(x) => i = x,
        Num::F(x) => f = Some(x),
    }
    for n in &ns[1..] {
        f = match (f, *n) {
            (None, Num::I(x)) => {
                i = i.wrapping_sub(x);
                None
            }
            (None, Num::F(x)) => Some(i as f64 - x),
            (Some(acc), n) => Some(acc - n.f()),
        };
    }
    Ok(out(ctx, f.map_or(Num::I(i), Num::F)))
}

/// `/`: always a float; unary `1/x`.
pub(super) fn divide(args: &[Sym], ctx: &mut RhsContext) -> Result<Sym, String> {
    const ZERO: &str = "Error: attempt to divide ('/') by zero.";
    if args.is_empty() {
        return Err("Error: '/' function called with no arguments".into());
    }
    let ns = nums(ctx, args, "Error: non-number ({}) passed to / function")?;
    if ns.len() == 1 {
        let f = ns[0].f();
        if f != 0.0 {
            return Ok(ctx.symbols.float(1.0 / f));
        }
        return Err(ZERO.into());
    }
    let mut f = ns[0].f();
    for n in &ns[1..] {
        let d = match n {
            Num::I(0) => return Err(ZERO.into()),
            Num::F(x) if *x == 0.0 => return Err(ZERO.into()),
            n => n.f(),
        };
        f /= d;
    }
    Ok(ctx.symbols.float(f))
}

/// `div` and `mod`: two ints, C truncation (`(div -7 2)` = -3, `(mod -7 2)` = -1).
pub(super) fn div_mod(name: &str, args: &[Sym], ctx: &mut RhsContext) -> Result<Sym, String> {
    if args.len() < 2 {
        return Err(arity_error(name, 2));
    }
    let mut v = [0i64; 2];
    for (k, a) in args[..2].iter().enumerate() {
        match ctx.symbols.get(*a) {
            SymData::Int(i) => v[k] = *i,
            _ => {
                return Err(format!(
                    "Error: non-integer ({}) passed to {name} function",
                    ctx.y(*a)
                ))
            }
        }
    }
    if v[1] == 0 {
        return Err(format!("Error: attempt to divide ('{name}') by zero."));
    }
    // i64::MIN by -1 traps in C; it wraps here.
    let r = if name == "div" {
        v[0].wrapping_div(v[1])
    } else {
        v[0].wrapping_rem(v[1])
    };
    Ok(ctx.symbols.int(r))
}

/// `abs`, `sqrt`, `sin`, `cos`.
pub(super) fn unary(name: &str, args: &[Sym], ctx: &mut RhsContext) -> Result<Sym, String> {
    let Some(&a) = args.first() else {
        return Err(format!("Error: '{name}' function called with no arguments"));
    };
    let Some(n) = num(ctx, a) else {
        return Err(format!(
            "Error: '{name}' function called with non-numeric argument {}",
            ctx.y(a)
        ));
    };
    let r = match (name, n) {
        ("abs", Num::I(i)) => Num::I(i.wrapping_abs()),
        ("abs", Num::F(f)) => Num::F(f.abs()),
        ("sqrt", n) => Num::F(n.f().sqrt()),
        ("sin", n) => Num::F(n.f().sin()),
        (_, n) => Num::F(n.f().cos()),
    };
    Ok(out(ctx, r))
}

pub(super) fn atan2(args: &[Sym], ctx: &mut RhsContext) -> Result<Sym, String> {
    if args.is_empty() {
        return Err("Error: 'atan2' function called with no arguments".into());
    }
    let ns = nums(ctx, args, "Error: non-number ({}) passed to atan2")?;
    if ns.len() == 1 {
        return Err("Error: 'atan2' function called with only one argument".into());
    }
    if ns.len() > 2 {
        return Err("Error: 'atan2' function called with more than two arguments.".into());
    }
    Ok(ctx.symbols.float(ns[0].f().atan2(ns[1].f())))
}

/// `min`/`max`: ints while no float has been seen; then a double (the int extreme so far
/// carries over). No argument gives the int 0.
pub(super) fn min_max(is_min: bool, args: &[Sym], ctx: &mut RhsContext) -> Result<Sym, String> {
    let which = if is_min { "min" } else { "max" };
    let ns = nums(
        ctx,
        args,
        &format!("Error: non-number ({{}}) passed to {which} function"),
    )?;
    let better = |x: f64, y: f64| if is_min { x < y } else { x > y };
    let better_i = |x: i64, y: i64| if is_min { x < y } else { x > y };
    let mut best_i: i64 = 0;
    let mut best_f: Option<f64> = None;
    for (k, n) in ns.into_iter().enumerate() {
        let first = k == 0;
        match (best_f, n) {
            (None, Num::I(x)) => {
                if first || better_i(x, best_i) {
                    best_i = x;
                }
            }
            (None, Num::F(x)) => {
                let cur = best_i as f64;
                best_f = Some(if first || better(x, cur) { x } else { cur });
            }
            (Some(cur), n) => {
                let x = n.f();
                if better(x, cur) {
                    best_f = Some(x);
                }
            }
        }
    }
    Ok(out(ctx, best_f.map_or(Num::I(best_i), Num::F)))
}

pub(super) fn int(args: &[Sym], ctx: &mut RhsContext) -> Result<Sym, String> {
    if args.is_empty() {
        return Err("Error: 'int' function called with no arguments.".into());
    }
    if args.len() > 1 {
        return Err("Error: 'int' takes exactly 1 argument.".into());
    }
    let a = args[0];
    let v = match ctx.symbols.get(a) {
        SymData::Id(_) => {
            return Err(format!(
                "Error: identifier ({}) passed to 'int' RHS function.",
                ctx.y(a)
            ))
        }
        SymData::Int(_) => return Ok(a),
        SymData::Float(f) => f64_to_i64(f.trunc()),
        SymData::Str(s) => c_strtol(s).map_err(|_| {
            format!(
                "Error: bad integer ({}) given to 'int' RHS function",
                ctx.y(a)
            )
        })?,
    };
    Ok(ctx.symbols.int(v))
}

pub(super) fn float(args: &[Sym], ctx: &mut RhsContext) -> Result<Sym, String> {
    if args.is_empty() {
        return Err("Error: 'float' function called with no arguments.".into());
    }
    if args.len() > 1 {
        return Err("Error: 'float' takes exactly 1 argument.".into());
    }
    let a = args[0];
    let v = match ctx.symbols.get(a) {
        SymData::Id(_) => {
            return Err(format!(
                "Error: identifier ({}) passed to 'float' RHS function.",
                ctx.y(a)
            ))
        }
        SymData::Float(_) => return Ok(a),
        SymData::Int(i) => *i as f64,
        SymData::Str(s) => {
            let (v, erange) = c_strtod(s);
            if erange {
                return Err(format!(
                    "Error: bad float ({}) given to 'float' RHS function",
                    ctx.y(a)
                ));
            }
            v
        }
    };
    Ok(ctx.symbols.float(v))
}

/// `round-off` and `round-off-heading`: an int divisor rounds the (truncated) first argument
/// with integer arithmetic (`(round-off 17 5)` = 15: 9.6 adds `m/2` and truncates); a float
/// divisor works in tenths. Non-numbers read as 0, without an error.
pub(super) fn round_off(heading: bool, args: &[Sym], ctx: &mut RhsContext) -> Result<Sym, String> {
    let (label, label2) = if heading {
        (
            "'round-off-heading' function",
            "'round-off-heading' function",
        )
    } else {
        ("'round_off' function", "'round_off' function")
    };
    if args.is_empty() {
        return Err(format!("Error: {label} called with no arguments"));
    }
    if args.len() == 1 {
        return Err(format!("Error: {label2} called with only one argument."));
    }
    if args.len() > 2 {
        return Err(format!(
            "Error: {label2} called with more than two arguments."
        ));
    }
    let n = num(ctx, args[0]).map_or(0.0, Num::f);
    match num(ctx, args[1]) {
        Some(Num::F(m)) => {
            let r = round_off_float(n, m);
            let r = if heading {
                normalize_heading_float(r)
            } else {
                r
            };
            Ok(ctx.symbols.float(r))
        }
        other => {
            let m = match other {
                Some(Num::I(i)) => i,
                _ => 0,
            };
            if m == 0 {
                // 9.6 divides by zero here and dies with SIGFPE.
                let name = if heading {
                    "round-off-heading"
                } else {
                    "round-off"
                };
                return Err(format!("Error: attempt to divide ('{name}') by zero."));
            }
            let r = round_off_int(f64_to_i64(n), m);
            let r = if heading { normalize_heading_int(r) } else { r };
            Ok(ctx.symbols.int(r))
        }
    }
}

fn round_off_int(n: i64, m: i64) -> i64 {
    let half = m / 2;
    let shifted = if n < 0 {
        n.wrapping_sub(half)
    } else {
        n.wrapping_add(half)
    };
    m.wrapping_mul(shifted.wrapping_div(m))
}

fn round_off_float(n: f64, m: f64) -> f64 {
    let n10 = (n * 10.0).trunc();
    let m10 = (m * 10.0).trunc();
    let half = (m10 / 2.0).trunc();
    let q = if n10 < 0.0 {
        ((n10 - half) / m10).trunc()
    } else {
        ((n10 + half) / m10).trunc()
    };
    (m10 * q) / 10.0
}

/// Into (-180, 180] (9.6 loops adding or subtracting 360).
fn normalize_heading_int(n: i64) -> i64 {
    (((i128::from(n) + 179).rem_euclid(360)) - 179) as i64
}

fn normalize_heading_float(mut n: f64) -> f64 {
    if n.is_finite() && n.abs() < 1e7 {
        while n <= -180.0 {
            n += 360.0;
        }
        while n > 180.0 {
            n -= 360.0;
        }
        n
    } else {
        // 9.6 would loop (nearly) for ever; a closed form instead.
        let r = (n + 179.0).rem_euclid(360.0) - 179.0;
        if r <= -180.0 {
            r + 360.0
        } else {
            r
        }
    }
}

/// 9.6's own (short) value of pi, which its headings depend on.
#[allow(clippy::approx_constant)]
const PI: f64 = 3.141592653589;
const PI_OVER_TWO: f64 = PI / 2.0;
const TWO_PI: f64 = PI * 2.0;

fn heading_to_point(cx: i64, cy: i64, x: i64, y: i64) -> i64 {
    let dx = x as f64 - cx as f64;
    let dy = y as f64 - cy as f64;
    let mag = (dx * dx + dy * dy).sqrt();
    let (nx, ny) = if mag < 0.01 {
        (1.0, 0.0)
    } else {
        (dx / mag, dy / mag)
    };
    let mut h = ny.atan2(nx) - PI_OVER_TWO;
    if h < 0.0 {
        h += TWO_PI;
    }
    h = TWO_PI - h;
    if h > PI {
        h -= TWO_PI;
    }
    // air_soar_round_off_angle(n, 1): the remainder keeps the dividend's sign.
    let n = f64_to_i64((h * 180.0) / PI);
    let mut b = n.wrapping_rem(360);
    if b > 180 {
        b -= 360;
    }
    if b <= -180 {
        b += 360;
    }
    b
}

/// `compute-heading` (int degrees from x1,y1 to x2,y2) and `compute-range` (int distance).
pub(super) fn heading_range(
    heading: bool,
    args: &[Sym],
    ctx: &mut RhsContext,
) -> Result<Sym, String> {
    let name = if heading {
        "compute-heading"
    } else {
        "compute-range"
    };
    if args.is_empty() {
        return Err(format!("Error: '{name}' function called with no arguments"));
    }
    let ns = nums(
        ctx,
        args,
        &format!("Error: non-number ({{}}) passed to - {name}"),
    )?;
    if ns.len() != 4 {
        return Err(format!("Error: '{name}' takes exactly 4 arguments."));
    }
    let r = if heading {
        heading_to_point(ns[0].i(), ns[1].i(), ns[2].i(), ns[3].i())
    } else {
        let (dx, dy) = (ns[0].f() - ns[2].f(), ns[1].f() - ns[3].f());
        f64_to_i64((dx * dx + dy * dy).sqrt())
    };
    Ok(ctx.symbols.int(r))
}

/// More dice than this make `compute-dice-probability` an error (9.6 computes binomials
/// with a Pascal triangle of that size, in quadratic time).
pub const MAX_DICE: i64 = 20_000;

/// `compute-dice-probability dice sides count pred`.
pub(super) fn dice(args: &[Sym], ctx: &mut RhsContext) -> Result<Sym, String> {
    if args.len() < 4 {
        return Err(arity_error("compute-dice-probability", 4));
    }
    let mut v = [0i64; 3];
    for (k, what) in ["dice", "sides", "count"].iter().enumerate() {
        match num(ctx, args[k]) {
            Some(n) => v[k] = n.i(),
            None => {
                return Err(format!(
                    "Error: non-number ({}) passed as '{what}' to - compute-dice-probability",
                    ctx.y(args[k])
                ))
            }
        }
    }
    let pred = match ctx.symbols.get(args[3]) {
        SymData::Str(s) => s.to_string(),
        _ => {
            return Err(format!(
                "Error: non-string ({}) passed as 'pred' to - compute-dice-probability",
                ctx.y(args[3])
            ))
        }
    };
    if !["eq", "ne", "lt", "gt", "le", "ge"].contains(&pred.as_str()) {
        return Err(format!(
            "Error: invalid string ({}) passed as 'pred' to - compute-dice-probability",
            ctx.y(args[3])
        ));
    }
    let [d, s, c] = v;
    if d > MAX_DICE {
        return Err(format!(
            "Error: too many dice ({d}) passed to compute-dice-probability (at most {MAX_DICE})"
        ));
    }
    let dp = Dice::new(d, s);
    let z = |x: f64| if x.abs() <= 0.00001 { 0.0 } else { x };
    let r = match pred.as_str() {
        "eq" if c < 0 || c > d => 0.0,
        "eq" => z(dp.exact(c)),
        "ne" if c < 0 || c > d => 1.0,
        "ne" => z(1.0 - dp.exact(c)),
        "lt" if c <= 0 => 0.0,
        "lt" if c > d => 1.0,
        "lt" => z(1.0 - dp.at_least(c)),
        "gt" if c < 0 => 1.0,
        "gt" if c >= d => 0.0,
        "gt" => z(dp.at_least(c) - dp.exact(c)),
        "le" if c < 0 => 0.0,
        "le" if c >= d => 1.0,
        "le" => z((1.0 - dp.at_least(c)) + dp.exact(c)),
        // "ge"
        _ if c <= 0 => 1.0,
        _ if c > d => 0.0,
        _ => z(dp.at_least(c)),
    };
    Ok(ctx.symbols.float(r))
}

/// 9.6's `_dice_prob_exact` and `_dice_prob_atleast`, with the binomials (wrapping `u64`
/// Pascal triangle, as 9.6 computes them) taken from one row.
struct Dice {
    dice: i64,
    sides: i64,
    row: Vec<u64>,
}

impl Dice {
    fn new(dice: i64, sides: i64) -> Self {
        let n = dice.max(0) as usize;
        let mut row = vec![0u64; n + 1];
        row[0] = 1;
        for i in 1..=n {
            row[i] = 1;
            for j in (1..i).rev() {
                row[j] = row[j].wrapping_add(row[j - 1]);
            }
        }
        Dice { dice, sides, row }
    }

    fn exact(&self, count: i64) -> f64 {
        let (dice, sides) = (self.dice, self.sides);
        if dice < 0 || count < 0 || sides < 1 {
            return 0.0;
        }
        if dice == 0 {
            return if count == 0 { 1.0 } else { 0.0 };
        }
        if count > dice {
            return 0.0;
        }
        let p1kd = (sides as f64).powf(count as f64);
        let p2nkn = ((sides - 1) as f64).powf((dice - count) as f64);
        let p2nkd = (sides as f64).powf((dice - count) as f64);
        let mut r = self.row[count as usize] as f64;
        r *= 1.0 / p1kd;
        r *= p2nkn / p2nkd;
        r
    }

    fn at_least(&self, count: i64) -> f64 {
        if self.dice < 0 || count < 0 || self.sides < 1 {
            return 0.0;
        }
        let mut r = 0.0;
        let mut k = count;
        while k <= self.dice {
            r += self.exact(k);
            k += 1;
        }
        r
    }
}

/// `rand-int [n]`: with n > 0 (a float truncated), uniform in `0..=n` (n cast to 32 bits,
/// as 9.6 does); otherwise the generator's raw 32-bit output.
pub(super) fn rand_int(args: &[Sym], ctx: &mut RhsContext) -> Result<Sym, String> {
    let n = match args.first() {
        None => 0,
        Some(&a) => match num(ctx, a) {
            Some(n) => n.i(),
            None => {
                return Err(format!(
                    "Error: non-number ({}) passed to - rand-int",
                    ctx.y(a)
                ))
            }
        },
    };
    let v = if n > 0 {
        ctx.rng.rand_int(n as u32)
    } else {
        ctx.rng.next_u32()
    };
    Ok(ctx.symbols.int(i64::from(v)))
}

/// `rand-float [n]`: `rand() * n` when n > 0, else `rand()`, in `[0, 1]`.
pub(super) fn rand_float(args: &[Sym], ctx: &mut RhsContext) -> Result<Sym, String> {
    let n = match args.first() {
        None => 0.0,
        Some(&a) => match num(ctx, a) {
            Some(n) => n.f(),
            None => {
                return Err(format!(
                    "Error: non-number ({}) passed to - rand-float",
                    ctx.y(a)
                ))
            }
        },
    };
    let r = ctx.rng.rand_float();
    Ok(ctx.symbols.float(if n > 0.0 { r * n } else { r }))
}
