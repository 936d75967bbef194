//! `chunk` with no arguments and `chunk ?`: 9.6's summary and settings listing
//! (Soar manual, ch. 9, `chunk`), with this agent's settings and counts filled in.

use crate::agent::{AgentCore, LearnMode};

/// `chunk`: the Explanation-Based Chunking summary.
pub fn summary(agent: &AgentCore) -> String {
    let s = &agent.settings;
    let l = &agent.learn;
    let row = |label: &str, value: String| format!("{label}{value:>w$}\n", w = 55 - label.len());
    let mut out = String::from(
        "=======================================================\n           Explanation-Based Chunking Summary\n=======================================================\n",
    );
    out += &row(
        "When Soar will learn rules",
        s.learn.word().trim_end().to_string(),
    );
    out += &row("Incorporate operator selection knowledge", "Yes".into());
    out += &row("Interrupt after learning any rule", "No".into());
    out += &row("Interrupt after learning from watched rule", "No".into());
    out += &row("Interrupt after learning failure", "No".into());
    out += "\n";
    out += &row("Chunks learned", l.chunks_since_init.to_string());
    out += &row(
        "Justifications learned",
        l.justifications_since_init.to_string(),
    );
    out += &row("Substates analyzed", l.substates_analyzed.to_string());
    out += "-------------------------------------------------------\n\nTry 'chunk ?' to learn more about chunking's sub-commands and settings.\nFor a detailed article about the chunk command, use 'help chunk'.\n";
    out
}

/// `chunk ?`: every setting, the current choice in capitals (as 9.6 lists them).
pub fn settings(agent: &AgentCore) -> String {
    let s = &agent.settings;
    let modes = [
        ("always", LearnMode::Always),
        ("never", LearnMode::Never),
        ("only", LearnMode::Only),
        ("except", LearnMode::Except),
    ]
    .iter()
    .map(|(w, m)| {
        if *m == s.learn {
            w.to_uppercase()
        } else {
            w.to_string()
        }
    })
    .collect::<Vec<_>>()
    .join(" | ");
    let number = |name: &str, n: i64, what: &str| format!("{name:<35}{n:>10}         {what}\n");
    let mut out = String::from(
        "===================================================\n           Chunk Commands and Settings\n===================================================\nchunk ? | help                                        Print all EBC settings\nchunk stats                                           Print statistics on learning that has occurred\n------------------- Settings ----------------------\n",
    );
    out += &format!("{modes:<54}When Soar will learn new rules\n");
    out += "bottom-only                            [ on | OFF ]   Learn only from bottom sub-state\nnaming-style                     [ numbered | RULE]   Simple numeric chunk names or informational rule-based name\n";
    out += &number(
        "max-chunks",
        s.max_chunks,
        "Maximum chunks that can be learned (per phase)",
    );
    out += &number(
        "max-dupes",
        s.max_dupes,
        "Maximum duplicate chunks (per rule, per phase)",
    );
    out += STATIC_TAIL;
    out
}

/// The listing's fixed part: settings rusoar does not offer to change keep 9.6's defaults.
const STATIC_TAIL: &str = "------------------- Debugging ---------------------\ninterrupt                              [ on | OFF ]   Stop Soar after learning from any rule\nexplain-interrupt                      [ on | OFF ]   Stop Soar after learning rule watched by explainer\nwarning-interrupt                      [ on | OFF ]   Stop Soar after detecting learning issue\n------------------- Fine Tune ---------------------\nsingleton                                             Print all WME singletons\nsingleton                <type> <attribute> <type>    Add a WME singleton pattern\nsingleton -r             <type> <attribute> <type>    Remove a WME singleton pattern\nautomatically-create-singletons        [ ON | off ]   Attempt creating singletons for every string attribute\n----------------- EBC Mechanisms ------------------\nadd-ltm-links                          [ on | OFF ]   Recreate LTM links in original results\nadd-osk                                [ ON | off ]   Incorporate operator selection knowledge\n---------- Correctness Guarantee Filters ----------   Allow rules to form that...\nallow-local-negations                  [ ON | off ]   ...used local negative reasoning\nallow-opaque                           [ ON | off ]   ...used knowledge from a LTM recall\n---------------------------------------------------\n\nTo change a setting:                                  chunk <setting> [<value>]\nFor a detailed explanation of these settings:         help chunk\n";
