//! `trace` (alias `watch`): levels 0 to 5, the single flags (`-p`, `--wmes`, `-w remove`,
//! ...), and the listing with no arguments, with 9.6's messages (Soar manual, ch. 9,
//! `trace`; checked on the official kernel).

use super::{CmdResult, Ctx, Interpreter};
use crate::agent::{TraceFlags, WmeDetail};
use crate::source::Diagnostic;

/// The flags `trace` sets one by one: short letter, long name, and the end of the message
/// after "Now printing " / "Will not print ". 9.6 reports changed flags in this order,
/// whatever the order of the options (checked: `trace -w remove -p`).
const FLAGS: &[(char, &str, &str)] = &[
    (
        'A',
        "assertions",
        "assertions of rule instantiations and the preferences they generate.",
    ),
    (
        'b',
        "backtracing",
        "chunking's dependency analysis trace messages.",
    ),
    ('c', "chunks", "when chunks fire."),
    (
        'C',
        "chunk-warnings",
        "warnings when issues detected while learning rules.",
    ),
    (
        'o',
        "consistency",
        "operator proposal consistency messages and any states removed as a result.",
    ),
    ('d', "decisions", "states created and operators selected."),
    ('D', "default", "when rules marked as :default fire."),
    (
        'G',
        "gds-wmes",
        "all WMEs added or removed from the Goal Dependency Set.",
    ),
    (
        'g',
        "gds",
        "when a state is removed because of a GDS violation.",
    ),
    (
        'i',
        "indifferent-selection",
        "how Soar calculates and resolves numeric preferences.",
    ),
    (
        'R',
        "rl",
        "reinforcement learning value updates and gap intervals.",
    ),
    (
        'e',
        "epmem",
        "when episodic memory records a new episode or considers an episode in a query.",
    ),
    ('j', "justifications", "when justifications fire."),
    ('T', "template", "when templates match."),
    ('p', "phases", "each individual phase."),
    ('r', "preferences", "preferences as they are created."),
    ('s', "smem", "additions to semantic memory."),
    ('u', "user", "when user rules fire."),
    (
        'w',
        "wmes",
        "when working memory elements are added to or removed from memory.",
    ),
    (
        'W',
        "waterfall",
        "when rules do not fire because a higher level rule matches and needs to fire first.",
    ),
    (
        'a',
        "wma",
        "working memory activations, changed values, and removals caused by forgetting (if enabled).",
    ),
];

/// The other options: `-l N`, `-L N`, `-N`, `-P` (`-cDju`) and the WME detail levels.
const OTHER: &[(char, &str)] = &[
    ('l', "level"),
    ('L', "learning"),
    ('N', "none"),
    ('P', "productions"),
    ('n', "nowmes"),
    ('t', "timetags"),
    ('f', "fullwmes"),
];

const LEVELS: [&str; 6] = [
    "Trace level 0 enabled:  All trace messages disabled.",
    "Trace level 1 enabled:  Decision cycles, state creation and operator selection",
    "Trace level 2 enabled:  All phases, state removals caused by operator selection\n                        or a GDS violation, and any learning issues detected",
    "Trace level 3 enabled:  All rule firings",
    "Trace level 4 enabled:  Working memory element additions and removals",
    "Trace level 5 enabled: Preferences",
];

fn flag_mut<'a>(t: &'a mut TraceFlags, long: &str) -> &'a mut bool {
    match long {
        "assertions" => &mut t.assertions,
        "backtracing" => &mut t.backtracing,
        "chunks" => &mut t.chunks,
        "chunk-warnings" => &mut t.chunk_warnings,
        "consistency" => &mut t.consistency,
        "decisions" => &mut t.decisions,
        "default" => &mut t.default_rules,
        "gds-wmes" => &mut t.gds_wmes,
        "gds" => &mut t.gds,
        "indifferent-selection" => &mut t.indifferent,
        "rl" => &mut t.rl,
        "epmem" => &mut t.epmem,
        "justifications" => &mut t.justifications,
        "template" => &mut t.templates,
        "phases" => &mut t.phases,
        "preferences" => &mut t.preferences,
        "smem" => &mut t.smem,
        "user" => &mut t.user_rules,
        "wmes" => &mut t.wmes,
        "waterfall" => &mut t.waterfall,
        _ => &mut t.wma,
    }
}

/// What one option of a `trace` command asks for.
enum Change {
    Flag(&'static str, bool),
    Level(u8),
    Learning(u8),
    None,
    Detail(WmeDetail),
}

/// The long name of a `--word` (any unique prefix) or of a short letter.
fn long_name(word: &str) -> Result<&'static str, String> {
    let all = FLAGS
        .iter()
        .map(|f| (f.0, f.1))
        .chain(OTHER.iter().copied());
    if let Some(rest) = word.strip_prefix("--") {
        let hits: Vec<&'static str> = all
            .filter(|(_, l)| l.starts_with(rest))
            .map(|(_, l)| l)
            .collect();
        return match hits.iter().find(|l| **l == rest) {
            Some(l) => Ok(l),
            None if hits.len() == 1 => Ok(hits[0]),
            _ => Err(format!("No such option: {rest}")),
        };
    }
    let c = word.chars().next().unwrap_or(' ');
    let found = all.clone().find(|(s, _)| *s == c).map(|(_, l)| l);
    found.ok_or_else(|| format!("No such option: {c}"))
}

fn parse_level(word: &str, learning: bool) -> Result<u8, String> {
    let max = if learning { 2 } else { 5 };
    match word.parse::<i64>() {
        Ok(l) if (0..=max).contains(&l) => Ok(l as u8),
        Ok(_) if learning => Err("Learning trace level must be 0, 1 or 2.".into()),
        Ok(_) => Err("Expected trace level from 0 to 5.".into()),
        Err(_) => Err("Integer argument expected.".into()),
    }
}

/// Reads the words of a `trace` command into changes. An option's optional argument
/// (`remove` or `0`) is the next word if that is not an option; in a cluster it belongs
/// to the last letter (checked: `trace -pw remove`).
fn parse(args: &[String]) -> Result<Vec<Change>, String> {
    let mut out = Vec::new();
    let mut positional: Option<u8> = None;
    let mut i = 0;
    while i < args.len() {
        let word = &args[i];
        i += 1;
        let is_option = word.len() > 1 && word.starts_with('-') && word.parse::<i64>().is_err();
        if !is_option {
            if positional.is_some() {
                return Err("Only non option argument allowed is watch level.".into());
            }
            let l = parse_level(word, false)?;
            positional = Some(l);
            out.push(Change::Level(l));
            continue;
        }
        let names: Vec<&'static str> = if word.starts_with("--") {
            vec![long_name(word)?]
        } else {
            word[1..]
                .chars()
                .map(|c| long_name(&c.to_string()))
                .collect::<Result<_, _>>()?
        };
        let next_is_value = args
            .get(i)
            .is_some_and(|w| !(w.len() > 1 && w.starts_with('-') && w.parse::<i64>().is_err()));
        let last = names.len() - 1;
        for (k, name) in names.into_iter().enumerate() {
            let takes_value = k == last && next_is_value;
            match name {
                "level" | "learning" => {
                    if k != last || !next_is_value {
                        return Err(format!("Option '{name}' requires an argument."));
                    }
                    let l = parse_level(&args[i], name == "learning")?;
                    i += 1;
                    out.push(if name == "level" {
                        Change::Level(l)
                    } else {
                        Change::Learning(l)
                    });
                }
                "none" => out.push(Change::None),
                "nowmes" => out.push(Change::Detail(WmeDetail::None)),
                "timetags" => out.push(Change::Detail(WmeDetail::Timetags)),
                "fullwmes" => out.push(Change::Detail(WmeDetail::Full)),
                _ => {
                    let mut on = true;
                    if takes_value {
                        match args[i].as_str() {
                            "remove" | "0" => on = false,
                            other => {
                                return Err(format!(
                                    "Invalid argument, expected remove or 0. Got: {other}"
                                ))
                            }
                        }
                        i += 1;
                    }
                    if name == "productions" {
                        for n in ["chunks", "default", "justifications", "user"] {
                            out.push(Change::Flag(n, on));
                        }
                    } else {
                        out.push(Change::Flag(name, on));
                    }
                }
            }
        }
    }
    Ok(out)
}

fn on_off(b: bool) -> &'static str {
    if b {
        "Now printing "
    } else {
        "Will not print "
    }
}

impl Interpreter {
    /// `trace` / `watch`: with no arguments the listing; a level (or `-l N`) sets the
    /// flags of levels 1 to N; single flags report what they changed.
    pub(super) fn cmd_trace(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        if args.is_empty() {
            return Ok(trace_listing(
                &self.agent.settings.trace,
                self.agent.settings.learning_trace,
            ));
        }
        let changes = parse(args).map_err(|m| {
            let at = ctx.cmd.span;
            Diagnostic::error(m).at(at).with_label("in this command")
        })?;
        // Turning `-A` on: the matches queued so far were queued untraced (9.6 traces a
        // match as it is queued, never later).
        let assertions_on = changes
            .iter()
            .any(|c| matches!(c, Change::Flag("assertions", true)));
        if assertions_on && !self.agent.settings.trace.assertions {
            self.agent.classify_new_matches();
        }
        let trace = &mut self.agent.settings.trace;
        let mut level = None;
        // What each flag was set to, reported in 9.6's order.
        let mut told: Vec<(&'static str, bool)> = Vec::new();
        let mut learning = None;
        let mut detail = None;
        for c in changes {
            match c {
                Change::Level(l) => level = Some(l),
                Change::Flag(name, on) => {
                    *flag_mut(trace, name) = on;
                    told.retain(|(n, _)| *n != name);
                    told.push((name, on));
                }
                Change::Learning(l) => learning = Some(l),
                Change::Detail(d) => {
                    trace.wme_detail = d;
                    detail = Some(d);
                }
                Change::None => {
                    *trace = TraceFlags::default();
                    self.agent.settings.learning_trace = 0;
                    told = FLAGS.iter().map(|f| (f.1, false)).collect();
                    learning = Some(0);
                    detail = Some(WmeDetail::None);
                }
            }
        }
        if let Some(l) = learning {
            self.agent.settings.learning_trace = l;
        }
        if let Some(l) = level {
            let trace = &mut self.agent.settings.trace;
            trace.set_level(l);
            if l == 0 {
                self.agent.settings.learning_trace = 0;
            }
            let mut s = String::new();
            for l in (if l == 0 { 0..=0 } else { 1..=l as usize }).rev() {
                s.push_str(LEVELS[l]);
                s.push('\n');
            }
            s.push_str("\nFor a full list of trace options, use 'trace' (no arguments)\n");
            return Ok(s);
        }
        let mut s = String::new();
        for (_, long, what) in FLAGS {
            if let Some((_, on)) = told.iter().find(|(n, _)| n == long) {
                s.push_str(on_off(*on));
                s.push_str(what);
                s.push('\n');
            }
        }
        if let Some(l) = learning {
            s.push_str(match l {
                0 => "Will not print any information about chunks or justifications learned.\n",
                1 => "Now printing the names of chunks and justifications that are learned and any chunking issues detected.\n",
                _ => "Now printing the full chunks and justifications that are learned and any chunking issues detected.\n",
            });
        }
        if let Some(d) = detail {
            s.push_str(match d {
                WmeDetail::None => "Will not print working memory element details.\n",
                WmeDetail::Timetags => "Will only print working memory element timetags.\n",
                WmeDetail::Full => "Will print the full working memory element.\n",
            });
        }
        s.push('\n');
        Ok(s)
    }
}

/// The listing of `trace` with no arguments.
fn trace_listing(t: &TraceFlags, learning: u8) -> String {
    fn header(text: &str, fill: char) -> String {
        let text = format!(" {text} ");
        let left = (60 - text.len()) / 2;
        let right = 60 - text.len() - left;
        format!(
            "{}{text}{}\n",
            fill.to_string().repeat(left),
            fill.to_string().repeat(right)
        )
    }
    fn row(name: &str, value: &str, flags: &str) -> String {
        format!("{name}{value:>w$}     {flags}\n", w = 60 - name.len())
    }
    let on = |b: bool| if b { "on" } else { "off" };
    let rule = "=".repeat(60);
    let mut s = format!("{rule}\n{:^60}\n{rule}\n", "Soar Trace Messages");
    // `{:^60}` puts the odd space on the right, as 9.6 does.
    s.push_str(&header("Level 1", '-'));
    s.push_str(&row(
        "Operator decisions and states",
        on(t.decisions),
        "-d, --decisions",
    ));
    s.push_str(&header("Level 2", '-'));
    for (name, b, flags) in [
        ("Phases", t.phases, "-p, --phases"),
        (
            "Chunking warnings",
            t.chunk_warnings,
            "-C, --chunk-warnings",
        ),
        ("State removals caused by GDS violation", t.gds, "-g, --gds"),
        (
            "State removals caused by operator consistency checks",
            t.consistency,
            "-o, --consistency",
        ),
    ] {
        s.push_str(&row(name, on(b), flags));
    }
    s.push_str(&header("Level 3: Rule firings", '-'));
    for (name, b, flags) in [
        ("Default rules", t.default_rules, "-D, --default"),
        ("User rules", t.user_rules, "-u, --user"),
        ("Chunks", t.chunks, "-c, --chunks"),
        ("Justifications", t.justifications, "-j, --justifications"),
        ("Templates", t.templates, "-T, --template"),
        (
            "Firings inhibited by higher-level firings",
            t.waterfall,
            "-W, --waterfall",
        ),
    ] {
        s.push_str(&row(name, on(b), flags));
    }
    s.push_str(&header("Level 4", '-'));
    s.push_str(&row("WME additions and removals", on(t.wmes), "-w, --wmes"));
    s.push_str(&header("Level 5", '-'));
    s.push_str(&row("Preferences", on(t.preferences), "-r, --preferences"));
    s.push_str(" \n");
    s.push_str(&header("Additional General Trace Messages", '-'));
    s.push_str(&row(
        "Assertions of rules and preferences",
        on(t.assertions),
        "-A, --assertions",
    ));
    s.push_str(&row(
        "Goal dependency set changes",
        on(t.gds_wmes),
        "-G, --gds-wmes",
    ));
    s.push_str(&row(
        "Numeric preference calculations",
        on(t.indifferent),
        "-i, --indifferent-selection",
    ));
    s.push_str(&row(
        "Reinforcement learning value updates",
        on(t.rl),
        "-R, --rl",
    ));
    s.push_str(&row(
        "WME Detail Level",
        match t.wme_detail {
            WmeDetail::None => "none",
            WmeDetail::Timetags => "timetag",
            WmeDetail::Full => "full detail",
        },
        "--nowmes, --timetags, --fullwmes",
    ));
    s.push_str(" \n");
    s.push_str(&header("Additional Chunking Trace Messages", '-'));
    s.push_str(&row(
        "Dependency analysis",
        on(t.backtracing),
        "-b, --backtracing",
    ));
    s.push_str(&row(
        "Rules learned (verbosity level)",
        match learning {
            0 => "none (0)",
            1 => "rule name (1)",
            _ => "full rules (2)",
        },
        "-L, --learning [0-2]",
    ));
    s.push_str(" \n");
    s.push_str(&header("Additional Memory System Trace Messages", '-'));
    s.push_str(&row(
        "Episodic memory recording and queries",
        on(t.epmem),
        "-e, --epmem",
    ));
    s.push_str(&row("Semantic memory additions", on(t.smem), "-s, --smem"));
    s.push_str(&row(
        "Working memory activation and forgetting",
        on(t.wma),
        "-a, --wma",
    ));
    s
}
