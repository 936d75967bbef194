//! The kernel thread: it owns the kernel's agents (a `rusoar::Agent` lives on one thread)
//! and runs the jobs the Python thread sends it, while the Python thread waits with the GIL
//! released. Python callbacks are called from here, taking the GIL for the call.

use crate::mirror::{plain, CValue, Op, OutValue, OutWme};
use crate::shared::{lock, AgentShared, Engine, EngineAgent, Job, KernelShared, PrintBuffer};
use crate::sml_events as ev;
use pyo3::prelude::*;
use rusoar::{AgentEvent, Io, Phase, Printed, Symbol, Value};
use std::collections::HashSet;
use std::rc::Rc;
use std::sync::atomic::Ordering;
use std::sync::{mpsc, Arc};

/// The notice 9.6 prints when an agent halts during a run.
const HALT_NOTICE: &str = "\nInterrupt received.This Agent halted.";

/// What `init-soar` returns.
const REINIT_NOTICE: &str = "\nAgent reinitialized.\n";

/// Starts the kernel thread of `kernel`.
pub fn start(kernel: &Arc<KernelShared>) -> PyResult<()> {
    let (tx, rx) = mpsc::channel::<Job>();
    let k = Arc::clone(kernel);
    let handle = std::thread::Builder::new()
        .name("rusoar-kernel".to_string())
        .spawn(move || {
            let mut engine = Engine {
                kernel: k,
                agents: Vec::new(),
            };
            while let Ok(job) = rx.recv() {
                // A panic ends the job, not the thread: the caller sees its reply dropped.
                let _ = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| job(&mut engine)));
            }
        })
        .map_err(|e| {
            crate::errors::SoarError::new_err(format!("cannot start the kernel thread: {e}"))
        })?;
    let _ = kernel.thread.set(handle.thread().id());
    *lock(&kernel.jobs) = Some(tx);
    Ok(())
}

impl Engine {
    /// The agent named `name`.
    pub fn agent(&mut self, name: &str) -> Option<&mut EngineAgent> {
        self.agents.iter_mut().find(|a| a.shared.name == name)
    }

    /// Makes the kernel's agent for `shared`, with the hooks that connect it to Python.
    pub fn add_agent(&mut self, shared: Arc<AgentShared>) {
        let mut agent = rusoar::Agent::new(&shared.name);
        let _ = shared.interrupt.set(agent.interrupt_flag());
        {
            let io = agent.io();
            let il = io.input_link();
            let name = io.text(il);
            let mut m = shared.mirror();
            let il_obj = m.value_obj(m.input_link).unwrap_or(0);
            m.objs[il_obj].sym = Some(il);
            m.objs[il_obj].name = name;
        }
        let printing = Rc::new(PrintBuffer::default());
        let s = Arc::clone(&shared);
        agent.on_input_phase(move |io| apply_changes(&s, io));
        let s = Arc::clone(&shared);
        agent.on_output_phase(move |io| output_phase(&s, io));
        let (s, p) = (Arc::clone(&shared), Rc::clone(&printing));
        agent.on_event(move |e| agent_event(&s, &p, e));
        let (s, p) = (Arc::clone(&shared), Rc::clone(&printing));
        agent.on_print(move |printed| print(&s, &p, printed));
        let mut a = EngineAgent {
            shared,
            agent,
            printing,
        };
        for name in self.kernel.rhs_functions.names() {
            a.add_rhs_function(&name);
        }
        self.agents.push(a);
    }
}

impl EngineAgent {
    /// Runs a command line as SML's `ExecuteCommandLine` does: the result is returned and
    /// not printed; what the commands printed on the way (a run's trace) goes to the print
    /// events. The client's changes wait for the next input phase, as in SML, so a `print`
    /// shows them only once a run has passed one.
    pub fn execute(&mut self, text: &str) -> Result<String, rusoar::Error> {
        self.start_run();
        self.printing.holding.set(true);
        let result = self.agent.execute(text);
        self.printing.holding.set(false);
        let mut held: String = self.printing.pieces.borrow_mut().drain(..).collect();
        let mut result = result;
        if let Ok(r) = &mut result {
            if held.ends_with(r.as_str()) {
                held.truncate(held.len() - r.len());
            }
            // 9.6 prints the trace of `init-soar`; it returns only its notice.
            if let Some(at) = r.find(REINIT_NOTICE) {
                if at > 0 && r.ends_with(REINIT_NOTICE) {
                    held.push_str(&r[..at]);
                    *r = REINIT_NOTICE.to_string();
                }
            }
            // 9.6 prints its notice of a halt; the kernel puts it in the run's result.
            if let Some(rest) = r.strip_prefix(HALT_NOTICE) {
                held.push_str(HALT_NOTICE);
                *r = rest.to_string();
            }
        }
        deliver(&self.shared, held);
        self.sync_output();
        result
    }

    /// Runs `count` decisions with the kernel's typed call (for runs of several agents).
    pub fn run(
        &mut self,
        count: u64,
        unit: rusoar::RunUnit,
    ) -> Result<rusoar::RunResult, rusoar::Error> {
        self.start_run();
        let r = self.agent.run(count, unit);
        self.sync_output();
        r
    }

    /// Readies the agent for a command that may run it: a stop asked for between runs (or
    /// left by a callback's failure after the last check) does not stop this one, as SML's
    /// `StopSelf` acts only on a run in progress.
    fn start_run(&mut self) {
        if let Some(flag) = self.shared.interrupt.get() {
            flag.store(false, Ordering::Relaxed);
        }
        self.shared.mirror().new_run = true;
    }

    /// Brings the client's copy of the output-link up to date.
    pub fn sync_output(&mut self) {
        let io = self.agent.io();
        sync_output(&self.shared, &io, false);
    }

    /// Makes the kernel call the Python RHS function `name`.
    pub fn add_rhs_function(&mut self, name: &str) {
        let s = Arc::clone(&self.shared);
        let fname = name.to_string();
        self.agent
            .register_sml_rhs_function(name, move |_agent, args| rhs_call(&s, &fname, args));
    }
}

/// Applies the program's committed changes through `io`.
fn apply_changes(shared: &Arc<AgentShared>, io: &mut Io) {
    let mut m = shared.mirror();
    let committed = if shared.kernel.auto_commit.load(Ordering::Relaxed) {
        m.queue.len()
    } else {
        m.committed.min(m.queue.len())
    };
    if committed == 0 {
        return;
    }
    let ops: Vec<Op> = m.queue.drain(..committed).collect();
    m.committed = 0;
    let mut added = HashSet::new();
    for op in ops {
        match op {
            Op::Add(w) => {
                if !m.wmes[w].alive {
                    continue;
                }
                let Some(parent) = m.objs[m.wmes[w].parent].sym else {
                    continue;
                };
                let attr = m.wmes[w].attr.clone();
                let made = match m.wmes[w].value.clone() {
                    CValue::Id(o) => match m.objs[o].sym {
                        Some(sym) => io.add(parent, &attr, Value::Id(sym)),
                        None => io.add_object(parent, &attr).map(|(h, sym)| {
                            m.objs[o].sym = Some(sym);
                            h
                        }),
                    },
                    v => io.add(parent, &attr, kernel_value(&v)),
                };
                if let Ok(h) = made {
                    m.wmes[w].handle = Some(h);
                    added.insert(w);
                }
            }
            Op::Update(w) => {
                if added.contains(&w) || !m.wmes[w].alive {
                    continue;
                }
                if let Some(h) = m.wmes[w].handle {
                    let v = match m.wmes[w].value.clone() {
                        CValue::Id(o) => match m.objs[o].sym {
                            Some(sym) => Value::Id(sym),
                            None => continue,
                        },
                        v => kernel_value(&v),
                    };
                    let _ = io.update(h, v);
                }
            }
            Op::Remove(w) => {
                if let Some(h) = m.wmes[w].handle.take() {
                    let _ = io.remove(h);
                }
            }
        }
    }
}

/// A constant of the client's copy as a kernel value.
fn kernel_value(v: &CValue) -> Value {
    match v {
        CValue::Int(i) => Value::Int(*i),
        CValue::Float(f) => Value::Float(*f),
        CValue::Str(s) => Value::Str(s.clone()),
        CValue::Id(_) => Value::Int(0),
    }
}

/// Reads the kernel's output-link into the client's copy; returns the new commands.
fn sync_output(shared: &Arc<AgentShared>, io: &Io, at_output: bool) -> Vec<usize> {
    let ol = io.output_link();
    let mut seen: Vec<(Symbol, OutWme)> = Vec::new();
    let mut visited = HashSet::new();
    let mut stack = vec![ol];
    visited.insert(ol);
    while let Some(id) = stack.pop() {
        for w in io.children(id) {
            let value = match io.value_of(w.value) {
                Value::Id(sym) => {
                    if visited.insert(sym) {
                        stack.push(sym);
                    }
                    OutValue::Id(sym, io.text(sym))
                }
                v => match plain(&v) {
                    Some(c) => OutValue::Plain(c),
                    None => continue,
                },
            };
            seen.push((
                id,
                OutWme {
                    attr: io.text(w.attr),
                    value,
                    timetag: w.timetag,
                },
            ));
        }
    }
    let name = io.text(ol);
    shared.mirror().sync_output(ol, &name, &seen, at_output)
}

/// The output phase: the copy of the output-link is brought up to date and the output
/// handlers are called for the new commands.
fn output_phase(shared: &Arc<AgentShared>, io: &mut Io) {
    let new = sync_output(shared, io, true);
    if new.is_empty() || !shared.output_handlers.any() {
        return;
    }
    let names: Vec<(usize, String)> = {
        let m = shared.mirror();
        new.iter().map(|&w| (w, m.wmes[w].attr.clone())).collect()
    };
    Python::attach(|py| {
        for (w, name) in names {
            for cb in shared.output_handlers.matching(py, |c| c.name == name) {
                let wme = match crate::wme::make(py, shared, w) {
                    Ok(o) => o,
                    Err(e) => return shared.kernel.fail(e),
                };
                let args = (cb.data, shared.py_object(py), name.clone(), wme);
                if let Err(e) = cb.func.call1(py, args) {
                    shared.kernel.fail(e);
                    return;
                }
            }
        }
    });
}

/// A kernel event: run and production events for Python.
fn agent_event(shared: &AgentShared, printing: &PrintBuffer, e: &AgentEvent) {
    let (ids, phase): (&[i32], Phase) = match e {
        AgentEvent::BeforePhase(p) => (ev::before_phase(*p), *p),
        AgentEvent::AfterPhase(p) => (ev::after_phase(*p), *p),
        AgentEvent::Fired { rule } => {
            return production_event(shared, printing, ev::AFTER_PRODUCTION_FIRED, rule)
        }
        AgentEvent::Retracted { rule } => {
            return production_event(shared, printing, ev::BEFORE_PRODUCTION_RETRACTED, rule)
        }
        _ => return,
    };
    // The update events come once all agents of the run have had their output phase: after
    // this agent's, or the last agent's in a run of all of them.
    let update = *e == AgentEvent::AfterPhase(Phase::Output)
        && shared.kernel.update_events.any()
        && (shared.kernel.run_flags.load(Ordering::Relaxed) == ev::RUN_SELF
            || lock(&shared.kernel.agents)
                .last()
                .is_some_and(|a| std::ptr::eq(a.as_ref(), shared)));
    // `AFTER_ALL_GENERATED_OUTPUT` follows an output phase that changed the output-link.
    let generated = update && shared.mirror().output_changed;
    if !shared.run_events.any() && !update {
        return;
    }
    release_held(shared, printing);
    Python::attach(|py| {
        for &id in ids {
            for cb in shared.run_events.matching(py, |c| c.event == id) {
                let args = (id, cb.data, shared.py_object(py), ev::phase_number(phase));
                if let Err(e) = cb.func.call1(py, args) {
                    return shared.kernel.fail(e);
                }
            }
        }
        if update {
            crate::dispatch::fire_update(py, &shared.kernel, ev::AFTER_ALL_OUTPUT_PHASES);
        }
        if generated {
            crate::dispatch::fire_update(py, &shared.kernel, ev::AFTER_ALL_GENERATED_OUTPUT);
        }
    });
}

fn production_event(shared: &AgentShared, printing: &PrintBuffer, id: i32, rule: &str) {
    if !shared.production_events.any() {
        return;
    }
    release_held(shared, printing);
    Python::attach(|py| {
        for cb in shared.production_events.matching(py, |c| c.event == id) {
            let args = (id, cb.data, shared.py_object(py), rule.to_string(), "");
            if let Err(e) = cb.func.call1(py, args) {
                return shared.kernel.fail(e);
            }
        }
    });
}

/// Text the agent printed: to the print events, or held while a command line runs.
fn print(shared: &AgentShared, printing: &PrintBuffer, printed: &Printed) {
    let text = printed.to_string();
    if printing.holding.get() {
        printing.pieces.borrow_mut().push(text);
    } else {
        deliver(shared, text);
    }
}

/// Hands the text held so far to the print events (a run's trace, at each event, so that
/// print and run events keep their order).
fn release_held(shared: &AgentShared, printing: &PrintBuffer) {
    if printing.holding.get() && !printing.pieces.borrow().is_empty() {
        let held: String = printing.pieces.borrow_mut().drain(..).collect();
        deliver(shared, held);
    }
}

/// Calls the print events with `text`.
fn deliver(shared: &AgentShared, text: String) {
    if text.is_empty() || !shared.print_events.any() {
        return;
    }
    Python::attach(|py| {
        for cb in shared.print_events.matching(py, |c| c.event == ev::PRINT) {
            let args = (ev::PRINT, cb.data, shared.py_object(py), text.clone());
            if let Err(e) = cb.func.call1(py, args) {
                return shared.kernel.fail(e);
            }
        }
    });
}

/// Calls the Python RHS function `name` with the arguments' text; its string is the result.
fn rhs_call(shared: &AgentShared, name: &str, args: &str) -> String {
    Python::attach(|py| {
        let Some(cb) = shared
            .kernel
            .rhs_functions
            .matching(py, |c| c.name == name)
            .pop()
        else {
            return String::new();
        };
        let call = (
            ev::RHS_USER_FUNCTION,
            cb.data,
            shared.py_object(py),
            name.to_string(),
            args.to_string(),
        );
        match cb.func.call1(py, call) {
            Ok(v) => match v.extract::<String>(py) {
                Ok(s) => s,
                Err(_) if v.is_none(py) => String::new(),
                Err(_) => match v.bind(py).str() {
                    Ok(s) => s.to_string(),
                    Err(e) => {
                        shared.kernel.fail(e);
                        String::new()
                    }
                },
            },
            Err(e) => {
                shared.kernel.fail(e);
                String::new()
            }
        }
    })
}
