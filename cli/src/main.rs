//! The `rusoar` command line: run Soar commands from `--source FILE` and `-c COMMAND`
//! arguments (in the order given), from standard input, or interactively (the REPL of
//! `cli::repl`, after any `--source`, when standard input is a terminal and no `-c` is
//! given). `rusoar test FILE_OR_DIR` runs SoarUnit files; `rusoar slam` the experiment.

use clap::{Arg, ArgAction, Command as ClapCommand};
use rusoar::commands::{Event, Interpreter};
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

fn flush(interp: &mut Interpreter) {
    let events = interp.take_events();
    let mut out = std::io::stdout().lock();
    for e in &events {
        match e {
            Event::Text(t) => {
                let _ = out.write_all(t.as_bytes());
            }
            Event::Diag(_) => {
                let _ = out.flush();
                let r = interp.render(e);
                let _ = std::io::stderr().write_all(r.as_bytes());
            }
        }
    }
    let _ = out.flush();
}

fn report_failure(interp: &mut Interpreter, d: rusoar::source::Diagnostic) {
    flush(interp);
    let text = interp.sources.render(&d);
    let _ = std::io::stderr().write_all(text.as_bytes());
}

/// The per-file summary printed after `--source`.
fn load_report(interp: &Interpreter) -> String {
    let r = &interp.report;
    let cwd = std::env::current_dir().unwrap_or_default();
    let mut s = format!(
        "Loaded {} production{} from {} file{}:\n",
        r.added,
        if r.added == 1 { "" } else { "s" },
        r.per_file.len(),
        if r.per_file.len() == 1 { "" } else { "s" }
    );
    let names: Vec<String> = r
        .per_file
        .keys()
        .map(|p| {
            let p = p.canonicalize().unwrap_or(p.clone());
            p.strip_prefix(&cwd)
                .map(|q| q.display().to_string())
                .unwrap_or(p.display().to_string())
        })
        .collect();
    let width = names.iter().map(|n| n.len()).max().unwrap_or(0);
    for (name, count) in names.iter().zip(r.per_file.values()) {
        s.push_str(&format!("  {name:<width$}  {count:>5}\n"));
    }
    if r.excised > 0 {
        s.push_str(&format!("  ({} redefined rule(s) excised)\n", r.excised));
    }
    if r.ignored > 0 {
        s.push_str(&format!("  ({} duplicate rule(s) ignored)\n", r.ignored));
    }
    s
}

/// Reads commands line by line; waits for more lines while a brace is open.
fn interactive(interp: &mut Interpreter) -> ExitCode {
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
        if let Err(d) = interp.run_text("<stdin>", &text) {
            report_failure(interp, d);
            failed = true;
        }
        flush(interp);
        if interp.exit_requested {
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
    let mut interp = Interpreter::new();
    let code = run(&mut interp);
    // The process ends here: freeing a large agent piece by piece only costs time.
    std::mem::forget(interp);
    code
}

fn run(interp: &mut Interpreter) -> ExitCode {
    let interp = &mut *interp;
    let matches = cli().get_matches();
    let steps = ordered_steps(&matches);
    let terminal = std::io::stdin().is_terminal();
    if terminal && steps.iter().all(|(_, is_source, _)| *is_source) {
        // The REPL, after the `--source` files.
        for (_, _, file) in &steps {
            let r = interp.run_text("--source", &format!("source {{{file}}}"));
            flush(interp);
            match r {
                Ok(()) => print!("{}", load_report(interp)),
                Err(d) => report_failure(interp, d),
            }
        }
        println!(
            "rusoar {} — Soar 9.6 commands; `help` lists them, Tab completes, Ctrl-D quits.",
            env!("CARGO_PKG_VERSION")
        );
        if repl::run(interp) {
            return ExitCode::SUCCESS;
        }
        return interactive(interp);
    }
    if steps.is_empty() {
        let mut text = String::new();
        if std::io::stdin().read_to_string(&mut text).is_err() {
            eprintln!("error: standard input is not valid UTF-8");
            return ExitCode::FAILURE;
        }
        let result = interp.run_text("<stdin>", &text);
        return finish(interp, result);
    }
    for (_, is_source, value) in steps {
        let result = if is_source {
            let cmd = format!("source {{{value}}}");
            let r = interp.run_text("--source", &cmd);
            flush(interp);
            if r.is_ok() {
                print!("{}", load_report(interp));
            }
            r
        } else {
            interp.run_text("-c", &value)
        };
        if let Err(d) = result {
            if is_source {
                eprint!("{}", load_report(interp));
            }
            report_failure(interp, d);
            return ExitCode::FAILURE;
        }
        flush(interp);
        if interp.exit_requested {
            break;
        }
    }
    ExitCode::SUCCESS
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
        host_functions: |interp| soar_slam::functions::register(&mut interp.agent),
    };
    let summary = soarunit::run_paths(&paths, &opts, &mut std::io::stdout());
    if summary.ok() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}

fn finish(interp: &mut Interpreter, result: Result<(), rusoar::source::Diagnostic>) -> ExitCode {
    match result {
        Ok(()) => {
            flush(interp);
            ExitCode::SUCCESS
        }
        Err(d) => {
            report_failure(interp, d);
            ExitCode::FAILURE
        }
    }
}
