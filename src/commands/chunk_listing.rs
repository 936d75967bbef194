//! `chunk` with no arguments and `chunk ?`: 9.6's summary and settings listing
//! (Soar manual, ch. 9, `chunk`), with this agent's settings and counts filled in.

use crate::agent::{AgentCore, LearnMode};
use crate::learn::settings::NamingStyle;

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
    let yes_no = |b: bool| if b { "Yes" } else { "No" }.to_string();
    let c = &s.chunk;
    out += &row("Incorporate operator selection knowledge", yes_no(c.add_osk));
    out += &row("Interrupt after learning any rule", yes_no(c.interrupt));
    out += &row(
        "Interrupt after learning from watched rule",
        yes_no(c.explain_interrupt),
    );
    out += &row("Interrupt after learning failure", yes_no(c.warning_interrupt));
    out += "\n";
    out += &row("Chunks learned", l.chunks_since_init.to_string());
    out += &row(
        "Justifications learned",
        l.justifications_since_init.to_string(),
    );
    out += &row("Substates analyzed", l.substates_analyzed.to_string());
    let marked = match s.learn {
        LearnMode::Only => Some(("Only Learning In States", &l.force_learn, "No current learning states.")),
        LearnMode::Except => Some((
            "Learning in All States Except",
            &l.dont_learn,
            "Currently learning in all states.",
        )),
        _ => None,
    };
    if let Some((title, states, none)) = marked {
        out += title;
        out += "\n";
        if states.is_empty() {
            out += none;
            out += "\n";
        }
        for &st in states.iter().rev() {
            out += &agent.symbols.text(st);
            out += "\n";
        }
    }
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
    let c = &s.chunk;
    out += &switch("bottom-only", c.bottom_only, "Learn only from bottom sub-state");
    out += match c.naming_style {
        NamingStyle::Numbered => "naming-style                     [ NUMBERED | rule]",
        NamingStyle::Rule => "naming-style                     [ numbered | RULE]",
    };
    out += "   Simple numeric chunk names or informational rule-based name\n";
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
    out += "------------------- Debugging ---------------------\n";
    out += &switch("interrupt", c.interrupt, "Stop Soar after learning from any rule");
    out += &switch(
        "explain-interrupt",
        c.explain_interrupt,
        "Stop Soar after learning rule watched by explainer",
    );
    out += &switch(
        "warning-interrupt",
        c.warning_interrupt,
        "Stop Soar after detecting learning issue",
    );
    out += "------------------- Fine Tune ---------------------\nsingleton                                             Print all WME singletons\nsingleton                <type> <attribute> <type>    Add a WME singleton pattern\nsingleton -r             <type> <attribute> <type>    Remove a WME singleton pattern\n";
    out += &switch(
        "automatically-create-singletons",
        c.automatically_create_singletons,
        "Attempt creating singletons for every string attribute",
    );
    out += "----------------- EBC Mechanisms ------------------\n";
    out += &switch(
        "add-ltm-links",
        c.add_ltm_links,
        "Recreate LTM links in original results",
    );
    out += &switch("add-osk", c.add_osk, "Incorporate operator selection knowledge");
    out += "---------- Correctness Guarantee Filters ----------   Allow rules to form that...\n";
    out += &switch(
        "allow-local-negations",
        c.allow_local_negations,
        "...used local negative reasoning",
    );
    out += &switch(
        "allow-opaque",
        c.allow_opaque,
        "...used knowledge from a LTM recall",
    );
    out += "---------------------------------------------------\n\nTo change a setting:                                  chunk <setting> [<value>]\nFor a detailed explanation of these settings:         help chunk\n";
    out
}

/// An on/off row of `chunk ?`, the current value in capitals.
fn switch(name: &str, on: bool, what: &str) -> String {
    let choice = if on { "[ ON | off ]" } else { "[ on | OFF ]" };
    format!("{name:<39}{choice}   {what}\n")
}
