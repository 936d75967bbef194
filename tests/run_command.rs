//! `run`'s report, against what the official 9.6 kernel printed for the same commands: the
//! decision-cycle count (with its quirks) and the texts after a halt.

use rusoar::Agent;

fn out(i: &mut Agent, cmd: &str) -> String {
    i.source_text("t", cmd).unwrap();
    i.take_output()
}

fn report(i: &mut Agent, cmd: &str) -> String {
    let text = out(i, cmd);
    let start = text.find("--> ").expect("a run report");
    text[start..].trim_end().to_string()
}

#[test]
fn the_cycle_count_follows_the_cycle_counter() {
    let mut i = Agent::default();
    out(&mut i, "watch 0");
    // (command, what 9.6 reported), all in one interpreter.
    for (cmd, n) in [
        ("run 1", "1 decision cycle"),
        ("run 1", "2 decision cycles"),
        ("run 1", "1 decision cycle"),
        ("run 3 -p", "1 decision cycle"),
        ("run 3 -p", "0 decision cycle"),
        ("run 2 -e", "1 decision cycle"),
        ("init-soar", ""),
        ("run 2 -p", "1 decision cycle"),
        ("run 4 -p", "2 decision cycles"),
        ("run 1 -p", "0 decision cycle"),
        ("run 1 -p", "0 decision cycle"),
        ("init-soar", ""),
        ("run 3 -e", "1 decision cycle"),
        ("run 1", "2 decision cycles"),
        ("init-soar", ""),
        ("run 5", "5 decision cycles"),
        ("run 5", "5 decision cycles"),
    ] {
        if n.is_empty() {
            out(&mut i, cmd);
            continue;
        }
        assert_eq!(
            report(&mut i, cmd),
            format!("--> {n} executed. No rules fired."),
            "{cmd}"
        );
    }
}

#[test]
fn a_halt_is_reported_and_a_halted_agent_does_not_run() {
    let mut i = Agent::default();
    i.set_working_directory(
        std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/traces"),
    );
    out(&mut i, "source counter.soar");
    assert_eq!(
        out(&mut i, "run"),
        "\n     1:    O: O1 (init)\n     2:    O: O2 (increment)\n     3:    O: O3 (increment)\n     4:    O: O4 (increment)\nCounted to 3.\nSystem halted.\nInterrupt received.This Agent halted.\n\n--> 4 decision cycles executed. 10 rules fired. \nAn agent halted during the run.\n"
    );
    for cmd in ["run", "run 1"] {
        assert_eq!(
            out(&mut i, cmd),
            "\n\n--> 0 decision cycle executed. No rules fired. \nAn agent halted during the run.\n"
        );
    }
    // The print column is 0 after the halt.
    assert_eq!(
        out(&mut i, "print s1"),
        "(S1 ^count 3 ^done yes ^epmem E1 ^io I1 ^reward-link R1 ^smem L1\n       ^superstate nil ^type state)\n"
    );
    out(&mut i, "init-soar");
    assert_eq!(
        report(&mut i, "run 2"),
        "--> 2 decision cycles executed. 3 rules fired."
    );
}

/// Misused `run`, `trace` and `print`: 9.6's messages (the official kernel's, one by one).
#[test]
fn misuse_gets_9_6_messages() {
    let mut i = Agent::default();
    for (cmd, msg) in [
        ("run x", "Integer count expected."),
        ("run -1", "Count must be positive."),
        (
            "run 1 2",
            "Syntax: run  [-f|count]\nrun -[d|e|o|p][s][un][g] [f|count]\nrun -[d|e|o|p][un] count [-i e|p|d|o]",
        ),
        ("trace 9", "Expected trace level from 0 to 5."),
        ("trace -1", "Expected trace level from 0 to 5."),
        ("trace x", "Integer argument expected."),
        ("trace 3 4", "Only non option argument allowed is watch level."),
        ("p -d -1 s1", "Non-negative depth expected."),
        ("wmes", "Non-negative depth expected."),
        ("print --depth", "Option 'depth' requires an argument."),
        (
            "print -d 1",
            "Syntax: print [options] [production_name]\nprint [options] identifier|timetag|pattern",
        ),
    ] {
        let err = i.source_text("t", cmd).unwrap_err();
        assert_eq!(err.message(), msg, "{cmd}");
    }
    assert_eq!(out(&mut i, "print"), "");
    assert_eq!(
        out(&mut i, "print s1 s2"),
        "Expected '(' to begin wme pattern not string 's1' or char ' '\n"
    );
    // A count of 0 runs one decision, and `1.5` reads as 1.
    out(&mut i, "watch 0");
    assert_eq!(
        report(&mut i, "run 0"),
        "--> 1 decision cycle executed. No rules fired."
    );
    assert_eq!(
        report(&mut i, "run 1.5"),
        "--> 2 decision cycles executed. No rules fired."
    );
}

/// Past `max-goal-depth` 9.6 stops the run as interrupted and does not halt: a later run
/// goes one state deeper, with the same message (observed on soar-sml 9.6.5).
#[test]
fn max_goal_depth_interrupts_the_run_without_halting() {
    let mut i = Agent::default();
    i.set_working_directory(std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")));
    out(&mut i, "srand 1");
    out(&mut i, "source tests/agents/max-goal-depth.soar");
    out(&mut i, "trace 1");
    let first = out(&mut i, "run 1000");
    assert!(first.contains(
        "==>S: S7 (operator no-change)\nSystem halted.\nInterrupt received.Interrupt received.\n\n\
         --> 12 decision cycles executed. 6 rules fired. \nRun stopped (interrupted)."
    ));
    let second = out(&mut i, "run 3");
    assert!(second.contains("O: O7 (dive)\nGoal stack depth exceeded 6 on a no-change impasse."));
    assert!(second.contains(
        "==>S: S8 (operator no-change)\nSystem halted.\nInterrupt received.Interrupt received.\n\n\
         --> 2 decision cycles executed. 1 rule fired. \nRun stopped (interrupted)."
    ));
}

/// `fc N` lists the N most fired rules, as 9.6 does (observed on soar-sml 9.6.5 with these
/// two rules after `run 2`: `fc 25` lists both, `fc 1` only `a`).
#[test]
fn firing_counts_takes_a_count_of_rules_to_list() {
    let mut i = rusoar::Agent::default();
    i.source_text(
        "setup",
        "watch 0\nsp {a (state <s> ^superstate nil) --> (<s> ^x 1)}\n\
         sp {b (state <s> ^superstate nil) --> (<s> ^y 1)}\nrun 2",
    )
    .unwrap();
    i.take_output();
    i.source_text("t", "fc 25").unwrap();
    assert_eq!(i.take_output(), "     1:  a\n     1:  b\n");
    i.source_text("t", "fc 1").unwrap();
    assert_eq!(i.take_output(), "     1:  a\n");
    i.source_text("t", "fc b").unwrap();
    assert_eq!(i.take_output(), "     1:  b\n");
}
