//! The REPL as a person uses it: the real binary in a pseudo-terminal, typing a multi-line
//! `sp`, stepping with `run 1 -d`, printing, interrupting an endless `run` with Ctrl-C,
//! clearing a half-typed line with Ctrl-C, and leaving with Ctrl-D. Skipped (with a note)
//! where no pseudo-terminal can be opened.
#![cfg(unix)]

use rexpect::session::{spawn_command, PtySession};
use std::process::Command;
use std::time::Duration;

/// Generous: CI machines are slow and shared.
const TIMEOUT_MS: u64 = 30_000;

fn start(history: &std::path::Path) -> Option<PtySession> {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_rusoar"));
    cmd.env("RUSOAR_HISTORY", history)
        .env("TERM", "xterm")
        .env_remove("NO_COLOR");
    match spawn_command(cmd, Some(TIMEOUT_MS)) {
        Ok(s) => Some(s),
        Err(e) => {
            eprintln!("skipped: cannot open a pseudo-terminal ({e})");
            None
        }
    }
}

#[test]
fn a_session_in_a_pseudo_terminal() {
    let dir = std::env::temp_dir().join(format!("rusoar-pty-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let history = dir.join("history");
    let Some(mut p) = start(&history) else {
        return;
    };
    p.exp_string("Ctrl-D quits.").unwrap();
    p.exp_string("soar 0> ").unwrap();

    // A rule typed over several lines: the REPL waits while the brace is open.
    p.send_line("sp {test*propose").unwrap();
    p.send_line("   (state <s> ^superstate nil -^flag)")
        .unwrap();
    p.send_line("-->").unwrap();
    p.send_line("   (<s> ^operator <o> +)").unwrap();
    p.send_line("   (<o> ^name on)}").unwrap();
    p.exp_string("*").unwrap();
    p.exp_string("soar 0> ").unwrap();

    p.send_line("run 1 -d").unwrap();
    p.exp_string("     1:    O: O1 (on)").unwrap();
    p.exp_string("--> 1 decision cycle executed. 1 rule fired.")
        .unwrap();
    p.exp_string("soar 1> ").unwrap();

    p.send_line("print s1").unwrap();
    // The first line wraps early: the stream stood after the trace line (as in 9.6).
    p.exp_string("(S1 ^epmem E1 ^io I1 ^operator O1 ^operator O1 +\r\n       ^reward-link R1")
        .unwrap();
    p.exp_string("soar 1> ").unwrap();

    // Two more rules on one line make the agent run forever (on, off, on, ...).
    p.send_line(
        "sp {test*apply*on (state <s> ^operator.name on) --> (<s> ^flag 1)}; \
         sp {test*propose*off (state <s> ^flag <f>) --> (<s> ^operator <o> +) (<o> ^name off)}; \
         sp {test*apply*off (state <s> ^operator.name off ^flag <f>) --> (<s> ^flag <f> -)}",
    )
    .unwrap();
    p.exp_string("***").unwrap();
    p.exp_string("soar 1> ").unwrap();
    p.send_line("watch 0").unwrap();
    p.exp_string("Trace level 0 enabled").unwrap();
    p.exp_string("soar 1> ").unwrap();
    p.send_line("run").unwrap();
    std::thread::sleep(Duration::from_millis(700));
    p.send_control('c').unwrap();
    p.exp_string("Interrupted.").unwrap();
    let (_, count) = p.exp_regex(r"--> \d+ decision cycles executed").unwrap();
    let decisions: u64 = count
        .trim_start_matches("--> ")
        .split(' ')
        .next()
        .and_then(|n| n.parse().ok())
        .unwrap();
    assert!(decisions > 3, "the run stopped at once: {count}");
    // Still alive: the prompt counts the decisions run, and commands still work.
    let (_, prompt) = p.exp_regex(r"soar \d+> ").unwrap();
    // The run started in cycle 1, so 9.6's count is the cycle counter itself: one ahead of
    // the decisions made when the run stops after the decision phase of a cycle, equal to
    // them when it stops (within an elaboration cycle) before it.
    assert!(
        prompt == format!("soar {}> ", decisions - 1) || prompt == format!("soar {decisions}> "),
        "{prompt} after {count}"
    );
    p.send_line("echo still here").unwrap();
    p.exp_string("still here").unwrap();

    p.exp_regex(r"soar \d+> ").unwrap();

    // Ctrl-C at the prompt drops the half-typed line. (Wait for each echo and prompt:
    // keys typed ahead of a Ctrl-C are dropped with it.)
    p.send("echo never printed").unwrap();
    p.flush().unwrap();
    p.exp_string("echo never printed").unwrap();
    p.send_control('c').unwrap();
    p.exp_regex(r"soar \d+> ").unwrap();
    p.send_line("echo after ctrl-c").unwrap();
    let before = p.exp_string("after ctrl-c\r\n").unwrap();
    assert!(!before.contains("never printed\r\n"), "{before}");

    // Ctrl-D leaves, and the history was saved. (Wait for the prompt: a Ctrl-D typed
    // while the line editor is still drawing it can be lost on a loaded machine.)
    p.exp_regex(r"soar \d+> ").unwrap();
    p.send_control('d').unwrap();
    p.exp_eof().unwrap();
    let saved = std::fs::read_to_string(&history).unwrap_or_default();
    assert!(saved.contains("run 1 -d"), "history: {saved}");
    assert!(saved.contains("echo after ctrl-c"), "history: {saved}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_repl_killed_by_a_signal_keeps_its_history() {
    let dir = std::env::temp_dir().join(format!("rusoar-pty-kill-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let history = dir.join("history");
    let Some(mut p) = start(&history) else {
        return;
    };
    p.exp_string("soar 0> ").unwrap();
    p.send_line("echo before the signal").unwrap();
    p.exp_string("before the signal\r\n").unwrap();
    p.exp_string("soar 0> ").unwrap();
    p.process_mut()
        .kill(rexpect::process::Signal::SIGKILL)
        .unwrap();
    let saved = std::fs::read_to_string(&history).unwrap_or_default();
    assert!(saved.contains("echo before the signal"), "history: {saved}");
    let _ = std::fs::remove_dir_all(&dir);
}
