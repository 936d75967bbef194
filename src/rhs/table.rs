//! The table of built-in RHS function names, arities and where each may appear (Soar
//! manual, ch. 3, "Right-hand side Functions"). Evaluation lives with the decision cycle;
//! the parser needs only this table to check argument counts and to rewrite unknown names
//! to `exec`.

/// Where a function may be used.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Use {
    /// Only as a stand-alone action, e.g. `(write ...)`.
    Standalone,
    /// Only in value position, e.g. `^x (+ 1 2)`.
    Value,
    Both,
}

#[derive(Debug, Clone, Copy)]
pub struct FunctionInfo {
    pub name: &'static str,
    /// Exact argument count, or `None` for any number.
    pub arity: Option<usize>,
    pub usage: Use,
}

const fn f(name: &'static str, arity: Option<usize>, usage: Use) -> FunctionInfo {
    FunctionInfo { name, arity, usage }
}

/// The kernel's and the SML layer's functions, as registered in 9.6 (its `add_rhs_function`
/// calls).
pub const BUILTINS: &[FunctionInfo] = &[
    f("+", None, Use::Value),
    f("*", None, Use::Value),
    f("-", None, Use::Value),
    f("/", None, Use::Value),
    f("div", Some(2), Use::Value),
    f("mod", Some(2), Use::Value),
    f("abs", Some(1), Use::Value),
    f("sqrt", Some(1), Use::Value),
    f("sin", Some(1), Use::Value),
    f("cos", Some(1), Use::Value),
    f("atan2", Some(2), Use::Value),
    f("min", None, Use::Value),
    f("max", None, Use::Value),
    f("int", Some(1), Use::Value),
    f("float", Some(1), Use::Value),
    f("round-off", Some(2), Use::Value),
    f("round-off-heading", Some(2), Use::Value),
    f("compute-heading", Some(4), Use::Value),
    f("compute-range", Some(4), Use::Value),
    f("compute-dice-probability", Some(4), Use::Value),
    f("rand-int", None, Use::Value),
    f("rand-float", None, Use::Value),
    f("size", Some(1), Use::Value),
    f("sum", Some(1), Use::Value),
    f("product", Some(1), Use::Value),
    f("set-count", None, Use::Value),
    f("set-sum", None, Use::Value),
    f("set-multiply", None, Use::Value),
    f("set-min", None, Use::Value),
    f("set-max", None, Use::Value),
    f("set-range", None, Use::Value),
    f("set-mean", None, Use::Value),
    f("set-stdev", None, Use::Value),
    f("concat", None, Use::Value),
    f("@", Some(1), Use::Value),
    f("from-st-xml", Some(1), Use::Value),
    f("exec", None, Use::Both),
    f("cmd", None, Use::Both),
    f("interrupt", Some(0), Use::Standalone),
    f("write", None, Use::Standalone),
    f("crlf", Some(0), Use::Value),
    f("log", None, Use::Standalone),
    f("trace", None, Use::Standalone),
    f("halt", Some(0), Use::Standalone),
    f("wait", Some(1), Use::Standalone),
    f("make-constant-symbol", None, Use::Value),
    f("timestamp", Some(0), Use::Value),
    f("dc", Some(0), Use::Value),
    f("ifeq", Some(4), Use::Value),
    f("strlen", Some(1), Use::Value),
    f("string", Some(1), Use::Value),
    f("trim", Some(1), Use::Value),
    f("capitalize-symbol", Some(1), Use::Value),
    f("deep-copy", Some(1), Use::Value),
    f("accept", Some(0), Use::Value),
    f("count", None, Use::Standalone),
    f("dont-learn", Some(1), Use::Standalone),
    f("force-learn", Some(1), Use::Standalone),
    f("link-stm-to-ltm", Some(2), Use::Standalone),
];

/// Looks a built-in up by name. `succeeded` and `failed` read as `halt` outside unit tests.
pub fn lookup(name: &str) -> Option<&'static FunctionInfo> {
    let name = match name {
        "succeeded" | "failed" => "halt",
        n => n,
    };
    BUILTINS.iter().find(|f| f.name == name)
}
