//! Functions the embedding program adds, typed: they get the arguments as symbols and
//! numbers, and return a value or an error. A rule calls one as `(name args...)` or
//! `(exec name args...)`. (SML's string functions, which get the arguments' texts joined
//! into one string and return a string, are the registry's other kind; see [`super::exec`].)
//!
//! A function that panics is caught: the panic is reported in the trace as an error and
//! the call's value is the error text, so the agent stays usable.

use crate::value::Value;
use crate::symbols::{Sym, SymData, Symbols};

/// One argument of a host function's call.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RhsArg<'a> {
    /// An integer constant.
    Int(i64),
    /// A floating-point constant.
    Float(f64),
    /// A string constant.
    Str(&'a str),
    /// An identifier.
    Id(Sym),
}

impl RhsArg<'_> {
    /// The argument as a number, if it is an integer or a float.
    pub fn as_f64(&self) -> Option<f64> {
        match *self {
            RhsArg::Int(i) => Some(i as f64),
            RhsArg::Float(f) => Some(f),
            _ => None,
        }
    }

    /// The argument as an integer, if it is one.
    pub fn as_i64(&self) -> Option<i64> {
        match *self {
            RhsArg::Int(i) => Some(i),
            _ => None,
        }
    }

    /// The argument as a string constant, if it is one.
    pub fn as_str(&self) -> Option<&str> {
        match self {
            RhsArg::Str(s) => Some(s),
            _ => None,
        }
    }
}

/// What a host function can see of the agent that calls it.
pub struct RhsCall<'a> {
    pub(crate) agent_name: &'a str,
    pub(crate) decision: u64,
    pub(crate) symbols: &'a Symbols,
}

impl RhsCall<'_> {
    /// The calling agent's name.
    pub fn agent_name(&self) -> &str {
        self.agent_name
    }

    /// The decision cycle the call happens in (as the `dc` RHS function counts).
    pub fn decision(&self) -> u64 {
        self.decision
    }

    /// A symbol as Soar prints it (`S1`, `|hello world|`, `3.5`).
    pub fn text(&self, s: Sym) -> String {
        self.symbols.text(s)
    }
}

/// A typed host function.
pub type TypedRhsFn = Box<dyn FnMut(&RhsCall, &[RhsArg]) -> Result<Value, String>>;

/// The arguments of a call as [`RhsArg`]s.
pub(crate) fn args<'a>(symbols: &'a Symbols, syms: &[Sym]) -> Vec<RhsArg<'a>> {
    syms.iter()
        .map(|&s| match symbols.get(s) {
            SymData::Int(i) => RhsArg::Int(*i),
            SymData::Float(f) => RhsArg::Float(*f),
            SymData::Str(x) => RhsArg::Str(x),
            SymData::Id(_) => RhsArg::Id(s),
        })
        .collect()
}

/// Runs `f`; a panic in it is caught and its message returned as the outer error.
pub(crate) fn guarded<T>(
    name: &str,
    f: impl FnOnce() -> Result<T, String>,
) -> Result<Result<T, String>, String> {
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)) {
        Ok(r) => Ok(r),
        Err(payload) => {
            let why = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "no message".to_string());
            Err(format!("rhs function {name} panicked: {why}"))
        }
    }
}
