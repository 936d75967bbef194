//! `wm activation` (Soar manual, ch. 9, `wm`; ch. 8, "Working Memory Activation"): the
//! settings of working-memory activation (the listing, `--get`, `--set`), its statistics
//! (`--stats`) and a WME's reference history (`--history`), with 9.6's texts and errors.

use super::options::{self, opt, opt_arg};
use super::{CmdResult, Ctx, Interpreter};
use crate::wma::params::SetError;

impl Interpreter {
    /// `wm activation`, `-g NAME`, `-s NAME VALUE`, `-S [STAT]`, `-h TIMETAG`.
    pub(super) fn cmd_wm_activation(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        // 9.6 reads `-t` (timers) with an argument it calls `type`, and knows no long name
        // for it.
        if let Some(long) = args.iter().find_map(|a| a.strip_prefix("--")) {
            if !long.is_empty() && ["history", "get", "set", "stats"].iter().all(|o| !o.starts_with(long)) {
                return Err(ctx.error(format!("No such option: {long}")));
            }
        }
        let specs = [
            opt('g', "get"),
            opt('h', "history"),
            opt('s', "set"),
            opt('S', "stats"),
            opt_arg('t', "type"),
        ];
        let parsed = options::parse(args, &specs).map_err(|m| ctx.error(m))?;
        let words = &parsed.args;
        let Some((option, _)) = parsed.options.first() else {
            if !words.is_empty() {
                return Err(ctx.error("Too many args."));
            }
            return Ok(self.agent.wma.params.listing());
        };
        if parsed.options.len() > 1 {
            return Err(ctx.error("wm activation takes only one option at a time."));
        }
        let count = |min, max| parsed.arg_count(min, max).map_err(|m| ctx.error(m));
        let wma = &mut self.agent.wma;
        match *option {
            "get" => {
                count(1, 1)?;
                wma.params
                    .get(&words[0])
                    .ok_or_else(|| ctx.error("Invalid activation setting."))
            }
            "set" => {
                count(2, 2)?;
                match wma.params.set(&words[0], &words[1]) {
                    Ok(()) => {
                        wma.sync();
                        // Freed preferences are logged only while activation sets exist.
                        let on = self.agent.wma.on();
                        self.agent.decider.log_freed_prefs = on;
                        if !on {
                            self.agent.decider.freed_prefs_log.clear();
                        }
                        Ok(String::new())
                    }
                    Err(SetError::Name) => Err(ctx.error("Invalid activation setting.")),
                    Err(SetError::Value) => {
                        Err(ctx.error("Invalid value for activation setting."))
                    }
                    Err(SetError::Protected) => Err(ctx.error(
                        "ERROR: this parameter is protected while WMA is on.",
                    )),
                }
            }
            "stats" => {
                count(0, 1)?;
                match words.first().map(String::as_str) {
                    None => Ok(format!("Forgotten WMEs: {}\n", wma.forgotten)),
                    Some("forgotten-wmes") => Ok(wma.forgotten.to_string()),
                    Some(_) => Err(ctx.error("Invalid statistic.")),
                }
            }
            "history" => {
                count(1, 1)?;
                let tt = stream_timetag(&words[0])
                    .filter(|&t| t != 0)
                    .ok_or_else(|| ctx.error("Invalid timetag."))?;
                if self.agent.wm.by_timetag(tt).is_none() {
                    return Ok(String::new());
                }
                let now = self.agent.decider.d_cycle_count;
                Ok(self.agent.wma.history_text(tt, now))
            }
            // 9.6 has no timers to show here.
            _ => Err(ctx.error("Invalid timer.")),
        }
    }
}

/// A timetag read as a C++ stream reads a `uint64_t`: the leading digits (a `-` wraps
/// around, as the stream does); `None` without digits or when it overflows.
fn stream_timetag(text: &str) -> Option<u64> {
    let (neg, rest) = match text.as_bytes().first() {
        Some(b'-') => (true, &text[1..]),
        Some(b'+') => (false, &text[1..]),
        _ => (false, text),
    };
    let end = rest
        .bytes()
        .position(|b| !b.is_ascii_digit())
        .unwrap_or(rest.len());
    let v: u64 = rest[..end].parse().ok()?;
    Some(if neg { v.wrapping_neg() } else { v })
}

#[cfg(test)]
mod tests {
    use super::stream_timetag;

    #[test]
    fn timetags_read_as_a_cpp_stream_reads_them() {
        assert_eq!(stream_timetag("3x"), Some(3));
        assert_eq!(stream_timetag("+3"), Some(3));
        assert_eq!(stream_timetag("1.5"), Some(1));
        assert_eq!(stream_timetag("-1"), Some(u64::MAX));
        assert_eq!(stream_timetag("abc"), None);
        assert_eq!(stream_timetag("99999999999999999999999"), None);
    }
}
