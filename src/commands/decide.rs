//! `decide` (Soar manual, ch. 9, "decide"): the exploration policy and its parameters,
//! their automatic reduction, the numeric-indifferent mode, forcing and predicting the next
//! operator, and the random seed. Texts and ranges are the official kernel's (soar-sml
//! 9.6.5).

use super::on_off;
use super::options::{self, opt};
use super::{CmdResult, Ctx, Interpreter};
use crate::agent::{Exploration, Reduction, ReductionPolicy, Settings};
use crate::decide::procedure::NumericMode;
use crate::rhs::{c_fixed, c_general};
use crate::source::Diagnostic;

/// An exploration parameter of `indifferent-selection`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Parameter {
    Epsilon,
    Temperature,
}

impl Parameter {
    fn from_name(name: &str) -> Option<Self> {
        match name {
            "epsilon" => Some(Parameter::Epsilon),
            "temperature" => Some(Parameter::Temperature),
            _ => None,
        }
    }


    fn value(self, s: &mut Settings) -> &mut f64 {
        match self {
            Parameter::Epsilon => &mut s.epsilon,
            Parameter::Temperature => &mut s.temperature,
        }
    }

    fn reduction(self, s: &mut Settings) -> &mut Reduction {
        match self {
            Parameter::Epsilon => &mut s.epsilon_reduction,
            Parameter::Temperature => &mut s.temperature_reduction,
        }
    }

    /// Epsilon is a probability; the temperature any positive number.
    fn accepts(self, v: f64) -> bool {
        match self {
            Parameter::Epsilon => (0.0..=1.0).contains(&v),
            Parameter::Temperature => v > 0.0 && v.is_finite(),
        }
    }
}

impl Interpreter {
    pub(super) fn cmd_decide(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        match args.first().map(String::as_str) {
            None => Ok(decide_summary(&self.agent.settings)),
            Some("?" | "help") => Ok(DECIDE_USAGE.to_string()),
            Some("indifferent-selection") => self.indifferent_selection(ctx, &args[1..]),
            Some("numeric-indifferent-mode") => self.numeric_indifferent_mode(ctx, &args[1..]),
            // `set-random-seed` is 9.6's long name of `srand`.
            Some("srand" | "set-random-seed") => self.set_random_seed(ctx, args.get(1)),
            Some("select") => Ok(self.select_operator(args.get(1))),
            Some("predict") => Ok(format!("{}\n", self.agent.predict_decision())),
            Some(_) => Err(ctx.error(
                "Invalid decide command.  Use 'decide ?' to see a list of valid settings.",
            )),
        }
    }

    /// `decide select [ID]`: forces the next decision's operator, or shows the forced one.
    fn select_operator(&mut self, id: Option<&String>) -> String {
        let forced = &mut self.agent.decider.forced_operator;
        match id {
            None => match forced {
                Some(op) => format!("{op}\n"),
                None => "No operator selected.\n".to_string(),
            },
            Some(id) => {
                // 9.6 keeps the text with its first letter upper-cased, as an id prints.
                let mut chars = id.chars();
                let first = chars.next().map(|c| c.to_ascii_uppercase());
                *forced = Some(first.into_iter().chain(chars).collect());
                format!("Operator {id} will be selected.\n")
            }
        }
    }

    fn indifferent_selection(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let mut rest = args.to_vec();
        if let Some(pos) = rest.iter().position(|a| a == "-random") {
            self.warn(
                Diagnostic::warning(
                    "Soar 8 spelling `indifferent-selection -random`: Soar 9.6 has no such policy; its default softmax is already uniform over plain indifferent operators",
                )
                .at(ctx.cmd.span)
                .with_label("read as `indifferent-selection --softmax`"),
            );
            rest[pos] = "--softmax".into();
        }
        // Options take their values as positional words: alone, a parameter is shown.
        let specs = [
            opt('b', "boltzmann"),
            opt('g', "epsilon-greedy"),
            opt('f', "first"),
            opt('l', "last"),
            opt('x', "softmax"),
            opt('e', "epsilon"),
            opt('t', "temperature"),
            opt('p', "reduction-policy"),
            opt('r', "reduction-rate"),
            opt('a', "auto-reduce"),
            opt('s', "stats"),
        ];
        let parsed = options::parse(&rest, &specs).map_err(|m| ctx.error(m))?;
        let s = &mut self.agent.settings;
        let option = match parsed.options.as_slice() {
            [] => return Ok(format!("{}\n", s.exploration.name())),
            [(o, _)] => *o,
            _ => {
                return Err(ctx.error("indifferent-selection takes only one option at a time."))
            }
        };
        let words = &parsed.args;
        let invalid = || ctx.error("Invalid parameter value.");
        let number = |i: usize| words.get(i).map(|w| w.parse::<f64>().map_err(|_| invalid()));
        match option {
            "epsilon" | "temperature" => {
                let p = Parameter::from_name(option).ok_or_else(invalid)?;
                match number(0).transpose()? {
                    None => Ok(format!("{}\n", c_general(*p.value(s), 16))),
                    Some(v) if p.accepts(v) => {
                        *p.value(s) = v;
                        Ok(String::new())
                    }
                    Some(_) => Err(invalid()),
                }
            }
            "reduction-policy" => {
                let p = parameter(ctx, words.first())?;
                match words.get(1) {
                    None => Ok(format!("{}\n", p.reduction(s).policy.name())),
                    Some(name) => {
                        p.reduction(s).policy =
                            ReductionPolicy::from_name(name).ok_or_else(invalid)?;
                        Ok(String::new())
                    }
                }
            }
            "reduction-rate" => {
                let p = parameter(ctx, words.first())?;
                let policy = words
                    .get(1)
                    .ok_or_else(|| ctx.error("Too few arguments."))?;
                let policy = ReductionPolicy::from_name(policy).ok_or_else(invalid)?;
                let reduction = p.reduction(s);
                let rate = match policy {
                    ReductionPolicy::Exponential => &mut reduction.exponential_rate,
                    ReductionPolicy::Linear => &mut reduction.linear_rate,
                };
                match number(2).transpose()? {
                    None => Ok(format!("{}\n", c_general(*rate, 16))),
                    Some(v) => {
                        let ok = match policy {
                            ReductionPolicy::Exponential => (0.0..=1.0).contains(&v),
                            ReductionPolicy::Linear => v >= 0.0 && v.is_finite(),
                        };
                        if !ok {
                            return Err(invalid());
                        }
                        *rate = v;
                        Ok(String::new())
                    }
                }
            }
            "auto-reduce" => match words.first().map(String::as_str) {
                None => Ok(format!("{}\n", on_off(s.auto_reduce))),
                Some("on") => {
                    s.auto_reduce = true;
                    Ok(String::new())
                }
                Some("off") => {
                    s.auto_reduce = false;
                    Ok(String::new())
                }
                Some(_) => Err(invalid()),
            },
            "stats" => Ok(exploration_stats(s)),
            policy => {
                s.exploration = Exploration::from_name(policy).unwrap_or(s.exploration);
                Ok(String::new())
            }
        }
    }

    fn numeric_indifferent_mode(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let specs = [opt('a', "avg"), opt('s', "sum")];
        let parsed = options::parse(args, &specs).map_err(|m| ctx.error(m))?;
        let mut mode = None;
        for (o, _) in &parsed.options {
            mode = match *o {
                "avg" => Some(NumericMode::Avg),
                "sum" => Some(NumericMode::Sum),
                _ => mode,
            };
        }
        match mode {
            Some(m) => {
                self.agent.settings.numeric_mode = m;
                Ok(String::new())
            }
            None => Ok(match self.agent.settings.numeric_mode {
                NumericMode::Sum => {
                    "Current numeric indifferent mode: Soar will use the sum of numeric preferences.\n"
                }
                NumericMode::Avg => {
                    "Current numeric indifferent mode: Soar will average numeric preferences.\n"
                }
            }
            .to_string()),
        }
    }

    fn set_random_seed(&mut self, ctx: &Ctx, seed: Option<&String>) -> CmdResult {
        let seed = match seed {
            Some(s) => s.parse::<u32>().map_err(|_| {
                Diagnostic::error(format!("Integer expected: {s}"))
                    .at(ctx.arg_span(1))
                    .with_label("not a seed")
            })?,
            None => {
                // No seed: a new random one, as 9.6 does (from the clock).
                let now = std::time::SystemTime::now()
                    .duration_since(std::time::UNIX_EPOCH)
                    .map(|d| d.as_nanos())
                    .unwrap_or(0);
                let seed = (now ^ (now >> 32)) as u32;
                self.agent.seed = Some(seed);
                self.agent.rng.seed(seed);
                return Ok("Random number generator seed set to new random value.\n".into());
            }
        };
        self.agent.seed = Some(seed);
        self.agent.rng.seed(seed);
        Ok(format!("Random number generator seed set to {seed}\n"))
    }
}

/// The parameter named by `word` (`epsilon` or `temperature`).
fn parameter(ctx: &Ctx, word: Option<&String>) -> Result<Parameter, Diagnostic> {
    let word = word.ok_or_else(|| ctx.error("Too few arguments."))?;
    Parameter::from_name(word).ok_or_else(|| ctx.error("Invalid parameter value."))
}


/// `indifferent-selection --stats`.
fn exploration_stats(s: &Settings) -> String {
    let mut out = format!(
        "Exploration Policy: {}\nAutomatic Policy Parameter Reduction: {}\n\n",
        s.exploration.name(),
        on_off(s.auto_reduce)
    );
    for (name, value, r) in [
        ("epsilon", s.epsilon, &s.epsilon_reduction),
        ("temperature", s.temperature, &s.temperature_reduction),
    ] {
        out.push_str(&format!(
            "{name}: {}\n{name} Reduction Policy: {}\n{name} Reduction Rate (exponential/linear): {}/{}\n\n",
            c_general(value, 16),
            r.policy.name(),
            c_general(r.exponential_rate, 16),
            c_general(r.linear_rate, 16),
        ));
    }
    out
}

/// `decide` with no arguments: a label on the left, its value right-aligned to the rule.
fn decide_summary(s: &Settings) -> String {
    let rule = "=".repeat(55);
    let line = "-".repeat(55);
    let row = |label: &str, value: &str| format!("{label}{value:>w$}\n", w = 55 - label.len());
    let mode = match s.numeric_mode {
        NumericMode::Sum => "sum",
        NumericMode::Avg => "average",
    };
    let mut out = format!("{rule}\n{:>35}\n{rule}\n", "Decide Summary");
    out.push_str(&row("Numeric indifference mode:", mode));
    out.push_str(&format!("{line}\n"));
    out.push_str(&row("Exploration Policy:", s.exploration.name()));
    out.push_str(&row(
        "Automatic Policy Parameter Reduction:",
        on_off(s.auto_reduce),
    ));
    out.push_str(&row("Epsilon:", &c_fixed(s.epsilon, 6)));
    out.push_str(&row(
        "Epsilon Reduction Policy:",
        s.epsilon_reduction.policy.name(),
    ));
    out.push_str(&row("Temperature:", &c_fixed(s.temperature, 6)));
    out.push_str(&row(
        "Temperature Reduction Policy:",
        s.temperature_reduction.policy.name(),
    ));
    out.push_str(&format!(
        "{line}\n\nUse 'decide ?' for a command overview or 'help decide' for the manual page.\n"
    ));
    out
}

/// `decide ?`: the sub-commands and their options.
const DECIDE_USAGE: &str = "\
=============================================================================
-                      Decide Sub-Commands and Options                      -
=============================================================================
decide                           [? | help]
-----------------------------------------------------------------------------
decide numeric-indifferent-mode  [--avg --sum]
-----------------------------------------------------------------------------
decide indifferent-selection
decide indifferent-selection     <policy>
                                 <policy> = [--boltzmann | --epsilon-greedy |
                                             --first | --last | -- softmax ]
decide indifferent-selection     <param> [value]
                                 <param> = [--epsilon --temperature]
decide indifferent-selection     [--reduction-policy | -p] <param> [<policy>]
decide indifferent-selection     [--reduction-rate | -r] <param> <policy> [<rate>]
decide indifferent-selection     [--auto-reduce] [setting]
decide indifferent-selection     [--stats]
-----------------------------------------------------------------------------
decide predict
decide select                    <operator ID>
-----------------------------------------------------------------------------
decide set-random-seed           [<seed>] 
-----------------------------------------------------------------------------

For a detailed explanation of sub-commands:    help decide
";
