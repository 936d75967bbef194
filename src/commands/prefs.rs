//! `preferences [options] [ID [ATTR]]` (Soar manual, ch. 9, `preferences`): one slot's
//! preferences grouped by type in 9.6's order and format, and, for a state's operator slot
//! that has a choice to make, each candidate's selection probability. The detail options
//! add the rule behind each preference (`-n`/`-N`/`--names`), the timetags of the WMEs it
//! matched (`-t`/`--timetags`) or those WMEs whole (`-w`/`--wmes`); `--none` goes back to
//! the preferences alone, and the last of them given counts. An identifier that is not a
//! state, given alone, lists the support of each WME that points at it, and `-o`/`--object`
//! every slot of an object (`prefs_support.rs`). Checked against soar-sml 9.6.5.

use super::options::{self, long_only, opt};
use super::{CmdResult, Ctx, Interpreter};
use crate::agent::AgentCore;
use crate::decide::procedure::{self, NumericMode, Pref, PrefType};
use crate::decide::state::Preference;
use crate::symbols::Sym;
use crate::wm::Wme;

/// Sections in 9.6's order (its preference type numbering), with their headings.
pub(super) const SECTIONS: [(PrefType, &str); 11] = [
    (PrefType::Acceptable, "acceptables"),
    (PrefType::Require, "requires"),
    (PrefType::Reject, "rejects"),
    (PrefType::Prohibit, "prohibits"),
    (PrefType::UnaryIndifferent, "unary indifferents"),
    (PrefType::Best, "bests"),
    (PrefType::Worst, "worsts"),
    (PrefType::BinaryIndifferent, "binary indifferents"),
    (PrefType::Better, "betters"),
    (PrefType::Worse, "worses"),
    (PrefType::NumericIndifferent, "numeric indifferents"),
];

/// How much is listed under each preference.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(super) enum Detail {
    /// The preference alone.
    None,
    /// The rule that made it.
    Names,
    /// The rule and the timetags of the WMEs its match held.
    Timetags,
    /// The rule and those WMEs whole.
    Wmes,
}

const SYNTAX: &str = "Syntax: preferences [options] [identifier [attribute]]";
const FAILED: &str = "An Error occured trying to print the prefs.";

fn type_char(k: PrefType) -> &'static str {
    match k {
        PrefType::Acceptable => "+",
        PrefType::Require => "!",
        PrefType::Reject => "-",
        PrefType::Prohibit => "~",
        PrefType::UnaryIndifferent | PrefType::BinaryIndifferent => "=",
        PrefType::NumericIndifferent => "=",
        PrefType::Best | PrefType::Better => ">",
        PrefType::Worst | PrefType::Worse => "<",
    }
}

/// A number as 9.6 prints a candidate's value: integral values with a trailing point.
fn value_number(v: f64) -> String {
    if v.fract() == 0.0 && v.abs() < 1e15 {
        format!("{}.", v as i64)
    } else {
        format!("{v}")
    }
}

/// An identifier typed as `S1` (any case) or a context variable (`<s>`, `<o>`, ...).
pub(super) fn read_id(agent: &AgentCore, text: &str) -> Option<Sym> {
    if let Some(var) = text.strip_prefix('<').and_then(|t| t.strip_suffix('>')) {
        return super::print_cmd::context_variable(agent, var).ok().flatten();
    }
    if crate::lexer::is_identifier_shaped(text) {
        return agent.symbols.find_id(text);
    }
    None
}

/// An attribute as typed (`^` optional): an identifier, a context variable or a constant,
/// if such a symbol exists.
fn read_attr(agent: &AgentCore, text: &str) -> Option<Sym> {
    let text = text.strip_prefix('^').unwrap_or(text);
    if text.starts_with('<') && text.ends_with('>') || crate::lexer::is_identifier_shaped(text) {
        return read_id(agent, text);
    }
    let constant = if crate::lexer::is_int_lexeme(text) {
        text.parse::<i64>().ok().map(crate::ast::Constant::Int)
    } else {
        None
    };
    let constant = constant
        .or_else(|| {
            text.parse::<f64>()
                .ok()
                .filter(|_| text.contains('.'))
                .map(crate::ast::Constant::Float)
        })
        .unwrap_or_else(|| {
            let s = text
                .strip_prefix('|')
                .and_then(|t| t.strip_suffix('|'))
                .unwrap_or(text);
            crate::ast::Constant::Str(s.into())
        });
    agent.symbols.find_constant(&constant)
}

impl Interpreter {
    pub(super) fn cmd_preferences(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let specs = [
            long_only("none"),
            opt('n', "names"),
            opt('N', "names"),
            opt('t', "timetags"),
            opt('w', "wmes"),
            opt('o', "object"),
        ];
        let parsed = options::parse(args, &specs).map_err(|m| ctx.error(m))?;
        // The last detail option given counts.
        let detail = parsed
            .options
            .iter()
            .filter_map(|(long, _)| match *long {
                "none" => Some(Detail::None),
                "names" => Some(Detail::Names),
                "timetags" => Some(Detail::Timetags),
                "wmes" => Some(Detail::Wmes),
                _ => None,
            })
            .next_back()
            .unwrap_or(Detail::None);
        let object = parsed.has("object");
        if parsed.args.len() > 2 {
            return Err(ctx.error(SYNTAX));
        }
        let agent = &self.agent;
        let id = match parsed.args.first() {
            Some(text) => read_id(agent, text).ok_or_else(|| {
                ctx.error(format!("Could not find the id '{text}'\n{FAILED}"))
            })?,
            None => match agent.decider.goals.last() {
                Some(g) => g.state,
                None => agent.top.state,
            },
        };
        // The attribute counts only after an identifier.
        let attr_text = match parsed.args.get(1) {
            Some(a) if parsed.args.len() == 2 => a.as_str(),
            _ => "operator",
        };
        if object {
            return Ok(self.object_listing(id, detail));
        }
        let is_goal = agent.symbols.is_goal(id);
        if !is_goal && attr_text == "operator" {
            return Ok(self.value_support(id, detail));
        }
        let Some(attr) = read_attr(agent, attr_text) else {
            let typed = parsed
                .args
                .first()
                .cloned()
                .unwrap_or_else(|| agent.symbols.text(id));
            return Err(ctx.error(format!(
                "Could not find prefs for the id,attribute pair: {typed} {attr_text}\n{FAILED}"
            )));
        };
        if !self.has_slot(id, attr) {
            return Ok(
                "  This is probably an io- or arch-wme and does not have preferences\n".into(),
            );
        }
        let prefs = self.slot_prefs(id, attr);
        let mut out = format!(
            "\nPreferences for {} ^{}:\n",
            agent.symbols.text(id),
            agent.symbols.text(attr)
        );
        for (kind, heading) in SECTIONS {
            let of_kind: Vec<&Preference> = prefs.iter().filter(|p| p.kind == kind).collect();
            if of_kind.is_empty() {
                continue;
            }
            out.push_str(&format!("\n{heading}:\n"));
            for p in of_kind {
                out.push_str(&self.pref_line(p));
                out.push_str(&self.source_lines(p, detail));
            }
        }
        // 9.6 compares the attribute as typed: `^operator` lists no probabilities.
        if is_goal && attr_text == "operator" {
            out.push_str(&self.selection_probabilities(&prefs, detail));
        }
        Ok(out)
    }

    /// The live preferences of a slot as 9.6 lists it from its head: 9.6 keeps them by
    /// the level of their firings' match goals, the highest goal first (a result's
    /// justification before the substate firing that made it), newest first within a
    /// level.
    pub(super) fn slot_prefs(&self, id: Sym, attr: Sym) -> Vec<Preference> {
        let agent = &self.agent;
        let mut prefs: Vec<Preference> = agent
            .decider
            .slots
            .get(&(id, attr))
            .map(|slot| {
                slot.prefs
                    .iter()
                    .rev()
                    .map(|&p| agent.decider.prefs[p].clone())
                    .filter(|p| p.alive)
                    .collect()
            })
            .unwrap_or_default();
        prefs.sort_by_key(|p| self.pref_level(p));
        prefs
    }

    /// The level of the match goal of the firing that made `p` (of its identifier, once
    /// the firing is gone).
    fn pref_level(&self, p: &Preference) -> u32 {
        let agent = &self.agent;
        match p.inst.and_then(|i| agent.decider.insts[i].goal) {
            Some(g) => agent.symbols.id_data(g).map_or(1, |d| d.level),
            None => agent.symbols.id_data(p.id).map_or(1, |d| d.level),
        }
    }

    /// `  A1 (alpha) +  :I ` / `  E2 (e) = A1 (a) :I ` / `  (S1 ^thing x)  :I `, with
    /// ` [level N] ` for preferences below the top state.
    pub(super) fn pref_line(&self, p: &Preference) -> String {
        let support = if p.o_support { "O" } else { "I" };
        format!("  {}:{support} {}\n", self.pref_body(p), self.level_mark(p))
    }

    /// The preference before its support: an operator's value and type (and referent), or
    /// any other slot's `(id ^attr value)`.
    fn pref_body(&self, p: &Preference) -> String {
        let agent = &self.agent;
        if p.attr == agent.top.operator {
            let referent = match (p.kind, p.referent) {
                (PrefType::NumericIndifferent, Some(r)) => format!(" {} ", agent.symbols.text(r)),
                (_, Some(r)) => format!(" {} ", self.object_text(r)),
                (_, None) => "  ".into(),
            };
            format!(
                "{} {}{referent}",
                self.object_text(p.value),
                type_char(p.kind)
            )
        } else {
            format!(
                "({} ^{} {})  ",
                agent.symbols.text(p.id),
                agent.symbols.text(p.attr),
                agent.symbols.text(p.value)
            )
        }
    }

    fn level_mark(&self, p: &Preference) -> String {
        let level = self.pref_level(p);
        if level > 1 {
            format!(" [level {level}] ")
        } else {
            String::new()
        }
    }

    /// The line of a candidate with its value and chance: `  O1 (a) +  = 5. :I (62.50%)`.
    pub(super) fn candidate_line(&self, p: &Preference, value: f64, chance: f64) -> String {
        let support = if p.o_support { "O" } else { "I" };
        let body = if p.attr == self.agent.top.operator {
            format!("{} {}  ", self.object_text(p.value), type_char(p.kind))
        } else {
            self.pref_body(p)
        };
        format!(
            "  {body}= {} :{support} ({:.2}%)\n",
            value_number(value),
            chance * 100.0
        )
    }

    /// What `--names`, `--timetags` and `--wmes` add under a preference: `    From rule`,
    /// the matched WMEs, and a line end.
    pub(super) fn source_lines(&self, p: &Preference, detail: Detail) -> String {
        if detail == Detail::None {
            return String::new();
        }
        let agent = &self.agent;
        let rule = crate::trace::pref_rule(agent, p).unwrap_or("[dummy production]");
        let mut out = format!("    From {rule}\n");
        if detail >= Detail::Timetags {
            for w in self.matched_wmes(p) {
                let level = agent.symbols.id_data(w.id).map_or(1, |d| d.level);
                if detail == Detail::Timetags {
                    out.push_str(&format!(" {}", w.timetag));
                } else if level > 1 {
                    // 9.6 keeps the WMEs of substate matches alive and prints them whole;
                    // of a top-state match it keeps only the timetags.
                    out.push(' ');
                    let activation = agent.wme_activation(&w);
                    crate::trace_text::wme_text_activated(&mut out, &agent.symbols, &w, activation);
                    out.push('\n');
                } else {
                    out.push_str(&format!("WME with time tag {}\n", w.timetag));
                }
            }
        }
        out.push('\n');
        out
    }

    /// The WMEs matched by the instantiation behind a preference, in the order of the
    /// rule's (reordered) positive conditions. A substate firing's record keeps them past
    /// its retraction, and so does a top-level o-supported preference; an i-supported
    /// preference's are read from its match, which holds as long as it lives. (9.6 keeps
    /// no hold on the WMEs of a top-level firing: once they leave working memory it prints
    /// whatever its allocator put in their place, which rusoar cannot follow.)
    fn matched_wmes(&self, p: &Preference) -> Vec<Wme> {
        let agent = &self.agent;
        if let Some(origin) = &p.origin {
            return origin
                .trace
                .conds
                .iter()
                .filter(|c| c.cond.is_some())
                .map(|c| c.wme)
                .collect();
        }
        if let Some(matched) = &p.matched {
            return matched.to_vec();
        }
        let Some(inst) = p.inst.map(|i| &agent.decider.insts[i]) else {
            return Vec::new();
        };
        if !inst.alive {
            return Vec::new();
        }
        agent
            .rete
            .match_wmes(inst.prod, inst.token)
            .into_iter()
            .filter_map(|w| agent.wm.get(w).copied())
            .collect()
    }

    /// An operator with its names: `O1 (count-items)`.
    fn object_text(&self, o: Sym) -> String {
        let text = self.agent.symbols.text(o);
        let names = self.agent.name_values(o);
        if names.is_empty() {
            // 9.6 writes an object as `%id %ifdef[(%v[name])]`: the space stays.
            format!("{text} ")
        } else {
            format!("{text} ({})", names.join(" "))
        }
    }

    /// The candidates an operator slot would choose among now, in 9.6's order, with each
    /// one's value and the preference that makes it a candidate; `None` for an impasse.
    pub(super) fn candidates(&self, prefs: &[Preference]) -> Option<Vec<(Preference, f64)>> {
        let for_procedure: Vec<Pref> = prefs
            .iter()
            .rev()
            .map(|p| Pref {
                kind: p.kind,
                value: p.value,
                referent: p.referent,
                number: p.number,
            })
            .collect();
        let cands = procedure::candidates(&for_procedure).ok()?;
        let mut out = Vec::new();
        for c in cands {
            let value = procedure::numeric_value(&for_procedure, c, NumericMode::Sum);
            let made_by = prefs
                .iter()
                .find(|p| p.value == c && p.kind == PrefType::Require)
                .or_else(|| {
                    prefs
                        .iter()
                        .find(|p| p.value == c && p.kind == PrefType::Acceptable)
                });
            if let Some(p) = made_by {
                out.push((p.clone(), value));
            }
        }
        Some(out)
    }

    /// A candidate's chance among `among` (values): in proportion to the positive values,
    /// evenly when none is positive.
    pub(super) fn chance(value: f64, among: &[f64]) -> f64 {
        let total: f64 = among.iter().filter(|v| **v > 0.0).sum();
        if among.len() == 1 && total <= 0.0 {
            1.0
        } else if total > 0.0 {
            value.max(0.0) / total
        } else {
            1.0 / among.len() as f64
        }
    }

    /// The candidates an operator slot would choose among now, with their chances under
    /// the current policy's uniform or value-weighted draw (nothing for an impasse).
    fn selection_probabilities(&self, prefs: &[Preference], detail: Detail) -> String {
        let Some(cands) = self.candidates(prefs) else {
            return String::new();
        };
        if cands.is_empty() {
            return String::new();
        }
        let values: Vec<f64> = cands.iter().map(|(_, v)| *v).collect();
        let mut out = String::from("\nselection probabilities:\n");
        for (p, v) in &cands {
            let chance = if cands.len() == 1 {
                1.0
            } else {
                Self::chance(*v, &values)
            };
            out.push_str(&self.candidate_line(p, *v, chance));
            out.push_str(&self.source_lines(p, detail));
        }
        out
    }
}
