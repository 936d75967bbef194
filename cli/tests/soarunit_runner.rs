//! `rusoar test`: the SoarUnit runner on the project's `.soarunit` files (which test the
//! thesis rules and must all pass) and on a deliberately failing file.

use std::process::Command;

fn rusoar_test(args: &[&str]) -> (String, i32) {
    let out = Command::new(env!("CARGO_BIN_EXE_rusoar"))
        .arg("test")
        .args(args)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .output()
        .expect("run rusoar");
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    (stdout, out.status.code().unwrap_or(-1))
}

/// The report's `PASS`/`FAIL` lines, without the transcripts.
fn verdicts(report: &str) -> Vec<String> {
    report
        .lines()
        .filter(|l| l.starts_with("  PASS") || l.starts_with("  FAIL") || l.ends_with("tests)"))
        .map(str::to_string)
        .collect()
}

#[test]
fn the_thesis_rule_tests_pass() {
    let (report, code) = rusoar_test(&["tests/soarunit"]);
    assert_eq!(code, 0, "{report}");
    assert_eq!(
        verdicts(&report),
        [
            "tests/soarunit/checkrobotposition.soarunit (3 tests)",
            "  PASS  sonar-shorter-than-the-map-moves-the-robot-forward (2 decisions)",
            "  PASS  sonar-agreeing-with-the-map-changes-nothing (2 decisions)",
            "  PASS  each-difference-is-corrected-once (3 decisions)",
            "tests/soarunit/checkwallrelation.soarunit (3 tests)",
            "  PASS  two-overlapping-walls-of-the-same-time-merge (5 decisions)",
            "  PASS  walls-far-apart-are-not-merged (3 decisions)",
            "  PASS  overlapping-walls-of-different-times-correct-the-robot (5 decisions)",
            "tests/soarunit/copywall.soarunit (3 tests)",
            "  PASS  copies-a-wall-from-the-input-link (1 decision)",
            "  PASS  copies-each-of-two-walls-once (3 decisions)",
            "  PASS  leaves-copied-walls-alone (1 decision)",
        ]
    );
    assert!(report.ends_with("\nok: 9 passed, 0 failed\n"), "{report}");
}

#[test]
fn failures_are_reported_per_test_with_a_non_zero_exit() {
    let (report, code) = rusoar_test(&[
        "--max-decisions",
        "50",
        "tests/data/soarunit-failing/mixed.soarunit",
    ]);
    assert_eq!(code, 1, "{report}");
    assert_eq!(
        verdicts(&report),
        [
            "tests/data/soarunit-failing/mixed.soarunit (4 tests)",
            "  PASS  passes (1 decision)",
            "  FAIL  calls-fail (line 18): (fail) was called: ready was set",
            "  FAIL  never-ends (line 25): reached the decision limit (50) without (pass) or (fail)",
            "  FAIL  does-not-load (line 30): error while loading: Illegal value for RHS value",
        ]
    );
    // A failing test's transcript follows it: the load error points into the test file.
    assert!(
        report.contains("tests/data/soarunit-failing/mixed.soarunit:34:15"),
        "{report}"
    );
    assert!(
        report.ends_with("\nFAILED: 1 passed, 3 failed\n"),
        "{report}"
    );
}

#[test]
fn bad_paths_and_bad_files_fail_cleanly() {
    let (report, code) = rusoar_test(&["tests/data/no-such-dir"]);
    assert_eq!(code, 1);
    assert!(
        report.starts_with("error: cannot read tests/data/no-such-dir"),
        "{report}"
    );
    let dir = std::env::temp_dir().join(format!("rusoar-soarunit-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.soarunit");
    std::fs::write(&bad, "setup {\n  sp {a\n").unwrap();
    let (report, code) = rusoar_test(&[bad.to_str().unwrap()]);
    assert_eq!(code, 1, "{report}");
    assert!(report.contains("unmatched opening brace"), "{report}");
    std::fs::write(&bad, "run 5\n").unwrap();
    let (report, code) = rusoar_test(&[bad.to_str().unwrap()]);
    assert_eq!(code, 1, "{report}");
    assert!(
        report.contains("unexpected `run` in a .soarunit file"),
        "{report}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
