//! SoarUnit: `rusoar test FILE_OR_DIR` runs `.soarunit` files, the unit-test format of
//! SoarUnit (JSoar's test runner, also used with CSoar). A file holds an optional
//! `setup { ... }` block and `test NAME { ... }` blocks. Each test gets a fresh agent; the
//! setup block is sourced, then the test's block, then the agent runs until a rule calls
//! `(pass)` or `(fail)`, or the decision limit is reached (a failure).
//!
//! Blocks run from the test file's directory, so `source ../rules/x.soar` works as it does
//! in a sourced file. The RHS functions of the Soar-SLAM rules (`getlength`,
//! `checkwallrelation`, `getwalldistance`) are registered too, so the thesis rules can be
//! tested as they run in the experiment.

use rusoar::syntax::Diagnostic;
use rusoar::syntax::{Tokenizer, WordKind};
use rusoar::{Agent, Printed};
use std::cell::RefCell;
use std::path::{Path, PathBuf};
use std::rc::Rc;

/// A block of commands and where it starts in its file.
#[derive(Debug, Clone)]
pub struct Block {
    /// The commands, at the same byte offsets as in the file (earlier text blanked), so
    /// diagnostics point at the right line and column of the `.soarunit` file.
    pub text: String,
}

#[derive(Debug, Clone)]
pub struct TestCase {
    pub name: String,
    /// 1-based line of the `test` command.
    pub line: usize,
    pub body: Block,
}

/// One parsed `.soarunit` file.
#[derive(Debug, Clone)]
pub struct TestFile {
    pub path: PathBuf,
    pub setup: Option<Block>,
    pub tests: Vec<TestCase>,
}

/// How a test ended.
#[derive(Debug, Clone, PartialEq)]
pub enum Outcome {
    Passed,
    Failed(String),
}

#[derive(Debug, Clone)]
pub struct Options {
    /// A test that has not called `(pass)` or `(fail)` after this many decisions fails.
    pub decision_limit: u64,
    /// Print each test's transcript, not only a failing one's.
    pub verbose: bool,
    /// Registers the host's RHS functions on each test's fresh agent, as any embedding
    /// program does before it sources rules (the `rusoar` binary registers Soar-SLAM's).
    pub host_functions: fn(&mut Agent),
}

impl Default for Options {
    fn default() -> Self {
        Options {
            decision_limit: 10_000,
            verbose: false,
            host_functions: |_| {},
        }
    }
}

/// A test's result: outcome, decisions run, and everything the agent printed.
#[derive(Debug, Clone)]
pub struct TestResult {
    pub outcome: Outcome,
    pub decisions: u64,
    pub transcript: String,
}

/// Totals over a whole `rusoar test` run.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct Summary {
    pub passed: usize,
    pub failed: usize,
    /// Files that could not be read or parsed (counted as failures for the exit code).
    pub broken_files: usize,
}

impl Summary {
    pub fn ok(&self) -> bool {
        self.failed == 0 && self.broken_files == 0
    }
}

/// Keeps the file's byte offsets: every character before `offset` becomes a blank
/// (newlines stay), then the block's text follows.
fn block_at(file_text: &str, offset: usize, body: &str) -> Block {
    let mut text = String::with_capacity(offset + body.len());
    for c in file_text[..offset].chars() {
        if c == '\n' {
            text.push('\n');
        } else {
            // One blank per byte, so later offsets stay those of the file.
            text.extend(std::iter::repeat_n(' ', c.len_utf8()));
        }
    }
    text.push_str(body);
    Block { text }
}

/// Parses a `.soarunit` text. Errors are diagnostics located in file 0: the caller
/// registers `text` as the first file of a fresh source map to render them.
pub fn parse(path: &Path, text: &str) -> Result<TestFile, Diagnostic> {
    let mut file = TestFile {
        path: path.to_path_buf(),
        setup: None,
        tests: Vec::new(),
    };
    for cmd in Tokenizer::new(text, 0) {
        let cmd = cmd?;
        let words = &cmd.words;
        let line = text[..cmd.span.start].matches('\n').count() + 1;
        match words[0].text.as_str() {
            "setup" => {
                if words.len() != 2 || words[1].kind != WordKind::Braced {
                    return Err(Diagnostic::error("setup expects one block: setup { ... }")
                        .at(cmd.span)
                        .with_label("here"));
                }
                if file.setup.is_some() {
                    return Err(Diagnostic::error("a second setup block")
                        .at(words[0].span)
                        .with_label("only one setup block per file"));
                }
                file.setup = Some(block_at(text, words[1].content_offset(), &words[1].text));
            }
            "test" => {
                if words.len() != 3 || words[2].kind != WordKind::Braced {
                    return Err(Diagnostic::error(
                        "test expects a name and a block: test NAME { ... }",
                    )
                    .at(cmd.span)
                    .with_label("here"));
                }
                let name = words[1].text.clone();
                if file.tests.iter().any(|t| t.name == name) {
                    return Err(Diagnostic::error(format!("a second test named {name}"))
                        .at(words[1].span)
                        .with_label("test names must be unique in a file"));
                }
                file.tests.push(TestCase {
                    name,
                    line,
                    body: block_at(text, words[2].content_offset(), &words[2].text),
                });
            }
            other => {
                return Err(
                    Diagnostic::error(format!("unexpected `{other}` in a .soarunit file"))
                        .at(words[0].span)
                        .with_label("expected `setup { ... }` or `test NAME { ... }`"),
                )
            }
        }
    }
    Ok(file)
}

/// Everything printed so far, rendered, appended to `out`; without the parser's "Adding
/// exec" warnings for `(pass)` and `(fail)`, which every test would show.
fn drain(agent: &mut Agent, out: &mut String) {
    for p in agent.take_printed() {
        if let Printed::Diagnostic(e) = &p {
            if matches!(
                e.message().as_str(),
                "Adding exec to RHS function: pass" | "Adding exec to RHS function: fail"
            ) {
                continue;
            }
            if !out.is_empty() && !out.ends_with('\n') {
                out.push('\n');
            }
        }
        out.push_str(&p.to_string());
    }
}

/// Runs one test on a fresh agent.
pub fn run_test(file: &TestFile, test: &TestCase, opts: &Options) -> TestResult {
    let mut agent = Agent::new("soar");
    if let Some(dir) = file.path.parent() {
        let dir = if dir.as_os_str().is_empty() {
            Path::new(".")
        } else {
            dir
        };
        agent.set_working_directory(dir.canonicalize().unwrap_or_else(|_| dir.to_path_buf()));
    }
    (opts.host_functions)(&mut agent);
    let outcome: Rc<RefCell<Option<Outcome>>> = Rc::new(RefCell::new(None));
    {
        let o = Rc::clone(&outcome);
        // (9.6's built-in `(succeeded)` and `(failed)` only halt, so a test cannot tell
        // them apart: a halt without `(pass)` or `(fail)` fails the test.)
        agent.register_sml_rhs_function("pass", move |_, _| {
            o.borrow_mut().get_or_insert(Outcome::Passed);
            String::new()
        });
        let o = Rc::clone(&outcome);
        agent.register_sml_rhs_function("fail", move |_, args| {
            let why = if args.is_empty() {
                "(fail) was called".to_string()
            } else {
                format!("(fail) was called: {args}")
            };
            *o.borrow_mut() = Some(Outcome::Failed(why));
            String::new()
        });
        // Stop at the end of the decision in which a rule called (pass) or (fail).
        let o = Rc::clone(&outcome);
        agent.on_output_phase(move |io| {
            if o.borrow().is_some() {
                io.stop();
            }
        });
    }
    let name = file.path.display().to_string();
    let mut transcript = String::new();
    let blocks = file.setup.iter().chain(std::iter::once(&test.body));
    for block in blocks {
        let result = agent.source_text(&name, &block.text);
        drain(&mut agent, &mut transcript);
        if let Err(e) = result {
            transcript.push_str(&e.render());
            return TestResult {
                outcome: Outcome::Failed(format!("error while loading: {}", e.message())),
                decisions: agent.decisions(),
                transcript,
            };
        }
    }
    // A block may already have run the agent to its end.
    if outcome.borrow().is_none() {
        let result = agent.source_text("soarunit", &format!("run {}", opts.decision_limit));
        drain(&mut agent, &mut transcript);
        if let Err(e) = result {
            transcript.push_str(&e.render());
        }
    }
    let decisions = agent.decisions();
    let outcome = match outcome.borrow().clone() {
        Some(o) => o,
        None if agent.is_halted() => {
            Outcome::Failed("the agent halted without calling (pass) or (fail)".into())
        }
        None => Outcome::Failed(format!(
            "reached the decision limit ({}) without (pass) or (fail)",
            opts.decision_limit
        )),
    };
    TestResult {
        outcome,
        decisions,
        transcript,
    }
}

/// The `.soarunit` files under `path` (itself, if it is a file), sorted by path.
pub fn collect_files(path: &Path) -> std::io::Result<Vec<PathBuf>> {
    if path.is_file() {
        return Ok(vec![path.to_path_buf()]);
    }
    let mut out = Vec::new();
    let mut dirs = vec![path.to_path_buf()];
    while let Some(d) = dirs.pop() {
        for entry in std::fs::read_dir(&d)? {
            let p = entry?.path();
            if p.is_dir() {
                dirs.push(p);
            } else if p.extension().is_some_and(|e| e == "soarunit") {
                out.push(p);
            }
        }
    }
    out.sort();
    Ok(out)
}

/// Runs every test of every `.soarunit` file under `paths`, writing a line per test and a
/// summary to `out` (a failing test's transcript follows its line).
pub fn run_paths(paths: &[PathBuf], opts: &Options, out: &mut dyn std::io::Write) -> Summary {
    let mut summary = Summary::default();
    for path in paths {
        let files = match collect_files(path) {
            Ok(f) if f.is_empty() => {
                let _ = writeln!(out, "error: no .soarunit files in {}", path.display());
                summary.broken_files += 1;
                continue;
            }
            Ok(f) => f,
            Err(e) => {
                let _ = writeln!(out, "error: cannot read {}: {e}", path.display());
                summary.broken_files += 1;
                continue;
            }
        };
        for f in files {
            run_file(&f, opts, out, &mut summary);
        }
    }
    let _ = writeln!(
        out,
        "\n{}: {} passed, {} failed",
        if summary.ok() { "ok" } else { "FAILED" },
        summary.passed,
        summary.failed
    );
    summary
}

fn run_file(path: &Path, opts: &Options, out: &mut dyn std::io::Write, summary: &mut Summary) {
    let text = match std::fs::read_to_string(path) {
        Ok(t) => t,
        Err(e) => {
            let _ = writeln!(out, "error: cannot read {}: {e}", path.display());
            summary.broken_files += 1;
            return;
        }
    };
    let file = match parse(path, &text) {
        Ok(f) => f,
        Err(d) => {
            let mut map = rusoar::syntax::SourceMap::new();
            map.add(path.display().to_string(), text.as_str());
            let _ = write!(out, "{}", map.render(&d));
            summary.broken_files += 1;
            return;
        }
    };
    let _ = writeln!(out, "{} ({} tests)", path.display(), file.tests.len());
    for test in &file.tests {
        let r = run_test(&file, test, opts);
        match &r.outcome {
            Outcome::Passed => {
                summary.passed += 1;
                let _ = writeln!(
                    out,
                    "  PASS  {} ({} decision{})",
                    test.name,
                    r.decisions,
                    if r.decisions == 1 { "" } else { "s" }
                );
            }
            Outcome::Failed(why) => {
                summary.failed += 1;
                let _ = writeln!(out, "  FAIL  {} (line {}): {why}", test.name, test.line);
            }
        }
        let failed = r.outcome != Outcome::Passed;
        if opts.verbose || failed {
            let shown = tail_lines(&r.transcript, if opts.verbose { usize::MAX } else { 30 });
            for line in shown.lines() {
                let _ = writeln!(out, "        | {line}");
            }
        }
    }
}

/// The last `n` lines of `text` (with a marker when lines were left out).
fn tail_lines(text: &str, n: usize) -> String {
    let lines: Vec<&str> = text.trim_matches('\n').lines().collect();
    if lines.len() <= n {
        return lines.join("\n");
    }
    format!(
        "... ({} earlier lines)\n{}",
        lines.len() - n,
        lines[lines.len() - n..].join("\n")
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parsed(text: &str) -> TestFile {
        parse(Path::new("t.soarunit"), text).unwrap()
    }

    #[test]
    fn parses_setup_and_tests_keeping_offsets() {
        let text = "# c\nsetup {\n  sp {a (state <s> ^superstate nil) --> (<s> ^x 1)}\n}\ntest one {\n  echo hi\n}\ntest |two words| { echo 2 }\n";
        let f = parsed(text);
        let setup = f.setup.unwrap();
        assert_eq!(setup.text.find("sp {a"), text.find("sp {a"));
        assert_eq!(setup.text.len(), text.find("\n}\ntest").unwrap() + 1);
        assert_eq!(f.tests.len(), 2);
        assert_eq!(f.tests[0].name, "one");
        assert_eq!(f.tests[0].line, 5);
        assert_eq!(f.tests[1].name, "|two words|");
        let off = f.tests[0].body.text.find("echo").unwrap();
        assert_eq!(off, text.find("echo hi").unwrap());
    }

    #[test]
    fn rejects_other_commands_and_bad_shapes() {
        for bad in [
            "run 1",
            "test x",
            "setup a b",
            "setup {} \nsetup {}",
            "test a {}\ntest a {}",
        ] {
            assert!(parse(Path::new("t"), bad).is_err(), "{bad}");
        }
    }

    fn run_one(text: &str, opts: &Options) -> TestResult {
        let f = parsed(text);
        run_test(&f, &f.tests[0], opts)
    }

    #[test]
    fn pass_fail_limit_and_halt() {
        let opts = Options {
            decision_limit: 20,
            ..Options::default()
        };
        let pass = run_one(
            "test p { sp {p (state <s> ^superstate nil) --> (pass)} }",
            &opts,
        );
        assert_eq!(pass.outcome, Outcome::Passed);
        assert_eq!(pass.decisions, 1);
        let fail = run_one(
            "test f { sp {f (state <s> ^superstate nil) --> (fail |bad value|)} }",
            &opts,
        );
        assert_eq!(
            fail.outcome,
            Outcome::Failed("(fail) was called: bad value".into())
        );
        let limit = run_one(
            "setup { soar max-goal-depth 1000 }\ntest l { echo nothing }",
            &opts,
        );
        assert_eq!(
            limit.outcome,
            Outcome::Failed("reached the decision limit (20) without (pass) or (fail)".into())
        );
        assert_eq!(limit.decisions, 20);
        let quoted = run_one(
            "test \"quoted name\" { sp {p (state <s> ^superstate nil) --> (pass)} }",
            &opts,
        );
        assert_eq!(quoted.outcome, Outcome::Passed);
        let halt = run_one(
            "test h { sp {h (state <s> ^superstate nil) --> (halt)} }",
            &opts,
        );
        assert_eq!(
            halt.outcome,
            Outcome::Failed("the agent halted without calling (pass) or (fail)".into())
        );
        let broken = run_one("test b { sp {b (state <s>) --> } }", &opts);
        assert!(
            matches!(&broken.outcome, Outcome::Failed(w) if w.starts_with("error while loading")),
            "{:?}",
            broken.outcome
        );
        assert!(
            broken.transcript.contains("t.soarunit:1:"),
            "{}",
            broken.transcript
        );
    }
}
