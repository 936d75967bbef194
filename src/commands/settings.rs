//! Settings commands: `learn` (with Soar 8 spellings), `chunk`, `soar`, `trace`, `decide`,
//! `output`, `alias` (Soar manual, ch. 9).

use super::options::{self, opt};
use super::{CmdResult, Ctx, Interpreter};
use crate::agent::LearnMode;
use crate::decide::state::Phase;
use crate::source::Diagnostic;

/// Soar 8 single-dash words and their 9.6 spellings.
const LEARN_SOAR8: &[(&str, &str)] = &[
    ("-off", "--off"),
    ("-on", "--on"),
    ("-only", "--only"),
    ("-except", "--except"),
    ("-list", "--list"),
    ("-all-levels", "--all-levels"),
    ("-bottom-up", "--bottom-up"),
];

impl Interpreter {
    /// The deprecated `learn` command. Soar 8's `learn -off` is accepted with a warning
    /// (9.6 reads it as `-o -f -f` and aborts the load).
    pub(super) fn cmd_learn(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let mut args = args.to_vec();
        let soar8_except = args.iter().any(|a| a == "-except");
        for (i, a) in args.iter_mut().enumerate() {
            if let Some((old, new)) = LEARN_SOAR8.iter().find(|(old, _)| a == old) {
                let nine_six = match *new {
                    "--off" => "chunk never",
                    "--on" => "chunk always",
                    "--only" => "chunk only",
                    "--except" => "chunk except",
                    _ => "chunk",
                };
                self.warn(
                    Diagnostic::warning(format!(
                        "Soar 8 spelling `learn {old}`: Soar 9.6 reads it as a cluster of one-letter options and rejects it; read as `learn {new}` (9.6: `{nine_six}`)"
                    ))
                    .at(ctx.arg_span(i))
                    .with_label(format!("Soar 9.6 spelling: {nine_six}")),
                );
                *a = new.to_string();
            }
        }
        let specs = [
            opt('a', "all-levels"),
            opt('b', "bottom-up"),
            opt('d', "disable"),
            super::options::long_only("off"),
            opt('e', "enable"),
            super::options::long_only("on"),
            opt('E', "except"),
            opt('l', "list"),
            opt('o', "only"),
            opt('n', "local-negations"),
            opt('N', "no-local-negations"),
            opt('p', "desirability-prefs"),
            opt('P', "no-desirability-prefs"),
        ];
        let parsed = options::parse(&args, &specs).map_err(|m| ctx.error(m))?;
        // 9.6 passes `--except` on as a setting `chunk` rejects; Soar 8's `-except` meant
        // `chunk except`, which is what it gets.
        if parsed.has("except") && !soar8_except {
            return Err(ctx.error(
                "Invalid argument for chunking command. Use 'chunk ?' to see a list of valid settings.",
            ));
        }
        let deprecated = |chunk: &str| {
            format!("Warning:  'learn' has been deprecated.  New corresponding command is: chunk{chunk}\n")
        };
        // 9.6 applies the given modes in a fixed order, whatever the order on the line
        // (`learn -de` and `learn -ed` both end "never"), reporting each one.
        let mut text = String::new();
        for (names, mode) in [
            (&["only"][..], LearnMode::Only),
            (&["except"][..], LearnMode::Except),
            (&["enable", "on"][..], LearnMode::Always),
            (&["disable", "off"][..], LearnMode::Never),
        ] {
            if names.iter().any(|n| parsed.has(n)) {
                self.agent.settings.learn = mode;
                text.push_str(&format!("learn is now {}\n", mode.word()));
                text.push_str(&deprecated(&format!(" {}", mode.word())));
            }
        }
        // The other options become `chunk` settings; 9.6 echoes only some of them.
        let c = &mut self.agent.settings.chunk;
        for (option, switch, on, echoed) in [
            ("all-levels", "bottom-only", false, true),
            ("bottom-up", "bottom-only", true, true),
            ("local-negations", "allow-local-negations", true, true),
            ("no-local-negations", "allow-local-negations", false, false),
            ("desirability-prefs", "add-osk", true, false),
            ("no-desirability-prefs", "add-osk", false, false),
        ] {
            if !parsed.has(option) {
                continue;
            }
            if let Some(slot) = c.switch(switch) {
                *slot = on;
            }
            let word = if on { "on" } else { "off" };
            if echoed {
                text.push_str(&format!("{switch} is now {word}\n"));
            }
            text.push_str(&deprecated(&format!(" {switch} {word}")));
        }
        if text.is_empty() {
            // `learn` and `learn --list`: the chunking summary.
            let mut summary = super::chunk_listing::summary(&self.agent);
            summary.push_str(&deprecated(""));
            return Ok(summary);
        }
        Ok(text)
    }
    pub(super) fn cmd_soar(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let s = &mut self.agent.settings;
        match args.first().map(String::as_str) {
            Some("max-elaborations") => match args.get(1) {
                // 9.6 reads the value with atoi: `max-elaborations lots` sets 0, silently.
                Some(v) if v.parse::<i64>().is_err() => {
                    let n = atoi(v);
                    self.warn(
                        Diagnostic::warning(format!(
                            "max-elaborations: `{v}` is not an integer; Soar 9.6 reads it as {n}"
                        ))
                        .at(ctx.arg_span(1))
                        .with_label(format!("read as {n}")),
                    );
                    let s = &mut self.agent.settings;
                    s.max_elaborations = n;
                    Ok(format!(
                        "The maximum number of elaborations in a phase is now {n}.\n"
                    ))
                }
                _ => int_setting(
                    ctx,
                    &args[1..],
                    "max-elaborations",
                    &mut s.max_elaborations,
                    SOAR_INVALID,
                    |n| format!("The maximum number of elaborations in a phase is now {n}.\n"),
                ),
            },
            Some("max-goal-depth") => int_setting(
                ctx,
                &args[1..],
                "max-goal-depth",
                &mut s.max_goal_depth,
                SOAR_INVALID,
                |n| format!("The maximum goal depth is now {n}.\n"),
            ),
            Some("max-nil-output-cycles") => int_setting(
                ctx,
                &args[1..],
                "max-nil-output-cycles",
                &mut s.max_nil_output_cycles,
                SOAR_INVALID,
                |n| format!("The maximum number of decision cycles without output before interrupting is now {n}.  (used with run --output)\n"),
            ),
            Some("wait-snc") => {
                match args.get(1).map(String::as_str) {
                    None => Ok(format!(
                        "wait-snc is {}\n",
                        if s.wait_snc { "on" } else { "off" }
                    )),
                    Some("on") => {
                        s.wait_snc = true;
                        Ok("Soar will now wait instead of impassing when a state doesn't change.\n".into())
                    }
                    Some("off") => {
                        s.wait_snc = false;
                        Ok("Soar will now impasse when a state doesn't change.\n".into())
                    }
                    Some(_) => Err(Diagnostic::error(SOAR_INVALID)
                        .at(ctx.arg_span(1))
                        .with_label("expected on or off")),
                }
            }
            Some("timers") => on_off_soar(
                ctx,
                args.get(1),
                &mut s.timers,
                "timers",
                ["Timers are now enabled.", "Timers are now disabled."],
            ),
            Some("keep-all-top-oprefs") => on_off_soar(
                ctx,
                args.get(1),
                &mut s.keep_all_top_oprefs,
                "keep-all-top-oprefs",
                [
                    "Soar will now always retain top level preferences for items that are already o-supported.",
                    "Soar will now not retain top level preferences for items that are already o-supported.",
                ],
            ),
            Some("stop-phase") => match args.get(1).map(String::as_str) {
                None => Ok(format!("Stop before {}\n", phase_name(s.stop_phase))),
                Some(name) => {
                    // 9.6 cannot stop before the decision phase.
                    let phase = [Phase::Input, Phase::Propose, Phase::Apply, Phase::Output]
                        .into_iter()
                        .find(|&p| phase_name(p) == name)
                        .ok_or_else(|| ctx.error(SOAR_INVALID))?;
                    s.stop_phase = phase;
                    Ok(format!("Soar will now stop before the {name} phase.\n"))
                }
            },
            Some("max-dc-time") => match args.get(1) {
                None => Ok(format!("max-dc-time is {}\n", s.max_dc_time)),
                Some(v) => match atoi(v) {
                    n if n < 0 => Err(ctx.error(SOAR_INVALID)),
                    0 => {
                        s.max_dc_time = 0;
                        // 9.6's text, its doubled word included.
                        Ok("Soar will no longer interrupt based on how how long a decision takes. (default)\n".into())
                    }
                    n => {
                        s.max_dc_time = n;
                        Ok(format!("Soar will now interrupt decisions after {n} seconds.\n"))
                    }
                },
            },
            Some("max-memory-usage") => match args.get(1) {
                None => Ok(format!("max-memory-usage is {}\n", s.max_memory_usage)),
                Some(v) => {
                    s.max_memory_usage = positive_atoi(ctx, v)?;
                    Ok(format!(
                        "Soar will now interrupt execution if more than {} bytes of memory are used.  (This requires a special build of Soar.  See manual for more information.)\n",
                        s.max_memory_usage
                    ))
                }
            },
            Some("max-gp") => match args.get(1) {
                None => Ok(format!("max-gp is {}\n", s.max_gp)),
                Some(v) => {
                    s.max_gp = positive_atoi(ctx, v)?;
                    Ok(format!(
                        "The maximum number of rules gp can generate is now {}.\n",
                        s.max_gp
                    ))
                }
            },
            // rusoar has no Tcl interpreter; 9.6 without its Tcl library answers the same.
            Some("tcl") => match args.get(1).map(String::as_str) {
                None => Ok("tcl is off\n".into()),
                Some("off") => Ok("Tcl mode is already off.\n".into()),
                Some("on") => Err(ctx.error("Could not load library tclsoarlib: Library not found.")),
                Some(_) => Err(ctx.error(SOAR_INVALID)),
            },
            Some("init") => self.cmd_init(),
            Some("stop") => {
                self.agent.decider.stop_requested = true;
                Ok(String::new())
            }
            Some("version") => Ok(format!(
                "rusoar {} (Soar 9.6 semantics)\n",
                env!("CARGO_PKG_VERSION")
            )),
            None => Ok(self.soar_summary()),
            Some("?") => Ok(self.soar_settings()),
            Some(_) => Err(super::not_yet(ctx, "soar")),
        }
    }

    /// `soar` with no arguments: 9.6's summary of the agent (rows 55 columns wide).
    fn soar_summary(&self) -> String {
        let a = &self.agent;
        let row = |label: &str, value: &str| format!("{label}{value:>w$}\n", w = 55 - label.len());
        let rule = "-".repeat(55);
        let states: Vec<String> = if a.decider.goals.is_empty() {
            vec![a.symbols.text(a.top.state)]
        } else {
            a.decider
                .goals
                .iter()
                .map(|g| a.symbols.text(g.state))
                .collect()
        };
        let phase = phase_name(a.decider.phase.unwrap_or(Phase::Input));
        let mut s = format!(
            "{eq}\n-{:^53}-\n{eq}\n",
            format!("rusoar {} Summary", env!("CARGO_PKG_VERSION")),
            eq = "=".repeat(55)
        );
        s.push_str(&row("Enabled:", "Core"));
        s.push_str(&row("Disabled:", "EBC, SMem, EpMem, SVS, RL, WMA, SSA"));
        s.push_str(&format!("{rule}\n"));
        s.push_str(&row("Number of rules:", &a.production_count().to_string()));
        s.push_str(&row("Number of chunks:", "0"));
        s.push_str(&row("Decisions", &a.decider.d_cycle_count.to_string()));
        s.push_str(&row("Elaborations", &a.decider.e_cycles.to_string()));
        s.push_str(&format!("{rule}\n"));
        // 9.6 shows a stack of more than four states by its two ends.
        let stack = match states.as_slice() {
            [a, b, .., y, z] if states.len() > 4 => format!("{a}, {b} ... {y}, {z}"),
            all => all.join(", "),
        };
        s.push_str(&row("State stack", &stack));
        s.push_str(&row("Current number of states", &states.len().to_string()));
        s.push_str(&row("Next phase", phase));
        s.push_str(&format!("{rule}\n\n"));
        s.push_str("Use 'soar ?' for a command overview or 'help soar' for the manual page.");
        s
    }

    /// `soar ?`: the sub-commands and the settings with their values, as 9.6 lists them.
    fn soar_settings(&self) -> String {
        let st = &self.agent.settings;
        let on_off = |b: bool| if b { "on" } else { "off" };
        let mut s = String::from("====== Soar General Commands and Settings =====\n");
        for (cmd, what) in [
            ("soar ?", "Print this help listing"),
            ("soar init", "Re-initializes current state of Soar"),
            ("soar stop [--self]", "Stop Soar execution"),
            ("soar version", "Print version number of Soar"),
        ] {
            s.push_str(&format!("{cmd:<51}{what}\n"));
        }
        s.push_str("----------------- Settings --------------------\n");
        for (name, value, what) in [
            (
                "keep-all-top-oprefs",
                on_off(st.keep_all_top_oprefs).to_string(),
                "Keep all preferences for o-supported WMEs on top state",
            ),
            (
                "max-elaborations",
                st.max_elaborations.to_string(),
                "Maximum elaboration in a decision cycle",
            ),
            (
                "max-goal-depth",
                st.max_goal_depth.to_string(),
                "Halt if goal stack reaches this depth",
            ),
            (
                "max-nil-output-cycles",
                st.max_nil_output_cycles.to_string(),
                "Impasse after this many nil outputs (run --out)",
            ),
            (
                "max-dc-time",
                st.max_dc_time.to_string(),
                "Interrupt decision after this much time",
            ),
            (
                "max-memory-usage",
                st.max_memory_usage.to_string(),
                "Threshold for memory warning (see help)",
            ),
            (
                "max-gp",
                st.max_gp.to_string(),
                "Maximum rules gp can generate",
            ),
            (
                "stop-phase",
                phase_name(st.stop_phase).into(),
                "Phase before which Soar will stop",
            ),
            ("tcl", "off".into(), "Allow Tcl code in commands"),
            (
                "timers",
                on_off(st.timers).into(),
                "Profile where Soar spends its time",
            ),
            (
                "wait-snc",
                on_off(st.wait_snc).into(),
                "Wait instead of impasse after state-no-change",
            ),
        ] {
            s.push_str(&format!(
                "{name}{value:>w$}    {what}\n",
                w = 47 - name.len()
            ));
        }
        s.push_str("-----------------------------------------------\n\n");
        s.push_str("To change a setting:                               soar <setting> [<value>]\n");
        s.push_str("For a detailed explanation of these settings:      help soar\n");
        s
    }

    pub(super) fn cmd_alias(&mut self, args: &[String]) -> CmdResult {
        match args {
            [] => Ok(self.aliases.listing()),
            // 9.6 removes or shows an alias that does not exist without a word.
            [flag, name] if flag == "-r" || flag == "--remove" => {
                self.aliases.remove(name);
                Ok(String::new())
            }
            [name] => match self.aliases.get(name) {
                // One alias is shown with its expansion quoted (9.6: `d = "run -d"`).
                Some(exp) => Ok(format!("{name} = \"{}\"\n", exp.join(" "))),
                None => Ok(String::new()),
            },
            [name, rest @ ..] => {
                self.aliases.set(name, rest.to_vec());
                Ok(String::new())
            }
        }
    }
}

/// Soar's message for a bad value of a `soar` setting.
const SOAR_INVALID: &str = "Invalid argument. Use 'soar ?' to see a list of valid settings.";

/// A setting's value read with `atoi`, which must be positive.
fn positive_atoi(ctx: &Ctx, v: &str) -> Result<i64, Diagnostic> {
    match atoi(v) {
        n if n > 0 => Ok(n),
        _ => Err(ctx.error(SOAR_INVALID)),
    }
}

/// An on/off setting of `soar`: shown as `NAME is on`, set with 9.6's messages.
fn on_off_soar(
    ctx: &Ctx,
    value: Option<&String>,
    slot: &mut bool,
    name: &str,
    [on, off]: [&str; 2],
) -> CmdResult {
    match value.map(String::as_str) {
        None => Ok(format!("{name} is {}\n", if *slot { "on" } else { "off" })),
        Some("on") => {
            *slot = true;
            Ok(format!("{on}\n"))
        }
        Some("off") => {
            *slot = false;
            Ok(format!("{off}\n"))
        }
        Some(_) => Err(ctx.error(SOAR_INVALID)),
    }
}

/// A phase's name as `soar` prints it.
fn phase_name(p: Phase) -> &'static str {
    match p {
        Phase::Input => "input",
        Phase::Propose => "propose",
        Phase::Decide => "decide",
        Phase::Apply => "apply",
        Phase::Output => "output",
    }
}

/// C's `atoi`: optional blanks and sign, then digits; anything else ends the number.
pub(super) fn atoi(s: &str) -> i64 {
    let t = s.trim_start();
    let (neg, digits) = match t.as_bytes().first() {
        Some(b'-') => (true, &t[1..]),
        Some(b'+') => (false, &t[1..]),
        _ => (false, t),
    };
    let mut n: i64 = 0;
    for b in digits.bytes().take_while(u8::is_ascii_digit) {
        n = n.saturating_mul(10).saturating_add(i64::from(b - b'0'));
    }
    if neg {
        -n
    } else {
        n
    }
}

/// `setting [N]`: shows or sets a non-negative integer setting; `invalid` is Soar's message
/// for a value that is not one.
pub(super) fn int_setting(
    ctx: &Ctx,
    args: &[String],
    name: &str,
    slot: &mut i64,
    invalid: &str,
    msg: impl Fn(i64) -> String,
) -> CmdResult {
    match args.first() {
        None => Ok(format!("{name} is {slot}\n")),
        Some(v) => match v.parse::<i64>() {
            Ok(n) if n > 0 => {
                *slot = n;
                Ok(msg(n))
            }
            _ => Err(Diagnostic::error(invalid)
                .at(ctx.cmd.words.last().map(|w| w.span).unwrap_or(ctx.cmd.span))
                .with_label(format!("{name} wants a positive integer"))),
        },
    }
}

