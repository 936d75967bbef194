//! `explain` (Soar manual, ch. 9, `explain`): which learned rules the explainer records,
//! its summary, settings and lists, with soar-sml 9.6.5's text and messages. rusoar keeps
//! the records (`src/learn/explain.rs`) but not the formation of each rule, so a rule
//! cannot be chosen for the explanation itself (`explain chunk`, `formation`, ...): that
//! is refused with an error that says so.

use super::{CmdResult, Ctx, Interpreter};
use crate::learn::explain::{Explainer, Recorded};
use crate::source::Diagnostic;

/// The sub-commands and settings, by the names 9.6 matches a word's prefix against.
const NAMES: [&str; 15] = [
    "all",
    "chunk",
    "constraints",
    "contributors",
    "explanation-trace",
    "formation",
    "identity",
    "instantiations",
    "justifications",
    "list-chunks",
    "list-justifications",
    "only-chunk-identities",
    "record",
    "stats",
    "wm-trace",
];

const INVALID: &str =
    "Invalid explain sub-command.  Use 'explain ?' to see a list of valid sub-commands and settings.";
const BAD_VALUE: &str =
    "Invalid argument for explain command. Use 'explain ?' to see a list of valid sub-commands and settings.";
const NO_CHUNK: &str = "Please first specify the chunk you want to discuss with the command 'explain chunk [chunk-name | chunk ID]'.";
/// How many records of each kind the summary lists.
const SUMMARY_LIST: usize = 10;

/// The summary's and lists' column for values.
fn row(label: &str, value: &str) -> String {
    format!("{label:<54}{value}\n")
}

impl Interpreter {
    pub(super) fn cmd_explain(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        if let Some((i, option)) = args
            .iter()
            .enumerate()
            .find(|(_, a)| a.len() > 1 && a.starts_with('-'))
        {
            return Err(Diagnostic::error(format!(
                "No such option: {}",
                option.trim_start_matches('-')
            ))
            .at(ctx.arg_span(i))
            .with_label("explain takes no options")
            .with_note("Use 'explain ?' or 'help explain' to learn more about the explain command."));
        }
        if args.len() > 2 {
            return Err(ctx.error("Too many arguments for the 'explain' command."));
        }
        let Some(first) = args.first() else {
            // 9.6 prints the summary on a line of its own: after a trace line that did not
            // end, it starts a new one.
            let lead = if self.print_column() == 0 { "" } else { "\n" };
            self.print_col.set(0);
            return Ok(format!("{lead}{}", summary(&self.agent.learn.explainer)));
        };
        if first == "?" {
            return Ok(listing(&self.agent.learn.explainer));
        }
        let value = args.get(1).map(String::as_str);
        let name = match resolve(first) {
            Ok(name) => name,
            // A recorded rule's name alone is `explain chunk NAME`.
            Err(_) if self.agent.learn.explainer.find(first).is_some() => "chunk",
            Err(candidates) => {
                let d = Diagnostic::error(INVALID)
                    .at(ctx.arg_span(0))
                    .with_label("not a sub-command or setting");
                return Err(if candidates.is_empty() {
                    d
                } else {
                    d.with_note(format!("did you mean: {}", candidates.join(", ")))
                });
            }
        };
        let value = if name == "chunk" && resolve(first).is_err() {
            Some(first.as_str())
        } else {
            value
        };
        let explainer = &mut self.agent.learn.explainer;
        match name {
            "all" | "justifications" | "only-chunk-identities" => {
                switch(ctx, explainer, name, value)
            }
            "record" => match value {
                None => {
                    let mut s = String::from("Rules watched:\n");
                    for rule in explainer.recorded_rules.iter().rev() {
                        s += &format!("   {rule}\n");
                    }
                    Ok(s)
                }
                Some(rule) => {
                    if self.agent.production_arc(rule).is_none() {
                        return Err(Diagnostic::error(format!(
                            "Could not find a rule named {rule} to watch."
                        ))
                        .at(ctx.arg_span(1))
                        .with_label("no rule of this name")
                        .with_note("Type 'print' to see a list of all rules."));
                    }
                    self.agent.learn.explainer.watch(rule);
                    Ok(format!("Now watching any chunks formed by rule '{rule}'"))
                }
            },
            "list-chunks" => Ok(list(explainer, true)),
            "list-justifications" => Ok(list(explainer, false)),
            "chunk" => {
                let Some(word) = value else {
                    return Err(ctx.error(
                        "Please specify the chunk using either the chunk's name or its ID.",
                    ));
                };
                match explainer.find(word) {
                    None => Err(Diagnostic::error(format!(
                        "Could not find a rule name or id {word}."
                    ))
                    .at(ctx.cmd.span)
                    .with_label("not a recorded rule")
                    .with_note("Type 'explain list-chunks' or 'explain list-justifications' to see a list of rule formations Soar has recorded.")),
                    Some(r) => Err(ctx
                        .error(format!(
                            "rusoar cannot explain the formation of {} yet",
                            r.name
                        ))
                        .with_note("the explainer records which rules were learned (`explain list-chunks`), not the instantiations, identities and constraints behind each")),
                }
            }
            // The rest browse the explanation of a chosen rule, and none can be chosen.
            _ => Err(ctx
                .error(NO_CHUNK)
                .with_note("rusoar cannot choose a rule to explain yet (`explain chunk`)")),
        }
    }
}

/// The word's sub-command or setting: an exact name, or the prefix of just one.
fn resolve(word: &str) -> Result<&'static str, Vec<&'static str>> {
    super::resolve_prefix(&NAMES, word)
}

/// `all`, `justifications`, `only-chunk-identities`: shown, or set to `on` or `off`.
fn switch(ctx: &Ctx, e: &mut Explainer, name: &str, value: Option<&str>) -> CmdResult {
    let setting = match name {
        "all" => &mut e.all,
        "justifications" => &mut e.justifications,
        _ => &mut e.only_chunk_identities,
    };
    let Some(value) = value else {
        let now = *setting;
        return Ok(match (name, now) {
            ("all", true) => "The explainer is currently recording all rules formed.",
            ("all", false) => "The explainer is not currently recording all rules formed.",
            ("justifications", true) => {
                "The explainer is currently recording justifications created."
            }
            ("justifications", false) => {
                "The explainer is not currently recording justifications created."
            }
            (_, true) => "The explainer is currently showing identity analysis only for identities that appear in the chunk.",
            (_, false) => "The explainer is currently showing identity analysis for all identities involved in problem-solving.",
        }
        .to_string());
    };
    *setting = match value {
        "on" => true,
        "off" => false,
        _ => {
            return Err(Diagnostic::error(BAD_VALUE)
                .at(ctx.arg_span(1))
                .with_label("`on` or `off`"))
        }
    };
    Ok(match (name, *setting) {
        ("all", true) => "Will monitor all chunks created.",
        ("all", false) => "Will only monitor specific chunks.",
        ("justifications", true) => "Will record justifications created.",
        ("justifications", false) => "Will not record justifications created.",
        (_, true) => "Will only print identities that appear in the chunk.",
        (_, false) => "Will print all identities involved in problem-solving.",
    }
    .to_string())
}

/// `explain list-chunks` / `list-justifications`.
fn list(e: &Explainer, chunks: bool) -> String {
    let records: Vec<&Recorded> = e.records.iter().filter(|r| r.is_chunk == chunks).collect();
    if records.is_empty() {
        return none_recorded(chunks).to_string();
    }
    let mut s = format!("{}\n", available(chunks));
    for r in records {
        s += &format!("   {} (c {})\n", r.name, r.id);
    }
    s
}

fn none_recorded(chunks: bool) -> &'static str {
    if chunks {
        "No chunks have been recorded."
    } else {
        "No justifications have been recorded."
    }
}

fn available(chunks: bool) -> &'static str {
    if chunks {
        "Chunks available for explanation:"
    } else {
        "Justifications available for explanation:"
    }
}

/// `explain`: the settings, the watched rules and the records.
fn summary(e: &Explainer) -> String {
    let yes_no = |b: bool| if b { "Yes" } else { "No" };
    let mut s = String::from(
        "=======================================================\n                   Explainer Summary\n=======================================================\n",
    );
    s += &row("Watch all chunk formations", yes_no(e.all));
    s += &row("Explain justifications", yes_no(e.justifications));
    s += &row(
        "Number of specific rules watched",
        &e.recorded_rules.len().to_string(),
    );
    if e.all {
        s += "\n";
    } else {
        // The rules `record` named, newest first, then the chunks watched through them.
        let learned = e.watched.iter().filter(|w| !e.recorded_rules.contains(w));
        let watched: Vec<&String> = e.recorded_rules.iter().rev().chain(learned.rev()).collect();
        if watched.is_empty() {
            s += "Rules watched:\n";
        } else {
            for (i, w) in watched.iter().enumerate() {
                s += &row(if i == 0 { "Rules watched:" } else { "" }, w);
            }
            s += "\n";
        }
    }
    s += "No rule is currently being explained.\n";
    let total = e.records.len();
    for chunks in [true, false] {
        let records: Vec<&Recorded> = e.records.iter().filter(|r| r.is_chunk == chunks).collect();
        if records.is_empty() {
            s += none_recorded(chunks);
            s += "\n";
            continue;
        }
        let shown = records.len().min(SUMMARY_LIST);
        for (i, r) in records.iter().take(shown).enumerate() {
            let label = if i == 0 { available(chunks) } else { "" };
            s += &row(label, &format!("{} (c {})", r.name, r.id));
        }
        s += "\n";
        // 9.6 counts the records of both kinds here.
        if shown < total {
            let (kind, command) = if chunks {
                ("chunks", "list-chunks")
            } else {
                ("justifications", "list-justifications")
            };
            s += &format!(
                "* Note:  Only listed the first {SUMMARY_LIST} {kind} recorded.  Type 'explain {command}' to see the other {} {kind}.\n\n",
                total - shown
            );
        }
    }
    s += "-------------------------------------------------------\n\nUse 'explain chunk [ <chunk-name> | id ]' to explore the formation of that chunk.\nUse 'explain ?' to learn more about explain's sub-command and settings.\n";
    s
}

/// `explain ?`: 9.6's listing, each switch with its current value in capitals.
fn listing(e: &Explainer) -> String {
    let choice = |on: bool| if on { "[ ON | off ]" } else { "[ on | OFF ]" };
    let switch = |name: &str, on: bool, what: &str| format!("{name:<39}{}   {what}\n", choice(on));
    let mut s = String::from("========= Explainer Commands and Settings =========\n");
    s += "explain ?                                             Print this help listing\n";
    s += "------------------ What to Record -----------------\n";
    s += &switch("all", e.all, "Whether to record all rules that are learned");
    s += &switch("justifications", e.justifications, "Whether to record justifications");
    s += LISTING_MIDDLE;
    s += &switch(
        "only-chunk-identities",
        e.only_chunk_identities,
        "Identity analysis only prints identities sets found in chunk",
    );
    s += "---------------------------------------------------\n\nTo change a setting:                                  explain <setting> [<value>]\nFor a detailed explanation of these settings:         help explain\n";
    s
}

const LISTING_MIDDLE: &str = "record <chunk-name>                                   Record any chunks formed from a specific rule
list-chunks                                           List all rules learned
list-justifications                                   List all justifications learned
------------- Starting an Explanation -------------
chunk [<chunk name> | <chunk id> ]                    Start discussing chunk
formation                                             Describe initial formation of chunk
------------- Browsing an Explanation -------------
instantiation <inst id>                               Explain instantiation
explanation-trace                                     Switch to explanation trace inspection
wm-trace                                              Switch to working memory trace inspection
-------------- Supporting Analysis ----------------
constraints                                           Display extra transitive constraints required by problem-solving
identity                                              Display identity to identity set mappings
stats                                                 Display statistics about currently discussed chunk
";
