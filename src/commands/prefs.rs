//! `preferences [ID [ATTR]] [--names] [--wmes]` (Soar manual, ch. 9, `preferences`): one
//! slot's preferences grouped by type in 9.6's order and format, and, for an operator slot
//! that has a choice to make, each candidate's selection probability. Checked against
//! soar-sml 9.6.5.

use super::options::{self, opt};
use super::{CmdResult, Ctx, Interpreter};
use crate::decide::procedure::{self, NumericMode, Pref, PrefType};
use crate::decide::state::Preference;
use crate::symbols::Sym;

/// Sections in 9.6's order (its preference type numbering), with their headings.
const SECTIONS: [(PrefType, &str); 11] = [
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

impl Interpreter {
    pub(super) fn cmd_preferences(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let specs = [
            opt('n', "names"),
            opt('w', "wmes"),
            opt('t', "timetags"),
            opt('o', "object"),
        ];
        let parsed = options::parse(args, &specs).map_err(|m| ctx.error(m))?;
        // 9.6's listings of the matched WMEs and of a whole object are not built yet.
        for (option, shown) in [
            ("wmes", "preferences --wmes"),
            ("timetags", "preferences --timetags"),
            ("object", "preferences --object"),
        ] {
            if parsed.has(option) {
                return Err(super::not_yet(ctx, shown));
            }
        }
        let names = parsed.has("names");
        let agent = &mut self.agent;
        let id = match parsed.args.first() {
            Some(text) => agent
                .symbols
                .find_id(&text.to_ascii_uppercase())
                .ok_or_else(|| {
                    ctx.error(format!(
                        "Could not find the id '{text}'\nAn Error occured trying to print the prefs."
                    ))
                })?,
            None => match agent.decider.goals.last() {
                Some(g) => g.state,
                None => agent.top.state,
            },
        };
        let attr_text = parsed.args.get(1).map_or("operator", String::as_str);
        let attr_text = attr_text.strip_prefix('^').unwrap_or(attr_text);
        let attr = agent.symbols.str(attr_text);
        let prefs: Vec<Preference> = agent
            .decider
            .slots
            .get(&(id, attr))
            .map(|slot| {
                // 9.6 lists a slot from its head: the newest preference first.
                slot.prefs
                    .iter()
                    .rev()
                    .map(|&p| agent.decider.prefs[p].clone())
                    .filter(|p| p.alive)
                    .collect()
            })
            .unwrap_or_default();
        if prefs.is_empty() {
            let has_wme = agent
                .wm
                .of_id(id)
                .filter_map(|w| agent.wm.get(w))
                .any(|w| w.attr == attr);
            if has_wme {
                return Ok(
                    "  This is probably an io- or arch-wme and does not have preferences\n".into(),
                );
            }
            // The id as typed (9.6 does not upper-case it here).
            let typed = parsed
                .args
                .first()
                .cloned()
                .unwrap_or_else(|| agent.symbols.text(id));
            return Err(ctx.error(format!(
                "Could not find prefs for the id,attribute pair: {typed} {attr_text}\nAn Error occured trying to print the prefs."
            )));
        }
        let context = attr_text == "operator" && agent.symbols.is_goal(id);
        let mut out = format!(
            "\nPreferences for {} ^{attr_text}:\n",
            agent.symbols.text(id)
        );
        for (kind, heading) in SECTIONS {
            let of_kind: Vec<&Preference> = prefs.iter().filter(|p| p.kind == kind).collect();
            if of_kind.is_empty() {
                continue;
            }
            out.push_str(&format!("\n{heading}:\n"));
            for p in of_kind {
                out.push_str(&self.pref_line(p, context));
                if names {
                    out.push_str(&self.rule_line(p));
                }
            }
        }
        if context {
            out.push_str(&self.selection_probabilities(&prefs, names));
        }
        Ok(out)
    }

    /// `  A1 (alpha) +  :I ` / `  E2 (e) = A1 (a) :I ` / `  (S1 ^thing x)  :I `, with
    /// ` [level N] ` for preferences below the top state.
    fn pref_line(&self, p: &Preference, context: bool) -> String {
        let agent = &self.agent;
        let support = if p.o_support { "O" } else { "I" };
        let body = if context {
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
        };
        let level = agent.symbols.id_data(p.id).map_or(1, |d| d.level);
        let level = if level > 1 {
            format!(" [level {level}] ")
        } else {
            String::new()
        };
        format!("  {body}:{support} {level}\n")
    }

    /// `    From rule` and a blank line, for `--names`.
    fn rule_line(&self, p: &Preference) -> String {
        match p.inst {
            Some(i) => {
                let prod = self.agent.decider.insts[i].prod;
                format!("    From {}\n\n", self.agent.production_name(prod))
            }
            None => "\n".into(),
        }
    }

    /// An operator with its names: `O1 (count-items)`.
    fn object_text(&self, o: Sym) -> String {
        let text = self.agent.symbols.text(o);
        let names = self.agent.name_values(o);
        if names.is_empty() {
            text
        } else {
            format!("{text} ({})", names.join(" "))
        }
    }

    /// The candidates an operator slot would choose among now, with their chances under
    /// the current policy's uniform or value-weighted draw (nothing for an impasse).
    fn selection_probabilities(&self, prefs: &[Preference], names: bool) -> String {
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
        let Ok(cands) = procedure::candidates(&for_procedure) else {
            return String::new();
        };
        let values: Vec<f64> = cands
            .iter()
            .map(|c| procedure::numeric_value(&for_procedure, *c, NumericMode::Sum))
            .collect();
        let total: f64 = values.iter().filter(|v| **v > 0.0).sum();
        let mut out = String::from("\nselection probabilities:\n");
        for (c, v) in cands.iter().zip(&values) {
            let chance = if cands.len() == 1 {
                1.0
            } else if total > 0.0 {
                v.max(0.0) / total
            } else {
                1.0 / cands.len() as f64
            };
            let made_by = prefs
                .iter()
                .find(|p| p.value == *c && p.kind == PrefType::Require)
                .or_else(|| {
                    prefs
                        .iter()
                        .find(|p| p.value == *c && p.kind == PrefType::Acceptable)
                });
            let (tc, support) = made_by.map_or(("+", "I"), |p| {
                (type_char(p.kind), if p.o_support { "O" } else { "I" })
            });
            out.push_str(&format!(
                "  {} {tc}  = {} :{support} ({:.2}%)\n",
                self.object_text(*c),
                value_number(*v),
                chance * 100.0
            ));
            if names {
                if let Some(p) = made_by {
                    out.push_str(&self.rule_line(p));
                }
            }
        }
        out
    }
}
