//! The `rl` command (Soar manual, ch. 9, `rl`): reinforcement learning's parameters (the
//! listing, `--get`, `--set`), statistics (`--stats`) and trace (`-t`), with 9.6's texts
//! and error messages.

use super::options::{self, opt};
use super::{CmdResult, Ctx, Interpreter};
use crate::rl::params::{number_text, SetError};

/// The statistics of `rl --stats`: name, and the label of the listing.
const STATS: [(&str, &str); 3] = [
    ("update-error", "Error from last update"),
    ("total-reward", "Total reward in last cycle"),
    ("global-reward", "Global reward since init"),
];

impl Interpreter {
    /// `rl`, `rl -g NAME`, `rl -s NAME VALUE`, `rl -S [STAT]`.
    pub(super) fn cmd_rl(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let specs = [
            opt('g', "get"),
            opt('s', "set"),
            opt('S', "stats"),
            opt('t', "trace"),
        ];
        let parsed = options::parse(args, &specs).map_err(|m| ctx.error(m))?;
        let words = &parsed.args;
        let Some((option, _)) = parsed.options.first() else {
            if !words.is_empty() {
                return Err(ctx.error("Invalid syntax."));
            }
            return Ok(self.agent.rl.params.listing());
        };
        if parsed.options.len() > 1 {
            return Err(ctx.error("rl takes only one option at a time."));
        }
        let count = |min, max| parsed.arg_count(min, max).map_err(|m| ctx.error(m));
        match *option {
            "get" => {
                count(1, 1)?;
                self.agent
                    .rl
                    .params
                    .get(&words[0])
                    .ok_or_else(|| ctx.error("Invalid setting."))
            }
            "set" => {
                count(2, 2)?;
                self.rl_set(ctx, &words[0], &words[1])
            }
            "stats" => {
                count(0, 1)?;
                let s = self.agent.rl.stats;
                let values = [s.update_error, s.total_reward, s.global_reward];
                match words.first() {
                    None => Ok(STATS
                        .iter()
                        .zip(values)
                        .map(|((_, label), v)| format!("{label}: {}\n", number_text(v)))
                        .collect()),
                    Some(w) => STATS
                        .iter()
                        .zip(values)
                        .find(|((name, _), _)| name == w)
                        .map(|(_, v)| number_text(v))
                        .ok_or_else(|| ctx.error("Invalid statistic.")),
                }
            }
            _ => {
                count(0, 2)?;
                self.rl_trace_command(ctx, words)
            }
        }
    }

    /// `rl -t [LEVEL]`, `rl -t print [LEVEL]`, `rl -t clear [LEVEL]`, `rl -t init [LEVEL]`,
    /// with 9.6's reading of levels (C's `atoi`: `x` is 0) and its messages.
    fn rl_trace_command(&mut self, ctx: &Ctx, words: &[String]) -> CmdResult {
        let level_of = |w: &String, what: &str| match super::settings::atoi(w) {
            l if l >= 1 => Ok(l as u32),
            _ => Err(ctx.error(format!("Invalid RL goal level for rl -t{what}."))),
        };
        let first = words.first().map(String::as_str);
        let second = words.get(1);
        match first {
            Some("clear") => {
                let level = second.map(|w| level_of(w, " clear")).transpose()?;
                self.agent.rl.trace.clear(level);
                Ok(String::new())
            }
            Some("init") => {
                let level = second.map(|w| level_of(w, " init")).transpose()?;
                self.agent.rl_trace_init(level);
                Ok(String::new())
            }
            _ => {
                let level = match (first, second) {
                    (None, _) => 1,
                    (Some("print"), None) => 1,
                    (Some("print"), Some(w)) => level_of(w, "")?,
                    (Some(_), Some(_)) => return Err(ctx.error("Invalid arguments to rl -t.")),
                    (Some(_), None) => level_of(&words[0], "")?,
                };
                let mut out = format!("# RL Trace, Goal Level {level}:\n");
                out.push_str(&self.agent.rl.trace.dot(level).unwrap_or_default());
                Ok(out)
            }
        }
    }

    /// `rl --set NAME VALUE`.
    fn rl_set(&mut self, ctx: &Ctx, name: &str, value: &str) -> CmdResult {
        match self.agent.rl.set_param(name, value) {
            Err(SetError::Name) => Err(ctx.error("Invalid setting.")),
            Err(SetError::Value) => Err(ctx.error("Invalid value for setting.")),
            Err(SetError::Protected) => Err(ctx.error("Failed to set value.")),
            Ok(()) => Ok(String::new()),
        }
    }
}
