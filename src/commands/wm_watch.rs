//! `wm watch` (Soar manual, ch. 9, `wm`): the filters of the `=>WM:` and `<=WM:` trace
//! lines (`wme_filters.rs`), with 9.6's messages.

use super::options::{self, opt, opt_arg};
use super::{CmdResult, Ctx, Interpreter};
use crate::lexer::is_identifier_shaped;
use crate::symbols::Sym;
use crate::wme_filters::WmeFilter;

const SYNTAX: &str = "Syntax: wm watch -[a|r]  -t <type>  <pattern>\nwm watch -[l|R] [-t <type>]";

/// What `wm watch` does: the last of `-a`, `-r`, `-l`, `-R` given wins, as in 9.6;
/// listing when none is.
#[derive(Clone, Copy, PartialEq)]
enum Mode {
    Add,
    Remove,
    List,
    Reset,
}

impl Interpreter {
    /// `wm watch -[a|r] -t TYPE ID ATTR VALUE`, `wm watch [-l|-R] [-t TYPE]`.
    pub(super) fn cmd_wm_watch(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let specs = [
            opt('a', "add-filter"),
            opt('r', "remove-filter"),
            opt('l', "list-filter"),
            opt('R', "reset-filter"),
            opt_arg('t', "type"),
        ];
        let parsed = options::parse(args, &specs).map_err(|m| ctx.error(m))?;
        let mode = parsed
            .options
            .iter()
            .filter_map(|(o, _)| match *o {
                "add-filter" => Some(Mode::Add),
                "remove-filter" => Some(Mode::Remove),
                "list-filter" => Some(Mode::List),
                "reset-filter" => Some(Mode::Reset),
                _ => None,
            })
            .next_back()
            .unwrap_or(Mode::List);
        let kinds = match parsed.value("type") {
            Some("adds") => Some((true, false)),
            Some("removes") => Some((false, true)),
            Some("both") => Some((true, true)),
            Some(other) => {
                return Err(ctx.error(format!("Invalid wme filter type, got: {other}")));
            }
            None => None,
        };
        let words = &parsed.args;
        match mode {
            Mode::List | Mode::Reset => {
                if !words.is_empty() {
                    return Err(ctx.error(SYNTAX));
                }
                let (adds, removes) = kinds.unwrap_or((true, true));
                let picked = |f: &WmeFilter| (adds && f.adds) || (removes && f.removes);
                if mode == Mode::List {
                    let list = &self.agent.wme_filters.list;
                    let lines = list.iter().filter(|f| picked(f));
                    return Ok(lines.map(|f| format!("wme filter: {}\n", self.filter_text(f))).collect());
                }
                let (gone, kept): (Vec<WmeFilter>, Vec<WmeFilter>) =
                    self.agent.wme_filters.list.iter().partition(|f| picked(f));
                if gone.is_empty() {
                    return Err(ctx.error("The specified WME filter was not found."));
                }
                self.agent.wme_filters.list = kept;
                Ok(gone.iter().map(|f| format!("Removed: {}\n", self.filter_text(f))).collect())
            }
            Mode::Add | Mode::Remove => {
                let Some((adds, removes)) = kinds else {
                    return Err(ctx.error("Wme type required."));
                };
                let [id, attr, value] = words.as_slice() else {
                    return Err(ctx.error(SYNTAX));
                };
                let filter = WmeFilter {
                    id: self.pattern_symbol(ctx, id, "id", true)?,
                    attr: self.pattern_symbol(ctx, attr, "attribute", false)?,
                    value: self.pattern_symbol(ctx, value, "value", false)?,
                    adds,
                    removes,
                };
                let list = &mut self.agent.wme_filters.list;
                let at = list.iter().position(|f| *f == filter);
                match (mode, at) {
                    (Mode::Add, Some(_)) => Err(ctx.error("That WME filter already exists.")),
                    (Mode::Add, None) => {
                        list.insert(0, filter);
                        Ok(String::new())
                    }
                    (_, Some(i)) => {
                        list.remove(i);
                        Ok(String::new())
                    }
                    (_, None) => Err(ctx.error("The specified WME filter was not found.")),
                }
            }
        }
    }

    /// One field of a filter's pattern: `*` for any; an identifier, which must exist (the
    /// identifier field takes nothing else); or a constant.
    fn pattern_symbol(
        &mut self,
        ctx: &Ctx,
        word: &str,
        field: &str,
        id_only: bool,
    ) -> Result<Option<Sym>, crate::source::Diagnostic> {
        if word == "*" {
            return Ok(None);
        }
        let invalid = || ctx.error(format!("Invalid {field}, got: {word}"));
        if id_only || is_identifier_shaped(word) {
            return self.agent.symbols.find_id(word).map(Some).ok_or_else(invalid);
        }
        super::memory::symbol_for_word(&mut self.agent, word, false)
            .map(Some)
            .ok_or_else(invalid)
    }

    /// A filter as 9.6 lists it: `(ID ^ATTR VALUE) adds removes`.
    fn filter_text(&self, f: &WmeFilter) -> String {
        let field = |s: Option<Sym>| s.map_or_else(|| "*".to_string(), |s| self.agent.symbols.text(s));
        format!(
            "({} ^{} {}) {} {}",
            field(f.id),
            field(f.attr),
            field(f.value),
            if f.adds { "adds" } else { "" },
            if f.removes { "removes" } else { "" }
        )
    }
}
