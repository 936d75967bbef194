//! The `rl` command (Soar manual, ch. 9, `rl`): reinforcement learning's parameters (the
//! listing, `--get`, `--set`) and statistics (`--stats`), with 9.6's texts and error
//! messages. The parts of Soar-RL rusoar does not have answer with an error that names
//! them.

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
        let count = |min: usize, max: usize| {
            if words.len() < min {
                Err(ctx.error("Too few arguments."))
            } else if words.len() > max {
                Err(ctx.error("Too many arguments."))
            } else {
                Ok(())
            }
        };
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
            _ => Err(ctx.error(
                "rl --trace: the graph of RL updates is not yet supported by rusoar",
            )),
        }
    }

    /// `rl --set NAME VALUE`, refusing the values of the parts rusoar does not have.
    fn rl_set(&mut self, ctx: &Ctx, name: &str, value: &str) -> CmdResult {
        if name == "trace" && value == "on" {
            return Err(ctx.error(format!(
                "rl --set {name} {value}: the graph of RL updates (trace) is not yet supported by rusoar"
            )));
        }
        match self.agent.rl.set_param(name, value) {
            Err(SetError::Name) => Err(ctx.error("Invalid setting.")),
            Err(SetError::Value) => Err(ctx.error("Invalid value for setting.")),
            Err(SetError::Protected) => Err(ctx.error("Failed to set value.")),
            Ok(()) => Ok(String::new()),
        }
    }
}
