//! [`Value`]: a constant or an identifier, as the embedding program hands it to the kernel
//! and gets it back (input WMEs, output-command parameters, host functions' results).

use crate::symbols::Sym;

/// A value: a constant or an existing identifier.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// An integer constant.
    Int(i64),
    /// A floating-point constant.
    Float(f64),
    /// A string constant.
    Str(String),
    /// An identifier that already exists.
    Id(Sym),
}

impl From<i64> for Value {
    fn from(v: i64) -> Self {
        Value::Int(v)
    }
}
impl From<i32> for Value {
    fn from(v: i32) -> Self {
        Value::Int(i64::from(v))
    }
}
impl From<f64> for Value {
    fn from(v: f64) -> Self {
        Value::Float(v)
    }
}
impl From<&str> for Value {
    fn from(v: &str) -> Self {
        Value::Str(v.to_string())
    }
}
impl From<String> for Value {
    fn from(v: String) -> Self {
        Value::Str(v)
    }
}
impl From<Sym> for Value {
    fn from(v: Sym) -> Self {
        Value::Id(v)
    }
}

impl Value {
    /// The value as a number: an integer or a float, or a string that reads as one (an SML
    /// client reads a command's parameters from their text).
    pub fn as_number(&self) -> Option<f64> {
        match self {
            Value::Int(i) => Some(*i as f64),
            Value::Float(f) => Some(*f),
            Value::Str(s) => s.trim().parse().ok(),
            Value::Id(_) => None,
        }
    }
}

