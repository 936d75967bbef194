//! Evaluation of the built-in RHS functions (Soar manual, ch. 3, "Right-hand side
//! Functions") with Soar 9.6's exact results and error texts, and the [`Registry`] through
//! which an embedding program adds its own functions by name (`exec`, and direct calls such
//! as `(getlength a b)`).
//!
//! The decision cycle evaluates a function call's arguments first (innermost calls first,
//! left to right); if one of them failed, 9.6 does not call the outer function and the
//! action is skipped. Otherwise it calls [`call`] with the argument symbols:
//!
//! - `Ok(Some(value))`: a value function's result.
//! - `Ok(None)`: a stand-alone function (`write`, `halt`, ...) ran.
//! - `Err(message)`: the function failed (9.6's NIL). The caller prints `message` followed
//!   by a newline, starting on a fresh line first when [`RhsContext::error_fresh_line`] is
//!   set (9.6's `%e`), and skips the make action. An **empty** message means 9.6 fails
//!   silently (`accept` at end of input, `from-st-xml` on bad XML, `ifeq` without an else
//!   value): print nothing.
//!
//! Besides its result, a call can leave things in the context for the caller:
//! [`RhsContext::halt`], [`RhsContext::interrupt`], [`RhsContext::dont_learn`],
//! [`RhsContext::force_learn`], text appended to [`RhsContext::output`] (`write`, `trace`,
//! `log`), [`RhsContext::deep_copy_wmes`] (`deep-copy`) and [`RhsContext::module_wmes`]
//! (`from-st-xml`). See each field.
//!
//! Known differences from 9.6, all where 9.6 crashes, hangs or reads freed memory:
//! `round-off`/`round-off-heading` with an integer 0 divisor (9.6: SIGFPE; here an error),
//! `div`/`mod` of `i64::MIN` by -1 (9.6: SIGFPE; here wrapping), `set-*` with no argument
//! (9.6: segfault; here the "first parameter" error string), `sum`/`product` over string
//! values (9.6 adds the low bits of a pointer; here 0), headings of huge or infinite values
//! (9.6 loops for ever; here a closed form), `compute-dice-probability` with more than
//! [`MAX_DICE`] dice (9.6 allocates and loops for ever; here an error), `timestamp` (local
//! time in 9.6; UTC here, the same when `TZ` is UTC).

pub mod host;
mod math;
mod numeric;
pub mod table;
mod text;

mod wmefns;
mod xml;

#[cfg(test)]
mod tests;

use crate::rng::Mt19937;
use crate::symbols::{Sym, SymData, Symbols};
use crate::wm::{WmeId, WorkingMemory};
use std::collections::BTreeMap;

pub use numeric::NumericRhsFn;
pub use text::{c_fixed, c_general, value_text};

/// A function registered by the embedding program: `(agent name, argument string) -> result`.
pub type RhsFn = Box<dyn FnMut(&str, &str) -> String>;

/// Functions added by the embedding program (SML's string form, [`RhsFn`], or typed,
/// [`host::TypedRhsFn`]), and the per-agent state of the built-ins
/// that outlives one call (`make-constant-symbol`'s counter, `count`'s counters).
pub struct Registry {
    functions: BTreeMap<String, RhsFn>,
    typed: BTreeMap<String, host::TypedRhsFn>,
    /// Numeric forms of some of `functions` (see `numeric.rs`).
    numeric: BTreeMap<String, NumericRhsFn>,
    /// The numbers of the current numeric call (a reused buffer).
    numbers: Vec<f64>,
    /// The next number `make-constant-symbol` tries. Starts at 1; `init-soar` does **not**
    /// reset it (observed on 9.6).
    pub mcs_counter: u64,
    /// `(count a b)` counters by the arguments' text.
    pub counts: BTreeMap<String, u64>,
}

impl Default for Registry {
    fn default() -> Self {
        Self::new()
    }
}

impl std::fmt::Debug for Registry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Registry")
            .field("functions", &self.functions.keys().collect::<Vec<_>>())
            .field("mcs_counter", &self.mcs_counter)
            .field("counts", &self.counts)
            .finish()
    }
}

impl Registry {
    pub fn new() -> Self {
        Registry {
            functions: BTreeMap::new(),
            typed: BTreeMap::new(),
            numeric: BTreeMap::new(),
            numbers: Vec::new(),
            mcs_counter: 1,
            counts: BTreeMap::new(),
        }
    }

    /// Registers `f` under `name`, returning the function it replaces. `(exec name ...)` and
    /// `(name ...)` (which the parser rewrites to `exec`) call it with the agent's name and
    /// the arguments' texts concatenated with no separator; its result becomes a string.
    /// A numeric form registered before for `name` is dropped: it belonged to the old
    /// function.
    pub fn register(&mut self, name: &str, f: RhsFn) -> Option<RhsFn> {
        self.numeric.remove(name);
        self.typed.remove(name);
        self.functions.insert(name.to_string(), f)
    }

    /// Registers a typed function under `name`, in place of any function of that name.
    pub fn register_typed(&mut self, name: &str, f: host::TypedRhsFn) {
        self.unregister(name);
        self.typed.insert(name.to_string(), f);
    }

    /// Adds a numeric form to the function registered as `name` (false, and nothing added,
    /// when there is none): `exec` calls it instead when the arguments are numbers between
    /// comma separators, with the numbers the argument string would hold. It must return
    /// what the text form returns for that string (see `numeric.rs`).
    pub fn register_numeric(&mut self, name: &str, f: NumericRhsFn) -> bool {
        if !self.functions.contains_key(name) {
            return false;
        }
        self.numeric.insert(name.to_string(), f);
        true
    }

    /// Removes the function registered as `name`; false when there was none.
    pub fn unregister(&mut self, name: &str) -> bool {
        self.numeric.remove(name);
        let typed = self.typed.remove(name).is_some();
        self.functions.remove(name).is_some() || typed
    }

    /// Whether a function of either kind is registered as `name`.
    pub fn is_registered(&self, name: &str) -> bool {
        self.functions.contains_key(name) || self.typed.contains_key(name)
    }

    /// Calls the string function registered as `name`, if any; a panic in it is the outer
    /// error (see [`host::guarded`]).
    pub fn call(
        &mut self,
        name: &str,
        agent: &str,
        args: &str,
    ) -> Option<Result<Result<String, String>, String>> {
        let f = self.functions.get_mut(name)?;
        Some(host::guarded(name, || Ok(f(agent, args))))
    }
}

/// The WMEs of an identifier as 9.6 walks them: `.0` the WMEs in its slots (slots in the
/// kernel's slot-list order, each slot's WMEs newest first), `.1` its input WMEs (added by
/// I/O; newest first). Architecture WMEs of states and impasses (`^type state`,
/// `^superstate`, `^impasse`, `^item`, ...) and acceptable-preference WMEs are in neither.
pub type WmeOrder<'a> = &'a dyn Fn(Sym) -> (Vec<WmeId>, Vec<WmeId>);

/// Everything an RHS function may read or change.
pub struct RhsContext<'a> {
    pub symbols: &'a mut Symbols,
    pub wm: &'a WorkingMemory,
    /// The process-global generator (`rand-int`, `rand-float`), one for all agents as in
    /// Soar.
    pub rng: &'a mut Mt19937,
    pub registry: &'a mut Registry,
    /// `write`, `trace` and `log` append here.
    pub output: &'a mut String,
    pub agent_name: &'a str,
    /// `dc`: the agent's count of decision phases.
    pub decision_count: u64,
    /// `output agent-writes`: when false, `write`, `trace` and `log` do nothing (not even
    /// their argument checks), as in 9.6.
    pub agent_writes: bool,
    /// `(trace n ...)` prints when `trace_flags[n]` is set; see [`trace_flags_for_level`].
    pub trace_flags: [bool; 6],
    /// How `size`, `sum`, `product`, `set-*` and `deep-copy` see an identifier's WMEs. When
    /// `None`, all non-acceptable WMEs of the id count as slot WMEs, grouped by attribute
    /// (attributes by their oldest WME, WMEs newest first), which is 9.6's order for
    /// structures one firing created but counts the architecture WMEs 9.6 leaves out
    /// (`(size <s>)` of the top state is 3 in 9.6).
    pub wme_order: Option<WmeOrder<'a>>,
    /// Runs a command line for `cmd` and returns its output. `None`: `cmd` returns `||`.
    pub command: Option<&'a mut dyn FnMut(&str) -> String>,

    /// Set by `halt` (and `succeeded`/`failed`): stop at the end of the phase.
    pub halt: bool,
    /// Set by `interrupt`: stop all agents after the smallest step.
    pub interrupt: bool,
    /// Set by `dont-learn` to its state (9.6 adds it to `chunk_free_problem_spaces`).
    pub dont_learn: Option<Sym>,
    /// Set by `force-learn` to its state (9.6 adds it to `chunky_problem_spaces`).
    pub force_learn: Option<Sym>,
    /// `deep-copy`: the copied WMEs, in 9.6's order (`glbDeepCopyWMEs`: each WME after the
    /// structure under its attribute and value). Every call of `deep-copy` clears it first.
    /// 9.6 turns them into acceptable preferences of the instantiation (o- or i-support as
    /// the rule's) right after the make action whose value produced them: after executing a
    /// make action that made a preference, if this list is non-empty, add one preference per
    /// entry in order, then clear it. (9.6 does not clear it after a stand-alone action, so
    /// a `(write (deep-copy <x>))` leaks its copy into the next make action; checking after
    /// every make action reproduces that.) The new identifiers have level 0; the caller
    /// sets them to the level of the make action's id.
    pub deep_copy_wmes: Vec<(Sym, Sym, Sym)>,
    /// `from-st-xml`: WMEs 9.6 adds to working memory at once, as architecture (module)
    /// WMEs without preferences, in this order, before the action's own preference. Their
    /// new identifiers have level 0.
    pub module_wmes: Vec<(Sym, Sym, Sym)>,
    /// Set with an `Err` whose text 9.6 prints with `%e`: start a fresh line first.
    pub error_fresh_line: bool,
    /// The `log` channels turned off (`output agent-logs N off`), as bits 1 to 100.
    pub log_channels_off: u128,
    /// For `link-stm-to-ltm`: whether semantic memory holds the long-term identifier its
    /// second argument names (the caller, which holds the memory, looks it up).
    pub ltm_exists: bool,
}

impl<'a> RhsContext<'a> {
    pub fn new(
        symbols: &'a mut Symbols,
        wm: &'a WorkingMemory,
        rng: &'a mut Mt19937,
        registry: &'a mut Registry,
        output: &'a mut String,
        agent_name: &'a str,
    ) -> Self {
        RhsContext {
            symbols,
            wm,
            rng,
            registry,
            output,
            agent_name,
            decision_count: 0,
            agent_writes: true,
            trace_flags: trace_flags_for_level(1),
            wme_order: None,
            command: None,
            halt: false,
            interrupt: false,
            dont_learn: None,
            force_learn: None,
            deep_copy_wmes: Vec::new(),
            module_wmes: Vec::new(),
            error_fresh_line: false,
            log_channels_off: 0,
            ltm_exists: false,
        }
    }

    /// 9.6's `to_string()`: strings without bars, floats with 6 decimals (`-nan`, `inf`).
    pub fn value_text(&self, s: Sym) -> String {
        value_text(self.symbols, s)
    }

    /// 9.6's `%y`: the rereadable form (strings with bars when needed).
    fn y(&self, s: Sym) -> String {
        text::rereadable_text(self.symbols, s)
    }

    fn str_sym(&mut self, s: &str) -> Sym {
        self.symbols.str(s)
    }
}

/// Which `(trace n ...)` levels print at a `watch`/`trace` level (observed on 9.6: level 1
/// prints `trace 1`, level 2 adds `trace 2`, level 3 and above add 3, 4 and 5; `trace 0`
/// never prints). Index n is 9.6's trace setting n: decisions, phases, user, default and
/// chunk firings.
pub fn trace_flags_for_level(level: u8) -> [bool; 6] {
    [
        false,
        level >= 1,
        level >= 2,
        level >= 3,
        level >= 3,
        level >= 3,
    ]
}

/// The built-in functions of the 9.6.5 binary this module implements: kernel functions and
/// the SML layer's `concat`, `exec`, `cmd` and `interrupt`. (`predict-x`, `predict-y` and
/// `compute-closest-intercept` are in newer kernel sources but not in the 9.6 binary: it
/// reads them as `exec` calls of unregistered functions, as [`call`] does.)
#[cfg(test)]
pub const BUILTIN_NAMES: &[&str] = &[
    "+",
    "*",
    "-",
    "/",
    "div",
    "mod",
    "abs",
    "sqrt",
    "sin",
    "cos",
    "atan2",
    "min",
    "max",
    "int",
    "float",
    "round-off",
    "round-off-heading",
    "compute-heading",
    "compute-range",
    "compute-dice-probability",
    "rand-int",
    "rand-float",
    "size",
    "sum",
    "product",
    "set-count",
    "set-sum",
    "set-multiply",
    "set-min",
    "set-max",
    "set-range",
    "set-mean",
    "set-stdev",
    "concat",
    "exec",
    "cmd",
    "interrupt",
    "write",
    "crlf",
    "log",
    "trace",
    "halt",
    "succeeded",
    "failed",
    "wait",
    "make-constant-symbol",
    "timestamp",
    "dc",
    "ifeq",
    "strlen",
    "string",
    "trim",
    "capitalize-symbol",
    "deep-copy",
    "accept",
    "count",
    "dont-learn",
    "force-learn",
    "link-stm-to-ltm",
    "@",
    "from-st-xml",
];

#[cfg(test)]
pub fn is_builtin(name: &str) -> bool {
    BUILTIN_NAMES.contains(&name)
}

/// Evaluates the RHS function `name` on already-evaluated arguments (see the module
/// documentation for the result). A name that is not a built-in is an `exec` call of a
/// registered function, as the parser rewrites it: `(getlength a b)` is
/// `(exec getlength a b)`.
pub fn call(name: &str, args: &[Sym], ctx: &mut RhsContext) -> Result<Option<Sym>, String> {
    ctx.error_fresh_line = false;
    // `exec` first: robot agents call it in most firings, and the match below tries its
    // arms in turn.
    if name == "exec" {
        return Ok(Some(exec(args, ctx)));
    }
    match name {
        "+" => math::plus(args, ctx).map(Some),
        "*" => math::times(args, ctx).map(Some),
        "-" => math::minus(args, ctx).map(Some),
        "/" => math::divide(args, ctx).map(Some),
        "div" | "mod" => math::div_mod(name, args, ctx).map(Some),
        "abs" | "sqrt" | "sin" | "cos" => math::unary(name, args, ctx).map(Some),
        "atan2" => math::atan2(args, ctx).map(Some),
        "min" | "max" => math::min_max(name == "min", args, ctx).map(Some),
        "int" => math::int(args, ctx).map(Some),
        "float" => math::float(args, ctx).map(Some),
        "round-off" | "round-off-heading" => {
            math::round_off(name == "round-off-heading", args, ctx).map(Some)
        }
        "compute-heading" | "compute-range" => {
            math::heading_range(name == "compute-heading", args, ctx).map(Some)
        }
        "compute-dice-probability" => math::dice(args, ctx).map(Some),
        "rand-int" => math::rand_int(args, ctx).map(Some),
        "rand-float" => math::rand_float(args, ctx).map(Some),
        "size" | "sum" | "product" => wmefns::size_sum_product(name, args, ctx).map(Some),
        "set-count" | "set-sum" | "set-multiply" | "set-min" | "set-max" | "set-range"
        | "set-mean" | "set-stdev" => wmefns::set_function(name, args, ctx).map(Some),
        "deep-copy" => wmefns::deep_copy(args, ctx).map(Some),
        "from-st-xml" => xml::from_st_xml(args, ctx).map(Some),
        "concat" => {
            let mut s = String::new();
            for a in args {
                text::push_value_text(ctx.symbols, *a, &mut s);
            }
            Ok(Some(ctx.str_sym(&s)))
        }
        "cmd" => Ok(Some(cmd(args, ctx))),
        "interrupt" => {
            ctx.interrupt = true;
            Ok(None)
        }
        "halt" | "succeeded" | "failed" => {
            ctx.halt = true;
            Ok(None)
        }
        "write" => {
            if ctx.agent_writes {
                for a in args {
                    text::push_value_text(ctx.symbols, *a, ctx.output);
                }
            }
            Ok(None)
        }
        "trace" | "log" => trace_log(name == "log", args, ctx),
        "crlf" => Ok(Some(ctx.str_sym("\n"))),
        "wait" => {
            // 9.6: `int ms = value` (default 1 when the argument is not an integer).
            let ms = match args.first().map(|a| ctx.symbols.get(*a)) {
                Some(SymData::Int(i)) => *i as i32,
                _ => 1,
            };
            if ms > 0 {
                std::thread::sleep(std::time::Duration::from_millis(ms as u64));
            }
            Ok(None)
        }
        "make-constant-symbol" => {
            let prefix: String = if args.is_empty() {
                // 9.6 returns `constant` itself only when no such string exists, but its
                // kernel always holds one: the first call gives `constant1` (observed).
                "constant".to_string()
            } else {
                args.iter().map(|a| ctx.value_text(*a)).collect()
            };
            loop {
                let name = format!("{prefix}{}", ctx.registry.mcs_counter);
                ctx.registry.mcs_counter = ctx.registry.mcs_counter.wrapping_add(1);
                if ctx.symbols.find_str(&name).is_none() {
                    return Ok(Some(ctx.str_sym(&name)));
                }
            }
        }
        "timestamp" => {
            let s = text::timestamp_now();
            Ok(Some(ctx.str_sym(&s)))
        }
        "dc" => {
            let n = ctx.decision_count as i64;
            Ok(Some(ctx.symbols.int(n)))
        }
        "ifeq" => ifeq(args, ctx),
        "strlen" => {
            let a = arg(name, args, 0, 1)?;
            let n = ctx.value_text(a).len() as i64;
            Ok(Some(ctx.symbols.int(n)))
        }
        "string" => {
            if args.is_empty() {
                return fresh(ctx, "Error: 'string' function called with no arguments.");
            }
            if args.len() > 1 {
                return fresh(ctx, "Error: 'string' takes exactly 1 argument.");
            }
            let s = match ctx.symbols.get(args[0]) {
                // `max_digits10` (17) digits after the point, `std::fixed`.
                SymData::Float(f) => c_fixed(*f, 17),
                _ => ctx.value_text(args[0]),
            };
            Ok(Some(ctx.str_sym(&s)))
        }
        "trim" | "capitalize-symbol" => text::trim_capitalize(name == "trim", args, ctx),
        "accept" => text::accept(ctx),
        "count" => {
            for a in args {
                let s = ctx.value_text(*a);
                *ctx.registry.counts.entry(s).or_insert(0) += 1;
            }
            Ok(None)
        }
        "dont-learn" | "force-learn" => learn_flag(name, args, ctx),
        "@" => {
            // No semantic memory: no identifier is linked to a long-term one.
            let a = match args.first() {
                Some(a) => *a,
                None => return fresh(ctx, "Error: '@' function called with no arguments."),
            };
            let msg = format!(
                "Error: {} is not linked to a semantic identifier.",
                ctx.y(a)
            );
            fresh(ctx, &msg)
        }
        "link-stm-to-ltm" => link_stm_to_ltm(args, ctx),
        _ => {
            // An unknown name is an `exec` call (the parser's rewrite).
            let mut all = Vec::with_capacity(args.len() + 1);
            all.push(ctx.str_sym(name));
            all.extend_from_slice(args);
            Ok(Some(exec(&all, ctx)))
        }
    }
}

/// `Err` with 9.6's `%e`: the caller starts a fresh line before printing it.
fn fresh<T>(ctx: &mut RhsContext, msg: &str) -> Result<T, String> {
    ctx.error_fresh_line = true;
    Err(msg.to_string())
}

/// Argument `i` of a function whose parse-time arity is `n` (the parser guarantees it; a
/// direct caller that breaks it gets the parser's message instead of a crash).
fn arg(name: &str, args: &[Sym], i: usize, n: usize) -> Result<Sym, String> {
    args.get(i).copied().ok_or_else(|| arity_error(name, n))
}

fn arity_error(name: &str, n: usize) -> String {
    format!("Wrong number of arguments to function {name} (expected {n})")
}

/// `exec` (SML): `args[0]` names the registered function; the rest are concatenated with no
/// separator. The result is always a string constant.
fn exec(args: &[Sym], ctx: &mut RhsContext) -> Sym {
    let Some((&f, rest)) = args.split_first() else {
        // 9.6 prints this to stderr and its RHS callback substitutes this value.
        eprintln!("exec should be followed by a function name ");
        return ctx.str_sym("error_expected_rhs_function_to_return_value_but_it_did_NOT");
    };
    let owned;
    let function: &str = match ctx.symbols.get(f) {
        SymData::Str(name) => name,
        _ => {
            owned = ctx.value_text(f);
            &owned
        }
    };
    let registry = &mut *ctx.registry;
    if let Some(f) = registry.typed.get_mut(function) {
        let call = host::RhsCall {
            agent_name: ctx.agent_name,
            decision: ctx.decision_count,
            symbols: ctx.symbols,
        };
        let args = host::args(ctx.symbols, rest);
        let result = match host::guarded(function, || f(&call, &args)) {
            Ok(r) => r,
            Err(panicked) => {
                // A panic is the host program's bug, not the agent's: the run stops after
                // this phase (as `(interrupt)` stops it), and the agent can go on.
                ctx.interrupt = true;
                Err(panicked)
            }
        };
        let function = function.to_string();
        let function = function.as_str();
        return match result {
            Ok(crate::value::Value::Int(i)) => ctx.symbols.int(i),
            Ok(crate::value::Value::Float(x)) => ctx.symbols.float(x),
            Ok(crate::value::Value::Str(s)) => ctx.str_sym(&s),
            Ok(crate::value::Value::Id(s)) if ctx.symbols.is_id(s) => s,
            Ok(crate::value::Value::Id(_)) => {
                host_error(ctx, function, "it returned a constant as an identifier")
            }
            Err(why) => host_error(ctx, function, &why),
        };
    }
    let fast = match registry.numeric.get_mut(function) {
        Some(numeric_form) => numeric::numbers(ctx.symbols, rest, &mut registry.numbers)
            .and_then(|()| numeric_form(&registry.numbers)),
        None => None,
    };
    let mut interrupt = false;
    let result = fast.unwrap_or_else(|| {
        let mut argument = String::new();
        for a in rest {
            text::push_value_text(ctx.symbols, *a, &mut argument);
        }
        match registry.call(function, ctx.agent_name, &argument) {
            Some(Ok(Ok(r))) => r,
            Some(Ok(Err(why))) => {
                report_host_error(ctx.output, ctx.symbols, &why);
                format!("Error: {why}")
            }
            Some(Err(panicked)) => {
                interrupt = true;
                report_host_error(ctx.output, ctx.symbols, &panicked);
                format!("Error: {panicked}")
            }
            None => format!("Error: Nobody was registered to implement rhs function {function}"),
        }
    });
    // As for a typed function: a panic stops the run after this phase.
    ctx.interrupt |= interrupt;
    ctx.str_sym(&result)
}

/// A host function failed: the trace says why, and the call's value is the error's text.
fn host_error(ctx: &mut RhsContext, function: &str, why: &str) -> Sym {
    let why = if why.contains(function) {
        why.to_string()
    } else {
        format!("rhs function {function} failed: {why}")
    };
    report_host_error(ctx.output, ctx.symbols, &why);
    ctx.str_sym(&format!("Error: {why}"))
}

fn report_host_error(output: &mut String, symbols: &Symbols, why: &str) {
    let event = crate::trace_events::TraceEvent::RhsError {
        message: &format!("Error: {why}"),
        fresh_line: true,
    };
    crate::trace_text::TraceText96.write(output, true, symbols, &event);
}

/// `cmd` (SML): every argument is preceded by a space (9.6's `first` flag is never set,
/// so the command line starts with a space); the output is returned as a string.
fn cmd(args: &[Sym], ctx: &mut RhsContext) -> Sym {
    if args.is_empty() {
        eprintln!("cmd should be followed by a command name ");
        return ctx.str_sym("error_expected_rhs_function_to_return_value_but_it_did_NOT");
    }
    let mut line = String::new();
    for a in args {
        line.push(' ');
        line.push_str(&ctx.value_text(*a));
    }
    let out = match ctx.command.as_mut() {
        Some(run) => run(&line),
        None => String::new(),
    };
    ctx.str_sym(&out)
}

fn trace_log(is_log: bool, args: &[Sym], ctx: &mut RhsContext) -> Result<Option<Sym>, String> {
    if !ctx.agent_writes {
        return Ok(None);
    }
    let name = if is_log { "log" } else { "trace" };
    let Some((&first, rest)) = args.split_first() else {
        return Err(arity_error(name, 1));
    };
    let n = match ctx.symbols.get(first) {
        SymData::Int(i) => Some(*i),
        _ => None,
    };
    let enabled = if is_log {
        match n {
            // Every channel is on until `output agent-logs N off`.
            Some(c @ 1..=100) => ctx.log_channels_off & (1u128 << c) == 0,
            _ => {
                let msg = format!(
                    "Error: First argument of agent's (log) rhs-function must be an integer channel number between 1 and 100.  {} is invalid.",
                    ctx.y(first)
                );
                return fresh(ctx, &msg);
            }
        }
    } else {
        match n {
            Some(l @ 0..=5) => ctx.trace_flags[l as usize],
            _ => {
                let msg = format!(
                    "Error: First argument of agent's (trace) rhs-function must be an integer trace level between 0 and 5.  {} is invalid.",
                    ctx.y(first)
                );
                return fresh(ctx, &msg);
            }
        }
    };
    if enabled {
        let s: String = rest.iter().map(|a| ctx.value_text(*a)).collect();
        ctx.output.push_str(&s);
    }
    Ok(None)
}

fn ifeq(args: &[Sym], ctx: &mut RhsContext) -> Result<Option<Sym>, String> {
    if args.is_empty() {
        return fresh(ctx, "Error: 'ifeq' function called with no arguments");
    }
    if args.len() < 3 {
        return Err(arity_error("ifeq", 4));
    }
    if args[0] == args[1] {
        Ok(Some(args[2]))
    } else if let Some(&e) = args.get(3) {
        Ok(Some(e))
    } else {
        Err(String::new())
    }
}

fn learn_flag(name: &str, args: &[Sym], ctx: &mut RhsContext) -> Result<Option<Sym>, String> {
    let Some(&state) = args.first() else {
        return fresh(
            ctx,
            &format!("Error: '{name}' function called with no arg."),
        );
    };
    if !ctx.symbols.is_id(state) {
        let msg = format!(
            "Error: non-identifier ({}) passed to {name} function.",
            ctx.y(state)
        );
        return fresh(ctx, &msg);
    }
    // 9.6 complains about a non-state but still records it.
    let mut complaint = None;
    if !ctx.symbols.is_goal(state) {
        complaint = Some(format!(
            "Error: identifier passed to {name} is not a state: {}.",
            ctx.y(state)
        ));
    }
    if args.len() > 1 {
        let mut msg = complaint.map(|c| c + "\n").unwrap_or_default();
        msg.push_str(&format!("Error: '{name}' takes exactly 1 argument."));
        return fresh(ctx, &msg);
    }
    if name == "dont-learn" {
        ctx.dont_learn = Some(state);
    } else {
        ctx.force_learn = Some(state);
    }
    match complaint {
        Some(c) => fresh(ctx, &c),
        None => Ok(None),
    }
}

fn link_stm_to_ltm(args: &[Sym], ctx: &mut RhsContext) -> Result<Option<Sym>, String> {
    let Some(&sym) = args.first() else {
        return fresh(ctx, "Error: '@' rhs function called with no arguments.");
    };
    if !ctx.symbols.is_id(sym) {
        let msg = format!(
            "Error: '@' rhs function cannot accept {} because it is not a Soar identifier",
            ctx.y(sym)
        );
        return fresh(ctx, &msg);
    }
    if args.len() != 2 {
        return fresh(ctx, "Error: '@' rhs function takes exactly 2 arguments.");
    }
    let lti = args[1];
    let n = match ctx.symbols.get(lti) {
        SymData::Int(i) => *i,
        _ => {
            let msg = format!(
                "Error: '@' rhs function cannot accept {} as an LTI ID because it is not an integer",
                ctx.y(lti)
            );
            return fresh(ctx, &msg);
        }
    };
    if ctx.ltm_exists {
        if let Some(d) = ctx.symbols.id_data_mut(sym) {
            d.lti = n;
        }
        return Ok(None);
    }
    let msg = format!(
        "Warning: Long-term memory @{} does not exist.  Could not link short-term memory {}.",
        n as u64,
        ctx.y(sym)
    );
    fresh(ctx, &msg)
}
