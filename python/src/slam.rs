//! `rusoar slam` for Python, in the three steps of `soar_slam::plan`, so that its runs can be
//! carried out anywhere (the Ray tasks of `rusoar.sweep`): `slam_plan` gives each run's
//! description as bytes, `slam_run` carries one out and gives its result as bytes, and a
//! `SlamAssembly` writes the results into the files `rusoar slam` writes. `slam_main` is
//! `rusoar slam` itself, threads and all, in this process.

use pyo3::create_exception;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use soar_slam::experiment::{self, parse_options};
use soar_slam::plan::{self, Assembly, Finished, Plan, RunOutput, RunSpec};

create_exception!(
    _rusoar,
    SlamUsageError,
    PyValueError,
    "Options `rusoar slam` does not take, or a request for its help. `message` is the text \
     `rusoar slam` prints (its usage, or the help), `status` its exit status: 2 for bad \
     options, 0 for --help."
);

create_exception!(
    _rusoar,
    SlamError,
    PyRuntimeError,
    "An experiment of `rusoar slam` that could not be made: a file that could not be \
     written, a run result of another experiment, a run missing."
);

/// The options and plan of `rusoar slam ARGS`, or the usage error it prints.
fn plan_of(args: &[String]) -> PyResult<Plan> {
    let opts = parse_options(args).map_err(|e| {
        let message = e.render().to_string();
        let status = if e.use_stderr() { 2 } else { 0 };
        let err = SlamUsageError::new_err(message.trim_end().to_string());
        Python::attach(|py| {
            // Setting attributes on a fresh exception object cannot fail.
            let value = err.value(py);
            let _ = value.setattr("message", message);
            let _ = value.setattr("status", status);
        });
        err
    })?;
    plan::plan(&opts).map_err(SlamError::new_err)
}

/// A run's description for Python: where its files go, its seed and condition, and the
/// bytes `slam_run` takes.
fn describe<'py>(py: Python<'py>, plan: &Plan, spec: &RunSpec) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("index", spec.index)?;
    d.set_item("out", plan.parts[spec.part].opts.out.clone())?;
    d.set_item("seed", spec.seed)?;
    d.set_item("slam", if spec.slam { "on" } else { "off" })?;
    d.set_item("spec", PyBytes::new(py, &spec.to_bytes()))?;
    Ok(d)
}

/// `slam_plan(args)`: the runs of `rusoar slam ARGS`, one dict per run (`index`, `out`,
/// `seed`, `slam`, `spec`).
#[pyfunction]
fn slam_plan<'py>(py: Python<'py>, args: Vec<String>) -> PyResult<Vec<Bound<'py, PyDict>>> {
    let plan = plan_of(&args)?;
    plan.specs.iter().map(|s| describe(py, &plan, s)).collect()
}

/// `slam_run(spec)`: carries out one run described by `slam_plan`, returns its result.
#[pyfunction]
fn slam_run<'py>(py: Python<'py>, spec: &[u8]) -> PyResult<Bound<'py, PyBytes>> {
    let spec = RunSpec::from_bytes(spec).map_err(PyValueError::new_err)?;
    let output = py.detach(move || {
        // The run needs a deep stack, which the calling thread (a Ray worker's main
        // thread) may not have.
        std::thread::Builder::new()
            .name("slam-run".into())
            .stack_size(plan::RUN_STACK_BYTES)
            .spawn(move || plan::run(&spec).to_bytes())
            .map_err(|e| format!("cannot start the run's thread: {e}"))?
            .join()
            .map_err(|_| "the run stopped unexpectedly".to_string())
    });
    output
        .map(|bytes| PyBytes::new(py, &bytes))
        .map_err(SlamError::new_err)
}

/// `slam_main(args)`: `rusoar slam ARGS` in this process (on its own threads); returns its
/// exit status. It prints to the process's standard output and error.
#[pyfunction]
fn slam_main(py: Python<'_>, args: Vec<String>) -> u8 {
    py.detach(move || experiment::status(&args))
}

/// The files of `rusoar slam ARGS`, from its runs' results: each result's files are written
/// as it is added, the reports by `finish`.
#[pyclass(module = "rusoar._rusoar")]
struct SlamAssembly {
    inner: Option<Assembly>,
}

impl SlamAssembly {
    fn get(&mut self) -> PyResult<&mut Assembly> {
        self.inner
            .as_mut()
            .ok_or_else(|| SlamError::new_err("this experiment is finished"))
    }
}

#[pymethods]
impl SlamAssembly {
    /// Plans `rusoar slam ARGS` and makes its output folders.
    #[new]
    fn new(args: Vec<String>) -> PyResult<Self> {
        let plan = plan_of(&args)?;
        let inner = Assembly::new(plan).map_err(SlamError::new_err)?;
        Ok(SlamAssembly { inner: Some(inner) })
    }

    /// The runs to carry out, as `slam_plan` gives them.
    fn runs<'py>(&mut self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
        let plan = self.get()?.plan();
        plan.specs.iter().map(|s| describe(py, plan, s)).collect()
    }

    /// How many runs the experiment has.
    #[getter]
    fn total(&mut self) -> PyResult<usize> {
        Ok(self.get()?.plan().specs.len())
    }

    /// How many results are in.
    #[getter]
    fn received(&mut self) -> PyResult<usize> {
        Ok(self.get()?.received())
    }

    /// Adds a result of `slam_run`: writes the run's files. Returns its seed, condition,
    /// final position error (mm) and outcome, for a progress line.
    fn add<'py>(&mut self, py: Python<'py>, result: &[u8]) -> PyResult<Bound<'py, PyDict>> {
        let output = RunOutput::from_bytes(result).map_err(PyValueError::new_err)?;
        let d = PyDict::new(py);
        d.set_item("index", output.index)?;
        d.set_item("seed", output.summary.seed)?;
        d.set_item("slam", if output.summary.slam { "on" } else { "off" })?;
        d.set_item("final_mm", output.summary.final_mm)?;
        d.set_item("wall_time_s", output.summary.wall_time_s)?;
        d.set_item("outcome", output.summary.outcome.to_string())?;
        let assembly = self.get()?;
        py.detach(|| assembly.add(output))
            .map_err(SlamError::new_err)?;
        Ok(d)
    }

    /// Writes the reports once every result is in. `jobs` is the number of runs carried out
    /// at once that the reports state. Returns what `rusoar slam` prints at the end and its
    /// exit status (1 when a run did not complete).
    fn finish(&mut self, py: Python<'_>, jobs: usize) -> PyResult<(String, u8)> {
        let assembly = self
            .inner
            .take()
            .ok_or_else(|| SlamError::new_err("this experiment is finished"))?;
        let out = assembly.plan().opts.out.display().to_string();
        let finished = py
            .detach(move || assembly.finish(jobs.max(1)))
            .map_err(SlamError::new_err)?;
        Ok(match finished {
            Finished::Comparison(text) => (format!("{text}Wrote {out}\n"), 0),
            Finished::Experiment(exp) => {
                let done = exp.runs.iter().all(|r| r.outcome.completed());
                (format!("{}Wrote {out}\n", exp.table()), u8::from(!done))
            }
        })
    }
}

/// Adds the functions and classes of this module to `_rusoar`.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(slam_plan, m)?)?;
    m.add_function(wrap_pyfunction!(slam_run, m)?)?;
    m.add_function(wrap_pyfunction!(slam_main, m)?)?;
    m.add_class::<SlamAssembly>()?;
    m.add("SlamUsageError", m.py().get_type::<SlamUsageError>())?;
    m.add("SlamError", m.py().get_type::<SlamError>())?;
    Ok(())
}
