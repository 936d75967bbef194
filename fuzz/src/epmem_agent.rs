//! Episodic memory driven from bytes: an agent whose top state changes every decision
//! (a counter, objects that come and go, elaborations that blink), rules that put
//! `^epmem.command`s on a state's link (queries with positive and negative cues, nested
//! identifiers, `before`, `after`, `prohibit`; retrievals, `next`, `previous`, and malformed
//! commands), and steps that run it a phase or a decision at a time between `epmem`
//! commands (settings, `--print`, `--viz`, `--init`, `init-soar`). The agent is valid, so
//! it must load; a command may fail with an error. The kernel's invariants are checked
//! after every step.
//!
//! The `epmem` fuzz target feeds it libFuzzer's bytes; `tests/epmem_sequences.rs` includes
//! this same file and feeds it seeded pseudo-random bytes.

use crate::steps::{Step, Steps};
use arbitrary::{Result, Unstructured};
use std::fmt::Write;

const ATTRS: &[&str] = &["color", "size", "next", "on", "kind"];
const CONSTANTS: &[&str] = &["red", "blue", "1", "2", "2.5", "-3", "yes"];
const MAX_STEPS: u32 = 60;

fn pick<'a>(u: &mut Unstructured, from: &'a [&'a str]) -> Result<&'a str> {
    Ok(from[u.choose_index(from.len())?])
}

/// The counter that makes each episode differ from the last, and the operator that clears
/// a command once its result is in.
const BASE: &str = "sp {epmem*propose*init
    (state <s> ^superstate nil -^count)
-->
    (<s> ^operator <o> + >)
    (<o> ^name init)
}
sp {epmem*apply*init
    (state <s> ^operator.name init)
-->
    (<s> ^count 0)
}
sp {epmem*propose*count
    (state <s> ^superstate nil ^count <c>)
-->
    (<s> ^operator <o> + <)
    (<o> ^name count ^n <c>)
}
sp {epmem*apply*count
    (state <s> ^operator <o> ^count <c>)
    (<o> ^name count ^n <c>)
-->
    (<s> ^count <c> - (+ <c> 1))
}
sp {epmem*apply*clear
    (state <s> ^operator <o> ^epmem.command <c>)
    (<o> ^name clear ^cmd <cmd> ^x <x>)
-->
    (<c> ^<cmd> <x> -)
}
";

/// A cue object's augmentations: constants, a variable, or a nested object.
fn cue(u: &mut Unstructured, id: &str, depth: u32) -> Result<String> {
    let mut text = String::new();
    let mut nested = String::new();
    for i in 0..u.int_in_range(1..=3)? {
        let attr = pick(u, &["count", "thing", "flag", "color", "size", "on"])?;
        match u.int_in_range(0..=3)? {
            0 | 1 if attr == "count" => {
                let _ = write!(text, " ^count {}", u.int_in_range(0..=12)?);
            }
            0 | 1 => {
                let _ = write!(text, " ^{attr} {}", pick(u, CONSTANTS)?);
            }
            2 if depth < 2 => {
                let child = format!("{id}{i}");
                let _ = write!(text, " ^{attr} <{child}>");
                nested.push_str(&cue(u, &child, depth + 1)?);
            }
            _ => {
                let _ = write!(text, " ^{attr} <any{id}{i}>");
            }
        }
    }
    Ok(format!(" (<{id}>{text}){nested}"))
}

/// One rule, named `name`: it changes the top state, or puts a command on a link.
fn rule(u: &mut Unstructured, name: &str) -> Result<String> {
    let state = if u.ratio(3, 4)? {
        "(state <s> ^superstate nil ^epmem <ep>) (<ep> ^command <c>)"
    } else {
        "(state <s> ^type state ^epmem <ep>) (<ep> ^command <c>)"
    };
    // Most commands hold while the state they test does (the count moves on each
    // decision); a quiet one is made only while the link is empty.
    let quiet = if u.ratio(1, 4)? { " -(<c> ^<any>)" } else { "" };
    let when = format!(
        " (<s> ^count {} {})",
        pick(u, &[">", "<", "<>"])?,
        u.int_in_range(0..=12)?
    );
    let state = format!("{state}{when}");
    let (lhs, rhs) = match u.int_in_range(0..=9)? {
        0..=2 => {
            let mut rhs = format!("(<c> ^query <q>){}", cue(u, "q", 0)?);
            if u.ratio(1, 3)? {
                let _ = write!(rhs, " (<c> ^neg-query <nq>){}", cue(u, "nq", 0)?);
            }
            for kw in ["before", "after"] {
                if u.ratio(1, 5)? {
                    let _ = write!(rhs, " (<c> ^{kw} {})", u.int_in_range(0..=12)?);
                }
            }
            if u.ratio(1, 5)? {
                let _ = write!(rhs, " (<c> ^prohibit {})", u.int_in_range(1..=8)?);
            }
            (format!("{state}{quiet}"), rhs)
        }
        3 => (
            format!("{state}{quiet}"),
            format!("(<c> ^retrieve {})", u.int_in_range(0..=12)?),
        ),
        4 => (
            format!("{state} (<ep> ^result.retrieved <r>){quiet}"),
            pick(u, &["(<c> ^next <n>)", "(<c> ^previous <n>)"])?.to_string(),
        ),
        // Malformed: two commands at once, or a retrieval of something not a number.
        5 => (
            format!("{state}{quiet}"),
            pick(
                u,
                &[
                    "(<c> ^retrieve 2 ^next <n>)",
                    "(<c> ^retrieve red)",
                    "(<c> ^query <q> ^retrieve 1) (<q> ^count 1)",
                    "(<c> ^before 3)",
                    "(<c> ^query red)",
                ],
            )?
            .to_string(),
        ),
        // The top state: objects that come with a count and go with the next.
        6 | 7 => (
            format!(
                "(state <s> ^superstate nil ^count {{<k> {} {}}})",
                pick(u, &[">", "<", "<>"])?,
                u.int_in_range(0..=10)?
            ),
            format!(
                "(<s> ^thing <t>) (<t> ^{} {} ^{} <u>) (<u> ^{} {})",
                pick(u, ATTRS)?,
                pick(u, CONSTANTS)?,
                pick(u, ATTRS)?,
                pick(u, ATTRS)?,
                pick(u, CONSTANTS)?
            ),
        ),
        8 => (
            "(state <s> ^superstate nil ^thing <t> ^count <k>)".to_string(),
            format!(
                "(<s> ^flag <f>) (<f> ^on <k> ^{} {})",
                pick(u, ATTRS)?,
                pick(u, CONSTANTS)?
            ),
        ),
        _ => (
            format!("{state} (<c> ^<cmd> <x>) (<ep> ^result.<status> <y>)"),
            "(<s> ^operator <o> + =) (<o> ^name clear ^cmd <cmd> ^x <x>)".to_string(),
        ),
    };
    Ok(format!("sp {{{name}\n    {lhs}\n-->\n    {rhs}\n}}\n"))
}

/// Draws an episodic-memory agent from `u`.
pub fn epmem_agent(u: &mut Unstructured) -> Result<Steps> {
    let mut source = String::from("watch 0\nepmem --set learning on\n");
    for (setting, values) in [
        ("trigger", &["dc", "dc", "output", "none"][..]),
        ("phase", &["output", "selection"][..]),
        ("graph-match", &["on", "off"][..]),
        ("balance", &["1", "0.5", "0"][..]),
    ] {
        if u.ratio(1, 3)? {
            let _ = writeln!(source, "epmem --set {setting} {}", pick(u, values)?);
        }
    }
    source.push_str(BASE);
    for i in 0..u.int_in_range(1..=8)? {
        source.push_str(&rule(u, &format!("epmem*rule*{i}"))?);
    }
    let mut steps = Vec::new();
    for _ in 0..u.int_in_range(1..=MAX_STEPS)? {
        let episode = u.int_in_range(0..=14)?;
        steps.push(match u.int_in_range(0..=30)? {
            0..=12 => Step::Phase,
            13..=21 => Step::Decision,
            22 => Step::Command(format!("epmem --print {episode}")),
            23 => Step::Command(format!("epmem --viz {episode}")),
            24 => Step::Command(
                pick(
                    u,
                    &[
                        "epmem --init",
                        "init-soar",
                        "epmem --stats",
                        "print --depth 5 s1",
                    ],
                )?
                .into(),
            ),
            25 => Step::Command(format!(
                "epmem --set exclusions {}",
                pick(u, &["thing", "flag", "count", "epmem"])?
            )),
            26 => Step::Command(format!(
                "epmem --set force {}",
                pick(u, &["remember", "ignore", "off"])?
            )),
            27 => Step::Command(format!(
                "epmem --set trigger {}",
                pick(u, &["dc", "output", "none"])?
            )),
            28 => Step::Command("epmem --disable".into()),
            29 => Step::Command("epmem --enable".into()),
            _ => Step::Command(format!("run {}", u.int_in_range(2..=20)?)),
        });
    }
    Ok(Steps { source, steps })
}

/// Sources `spec` into `agent` and runs its steps, checking the kernel's invariants after
/// each.
pub fn run_epmem_agent(agent: &mut rusoar::Agent, spec: &Steps) -> std::result::Result<(), String> {
    crate::steps::run_steps(agent, "epmem-agent", spec)
}
