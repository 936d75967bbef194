//! The statistics and timers listings of the long-term memories' commands (`smem --stats`,
//! `epmem --timers`, ...): a 40-column banner, then one `label: value` row each, or one
//! value when a name is given, with 9.6's errors for an unknown name.

use super::{CmdResult, Ctx};

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

/// `--timers [NAME]`: rusoar does not time its memories, so each timer reads 0, as 9.6's
/// do with `timers off`.
pub(super) fn timers_answer(
    ctx: &Ctx,
    title: &str,
    timers: &[&str],
    which: Option<&String>,
) -> CmdResult {
    match which {
        None => {
            let mut s = banner(title);
            for t in timers {
                s.push_str(&row40(t, "0"));
            }
            Ok(s)
        }
        Some(w) if timers.contains(&w.as_str()) => Ok(" 0".into()),
        Some(_) => Err(ctx.error("Invalid timer.")),
    }
}
