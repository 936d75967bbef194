//! SML's `Agent`: commands, runs, the input and output links, and the agent's events.

use crate::dispatch::callable;
use crate::errors::{soar_error, SoarError};
use crate::mirror::CValue;
use crate::shared::EngineAgent;
use crate::shared::{AgentShared, Callback};
use crate::sml_events as ev;
use crate::wme::{self, Identifier, NewValue, WMElement};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use std::sync::atomic::Ordering;
use std::sync::Arc;

/// One Soar agent of a kernel.
#[pyclass(module = "rusoar._rusoar", name = "Agent")]
pub struct Agent {
    pub(crate) shared: Arc<AgentShared>,
}

/// SML's step sizes: `sml_PHASE`, `sml_ELABORATION`, `sml_DECISION`.
fn run_command(count: i64, step: i32) -> PyResult<String> {
    let flag = match step {
        0 => "-p ",
        1 => "-e ",
        2 => "",
        _ => {
            return Err(PyValueError::new_err(format!(
                "unknown step size {step}: use sml_DECISION, sml_PHASE or sml_ELABORATION"
            )))
        }
    };
    Ok(format!("run {flag}{count}"))
}

impl Agent {
    /// Runs `f` with this agent on the kernel thread.
    fn with<R: Send + 'static>(
        &self,
        py: Python<'_>,
        what: &str,
        f: impl FnOnce(&mut EngineAgent) -> R + Send + 'static,
    ) -> PyResult<R> {
        self.shared.check()?;
        let name = self.shared.name.clone();
        self.shared
            .kernel
            .call(py, what, move |e| e.agent(&name).map(f))?
            .ok_or_else(|| {
                SoarError::new_err(format!("agent `{}` was destroyed", self.shared.name))
            })
    }

    /// Runs a command line; Ok carries the result or Err the kernel's error.
    pub(crate) fn exec_text(
        &self,
        py: Python<'_>,
        what: &str,
        text: String,
    ) -> PyResult<Result<String, rusoar::Error>> {
        let r = self.with(py, what, move |a| {
            let r = a.execute(&text);
            let halted = a.agent.is_halted();
            (r, halted)
        })?;
        self.shared.halted.store(r.1, Ordering::Relaxed);
        self.shared.last_ok.store(r.0.is_ok(), Ordering::Relaxed);
        self.shared
            .kernel
            .last_ok
            .store(r.0.is_ok(), Ordering::Relaxed);
        Ok(r.0.map(without_run_newline))
    }

    /// A run through a command line, with the system events around it.
    fn run_text(&self, py: Python<'_>, what: &str, text: String) -> PyResult<String> {
        let kernel = &self.shared.kernel;
        kernel.run_flags.store(ev::RUN_SELF, Ordering::Relaxed);
        crate::dispatch::fire_system(py, kernel, ev::SYSTEM_START)?;
        self.shared.interrupted.store(false, Ordering::Relaxed);
        let r = self.exec_text(py, what, text)?;
        if let Some(e) = crate::shared::lock(&kernel.error).take() {
            return Err(e);
        }
        crate::dispatch::fire_system(py, kernel, ev::SYSTEM_STOP)?;
        Ok(text_of(r))
    }

    fn register(
        &self,
        list: &crate::shared::Callbacks,
        event: i32,
        name: &str,
        func: &Bound<'_, PyAny>,
        data: Option<Py<PyAny>>,
    ) -> PyResult<u64> {
        self.shared.check()?;
        let py = func.py();
        let id = self.shared.kernel.next_callback_id();
        list.add(Callback {
            id,
            event,
            name: name.to_string(),
            func: callable(func)?,
            data: data.unwrap_or_else(|| py.None()),
        });
        Ok(id)
    }
}

/// A result that ends with a run's report, without the newline the kernel's print stream
/// closes it with: SML returns the report as the `run` command made it.
fn without_run_newline(mut text: String) -> String {
    let last_line = text
        .trim_end_matches('\n')
        .rsplit('\n')
        .next()
        .unwrap_or("");
    let is_report = text.contains("\n\n--> ")
        && (last_line.starts_with("--> ")
            || last_line == "An agent halted during the run."
            || last_line == "Run stopped (interrupted).");
    if is_report && text.ends_with('\n') {
        text.pop();
    }
    text
}

/// A command's result, or its error's text, as `ExecuteCommandLine` returns them.
fn text_of(r: Result<String, rusoar::Error>) -> String {
    match r {
        Ok(s) => s,
        Err(e) => e.render(),
    }
}

#[pymethods]
impl Agent {
    /// The agent's name.
    #[pyo3(name = "GetAgentName")]
    fn get_agent_name(&self) -> String {
        self.shared.name.clone()
    }

    /// Runs Soar commands; returns their result, or the error's text.
    #[pyo3(name = "ExecuteCommandLine")]
    #[pyo3(signature = (command, echo = false, no_filter = false))]
    pub(crate) fn execute_command_line(
        &self,
        py: Python<'_>,
        command: String,
        echo: bool,
        no_filter: bool,
    ) -> PyResult<String> {
        let _ = (echo, no_filter);
        Ok(text_of(self.exec_text(
            py,
            "ExecuteCommandLine",
            command,
        )?))
    }

    /// Whether the last command line succeeded.
    #[pyo3(name = "GetLastCommandLineResult")]
    fn get_last_command_line_result(&self) -> bool {
        self.shared.last_ok.load(Ordering::Relaxed)
    }

    /// Sources a file of Soar commands; false if it failed.
    #[pyo3(name = "LoadProductions")]
    #[pyo3(signature = (path, echo = false))]
    fn load_productions(&self, py: Python<'_>, path: String, echo: bool) -> PyResult<bool> {
        let _ = echo;
        Ok(self
            .exec_text(py, "LoadProductions", format!("source {{{path}}}"))?
            .is_ok())
    }

    /// Runs `count` decisions (or phases, or elaborations); returns the run's report.
    #[pyo3(name = "RunSelf")]
    #[pyo3(signature = (count, step = 2))]
    fn run_self(&self, py: Python<'_>, count: i64, step: i32) -> PyResult<String> {
        if count < 0 {
            return Err(PyValueError::new_err(
                "RunSelf: the count must not be negative",
            ));
        }
        self.run_text(py, "RunSelf", run_command(count, step)?)
    }

    /// Runs until the agent halts or is stopped.
    #[pyo3(name = "RunSelfForever")]
    fn run_self_forever(&self, py: Python<'_>) -> PyResult<String> {
        self.run_text(py, "RunSelfForever", "run".to_string())
    }

    /// Runs until the agent puts something on its output-link, or `max-nil-output-cycles`
    /// decisions pass without.
    #[pyo3(name = "RunSelfTilOutput")]
    fn run_self_til_output(&self, py: Python<'_>) -> PyResult<String> {
        let kernel = &self.shared.kernel;
        crate::dispatch::fire_system(py, kernel, ev::SYSTEM_START)?;
        let r = self.with(py, "RunSelfTilOutput", |a| {
            let r = a.run(0, rusoar::RunUnit::Output);
            (r, a.agent.is_halted())
        })?;
        self.shared.halted.store(r.1, Ordering::Relaxed);
        let r = r.0.map_err(|e| soar_error(py, &e))?;
        crate::dispatch::fire_system(py, kernel, ev::SYSTEM_STOP)?;
        Ok(crate::dispatch::run_report(r))
    }

    /// Asks a run to stop at the end of the current elaboration cycle; works from callbacks.
    #[pyo3(name = "StopSelf")]
    fn stop_self(&self) -> PyResult<String> {
        self.shared.check()?;
        self.shared.stop();
        self.shared.interrupted.store(true, Ordering::Relaxed);
        Ok(String::new())
    }

    /// `init-soar`: working memory starts again; the client's input WMEs are added again.
    #[pyo3(name = "InitSoar")]
    fn init_soar(slf: &Bound<'_, Self>) -> PyResult<String> {
        let py = slf.py();
        let this = slf.borrow();
        let kernel = Arc::clone(&this.shared.kernel);
        crate::dispatch::fire_agent(py, &kernel, ev::BEFORE_AGENT_REINITIALIZED, slf.as_any())?;
        let r = this.exec_text(py, "InitSoar", "init-soar".to_string())?;
        crate::dispatch::fire_agent(py, &kernel, ev::AFTER_AGENT_REINITIALIZED, slf.as_any())?;
        Ok(text_of(r))
    }

    /// `sml_RUNSTATE_STOPPED`, `_HALTED` or `_INTERRUPTED`.
    #[pyo3(name = "GetRunState")]
    fn get_run_state(&self) -> i32 {
        if self.shared.halted.load(Ordering::Relaxed) {
            3
        } else if self.shared.interrupted.load(Ordering::Relaxed) {
            1
        } else {
            0
        }
    }

    /// Decisions made since the agent was created or last initialized.
    #[pyo3(name = "GetDecisionCycleCounter")]
    fn get_decision_cycle_counter(&self, py: Python<'_>) -> PyResult<u64> {
        self.with(py, "GetDecisionCycleCounter", |a| a.agent.decisions())
    }

    /// Whether a rule of that name is loaded.
    #[pyo3(name = "IsProductionLoaded")]
    fn is_production_loaded(&self, py: Python<'_>, name: String) -> PyResult<bool> {
        self.with(py, "IsProductionLoaded", move |a| {
            a.agent.production_names().contains(&name)
        })
    }

    /// Whether updating a WME to its own value removes and adds it again (the default).
    #[pyo3(name = "SetBlinkIfNoChange")]
    fn set_blink_if_no_change(&self, py: Python<'_>, blink: bool) -> PyResult<()> {
        let mode = if blink {
            rusoar::InputUpdate::BlinkIfNoChange
        } else {
            rusoar::InputUpdate::SkipIfNoChange
        };
        self.with(py, "SetBlinkIfNoChange", move |a| {
            a.agent.set_input_update(mode)
        })
    }

    // ---- The input and output links ----

    /// The input-link's identifier.
    #[pyo3(name = "GetInputLink")]
    fn get_input_link(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        self.shared.check()?;
        let w = self.shared.mirror().input_link;
        wme::make(py, &self.shared, w)
    }

    /// The output-link's identifier, once the agent has put something on it; else None.
    #[pyo3(name = "GetOutputLink")]
    fn get_output_link(&self, py: Python<'_>) -> PyResult<Option<Py<PyAny>>> {
        self.shared.check()?;
        let w = self.shared.mirror().output_link;
        w.map(|w| wme::make(py, &self.shared, w)).transpose()
    }

    /// Adds `(parent ^attr <new identifier>)`.
    #[pyo3(name = "CreateIdWME")]
    fn create_id_wme(
        &self,
        py: Python<'_>,
        parent: PyRef<'_, Identifier>,
        attr: &str,
    ) -> PyResult<Py<PyAny>> {
        wme::create(
            py,
            &self.shared,
            parent.as_super().object()?,
            attr,
            NewValue::NewId,
        )
    }

    /// Adds `(parent ^attr value)` with a string.
    #[pyo3(name = "CreateStringWME")]
    fn create_string_wme(
        &self,
        py: Python<'_>,
        parent: PyRef<'_, Identifier>,
        attr: &str,
        value: String,
    ) -> PyResult<Py<PyAny>> {
        let v = NewValue::Plain(CValue::Str(value));
        wme::create(py, &self.shared, parent.as_super().object()?, attr, v)
    }

    /// Adds `(parent ^attr value)` with an integer.
    #[pyo3(name = "CreateIntWME")]
    fn create_int_wme(
        &self,
        py: Python<'_>,
        parent: PyRef<'_, Identifier>,
        attr: &str,
        value: i64,
    ) -> PyResult<Py<PyAny>> {
        let v = NewValue::Plain(CValue::Int(value));
        wme::create(py, &self.shared, parent.as_super().object()?, attr, v)
    }

    /// Adds `(parent ^attr value)` with a float.
    #[pyo3(name = "CreateFloatWME")]
    fn create_float_wme(
        &self,
        py: Python<'_>,
        parent: PyRef<'_, Identifier>,
        attr: &str,
        value: f64,
    ) -> PyResult<Py<PyAny>> {
        let v = NewValue::Plain(CValue::Float(value));
        wme::create(py, &self.shared, parent.as_super().object()?, attr, v)
    }

    /// Adds `(parent ^attr shared)`, whose value is an identifier the client already has.
    #[pyo3(name = "CreateSharedIdWME")]
    fn create_shared_id_wme(
        &self,
        py: Python<'_>,
        parent: PyRef<'_, Identifier>,
        attr: &str,
        shared: PyRef<'_, Identifier>,
    ) -> PyResult<Py<PyAny>> {
        let o = shared.as_super().object()?;
        wme::create(
            py,
            &self.shared,
            parent.as_super().object()?,
            attr,
            NewValue::Shared(o),
        )
    }

    /// Gives a WME the client made a new value of its type; it reaches the agent at its
    /// next input phase.
    #[pyo3(name = "Update")]
    fn update(&self, wme: PyRef<'_, WMElement>, value: &Bound<'_, PyAny>) -> PyResult<()> {
        wme.read(|_, _| ())?;
        let shared = &self.shared;
        let old = shared.mirror().wmes[wme.key].value.clone();
        let new = match old {
            CValue::Int(_) => CValue::Int(value.extract()?),
            CValue::Float(_) => CValue::Float(value.extract()?),
            CValue::Str(_) => CValue::Str(value.extract()?),
            CValue::Id(_) => {
                return Err(PyTypeError::new_err(
                    "an identifier's WME has no value to update",
                ))
            }
        };
        let mut m = shared.mirror();
        if m.wmes[wme.key].timetag >= 0 {
            return Err(SoarError::new_err(
                "only WMEs the client made can be updated",
            ));
        }
        let tt = shared.kernel.next_timetag();
        m.update(wme.key, new, tt);
        Ok(())
    }

    /// Removes a WME the client made (and what hangs below it); true when done.
    #[pyo3(name = "DestroyWME")]
    fn destroy_wme(&self, wme: PyRef<'_, WMElement>) -> PyResult<bool> {
        wme.read(|_, _| ())?;
        let mut m = self.shared.mirror();
        if m.wmes[wme.key].timetag >= 0 || wme.key == m.input_link {
            return Ok(false);
        }
        m.destroy(wme.key);
        Ok(true)
    }

    /// Sends the changes made since the last commit (with auto-commit off).
    #[pyo3(name = "Commit")]
    fn commit(&self) -> PyResult<bool> {
        self.shared.check()?;
        let mut m = self.shared.mirror();
        m.committed = m.queue.len();
        m.uncommitted = false;
        Ok(true)
    }

    /// Whether changes wait for `Commit` (auto-commit off and changes made).
    #[pyo3(name = "IsCommitRequired")]
    fn is_commit_required(&self) -> bool {
        !self.shared.kernel.auto_commit.load(Ordering::Relaxed) && self.shared.mirror().uncommitted
    }

    /// How many commands are on the output-link.
    #[pyo3(name = "GetNumberCommands")]
    fn get_number_commands(&self) -> PyResult<usize> {
        self.shared.check()?;
        Ok(self.shared.mirror().commands().len())
    }

    /// Command `index` of the output-link, or None.
    #[pyo3(name = "GetCommand")]
    fn get_command(&self, py: Python<'_>, index: i64) -> PyResult<Option<Py<PyAny>>> {
        self.shared.check()?;
        let cmds = self.shared.mirror().commands();
        let w = usize::try_from(index)
            .ok()
            .and_then(|i| cmds.get(i).copied());
        w.map(|w| wme::make(py, &self.shared, w)).transpose()
    }

    /// Whether there are commands on the output-link (SML's `Commands` answers a bool).
    #[pyo3(name = "Commands")]
    fn commands(&self) -> PyResult<bool> {
        self.shared.check()?;
        Ok(!self.shared.mirror().commands().is_empty())
    }

    /// Forgets which output WMEs were just added.
    #[pyo3(name = "ClearOutputLinkChanges")]
    fn clear_output_link_changes(&self) -> PyResult<()> {
        // SML's client keeps its commands and their flags until the next output that
        // changes the output-link (checked on soar_sml 9.6.5); so does this copy.
        self.shared.check()
    }

    // ---- Events ----

    /// Calls `handler(userData, agent, commandName, outputWme)` for each new command
    /// named `name`; returns the handler's number.
    #[pyo3(name = "AddOutputHandler")]
    #[pyo3(signature = (name, handler, data = None, add_to_back = true))]
    fn add_output_handler(
        &self,
        name: &str,
        handler: &Bound<'_, PyAny>,
        data: Option<Py<PyAny>>,
        add_to_back: bool,
    ) -> PyResult<u64> {
        let _ = add_to_back;
        self.register(&self.shared.output_handlers, 0, name, handler, data)
    }

    /// Removes an output handler; false if there was none of that number.
    #[pyo3(name = "RemoveOutputHandler")]
    fn remove_output_handler(&self, id: u64) -> bool {
        self.shared.output_handlers.remove(id)
    }

    /// Calls `handler(eventID, userData, agent, phase)` at the run event.
    #[pyo3(name = "RegisterForRunEvent")]
    #[pyo3(signature = (event, handler, data = None, add_to_back = true))]
    fn register_for_run_event(
        &self,
        event: i32,
        handler: &Bound<'_, PyAny>,
        data: Option<Py<PyAny>>,
        add_to_back: bool,
    ) -> PyResult<u64> {
        let _ = add_to_back;
        if !ev::is_run_event(event) {
            return Err(PyValueError::new_err(format!(
                "{event} is not a run event (smlEVENT_BEFORE_INPUT_PHASE, ...)"
            )));
        }
        self.register(&self.shared.run_events, event, "", handler, data)
    }

    /// Removes a run event handler.
    #[pyo3(name = "UnregisterForRunEvent")]
    fn unregister_for_run_event(&self, id: u64) -> bool {
        self.shared.run_events.remove(id)
    }

    /// Calls `handler(eventID, userData, agent, message)` with what the agent prints.
    #[pyo3(name = "RegisterForPrintEvent")]
    #[pyo3(signature = (event, handler, data = None, ignore_own_echos = true, add_to_back = true))]
    fn register_for_print_event(
        &self,
        event: i32,
        handler: &Bound<'_, PyAny>,
        data: Option<Py<PyAny>>,
        ignore_own_echos: bool,
        add_to_back: bool,
    ) -> PyResult<u64> {
        let _ = (ignore_own_echos, add_to_back);
        if event != ev::PRINT && event != 46 {
            return Err(PyValueError::new_err(format!(
                "{event} is not a print event (smlEVENT_PRINT)"
            )));
        }
        self.register(&self.shared.print_events, event, "", handler, data)
    }

    /// Removes a print event handler.
    #[pyo3(name = "UnregisterForPrintEvent")]
    fn unregister_for_print_event(&self, id: u64) -> bool {
        self.shared.print_events.remove(id)
    }

    /// Calls `handler(eventID, userData, agent, productionName, instantiation)` when a rule
    /// fires (`smlEVENT_AFTER_PRODUCTION_FIRED`) or retracts
    /// (`smlEVENT_BEFORE_PRODUCTION_RETRACTED`).
    #[pyo3(name = "RegisterForProductionEvent")]
    #[pyo3(signature = (event, handler, data = None, add_to_back = true))]
    fn register_for_production_event(
        &self,
        event: i32,
        handler: &Bound<'_, PyAny>,
        data: Option<Py<PyAny>>,
        add_to_back: bool,
    ) -> PyResult<u64> {
        let _ = add_to_back;
        if !(37..=40).contains(&event) {
            return Err(PyValueError::new_err(format!(
                "{event} is not a production event (smlEVENT_AFTER_PRODUCTION_FIRED, ...)"
            )));
        }
        self.register(&self.shared.production_events, event, "", handler, data)
    }

    /// Removes a production event handler.
    #[pyo3(name = "UnregisterForProductionEvent")]
    fn unregister_for_production_event(&self, id: u64) -> bool {
        self.shared.production_events.remove(id)
    }

    // ---- For the Pythonic layer: errors as exceptions ----

    /// Runs Soar commands; raises `SoarError` (with `file`, `line`, `column`) on failure.
    fn execute(&self, py: Python<'_>, command: String) -> PyResult<String> {
        self.exec_text(py, "execute", command)?
            .map_err(|e| soar_error(py, &e))
    }

    /// Runs `count` decisions with the typed call; returns (decisions, firings, stop reason).
    fn run_decisions(&self, py: Python<'_>, count: u64) -> PyResult<(u64, u64, String)> {
        let r = self.with(py, "run", move |a| {
            let r = a.run(count, rusoar::RunUnit::Decisions);
            (r, a.agent.is_halted())
        })?;
        self.shared.halted.store(r.1, Ordering::Relaxed);
        let r = r.0.map_err(|e| soar_error(py, &e))?;
        Ok((r.decisions, r.firings, format!("{:?}", r.stop)))
    }

    fn __repr__(&self) -> String {
        format!("<rusoar Agent {:?}>", self.shared.name)
    }
}
