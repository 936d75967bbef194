//! [`Agent`]: one Soar agent, the kernel's front door.

use super::io::{children, has_attribute, value_text, Io};
use super::{Error, Printed};
use crate::commands::{Event, Interpreter, LoadReport};
use crate::decide::limits::Limits;
use crate::events::AgentEvent;
use crate::io::{InputUpdate, Value};
use crate::rhs::host::{RhsArg, RhsCall};
use crate::source::Severity;
use crate::symbols::Sym;
use crate::wm::Wme;
use std::cell::RefCell;
use std::path::{Path, PathBuf};
use std::rc::Rc;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

/// How far [`Agent::run`] goes (Soar manual, chapter 2, "The Soar Decision Cycle").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RunUnit {
    /// Decision cycles (`run N`).
    Decisions,
    /// Phases (`run -p N`).
    Phases,
    /// Elaboration cycles (`run -e N`).
    Elaborations,
    /// Decision cycles until the agent changes its output-link, or until
    /// `max-nil-output-cycles` decisions pass without output (SML's `RunSelfTilOutput`;
    /// the count is ignored).
    Output,
    /// Until the agent halts or is stopped (`run`; the count is ignored).
    Forever,
}

/// Why a run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StopReason {
    /// It ran the units asked for.
    LimitReached,
    /// The agent halted (the `halt` RHS function), in this run or before it.
    Halted,
    /// A stop was asked for: [`Io::stop`], the interrupt flag
    /// ([`Agent::interrupt_flag`]) or the `interrupt` RHS function.
    Interrupted,
    /// The goal stack reached `max-goal-depth` (Soar manual, `soar max-goal-depth`).
    GoalDepthExceeded,
    /// The run met a ceiling of [`Agent::set_limits`] (the `limits` command).
    CeilingReached,
    /// [`RunUnit::Output`]: the agent changed its output-link.
    Output,
    /// [`RunUnit::Output`]: `max-nil-output-cycles` decisions passed without output.
    NoOutput,
}

/// What a run did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RunResult {
    /// Decisions made in the run (decision phases run).
    pub decisions: u64,
    /// Rules fired.
    pub firings: u64,
    /// Why the run ended.
    pub stop: StopReason,
}

/// The handle of a print listener or a phase hook, for removing it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ListenerId(u64);

type PrintListener = Box<dyn FnMut(&Printed)>;
type PhaseHook = Box<dyn FnMut(&mut Io)>;
type Hooks = Rc<RefCell<Vec<(ListenerId, PhaseHook)>>>;

/// One Soar agent: its rules, working memory and settings, Soar's command language, and
/// the input and output links.
///
/// ```
/// use rusoar::{Agent, RunUnit};
///
/// let mut agent = Agent::new("hello");
/// agent.execute("sp {hello (state <s> ^superstate nil) --> (write |Hello| (crlf)) (halt)}")?;
/// let run = agent.run(10, RunUnit::Decisions)?;
/// assert_eq!(run.stop, rusoar::StopReason::Halted);
/// assert!(agent.take_output().contains("Hello"));
/// # Ok::<(), rusoar::Error>(())
/// ```
pub struct Agent {
    interp: Interpreter,
    listeners: Rc<RefCell<Vec<(ListenerId, PrintListener)>>>,
    input_hooks: Hooks,
    output_hooks: Hooks,
    next_id: u64,
    interrupt: Option<Arc<AtomicBool>>,
}

impl std::fmt::Debug for Agent {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Agent")
            .field("name", &self.interp.agent.name)
            .field("decisions", &self.interp.agent.decider.decisions)
            .finish()
    }
}

impl Default for Agent {
    fn default() -> Self {
        Agent::new("soar")
    }
}

impl Agent {
    /// A new agent with an empty rule base; its working directory is the process's.
    pub fn new(name: &str) -> Agent {
        let mut interp = Interpreter::new();
        interp.agent.name = name.to_string();
        Agent {
            interp,
            listeners: Rc::default(),
            input_hooks: Rc::default(),
            output_hooks: Rc::default(),
            next_id: 0,
            interrupt: None,
        }
    }

    /// The kernel's consistency checks (for tests and fuzzing): every WME linked to a goal,
    /// no matcher token holding a removed WME, slots agreeing with their preferences and
    /// WMEs. Each broken one is described; they hold between runs whatever the agent did.
    pub fn check_invariants(&self) -> Result<(), Vec<String>> {
        let found = self.interp.agent.invariant_violations();
        if found.is_empty() {
            Ok(())
        } else {
            Err(found)
        }
    }

    /// The agent's name.
    pub fn name(&self) -> &str {
        &self.interp.agent.name
    }

    // ---- Soar's command language ----

    /// Runs a text of Soar commands (`sp {...}`, `source`, `watch 5`, `print s1`, ...),
    /// one after another, up to the first that fails, and returns what they printed (as
    /// SML's `ExecuteCommandLine` returns its result). Print listeners get it too; it is not
    /// kept for [`Agent::take_output`]. On failure, what the commands printed before it
    /// stays on the print stream. Diagnostics name the text `<command>`.
    pub fn execute(&mut self, commands: &str) -> Result<String, Error> {
        self.deliver();
        self.interp.start_result();
        let start = self.interp.event_count();
        match self.interp.run_text("<command>", commands) {
            Ok(()) => {
                let events = self.interp.take_events_from(start);
                Ok(self.send(&events))
            }
            Err(d) => {
                self.deliver();
                Err(Error::from_diagnostic(&d, &self.interp.sources))
            }
        }
    }

    /// Runs a text of Soar commands that diagnostics name `name` (a file name, `-c`,
    /// `<stdin>`), up to the first that fails. What they print goes to the print stream: to
    /// the print listeners, or kept for [`Agent::take_output`].
    pub fn source_text(&mut self, name: &str, commands: &str) -> Result<(), Error> {
        let result = self.interp.run_text(name, commands);
        self.deliver();
        result.map_err(|d| Error::from_diagnostic(&d, &self.interp.sources))
    }

    /// Runs a text of Soar commands as Soar's command line reads its input: a command that
    /// fails puts its error on the print stream (a [`Printed::Diagnostic`]) and the next
    /// command runs. Only text that cannot be read as commands, such as an unclosed brace,
    /// ends it early. Returns how many commands failed.
    pub fn source_text_keep_going(&mut self, name: &str, commands: &str) -> usize {
        let failed = self.interp.run_text_keep_going(name, commands);
        self.deliver();
        failed
    }

    /// Sources a file of Soar commands, as `source FILE` does (relative paths resolve
    /// against the working directory); what it prints goes to the print stream.
    pub fn source_file(&mut self, path: impl AsRef<Path>) -> Result<(), Error> {
        let command = format!("source {{{}}}", path.as_ref().display());
        self.source_text("--source", &command)
    }

    /// Everything printed and not yet taken, rendered as one text (only what no print
    /// listener took: with a listener registered, printed text goes to it).
    pub fn take_output(&mut self) -> String {
        self.interp.take_output()
    }

    /// Everything printed and not yet taken, in order (only what no print listener took).
    pub fn take_printed(&mut self) -> Vec<Printed> {
        let events = self.interp.take_events();
        events
            .iter()
            .map(|e| Printed::from_event(e, &self.interp.sources))
            .collect()
    }

    /// Calls `f` with everything the agent prints from now on: command results, the trace
    /// (during a run, after each decision), `write` output and warnings. While any listener
    /// is registered, printed text is not kept for [`Agent::take_output`].
    pub fn on_print(&mut self, f: impl FnMut(&Printed) + 'static) -> ListenerId {
        let id = self.new_id();
        self.listeners.borrow_mut().push((id, Box::new(f)));
        if self.listeners.borrow().len() == 1 {
            let listeners = Rc::clone(&self.listeners);
            self.interp
                .set_live_output(Rc::new(RefCell::new(move |text: &str| {
                    let printed = Printed::Text(text.to_string());
                    for (_, l) in listeners.borrow_mut().iter_mut() {
                        l(&printed);
                    }
                })));
        }
        id
    }

    /// Calls `f` with every [`AgentEvent`] from now on: each phase's start and end, each
    /// rule firing and retraction, each WME added to or removed from working memory, and
    /// `init-soar`. An agent nobody listens to pays one branch per event.
    ///
    /// ```
    /// use rusoar::{Agent, AgentEvent, RunUnit};
    /// use std::{cell::RefCell, rc::Rc};
    ///
    /// let mut agent = Agent::new("events");
    /// agent.execute("sp {hi (state <s> ^superstate nil) --> (<s> ^greeting hello)}")?;
    /// let fired = Rc::new(RefCell::new(Vec::new()));
    /// let seen = Rc::clone(&fired);
    /// agent.on_event(move |e| {
    ///     if let AgentEvent::Fired { rule } = e {
    ///         seen.borrow_mut().push(rule.to_string());
    ///     }
    /// });
    /// agent.run(1, RunUnit::Decisions)?;
    /// assert_eq!(*fired.borrow(), ["hi"]);
    /// # Ok::<(), rusoar::Error>(())
    /// ```
    pub fn on_event(&mut self, f: impl FnMut(&AgentEvent) + 'static) -> ListenerId {
        let id = self.new_id();
        self.interp.agent.events.add(id.0, Box::new(f));
        id
    }

    /// Removes a print listener, an event listener or a phase hook; false if it was not
    /// registered.
    pub fn remove_listener(&mut self, id: ListenerId) -> bool {
        let found = self.interp.agent.events.remove(id.0)
            | remove_by_id(&self.input_hooks, id)
            | remove_by_id(&self.output_hooks, id)
            | remove_by_id(&self.listeners, id);
        if self.listeners.borrow().is_empty() {
            self.interp.clear_live_output();
        }
        found
    }

    /// Hands what is on the print stream to the print listeners, if there are any.
    fn deliver(&mut self) {
        if !self.listeners.borrow().is_empty() {
            let events = self.interp.take_events();
            self.send(&events);
        }
    }

    /// Hands `events` to the print listeners; returns them rendered.
    fn send(&mut self, events: &[Event]) -> String {
        let mut listeners = self.listeners.borrow_mut();
        if !listeners.is_empty() {
            for e in events {
                let printed = Printed::from_event(e, &self.interp.sources);
                for (_, l) in listeners.iter_mut() {
                    l(&printed);
                }
            }
        }
        self.interp.render_all(events)
    }

    fn new_id(&mut self) -> ListenerId {
        self.next_id += 1;
        ListenerId(self.next_id)
    }

    /// The directory relative paths resolve against (`cd`, `source`).
    pub fn working_directory(&self) -> &Path {
        self.interp.cwd()
    }

    /// Sets the directory relative paths resolve against.
    pub fn set_working_directory(&mut self, dir: impl Into<PathBuf>) {
        self.interp.set_cwd(dir.into());
    }

    /// Writes what the long-term memories' `lazy-commit` holds back to their database
    /// files (an agent that is dropped does this too). A program that ends without dropping
    /// its agent calls this first, or the episodes and facts since the last commit are lost.
    pub fn commit_memories(&mut self) -> Result<(), Error> {
        let core = &mut self.interp.agent;
        let smem = core.smem.commit();
        let epmem = core.epmem.commit();
        smem.and(epmem).map_err(|m| Error::Command {
            severity: Severity::Error,
            rendered: format!("error: {m}"),
            message: m,
            location: None,
        })
    }

    /// Whether the `exit` command was run.
    pub fn exit_requested(&self) -> bool {
        self.interp.exit_requested
    }

    /// The rules `source` has loaded, per file.
    pub fn load_report(&self) -> &LoadReport {
        &self.interp.report
    }

    /// The names a command line can start with: Soar's commands and the aliases.
    pub fn command_names(&self) -> Vec<String> {
        let mut names: Vec<String> = crate::commands::COMMANDS
            .iter()
            .map(|c| c.to_string())
            .collect();
        names.extend(self.interp.aliases().names().map(str::to_string));
        names
    }

    // ---- Running ----

    /// Runs the agent `count` units (see [`RunUnit`]); the trace goes to the print stream.
    /// Fails only when a print listener or a phase hook is running (a hook cannot run the
    /// agent it was called by).
    pub fn run(&mut self, count: u64, unit: RunUnit) -> Result<RunResult, Error> {
        let result = match unit {
            RunUnit::Output => self.run_til_output(),
            RunUnit::Decisions => self.run_units(count, crate::decide::cycle::RunUnit::Decisions),
            RunUnit::Phases => self.run_units(count, crate::decide::cycle::RunUnit::Phases),
            RunUnit::Elaborations => {
                self.run_units(count, crate::decide::cycle::RunUnit::Elaborations)
            }
            RunUnit::Forever => self.run_units(1, crate::decide::cycle::RunUnit::Forever),
        };
        self.deliver();
        Ok(result)
    }

    fn run_units(&mut self, count: u64, unit: crate::decide::cycle::RunUnit) -> RunResult {
        let r = self.interp.run_agent(count.max(1), unit);
        RunResult {
            decisions: r.decided,
            firings: r.fired,
            stop: if r.halted {
                StopReason::Halted
            } else if r.depth_exceeded {
                StopReason::GoalDepthExceeded
            } else if r.ceiling {
                StopReason::CeilingReached
            } else if r.interrupted {
                StopReason::Interrupted
            } else {
                StopReason::LimitReached
            },
        }
    }

    /// Decisions until the output-link changes, or `max-nil-output-cycles` pass.
    fn run_til_output(&mut self) -> RunResult {
        let limit = self.interp.agent.settings.max_nil_output_cycles.max(1) as u64;
        let mut total = RunResult {
            decisions: 0,
            firings: 0,
            stop: StopReason::NoOutput,
        };
        for _ in 0..limit {
            let before = self.interp.agent.output_link_stamp();
            let r = self.run_units(1, crate::decide::cycle::RunUnit::Decisions);
            total.decisions += r.decisions;
            total.firings += r.firings;
            if r.stop != StopReason::LimitReached {
                total.stop = r.stop;
                return total;
            }
            if self.interp.agent.output_link_stamp() != before {
                total.stop = StopReason::Output;
                return total;
            }
        }
        total
    }

    /// A flag that stops a run when set from anywhere (a Ctrl-C handler, another thread):
    /// within the current elaboration cycle, even in a phase that would go on for ever
    /// (the phase goes on at the next run). The run reports [`StopReason::Interrupted`] and
    /// clears the flag.
    pub fn interrupt_flag(&mut self) -> Arc<AtomicBool> {
        let flag = self
            .interrupt
            .get_or_insert_with(|| Arc::new(AtomicBool::new(false)));
        let flag = Arc::clone(flag);
        self.interp.set_interrupt(Arc::clone(&flag));
        flag
    }

    /// Sets ceilings on a run's growth (0: none, the default for each): a run that makes
    /// working memory hold more WMEs, or the matcher more partial matches, than its ceiling,
    /// or that learns as many chunks as its ceiling, stops after the elaboration cycle or
    /// phase in which it did, with a message in the trace, and reports
    /// [`StopReason::CeilingReached`]. The agent stays usable: a later run goes on (and
    /// stops again while a ceiling is still passed). The `limits` command sets the same.
    pub fn set_limits(&mut self, limits: Limits) {
        self.interp.agent.settings.limits = limits;
    }

    /// The ceilings of [`Agent::set_limits`].
    pub fn limits(&self) -> Limits {
        self.interp.agent.settings.limits
    }

    /// `init-soar`: working memory, the goal stack and the counters start again; rules stay.
    /// Input WMEs made through [`Io`] are added again (their handles stay valid).
    pub fn init_soar(&mut self) -> Result<(), Error> {
        self.source_text("<init-soar>", "init-soar")
    }

    // ---- Input and output ----

    /// The input and output links, for use between runs.
    pub fn io(&mut self) -> Io<'_> {
        Io::new(&mut self.interp.agent)
    }

    /// Calls `hook` at the start of every input phase, before the input changes made so far
    /// reach the matcher: the place to write the environment's state on the input-link.
    pub fn on_input_phase(&mut self, hook: impl FnMut(&mut Io) + 'static) -> ListenerId {
        let id = self.new_id();
        self.input_hooks.borrow_mut().push((id, Box::new(hook)));
        if self.interp.agent.input_callback.is_none() {
            self.interp.agent.input_callback = Some(dispatcher(&self.input_hooks));
        }
        id
    }

    /// Calls `hook` at the end of every output phase: the place to read and carry out the
    /// agent's output commands.
    pub fn on_output_phase(&mut self, hook: impl FnMut(&mut Io) + 'static) -> ListenerId {
        let id = self.new_id();
        self.output_hooks.borrow_mut().push((id, Box::new(hook)));
        if self.interp.agent.output_callback.is_none() {
            self.interp.agent.output_callback = Some(dispatcher(&self.output_hooks));
        }
        id
    }

    /// How an update of an input WME to its current value acts (default:
    /// [`InputUpdate::BlinkIfNoChange`], as in the official kernel).
    pub fn set_input_update(&mut self, mode: InputUpdate) {
        self.interp.agent.set_input_update(mode);
    }

    // ---- Host functions ----

    /// Registers a function the rules can call as `(name args...)` or `(exec name
    /// args...)`. It gets the arguments typed and returns a value, or an error that the
    /// trace reports (the call's value is then the error's text). A panic in it is caught
    /// and reported the same way. A function of the same name is replaced.
    pub fn register_rhs_function(
        &mut self,
        name: &str,
        f: impl FnMut(&RhsCall, &[RhsArg]) -> Result<Value, String> + 'static,
    ) {
        self.interp
            .agent
            .rhs_registry
            .register_typed(name, Box::new(f));
    }

    /// Registers a function in SML's form: it gets the agent's name and the arguments'
    /// texts joined with no separator, and returns a string, which becomes a string
    /// constant (Soar manual, `exec` in "Right-hand side functions").
    pub fn register_sml_rhs_function(
        &mut self,
        name: &str,
        f: impl FnMut(&str, &str) -> String + 'static,
    ) {
        self.interp.agent.register_rhs_function(name, f);
    }

    /// Gives an SML-form function a faster form for calls whose arguments are numbers
    /// separated by comma strings (`(f <x> |, | <y>)`): it gets the numbers the argument
    /// text holds, and must return what the text form returns for it (or `None` to let
    /// the text form answer). False when no SML-form function `name` is registered.
    pub fn register_sml_rhs_numeric_form(
        &mut self,
        name: &str,
        f: impl FnMut(&[f64]) -> Option<String> + 'static,
    ) -> bool {
        self.interp.agent.register_rhs_numeric(name, f)
    }

    /// Whether a function is registered as `name`.
    pub fn has_rhs_function(&self, name: &str) -> bool {
        self.interp.agent.rhs_registry.is_registered(name)
    }

    /// Removes a registered function; false when there was none.
    pub fn unregister_rhs_function(&mut self, name: &str) -> bool {
        self.interp.agent.rhs_registry.unregister(name)
    }

    // ---- Working memory and rules ----

    /// The identifier named `name` (`S1`, `i2`), if it exists.
    pub fn find_identifier(&self, name: &str) -> Option<Sym> {
        self.interp.agent.symbols.find_id(name)
    }

    /// The string constant `text`, if the agent has it.
    pub fn find_string(&self, text: &str) -> Option<Sym> {
        self.interp.agent.symbols.find_str(text)
    }

    /// A symbol as Soar prints it.
    pub fn text(&self, s: Sym) -> String {
        self.interp.agent.symbols.text(s)
    }

    /// A symbol as a [`Value`].
    pub fn value_of(&self, s: Sym) -> Value {
        self.interp.agent.value_of(s)
    }

    /// A value as Soar prints it (strings that need them in `|bars|`).
    pub fn value_text(&self, v: &Value) -> String {
        value_text(&self.interp.agent, v)
    }

    /// Whether a symbol is an identifier.
    pub fn is_identifier(&self, s: Sym) -> bool {
        self.interp.agent.symbols.is_id(s)
    }

    /// The WMEs of an identifier, oldest first.
    pub fn children(&self, id: Sym) -> Vec<Wme> {
        children(&self.interp.agent, id)
    }

    /// Whether identifier `id` has a WME with attribute `attr`.
    pub fn has_attribute(&self, id: Sym, attr: &str) -> bool {
        has_attribute(&self.interp.agent, id, attr)
    }

    /// The identifiers that have WMEs.
    pub fn identifiers(&self) -> Vec<Sym> {
        self.interp.agent.wm.ids().collect()
    }

    /// The number of WMEs in working memory.
    pub fn wme_count(&self) -> usize {
        self.interp.agent.wm.len()
    }

    /// The top state's identifier (`S1`).
    pub fn top_state(&self) -> Sym {
        self.interp.agent.top.state
    }

    /// The names of the loaded rules, in load order.
    pub fn production_names(&self) -> Vec<String> {
        self.interp
            .agent
            .productions()
            .map(|p| p.name.to_string())
            .collect()
    }

    /// The number of loaded rules.
    pub fn production_count(&self) -> usize {
        self.interp.agent.production_count()
    }

    /// Decisions made since the agent was created or last initialized.
    pub fn decisions(&self) -> u64 {
        self.interp.agent.decider.decisions
    }

    /// Rule firings since the agent was created or last initialized.
    pub fn firings(&self) -> u64 {
        self.interp.agent.decider.firings
    }

    /// Whether the agent has halted (it runs again after `init-soar`).
    pub fn is_halted(&self) -> bool {
        self.interp.agent.decider.halted
    }

    // ---- Settings ----

    /// Sets the trace level, as `watch N` does (0 to 5).
    pub fn set_trace_level(&mut self, level: u8) {
        self.interp.agent.settings.trace.set_level(level.min(5));
    }

    /// Sets the seed of the agent's random numbers, as `srand N` does.
    pub fn set_random_seed(&mut self, seed: u32) {
        self.interp.agent.seed_rng(seed);
    }
}

/// Removes entry `id` from a list of listeners or hooks; false if it was not there.
fn remove_by_id<T>(list: &RefCell<Vec<(ListenerId, T)>>, id: ListenerId) -> bool {
    let mut list = list.borrow_mut();
    let before = list.len();
    list.retain(|(i, _)| *i != id);
    list.len() != before
}

/// The kernel's phase callback that calls each hook of `hooks`, in the order registered.
fn dispatcher(hooks: &Hooks) -> crate::agent::PhaseCallback {
    let hooks = Rc::clone(hooks);
    Box::new(move |core| {
        let mut io = Io::new(core);
        for (_, h) in hooks.borrow_mut().iter_mut() {
            h(&mut io);
        }
    })
}

impl Drop for Agent {
    fn drop(&mut self) {
        // Hooks hold the listener lists; the agent's callbacks hold the hooks.
        self.interp.agent.input_callback = None;
        self.interp.agent.output_callback = None;
    }
}
