//! SML's `Kernel`: it makes and destroys agents, runs them together, and holds the
//! kernel-wide registrations (RHS functions, client messages, system, update and agent
//! events).

use crate::agent::Agent;
use crate::dispatch::{callable, fire_agent, fire_system, run_report};
use crate::errors::SoarError;
use crate::shared::{lock, AgentShared, Callback, Callbacks, KernelShared};
use crate::sml_events as ev;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, OnceLock};

/// A Soar kernel: its agents live on a thread of their own, and runs release the GIL.
#[pyclass(module = "rusoar._rusoar", name = "Kernel")]
pub struct Kernel {
    pub(crate) shared: Arc<KernelShared>,
}

impl Kernel {
    fn new(py: Python<'_>) -> PyResult<Py<Kernel>> {
        let shared = Arc::new(KernelShared::new());
        crate::engine::start(&shared)?;
        let k = Py::new(
            py,
            Kernel {
                shared: Arc::clone(&shared),
            },
        )?;
        // The kernel object callbacks get; a weak reference would do, but a kernel lives
        // as long as the program in practice, and `Shutdown` drops it.
        let _ = shared.py_object.set(k.clone_ref(py).into_any());
        Ok(k)
    }

    fn agents(&self) -> Vec<Arc<AgentShared>> {
        lock(&self.shared.agents).clone()
    }

    fn register(
        &self,
        list: &Callbacks,
        event: i32,
        name: &str,
        func: &Bound<'_, PyAny>,
        data: Option<Py<PyAny>>,
    ) -> PyResult<u64> {
        self.shared.check()?;
        let py = func.py();
        let id = self.shared.next_callback_id();
        list.add(Callback {
            id,
            event,
            name: name.to_string(),
            func: callable(func)?,
            data: data.unwrap_or_else(|| py.None()),
        });
        Ok(id)
    }

    /// Runs all agents `count` decisions, one decision each in turn.
    fn run_all(&self, py: Python<'_>, count: Option<u64>) -> PyResult<String> {
        let k = &self.shared;
        k.check()?;
        k.run_flags.store(ev::RUN_ALL, Ordering::Relaxed);
        fire_system(py, k, ev::SYSTEM_START)?;
        let agents = self.agents();
        for a in &agents {
            a.interrupted.store(false, Ordering::Relaxed);
        }
        let total = k.call(py, "RunAllAgents", move |e| {
            let mut total = rusoar::RunResult {
                decisions: 0,
                firings: 0,
                stop: rusoar::StopReason::LimitReached,
            };
            let mut step = 0;
            while count.is_none_or(|c| step < c) {
                step += 1;
                let mut going = false;
                for a in e.agents.iter_mut() {
                    if a.agent.is_halted() {
                        continue;
                    }
                    if let Ok(r) = a.run(1, rusoar::RunUnit::Decisions) {
                        total.decisions += r.decisions;
                        total.firings += r.firings;
                        match r.stop {
                            rusoar::StopReason::LimitReached => going = true,
                            s => total.stop = s,
                        }
                        a.shared
                            .halted
                            .store(a.agent.is_halted(), Ordering::Relaxed);
                    }
                }
                if !going || lock(&e.kernel.error).is_some() {
                    break;
                }
            }
            total
        })?;
        if let Some(e) = lock(&k.error).take() {
            return Err(e);
        }
        fire_system(py, k, ev::SYSTEM_STOP)?;
        Ok(run_report(total))
    }
}

#[pymethods]
impl Kernel {
    /// A kernel whose agents run on a thread of their own.
    #[staticmethod]
    #[pyo3(name = "CreateKernelInNewThread")]
    #[pyo3(signature = (port = 12121))]
    fn create_kernel_in_new_thread(py: Python<'_>, port: i64) -> PyResult<Py<Kernel>> {
        let _ = port;
        Kernel::new(py)
    }

    /// The same kernel as `CreateKernelInNewThread`: the agents always run on their own
    /// thread, so that runs release the GIL.
    #[staticmethod]
    #[pyo3(name = "CreateKernelInCurrentThread")]
    #[pyo3(signature = (optimized = false, port = 12121))]
    fn create_kernel_in_current_thread(
        py: Python<'_>,
        optimized: bool,
        port: i64,
    ) -> PyResult<Py<Kernel>> {
        let _ = (optimized, port);
        Kernel::new(py)
    }

    /// Makes an agent named `name`.
    #[pyo3(name = "CreateAgent")]
    fn create_agent(&self, py: Python<'_>, name: String) -> PyResult<Py<Agent>> {
        let k = &self.shared;
        k.check()?;
        if self.agents().iter().any(|a| a.name == name) {
            return Err(SoarError::new_err(format!(
                "an agent named `{name}` already exists"
            )));
        }
        let tt = k.next_timetag();
        let shared = Arc::new(AgentShared {
            name: name.clone(),
            kernel: Arc::clone(k),
            mirror: Mutex::new(crate::mirror::Mirror::new(tt)),
            interrupt: OnceLock::new(),
            alive: AtomicBool::new(true),
            last_ok: AtomicBool::new(true),
            halted: AtomicBool::new(false),
            interrupted: AtomicBool::new(false),
            run_events: Callbacks::default(),
            print_events: Callbacks::default(),
            production_events: Callbacks::default(),
            output_handlers: Callbacks::default(),
            py_object: OnceLock::new(),
        });
        let s = Arc::clone(&shared);
        k.call(py, "CreateAgent", move |e| e.add_agent(s))?;
        let agent = Py::new(
            py,
            Agent {
                shared: Arc::clone(&shared),
            },
        )?;
        let _ = shared.py_object.set(agent.clone_ref(py).into_any());
        lock(&k.agents).push(shared);
        fire_agent(py, k, ev::AFTER_AGENT_CREATED, agent.bind(py).as_any())?;
        Ok(agent)
    }

    /// Destroys an agent; true when done.
    #[pyo3(name = "DestroyAgent")]
    fn destroy_agent(&self, py: Python<'_>, agent: &Bound<'_, Agent>) -> PyResult<bool> {
        let k = &self.shared;
        k.check()?;
        let shared = Arc::clone(&agent.borrow().shared);
        if !shared.alive.load(Ordering::Relaxed) {
            return Ok(false);
        }
        fire_agent(py, k, ev::BEFORE_AGENT_DESTROYED, agent.as_any())?;
        let name = shared.name.clone();
        k.call(py, "DestroyAgent", move |e| {
            e.agents.retain(|a| a.shared.name != name)
        })?;
        shared.alive.store(false, Ordering::Relaxed);
        lock(&k.agents).retain(|a| !Arc::ptr_eq(a, &shared));
        Ok(true)
    }

    /// The agent named `name`, or None.
    #[pyo3(name = "GetAgent")]
    fn get_agent(&self, py: Python<'_>, name: &str) -> PyResult<Option<Py<PyAny>>> {
        self.shared.check()?;
        Ok(self
            .agents()
            .iter()
            .find(|a| a.name == name)
            .map(|a| a.py_object(py)))
    }

    /// Agent `index`, in the order made, or None.
    #[pyo3(name = "GetAgentByIndex")]
    fn get_agent_by_index(&self, py: Python<'_>, index: i64) -> PyResult<Option<Py<PyAny>>> {
        self.shared.check()?;
        let agents = self.agents();
        Ok(usize::try_from(index)
            .ok()
            .and_then(|i| agents.get(i))
            .map(|a| a.py_object(py)))
    }

    /// How many agents there are.
    #[pyo3(name = "GetNumberAgents")]
    fn get_number_agents(&self) -> PyResult<usize> {
        self.shared.check()?;
        Ok(self.agents().len())
    }

    /// Runs Soar commands on the agent named `agent_name`; returns the result, or the
    /// error's text.
    #[pyo3(name = "ExecuteCommandLine")]
    #[pyo3(signature = (command, agent_name = None, echo = false, no_filter = false))]
    fn execute_command_line(
        &self,
        py: Python<'_>,
        command: String,
        agent_name: Option<String>,
        echo: bool,
        no_filter: bool,
    ) -> PyResult<String> {
        let _ = (echo, no_filter);
        self.shared.check()?;
        let agents = self.agents();
        let agent = match &agent_name {
            Some(n) => agents.iter().find(|a| &a.name == n),
            None => agents.first(),
        };
        let Some(agent) = agent else {
            self.shared.last_ok.store(false, Ordering::Relaxed);
            return Ok(match agent_name {
                Some(n) => format!("No agent named `{n}`.\n"),
                None => "No agent to run the command.\n".to_string(),
            });
        };
        let a = Agent {
            shared: Arc::clone(agent),
        };
        a.execute_command_line(py, command, false, false)
    }

    /// Whether the last command line succeeded.
    #[pyo3(name = "GetLastCommandLineResult")]
    fn get_last_command_line_result(&self) -> bool {
        self.shared.last_ok.load(Ordering::Relaxed)
    }

    /// Runs every agent `count` decisions, interleaved a decision at a time.
    #[pyo3(name = "RunAllAgents")]
    #[pyo3(signature = (count, step = 2, interleave = 0))]
    fn run_all_agents(
        &self,
        py: Python<'_>,
        count: i64,
        step: i32,
        interleave: i32,
    ) -> PyResult<String> {
        let _ = interleave;
        if step != 2 {
            return Err(PyValueError::new_err(
                "RunAllAgents runs decisions (sml_DECISION); other step sizes are not offered",
            ));
        }
        let count = u64::try_from(count)
            .map_err(|_| PyValueError::new_err("RunAllAgents: the count must not be negative"))?;
        self.run_all(py, Some(count))
    }

    /// Runs every agent until all halt or are stopped.
    #[pyo3(name = "RunAllAgentsForever")]
    #[pyo3(signature = (interleave = 0))]
    fn run_all_agents_forever(&self, py: Python<'_>, interleave: i32) -> PyResult<String> {
        let _ = interleave;
        self.run_all(py, None)
    }

    /// Stops every agent's run; works from callbacks.
    #[pyo3(name = "StopAllAgents")]
    fn stop_all_agents(&self) -> PyResult<String> {
        self.shared.check()?;
        for a in self.agents() {
            a.stop();
            a.interrupted.store(true, Ordering::Relaxed);
        }
        Ok(String::new())
    }

    /// Stops the kernel thread and destroys the agents; any later call raises `SoarError`.
    #[pyo3(name = "Shutdown")]
    fn shutdown(&self) -> PyResult<()> {
        if self.shared.on_kernel_thread() {
            return Err(SoarError::new_err(
                "Shutdown cannot be called from inside a callback while the kernel runs",
            ));
        }
        let jobs = lock(&self.shared.jobs).take();
        drop(jobs);
        for a in lock(&self.shared.agents).drain(..) {
            a.alive.store(false, Ordering::Relaxed);
        }
        for list in [
            &self.shared.rhs_functions,
            &self.shared.client_messages,
            &self.shared.system_events,
            &self.shared.update_events,
            &self.shared.agent_events,
        ] {
            list.clear();
        }
        Ok(())
    }

    /// Whether changes go to the kernel without `Commit` (the default).
    #[pyo3(name = "SetAutoCommit")]
    fn set_auto_commit(&self, auto: bool) {
        self.shared.auto_commit.store(auto, Ordering::Relaxed);
    }

    /// Whether auto-commit is on.
    #[pyo3(name = "IsAutoCommitEnabled")]
    fn is_auto_commit_enabled(&self) -> bool {
        self.shared.auto_commit.load(Ordering::Relaxed)
    }

    /// Commits every agent's changes.
    #[pyo3(name = "CommitAll")]
    fn commit_all(&self) -> PyResult<()> {
        for a in self.agents() {
            let mut m = a.mirror();
            m.committed = m.queue.len();
            m.uncommitted = false;
        }
        Ok(())
    }

    /// Registers `handler(eventID, userData, agent, functionName, argument)` as RHS
    /// function `name`: rules call it as `(exec name args...)`; it returns a string.
    #[pyo3(name = "AddRhsFunction")]
    #[pyo3(signature = (name, handler, data = None))]
    fn add_rhs_function(
        &self,
        py: Python<'_>,
        name: String,
        handler: &Bound<'_, PyAny>,
        data: Option<Py<PyAny>>,
    ) -> PyResult<u64> {
        let id = self.register(
            &self.shared.rhs_functions,
            ev::RHS_USER_FUNCTION,
            &name,
            handler,
            data,
        )?;
        self.shared.call(py, "AddRhsFunction", move |e| {
            for a in e.agents.iter_mut() {
                a.add_rhs_function(&name);
            }
        })?;
        Ok(id)
    }

    /// Removes an RHS function; false if there was none of that number.
    #[pyo3(name = "RemoveRhsFunction")]
    fn remove_rhs_function(&self, py: Python<'_>, id: u64) -> PyResult<bool> {
        let before: Vec<String> = self.shared.rhs_functions.names();
        if !self.shared.rhs_functions.remove(id) {
            return Ok(false);
        }
        let after = self.shared.rhs_functions.names();
        let gone: Vec<String> = before.into_iter().filter(|n| !after.contains(n)).collect();
        self.shared.call(py, "RemoveRhsFunction", move |e| {
            for a in e.agents.iter_mut() {
                for n in &gone {
                    a.agent.unregister_rhs_function(n);
                }
            }
        })?;
        Ok(true)
    }

    /// Registers `handler(eventID, userData, agent, clientName, message)` for the client
    /// messages named `name`; it returns a string.
    #[pyo3(name = "RegisterForClientMessageEvent")]
    #[pyo3(signature = (name, handler, data = None, add_to_back = true))]
    fn register_for_client_message_event(
        &self,
        name: &str,
        handler: &Bound<'_, PyAny>,
        data: Option<Py<PyAny>>,
        add_to_back: bool,
    ) -> PyResult<u64> {
        let _ = add_to_back;
        self.register(
            &self.shared.client_messages,
            ev::CLIENT_MESSAGE,
            name,
            handler,
            data,
        )
    }

    /// Removes a client message handler.
    #[pyo3(name = "UnregisterForClientMessageEvent")]
    fn unregister_for_client_message_event(&self, id: u64) -> bool {
        self.shared.client_messages.remove(id)
    }

    /// Sends `message` to the client message handler `client_name`; returns its answer.
    #[pyo3(name = "SendClientMessage")]
    fn send_client_message(
        &self,
        py: Python<'_>,
        agent: &Bound<'_, Agent>,
        client_name: &str,
        message: &str,
    ) -> PyResult<String> {
        self.shared.check()?;
        let cbs = self
            .shared
            .client_messages
            .matching(py, |c| c.name == client_name);
        let mut answer = String::new();
        for cb in cbs {
            let r = cb.func.call1(
                py,
                (ev::CLIENT_MESSAGE, cb.data, agent, client_name, message),
            )?;
            if !r.is_none(py) {
                answer = r.bind(py).str()?.to_string();
            }
        }
        Ok(answer)
    }

    /// Registers `handler(eventID, userData, kernel)` for a system event
    /// (`smlEVENT_SYSTEM_START`, `smlEVENT_SYSTEM_STOP`, ...).
    #[pyo3(name = "RegisterForSystemEvent")]
    #[pyo3(signature = (event, handler, data = None, add_to_back = true))]
    fn register_for_system_event(
        &self,
        event: i32,
        handler: &Bound<'_, PyAny>,
        data: Option<Py<PyAny>>,
        add_to_back: bool,
    ) -> PyResult<u64> {
        let _ = add_to_back;
        if !(1..=7).contains(&event) {
            return Err(PyValueError::new_err(format!(
                "{event} is not a system event (smlEVENT_SYSTEM_START, ...)"
            )));
        }
        self.register(&self.shared.system_events, event, "", handler, data)
    }

    /// Removes a system event handler.
    #[pyo3(name = "UnregisterForSystemEvent")]
    fn unregister_for_system_event(&self, id: u64) -> bool {
        self.shared.system_events.remove(id)
    }

    /// Registers `handler(eventID, userData, kernel, runFlags)` for an update event
    /// (`smlEVENT_AFTER_ALL_OUTPUT_PHASES`, `smlEVENT_AFTER_ALL_GENERATED_OUTPUT`).
    #[pyo3(name = "RegisterForUpdateEvent")]
    #[pyo3(signature = (event, handler, data = None, add_to_back = true))]
    fn register_for_update_event(
        &self,
        event: i32,
        handler: &Bound<'_, PyAny>,
        data: Option<Py<PyAny>>,
        add_to_back: bool,
    ) -> PyResult<u64> {
        let _ = add_to_back;
        if event != ev::AFTER_ALL_OUTPUT_PHASES && event != ev::AFTER_ALL_GENERATED_OUTPUT {
            return Err(PyValueError::new_err(format!(
                "{event} is not an update event (smlEVENT_AFTER_ALL_OUTPUT_PHASES, ...)"
            )));
        }
        self.register(&self.shared.update_events, event, "", handler, data)
    }

    /// Removes an update event handler.
    #[pyo3(name = "UnregisterForUpdateEvent")]
    fn unregister_for_update_event(&self, id: u64) -> bool {
        self.shared.update_events.remove(id)
    }

    /// Registers `handler(eventID, userData, agent)` for an agent event
    /// (`smlEVENT_AFTER_AGENT_CREATED`, `smlEVENT_BEFORE_AGENT_DESTROYED`,
    /// `smlEVENT_BEFORE_AGENT_REINITIALIZED`, `smlEVENT_AFTER_AGENT_REINITIALIZED`).
    #[pyo3(name = "RegisterForAgentEvent")]
    #[pyo3(signature = (event, handler, data = None, add_to_back = true))]
    fn register_for_agent_event(
        &self,
        event: i32,
        handler: &Bound<'_, PyAny>,
        data: Option<Py<PyAny>>,
        add_to_back: bool,
    ) -> PyResult<u64> {
        let _ = add_to_back;
        if !(41..=44).contains(&event) {
            return Err(PyValueError::new_err(format!(
                "{event} is not an agent event (smlEVENT_AFTER_AGENT_CREATED, ...)"
            )));
        }
        self.register(&self.shared.agent_events, event, "", handler, data)
    }

    /// Removes an agent event handler.
    #[pyo3(name = "UnregisterForAgentEvent")]
    fn unregister_for_agent_event(&self, id: u64) -> bool {
        self.shared.agent_events.remove(id)
    }

    fn __enter__(slf: Py<Self>) -> Py<Self> {
        slf
    }

    fn __exit__(&self, _a: Py<PyAny>, _b: Py<PyAny>, _c: Py<PyAny>) -> PyResult<bool> {
        if self.shared.check().is_ok() {
            self.shutdown()?;
        }
        Ok(false)
    }
}
