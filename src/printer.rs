//! Printing productions and symbols back in Soar 9.6's form (`print <rule>`): constants in
//! rereadable form, conditions grouped by identifier, 80-column wrapping. Constants print
//! as `constants.rs` says; a single test, term or action as the production types' own text
//! functions do (`production.rs`, whose load-time messages quote them too).

pub(crate) mod constants;

pub use constants::{float_text, push_constant_text, rereadable};

use crate::ast::{Constant, Head};
use crate::production::{
    call_text, rhs_term_text, test_text, Action, Cond, Condition, Make, PrefKind, Production,
    RhsTerm,
};

/// An action's id: identifier-shaped constants (`S1`) print bare, as they were written.
fn rhs_id_text(t: &RhsTerm) -> String {
    match t {
        RhsTerm::Const(Constant::Str(s)) if crate::lexer::is_identifier_shaped(s) => s.to_string(),
        other => rhs_term_text(other),
    }
}

fn is_operator(t: &RhsTerm) -> bool {
    matches!(t, RhsTerm::Const(Constant::Str(s)) if &**s == "operator")
}

/// ` ^attr value [pref [referent]]` as it appears inside a printed make action.
fn make_item(m: &Make) -> String {
    let mut s = format!("^{} {}", rhs_term_text(&m.attr), rhs_term_text(&m.value));
    let show_pref = match m.pref {
        PrefKind::Acceptable => is_operator(&m.attr),
        _ => true,
    };
    if show_pref {
        s.push(' ');
        s.push_str(m.pref.symbol());
        if let Some(r) = &m.referent {
            s.push(' ');
            s.push_str(&rhs_term_text(r));
        }
    }
    s
}

/// Appends `items` after `head`, wrapping before an item that would make the line reach
/// `limit` columns (79 for conditions and actions alike, observed on soar-sml 9.6.5); even
/// the first item goes to a new line when it does not fit after the head.
fn wrap_items_at(
    out: &mut String,
    head: &str,
    items: &[String],
    indent: usize,
    close: &str,
    limit: usize,
) {
    let mut line = head.to_string();
    let mut first = true;
    for it in items {
        let sep = if first { "" } else { " " };
        if line.len() + sep.len() + it.len() >= limit {
            out.push_str(line.trim_end());
            out.push('\n');
            line = " ".repeat(indent);
            line.push_str(it);
        } else {
            line.push_str(sep);
            line.push_str(it);
        }
        first = false;
    }
    line.push_str(close);
    out.push_str(&line);
}

/// One condition on its own line, as `matches <rule>` lists them: `(state <s> ^a 1)`,
/// `(<x> -^b 2)`, or a conjunctive negation's conditions inside `-{ ... }`.
pub fn cond_text(c: &Condition) -> String {
    cond_text_with(c, true)
}

/// As [`cond_text`]; `show_goal` false leaves out `state`/`impasse` (Soar shows it on the
/// first condition of an identifier only).
pub fn cond_text_with(c: &Condition, show_goal: bool) -> String {
    let one = |c: &Cond, neg: bool| {
        let head = match if show_goal { c.goal } else { Head::None } {
            Head::State => "state ",
            Head::Impasse => "impasse ",
            Head::None => "",
        };
        format!("({head}{} {})", test_text(&c.id), cond_item(c, neg))
    };
    match c {
        Condition::Positive(c) => one(c, false),
        Condition::Negative(c) => one(c, true),
        Condition::Ncc(inner) => {
            let parts: Vec<String> = inner.iter().map(cond_text).collect();
            format!("-{{ {} }}", parts.join(" "))
        }
    }
}

fn cond_item(c: &Cond, negated: bool) -> String {
    let mut s = String::new();
    if negated {
        s.push('-');
    }
    s.push('^');
    s.push_str(&test_text(&c.attr));
    s.push(' ');
    s.push_str(&test_text(&c.value));
    if c.acceptable {
        s.push_str(" +");
    }
    s
}

/// Prints a list of conditions, grouping those on the same id (at this level) into one
/// parenthesised condition at the place of the first, as Soar prints them; `internal`
/// (`print --internal`) prints each condition alone, as the matcher holds it.
fn print_conditions(out: &mut String, conds: &[Condition], indent: usize, internal: bool) {
    if internal {
        print_conditions_internal(out, conds, indent);
        return;
    }
    enum Item<'a> {
        Group(String, Head, Vec<(&'a Cond, bool)>),
        Ncc(&'a [Condition]),
    }
    let mut items: Vec<Item> = Vec::new();
    for c in conds {
        let (cc, neg) = match c {
            Condition::Ncc(inner) => {
                items.push(Item::Ncc(inner));
                continue;
            }
            Condition::Positive(cc) => (cc, false),
            Condition::Negative(cc) => (cc, true),
        };
        let id = test_text(&cc.id);
        // A negated condition's state/impasse test can ride on the group's head only if a
        // positive condition on the same id (at this level) has the same test; otherwise the
        // condition gets a group of its own, `(state <x> -^a v)`, so the test is not lost.
        let own = neg
            && cc.goal != Head::None
            && !conds
                .iter()
                .any(|o| matches!(o, Condition::Positive(p) if p.id == cc.id && p.goal == cc.goal));
        let key = if own { cc.goal } else { Head::None };
        let existing = items.iter_mut().find_map(|it| match it {
            Item::Group(gid, k, members) if *gid == id && *k == key => Some(members),
            _ => None,
        });
        match existing {
            Some(members) => members.push((cc, neg)),
            None => items.push(Item::Group(id, key, vec![(cc, neg)])),
        }
    }
    for it in items {
        match it {
            Item::Ncc(inner) => {
                out.push_str(&" ".repeat(indent.saturating_sub(1)));
                out.push_str("-{ ");
                let mut body = String::new();
                print_conditions(&mut body, inner, indent + 2, false);
                push_ncc_body(out, &body);
            }
            Item::Group(id, key, members) => {
                let goal = members
                    .iter()
                    .find(|(c, neg)| !neg && c.goal != Head::None)
                    .map(|(c, _)| c.goal)
                    .unwrap_or(key);
                let texts: Vec<String> =
                    members.iter().map(|(c, neg)| cond_item(c, *neg)).collect();
                // A lone negated condition prints inside the parentheses too: `(<w> -^a v)`.
                let mut head = " ".repeat(indent);
                head.push('(');
                match goal {
                    Head::State => head.push_str("state "),
                    Head::Impasse => head.push_str("impasse "),
                    Head::None => {}
                }
                head.push_str(&id);
                head.push(' ');
                // Continuation lines start 6 past the indent, whatever the id (observed).
                let cont = indent + 6;
                wrap_items_at(out, &head, &texts, cont, ")", 79);
                out.push('\n');
            }
        }
    }
}

/// A negated conjunction's conditions printed at `indent + 2`, after `-{ ` (the first line
/// sits after it, the rest keep their own indent).
fn push_ncc_body(out: &mut String, body: &str) {
    out.push_str(body.trim_start().trim_end_matches('\n'));
    out.push_str("}\n");
}

/// `print --internal`: one condition a line in the matcher's order. A state or impasse
/// test is printed on the first condition of its identifier that carries it, as 9.6 keeps
/// it on one condition.
fn print_conditions_internal(out: &mut String, conds: &[Condition], indent: usize) {
    let mut headed: Vec<(String, Head)> = Vec::new();
    for c in conds {
        let (cc, neg) = match c {
            Condition::Ncc(inner) => {
                out.push_str(&" ".repeat(indent.saturating_sub(1)));
                out.push_str("-{ ");
                let mut body = String::new();
                print_conditions_internal(&mut body, inner, indent + 2);
                push_ncc_body(out, &body);
                continue;
            }
            Condition::Positive(cc) => (cc, false),
            Condition::Negative(cc) => (cc, true),
        };
        let id = test_text(&cc.id);
        let mut head = " ".repeat(indent);
        head.push('(');
        if cc.goal != Head::None && !headed.iter().any(|(i, g)| *i == id && *g == cc.goal) {
            headed.push((id.clone(), cc.goal));
            head.push_str(if cc.goal == Head::State { "state " } else { "impasse " });
        }
        head.push_str(&id);
        head.push(' ');
        wrap_items_at(out, &head, &[cond_item(cc, neg)], indent + 6, ")", 79);
        out.push('\n');
    }
}

/// Prints the actions, each make action grouped with every later one on the same id (at the
/// place of the first, as 9.6 prints them), function calls where they stand.
fn print_actions(out: &mut String, actions: &[Action], internal: bool) {
    let mut printed = vec![false; actions.len()];
    for i in 0..actions.len() {
        if printed[i] {
            continue;
        }
        match &actions[i] {
            Action::Call(f) => {
                out.push_str("    ");
                out.push_str(&call_text(f));
                out.push('\n');
            }
            Action::Make(m) => {
                let id = rhs_id_text(&m.id);
                let mut items = Vec::new();
                for (j, a) in actions.iter().enumerate().skip(i) {
                    if let Action::Make(mm) = a {
                        // `--internal` keeps each action alone.
                        if internal && j > i {
                            break;
                        }
                        if !printed[j] && rhs_id_text(&mm.id) == id {
                            items.push(make_item(mm));
                            printed[j] = true;
                        }
                    }
                }
                let head = format!("    ({id} ");
                // Continuation lines of an action start in column 12, whatever the id; an
                // action wraps even before its first item (observed on soar-sml 9.6.5).
                let cont = 11;
                wrap_items_at(out, &head, &items, cont, ")", 79);
                out.push('\n');
            }
        }
    }
}

/// `print <rule>` text (without the trailing blank line Soar adds after the brace).
pub fn production_text(p: &Production) -> String {
    production_text_as(p, false)
}

/// [`production_text`], or with `internal` (`print --internal`) each condition and each
/// action on a line of its own, in the matcher's order.
pub fn production_text_as(p: &Production, internal: bool) -> String {
    let mut out = format!("sp {{{}\n", rereadable(&p.name));
    if let Some(doc) = &p.doc {
        out.push_str(&format!(
            "    \"{}\"\n",
            doc.replace('\\', "\\\\").replace('"', "\\\"")
        ));
    }
    let f = &p.flags;
    for (on, name) in [
        (f.default, "    :default"),
        (f.chunk, "    :chunk"),
        (f.justification, "    :justification ;# not reloadable"),
        (f.o_support, "    :o-support"),
        (f.i_support, "    :i-support"),
        // The kernel indents :template one space less than the others (observed).
        (f.template, "   :template"),
        (f.interrupt, "    :interrupt"),
        // 9.6 does not print :explain back; we do, so that printing and re-reading a rule
        // keeps it (rules must survive a print and a reload unchanged).
        (f.explain, "    :explain"),
    ] {
        if on {
            out.push_str(name);
            out.push('\n');
        }
    }
    print_conditions(&mut out, &p.conditions, 4, internal);
    out.push_str("    -->\n");
    if p.actions.is_empty() {
        // Soar prints an indented empty line for an empty right-hand side.
        out.push_str("    \n");
    }
    print_actions(&mut out, &p.actions, internal);
    out.push_str("}\n");
    out
}
