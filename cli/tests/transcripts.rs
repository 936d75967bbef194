//! Snapshots of what a user sees: REPL sessions typed without a terminal
//! (`tests/data/repl/*.txt`), and the trace and final state of short runs of small agents
//! (`tests/data/traces/*.soar`). One snapshot per input file.

#[path = "../../tests/common/mod.rs"]
mod common;

use common::mask_decimals;
use rusoar::Agent;
use rusoar_cli::repl::transcript;
use std::path::Path;

/// An interpreter working in `path`'s directory, as if started there.
fn interpreter_at(path: &Path) -> Agent {
    let mut interp = Agent::default();
    let dir = path.parent().expect("a file in a directory");
    interp.set_working_directory(dir.canonicalize().expect("the data directory exists"));
    interp
}

/// `stats` prints the host, the date and measured times: those are masked (`#.###` for
/// each time, in the timing table, the single timers and the `msec/` lines).
fn mask_stats_timings(text: &str) -> String {
    let timed = [
        "Kernel:",
        "Input fn:",
        "Outpt fn:",
        "Callbcks:",
        "Totals:",
        " Kernel CPU Time:",
        " Total  CPU Time:",
    ];
    let mut out = String::new();
    for line in text.split_inclusive('\n') {
        if line.starts_with("Soar 9.6 (rusoar) on ") {
            out.push_str("Soar 9.6 (rusoar) on [host] at [date]\n");
        } else if timed.iter().any(|t| line.starts_with(t)) {
            out.push_str(&mask_decimals(line, |_| true));
        } else if line.contains("msec/") {
            // Only the `N.NNN msec/...` values; the ratios are counts.
            out.push_str(&mask_decimals(line, |rest| rest.starts_with(" msec/")));
        } else {
            out.push_str(line);
        }
    }
    out
}

#[test]
fn repl_sessions() {
    insta::glob!("../../tests/data/repl", "*.txt", |path| {
        let script = std::fs::read_to_string(path).unwrap();
        let mut interp = interpreter_at(path);
        insta::assert_snapshot!(mask_stats_timings(&transcript(&mut interp, &script)));
    });
}

/// `# run: N` in an agent file sets how many decisions its trace covers (default 5).
fn decisions_to_run(agent: &str) -> u64 {
    agent
        .lines()
        .find_map(|l| l.strip_prefix("# run:"))
        .and_then(|n| n.trim().parse().ok())
        .unwrap_or(5)
}

#[test]
fn traces_of_short_runs() {
    insta::glob!("../../tests/data/traces", "*.soar", |path| {
        let agent = std::fs::read_to_string(path).unwrap();
        let name = path.file_name().unwrap().to_string_lossy();
        let script = format!(
            "srand 1\nsource {name}\nwatch 4\nrun {}\nprint --depth 3 s1\n",
            decisions_to_run(&agent)
        );
        let mut interp = interpreter_at(path);
        insta::assert_snapshot!(transcript(&mut interp, &script));
    });
}
