//! The exceptions the binding raises: every misuse becomes one, with a message that says
//! what went wrong, never a crash.

use pyo3::create_exception;
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;

create_exception!(
    _rusoar,
    SoarError,
    PyRuntimeError,
    "An error of the Soar kernel or a misuse of its API. A rule or command that does not \
     parse carries `file`, `line` and `column` (None when the text has no place)."
);

/// The error of a call made after `Kernel.Shutdown`.
pub fn shut_down() -> PyErr {
    SoarError::new_err("the kernel was shut down: create a new kernel to go on")
}

/// The error of a call on something destroyed.
pub fn destroyed(what: &str) -> PyErr {
    SoarError::new_err(what.to_string())
}

/// A kernel error as a `SoarError` with its message and place.
pub fn soar_error(py: Python<'_>, e: &rusoar::Error) -> PyErr {
    let err = SoarError::new_err(e.render().trim_end().to_string());
    let value = err.value(py);
    let (file, line, column) = match e.location() {
        Some(l) => (
            Some(l.name.clone()),
            Some(l.line as u64),
            Some(l.column as u64),
        ),
        None => (None, None, None),
    };
    // Setting attributes on a fresh exception object cannot fail.
    let _ = value.setattr("message", e.message());
    let _ = value.setattr("file", file);
    let _ = value.setattr("line", line);
    let _ = value.setattr("column", column);
    err
}
