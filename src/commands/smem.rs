//! The `smem` command (Soar manual, ch. 9, `smem`): the summary, the settings listing,
//! `--get`/`--set`, `--enable`/`--disable`, knowledge added, queried, removed, exported
//! and backed up, the store reinitialized or cleared, and the statistics and timers, with
//! 9.6's texts and error messages (checked on soar-sml 9.6.5).

use super::options::{self, opt};
use super::memory_stats::{stats_answer, timers_answer};
use super::{CmdResult, Ctx, Interpreter};
use crate::smem::params::SetError;
use crate::smem::query::{Cue, Want};
use crate::smem::text::{self, Item, Node};

/// The statistics of `smem --stats`: name, and the label of the listing.
const STATS: [(&str, &str); 10] = [
    ("db-lib-version", "SQLite Version"),
    ("mem-usage", "Memory Usage"),
    ("mem-high", "Memory Highwater"),
    ("retrieves", "Retrieves"),
    ("queries", "Queries"),
    ("stores", "Stores"),
    ("act_updates", "Activation Updates"),
    ("nodes", "Nodes"),
    ("edges", "Edges"),
    ("spread-size", "Spread Size"),
];

/// The timers of `smem --timers`, in 9.6's order.
const TIMERS: [&str; 29] = [
    "_total",
    "smem_api",
    "smem_hash",
    "smem_init",
    "smem_ncb_retrieval",
    "smem_query",
    "smem_storage",
    "spreading",
    "spreading-1",
    "spreading-2",
    "spreading-3",
    "spreading-4",
    "spreading-5",
    "spreading-6",
    "spreading-7",
    "spreading-7-1",
    "spreading-7-2",
    "spreading-7-2-1",
    "spreading-7-2-2",
    "spreading-7-2-3",
    "spreading-7-2-4",
    "spreading-7-2-5",
    "spreading-7-2-6",
    "spreading-7-2-7",
    "spreading-7-2-8",
    "spreading-wma-1",
    "spreading-wma-2",
    "spreading-wma-3",
    "three_activation",
];

/// A 52-column row of the summary, with its note.
fn row52(label: &str, value: &str, note: &str) -> String {
    let width = 52usize.saturating_sub(label.len());
    format!("{label}{value:>width$}   {note}\n")
}

impl Interpreter {
    /// `smem [OPTION [ARGS]]`.
    pub(super) fn cmd_smem(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        if matches!(args.first().map(String::as_str), Some("?" | "help")) {
            return Ok(self.agent.smem.params.listing(self.agent.smem.enabled));
        }
        let specs = [
            opt('a', "add"),
            opt('b', "backup"),
            opt('c', "clear"),
            opt('d', "disable"),
            opt('e', "enable"),
            opt('g', "get"),
            opt('h', "history"),
            opt('i', "init"),
            opt('q', "query"),
            opt('r', "remove"),
            opt('s', "set"),
            opt('S', "stats"),
            opt('t', "timers"),
            opt('x', "export"),
        ];
        let parsed = options::parse(args, &specs).map_err(|m| ctx.error(m))?;
        let words = &parsed.args;
        let Some((option, _)) = parsed.options.first() else {
            if !words.is_empty() {
                return Err(ctx.error("Invalid syntax."));
            }
            return self.smem_summary(ctx);
        };
        if parsed.options.len() > 1 {
            return Err(ctx.error("smem takes only one option at a time."));
        }
        let count = |min, max| parsed.arg_count(min, max).map_err(|m| ctx.error(m));
        let db = |e: String| ctx.error(e);
        let smem = &mut self.agent.smem;
        match *option {
            "enable" => {
                count(0, 0)?;
                smem.enabled = true;
                Ok("Semantic memory enabled.\n".into())
            }
            "disable" => {
                count(0, 0)?;
                smem.enabled = false;
                Ok("Semantic memory disabled.\n".into())
            }
            "get" => {
                count(1, 1)?;
                match smem.params.get(&words[0]) {
                    Some(v) => Ok(format!("{} is {v}\n", words[0])),
                    None => Err(ctx.error(
                        "Invalid semantic memory parameter.  Use 'help smem' to see list of valid settings.",
                    )),
                }
            }
            "set" => {
                count(2, 2)?;
                let open = smem.is_open();
                match smem.params.set(&words[0], &words[1], open) {
                    Err(SetError::Name) => Err(ctx.error("Invalid SMem parameter.")),
                    Err(SetError::Value) => Err(ctx.error("Invalid setting for SMem parameter.")),
                    Err(SetError::Protected) => Err(ctx.error(
                        "This parameter is protected while the semantic memory database is open.",
                    )),
                    Err(SetError::SpreadingNeedsBaseLevel) => Err(ctx.error(
                        "Spreading activation cannot be turned on until the 'activation-mode' is also set to base-level.\nRun 'smem --set activation-mode base-level' first if you intend to use spreading.",
                    )),
                    Err(SetError::ModeWhileSpreading) => Err(ctx.error(
                        "activation-mode cannot be changed while spreading activation is on.",
                    )),
                    Err(SetError::SpreadingLocked) => Err(ctx.error(
                        "Some spreading activation settings cannot be changed once spreading activation has been turned on.",
                    )),
                    Ok(()) => {
                        let mut s = format!("{} is now {}\n", words[0], words[1]);
                        if words[0] == "append" && words[1] == "off" {
                            s.push_str("Warning: Since append mode is off, starting/reinitializing,\n");
                            s.push_str("         Soar will erase the semantic memory database.\n\n");
                        }
                        Ok(s)
                    }
                }
            }
            "add" => {
                count(1, 1)?;
                let (mut clauses, wrong) = text::parse_prefix(&words[0], true);
                in_symbol_order(&mut clauses, &mut self.agent.symbols);
                let marks = self.agent.smem.add(&clauses, self.agent.settings.trace.smem).map_err(db)?;
                match wrong {
                    // The clauses before the wrong one are stored, as in 9.6.
                    Some(n) if marks.is_empty() => {
                        Err(ctx.error(format!("Error parsing clause #{n}")))
                    }
                    Some(n) => Err(ctx.error(format!("{marks}\nError parsing clause #{n}"))),
                    None => Ok(marks),
                }
            }
            "remove" => {
                count(1, 1)?;
                let clauses = text::parse(&words[0], false)
                    .map_err(|n| ctx.error(format!("Error parsing clause #{n}")))?;
                match smem.remove(&clauses) {
                    Ok(marks) => Ok(format!("{marks}\n\nSMem| Removal complete.\n")),
                    Err(e) => Err(ctx.error(format!("Error while attempting removal.\n{e}\n"))),
                }
            }
            "query" => {
                count(1, 2)?;
                let clauses = text::parse(&words[0], true)
                    .map_err(|n| ctx.error(format!("Error parsing clause #{n}")))?;
                let how_many = words
                    .get(1)
                    .and_then(|w| w.parse::<usize>().ok())
                    .unwrap_or(1)
                    .max(1);
                let cue = command_line_cue(&clauses);
                self.agent.smem_note_context();
                let smem = &mut self.agent.smem;
                let found = smem.query_first(&cue, how_many).map_err(db)?;
                let mut s = String::new();
                if found.is_empty() {
                    s.push_str("SMem| No results for query.\n");
                } else {
                    for lti in found.into_iter().take(how_many) {
                        let mut text = smem.print_lti(lti).map_err(db)?.unwrap_or_default();
                        // 9.6 shows the activation the answer would get from the query.
                        if let Some(at) = text.rfind(" [") {
                            text.truncate(at);
                            text.push_str(" [+1.000])\n");
                        }
                        s.push_str(&text);
                    }
                    s.push('\n');
                }
                s.push_str("SMem| Query complete.\n");
                Ok(s)
            }
            "history" => {
                count(1, 1)?;
                let lti = lti_word(&words[0]).ok_or_else(|| ctx.error("Invalid LTI."))?;
                match smem.print_lti(lti).map_err(db)? {
                    Some(t) => Ok(format!("{t}\n")),
                    None => Err(ctx.error(format!(
                        "LTI @{lti} not found in semantic memory."
                    ))),
                }
            }
            "export" => {
                count(1, 2)?;
                let only = match words.get(1) {
                    Some(w) => Some(lti_word(w).ok_or_else(|| ctx.error("Invalid LTI."))?),
                    None => None,
                };
                let text = smem.export(only).map_err(db)?;
                let path = self.cwd.join(&words[0]);
                std::fs::write(&path, text).map_err(|e| {
                    ctx.error(format!("Could not write '{}': {e}", words[0]))
                })?;
                Ok(format!(
                    "Exported semantic memory to file '{}'.\n",
                    words[0]
                ))
            }
            "backup" => {
                count(1, 1)?;
                let lazy = smem.params.lazy_commit();
                let path = self.cwd.join(&words[0]);
                let _ = std::fs::remove_file(&path);
                smem.store()
                    .and_then(|s| s.backup(&path.to_string_lossy(), lazy))
                    .map_err(db)?;
                Ok(format!(
                    "Semantic memory database backed up to {}\n",
                    words[0]
                ))
            }
            "init" => {
                count(0, 0)?;
                let append = smem.params.append();
                // The store stays open, with what it holds (observed on soar-sml 9.6.5,
                // with append on and off); what lazy-commit held back is written.
                let lazy = smem.params.lazy_commit();
                smem.store().and_then(|s| s.commit(lazy)).map_err(db)?;
                let mut s = String::from("Semantic memory system re-initialized.\n");
                if append {
                    s.push_str("Note: Since append mode is on, smem --init does not clear the database.\n");
                    s.push_str("      Use smem --clear to clear the contents.\n");
                }
                Ok(s)
            }
            "clear" => {
                count(0, 0)?;
                let lazy = smem.params.lazy_commit();
                smem.store()
                    .and_then(|s| {
                        s.clear()?;
                        s.commit(lazy)
                    })
                    .map_err(db)?;
                Ok("Semantic memory system cleared.\n".into())
            }
            "stats" => {
                count(0, 1)?;
                let values = self.smem_stat_values().map_err(db)?;
                stats_answer(ctx, "Semantic Memory Statistics", &STATS, &values, words.first())
            }
            _ => {
                // "timers"
                count(0, 1)?;
                let timers = &self.agent.smem.timers;
                timers_answer(ctx, "Semantic Memory Timers", &TIMERS, timers, words.first())
            }
        }
    }

    /// The statistics' values, in the order of [`STATS`]; the store opens for them.
    fn smem_stat_values(&mut self) -> Result<Vec<String>, String> {
        let smem = &mut self.agent.smem;
        let stats = smem.stats;
        let store = smem.store()?;
        let (nodes, edges) = store.counts()?;
        let bytes = store.bytes()?;
        Ok(vec![
            rusqlite::version().to_string(),
            bytes.to_string(),
            bytes.to_string(),
            stats.retrieves.to_string(),
            stats.queries.to_string(),
            stats.stores.to_string(),
            stats.act_updates.to_string(),
            nodes.to_string(),
            edges.to_string(),
            "0".to_string(),
        ])
    }

    /// `smem`: the summary.
    fn smem_summary(&mut self, ctx: &Ctx) -> CmdResult {
        let smem = &mut self.agent.smem;
        let (nodes, edges, bytes) = if smem.is_open() {
            let store = smem.store().map_err(|e| ctx.error(e))?;
            let (n, e) = store.counts().map_err(|e| ctx.error(e))?;
            (n, e, store.bytes().map_err(|e| ctx.error(e))?)
        } else {
            (0, 0, 0)
        };
        let p = &smem.params;
        let mut s = String::new();
        s.push_str("====================================================\n");
        s.push_str("              Semantic Memory Summary\n");
        s.push_str("====================================================\n");
        s.push_str(&row52("Enabled", if smem.enabled { "on" } else { "off" }, ""));
        let append = if p.append() {
            "(append after init)"
        } else {
            "(overwrite after init)"
        };
        let storage = if p.in_file() { "File" } else { "Memory" };
        s.push_str(&row52("Storage", storage, append));
        if p.in_file() {
            s.push_str(&row52("path", p.path(), ""));
        }
        s.push_str("----------------------------------------------------\n");
        s.push_str(&row52("Nodes", &nodes.to_string(), ""));
        s.push_str(&row52("Edges", &edges.to_string(), ""));
        s.push_str(&row52("Memory Usage", &bytes.to_string(), "bytes"));
        s.push_str("----------------------------------------------------\n");
        s.push_str("For a full list of smem's sub-commands and settings:  smem ?");
        Ok(s)
    }
}

/// `@N` as an LTI number.
fn lti_word(w: &str) -> Option<i64> {
    w.strip_prefix('@')?.parse().ok().filter(|&n: &i64| n > 0)
}

/// The cue of `smem --query`: the first clause's augmentations; a variable value asks for
/// any value.
fn command_line_cue(clauses: &[text::Clause]) -> Cue {
    let mut cue = Cue::default();
    if let Some(c) = clauses.first() {
        for (attr, values) in &c.augs {
            for v in values {
                let want = match v {
                    Item::Const(k) => Want::Const(k.clone()),
                    Item::Node(Node::Lti(l)) => Want::Lti(*l),
                    Item::Node(Node::Var(_)) => Want::Any,
                };
                cue.pos.push((attr.clone(), want));
            }
        }
    }
    cue
}

/// Puts each clause's attributes in the order of their symbols' creation, the symbols of
/// the text made in the order it is read: 9.6 files a clause's attributes by symbol, in
/// memory order, which is the order it stores them in (and so the order of its semantic
/// memory's symbol numbers, and of the WMEs a retrieval makes).
fn in_symbol_order(clauses: &mut [text::Clause], symbols: &mut crate::symbols::Symbols) {
    use crate::smem::store::Val;
    let mut sym = |v: &Val| match v {
        Val::Str(s) => Some(symbols.str(s)),
        Val::Int(i) => Some(symbols.int(*i)),
        Val::Float(f) => Some(symbols.float(*f)),
        Val::Lti(_) => None,
    };
    for c in clauses.iter_mut() {
        let mut keyed: Vec<_> = std::mem::take(&mut c.augs)
            .into_iter()
            .map(|(attr, values)| {
                let key = sym(&attr);
                for v in &values {
                    if let text::Item::Const(k) = v {
                        sym(k);
                    }
                }
                (key, attr, values)
            })
            .collect();
        keyed.sort_by_key(|(key, _, _)| *key);
        c.augs = keyed.into_iter().map(|(_, attr, values)| (attr, values)).collect();
    }
}
