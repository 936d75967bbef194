//! The `rusoar` binary without a terminal (`--source`, `-c`, standard input), and the thesis
//! rules loading through the library with no error.

use rusoar::{Agent, Printed};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn rusoar(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rusoar"))
        .args(args)
        .current_dir(root())
        .stdin(Stdio::null())
        .output()
        .expect("the rusoar binary runs")
}

/// `rusoar` with no arguments, reading `input` on standard input.
fn rusoar_stdin(input: &[u8]) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_rusoar"))
        .current_dir(root())
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    child.stdin.take().unwrap().write_all(input).unwrap();
    child.wait_with_output().unwrap()
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

#[test]
fn source_robotagent_loads_the_thesis_agent() {
    let out = rusoar(&["--source", "rules/robotagent.soar"]);
    let stdout = text(&out.stdout);
    let stderr = text(&out.stderr);
    assert!(out.status.success(), "stdout:\n{stdout}\nstderr:\n{stderr}");
    // The per-file report.
    assert!(
        stdout.contains("Loaded 36 productions from 8 files:"),
        "{stdout}"
    );
    for (file, n) in [
        ("rules/robotagent.soar", 0),
        ("rules/moving/moving.soar", 9),
        ("rules/slam.soar", 0),
        ("rules/Elaborate.soar", 3),
        ("rules/CopyWall.soar", 2),
        ("rules/CheckWallRelation.soar", 14),
        ("rules/CheckRobotPosition.soar", 6),
        ("rules/SubGoalElaborate.soar", 2),
    ] {
        let line = stdout
            .lines()
            .find(|l| l.split_whitespace().next() == Some(file))
            .unwrap_or_else(|| panic!("no report line for {file}:\n{stdout}"));
        assert!(line.trim_end().ends_with(&format!(" {n}")), "{line}");
    }
    assert!(
        stdout.contains("Total: 36 productions sourced."),
        "{stdout}"
    );
    // The Soar 8 `learn -off` warning, located, on standard error; and no error anywhere.
    assert!(
        stderr.contains("warning: Soar 8 spelling `learn -off`"),
        "{stderr}"
    );
    assert!(stderr.contains("robotagent.soar:13:7"), "{stderr}");
    assert!(!stderr.contains("error"), "{stderr}");
    assert!(!stdout.contains("error"), "{stdout}");
}

#[test]
fn repeated_c_options_run_in_order_with_source() {
    let out = rusoar(&[
        "-c",
        "echo first",
        "--source",
        "tests/data/parse/1a_sp_echo.soar",
        "-c",
        "sp {late*rule (state <s> ^superstate nil) --> (<s> ^a b)}",
        "-c",
        "print late*rule",
        "-c",
        "echo last",
    ]);
    let stdout = text(&out.stdout);
    assert!(out.status.success(), "{stdout}\n{}", text(&out.stderr));
    let pos = |s: &str| {
        stdout
            .find(s)
            .unwrap_or_else(|| panic!("{s:?} missing from:\n{stdout}"))
    };
    assert!(pos("first") < pos("after the stars"));
    assert!(pos("after the stars") < pos("Loaded 3 productions from 1 file"));
    assert!(pos("Loaded 3 productions") < pos("sp {late*rule"));
    assert!(pos("sp {late*rule") < pos("last"));
}

#[test]
fn commands_on_standard_input() {
    let out = rusoar_stdin(
        b"echo from stdin\nsp {piped\n   (state <s> ^superstate nil)\n-->\n   (write |hi|)}\nprint piped\n",
    );
    let stdout = text(&out.stdout);
    assert!(out.status.success(), "{stdout}\n{}", text(&out.stderr));
    assert!(stdout.contains("from stdin"), "{stdout}");
    assert!(stdout.contains("sp {piped\n"), "{stdout}");
    assert!(stdout.contains("    (write hi)\n"), "{stdout}");
}

#[test]
fn a_failing_c_exits_nonzero_with_a_located_diagnostic() {
    // As on Soar's command line, the commands after a failing one still run.
    let out = rusoar(&["-c", "echo ok", "-c", "learn -x", "-c", "echo after"]);
    let stdout = text(&out.stdout);
    let stderr = text(&out.stderr);
    assert!(!out.status.success());
    assert!(stdout.contains("ok"), "{stdout}");
    assert!(stdout.contains("after"), "{stdout}");
    assert!(stderr.contains("error: No such option: x"), "{stderr}");
    assert!(stderr.contains("┌─ -c:1:1"), "{stderr}");

    // `--strict` stops at the first failure.
    let out = rusoar(&[
        "--strict",
        "-c",
        "echo ok",
        "-c",
        "learn -x",
        "-c",
        "echo never",
    ]);
    assert!(!out.status.success());
    assert!(!text(&out.stdout).contains("never"));

    // So does standard input: each error is printed, the rest runs, the status says so.
    let out = rusoar_stdin(b"echo one\nbogus-command\necho two\n");
    assert!(!out.status.success());
    assert!(
        text(&out.stdout).contains("one\ntwo\n"),
        "{}",
        text(&out.stdout)
    );
    assert!(
        text(&out.stderr).contains("┌─ <stdin>:2:1"),
        "{}",
        text(&out.stderr)
    );

    let out = rusoar(&["-c", "sp {p1 (state <s> ^superstate nil) --> (<s> ^a b)}"]);
    let stderr = text(&out.stderr);
    assert!(!out.status.success());
    assert!(
        stderr.contains("error: Expected symbol for production name"),
        "{stderr}"
    );
    assert!(stderr.contains("┌─ -c:1:5"), "{stderr}");
}

#[test]
fn a_failing_source_exits_nonzero_and_points_into_the_file() {
    let out = rusoar(&["--source", "tests/data/errors/6d_nested_source_error.soar"]);
    let stderr = text(&out.stderr);
    assert!(!out.status.success());
    assert!(
        stderr.contains("tests/data/errors/nested/inner.soar:3:47"),
        "{stderr}"
    );
    assert!(
        stderr.contains("while sourcing") && stderr.contains("6d_nested_source_error.soar:3"),
        "{stderr}"
    );
}

fn soar_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap().filter_map(Result::ok) {
        let p = e.path();
        if p.is_dir() {
            soar_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "soar") {
            out.push(p);
        }
    }
}

/// The `.soar` files below `dir` (but not below `skip`), sorted, as paths relative to the
/// repository.
fn relative_soar_files(dir: &str, skip: Option<&str>) -> Vec<String> {
    let mut files = Vec::new();
    soar_files(&root().join(dir), &mut files);
    if let Some(skip) = skip {
        files.retain(|f| !f.starts_with(root().join(skip)));
    }
    files.sort();
    files
        .iter()
        .map(|f| {
            f.strip_prefix(root())
                .unwrap()
                .to_string_lossy()
                .into_owned()
        })
        .collect()
}

/// A fresh agent working in the repository's folder.
fn agent_at_root() -> Agent {
    let mut interp = Agent::default();
    interp.set_working_directory(root());
    interp
}

/// Sources `rel` (relative to the repository) and returns the error diagnostics it printed.
fn source_errors(interp: &mut Agent, rel: &str) -> Vec<String> {
    let result = interp.source_text("<test>", &format!("source {{{rel}}}"));
    let mut errors: Vec<String> = interp
        .take_printed()
        .into_iter()
        .filter_map(|e| match e {
            Printed::Diagnostic(d) if !d.is_warning() => Some(d.message()),
            _ => None,
        })
        .collect();
    if let Err(d) = result {
        errors.push(d.message());
    }
    errors
}

#[test]
fn all_of_rules_loads_with_zero_errors() {
    // The whole agent, as the thesis loads it.
    let mut interp = Agent::default();
    interp.set_working_directory(root());
    let errors = source_errors(&mut interp, "rules/robotagent.soar");
    assert!(errors.is_empty(), "{errors:#?}");
    assert_eq!(interp.load_report().added(), 36);
    assert_eq!(interp.load_report().files().count(), 8);
    assert_eq!(interp.production_count(), 36);

    // And every file on its own (the ablation variants, below, need the thesis rules first;
    // rules v2 are tested on their own).
    let mut files = relative_soar_files("rules", Some("rules/variants"));
    files.retain(|f| !f.starts_with("rules/v2"));
    assert_eq!(files.len(), 8);
    for rel in files {
        let mut interp = agent_at_root();
        let errors = source_errors(&mut interp, &rel);
        assert!(errors.is_empty(), "{rel}: {errors:#?}");
    }
}

#[test]
fn rules_v2_and_their_oracle_load_with_zero_errors() {
    let mut interp = agent_at_root();
    let errors = source_errors(&mut interp, "rules/v2/robotagent.soar");
    assert!(errors.is_empty(), "{errors:#?}");
    // The 9 moving rules of the thesis and the 58 of rules v2.
    assert_eq!(interp.production_count(), 9 + 58);
    let errors = source_errors(&mut interp, "rules/v2/oracle.soar");
    assert!(errors.is_empty(), "{errors:#?}");
    // The oracle excises the anchor and the proposal of new walls, and adds four rules.
    assert_eq!(interp.production_count(), 9 + 58 - 2 + 4);
}

#[test]
fn each_rule_variant_loads_after_the_thesis_rules_with_zero_errors() {
    let files = relative_soar_files("rules/variants", None);
    assert_eq!(files.len(), 4);
    for rel in files {
        let mut interp = agent_at_root();
        assert!(source_errors(&mut interp, "rules/robotagent.soar").is_empty());
        let errors = source_errors(&mut interp, &rel);
        assert!(errors.is_empty(), "{rel}: {errors:#?}");
        // Each `excise` removes a thesis rule, each `sp` adds one under a new name.
        let text = std::fs::read_to_string(root().join(&rel)).unwrap();
        let excised = text.lines().filter(|l| l.starts_with("excise ")).count();
        let added = text.lines().filter(|l| l.starts_with("sp {")).count();
        assert_eq!(interp.production_count(), 36 - excised + added, "{rel}");
    }
}

#[test]
fn slam_rejects_an_unknown_method_with_a_clear_error() {
    let dir = std::env::temp_dir().join(format!("rusoar-ekf-bad-{}", std::process::id()));
    let out = rusoar(&["slam", "--method", "kalman", "--out", dir.to_str().unwrap()]);
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("invalid value 'kalman'"), "{stderr}");
    assert!(
        stderr.contains("thesis") && stderr.contains("ekf"),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(!dir.exists());
    let out = rusoar(&["slam", "--method", "ekf", "--slam", "on"]);
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("--method thesis"), "{stderr}");
}

#[test]
fn the_slam_comparison_refuses_to_compare_failed_runs() {
    let dir = std::env::temp_dir().join(format!("rusoar-compare-fail-{}", std::process::id()));
    let out = rusoar(&[
        "slam",
        "--rules",
        "/nonexistent",
        "--seeds",
        "1",
        "--duration",
        "1",
        "--out",
        dir.to_str().unwrap(),
    ]);
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("did not complete") && stderr.contains("robotagent.soar"),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(!dir.join("comparison.md").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn slam_ekf_outputs_are_byte_identical_for_the_same_seed() {
    let base = std::env::temp_dir().join(format!("rusoar-ekf-same-{}", std::process::id()));
    let run = |name: &str| {
        let dir = base.join(name);
        let args = [
            "slam",
            "--method",
            "ekf",
            "--seeds",
            "1",
            "--first-seed",
            "3",
            "--duration",
            "60",
            "--jobs",
            "1",
            "--out",
        ];
        let mut args: Vec<&str> = args.to_vec();
        args.push(dir.to_str().unwrap());
        let out = rusoar(&args);
        assert!(out.status.success(), "{}", text(&out.stderr));
        dir
    };
    let (a, b) = (run("a"), run("b"));
    for f in [
        "steps-ekf-3.csv",
        "believed-ekf-3.tum",
        "true-ekf-3.tum",
        "map-ekf-3.csv",
        "ekf-runs.csv",
    ] {
        let (x, y) = (
            std::fs::read(a.join(f)).unwrap(),
            std::fs::read(b.join(f)).unwrap(),
        );
        assert!(!x.is_empty(), "{f} is empty");
        assert!(x == y, "{f} differs between two runs of the same seed");
    }
    let md = std::fs::read_to_string(a.join("ekf.md")).unwrap();
    assert!(md.contains("| EKF |"), "{md}");
    let _ = std::fs::remove_dir_all(&base);
}

#[test]
fn exit_and_quit_end_the_commands() {
    for word in ["exit", "quit"] {
        let out = rusoar(&["-c", "echo before", "-c", word, "-c", "echo after"]);
        assert!(out.status.success(), "{word}: {:?}", out.status);
        let stdout = text(&out.stdout);
        assert!(stdout.contains("before"), "{word}: {stdout}");
        assert!(!stdout.contains("after"), "{word}: {stdout}");
        let piped = rusoar_stdin(format!("echo before\n{word}\necho after\n").as_bytes());
        assert!(
            !text(&piped.stdout).contains("after"),
            "{word}, standard input"
        );
    }
}
