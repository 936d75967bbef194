//! Soar's command language over an [`AgentCore`]: alias expansion, unique-prefix command names,
//! option clusters, `source` with its directory handling and first-error abort
//! (Soar manual, ch. 9, "The Soar User Interface"). The interpreter runs without a
//! terminal; front ends drain its [`Event`]s.

pub mod aliases;
mod chunk;
mod chunk_listing;
mod chunk_stats;
mod debug;
mod decide;
mod file_commands;
mod files;
mod gp;
mod limits;
mod load_forecast;
pub mod help;
mod memory;
mod memory_usage;
pub mod options;
mod output;
mod percepts;
mod prefs;
mod prefs_support;
mod print_cmd;
mod printing;
mod production_find;
mod rete_net;
mod rl;
mod rules;
mod save;
mod running;
mod settings;
mod epmem;
mod explain;
mod memory_stats;
mod smem;
mod stats;
mod svs;
pub mod tokenizer;
mod tracing;
mod visualize;
mod visualize_graph;
mod wm_activation;
mod wm_watch;

use crate::agent::{AgentCore, PhaseCallback};
use crate::commands::tokenizer::{Command, WordKind};
use crate::source::{Diagnostic, SourceMap, Span};
use aliases::Aliases;
use indexmap::IndexMap;
use std::cell::{Cell, RefCell};
use std::path::PathBuf;
use std::rc::Rc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// The real (non-alias) top-level command names of 9.6 (`help`), plus `learn` and `exit`.
pub const COMMANDS: &[&str] = &[
    "alias",
    "cd",
    "chunk",
    "debug",
    "decide",
    "dirs",
    "echo",
    "epmem",
    "exit",
    "explain",
    "file-system",
    "gp",
    "help",
    "learn",
    "limits",
    "load",
    "ls",
    "output",
    "popd",
    "preferences",
    "print",
    "production",
    "pushd",
    "pwd",
    "rl",
    "run",
    "save",
    "smem",
    "soar",
    "sp",
    "stats",
    "svs",
    "trace",
    "visualize",
    "wm",
];

/// What the interpreter has to show, in order.
#[derive(Debug, Clone, PartialEq)]
pub enum Event {
    /// Text as Soar prints it (command results, `echo`, progress marks).
    Text(String),
    /// A located warning or error.
    Diag(Diagnostic),
}

/// What `source` has loaded: the rules per file, and how many replaced or repeated a rule.
#[derive(Debug, Default, Clone)]
pub struct LoadReport {
    pub(crate) per_file: IndexMap<PathBuf, usize>,
    pub(crate) added: usize,
    pub(crate) excised: usize,
    pub(crate) ignored: usize,
    /// The names of the excised rules, in order (`source -v` lists them).
    pub(crate) excised_names: Vec<String>,
    /// Rules added and excised since the last per-file summary of `source -a`.
    pub(crate) added_since_summary: usize,
    pub(crate) excised_since_summary: Vec<String>,
}

impl LoadReport {
    /// Each sourced file with the rules it added, in the order the files were first read.
    pub fn files(&self) -> impl Iterator<Item = (&std::path::Path, usize)> {
        self.per_file.iter().map(|(p, n)| (p.as_path(), *n))
    }

    /// Rules added.
    pub fn added(&self) -> usize {
        self.added
    }

    /// Rules that replaced a rule of the same name (which was excised).
    pub fn excised(&self) -> usize {
        self.excised
    }

    /// Rules ignored because an identical rule was already loaded.
    pub fn ignored(&self) -> usize {
        self.ignored
    }

    /// Counts an excised rule, for the summaries of `source`.
    pub(crate) fn note_excised(&mut self, name: &str) {
        self.excised += 1;
        self.excised_names.push(name.to_string());
        self.excised_since_summary.push(name.to_string());
    }
}

pub struct Interpreter {
    pub agent: AgentCore,
    pub sources: SourceMap,
    aliases: Aliases,
    cwd: PathBuf,
    home: PathBuf,
    dir_stack: Vec<PathBuf>,
    /// Files being sourced, innermost last.
    source_stack: Vec<PathBuf>,
    /// The listings the outermost `source` asked for (`-a`, `-v`).
    source_listing: files::SourceListing,
    /// The path of the file `source` read last (`source -a` names it at its end).
    last_sourced: Option<PathBuf>,
    events: Vec<Event>,
    pub report: LoadReport,
    /// Set by `exit`.
    pub exit_requested: bool,
    /// How many `debug time` commands are running inside one another (an alias can make
    /// one time itself).
    timed_depth: usize,
    /// The last thing printed was an `sp` progress mark, so other output starts a new line.
    after_star: bool,
    /// The line of marks holds only `smem --add`'s `@` marks (a nested `source` goes on on
    /// it, as in 9.6).
    after_at_marks: bool,
    /// A `gp` is loading its rules: their marks are a run of their own.
    in_gp: bool,
    /// The line's last marks came from a `gp`: 9.6 ends the line (with a space) where
    /// the marks of a `gp` and those of other rules meet.
    gp_marks: bool,
    /// The `output log` file, when one is open.
    log: Option<output::OutputLog>,
    /// Set from outside (the REPL's Ctrl-C handler) to stop a `run` at the next decision.
    interrupt: Option<Arc<AtomicBool>>,
    /// A run inside a sourced file was interrupted (Ctrl-C): the sourcing stops too.
    run_interrupted_in_source: bool,
    /// Receives the trace while a `run` goes on, once per decision, instead of at its end.
    live: Option<LiveSink>,
    /// The column where the agent's print stream stands: trace output and the output of
    /// `print`, `matches`, `learn` and `chunk` move it, other command results do not. 9.6
    /// wraps a printed object's first line from there.
    print_col: Rc<Cell<usize>>,
    /// `visualize`'s settings and the number of its last file.
    viz: visualize::VizSettings,
}

/// A sub-command or setting `word` names among `names`: the exact name, or the prefix of
/// just one; otherwise the names it is a prefix of (none, or several).
fn resolve_prefix(names: &[&'static str], word: &str) -> Result<&'static str, Vec<&'static str>> {
    if let Some(n) = names.iter().find(|n| **n == word) {
        return Ok(n);
    }
    let found: Vec<&'static str> = names.iter().copied().filter(|n| n.starts_with(word)).collect();
    match found.as_slice() {
        [one] => Ok(one),
        _ => Err(found),
    }
}

/// A switch's value as the settings listings write it.
fn on_off(b: bool) -> &'static str {
    if b {
        "on"
    } else {
        "off"
    }
}

/// Moves a print-stream column over `text`.
fn advance_col(col: &Cell<usize>, text: &str) {
    match text.rfind('\n') {
        Some(i) => col.set(text[i + 1..].chars().count()),
        None => col.set(col.get() + text.chars().count()),
    }
}

/// A front end's sink for text printed during a long command (see [`Interpreter::set_live_output`]).
pub type LiveSink = Rc<RefCell<dyn FnMut(&str)>>;

/// A command's outcome: its result text, or the diagnostic that made it fail.
pub type CmdResult = Result<String, Diagnostic>;

impl Default for Interpreter {
    fn default() -> Self {
        Self::new()
    }
}

impl Interpreter {
    pub fn new() -> Self {
        let cwd = std::env::current_dir().unwrap_or_else(|_| PathBuf::from("."));
        Interpreter {
            agent: AgentCore::new("soar"),
            sources: SourceMap::new(),
            aliases: Aliases::default(),
            home: cwd.clone(),
            cwd,
            dir_stack: Vec::new(),
            source_stack: Vec::new(),
            source_listing: files::SourceListing::default(),
            last_sourced: None,
            events: Vec::new(),
            report: LoadReport::default(),
            exit_requested: false,
            timed_depth: 0,
            after_star: false,
            after_at_marks: false,
            in_gp: false,
            gp_marks: false,
            log: None,
            interrupt: None,
            run_interrupted_in_source: false,
            live: None,
            // Creating the agent printed `\n     0: ==>S: S1 ` (trace level 1).
            print_col: Rc::new(Cell::new("     0: ==>S: S1 ".len())),
            viz: visualize::VizSettings::default(),
        }
    }

    /// Starts a new command line's result: the `*` marks of an earlier one are not
    /// continued (each of SML's `ExecuteCommandLine` calls returns its own text).
    pub(crate) fn start_result(&mut self) {
        self.after_star = false;
    }

    /// The print stream's column (see [`Self::print_col`]).
    pub(crate) fn print_column(&self) -> usize {
        self.print_col.get()
    }

    /// Tells the agent whether the print stream stands at a line's start, before it
    /// traces (9.6 starts some lines only when it does not).
    fn sync_line_start(&mut self) {
        self.agent.output_line_start = self.print_col.get() == 0;
    }

    /// A flag that, once set, stops the current `run` after the elaboration cycle it is in
    /// (the phase goes on at the next run); the run then reports `Interrupted.` and clears
    /// the flag. The REPL's Ctrl-C handler sets it.
    pub fn set_interrupt(&mut self, flag: Arc<AtomicBool>) {
        self.agent.interrupt = Some(Arc::clone(&flag));
        self.interrupt = Some(flag);
    }

    /// Sends the trace of a `run` to `sink` as it happens (once per decision), and whatever
    /// was printed before the run first, so a terminal shows a long run while it goes on.
    pub fn set_live_output(&mut self, sink: LiveSink) {
        self.live = Some(sink);
    }

    /// Stops sending the trace to a live sink: it stays on the print stream.
    pub fn clear_live_output(&mut self) {
        self.live = None;
    }

    /// How many printed events are waiting.
    pub(crate) fn event_count(&self) -> usize {
        self.events.len()
    }

    /// Takes the printed events from place `start` on.
    pub(crate) fn take_events_from(&mut self, start: usize) -> Vec<Event> {
        self.events.split_off(start.min(self.events.len()))
    }

    /// The alias table (for completion and `help`).
    pub fn aliases(&self) -> &Aliases {
        &self.aliases
    }

    /// Wraps the agent's output callback for one run: the wrapper calls the program's own
    /// callback, then hands the trace to the live sink and turns an interrupt into a stop
    /// request. Gives back the program's callback for [`Self::end_run_hooks`].
    fn begin_run_hooks(&mut self) -> Option<Rc<RefCell<Option<PhaseCallback>>>> {
        if self.interrupt.is_none() && self.live.is_none() {
            return None;
        }
        if let Some(live) = self.live.clone() {
            // Text printed before the run comes out first.
            let before = self.take_output();
            if !before.is_empty() {
                (live.borrow_mut())(&before);
            }
        }
        let own = Rc::new(RefCell::new(self.agent.output_callback.take()));
        let inner = Rc::clone(&own);
        let flag = self.interrupt.clone();
        let live = self.live.clone();
        let col = Rc::clone(&self.print_col);
        self.agent.output_callback = Some(Box::new(move |a: &mut AgentCore| {
            if let Some(cb) = inner.borrow_mut().as_mut() {
                cb(a);
            }
            if let Some(live) = &live {
                if !a.output.is_empty() {
                    let text = std::mem::take(&mut a.output);
                    advance_col(&col, &text);
                    a.output_line_start = col.get() == 0;
                    (live.borrow_mut())(&text);
                }
            }
            if flag.as_ref().is_some_and(|f| f.load(Ordering::SeqCst)) {
                a.decider.stop_requested = true;
            }
        }));
        Some(own)
    }

    /// Puts the program's own output callback back; true if the run was interrupted.
    fn end_run_hooks(&mut self, own: Option<Rc<RefCell<Option<PhaseCallback>>>>) -> bool {
        if let Some(own) = own {
            self.agent.output_callback = own.borrow_mut().take();
        }
        if let Some(live) = &self.live {
            if !self.agent.output.is_empty() {
                let text = std::mem::take(&mut self.agent.output);
                advance_col(&self.print_col, &text);
                (live.borrow_mut())(&text);
            }
        }
        self.interrupt
            .as_ref()
            .is_some_and(|f| f.swap(false, Ordering::SeqCst))
    }

    /// The directory relative paths resolve against (Soar's working directory).
    pub fn cwd(&self) -> &std::path::Path {
        &self.cwd
    }

    pub fn set_cwd(&mut self, dir: PathBuf) {
        self.home = dir.clone();
        self.cwd = dir;
    }

    /// Takes everything printed so far.
    pub fn take_events(&mut self) -> Vec<Event> {
        std::mem::take(&mut self.events)
    }

    /// Renders an event as a terminal shows it (diagnostics through codespan).
    pub fn render(&self, e: &Event) -> String {
        match e {
            Event::Text(t) => t.clone(),
            Event::Diag(d) => self.sources.render(d),
        }
    }

    /// Renders and takes everything printed so far, as one string.
    pub fn take_output(&mut self) -> String {
        let events = self.take_events();
        self.render_all(&events)
    }

    /// Events rendered as one text: a diagnostic starts on a line of its own.
    pub(crate) fn render_all(&self, events: &[Event]) -> String {
        let mut s = String::new();
        for e in events {
            let r = self.render(e);
            if matches!(e, Event::Diag(_)) && !s.is_empty() && !s.ends_with('\n') {
                s.push('\n');
            }
            s.push_str(&r);
        }
        s
    }

    pub(crate) fn warn(&mut self, d: Diagnostic) {
        if self.after_star {
            self.events.push(Event::Text("\n".into()));
            self.after_star = false;
        }
        self.events.push(Event::Diag(d));
    }

    /// Runs a text of commands (a `-c` argument, a REPL line, standard input) under a display
    /// name, stopping at the first failing command. Results are printed as events.
    pub fn run_text(&mut self, name: &str, text: &str) -> Result<(), Diagnostic> {
        let file = self.sources.add(name, text);
        self.run_file_id(file)
    }

    /// Runs a text of commands as Soar's command line reads them: a command that fails
    /// puts its diagnostic on the print stream, and the next command runs. Only text that
    /// cannot be read as commands (an unclosed brace) ends it. Returns how many failed.
    pub fn run_text_keep_going(&mut self, name: &str, text: &str) -> usize {
        let file = self.sources.add(name, text);
        let mut failed = 0;
        for cmd in self.commands_of(file) {
            let cmd = match cmd {
                Ok(c) => c,
                Err(d) => {
                    let d = self.failing(d);
                    self.events.push(Event::Diag(d));
                    failed += 1;
                    break;
                }
            };
            let result = self.execute(&cmd);
            self.flush_agent_output();
            match result {
                Ok(r) => self.print_result(r),
                Err(d) => {
                    let d = self.failing(d);
                    self.events.push(Event::Diag(d));
                    failed += 1;
                }
            }
            if self.exit_requested {
                break;
            }
        }
        failed
    }

    /// The commands of a registered text.
    fn commands_of(&self, file: usize) -> file_commands::FileCommands {
        file_commands::FileCommands::new(file, self.sources.file_text(file))
    }

    fn run_file_id(&mut self, file: usize) -> Result<(), Diagnostic> {
        self.run_file_id_at(file).map_err(|(d, _)| d)
    }

    /// Runs a registered text; a failure also gives the span of the command that failed in
    /// this text (for `source`'s "while sourcing FILE:LINE" trail).
    fn run_file_id_at(&mut self, file: usize) -> Result<(), (Diagnostic, Span)> {
        let mut commands = self.commands_of(file);
        let (_, len, large) = commands.progress();
        let mut forecast = load_forecast::LoadForecast::new(len, large, self.report.added);
        while let Some(cmd) = commands.next() {
            if let Some(rules) = forecast.rules_to_come(commands.progress().0, self.report.added) {
                self.agent.reserve_for_rules(rules);
            }
            let cmd = match cmd {
                Ok(c) => c,
                Err(d) => {
                    let at = d.span.unwrap_or_default();
                    return Err((self.failing(d), at));
                }
            };
            let result = self.execute(&cmd);
            self.flush_agent_output();
            let result = match result {
                Ok(r) => r,
                Err(d) => return Err((self.failing(d), cmd.span)),
            };
            self.print_result(result);
            if self.exit_requested {
                break;
            }
            if self.source_interrupted() {
                let d = Diagnostic::error("Interrupted: the rest of this file is not sourced.")
                    .at(cmd.span)
                    .with_label("the last command run")
                    .with_note("what the file did up to here stays: its rules stay loaded");
                return Err((self.failing(d), cmd.span));
            }
        }
        Ok(())
    }

    /// Whether Ctrl-C (the interrupt flag) came while a file is being sourced, during a run
    /// in it or between its commands: the file stops after the command it is at, as a
    /// command that fails stops it, so the agent is left as that command left it.
    fn source_interrupted(&mut self) -> bool {
        if self.source_stack.is_empty() {
            return false;
        }
        let flagged = self
            .interrupt
            .as_ref()
            .is_some_and(|f| f.swap(false, Ordering::SeqCst));
        std::mem::take(&mut self.run_interrupted_in_source) || flagged
    }

    /// A failure ends a line of `*` progress marks first, as a warning does.
    fn failing(&mut self, d: Diagnostic) -> Diagnostic {
        if self.after_star {
            self.events.push(Event::Text("\n".into()));
            self.after_star = false;
        }
        d
    }

    /// Prints a command's result; `*` progress marks of `sp` (and `@` marks of `smem --add`)
    /// run together on one line.
    fn print_result(&mut self, result: String) {
        if result.is_empty() {
            return;
        }
        // `smem --add`'s `@` marks run on with them, as in 9.6.
        let this_is_star = result.chars().all(|c| c == '*' || c == '#' || c == '@');
        // Text after a line of `@` marks alone runs on with it, as in 9.6.
        if self.after_star && !this_is_star && !self.after_at_marks {
            self.events.push(Event::Text("\n".into()));
        }
        // Whether these marks meet another kind's on their line (see `gp_marks`).
        let meet = this_is_star && std::mem::replace(&mut self.gp_marks, self.in_gp) != self.in_gp;
        if self.after_star && this_is_star {
            self.after_at_marks &= result.chars().all(|c| c == '@');
            // One event per line of marks, not one per rule.
            if let Some(Event::Text(t)) = self.events.last_mut() {
                if meet {
                    t.push_str(" \n");
                }
                t.push_str(&result);
                return;
            }
        }
        let at_marks = result.chars().all(|c| c == '@');
        self.after_at_marks = this_is_star && at_marks && (!self.after_star || self.after_at_marks);
        self.after_star = this_is_star;
        let mut r = result;
        if !this_is_star && !r.ends_with('\n') {
            r.push('\n');
        }
        self.events.push(Event::Text(r));
    }

    /// Executes one tokenized command.
    pub fn execute(&mut self, cmd: &Command) -> CmdResult {
        if self.log.is_none() || !self.source_stack.is_empty() {
            return self.execute_command(cmd);
        }
        // `output log`: the command as typed, then what it printed.
        let start = self.events.len();
        let result = self.execute_command(cmd);
        self.flush_agent_output();
        let mut printed = self.render_all(&self.events[start..]);
        if let Ok(r) = &result {
            printed.push_str(r);
        }
        let line = self.sources.snippet(cmd.span);
        self.log_command(&line, &printed);
        result
    }

    fn execute_command(&mut self, cmd: &Command) -> CmdResult {
        // `sp` reads its body from the command itself, so a rule file's commands are not
        // copied word by word (unless `sp` is an alias).
        let w0 = &cmd.words[0];
        if w0.text == "sp" && (w0.kind != WordKind::Bare || self.aliases.get("sp").is_none()) {
            return self.cmd_sp(&Ctx { cmd, alias: None });
        }
        let mut words: Vec<String> = cmd.words.iter().map(|w| w.text.clone()).collect();
        let first = cmd.words.first().map(|w| w.span).unwrap_or(cmd.span);
        // Alias expansion: only the first word, by exact match, as in Soar.
        let mut expanded_from = None;
        if cmd.words[0].kind == WordKind::Bare {
            if let Some(exp) = self.aliases.get(&words[0]) {
                expanded_from = Some(words[0].clone());
                let mut new = exp.to_vec();
                new.extend(words.drain(1..));
                words = new;
            }
        }
        let name = match self.resolve_command(&words[0]) {
            Ok(n) => n,
            Err(possible) if !possible.is_empty() => {
                let list: String = possible.iter().map(|c| format!("'{c}' ")).collect();
                return Err(
                    Diagnostic::error(format!("Ambiguous command, possibilities: {list}"))
                        .at(first)
                        .with_label("a prefix of several commands"),
                );
            }
            Err(_) => {
                let mut d = Diagnostic::error(format!("No such command: {}", words[0]))
                    .at(first)
                    .with_label("unknown command");
                let near = nearest_commands(&words[0], &self.aliases);
                if !near.is_empty() {
                    d = d.with_note(format!("did you mean: {}", near.join(", ")));
                }
                return Err(d);
            }
        };
        let ctx = Ctx {
            cmd,
            alias: expanded_from.as_deref(),
        };
        let args = &words[1..];
        let result = match name {
            "sp" => self.cmd_sp(&ctx),
            "gp" => self.cmd_gp(&ctx),
            "load" => self.cmd_load(&ctx, args),
            "pushd" => self.cmd_pushd(&ctx, args),
            "popd" => self.cmd_popd(&ctx),
            "cd" => self.cmd_cd(&ctx, args),
            "pwd" => Ok(self.cwd.display().to_string()),
            "dirs" => Ok(self.cmd_dirs()),
            "ls" => self.cmd_ls(&ctx),
            "echo" => Ok(cmd_echo(args)),
            "alias" => self.cmd_alias(args),
            "learn" => self.cmd_learn(&ctx, args),
            "limits" => self.cmd_limits(&ctx, args),
            "chunk" => self.cmd_chunk(&ctx, args),
            "soar" => self.cmd_soar(&ctx, args),
            "trace" => self.cmd_trace(&ctx, args),
            "decide" => self.cmd_decide(&ctx, args),
            "output" => self.cmd_output(&ctx, args),
            "print" => self.cmd_print(&ctx, args),
            "preferences" => self.cmd_preferences(&ctx, args),
            "production" => self.cmd_production(&ctx, args),
            "wm" => self.cmd_wm(&ctx, args),
            "run" => self.cmd_run(&ctx, args),
            "stats" => self.cmd_stats_options(&ctx, args),
            "save" => self.cmd_save(&ctx, args),
            "rl" => self.cmd_rl(&ctx, args),
            "smem" => self.cmd_smem(&ctx, args),
            "epmem" => self.cmd_epmem(&ctx, args),
            "help" => self.cmd_help(&ctx, args),
            "debug" => self.cmd_debug(&ctx, args),
            "svs" => self.cmd_svs(&ctx, args),
            "visualize" => self.cmd_visualize(&ctx, args),
            "explain" => self.cmd_explain(&ctx, args),
            "exit" => {
                self.exit_requested = true;
                Ok(String::new())
            }
            other => Err(not_yet(&ctx, other)),
        };
        // These commands print through the agent's printer in 9.6 (checked one by one).
        // 9.6 answers `print` of an identifier that is gone without its printer.
        let no_such_id = matches!(&result, Ok(t) if t.starts_with("There is no identifier"));
        let printed = (matches!(name, "print" | "learn" | "chunk") && !no_such_id)
            || (name == "production" && args.first().is_some_and(|a| a == "matches"));
        // With `output enabled` or `output callbacks` off, what 9.6 prints through the
        // agent is not shown (checked one by one on soar-sml 9.6.5).
        let s = &self.agent.settings;
        if !(s.output_enabled && s.output_callbacks) {
            let listing = args.is_empty() || args[0] == "?";
            let through_agent = matches!(name, "print" | "preferences")
                || (name == "production" && args.first().is_some_and(|a| a == "matches"))
                || (listing && matches!(name, "soar" | "chunk" | "decide" | "output"));
            if let (true, Ok(text)) = (through_agent, &result) {
                // Not shown, but 9.6's printer still counts the columns it would take.
                advance_col(&self.print_col, text);
                return Ok(String::new());
            }
        }
        if let (true, Ok(text)) = (printed, &result) {
            advance_col(&self.print_col, text);
        }
        result
    }

    /// `help [command]`: the list, or one command's manual page (an alias: its expansion's).
    fn cmd_help(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let Some(name) = args.first() else {
            return Ok(help::listing());
        };
        match help::help_for(name, &self.aliases) {
            help::Help::Page(text) | help::Help::Ambiguous(text) => Ok(text),
            help::Help::Unknown => {
                let mut d = Diagnostic::error(format!("No such command '{name}'."))
                    .at(ctx.arg_span(0))
                    .with_label("not a command or alias");
                let near = nearest_commands(name, &self.aliases);
                if !near.is_empty() {
                    d = d.with_note(format!("did you mean: {}", near.join(", ")));
                }
                Err(d)
            }
        }
    }

    /// Exact name, else a unique prefix of a real command name (aliases are not prefixes).
    /// A prefix of several commands gives them all back as the error.
    /// `file-system` is a help topic, not a command, as in 9.6 (`fi`, `file-system`: `No
    /// such command`).
    fn resolve_command(&self, word: &str) -> Result<&'static str, Vec<&'static str>> {
        let runnable = || COMMANDS.iter().copied().filter(|c| *c != "file-system");
        if let Some(c) = runnable().find(|c| *c == word) {
            return Ok(c);
        }
        if word.is_empty() {
            return Err(Vec::new());
        }
        let matches: Vec<&'static str> = runnable().filter(|c| c.starts_with(word)).collect();
        match matches.as_slice() {
            [one] => Ok(one),
            _ => Err(matches),
        }
    }
}

/// Where a command came from, for diagnostics.
pub(crate) struct Ctx<'a> {
    pub cmd: &'a Command,
    /// The alias the command was written as, if any.
    pub alias: Option<&'a str>,
}

impl Ctx<'_> {
    /// Span of argument `i` (0 = first argument after the command word), or the command.
    pub fn arg_span(&self, i: usize) -> Span {
        self.cmd
            .words
            .get(i + 1)
            .map(|w| w.span)
            .unwrap_or(self.cmd.span)
    }
    pub fn error(&self, msg: impl Into<String>) -> Diagnostic {
        Diagnostic::error(msg)
            .at(self.cmd.span)
            .with_label("in this command")
    }
}

/// A clear error for a command (or subcommand) that parses but that rusoar does not run.
fn not_yet(ctx: &Ctx, name: &str) -> Diagnostic {
    let shown = ctx.alias.unwrap_or(name);
    Diagnostic::error(format!("{shown}: not yet supported by rusoar"))
        .at(ctx.cmd.span)
        .with_label("this command parses but does not run yet")
        .with_note(format!(
            "`{name}` is not implemented in rusoar yet; see README.md \"What works\""
        ))
}

fn cmd_echo(args: &[String]) -> String {
    let (newline, words) = match args.first().map(String::as_str) {
        Some("--nonewline") | Some("-n") => (false, &args[1..]),
        _ => (true, args),
    };
    let mut s = words.join(" ");
    if newline {
        s.push('\n');
    }
    s
}

/// Up to three command names or aliases close to `word` (edit distance), for "did you mean".
pub fn nearest_commands(word: &str, aliases: &Aliases) -> Vec<String> {
    let mut cands: Vec<(usize, String)> = COMMANDS
        .iter()
        .map(|c| c.to_string())
        .chain(aliases::DEFAULT_ALIASES.iter().map(|(a, _)| a.to_string()))
        .filter(|c| aliases.get(c).is_some() || COMMANDS.contains(&c.as_str()))
        .map(|c| (edit_distance(word, &c), c))
        .filter(|(d, c)| *d <= 2.max(word.len() / 3) && c.len() > 1)
        .collect();
    cands.sort();
    cands.dedup_by(|a, b| a.1 == b.1);
    cands.into_iter().take(3).map(|(_, c)| c).collect()
}

fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for i in 1..=a.len() {
        let mut cur = vec![i; b.len() + 1];
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            cur[j] = (prev[j] + 1).min(cur[j - 1] + 1).min(prev[j - 1] + cost);
        }
        prev = cur;
    }
    prev[b.len()]
}
