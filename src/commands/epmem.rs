//! The `epmem` command (Soar manual, ch. 9, `epmem`): the settings, `--get`/`--set`,
//! `--enable`/`--disable`, `--init`, episodes printed and drawn, the statistics and
//! timers, with 9.6's texts and error messages (checked on soar-sml 9.6.5).

use super::options::{self, opt};
use super::memory_stats::{banner, stats_answer, timers_answer};
use super::{CmdResult, Ctx, Interpreter};
use crate::epmem::params::SetError;

/// The statistics of `epmem --stats`: name, and the label of the listing.
const STATS: [(&str, &str); 14] = [
    ("time", "Time"),
    ("db-lib-version", "SQLite Version"),
    ("mem-usage", "Memory Usage"),
    ("mem-high", "Memory Highwater"),
    ("retrievals", "Retrievals"),
    ("queries", "Queries"),
    ("nexts", "Nexts"),
    ("prevs", "Prevs"),
    ("ncb-wmes", "Last Retrieval WMEs"),
    ("qry-pos", "Last Query Positive"),
    ("qry-neg", "Last Query Negative"),
    ("qry-ret", "Last Query Retrieved"),
    ("qry-card", "Last Query Cardinality"),
    ("qry-lits", "Last Query Literals"),
];

/// The timers of `epmem --timers`, in 9.6's order.
const TIMERS: [&str; 29] = [
    "_total",
    "epmem_api",
    "epmem_hash",
    "epmem_init",
    "epmem_ncb_retrieval",
    "epmem_next",
    "epmem_prev",
    "epmem_query",
    "epmem_storage",
    "epmem_trigger",
    "epmem_wm_phase",
    "ncb_edge",
    "ncb_edge_rit",
    "ncb_node",
    "ncb_node_rit",
    "query_cleanup",
    "query_dnf",
    "query_graph_match",
    "query_result",
    "query_sql_edge",
    "query_sql_end_ep",
    "query_sql_end_now",
    "query_sql_end_point",
    "query_sql_start_ep",
    "query_sql_start_now",
    "query_sql_start_point",
    "query_walk",
    "query_walk_edge",
    "query_walk_interval",
];

impl Interpreter {
    /// `epmem [OPTION [ARGS]]`.
    pub(super) fn cmd_epmem(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        if matches!(args.first().map(String::as_str), Some("?" | "help")) {
            return Ok(self.agent.epmem.params.listing());
        }
        let specs = [
            opt('b', "backup"),
            opt('d', "disable"),
            opt('e', "enable"),
            opt('g', "get"),
            opt('i', "init"),
            opt('p', "print"),
            opt('s', "set"),
            opt('S', "stats"),
            opt('t', "timers"),
            opt('v', "viz"),
        ];
        let parsed = options::parse(args, &specs).map_err(|m| ctx.error(m))?;
        let words = &parsed.args;
        let Some((option, _)) = parsed.options.first() else {
            if !words.is_empty() {
                return Err(ctx.error("Too many arguments, check syntax."));
            }
            return Ok(self.agent.epmem.params.listing());
        };
        if parsed.options.len() > 1 {
            return Err(ctx.error("epmem takes only one option at a time."));
        }
        let count = |min, max| parsed.arg_count(min, max).map_err(|m| ctx.error(m));
        match *option {
            "enable" | "disable" => {
                count(0, 0)?;
                let on = *option == "enable";
                let _ = self.agent.epmem.params.set(
                    "learning",
                    if on { "on" } else { "off" },
                    false,
                );
                Ok(format!(
                    "Episodic memory {}.\n",
                    if on { "enabled" } else { "disabled" }
                ))
            }
            "get" => {
                count(1, 1)?;
                match self.agent.epmem.params.get(&words[0]) {
                    Some(v) => Ok(format!("{} is {v}\n", words[0])),
                    None => Err(ctx.error("Invalid epmem parameter.")),
                }
            }
            "set" => {
                count(2, 2)?;
                let open = self.agent.epmem.is_open();
                let before = self.agent.epmem.params.get(&words[0]);
                match self.agent.epmem.params.set(&words[0], &words[1], open) {
                    Err(SetError::Name) => Err(ctx.error("Invalid epmem parameter.")),
                    Err(SetError::Value) => {
                        Err(ctx.error("Invalid setting for epmem parameter."))
                    }
                    Err(SetError::Protected) => Err(ctx.error(
                        "This parameter is protected while the episodic memory database is open.",
                    )),
                    Ok(()) => {
                        let mut s = format!("{} is now {}\n", words[0], words[1]);
                        let now = self.agent.epmem.params.get(&words[0]);
                        let switched = words[0] == "path" || (words[0] == "database" && now != before);
                        if open && switched {
                            s.push_str("To finalize episodic memory database switch, issue an epmem --init command.\n\n");
                        }
                        if words[0] == "append" && now.as_deref() == Some("off") {
                            s.push_str("Warning: Since append mode is off, starting/reinitializing,\n         Soar will erase the episodic memory database.\n\n");
                        }
                        Ok(s)
                    }
                }
            }
            "init" => {
                count(0, 0)?;
                self.agent.epmem_close();
                self.agent.epmem_attach();
                let mut s = String::from("Episodic memory system re-initialized.\n");
                let p = &self.agent.epmem.params;
                if p.get("database").as_deref() == Some("file") && p.get("append").as_deref() == Some("on") {
                    s.push_str("Note: There was no effective change to episodic memory contents \n      because Soar is storing episodic memory to a database file and append \n      mode is on.\n");
                }
                Ok(s)
            }
            "print" | "viz" => {
                count(1, 1)?;
                let t = words[0].parse::<i64>().unwrap_or(0);
                let store = self.agent.epmem.store();
                let valid = store.is_some_and(|s| s.valid(t));
                let Some(store) = store.filter(|_| valid) else {
                    return Err(ctx.error("Invalid episode."));
                };
                // 9.6 ends both with a blank line.
                if *option == "viz" {
                    Ok(format!("{}\n", store.visualize_episode(t)))
                } else {
                    let title = banner(&format!("Episode {t}"));
                    Ok(format!("{title}{}\n", store.print_episode(t)))
                }
            }
            "backup" => {
                count(1, 1)?;
                if !self.agent.epmem.is_open() {
                    return Err(ctx.error(
                        "Error while backing up database: Episodic database is not currently connected.",
                    ));
                }
                match self.agent.epmem.backup(&words[0]) {
                    Ok(()) => Ok(format!("Episodic memory database backed up to {}\n", words[0])),
                    Err(e) => Err(ctx.error(format!("Error while backing up database: {e}"))),
                }
            }
            "stats" => {
                count(0, 1)?;
                let values = self.epmem_stat_values();
                stats_answer(ctx, "Episodic Memory Statistics", &STATS, &values, words.first())
            }
            _ => {
                // "timers"
                count(0, 1)?;
                let timers = &self.agent.epmem.timers;
                timers_answer(ctx, "Episodic Memory Timers", &TIMERS, timers, words.first())
            }
        }
    }

    /// The statistics' values, in the order of [`STATS`].
    fn epmem_stat_values(&self) -> Vec<String> {
        let e = &self.agent.epmem;
        let s = e.stats;
        vec![
            e.time().to_string(),
            rusqlite::version().to_string(),
            "0".into(),
            "0".into(),
            s.retrievals.to_string(),
            s.queries.to_string(),
            s.nexts.to_string(),
            s.prevs.to_string(),
            s.ncb_wmes.to_string(),
            s.qry_pos.to_string(),
            s.qry_neg.to_string(),
            s.qry_ret.to_string(),
            s.qry_card.to_string(),
            s.qry_lits.to_string(),
        ]
    }
}
