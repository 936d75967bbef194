//! Soar 9.6's print formats for working memory (spec §2, §6a): `print <id>` objects with
//! attributes sorted and wrapped at 80 columns, `print -i` one WME per line with timetags,
//! and `matches <rule>` partial-match listings.

use crate::agent::Agent;
use crate::printer::{cond_text, cond_text_with, test_text};
use crate::production::Condition;
use crate::symbols::Sym;
use crate::wm::{Wme, WmeId};

/// `(tt: id ^attr value[ +])`
pub fn wme_internal(agent: &Agent, w: &Wme) -> String {
    let s = &agent.symbols;
    format!(
        "({}: {} ^{} {}{})",
        w.timetag,
        s.text(w.id),
        s.text(w.attr),
        s.text(w.value),
        if w.acceptable { " +" } else { "" }
    )
}

/// The WMEs of an object as `print` orders them: by attribute text, newest first on ties.
pub fn sorted_wmes(agent: &Agent, id: Sym) -> Vec<Wme> {
    let mut ws: Vec<Wme> = agent
        .wm
        .of_id(id)
        .iter()
        .filter_map(|w| agent.wm.get(*w).copied())
        .collect();
    ws.reverse();
    ws.sort_by(|a, b| {
        agent
            .symbols
            .text(a.attr)
            .as_bytes()
            .cmp(agent.symbols.text(b.attr).as_bytes())
    });
    ws
}

/// `print <id>` with `--depth` and `--internal` (spec §6a): children indented two spaces per
/// level, each identifier printed once at its shallowest depth.
pub fn print_object(agent: &Agent, id: Sym, depth: usize, internal: bool) -> String {
    print_object_at(agent, id, depth, internal, 0)
}

/// [`print_object`] when the output stream is already at column `start_col`: 9.6 counts the
/// first line's width from there, so a print after a trace line wraps earlier (E:t7 vs
/// E:t2), even right after `(S1`.
pub fn print_object_at(
    agent: &Agent,
    id: Sym,
    depth: usize,
    internal: bool,
    start_col: usize,
) -> String {
    let mut out = String::new();
    let mut seen = std::collections::HashSet::new();
    let mut frontier = vec![(id, 0usize)];
    // Breadth first, so an identifier prints at its shallowest depth.
    let mut order = Vec::new();
    while let Some((x, d)) = frontier.first().copied() {
        frontier.remove(0);
        if !seen.insert(x) {
            continue;
        }
        order.push((x, d));
        if d + 1 < depth {
            for w in sorted_wmes(agent, x) {
                if agent.symbols.is_id(w.value) && !seen.contains(&w.value) {
                    frontier.push((w.value, d + 1));
                }
            }
        }
    }
    // Print depth-first in the breadth-first ownership, as Soar lists children after parents.
    let owners: std::collections::HashMap<Sym, usize> =
        order.iter().map(|(x, d)| (*x, *d)).collect();
    let mut printed = std::collections::HashSet::new();
    let mut col = start_col;
    print_rec(
        agent,
        id,
        0,
        depth,
        internal,
        &owners,
        &mut printed,
        &mut out,
        &mut col,
    );
    out
}

#[allow(clippy::too_many_arguments)]
fn print_rec(
    agent: &Agent,
    id: Sym,
    level: usize,
    depth: usize,
    internal: bool,
    owners: &std::collections::HashMap<Sym, usize>,
    printed: &mut std::collections::HashSet<Sym>,
    out: &mut String,
    // The stream's column where the first line starts (0 after it).
    col: &mut usize,
) {
    if !printed.insert(id) {
        return;
    }
    let wmes = sorted_wmes(agent, id);
    if wmes.is_empty() && level > 0 {
        return;
    }
    let indent = "  ".repeat(level);
    if internal {
        for w in &wmes {
            out.push_str(&indent);
            out.push_str(&wme_internal(agent, w));
            out.push('\n');
        }
    } else {
        let head = format!("{indent}({}", agent.symbols.text(id));
        let mut line = head.clone();
        for w in &wmes {
            let item = format!(
                " ^{} {}{}",
                agent.symbols.text(w.attr),
                agent.symbols.text(w.value),
                if w.acceptable { " +" } else { "" }
            );
            // 9.6 wraps when the item would reach column 79, also before the first attribute
            // (`(I4` alone on its line); checked against the official kernel at both edges.
            if *col + line.len() + item.len() >= 79 {
                out.push_str(&line);
                out.push('\n');
                *col = 0;
                // Continuation lines start 7 columns in, under the first attribute (E:t5).
                line = format!("{indent}       {}", &item[1..]);
            } else {
                line.push_str(&item);
            }
        }
        line.push(')');
        out.push_str(&line);
        out.push('\n');
    }
    *col = 0;
    if level + 1 < depth {
        for w in &wmes {
            if agent.symbols.is_id(w.value) && owners.get(&w.value) == Some(&(level + 1)) {
                print_rec(
                    agent,
                    w.value,
                    level + 1,
                    depth,
                    internal,
                    owners,
                    printed,
                    out,
                    col,
                );
            }
        }
    }
}

/// `matches <rule>` (spec §6a): each condition with its partial-match count; from the first
/// condition with none, `>>>>` marks where matching stops.
pub fn matches_listing(agent: &Agent, name: &str) -> Option<String> {
    let loaded = agent.loaded(name)?;
    let counts = agent.rete.partial_match_counts(loaded.id, &agent.symbols);
    let mut out = String::new();
    let mut stopped = false;
    let mut goal_shown = std::collections::HashSet::new();
    for (i, count) in counts {
        let cond = &loaded.production.conditions[i];
        let text = match cond {
            Condition::Ncc(inner) => {
                let mut s = String::from("    -{\n");
                for c in inner {
                    s.push_str("          ");
                    s.push_str(&cond_text(c));
                    s.push('\n');
                }
                s.push_str(&format!("{} }}", counted(count, &mut stopped).trim_end()));
                out.push_str(&s);
                out.push('\n');
                continue;
            }
            Condition::Positive(c) | Condition::Negative(c) => {
                let first = goal_shown.insert(test_text(&c.id));
                cond_text_with(cond, first)
            }
        };
        out.push_str(&counted(count, &mut stopped));
        out.push_str(&text);
        out.push('\n');
    }
    let complete = agent.rete.matches_of(loaded.id).len();
    out.push_str(&format!("\n{complete} complete matches.\n"));
    Some(out)
}

fn counted(count: usize, stopped: &mut bool) -> String {
    if *stopped {
        "     ".to_string()
    } else if count == 0 {
        *stopped = true;
        ">>>> ".to_string()
    } else {
        format!("{count:>4} ")
    }
}

/// `matches` with no rule: the pending assertions and retractions, with their goals.
pub fn pending_matches(agent: &Agent) -> String {
    let mut o = String::from("O Assertions:\n");
    let mut i = String::from("I Assertions:\n");
    for &(p, t) in &agent.matches.assertions {
        let line = format!(
            "  {}  [{}] \n",
            agent.production_name(p),
            goal_text(agent, p, t)
        );
        if agent.is_o_supported(p, t) {
            o.push_str(&line);
        } else {
            i.push_str(&line);
        }
    }
    let mut r = String::from("Retractions:\n");
    for &(p, _) in &agent.matches.retractions {
        r.push_str(&format!("  {}\n", agent.production_name(p)));
    }
    format!("{o}{i}{r}")
}

fn goal_text(agent: &Agent, p: crate::rete::ProdId, t: crate::rete::TokId) -> String {
    match crate::support::match_goal(agent, p, t) {
        Some(g) => agent.symbols.text(g),
        None => "NIL".into(),
    }
}

/// The WMEs of a complete match, for `matches -w`.
pub fn match_wme_lines(agent: &Agent, ws: &[WmeId]) -> String {
    ws.iter()
        .filter_map(|w| agent.wm.get(*w))
        .map(|w| wme_internal(agent, w))
        .collect::<Vec<_>>()
        .join("\n ")
}
