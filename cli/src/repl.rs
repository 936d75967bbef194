//! The interactive front end: a rustyline editor over the [`Interpreter`]
//! backend. Line editing and persistent history, tab completion of command names, aliases,
//! rule names and identifiers, a prompt with the agent's name and decision count, input that
//! goes on over several lines while a brace, quote or `|` is open, Ctrl-C that stops a
//! running `run` (and clears the line at the prompt), Ctrl-D to quit.

use rusoar::syntax::Tokenizer;
use rusoar::{Agent, Printed};
use rustyline::completion::{Completer, Pair};
use rustyline::error::ReadlineError;
use rustyline::highlight::Highlighter;
use rustyline::hint::Hinter;
use rustyline::history::DefaultHistory;
use rustyline::validate::{ValidationContext, ValidationResult, Validator};
use rustyline::{CompletionType, Config, Context, Editor, Helper};
use std::cell::Cell;
use std::io::Write;
use std::panic::AssertUnwindSafe;
use std::path::PathBuf;
use std::rc::Rc;
use std::sync::atomic::Ordering;
use std::sync::Arc;

/// Whether `text` stops in the middle of a command: an open brace, quote or `|`, or a
/// final backslash that continues the line. Uses the command tokenizer itself, so the REPL
/// waits exactly when `source` would report "unexpected eof".
pub fn is_incomplete(text: &str) -> bool {
    let trailing_backslashes = text
        .trim_end_matches(['\n', '\r'])
        .bytes()
        .rev()
        .take_while(|b| *b == b'\\')
        .count();
    if trailing_backslashes % 2 == 1 {
        return true;
    }
    Tokenizer::new(text, 0).any(|c| match c {
        Err(d) => d.message.starts_with("unexpected eof"),
        Ok(_) => false,
    })
}

/// The prompt: the agent's name and how many decisions it has made, as in `soar 12> `.
pub fn prompt(agent: &Agent) -> String {
    format!("{} {}> ", agent.name(), agent.decisions())
}

/// Where the history lives: `$RUSOAR_HISTORY`, else `~/.rusoar_history`.
pub fn history_path() -> Option<PathBuf> {
    if let Some(p) = std::env::var_os("RUSOAR_HISTORY") {
        return Some(PathBuf::from(p));
    }
    std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".rusoar_history"))
}

/// Runs a script as if typed at the REPL, without a terminal: each entry (one line, or
/// several while a brace or quote is open) is shown after the prompt it was typed at,
/// followed by what it printed; errors are rendered as the REPL shows them. For transcript
/// tests and for replaying a session.
pub fn transcript(agent: &mut Agent, script: &str) -> String {
    let mut out = String::new();
    let mut entry = String::new();
    let mut entry_prompt = String::new();
    let mut lines = script.lines().peekable();
    while let Some(line) = lines.next() {
        if entry.is_empty() {
            if line.trim().is_empty() {
                continue;
            }
            entry_prompt = prompt(agent);
        } else {
            entry.push('\n');
        }
        entry.push_str(line);
        if is_incomplete(&entry) && lines.peek().is_some() {
            continue;
        }
        let text = std::mem::take(&mut entry);
        out.push_str(&entry_prompt);
        out.push_str(&text.replace('\n', "\n... "));
        out.push('\n');
        let result = agent.source_text("<stdin>", &text);
        let mut shown = agent.take_output();
        if let Err(e) = result {
            if !shown.is_empty() && !shown.ends_with('\n') {
                shown.push('\n');
            }
            shown.push_str(&e.render());
        }
        out.push_str(&shown);
        if !out.ends_with('\n') {
            out.push('\n');
        }
        if agent.exit_requested() {
            break;
        }
    }
    out
}

/// What tab completion offers, refreshed from the interpreter before each prompt.
#[derive(Debug, Default, Clone)]
pub struct ReplHelper {
    /// Command names and aliases (first word of a command).
    commands: Vec<String>,
    /// Rule names and identifiers in working memory (later words).
    things: Vec<String>,
    /// The interpreter's working directory, for completing file names.
    cwd: PathBuf,
}

/// Commands whose arguments are file or directory names.
const PATH_COMMANDS: &[&str] = &["source", "load", "pushd", "cd", "chdir", "ls", "dir"];

/// File names in `cwd` completing `word` (which may hold a directory part); directories end
/// in `/`. Hidden files only when asked for with a leading dot.
fn path_candidates(cwd: &std::path::Path, word: &str) -> Vec<String> {
    let (dir, prefix) = match word.rfind('/') {
        Some(i) => (&word[..=i], &word[i + 1..]),
        None => ("", word),
    };
    let base = if dir.starts_with('/') {
        PathBuf::from(dir)
    } else {
        cwd.join(dir)
    };
    let Ok(entries) = std::fs::read_dir(&base) else {
        return Vec::new();
    };
    let mut out: Vec<String> = entries
        .filter_map(Result::ok)
        .filter_map(|e| {
            let name = e.file_name().to_str()?.to_string();
            if !name.starts_with(prefix) || (name.starts_with('.') && !prefix.starts_with('.')) {
                return None;
            }
            let slash = if e.path().is_dir() { "/" } else { "" };
            Some(format!("{dir}{name}{slash}"))
        })
        .collect();
    out.sort();
    out
}

impl ReplHelper {
    pub fn new(agent: &Agent) -> Self {
        let mut h = ReplHelper::default();
        h.refresh(agent);
        h
    }

    /// Takes the current commands, aliases, rules and identifiers from the interpreter.
    pub fn refresh(&mut self, agent: &Agent) {
        let mut commands = agent.command_names();
        commands.sort();
        commands.dedup();
        self.commands = commands;
        let mut things = agent.production_names();
        let mut ids: Vec<String> = agent
            .identifiers()
            .into_iter()
            .map(|s| agent.text(s))
            .collect();
        ids.sort();
        ids.dedup();
        things.extend(ids);
        self.things = things;
        self.cwd = agent.working_directory().to_path_buf();
    }

    /// The candidates for the word that ends at `pos`: (start of the word, candidates).
    pub fn candidates(&self, line: &str, pos: usize) -> (usize, Vec<String>) {
        let before = &line[..pos];
        let start = before
            .rfind(|c: char| c.is_whitespace() || c == ';' || c == '{' || c == '(')
            .map_or(0, |i| i + 1);
        let word = &before[start..];
        let command = before[..start].rsplit([';', '\n']).next().unwrap_or("");
        let first_word = command.trim().is_empty();
        let command_name = command.split_whitespace().next().unwrap_or("");
        if !first_word && PATH_COMMANDS.contains(&command_name) {
            let start = before
                .rfind(|c: char| c.is_whitespace() || c == ';')
                .map_or(0, |i| i + 1);
            return (start, path_candidates(&self.cwd, &before[start..]));
        }
        let pool = if first_word {
            &self.commands
        } else {
            &self.things
        };
        // Identifiers are typed in either case (`s1` for S1).
        let lower = word.to_lowercase();
        let mut out: Vec<String> = pool
            .iter()
            .filter(|c| c.starts_with(word) || c.to_lowercase().starts_with(&lower))
            .cloned()
            .collect();
        out.dedup();
        (start, out)
    }
}

impl Completer for ReplHelper {
    type Candidate = Pair;
    /// A completed word is followed by a space, as in a shell.
    fn complete(
        &self,
        line: &str,
        pos: usize,
        _ctx: &Context<'_>,
    ) -> rustyline::Result<(usize, Vec<Pair>)> {
        let (start, words) = self.candidates(line, pos);
        let pairs = words
            .into_iter()
            .map(|w| Pair {
                // A directory is completed further, not ended.
                replacement: if w.ends_with('/') {
                    w.clone()
                } else {
                    format!("{w} ")
                },
                display: w,
            })
            .collect();
        Ok((start, pairs))
    }
}

impl Hinter for ReplHelper {
    type Hint = String;
}

impl Highlighter for ReplHelper {}

impl Validator for ReplHelper {
    fn validate(&self, ctx: &mut ValidationContext) -> rustyline::Result<ValidationResult> {
        Ok(if is_incomplete(ctx.input()) {
            ValidationResult::Incomplete
        } else {
            ValidationResult::Valid(None)
        })
    }
}

impl Helper for ReplHelper {}

/// Prints what the agent printed: text to standard output (as it comes, also during a
/// run), diagnostics rendered to standard error. Tracks whether the last text ended a
/// line, so the prompt starts on a fresh one.
fn print(p: &Printed, at_line_start: &Cell<bool>) {
    let mut out = std::io::stdout().lock();
    match p {
        Printed::Text(t) => {
            let _ = out.write_all(t.as_bytes());
            if !t.is_empty() {
                at_line_start.set(t.ends_with('\n'));
            }
        }
        Printed::Diagnostic(e) => {
            if !at_line_start.get() {
                let _ = out.write_all(b"\n");
                at_line_start.set(true);
            }
            let _ = out.flush();
            let _ = std::io::stderr().write_all(e.render().as_bytes());
        }
    }
    let _ = out.flush();
}

/// Runs the REPL until Ctrl-D or `exit`. Returns false if the editor could not start (no
/// terminal): the caller then reads standard input plainly.
pub fn run(agent: &mut Agent) -> bool {
    let config = Config::builder()
        .auto_add_history(false)
        .completion_type(CompletionType::List)
        .build();
    let mut editor: Editor<ReplHelper, DefaultHistory> = match Editor::with_config(config) {
        Ok(e) => e,
        Err(_) => return false,
    };
    editor.set_helper(Some(ReplHelper::new(agent)));
    let history = history_path();
    if let Some(h) = &history {
        // A missing or unreadable history file only means an empty history.
        let _ = editor.load_history(h);
    }

    // Ctrl-C while a command runs: the handler sets the flag and `run` stops within the
    // current elaboration cycle. At the prompt the terminal is in raw mode and rustyline
    // sees Ctrl-C itself.
    let interrupt = agent.interrupt_flag();
    {
        let flag = Arc::clone(&interrupt);
        // Only a third Ctrl-C before the run has stopped (a firing that never ends) leaves.
        let pressed = std::sync::atomic::AtomicU8::new(0);
        let handler = move || {
            if !flag.swap(true, Ordering::SeqCst) {
                pressed.store(1, Ordering::SeqCst);
                return;
            }
            if pressed.fetch_add(1, Ordering::SeqCst) >= 2 {
                eprintln!("\nInterrupted three times: leaving rusoar.");
                std::process::exit(130);
            }
            eprintln!("\nStopping at the end of the current elaboration cycle; Ctrl-C once more leaves rusoar.");
        };
        if let Err(e) = ctrlc::set_handler(handler) {
            eprintln!("warning: Ctrl-C will not interrupt a run ({e})");
        }
    }
    let at_line_start = Rc::new(Cell::new(true));
    {
        let at = Rc::clone(&at_line_start);
        agent.on_print(move |p| print(p, &at));
    }

    loop {
        if let Some(h) = editor.helper_mut() {
            h.refresh(agent);
        }
        if !at_line_start.get() {
            println!();
            at_line_start.set(true);
        }
        match editor.readline(&prompt(agent)) {
            Ok(line) => {
                if line.trim().is_empty() {
                    continue;
                }
                let _ = editor.add_history_entry(line.as_str());
                // Written at once, so that a REPL killed by a signal keeps its history.
                if let Some(h) = &history {
                    let _ = editor.append_history(h);
                }
                interrupt.store(false, Ordering::SeqCst);
                // A bug in rusoar must not end the session: the panic is reported (by the
                // panic hook, then here) and the REPL goes on.
                let result = std::panic::catch_unwind(AssertUnwindSafe(|| {
                    agent.source_text("<stdin>", &line)
                }));
                let failure = match result {
                    Ok(r) => r.err().map(|e| e.render()),
                    Err(_) => Some(
                        "internal error: rusoar panicked running this command (a bug: please \
                         report it); the agent may be inconsistent, `init-soar` resets it\n"
                            .to_string(),
                    ),
                };
                if let Some(text) = failure {
                    if !at_line_start.get() {
                        println!();
                    }
                    eprint!("{text}");
                    at_line_start.set(true);
                }
                if agent.exit_requested() {
                    break;
                }
            }
            // Ctrl-C at the prompt: the line is dropped, a new prompt comes.
            Err(ReadlineError::Interrupted) => continue,
            // Ctrl-D.
            Err(ReadlineError::Eof) => break,
            Err(e) => {
                eprintln!("error reading the terminal: {e}");
                break;
            }
        }
    }
    if !at_line_start.get() {
        println!();
    }
    if let Some(h) = &history {
        let _ = editor.save_history(h);
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn open_braces_quotes_and_pipes_are_incomplete() {
        assert!(is_incomplete("sp {a\n (state <s> ^superstate nil)"));
        assert!(is_incomplete("sp {a (state <s> ^x |}) -->"));
        assert!(is_incomplete("echo \"abc"));
        assert!(is_incomplete("echo |abc"));
        assert!(is_incomplete("echo a \\"));
        assert!(!is_incomplete("echo a \\\\"));
        assert!(!is_incomplete(
            "sp {a (state <s> ^superstate nil) --> (<s> ^b c)}"
        ));
        assert!(!is_incomplete("run 1 -d"));
        assert!(!is_incomplete(""));
        // A stray closing brace is an error for the interpreter, not more input.
        assert!(!is_incomplete("echo }"));
    }

    #[test]
    fn prompt_shows_agent_and_decisions() {
        let mut i = Agent::default();
        assert_eq!(prompt(&i), "soar 0> ");
        i.source_text("t", "watch 0\nrun 3").unwrap();
        assert_eq!(prompt(&i), "soar 3> ");
    }

    #[test]
    fn completes_commands_aliases_rules_and_identifiers() {
        let mut i = Agent::default();
        i.source_text(
            "t",
            "sp {my*rule (state <s> ^superstate nil) --> (<s> ^a b)}",
        )
        .unwrap();
        let h = ReplHelper::new(&i);
        let (start, c) = h.candidates("ru", 2);
        assert_eq!((start, c), (0, vec!["run".to_string()]));
        let (_, c) = h.candidates("init-", 5);
        assert_eq!(c, vec!["init-soar".to_string()]);
        let (start, c) = h.candidates("print my", 8);
        assert_eq!((start, c), (6, vec!["my*rule".to_string()]));
        let (_, c) = h.candidates("print -d 2 s", 12);
        assert_eq!(c, vec!["S1".to_string()]);
        let (_, c) = h.candidates("echo x; exc", 11);
        assert_eq!(c, vec!["excise".to_string()]);
    }

    #[test]
    fn completes_file_names_from_the_interpreters_directory() {
        let mut i = Agent::default();
        i.set_working_directory(PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/..")));
        let h = ReplHelper::new(&i);
        let (start, c) = h.candidates("source rules/Co", 15);
        assert_eq!((start, c), (7, vec!["rules/CopyWall.soar".to_string()]));
        let (_, c) = h.candidates("pushd rules/mo", 14);
        assert_eq!(c, vec!["rules/moving/".to_string()]);
        let (_, c) = h.candidates("source no/such/dir/x", 20);
        assert!(c.is_empty());
    }
}
