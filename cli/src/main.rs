//! The `rusoar` command line: run Soar commands from `--source FILE` and `-c COMMAND`
//! arguments (in the order given), from standard input, or interactively (the REPL of
//! `cli::repl`, after any `--source`, when standard input is a terminal and no `-c` is
//! given). `rusoar test FILE_OR_DIR` runs SoarUnit files; `rusoar slam` the experiment.

use clap::{Arg, ArgAction, Command as ClapCommand};
use rusoar::{Agent, Printed};
use rusoar_cli::{repl, soarunit};
use std::io::{BufRead, IsTerminal, Read, Write};
use std::process::ExitCode;

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn cli() -> ClapCommand {
    ClapCommand::new("rusoar")
        .about("The Soar cognitive architecture in Rust")
        .after_help(
            "With no -c, on a terminal: an interactive session (after any --source).\n\
             Also: `rusoar test FILE_OR_DIR` runs SoarUnit tests (.soarunit files);\n\
             `rusoar slam` runs the Soar-SLAM experiment (`rusoar slam --help`).",
        )
        .version(env!("CARGO_PKG_VERSION"))
        .arg(
            Arg::new("source")
                .long("source")
                .short('s')
                .value_name("FILE")
                .action(ArgAction::Append)
                .help("Source a .soar file and report the productions loaded per file"),
        )
        .arg(
            Arg::new("command")
                .short('c')
                .long("command")
                .value_name("COMMAND")
                .action(ArgAction::Append)
                .help("Run a Soar command (repeatable; runs in order with --source)"),
        )
        .arg(
            Arg::new("strict")
                .long("strict")
                .action(ArgAction::SetTrue)
                .help("Stop at the first command that fails (by default each error is printed and the rest run)"),
        )
}

/// `--source` and `-c` values in the order they were given.
fn ordered_steps(m: &clap::ArgMatches) -> Vec<(usize, bool, String)> {
    let mut steps = Vec::new();
    for (id, is_source) in [("source", true), ("command", false)] {
        if let (Some(vals), Some(idx)) = (m.get_many::<String>(id), m.indices_of(id)) {
            for (v, i) in vals.zip(idx) {
                steps.push((i, is_source, v.clone()));
            }
        }
    }
    steps.sort_by_key(|s| s.0);
    steps
}

/// Prints what the agent printed: text to standard output, diagnostics to standard error.
fn flush(agent: &mut Agent) {
    let printed = agent.take_printed();
    let mut out = std::io::stdout().lock();
    for p in &printed {
        match p {
            Printed::Text(t) => {
                let _ = out.write_all(t.as_bytes());
            }
            Printed::Diagnostic(e) => {
                let _ = out.flush();
                let _ = std::io::stderr().write_all(e.render().as_bytes());
            }
        }
    }
    let _ = out.flush();
}

fn report_failure(agent: &mut Agent, e: rusoar::Error) {
    flush(agent);
    let _ = std::io::stderr().write_all(e.render().as_bytes());
}

/// The per-file summary printed after `--source`.
fn load_report(agent: &Agent) -> String {
    let r = agent.load_report();
    let cwd = std::env::current_dir().unwrap_or_default();
    let files: Vec<(&std::path::Path, usize)> = r.files().collect();
    let mut s = format!(
        "Loaded {} production{} from {} file{}:\n",
        r.added(),
        if r.added() == 1 { "" } else { "s" },
        files.len(),
        if files.len() == 1 { "" } else { "s" }
    );
    let names: Vec<String> = files
        .iter()
        .map(|(p, _)| {
            let p = p.canonicalize().unwrap_or(p.to_path_buf());
            p.strip_prefix(&cwd)
                .map(|q| q.display().to_string())
                .unwrap_or(p.display().to_string())
        })
        .collect();
    let width = names.iter().map(|n| n.len()).max().unwrap_or(0);
    for (name, (_, count)) in names.iter().zip(&files) {
        s.push_str(&format!("  {name:<width$}  {count:>5}\n"));
    }
    if r.excised() > 0 {
        s.push_str(&format!("  ({} redefined rule(s) excised)\n", r.excised()));
    }
    if r.ignored() > 0 {
        s.push_str(&format!("  ({} duplicate rule(s) ignored)\n", r.ignored()));
    }
    s
}

/// Reads commands line by line; waits for more lines while a brace is open.
fn interactive(agent: &mut Agent) -> ExitCode {
    let stdin = std::io::stdin();
    let mut pending = String::new();
    let mut failed = false;
    loop {
        if std::io::stdin().is_terminal() {
            print!(
                "{}",
                if pending.is_empty() {
                    "soar> "
                } else {
                    "....> "
                }
            );
            let _ = std::io::stdout().flush();
        }
        let mut line = String::new();
        match stdin.lock().read_line(&mut line) {
            Ok(0) | Err(_) => break,
            Ok(_) => {}
        }
        pending.push_str(&line);
        if brace_depth(&pending) > 0 {
            continue;
        }
        let text = std::mem::take(&mut pending);
        if let Err(e) = agent.source_text("<stdin>", &text) {
            report_failure(agent, e);
            failed = true;
        }
        flush(agent);
        if agent.exit_requested() {
            break;
        }
    }
    if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}

/// Open braces not yet closed (outside `|...|` and comments), for multi-line input.
fn brace_depth(text: &str) -> i64 {
    let mut depth = 0i64;
    let mut in_pipe = false;
    let mut in_comment = false;
    for c in text.chars() {
        match c {
            '\n' => in_comment = false,
            _ if in_comment => {}
            '#' if !in_pipe => in_comment = true,
            '|' if depth > 0 => in_pipe = !in_pipe,
            '{' if !in_pipe => depth += 1,
            '}' if !in_pipe => depth -= 1,
            _ => {}
        }
    }
    depth
}

fn main() -> ExitCode {
    // `rusoar slam ...`: the Soar-SLAM experiment; its options live in experiment.rs.
    let args: Vec<String> = std::env::args().collect();
    if args.get(1).map(String::as_str) == Some("slam") {
        return soar_slam::experiment::main(&args[2..]);
    }
    if args.get(1).map(String::as_str) == Some("test") {
        return soarunit_main(&args[2..]);
    }
    let mut agent = Agent::new("soar");
    let code = run(&mut agent);
    if let Err(e) = agent.commit_memories() {
        eprintln!("{e}");
    }
    // The process ends here: freeing a large agent piece by piece only costs time.
    std::mem::forget(agent);
    code
}

fn run(agent: &mut Agent) -> ExitCode {
    let matches = cli().get_matches();
    let steps = ordered_steps(&matches);
    let terminal = std::io::stdin().is_terminal();
    if terminal && steps.iter().all(|(_, is_source, _)| *is_source) {
        // The REPL, after the `--source` files.
        for (_, _, file) in &steps {
            let r = agent.source_text("--source", &format!("source {{{file}}}"));
            flush(agent);
            match r {
                Ok(()) => print!("{}", load_report(agent)),
                Err(e) => report_failure(agent, e),
            }
        }
        println!(
            "rusoar {} — Soar 9.6 commands; `help` lists them, Tab completes, Ctrl-D quits.",
            env!("CARGO_PKG_VERSION")
        );
        if repl::run(agent) {
            return ExitCode::SUCCESS;
        }
        return interactive(agent);
    }
    let strict = matches.get_flag("strict");
    if steps.is_empty() {
        let mut text = String::new();
        if std::io::stdin().read_to_string(&mut text).is_err() {
            eprintln!("error: standard input is not valid UTF-8");
            return ExitCode::FAILURE;
        }
        if strict {
            let result = agent.source_text("<stdin>", &text);
            return finish(agent, result);
        }
        let failed = agent.source_text_keep_going("<stdin>", &text);
        flush(agent);
        return exit_code(failed);
    }
    let mut failed = 0;
    for (_, is_source, value) in steps {
        if !strict && !is_source {
            failed += agent.source_text_keep_going("-c", &value);
            flush(agent);
            if agent.exit_requested() {
                break;
            }
            continue;
        }
        let result = if is_source {
            let cmd = format!("source {{{value}}}");
            let r = agent.source_text("--source", &cmd);
            flush(agent);
            if r.is_ok() {
                print!("{}", load_report(agent));
            }
            r
        } else {
            agent.source_text("-c", &value)
        };
        if let Err(e) = result {
            if is_source {
                eprint!("{}", load_report(agent));
            }
            report_failure(agent, e);
            if strict {
                return ExitCode::FAILURE;
            }
            failed += 1;
            continue;
        }
        flush(agent);
        if agent.exit_requested() {
            break;
        }
    }
    exit_code(failed)
}

/// Success when no command failed.
fn exit_code(failed: usize) -> ExitCode {
    if failed == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}

/// `rusoar test [--max-decisions N] [--verbose] FILE_OR_DIR...`: SoarUnit.
fn soarunit_main(args: &[String]) -> ExitCode {
    let cmd = ClapCommand::new("rusoar test")
        .about("Run SoarUnit tests (.soarunit files)")
        .arg(
            Arg::new("paths")
                .value_name("FILE_OR_DIR")
                .num_args(1..)
                .required(true)
                .help(".soarunit files, or directories searched for them"),
        )
        .arg(
            Arg::new("max-decisions")
                .long("max-decisions")
                .short('d')
                .value_name("N")
                .value_parser(clap::value_parser!(u64))
                .default_value("10000")
                .help("A test that has not passed or failed after N decisions fails"),
        )
        .arg(
            Arg::new("verbose")
                .long("verbose")
                .short('v')
                .action(ArgAction::SetTrue)
                .help("Print every test's transcript, not only failing ones'"),
        );
    let m = match cmd.try_get_matches_from(
        std::iter::once("rusoar test".to_string()).chain(args.iter().cloned()),
    ) {
        Ok(m) => m,
        Err(e) => {
            let _ = e.print();
            return if e.use_stderr() {
                ExitCode::from(2)
            } else {
                ExitCode::SUCCESS
            };
        }
    };
    let paths: Vec<std::path::PathBuf> = m
        .get_many::<String>("paths")
        .into_iter()
        .flatten()
        .map(std::path::PathBuf::from)
        .collect();
    let opts = soarunit::Options {
        decision_limit: m.get_one::<u64>("max-decisions").copied().unwrap_or(10_000),
        verbose: m.get_flag("verbose"),
        host_functions: soar_slam::functions::register,
    };
    let summary = soarunit::run_paths(&paths, &opts, &mut std::io::stdout());
    if summary.ok() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}

fn finish(agent: &mut Agent, result: Result<(), rusoar::Error>) -> ExitCode {
    match result {
        Ok(()) => {
            flush(agent);
            ExitCode::SUCCESS
        }
        Err(e) => {
            report_failure(agent, e);
            ExitCode::FAILURE
        }
    }
}
