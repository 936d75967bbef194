//! `wm add`, `wm remove`, `production matches` and `print` of identifiers and timetags
//! (Soar manual, ch. 9, `wm`, `production`, `print`).

use super::options::{self, opt};
use super::{CmdResult, Ctx, Interpreter};
use crate::lexer::{is_identifier_shaped, is_int_lexeme};
use crate::source::Diagnostic;
use crate::symbols::Sym;

impl Interpreter {
    pub(super) fn cmd_wm(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        match args.first().map(String::as_str) {
            Some("add") => self.cmd_wm_add(ctx, &args[1..]),
            Some("remove") => self.cmd_wm_remove(ctx, &args[1..]),
            Some("watch") => self.cmd_wm_watch(ctx, &args[1..]),
            Some("activation") => self.cmd_wm_activation(ctx, &args[1..]),
            // 9.6's text, its spelling included.
            None => Err(ctx.error("The 'wm' commands contains commands and settings related to working memomory: add, remove, activation and watch.")),
            _ => Err(ctx.error(
                "Invalid wm command.  Use 'wm ?' to see a list of valid settings.",
            )),
        }
    }

    /// `wm add id [^]attr value [+]`: the id must exist; `*` as value makes a new identifier.
    fn cmd_wm_add(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        if args.len() < 3 || args.len() > 4 || (args.len() == 4 && args[3] != "+") {
            return Err(ctx.error("Syntax: wm add id [^]attribute value [+]"));
        }
        let agent = &mut self.agent;
        let invalid = || {
            Diagnostic::error("Invalid identifier")
                .at(ctx.arg_span(1))
                .with_label("no such identifier")
        };
        // One that garbage collection took is gone, as 9.6 frees its symbol (checked on
        // soar-sml 9.6.5).
        let id = agent.live_id(&args[0]).ok_or_else(invalid)?;
        let attr_word = args[1].strip_prefix('^').unwrap_or(&args[1]);
        // A word Soar's lexer does not read as one symbol (checked on soar-sml 9.6.5).
        if !reads_as_symbol(attr_word) {
            return Err(ctx.error("Unknown attribute type."));
        }
        if args[2] != "*" && !reads_as_symbol(&args[2]) {
            return Err(ctx.error("Unknown value type."));
        }
        // An identifier-shaped attribute names an identifier, which must exist.
        let attr = if is_identifier_shaped(attr_word) {
            agent.live_id(attr_word).ok_or_else(|| {
                let name = attr_word.to_ascii_uppercase();
                Diagnostic::error(format!(
                    "There is no identifier {name}.\nInvalid attribute."
                ))
                .at(ctx.arg_span(2))
                .with_label("no such identifier")
            })?
        } else {
            symbol_for_word(agent, attr_word, false).ok_or_else(|| {
                Diagnostic::error("Invalid identifier")
                    .at(ctx.arg_span(2))
                    .with_label("no such identifier")
            })?
        };
        let level = agent.symbols.id_data(id).map_or(1, |d| d.level);
        let value = if args[2] == "*" {
            agent.symbols.new_id('I', level)
        } else if is_identifier_shaped(&args[2]) && agent.live_id(&args[2]).is_none() {
            // An identifier-shaped value that names none makes one of that name, `S`
            // written `I` as a rule's new identifiers are (checked on soar-sml 9.6.5).
            new_named_id(agent, &args[2], level)
        } else {
            symbol_for_word(agent, &args[2], true).ok_or_else(|| {
                Diagnostic::error("Invalid identifier")
                    .at(ctx.arg_span(3))
                    .with_label("no such identifier")
            })?
        };
        let w = agent.add_wme(id, attr, value, args.len() == 4);
        let tt = agent.wm.get(w).map_or(0, |x| x.timetag);
        Ok(format!("Timetag: {tt}"))
    }

    /// `wm remove <timetag>`: an unknown timetag does nothing, as in 9.6.
    fn cmd_wm_remove(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let Some(tt) = args.first().and_then(|a| a.parse::<u64>().ok()) else {
            return Err(ctx.error("Syntax: wm remove <time-tag>"));
        };
        if let Some(w) = self.agent.wm.by_timetag(tt) {
            // Out of its slot too: a preference that still supports it makes it again when
            // the slot next changes (checked on soar-sml 9.6.5).
            self.agent.remove_slot_wme(w);
            // What only it linked goes at once (9.6: `wm remove` of `(S3 ^epmem E3)` leaves
            // no identifier E3).
            self.agent.collect_garbage();
        }
        Ok(String::new())
    }

    /// `production matches [rule]`.
    pub(super) fn cmd_matches(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let specs = [
            opt('a', "assertions"),
            opt('r', "retractions"),
            opt('n', "names"),
            opt('c', "count"),
            opt('t', "timetags"),
            opt('w', "wmes"),
        ];
        let parsed = options::parse(args, &specs).map_err(|m| ctx.error(m))?;
        match parsed.args.first() {
            None => {
                // `-a` keeps the assertions, `-r` the retractions (9.6 lists assertions
                // first, then `Retractions:`).
                let all = crate::trace::pending_matches(&self.agent);
                let (assertions, retractions) = match all.find("Retractions:") {
                    Some(i) => all.split_at(i),
                    None => (all.as_str(), ""),
                };
                Ok(match (parsed.has("assertions"), parsed.has("retractions")) {
                    (true, false) => assertions.to_string(),
                    (false, true) => retractions.to_string(),
                    _ => all.clone(),
                })
            }
            Some(name) => {
                let mut text =
                    crate::trace::matches_listing(&self.agent, name).ok_or_else(|| {
                        Diagnostic::error(format!("Production not found: {name}"))
                            .at(ctx.arg_span(0))
                            .with_label("no such rule")
                    })?;
                if parsed.has("wmes") || parsed.has("timetags") {
                    text.push_str("*** Complete Matches ***\n");
                    let loaded = self.agent.loaded(name).map(|l| l.id);
                    if let Some(id) = loaded {
                        for t in self.agent.rete.matches_of(id) {
                            let ws = self.agent.rete.match_wmes(id, t);
                            text.push_str(&crate::trace::match_wme_lines(&self.agent, &ws));
                            text.push_str("\n \n");
                        }
                    }
                }
                Ok(text)
            }
        }
    }

}

/// Whether a `wm add` word is one symbol to Soar's lexer: `|...|`, a number, or
/// constituents only (a `|` within is read as the start of a quote, as 9.6 reads it).
fn reads_as_symbol(word: &str) -> bool {
    word.starts_with('|')
        || (word.contains('.') && word.parse::<f64>().is_ok())
        || word
            .chars()
            .all(|c| c == '|' || crate::lexer::is_constituent(c))
}

/// A new identifier named as the identifier-shaped `word` (`Z9`) says, `S` written `I`,
/// as 9.6 makes it: a number too large for 64 bits is the largest, and 0 takes the
/// letter's next number.
fn new_named_id(agent: &mut crate::agent::AgentCore, word: &str, level: u32) -> Sym {
    let (letter, digits) = word.split_at(1);
    let letter = match letter.to_ascii_uppercase().as_str() {
        "S" => 'I',
        l => l.chars().next().unwrap_or('I'),
    };
    match digits.parse::<u64>().unwrap_or(u64::MAX) {
        0 => agent.symbols.new_id(letter, level),
        number => agent.symbols.new_id_numbered(letter, number, level),
    }
}

/// The symbol a `wm add` word names: an existing identifier for identifier-shaped words
/// (values only), else a number or a string constant (`|...|` quoting removed).
pub(super) fn symbol_for_word(agent: &mut crate::agent::AgentCore, word: &str, allow_id: bool) -> Option<Sym> {
    if let Some(inner) = word.strip_prefix('|').and_then(|w| w.strip_suffix('|')) {
        return Some(agent.symbols.str(inner));
    }
    if is_identifier_shaped(word) {
        if allow_id {
            return agent.symbols.find_id(word);
        }
        return Some(agent.symbols.str(&word.to_ascii_uppercase()));
    }
    if is_int_lexeme(word) {
        return word.parse::<i64>().ok().map(|i| agent.symbols.int(i));
    }
    if word.contains('.') {
        if let Ok(f) = word.parse::<f64>() {
            return Some(agent.symbols.float(f));
        }
    }
    Some(agent.symbols.str(word))
}
