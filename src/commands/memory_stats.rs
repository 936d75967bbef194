//! The statistics and timers listings of the long-term memories' commands (`smem --stats`,
//! `epmem --timers`, ...): a 40-column banner, then one `label: value` row each, or one
//! value when a name is given, with 9.6's errors for an unknown name.

use super::{CmdResult, Ctx};
use crate::memory_timers::MemoryTimers;
use crate::printer::constants::c_general;

/// A 40-column row: `label:` and the value right-aligned.
pub(super) fn row40(label: &str, value: &str) -> String {
    let width = 40usize.saturating_sub(label.len() + 1);
    format!("{label}:{value:>width$}\n")
}

/// A banner: the title centred in 40 columns between two rules.
pub(super) fn banner(title: &str) -> String {
    let left = 40usize.saturating_sub(title.len()) / 2;
    let right = 40usize.saturating_sub(title.len() + left);
    let rule = "=".repeat(40);
    format!(
        "{rule}\n{}{title}{}\n{rule}\n",
        " ".repeat(left),
        " ".repeat(right)
    )
}

/// `--stats [NAME]`: `stats` pairs each name with its label, `values` in the same order.
pub(super) fn stats_answer(
    ctx: &Ctx,
    title: &str,
    stats: &[(&str, &str)],
    values: &[String],
    which: Option<&String>,
) -> CmdResult {
    match which {
        None => {
            let mut s = banner(title);
            for ((_, label), v) in stats.iter().zip(values) {
                s.push_str(&row40(label, v));
            }
            Ok(s)
        }
        Some(w) => stats
            .iter()
            .zip(values)
            .find(|((name, _), _)| name == w)
            .map(|(_, v)| format!(" {v}"))
            .ok_or_else(|| ctx.error("Invalid statistic.")),
    }
}

/// `--timers [NAME]`: the seconds each timer has added up, as a C++ stream prints a double
/// (`0`, `2e-06`).
pub(super) fn timers_answer(
    ctx: &Ctx,
    title: &str,
    names: &[&str],
    timers: &MemoryTimers,
    which: Option<&String>,
) -> CmdResult {
    let value = |name: &str| c_general(timers.seconds(name), 6);
    match which {
        None => {
            let mut s = banner(title);
            for t in names {
                s.push_str(&row40(t, &value(t)));
            }
            Ok(s)
        }
        Some(w) if names.contains(&w.as_str()) => Ok(format!(" {}", value(w))),
        Some(_) => Err(ctx.error("Invalid timer.")),
    }
}
