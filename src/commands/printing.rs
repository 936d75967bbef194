//! `print --stack` (`ps`) and `print --tree`: the goal stack as decision lines with a blank
//! cycle field, and working memory one WME per line in a tree (Soar manual, ch. 9, `print`;
//! checked against the official kernel's output).

use crate::agent::AgentCore;
use crate::symbols::Sym;
use crate::trace::{sorted_wmes, wme_line};
use std::collections::HashSet;

/// The values of `o ^name`, as a decision line shows them: `(a b)`, or nothing.
fn operator_name(agent: &AgentCore, o: Sym) -> String {
    let vals: Vec<String> = sorted_wmes(agent, o)
        .iter()
        .filter(|w| !w.acceptable && agent.symbols.text(w.attr) == "name")
        .map(|w| agent.symbols.text(w.value))
        .collect();
    if vals.is_empty() {
        String::new()
    } else {
        format!("({})", vals.join(" "))
    }
}

/// `print --stack [--states] [--operators]`: one line per state and selected operator, top
/// first, in the format of the decision trace with `      : ` for the cycle number. With
/// neither or both flags, states and operators.
pub fn print_stack(agent: &AgentCore, states: bool, operators: bool) -> String {
    let (states, operators) = if states == operators {
        (true, true)
    } else {
        (states, operators)
    };
    let mut out = String::new();
    let goals = &agent.decider.goals;
    if goals.is_empty() {
        // Before the first run: only the top state.
        if states {
            out.push_str(&format!(
                "      : ==>S: {} \n",
                agent.symbols.text(agent.top.state)
            ));
        }
        return out;
    }
    for g in goals {
        let indent = "   ".repeat(g.level.saturating_sub(1) as usize);
        if states {
            let what = match g.impasse {
                Some((kind, on_operator)) => format!(
                    "({} {})",
                    if on_operator { "operator" } else { "state" },
                    kind.word()
                ),
                None => String::new(),
            };
            out.push_str(&format!(
                "      : {indent}==>S: {} {what}\n",
                agent.symbols.text(g.state)
            ));
        }
        if let (true, Some((o, _))) = (operators, g.operator) {
            out.push_str(&format!(
                "      : {indent}   O: {} {}\n",
                agent.symbols.text(o),
                operator_name(agent, o)
            ));
        }
    }
    out
}

/// `print --tree [--depth n] [--internal] id`: one WME per line, each identifier's WMEs
/// right under the WME that leads to it (indented two spaces per level), each identifier
/// expanded once; `varprint` shows identifiers as variables.
pub fn print_tree(
    agent: &AgentCore,
    id: Sym,
    depth: usize,
    internal: bool,
    varprint: bool,
) -> String {
    let mut out = String::new();
    let mut seen = HashSet::from([id]);
    let style = (internal, varprint);
    tree_rec(agent, id, 0, depth.max(1), style, &mut seen, &mut out);
    out
}

fn tree_rec(
    agent: &AgentCore,
    id: Sym,
    level: usize,
    depth: usize,
    style: (bool, bool),
    seen: &mut HashSet<Sym>,
    out: &mut String,
) {
    for w in sorted_wmes(agent, id) {
        out.push_str(&"  ".repeat(level));
        out.push_str(&wme_line(agent, &w, style.0, style.1));
        out.push('\n');
        // An identifier as attribute goes below the WME too, before the value (as in 9.6).
        for v in [w.attr, w.value] {
            if level + 1 < depth && agent.symbols.is_id(v) && seen.insert(v) {
                tree_rec(agent, v, level + 1, depth, style, seen, out);
            }
        }
    }
}
