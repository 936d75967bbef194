//! Trace levels 2 to 5 against the official Soar 9.6 kernel.
//!
//! `scripts/goldens.py` wrote `tests/golden/traces/NAME.LEVEL.txt`: everything the official
//! kernel printed for `srand 1`, `source tests/agents/NAME.soar`, `trace LEVEL`, `run 50`
//! (the trace, then run's result); `tests/golden/traces/long/NAME.LEVEL.txt` for the
//! long-run agents `tests/agents/long/NAME.soar`. Here rusoar runs the same commands and its text must be
//! the same, line for line, except for the pairs listed in [`KNOWN_DIFFERENCES`]; the test
//! also fails when a listed pair has started to match, so the list only shrinks.
//!
//! `python3 scripts/trace_compare.py` compares the same way on every agent and level.

use rusoar::Agent;
use std::path::PathBuf;

/// (agent, level) pairs whose trace still differs from 9.6's, with the reason (none now:
/// a pair that starts to differ is a regression, and one that must be listed says why).
const KNOWN_DIFFERENCES: &[(&str, u8, &str)] = &[];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// rusoar's text for one golden: what `run 50` printed, the result included.
fn ours(agent: &str, level: u8) -> String {
    let mut interp = Agent::default();
    interp.set_working_directory(root());
    let path = root().join("tests/agents").join(format!("{agent}.soar"));
    let setup = format!("srand 1\nsource {}\ntrace {level}", path.display());
    if let Err(d) = interp.source_text("<trace-goldens>", &setup) {
        return format!("[setup failed: {}]\n", d.message());
    }
    interp.take_output();
    let failed = interp.source_text("<trace-goldens>", "run 50").err();
    let mut text = interp.take_output();
    if let Some(d) = failed {
        text.push_str(&format!("[run failed: {}]\n", d.message()));
    }
    if !text.ends_with('\n') {
        text.push('\n');
    }
    text
}

/// The first differing line, with a little context.
fn first_difference(expected: &str, actual: &str) -> String {
    let a: Vec<&str> = expected.split('\n').collect();
    let b: Vec<&str> = actual.split('\n').collect();
    let i = a
        .iter()
        .zip(&b)
        .position(|(x, y)| x != y)
        .unwrap_or(a.len().min(b.len()));
    let from = i.saturating_sub(3);
    let show = |v: &[&str]| {
        v[from.min(v.len())..(i + 3).min(v.len())]
            .iter()
            .map(|l| format!("    |{l}"))
            .collect::<Vec<_>>()
            .join("\n")
    };
    format!(
        "line {}:\n  official:\n{}\n  rusoar:\n{}",
        i + 1,
        show(&a),
        show(&b)
    )
}

#[test]
fn trace_levels_match_the_official_kernel() {
    let dir = root().join("tests/golden/traces");
    // Long-run agents (`tests/agents/long/NAME.soar`) have theirs in `long/`.
    let mut files: Vec<(String, PathBuf)> = Vec::new();
    for (prefix, sub) in [("", dir.clone()), ("long/", dir.join("long"))] {
        let Ok(entries) = std::fs::read_dir(&sub) else {
            continue;
        };
        for e in entries {
            let p = e.unwrap().path();
            if p.extension().is_some_and(|x| x == "txt") {
                files.push((prefix.to_string(), p));
            }
        }
    }
    files.sort();
    assert!(!files.is_empty(), "no trace goldens in {}", dir.display());
    let mut problems = Vec::new();
    let mut same = 0;
    for (prefix, file) in &files {
        let stem = file.file_stem().unwrap().to_string_lossy().to_string();
        let (name, level) = stem.rsplit_once('.').expect("NAME.LEVEL.txt");
        let level: u8 = level.parse().expect("a trace level");
        let golden = std::fs::read_to_string(file).unwrap();
        let agent = format!("{prefix}{name}");
        let agent = agent.as_str();
        let text = ours(agent, level);
        let known = KNOWN_DIFFERENCES
            .iter()
            .any(|(a, l, _)| *a == agent && *l == level);
        match (text == golden, known) {
            (true, false) => same += 1,
            (false, true) => {}
            (true, true) => problems.push(format!(
                "{agent} at trace {level} now matches the official kernel: remove it from \
                 KNOWN_DIFFERENCES"
            )),
            (false, false) => problems.push(format!(
                "{agent} at trace {level} differs from the official kernel at {}",
                first_difference(&golden, &text)
            )),
        }
    }
    assert!(
        problems.is_empty(),
        "{} of {} trace goldens match; problems:\n{}",
        same,
        files.len(),
        problems.join("\n\n")
    );
}
