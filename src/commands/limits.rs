//! `limits`: rusoar's ceilings on a run's growth (not a 9.6 command; see
//! `crate::decide::limits`). With no option it lists them; each option sets one, 0 for none.

use super::options::{self, opt_arg};
use super::{CmdResult, Ctx, Interpreter};
use crate::source::Diagnostic;

impl Interpreter {
    pub(super) fn cmd_limits(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let specs = [
            opt_arg('w', "wmes"),
            opt_arg('t', "tokens"),
            opt_arg('p', "preferences"),
            opt_arg('c', "chunks"),
        ];
        let parsed = options::parse(args, &specs).map_err(|m| ctx.error(m))?;
        if !parsed.args.is_empty() {
            return Err(ctx.error(
                "Syntax: limits [-w|--wmes n] [-t|--tokens n] [-p|--preferences n] [-c|--chunks n]   (0: no ceiling)",
            ));
        }
        let mut limits = self.agent.settings.limits;
        for (long, value) in &parsed.options {
            let word = value.as_deref().unwrap_or_default();
            let n: u64 = word.parse().map_err(|_| {
                Diagnostic::error(format!(
                    "limits --{long} takes a whole number of 0 or more, not '{word}'."
                ))
                .at(ctx.cmd.span)
                .with_label("in this command")
            })?;
            match *long {
                "wmes" => limits.wmes = n,
                "tokens" => limits.tokens = n,
                "preferences" => limits.preferences = n,
                _ => limits.chunks = n,
            }
        }
        self.agent.settings.limits = limits;
        if !parsed.options.is_empty() {
            return Ok(String::new());
        }
        let shown = |n: u64| {
            if n == 0 {
                "none".to_string()
            } else {
                n.to_string()
            }
        };
        let rows = [
            ("wmes", limits.wmes, "WMEs in working memory"),
            ("tokens", limits.tokens, "partial matches in the matcher"),
            ("preferences", limits.preferences, "preferences in preference memory"),
            ("chunks", limits.chunks, "chunks learned in one run"),
        ];
        let mut text = String::from("=== Ceilings on a run ===");
        for (name, n, what) in rows {
            text.push_str(&format!("\n{name:<22}{:<12}{what}", shown(n)));
        }
        Ok(text)
    }
}
