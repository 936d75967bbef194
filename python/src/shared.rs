//! What the Python thread and the kernel thread share about a kernel and its agents: the
//! client's copy of each agent's links, the Python callbacks registered, the flags that stop
//! a run, and the first error a callback raised.

use crate::mirror::Mirror;
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use std::cell::{Cell, RefCell};
use std::rc::Rc;
use std::sync::atomic::{AtomicBool, AtomicI64, AtomicU64, Ordering};
use std::sync::mpsc::{self, Sender};
use std::sync::{Arc, Mutex, MutexGuard, OnceLock};
use std::thread::ThreadId;

/// A Python callback and the user data SML hands back to it.
pub struct Callback {
    /// The number `Register...` returned.
    pub id: u64,
    /// The SML event it is for (or 0 where a name selects it).
    pub event: i32,
    /// The name it is for: an output command's attribute, an RHS function's or a client
    /// message's name.
    pub name: String,
    /// The Python callable.
    pub func: Py<PyAny>,
    /// The user data, passed back as given.
    pub data: Py<PyAny>,
}

impl Callback {
    /// A copy for calling outside the lock.
    pub fn clone_ref(&self, py: Python<'_>) -> Callback {
        Callback {
            id: self.id,
            event: self.event,
            name: self.name.clone(),
            func: self.func.clone_ref(py),
            data: self.data.clone_ref(py),
        }
    }
}

/// A list of callbacks, with a flag the kernel thread reads without the GIL to skip the work
/// when nobody listens.
#[derive(Default)]
pub struct Callbacks {
    list: Mutex<Vec<Callback>>,
    any: AtomicBool,
}

impl Callbacks {
    /// Adds a callback.
    pub fn add(&self, cb: Callback) {
        let mut list = lock(&self.list);
        list.push(cb);
        self.any.store(true, Ordering::Relaxed);
    }

    /// Removes callback `id`; false if it was not registered.
    pub fn remove(&self, id: u64) -> bool {
        let mut list = lock(&self.list);
        let before = list.len();
        list.retain(|c| c.id != id);
        self.any.store(!list.is_empty(), Ordering::Relaxed);
        list.len() != before
    }

    /// Whether any callback is registered.
    pub fn any(&self) -> bool {
        self.any.load(Ordering::Relaxed)
    }

    /// The callbacks that `select` keeps, copied for calling.
    pub fn matching(&self, py: Python<'_>, select: impl Fn(&Callback) -> bool) -> Vec<Callback> {
        lock(&self.list)
            .iter()
            .filter(|c| select(c))
            .map(|c| c.clone_ref(py))
            .collect()
    }

    /// Every callback's name (for RHS functions registered on agents made later).
    pub fn names(&self) -> Vec<String> {
        lock(&self.list).iter().map(|c| c.name.clone()).collect()
    }

    /// Drops every callback.
    pub fn clear(&self) {
        lock(&self.list).clear();
        self.any.store(false, Ordering::Relaxed);
    }
}

/// Locks a mutex, also one a panicking thread left: the data it guards stays usable.
pub fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

/// One agent as both threads know it.
pub struct AgentShared {
    /// Its name.
    pub name: String,
    /// The kernel it belongs to.
    pub kernel: Arc<KernelShared>,
    /// The client's copy of its links.
    pub mirror: Mutex<Mirror>,
    /// Set to stop its run (`StopSelf`); the kernel's interrupt flag.
    pub interrupt: OnceLock<Arc<AtomicBool>>,
    /// False once destroyed.
    pub alive: AtomicBool,
    /// Whether the last command line succeeded.
    pub last_ok: AtomicBool,
    /// Whether it halted (as of the end of its last run).
    pub halted: AtomicBool,
    /// Whether its last run was stopped.
    pub interrupted: AtomicBool,
    /// Run events.
    pub run_events: Callbacks,
    /// Print events.
    pub print_events: Callbacks,
    /// Production events.
    pub production_events: Callbacks,
    /// Output handlers, by command name.
    pub output_handlers: Callbacks,
    /// The Python `Agent` object handed to callbacks, so that they get the client's own.
    pub py_object: OnceLock<Py<PyAny>>,
}

impl AgentShared {
    /// The client's copy of the links.
    pub fn mirror(&self) -> MutexGuard<'_, Mirror> {
        lock(&self.mirror)
    }

    /// Fails when the agent was destroyed or its kernel shut down.
    pub fn check(&self) -> PyResult<()> {
        self.kernel.check()?;
        if self.alive.load(Ordering::Relaxed) {
            Ok(())
        } else {
            Err(crate::errors::destroyed(&format!(
                "agent `{}` was destroyed",
                self.name
            )))
        }
    }

    /// Asks its run to stop at the end of the current elaboration cycle.
    pub fn stop(&self) {
        if let Some(f) = self.interrupt.get() {
            f.store(true, Ordering::Relaxed);
        }
    }

    /// The object callbacks get as their agent argument.
    pub fn py_object(&self, py: Python<'_>) -> Py<PyAny> {
        match self.py_object.get() {
            Some(o) => o.clone_ref(py),
            None => py.None(),
        }
    }
}

/// One kernel as both threads know it.
pub struct KernelShared {
    /// The kernel thread's job queue; `None` once shut down.
    pub jobs: Mutex<Option<Sender<Job>>>,
    /// The kernel thread.
    pub thread: OnceLock<ThreadId>,
    /// Its agents, in the order made.
    pub agents: Mutex<Vec<Arc<AgentShared>>>,
    /// The counter of client timetags (negative, as SML's are).
    pub timetags: AtomicI64,
    /// The counter of client identifier names (`p2`, `b3`, ...).
    pub id_names: AtomicU64,
    /// The counter of callback numbers.
    pub callback_ids: AtomicU64,
    /// Whether changes go to the kernel at once (SML's auto-commit).
    pub auto_commit: AtomicBool,
    /// RHS functions.
    pub rhs_functions: Callbacks,
    /// Client message handlers.
    pub client_messages: Callbacks,
    /// System events.
    pub system_events: Callbacks,
    /// Update events.
    pub update_events: Callbacks,
    /// Agent events.
    pub agent_events: Callbacks,
    /// The first exception a callback raised during the current call.
    pub error: Mutex<Option<PyErr>>,
    /// Whether the last command line succeeded.
    pub last_ok: AtomicBool,
    /// The run flags update events report (`sml_RUN_SELF`, `sml_RUN_ALL`).
    pub run_flags: std::sync::atomic::AtomicI32,
    /// The Python `Kernel` object handed to callbacks.
    pub py_object: OnceLock<Py<PyAny>>,
}

impl KernelShared {
    /// A kernel with no thread yet.
    pub fn new() -> Self {
        KernelShared {
            jobs: Mutex::new(None),
            thread: OnceLock::new(),
            agents: Mutex::new(Vec::new()),
            timetags: AtomicI64::new(-1),
            id_names: AtomicU64::new(1),
            callback_ids: AtomicU64::new(0),
            auto_commit: AtomicBool::new(true),
            rhs_functions: Callbacks::default(),
            client_messages: Callbacks::default(),
            system_events: Callbacks::default(),
            update_events: Callbacks::default(),
            agent_events: Callbacks::default(),
            error: Mutex::new(None),
            last_ok: AtomicBool::new(true),
            run_flags: std::sync::atomic::AtomicI32::new(crate::sml_events::RUN_SELF),
            py_object: OnceLock::new(),
        }
    }

    /// The next client timetag.
    pub fn next_timetag(&self) -> i64 {
        self.timetags.fetch_sub(1, Ordering::Relaxed) - 1
    }

    /// The next identifier name for a WME of attribute `attr`: its first letter, in lower
    /// case as SML's client writes it, and a number.
    pub fn next_id_name(&self, attr: &str) -> String {
        let n = self.id_names.fetch_add(1, Ordering::Relaxed) + 1;
        let letter = attr
            .chars()
            .find(|c| c.is_ascii_alphabetic())
            .map_or('i', |c| c.to_ascii_lowercase());
        format!("{letter}{n}")
    }

    /// The next callback number.
    pub fn next_callback_id(&self) -> u64 {
        self.callback_ids.fetch_add(1, Ordering::Relaxed) + 1
    }

    /// Fails once the kernel is shut down.
    pub fn check(&self) -> PyResult<()> {
        if lock(&self.jobs).is_some() {
            Ok(())
        } else {
            Err(crate::errors::shut_down())
        }
    }

    /// Whether this is the kernel thread (a callback is running).
    pub fn on_kernel_thread(&self) -> bool {
        self.thread.get() == Some(&std::thread::current().id())
    }

    /// Runs `f` on the kernel thread with the GIL released, and returns what it returns;
    /// then raises the first exception a callback raised meanwhile. From inside a callback
    /// (on the kernel thread, which is busy running) it fails with a clear message.
    pub fn call<R: Send + 'static>(
        &self,
        py: Python<'_>,
        what: &str,
        f: impl FnOnce(&mut Engine) -> R + Send + 'static,
    ) -> PyResult<R> {
        if self.on_kernel_thread() {
            return Err(PyRuntimeError::new_err(format!(
                "{what} cannot be called from inside a callback while the kernel runs; \
                 call it after the run returns (StopSelf and the WME calls work in callbacks)"
            )));
        }
        let jobs = lock(&self.jobs)
            .clone()
            .ok_or_else(crate::errors::shut_down)?;
        let (tx, rx) = mpsc::sync_channel(1);
        jobs.send(Box::new(move |e| {
            let _ = tx.send(f(e));
        }))
        .map_err(|_| crate::errors::shut_down())?;
        let result = py.detach(move || rx.recv());
        if let Some(err) = lock(&self.error).take() {
            return Err(err);
        }
        result.map_err(|_| {
            PyRuntimeError::new_err(format!("{what}: the kernel thread stopped unexpectedly"))
        })
    }

    /// Records the first exception a callback raised and stops every run, so that the
    /// call that started the run raises it.
    pub fn fail(&self, err: PyErr) {
        let mut slot = lock(&self.error);
        if slot.is_none() {
            *slot = Some(err);
        }
        drop(slot);
        for a in lock(&self.agents).iter() {
            a.stop();
        }
    }
}

impl Default for KernelShared {
    fn default() -> Self {
        Self::new()
    }
}

/// A piece of work for the kernel thread.
pub type Job = Box<dyn FnOnce(&mut Engine) + Send>;

/// What the kernel thread owns.
pub struct Engine {
    /// The kernel both threads know.
    pub kernel: Arc<KernelShared>,
    /// The agents, in the order made.
    pub agents: Vec<EngineAgent>,
}

/// Text printed while a command line runs: held back so that the command's result, which
/// SML returns and does not print, can be told apart from the trace.
#[derive(Default)]
pub struct PrintBuffer {
    pub(crate) holding: Cell<bool>,
    pub(crate) pieces: RefCell<Vec<String>>,
}

/// An agent on the kernel thread.
pub struct EngineAgent {
    /// What both threads know of it.
    pub shared: Arc<AgentShared>,
    /// The kernel's agent.
    pub agent: rusoar::Agent,
    pub(crate) printing: Rc<PrintBuffer>,
}
