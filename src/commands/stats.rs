//! `stats` (Soar manual, ch. 9, `stats`): the run report (`--system`, the default), the
//! decision count, the agent counters, the memory report, the rete's node counts, the
//! chunking statistics, and the per-cycle maxima and tracked cycles.

use super::options::{self, opt, opt_arg};
use super::{CmdResult, Ctx, Interpreter};
use crate::decide::cycle_stats::CycleRow;
use crate::pools::{MemoryReport, Pool};
use crate::rete::stats::NodeCounts;

/// The options, 9.6's.
const SPECS: [options::OptSpec; 13] = [
    opt('m', "memory"),
    opt('l', "learning"),
    opt('r', "rete"),
    opt('s', "system"),
    opt('M', "max"),
    opt('R', "reset"),
    opt('t', "track"),
    opt('T', "stop-track"),
    opt('c', "cycle"),
    opt('C', "cycle-csv"),
    opt_arg('S', "sort"),
    opt('d', "decision"),
    opt('a', "agent"),
];

impl Interpreter {
    /// `stats [options]`. With several options, 9.6 answers in a fixed order whatever the
    /// order typed (checked option pair by option pair on soar-sml 9.6.5): `--agent`,
    /// then `--decision`, then `--learning` each answer alone; otherwise `--track` starts
    /// tracking and `--cycle-csv` answers alone; otherwise the memory report, the maxima,
    /// their reset, the rete's counts, the tracked cycles (`--cycle`, or
    /// `--sort` alone), the end of tracking and the run report come in that order. The
    /// run report comes when `--system` is given or no option is.
    pub(super) fn cmd_stats_options(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let parsed = options::parse(args, &SPECS).map_err(|m| ctx.error(m))?;
        if !parsed.args.is_empty() {
            return Err(ctx.error("Syntax: stats [options]"));
        }
        let has = |o: &str| parsed.has(o);
        let sort = match parsed.value("sort") {
            Some(word) => Some(sort_column(word).ok_or_else(|| ctx.error("Integer expected"))?),
            None => None,
        };
        if has("agent") {
            return Ok("Agent counters:\nCounter          Value\n---------------- -----------\n".into());
        }
        if has("decision") {
            return Ok(format!("{}\n", self.agent.decider.decisions));
        }
        if has("learning") {
            // The chunking statistics, which `chunk stats` prints.
            return self.cmd_chunk(ctx, &["stats".to_string()]);
        }
        let stats = &mut self.agent.decider.cycle_stats;
        if has("track") {
            stats.tracking = true;
        }
        if has("cycle-csv") {
            return Ok(cycles_csv(&stats.rows));
        }
        let mut text = String::new();
        // 9.6 prints `--max` with six decimals and keeps that precision for the tables
        // printed after it in the same command.
        let mut decimals = 3;
        if has("memory") {
            text.push_str(&memory_report(&self.memory_report()));
        }
        let stats = &mut self.agent.decider.cycle_stats;
        if has("max") {
            text.push_str(&max_report(stats));
            decimals = 6;
        }
        if has("reset") {
            stats.reset_max();
        }
        if has("rete") {
            text.push_str(&rete_report(&self.agent.rete.node_counts(), &self.agent.rete));
        }
        let stats = &mut self.agent.decider.cycle_stats;
        if has("cycle") || sort.is_some() {
            text.push_str(&cycles_table(&stats.sorted_rows(sort.unwrap_or(0)), decimals));
        }
        if has("stop-track") {
            stats.stop_tracking();
        }
        if has("system") || parsed.options.is_empty() {
            text.push_str(&self.system_report(decimals));
        }
        Ok(text)
    }

    /// `stats`: 9.6's report: the production counts, the phase timing table, the single
    /// timers, then the counts. The timings are rusoar's own (wall-clock time per phase,
    /// `std::time::Instant`); the first line names rusoar, the host and the time. WM size
    /// is sampled at the end of every phase, as 9.6 samples it.
    fn system_report(&self, decimals: usize) -> String {
        // 9.6 counts no template rule here.
        let (mut defaults, mut chunks, mut templates) = (0, 0, 0);
        for p in self.agent.productions() {
            defaults += usize::from(p.flags.default);
            chunks += usize::from(p.flags.chunk);
            templates += usize::from(p.flags.template);
        }
        let total = self.agent.production_count() - templates;
        let mut text = format!(
            "Soar 9.6 (rusoar) on {} at {}\n\n{} productions ({defaults} default, {} user, {chunks} chunks)\n   + {} justifications\n",
            host_name(),
            ctime_now(),
            total,
            total - defaults - chunks,
            self.agent.learn.justifications.len(),
        );
        let d = &self.agent.decider;
        let (additions, removals) = self.agent.stats_wm_changes();
        let counts = StatsCounts {
            decisions: d.decisions,
            e_cycles: d.e_cycles,
            inner_e_cycles: d.inner_e_cycles,
            pe_cycles: d.pe_cycles,
            firings: d.firings,
            additions,
            removals,
            wm_current: self.agent.wm.len() as u64,
            wm_mean: if d.wm_size_samples == 0 {
                0.0
            } else {
                d.wm_size_sum as f64 / d.wm_size_samples as f64
            },
            wm_max: d.wm_size_max,
        };
        let secs = |t: std::time::Duration| t.as_secs_f64();
        let mut kernel = [0.0; 5];
        for (k, t) in kernel.iter_mut().zip(d.phase_time) {
            *k = secs(t);
        }
        // The callbacks ran inside the input and output phases: they are not kernel time.
        let (input_fn, output_fn) = (secs(d.input_fn_time), secs(d.output_fn_time));
        kernel[0] = (kernel[0] - input_fn).max(0.0);
        kernel[4] = (kernel[4] - output_fn).max(0.0);
        text.push_str(&stats_report(&kernel, input_fn, output_fn, &counts, decimals));
        text
    }

    /// The kernel's stores, for `--memory`.
    /// The stores as `debug allocate` lists them.
    pub(super) fn memory_pool_table(&self) -> String {
        pool_table(&self.memory_report().pools)
    }

    pub(super) fn memory_report(&self) -> MemoryReport {
        let a = &self.agent;
        let mut report = MemoryReport::default();
        let pools = &mut report.pools;
        let (text, symbol_hashes) = a.symbols.memory_pools(pools);
        let wm_hashes = a.wm.memory_pools(pools);
        let d = &a.decider;
        pools.push(Pool::of_vec::<crate::decide::state::Instantiation>(
            "instantiation",
            d.insts.capacity(),
        ));
        pools.push(Pool::of_vec::<crate::decide::state::Preference>(
            "preference",
            d.prefs.capacity(),
        ));
        let rete_hashes = a.rete.memory_pools(pools);
        report.string_bytes = text;
        report.hash_table_bytes = symbol_hashes + wm_hashes + rete_hashes;
        report
    }
}

/// A `--sort` column as 9.6 reads it: the leading integer of the word (`3x` is 3), which
/// must fit in 32 bits.
fn sort_column(word: &str) -> Option<i64> {
    let end = word
        .char_indices()
        .find(|&(i, c)| !(c.is_ascii_digit() || (i == 0 && (c == '-' || c == '+'))))
        .map_or(word.len(), |(i, _)| i);
    word[..end].parse::<i32>().ok().map(i64::from)
}

/// `--memory`, in 9.6's layout: the byte totals, then one row per store (see `pools.rs`).
/// rusoar keeps no statistics of its own beyond these and no other allocations are
/// counted, so the statistics overhead and the miscellaneous line are 0.
fn memory_report(r: &MemoryReport) -> String {
    let pool_bytes: usize = r.pools.iter().map(Pool::bytes).sum();
    let total = r.string_bytes + r.hash_table_bytes + pool_bytes;
    let mut s = format!("{total:>8} bytes total memory allocated\n");
    s.push_str(&format!("{:>8} bytes statistics overhead\n", 0));
    s.push_str(&format!("{:>8} bytes for strings\n", r.string_bytes));
    s.push_str(&format!("{:>8} bytes for hash tables\n", r.hash_table_bytes));
    s.push_str(&format!("{pool_bytes:>8} bytes for various memory pools\n"));
    s.push_str(&format!("{:>8} bytes for miscellaneous other things\n", 0));
    s.push_str(&pool_table(&r.pools));
    s
}

/// The stores' rows of `--memory` (and of `debug allocate`).
fn pool_table(pools: &[Pool]) -> String {
    let mut s = String::from("Memory pool statistics:\n\n");
    s.push_str("Pool Name        Item Size  Itm/Blk  Blocks  Total Bytes\n");
    s.push_str("---------------  ---------  -------  ------  -----------\n");
    for p in pools {
        // 9.6 shows at most 14 characters of a name.
        let name: String = p.name.chars().take(14).collect();
        s.push_str(&format!(
            "{name:>15}  {:>9}  {:>7}  {:>6}  {:>11}\n",
            p.item_size,
            p.per_block,
            p.blocks,
            p.bytes()
        ));
    }
    s
}

/// `--max`: the largest time, WM changes and firings of one decision cycle, and the cycle
/// (0: none yet). rusoar has no episodic or semantic memory: their times are 0.
fn max_report(stats: &crate::decide::cycle_stats::CycleStats) -> String {
    let row = |label: &str, value: String, cycle: u64| format!("{label:>16} {value:>10} {cycle:>11}\n");
    let mut s = String::from(
        "Single decision cycle maximums:\nStat             Value       Cycle\n---------------- ----------- -----------\n",
    );
    let t = stats.max_time;
    s.push_str(&row("Time (sec)", format!("{:.6}", t.value.as_secs_f64()), t.cycle));
    s.push_str(&row("EpMem Time (sec)", format!("{:.6}", 0.0), 0));
    s.push_str(&row("SMem Time (sec)", format!("{:.6}", 0.0), 0));
    let w = stats.max_wm_changes;
    s.push_str(&row("WM changes", w.value.to_string(), w.cycle));
    let f = stats.max_firings;
    s.push_str(&row("Firing count", f.value.to_string(), f.cycle));
    s
}

/// `--rete`: the beta nodes by 9.6's node types (see `rete/stats.rs`), and the matcher's
/// right and left activations. rusoar does not count null activations (those that find
/// nothing to join), so they show as 0.
fn rete_report(c: &NodeCounts, rete: &crate::rete::Rete) -> String {
    let u = c.unmerged();
    let rows: [(&str, u64, u64); 13] = [
        ("unhashed memory", c.unhashed_memory, u.unhashed_memory),
        ("memory", c.memory, u.memory),
        ("unhashed mem-pos", c.unhashed_mem_pos, u.unhashed_mem_pos),
        ("mem-pos", c.mem_pos, u.mem_pos),
        ("unhashed negative", c.unhashed_negative, u.unhashed_negative),
        ("negative", c.negative, u.negative),
        ("unhashed positive", c.unhashed_positive, u.unhashed_positive),
        ("positive", c.positive, u.positive),
        ("dummy top", c.dummy_top, u.dummy_top),
        // Built and dropped within one rule's addition in 9.6; never held in rusoar.
        ("dummy matches", 0, 0),
        ("conj. neg.", c.ncc, u.ncc),
        ("conj. neg. partner", c.ncc_partner, u.ncc_partner),
        ("production", c.production, u.production),
    ];
    let rule = "---------------------  ----------  -------------\n";
    let mut s = String::from("      Node Type            Actual  If no merging\n");
    s.push_str(rule);
    for (name, actual, unmerged) in rows {
        s.push_str(&format!("{name:>21}  {actual:>10}  {unmerged:>13}\n"));
    }
    s.push_str(rule);
    s.push_str(&format!("{:>21}  {:>10}  {:>13}\n\n", "Total", c.total(), u.total()));
    s.push_str(&format!(
        "Activations: {} right (0 null), {} left (0 null)\n",
        rete.right_activations, rete.left_activations
    ));
    s
}

/// `--cycle`: the tracked cycles as a table, nothing when there are none.
fn cycles_table(rows: &[CycleRow], decimals: usize) -> String {
    if rows.is_empty() {
        return String::new();
    }
    let rule = "----------- ----------- ----------- -----------\n";
    let mut s = format!("\n{rule}DC          Time (sec)  WM Changes  Firing Cnt\n{rule}");
    for r in rows {
        s.push_str(&format!(
            "{:>11} {:>11.decimals$} {:>11} {:>11}\n",
            r.cycle,
            r.time.as_secs_f64(),
            r.wm_changes,
            r.firings
        ));
    }
    s
}

/// `--cycle-csv`: the tracked cycles as comma-separated values (times in microseconds),
/// nothing when there are none.
fn cycles_csv(rows: &[CycleRow]) -> String {
    if rows.is_empty() {
        return String::new();
    }
    let mut s = String::from("dc,time,wm_changes,firing_count\n");
    for r in rows {
        s.push_str(&format!(
            "{},{},{},{}\n",
            r.cycle,
            r.time.as_micros(),
            r.wm_changes,
            r.firings
        ));
    }
    s
}

/// The counts `stats` prints.
pub(crate) struct StatsCounts {
    pub decisions: u64,
    pub e_cycles: u64,
    pub inner_e_cycles: u64,
    pub pe_cycles: u64,
    pub firings: u64,
    pub additions: u64,
    pub removals: u64,
    pub wm_current: u64,
    pub wm_mean: f64,
    pub wm_max: u64,
}

/// `stats` after the production counts, in 9.6's layout: the table of kernel time per
/// phase (seconds), the input and output functions' time, callbacks (none in rusoar), the
/// computed totals, the single timers, and the counts with their ratios, with `decimals`
/// decimals (9.6's stream precision at the time).
pub(crate) fn stats_report(
    kernel: &[f64; 5],
    input_fn: f64,
    output_fn: f64,
    c: &StatsCounts,
    decimals: usize,
) -> String {
    let rule = "========================================================|===========\n";
    let row = |label: &str, cells: [Option<f64>; 5], total: f64| {
        let mut line = format!("{label:<10}");
        for (i, cell) in cells.iter().enumerate() {
            if i > 0 {
                line.push(' ');
            }
            match cell {
                Some(v) => line.push_str(&format!("{v:>8.decimals$}")),
                None => line.push_str("        "),
            }
        }
        line.push_str(&format!("  |{total:>11.decimals$}\n"));
        line
    };
    let kernel_total: f64 = kernel.iter().sum();
    let mut totals = *kernel;
    totals[0] += input_fn;
    totals[4] += output_fn;
    let total: f64 = totals.iter().sum();
    let mut s = String::new();
    s.push_str("                                                        |   Computed\n");
    s.push_str("Phases:      Input   Propose   Decide   Apply    Output |     Totals\n");
    s.push_str(rule);
    s.push_str(&row("Kernel:", kernel.map(Some), kernel_total));
    s.push_str(rule);
    s.push_str(&row(
        "Input fn:",
        [Some(input_fn), None, None, None, None],
        input_fn,
    ));
    s.push_str(rule);
    s.push_str(&row(
        "Outpt fn:",
        [None, None, None, None, Some(output_fn)],
        output_fn,
    ));
    s.push_str(rule);
    s.push_str(&row("Callbcks:", [Some(0.0); 5], 0.0));
    s.push_str(rule);
    s.push_str("Computed------------------------------------------------+-----------\n");
    s.push_str(&row("Totals:", totals.map(Some), total));
    s.push('\n');
    s.push_str("Values from single timers:\n");
    s.push_str(&format!(" Kernel CPU Time:{kernel_total:>12.decimals$} sec. \n"));
    s.push_str(&format!(" Total  CPU Time:{total:>12.decimals$} sec.\n\n"));
    let ms = kernel_total * 1000.0;
    let per = |n: u64, of: f64| if n == 0 { 0.0 } else { of / n as f64 };
    let ratio = |a: u64, b: u64| if b == 0 { 0.0 } else { a as f64 / b as f64 };
    s.push_str(&format!(
        "{} decisions ({:.decimals$} msec/decision)\n",
        c.decisions,
        per(c.decisions, ms)
    ));
    s.push_str(&format!(
        "{} elaboration cycles ({:.decimals$} ec's per dc, {:.decimals$} msec/ec)\n",
        c.e_cycles,
        ratio(c.e_cycles, c.decisions),
        per(c.e_cycles, ms)
    ));
    s.push_str(&format!("{} inner elaboration cycles\n", c.inner_e_cycles));
    s.push_str(&format!(
        "{} p-elaboration cycles ({:.decimals$} pe's per dc, {:.decimals$} msec/pe)\n",
        c.pe_cycles,
        ratio(c.pe_cycles, c.decisions),
        per(c.pe_cycles, ms)
    ));
    s.push_str(&format!(
        "{} production firings ({:.decimals$} pf's per ec, {:.decimals$} msec/pf)\n",
        c.firings,
        ratio(c.firings, c.e_cycles),
        per(c.firings, ms)
    ));
    s.push_str(&format!(
        "{} wme changes ({} additions, {} removals)\n",
        c.additions + c.removals,
        c.additions,
        c.removals
    ));
    s.push_str(&format!(
        "WM size: {} current, {:.decimals$} mean, {} maximum\n\n",
        c.wm_current, c.wm_mean, c.wm_max
    ));
    s
}

/// The host's name (Linux), for `stats`' first line.
fn host_name() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .map(|h| h.trim().to_string())
        .ok()
        .filter(|h| !h.is_empty())
        .unwrap_or_else(|| "localhost".into())
}

/// The time now in ctime's form (`Tue Dec  1 21:30:37 2026`), in UTC.
fn ctime_now() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs()) as i64;
    let (days, rem) = (secs.div_euclid(86_400), secs.rem_euclid(86_400));
    // Days since 1970-01-01 to a civil date (proleptic Gregorian).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    const WEEKDAYS: [&str; 7] = ["Thu", "Fri", "Sat", "Sun", "Mon", "Tue", "Wed"];
    const MONTHS: [&str; 12] = [
        "Jan", "Feb", "Mar", "Apr", "May", "Jun", "Jul", "Aug", "Sep", "Oct", "Nov", "Dec",
    ];
    format!(
        "{} {} {day:>2} {:02}:{:02}:{:02} {year}",
        WEEKDAYS[days.rem_euclid(7) as usize],
        MONTHS[(month - 1) as usize],
        rem / 3600,
        rem / 60 % 60,
        rem % 60
    )
}
