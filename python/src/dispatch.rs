//! Calls into Python that both threads make: the kernel-wide events (system, update and
//! agent events) and the checks a registration makes.

use crate::shared::{Callbacks, KernelShared};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use std::sync::atomic::Ordering;

/// Checks that `f` can be called, so that a bad registration fails where it is made.
pub(crate) fn callable(f: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
    if f.is_callable() {
        Ok(f.clone().unbind())
    } else {
        Err(PyTypeError::new_err(format!(
            "a handler must be callable, not {}",
            f.get_type().name()?
        )))
    }
}

/// A run's report as `run` words it.
pub fn run_report(r: rusoar::RunResult) -> String {
    let dc = match r.decisions {
        0 | 1 => format!("{} decision cycle executed.", r.decisions),
        d => format!("{d} decision cycles executed."),
    };
    let rules = match r.firings {
        0 => "No rules fired.".to_string(),
        1 => "1 rule fired.".to_string(),
        f => format!("{f} rules fired."),
    };
    let halted = if r.stop == rusoar::StopReason::Halted {
        "\nAn agent halted during the run."
    } else {
        ""
    };
    format!("\n\n--> {dc} {rules} {halted}")
}

/// Calls the callbacks of `list` for `event` with `(event, userData, subject, extra...)`.
fn fire(
    py: Python<'_>,
    list: &Callbacks,
    event: i32,
    subject: &Bound<'_, PyAny>,
    extra: Option<i32>,
) -> PyResult<()> {
    if !list.any() {
        return Ok(());
    }
    for cb in list.matching(py, |c| c.event == event) {
        match extra {
            Some(x) => cb.func.call1(py, (event, cb.data, subject, x))?,
            None => cb.func.call1(py, (event, cb.data, subject))?,
        };
    }
    Ok(())
}

/// Calls the system event handlers.
pub fn fire_system(py: Python<'_>, k: &KernelShared, event: i32) -> PyResult<()> {
    if !k.system_events.any() {
        return Ok(());
    }
    let kernel = kernel_object(py, k);
    fire(py, &k.system_events, event, kernel.bind(py), None)
}

/// Calls the update event handlers (from the kernel thread or the Python thread); an
/// exception stops the run.
pub fn fire_update(py: Python<'_>, k: &KernelShared, event: i32) {
    if !k.update_events.any() {
        return;
    }
    let kernel = kernel_object(py, k);
    let flags = k.run_flags.load(Ordering::Relaxed);
    if let Err(e) = fire(py, &k.update_events, event, kernel.bind(py), Some(flags)) {
        k.fail(e);
    }
}

/// Calls the agent event handlers with `agent`.
pub fn fire_agent(
    py: Python<'_>,
    k: &KernelShared,
    event: i32,
    agent: &Bound<'_, PyAny>,
) -> PyResult<()> {
    fire(py, &k.agent_events, event, agent, None)
}

fn kernel_object(py: Python<'_>, k: &KernelShared) -> Py<PyAny> {
    match k.py_object.get() {
        Some(o) => o.clone_ref(py),
        None => py.None(),
    }
}
