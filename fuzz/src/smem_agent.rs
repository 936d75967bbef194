//! Semantic memory driven from bytes: a knowledge base for `smem --add`, rules that put
//! queries (with negative and math cues, prohibitions and depths), retrievals and stores
//! on `^smem.command`, and steps that run the agent a phase or a decision at a time between
//! `smem` commands (queries, removals, more additions, settings, `--init`, `--clear`). The
//! knowledge base and the rules are valid, so they must load; a command may fail with an
//! error. The kernel's invariants are checked after every step.
//!
//! The `smem` fuzz target feeds it libFuzzer's bytes; `tests/smem_sequences.rs` includes
//! this same file and feeds it seeded pseudo-random bytes.

use crate::steps::{Step, Steps};
use arbitrary::{Result, Unstructured};
use std::fmt::Write;

const ATTRS: &[&str] = &["name", "age", "kind", "next", "w"];
const CONSTANTS: &[&str] = &["alice", "bob", "cup", "1", "2", "2.5", "-3"];
/// The most long-term identifiers a knowledge base has.
const MAX_LTIS: u32 = 5;
const MAX_STEPS: u32 = 50;

fn pick<'a>(u: &mut Unstructured, from: &'a [&'a str]) -> Result<&'a str> {
    Ok(from[u.choose_index(from.len())?])
}

/// `smem --add {...}`: LTIs `@1`..`@n`, each with a few attributes whose values are
/// constants, other LTIs, or an object of its own (a variable, made an LTI by the addition).
fn knowledge_base(u: &mut Unstructured, first: u32) -> Result<String> {
    let n = u.int_in_range(1..=MAX_LTIS)?;
    let mut text = String::from("smem --add {");
    let mut objects = 0;
    for i in first..first + n {
        let _ = write!(text, "(@{i}");
        for _ in 0..u.int_in_range(1..=3)? {
            let attr = pick(u, ATTRS)?;
            match u.int_in_range(0..=4)? {
                0..=2 => {
                    let _ = write!(text, " ^{attr} {}", pick(u, CONSTANTS)?);
                }
                3 => {
                    let _ = write!(text, " ^{attr} @{}", u.int_in_range(1..=first + n - 1)?);
                }
                _ => {
                    objects += 1;
                    let _ = write!(text, " ^{attr} <o{objects}>");
                }
            }
        }
        text.push(')');
    }
    for o in 1..=objects {
        let _ = write!(
            text,
            " (<o{o}> ^{} {})",
            pick(u, ATTRS)?,
            pick(u, CONSTANTS)?
        );
    }
    text.push('}');
    Ok(text)
}

/// One rule that works semantic memory, named `name`.
fn rule(u: &mut Unstructured, name: &str) -> Result<String> {
    // The top state, or any state (substates have `^smem` links of their own).
    let state = if u.ratio(2, 3)? {
        "(state <s> ^superstate nil ^smem <sm>) (<sm> ^command <c>)"
    } else {
        "(state <s> ^type state ^smem <sm>) (<sm> ^command <c>)"
    };
    let quiet = if u.ratio(1, 2)? { " -(<c> ^<any>)" } else { "" };
    let (lhs, rhs) = match u.int_in_range(0..=7)? {
        0 | 1 => {
            let mut rhs = format!(
                "(<c> ^query <q>) (<q> ^{} {})",
                pick(u, ATTRS)?,
                pick(u, &["alice", "bob", "cup", "1", "2.5", "<any>"])?
            );
            if u.ratio(1, 3)? {
                let _ = write!(
                    rhs,
                    " (<c> ^neg-query <n>) (<n> ^{} {})",
                    pick(u, ATTRS)?,
                    pick(u, CONSTANTS)?
                );
            }
            if u.ratio(1, 3)? {
                let _ = write!(
                    rhs,
                    " (<c> ^math-query <m>) (<m> ^{} <t>) (<t> ^{} {})",
                    pick(u, ATTRS)?,
                    pick(
                        u,
                        &[
                            "max",
                            "min",
                            "less",
                            "greater",
                            "less-or-equal",
                            "greater-or-equal"
                        ]
                    )?,
                    pick(u, &["1", "2", "2.5", "-3", "alice"])?
                );
            }
            if u.ratio(1, 4)? {
                let _ = write!(rhs, " (<c> ^depth {})", u.int_in_range(0..=3)?);
            }
            (format!("{state}{quiet}"), rhs)
        }
        2 => (
            format!("{state} (<sm> ^result.retrieved <l>){quiet}"),
            "(<c> ^retrieve <l>)".to_string(),
        ),
        3 => (
            format!(
                "{state} (<sm> ^result.retrieved <l>) (<l> ^{} <v>){quiet}",
                pick(u, ATTRS)?
            ),
            format!(
                "(<c> ^{} <v>)",
                pick(u, &["retrieve", "prohibit", "store"])?
            ),
        ),
        4 => (
            format!("{state} (<sm> ^result.retrieved <l>)"),
            "(<c> ^query <q> ^prohibit <l>) (<q> ^kind cup)".to_string(),
        ),
        5 => (
            format!("{state} (<s> ^thing <t>){quiet}"),
            "(<c> ^store <t>)".to_string(),
        ),
        6 => (
            "(state <s> ^superstate nil)".to_string(),
            format!(
                "(<s> ^thing <t>) (<t> ^{} {} ^{} <u>) (<u> ^{} {})",
                pick(u, ATTRS)?,
                pick(u, CONSTANTS)?,
                pick(u, ATTRS)?,
                pick(u, ATTRS)?,
                pick(u, CONSTANTS)?
            ),
        ),
        // An operator that clears the command link once a result is in, so that later
        // rules can put new commands there.
        _ => (
            format!("{state} (<c> ^<cmd> <x>) (<sm> ^result.<status> <x>)"),
            "(<s> ^operator <o> + =) (<o> ^name clear ^cmd <cmd> ^x <x>)".to_string(),
        ),
    };
    Ok(format!("sp {{{name}\n    {lhs}\n-->\n    {rhs}\n}}\n"))
}

/// The operator that the `clear` proposals name: o-supported removal of the command.
const CLEAR: &str = "sp {smem*apply*clear
    (state <s> ^operator <o> ^smem.command <c>) (<o> ^name clear ^cmd <cmd> ^x <x>)
-->
    (<c> ^<cmd> <x> -)
}
";

/// Draws a semantic-memory agent from `u`.
pub fn smem_agent(u: &mut Unstructured) -> Result<Steps> {
    let mut source = String::from("watch 0\nsmem --enable\n");
    let _ = writeln!(
        source,
        "smem --set activation-mode {}",
        pick(u, &["recency", "frequency", "base-level"])?
    );
    if u.ratio(1, 3)? {
        source.push_str("smem --set activate-on-query off\n");
    }
    if u.ratio(1, 4)? {
        source.push_str("smem --set base-update-policy incremental\n");
    }
    source.push_str(&knowledge_base(u, 1)?);
    source.push('\n');
    source.push_str(CLEAR);
    for i in 0..u.int_in_range(1..=8)? {
        source.push_str(&rule(u, &format!("smem*rule*{i}"))?);
    }
    let mut steps = Vec::new();
    for _ in 0..u.int_in_range(1..=MAX_STEPS)? {
        let lti = u.int_in_range(1..=MAX_LTIS + 1)?;
        steps.push(match u.int_in_range(0..=30)? {
            0..=14 => Step::Phase,
            15..=19 => Step::Decision,
            20 => Step::Command(format!(
                "smem --query {{(<q> ^{} {})}} {}",
                pick(u, ATTRS)?,
                pick(u, CONSTANTS)?,
                u.int_in_range(1..=3)?
            )),
            21 => Step::Command(format!("smem --remove {{(@{lti} ^{})}}", pick(u, ATTRS)?)),
            22 => Step::Command(format!("smem --remove {{(@{lti})}}")),
            23 => {
                let first = u.int_in_range(1..=MAX_LTIS)?;
                Step::Command(knowledge_base(u, first)?)
            }
            24 => Step::Command(format!("smem --history @{lti}")),
            25 => Step::Command(format!("print @{lti}")),
            26 => Step::Command(
                pick(u, &["smem --init", "smem --clear", "init-soar", "print @"])?.into(),
            ),
            27 => Step::Command(
                pick(
                    u,
                    &["smem --stats", "smem --stats nodes", "print --depth 4 s1"],
                )?
                .into(),
            ),
            28 => Step::Command(format!(
                "smem --set activation-mode {}",
                pick(u, &["recency", "frequency", "base-level"])?
            )),
            29 => Step::Command("smem --disable".into()),
            _ => Step::Command("smem --enable".into()),
        });
    }
    Ok(Steps { source, steps })
}

/// Sources `spec` into `agent` and runs its steps, checking the kernel's invariants after
/// each.
pub fn run_smem_agent(agent: &mut rusoar::Agent, spec: &Steps) -> std::result::Result<(), String> {
    crate::steps::run_steps(agent, "smem-agent", spec)
}
