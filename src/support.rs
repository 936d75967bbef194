//! Match-time support classification (spec §3b, §3c): a match's goal is the deepest state
//! among its positive conditions' identifiers, and a match that tests that goal's selected
//! operator (and proposes none) is an o-support candidate. The decision cycle refines this
//! at fire time.

use crate::agent::Agent;
use crate::production::{Action, RhsTerm};
use crate::rete::{ProdId, TokId};
use crate::symbols::Sym;

/// The lowest goal among the identifiers of a match's WMEs.
pub fn match_goal(agent: &Agent, p: ProdId, t: TokId) -> Option<Sym> {
    goal_of(agent, &agent.rete.match_wmes(p, t))
}

fn goal_of(agent: &Agent, wmes: &[crate::wm::WmeId]) -> Option<Sym> {
    let mut best: Option<(u32, Sym)> = None;
    for &w in wmes {
        let Some(wme) = agent.wm.get(w) else { continue };
        if agent.symbols.is_goal(wme.id) {
            let level = agent.symbols.id_data(wme.id).map_or(0, |d| d.level);
            if best.is_none_or(|(l, _)| level > l) {
                best = Some((level, wme.id));
            }
        }
    }
    best.map(|(_, s)| s)
}

/// Spec §3c at match time: the rule tests its goal's selected operator and does not
/// propose an operator.
pub fn tests_selected_operator(agent: &Agent, p: ProdId, t: TokId) -> bool {
    let name = agent.production_name(p).to_string();
    let Some(prod) = agent.production(&name) else {
        return false;
    };
    let proposes = prod.actions.iter().any(|a| match a {
        Action::Make(m) => {
            matches!(&m.attr, RhsTerm::Const(crate::ast::Constant::Str(s)) if s == "operator")
        }
        Action::Call(_) => false,
    });
    if proposes {
        return false;
    }
    let wmes = agent.rete.match_wmes(p, t);
    let Some(goal) = goal_of(agent, &wmes) else {
        return false;
    };
    let operator = agent.symbols.find_str("operator");
    for &w in &wmes {
        let Some(wme) = agent.wm.get(w) else { continue };
        if wme.id == goal && Some(wme.attr) == operator && !wme.acceptable {
            return true;
        }
    }
    false
}
