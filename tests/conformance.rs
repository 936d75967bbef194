//! Conformance with the official Soar 9.6 kernel.
//!
//! Every agent in `tests/agents/` runs here exactly as `scripts/goldens.py` ran it in the
//! official kernel (`srand 1`, `watch 1`, `source AGENT`, `run 1000`, then `stats`), and its
//! decision lines and counts must equal `tests/golden/NAME.txt` line for line. The
//! conventions (which lines are decision lines, which counts, where they come from) are
//! documented at the top of `scripts/goldens.py`; this file follows them.
//!
//! Long runs (`tests/agents/long/`) are compared by their end state only: `stats` counts
//! and what `print` shows after N decisions (`tests/golden/long/NAME.txt`).
//!
//! With `CONFORMANCE_OUT=DIR`, rusoar's own text for each agent (same format as a golden)
//! is written to `DIR/NAME.txt` (`DIR/long/NAME.txt` for long runs), for
//! `diff -r tests/golden DIR`.
//!
//! Agents on which rusoar does not match yet are listed in [`KNOWN_DIFFERENCES`] with the
//! reason. The test fails if any other agent differs, and also if a listed agent has started
//! to match (so the list has to shrink as the kernel improves).

use rusoar::Agent;
use std::path::{Path, PathBuf};

/// Agents whose trace or counts still differ from the official kernel, with the reason.
/// "Match order" is the order in which one rule's several new matches fire: it sets
/// operator ids and the candidate order, hence seeded random choices.
const KNOWN_DIFFERENCES: &[(&str, &str)] = &[];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A decision line of the trace: whitespace, the cycle number, `": "` (`^\s+\d+: `).
fn is_decision_line(line: &str) -> bool {
    let rest = line.trim_start();
    if rest.len() == line.len() {
        return false;
    }
    let digits = rest.bytes().take_while(u8::is_ascii_digit).count();
    digits > 0 && rest[digits..].starts_with(": ")
}

/// The counts of a `run` result text: `--> N decision cycle(s) executed.` and
/// `M rule(s) fired.` or `No rules fired.`.
fn run_counts(text: &str) -> Option<(String, String)> {
    let at = text.rfind("--> ")?;
    let rest = &text[at + 4..];
    let decisions: String = rest.chars().take_while(char::is_ascii_digit).collect();
    let rest = &rest[decisions.len()..];
    let rest = rest
        .strip_prefix(" decision cycles executed. ")
        .or_else(|| rest.strip_prefix(" decision cycle executed. "))?;
    let firings = if rest.starts_with("No rules fired.") {
        "0".to_string()
    } else {
        let n: String = rest.chars().take_while(char::is_ascii_digit).collect();
        let after = &rest[n.len()..];
        if n.is_empty()
            || !(after.starts_with(" rules fired.") || after.starts_with(" rule fired."))
        {
            return None;
        }
        n
    };
    (!decisions.is_empty()).then_some((decisions, firings))
}

/// `N <what>` at the start of a line of `stats` (`N decisions`, `N elaboration cycles`, ...),
/// or `WM size: N current`.
fn stats_count(stats: &str, what: &str) -> Option<String> {
    stats.lines().find_map(|line| {
        if what == "wm size" {
            let n = line.strip_prefix("WM size: ")?;
            let digits: String = n.chars().take_while(char::is_ascii_digit).collect();
            return (!digits.is_empty() && n[digits.len()..].starts_with(" current"))
                .then_some(digits);
        }
        let digits: String = line.chars().take_while(char::is_ascii_digit).collect();
        let rest = line[digits.len()..].strip_prefix(' ')?.strip_prefix(what)?;
        let boundary = rest.chars().next().is_none_or(|c| !c.is_alphanumeric());
        (!digits.is_empty() && boundary).then_some(digits)
    })
}

/// The golden text for one run: decision lines, `--- counts ---`, `key: value` lines.
fn golden_text(output: &str, stats: &str) -> String {
    let mut lines: Vec<String> = output
        .split('\n')
        .filter(|l| is_decision_line(l))
        .map(str::to_string)
        .collect();
    let (run_decisions, run_firings) =
        run_counts(output).unwrap_or_else(|| ("?".into(), "?".into()));
    let halted = if output.split('\n').any(|l| l == "System halted.") {
        "yes"
    } else {
        "no"
    };
    lines.push("--- counts ---".into());
    lines.push(format!("run decisions: {run_decisions}"));
    lines.push(format!("run firings: {run_firings}"));
    lines.push(format!("halted: {halted}"));
    for (key, what) in [
        ("decisions", "decisions"),
        ("elaboration cycles", "elaboration cycles"),
        ("production firings", "production firings"),
        ("wm size", "wm size"),
    ] {
        let n = stats_count(stats, what).unwrap_or_else(|| "?".into());
        lines.push(format!("{key}: {n}"));
    }
    lines.join("\n") + "\n"
}

/// Learning agents whose learned rules (`tests/golden/NAME.rules.txt`) still differ from
/// the official kernel's, with the reason.
const KNOWN_RULE_DIFFERENCES: &[(&str, &str)] = &[];

/// The number in run's `N new rule(s) learned.`, 0 without it.
fn learned_count(run: &str) -> String {
    run.find(" new rule")
        .map(|at| {
            let digits: String = run[..at]
                .chars()
                .rev()
                .take_while(char::is_ascii_digit)
                .collect();
            digits.chars().rev().collect()
        })
        .unwrap_or_else(|| "0".into())
}

/// Episodes of each RL agent (`rl-*`), as `RL_EPISODES` in scripts/goldens.py.
const RL_EPISODES: u32 = 5;

fn command(interp: &mut Agent, cmd: &str) -> String {
    match interp.source_text("<conformance>", cmd) {
        Ok(()) => interp.take_output(),
        Err(d) => format!("[{cmd} failed: {}]", d.message()),
    }
}

/// Runs one agent in rusoar as the goldens script runs it in the official kernel: the
/// golden text, and for a learning agent (`learn-*`) its learned rules.
fn run_agent(path: &Path) -> (String, Option<String>) {
    let mut interp = Agent::default();
    interp.set_working_directory(root());
    let script = format!("srand 1\nwatch 1\nsource {}\nrun 1000", path.display());
    let failed = interp.source_text("<conformance>", &script).err();
    let mut output = interp.take_output();
    if let Some(d) = failed {
        output.push_str(&format!("\n[command failed: {}]\n", d.message()));
    }
    let stats = command(&mut interp, "stats");
    let mut text = golden_text(&output, &stats);
    let name = path
        .file_name()
        .and_then(|f| f.to_str())
        .unwrap_or_default();
    if name.starts_with("rl-") {
        text.push_str("--- print --rl ---\n");
        text.push_str(&ends_with_newline(command(&mut interp, "print --rl")));
        for episode in 2..=RL_EPISODES {
            command(&mut interp, "init-soar");
            let run = command(&mut interp, "run 1000");
            let stats = command(&mut interp, "stats");
            text.push_str(&format!("--- episode {episode} ---\n"));
            text.push_str(&golden_text(&run, &stats));
            text.push_str("--- print --rl ---\n");
            text.push_str(&ends_with_newline(command(&mut interp, "print --rl")));
        }
        return (text, None);
    }
    let learning = path
        .file_name()
        .and_then(|f| f.to_str())
        .is_some_and(|f| f.starts_with("learn-"));
    if !learning {
        return (text, None);
    }
    text.push_str(&format!("chunks learned: {}\n", learned_count(&output)));
    let listing = command(&mut interp, "print --chunks");
    let mut rules = listing.clone();
    for name in listing.lines().map(str::trim).filter(|n| !n.is_empty()) {
        rules.push_str(&command(&mut interp, &format!("print {name}")));
    }
    command(&mut interp, "init-soar");
    let run2 = command(&mut interp, "run 1000");
    let stats2 = command(&mut interp, "stats");
    text.push_str("--- after init-soar ---\n");
    text.push_str(&golden_text(&run2, &stats2));
    text.push_str(&format!("chunks learned: {}\n", learned_count(&run2)));
    (text, Some(rules))
}

/// A line diff (longest common subsequence) of `expected` (golden) against `actual`,
/// showing the changed lines with two lines of context, at most `limit` lines.
fn diff(expected: &str, actual: &str, limit: usize) -> String {
    let a: Vec<&str> = expected.lines().collect();
    let b: Vec<&str> = actual.lines().collect();
    let (n, m) = (a.len(), b.len());
    // lcs[i][j]: length of the LCS of a[i..] and b[j..].
    let mut lcs = vec![vec![0u32; m + 1]; n + 1];
    for i in (0..n).rev() {
        for j in (0..m).rev() {
            lcs[i][j] = if a[i] == b[j] {
                lcs[i + 1][j + 1] + 1
            } else {
                lcs[i + 1][j].max(lcs[i][j + 1])
            };
        }
    }
    // The edit script: (' ' | '-' | '+', line).
    let mut ops: Vec<(char, &str)> = Vec::new();
    let (mut i, mut j) = (0, 0);
    while i < n || j < m {
        if i < n && j < m && a[i] == b[j] {
            ops.push((' ', a[i]));
            i += 1;
            j += 1;
        } else if i < n && (j == m || lcs[i + 1][j] >= lcs[i][j + 1]) {
            ops.push(('-', a[i]));
            i += 1;
        } else {
            ops.push(('+', b[j]));
            j += 1;
        }
    }
    let near_change = |k: usize| {
        ops[k.saturating_sub(2)..(k + 3).min(ops.len())]
            .iter()
            .any(|o| o.0 != ' ')
    };
    let mut out = String::new();
    if let Some(k) = (0..n.max(m)).find(|&k| a.get(k) != b.get(k)) {
        let show = |l: Option<&&str>| l.map_or("(nothing)".to_string(), |l| format!("`{l}`"));
        out.push_str(&format!(
            "first difference at line {}:\n  golden {}\n  rusoar {}\n",
            k + 1,
            show(a.get(k)),
            show(b.get(k))
        ));
    }
    out.push_str("--- golden (official kernel)\n+++ rusoar\n");
    let mut shown = 0;
    let mut skipped = false;
    for (k, (tag, line)) in ops.iter().enumerate() {
        if !near_change(k) {
            skipped = true;
            continue;
        }
        if skipped {
            out.push_str("  ...\n");
            skipped = false;
        }
        if shown == limit {
            out.push_str("  ... (diff cut here)\n");
            break;
        }
        out.push_str(&format!("{tag} {line}\n"));
        shown += 1;
    }
    out
}

fn agent_names() -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(root().join("tests/agents"))
        .expect("tests/agents exists")
        .filter_map(|e| {
            let name = e.ok()?.file_name().into_string().ok()?;
            name.strip_suffix(".soar").map(str::to_string)
        })
        .collect();
    names.sort();
    names
}

#[test]
fn agents_match_the_official_kernel() {
    let names = agent_names();
    assert!(!names.is_empty(), "no agents in tests/agents");
    let mut problems = Vec::new();
    for (known, _) in KNOWN_DIFFERENCES {
        if !names.iter().any(|n| n == known) {
            problems.push(format!(
                "KNOWN_DIFFERENCES names `{known}`, which is not in tests/agents/"
            ));
        }
    }
    let mut matching = Vec::new();
    let mut differing = Vec::new();
    let mut matching_rules = Vec::new();
    for name in &names {
        let golden_path = root().join("tests/golden").join(format!("{name}.txt"));
        let Ok(golden) = std::fs::read_to_string(&golden_path) else {
            problems.push(format!(
                "{name}: no golden {}; run `python3 scripts/goldens.py`",
                golden_path.display()
            ));
            continue;
        };
        let (ours, rules) = run_agent(&root().join("tests/agents").join(format!("{name}.soar")));
        if let Some(rules) = rules {
            check_rules(name, &rules, &mut problems, &mut matching_rules);
        }
        if let Some(dir) = std::env::var_os("CONFORMANCE_OUT") {
            let dir = PathBuf::from(dir);
            std::fs::create_dir_all(&dir).expect("CONFORMANCE_OUT can be made");
            std::fs::write(dir.join(format!("{name}.txt")), &ours).expect("written");
        }
        let known = KNOWN_DIFFERENCES.iter().find(|(n, _)| n == name);
        match (ours == golden, known) {
            (true, None) => matching.push(name.as_str()),
            (true, Some(_)) => problems.push(format!(
                "{name}: now matches the official kernel; remove it from KNOWN_DIFFERENCES"
            )),
            (false, Some((_, why))) => differing.push(format!("{name} ({why})")),
            (false, None) => problems.push(format!(
                "{name}: differs from tests/golden/{name}.txt\n{}",
                diff(&golden, &ours, 60)
            )),
        }
    }
    println!("matching the official kernel: {}", matching.join(", "));
    println!("known differences: {}", differing.join("; "));
    println!("learned rules matching: {}", matching_rules.join(", "));
    assert!(
        problems.is_empty(),
        "{} problem(s):\n\n{}",
        problems.len(),
        problems.join("\n\n")
    );
}

/// A learning agent's learned rules against `tests/golden/NAME.rules.txt`.
fn check_rules(name: &str, ours: &str, problems: &mut Vec<String>, matching: &mut Vec<String>) {
    let path = root()
        .join("tests/golden")
        .join(format!("{name}.rules.txt"));
    let Ok(golden) = std::fs::read_to_string(&path) else {
        problems.push(format!("{name}: no golden {}", path.display()));
        return;
    };
    let known = KNOWN_RULE_DIFFERENCES.iter().any(|(n, _)| *n == name);
    match (ours == golden, known) {
        (true, false) => matching.push(name.to_string()),
        (true, true) => problems.push(format!(
            "{name}: learned rules now match; remove it from KNOWN_RULE_DIFFERENCES"
        )),
        (false, true) => {}
        (false, false) => problems.push(format!(
            "{name}: learned rules differ from tests/golden/{name}.rules.txt\n{}",
            diff(&golden, ours, 60)
        )),
    }
}

/// The numbers of `stats`' `WM size: N current, M mean, X maximum` line.
fn wm_size_line(stats: &str) -> Option<(String, String, String)> {
    let line = stats.lines().find_map(|l| l.strip_prefix("WM size: "))?;
    let mut parts = line.split(", ");
    let mut field = |suffix: &str| {
        parts
            .next()?
            .strip_suffix(suffix)
            .map(str::to_string)
            .filter(|n| !n.is_empty())
    };
    Some((field(" current")?, field(" mean")?, field(" maximum")?))
}

/// `J` of `stats`' `+ J justifications` line, 0 without one.
fn justification_count(stats: &str) -> String {
    stats
        .lines()
        .find_map(|l| {
            let n = l.trim_start().strip_prefix("+ ")?;
            let digits: String = n.chars().take_while(char::is_ascii_digit).collect();
            (!digits.is_empty() && n[digits.len()..].starts_with(" justification"))
                .then_some(digits)
        })
        .unwrap_or_else(|| "0".into())
}

/// The text a newline ends (one added if it has none).
fn ends_with_newline(text: String) -> String {
    if text.ends_with('\n') {
        text
    } else {
        text + "\n"
    }
}

/// A long run of `tests/agents/long/NAME.soar` as `scripts/goldens.py` runs it in the
/// official kernel (`srand 1`, `watch 0`, `source`, `run N`, `stats`, `print --depth 2
/// s1`, `print --justifications`), in the format of `tests/golden/long/NAME.txt`.
fn long_run(path: &Path, decisions: u64) -> String {
    let mut interp = Agent::default();
    interp.set_working_directory(root());
    let script = format!("srand 1\nwatch 0\nsource {}", path.display());
    let mut text = format!("run: {decisions}\n--- counts ---\n");
    if let Err(d) = interp.source_text("<conformance>", &script) {
        text.push_str(&format!("[loading failed: {}]\n", d.message()));
    }
    interp.take_output();
    let run = command(&mut interp, &format!("run {decisions}"));
    let stats = command(&mut interp, "stats");
    let printed = command(&mut interp, "print --depth 2 s1");
    let justifications = command(&mut interp, "print --justifications");
    let (run_decisions, run_firings) = run_counts(&run).unwrap_or_else(|| ("?".into(), "?".into()));
    let halted = if run.contains("An agent halted during the run.") {
        "yes"
    } else {
        "no"
    };
    let (_, mean, maximum) =
        wm_size_line(&stats).unwrap_or_else(|| ("?".into(), "?".into(), "?".into()));
    let mut counts = vec![
        ("run decisions", run_decisions),
        ("run firings", run_firings),
        ("halted", halted.to_string()),
    ];
    for (key, what) in [
        ("decisions", "decisions"),
        ("elaboration cycles", "elaboration cycles"),
        ("production firings", "production firings"),
        ("wm size", "wm size"),
    ] {
        counts.push((key, stats_count(&stats, what).unwrap_or_else(|| "?".into())));
    }
    counts.push(("wm mean", mean));
    counts.push(("wm maximum", maximum));
    counts.push(("justifications", justification_count(&stats)));
    for (key, value) in counts {
        text.push_str(&format!("{key}: {value}\n"));
    }
    text.push_str("--- print --depth 2 s1 ---\n");
    text.push_str(&ends_with_newline(printed));
    text.push_str("--- print --justifications ---\n");
    text.push_str(&ends_with_newline(justifications));
    text
}

/// Long runs end in the official kernel's state: every agent in `tests/agents/long/` runs
/// for the decisions its golden (`tests/golden/long/NAME.txt`, first line `run: N`) names,
/// and the counts of `stats` (justifications included) and what `print` shows of the top
/// state must equal the golden.
#[test]
fn long_runs_end_in_the_official_kernels_state() {
    let dir = root().join("tests/agents/long");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .expect("tests/agents/long exists")
        .filter_map(|e| {
            let name = e.ok()?.file_name().into_string().ok()?;
            name.strip_suffix(".soar").map(str::to_string)
        })
        .collect();
    names.sort();
    assert!(!names.is_empty(), "no agents in tests/agents/long");
    let mut problems = Vec::new();
    for name in &names {
        let golden_path = root().join("tests/golden/long").join(format!("{name}.txt"));
        let Ok(golden) = std::fs::read_to_string(&golden_path) else {
            problems.push(format!(
                "{name}: no golden {}; run `python3 scripts/goldens.py`",
                golden_path.display()
            ));
            continue;
        };
        let Some(decisions) = golden
            .lines()
            .next()
            .and_then(|l| l.strip_prefix("run: "))
            .and_then(|n| n.parse::<u64>().ok())
        else {
            problems.push(format!("{name}: the golden does not start with `run: N`"));
            continue;
        };
        let ours = long_run(&dir.join(format!("{name}.soar")), decisions);
        if let Some(out) = std::env::var_os("CONFORMANCE_OUT") {
            let out = PathBuf::from(out).join("long");
            std::fs::create_dir_all(&out).expect("CONFORMANCE_OUT can be made");
            std::fs::write(out.join(format!("{name}.txt")), &ours).expect("written");
        }
        if ours != golden {
            problems.push(format!(
                "{name}: differs from tests/golden/long/{name}.txt\n{}",
                diff(&golden, &ours, 60)
            ));
        }
    }
    assert!(
        problems.is_empty(),
        "{} problem(s):\n\n{}",
        problems.len(),
        problems.join("\n\n")
    );
}

#[test]
fn decision_lines_and_counts_are_extracted_as_goldens_py_does() {
    assert!(is_decision_line("     1:    O: O1 (a)"));
    assert!(is_decision_line("  1000:    ==>S: S2 (operator tie)"));
    assert!(!is_decision_line("1: no leading space"));
    assert!(!is_decision_line("     : print --stack line"));
    assert!(!is_decision_line("System halted."));
    assert_eq!(
        run_counts("\n\n--> 1 decision cycle executed. No rules fired. "),
        Some(("1".into(), "0".into()))
    );
    assert_eq!(
        run_counts("\n\n--> 12 decision cycles executed. 1 rule fired. "),
        Some(("12".into(), "1".into()))
    );
    let stats = "1000 decisions (0.010 msec/decision)\n\
                 2998 elaboration cycles (2.998 ec's per dc, 0.003 msec/ec)\n\
                 2998 inner elaboration cycles\n\
                 5314 production firings (1.773 pf's per ec, 0.002 msec/pf)\n\
                 WM size: 29 current, 31.494 mean, 36 maximum\n";
    assert_eq!(stats_count(stats, "decisions").as_deref(), Some("1000"));
    assert_eq!(
        stats_count(stats, "elaboration cycles").as_deref(),
        Some("2998")
    );
    assert_eq!(
        stats_count(stats, "production firings").as_deref(),
        Some("5314")
    );
    assert_eq!(stats_count(stats, "wm size").as_deref(), Some("29"));
    assert_eq!(
        wm_size_line(stats),
        Some(("29".into(), "31.494".into(), "36".into()))
    );
    assert_eq!(justification_count(stats), "0");
    assert_eq!(
        justification_count("5 productions (0 default, 5 user, 0 chunks)\n   + 2 justifications\n"),
        "2"
    );
    let d = diff("a\nb\nc\n", "a\nx\nc\n", 10);
    assert!(d.contains("- b\n+ x\n"), "{d}");
}
