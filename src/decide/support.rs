//! Match-time support classification (Soar manual, chapter 2, "The calculation of o-support"): a
//! match's goal is the deepest state among its positive conditions' identifiers, and a
//! match that tests that goal's selected operator (and proposes none) is an o-support
//! candidate. The decision cycle refines this at fire time.

use crate::agent::AgentCore;
use crate::decide::compiled::CompiledRule;
use crate::production::{Action, RhsTerm};
use crate::rete::{ProdId, TokId};
use crate::symbols::Sym;

/// The lowest goal among the identifiers of a match's WMEs: read at the places of the
/// rule's distinct identifiers once it is compiled, else from every WME of the match.
pub fn match_goal(agent: &AgentCore, p: ProdId, t: TokId) -> Option<Sym> {
    match agent.decider.compiled.get(p.0 as usize) {
        Some(Some(rule)) if t != TokId::NONE => compiled_goal(agent, rule, agent.rete.token_row(t)),
        _ => goal_of(agent, agent.rete.chain_wmes(t)),
    }
}

/// The lowest goal among a compiled rule's identifiers in a match's row.
fn compiled_goal(agent: &AgentCore, rule: &CompiledRule, row: &[crate::wm::WmeId]) -> Option<Sym> {
    goal_among(
        agent,
        rule.id_places.iter().filter_map(|&(depth, field)| {
            let w = *row.get(depth as usize)?;
            (w != crate::rete::NIL_WME).then(|| agent.rete.field(w, field))
        }),
    )
}

pub(crate) fn goal_of(agent: &AgentCore, wmes: impl Iterator<Item = crate::wm::WmeId>) -> Option<Sym> {
    goal_among(
        agent,
        wmes.filter_map(|w| agent.wm.get(w).map(|wme| wme.id)),
    )
}

/// The lowest goal among some identifiers.
pub(crate) fn goal_among(agent: &AgentCore, ids: impl Iterator<Item = Sym>) -> Option<Sym> {
    let mut best: Option<(u32, Sym)> = None;
    for id in ids {
        if let Some(d) = agent.symbols.id_data(id).filter(|d| d.is_goal) {
            if best.is_none_or(|(l, _)| d.level > l) {
                best = Some((d.level, id));
            }
        }
    }
    best.map(|(_, s)| s)
}

/// The support a match gets (decided at match time as 9.6's rete does).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MatchSupport {
    pub o_support: bool,
    /// The rule both elaborates the selected operator and applies it: I-support, with
    /// 9.6's warning (observed on the official kernel).
    pub mixed: bool,
}

/// Declared support wins; a rule that proposes an operator is I; otherwise a rule that
/// tests its goal's selected operator is O if one of its make actions is on something other
/// than that operator (an application), I if all are on the operator (operator
/// elaborations); both is I with a warning (when warnings are on).
pub fn match_support(agent: &AgentCore, p: ProdId, t: TokId) -> MatchSupport {
    let i_support = MatchSupport {
        o_support: false,
        mixed: false,
    };
    if let Some(Some(rule)) = agent.decider.compiled.get(p.0 as usize) {
        return compiled_support(agent, rule, t);
    }
    let name = agent.production_name(p);
    let Some(prod) = agent.production(name) else {
        return i_support;
    };
    if prod.flags.o_support {
        return MatchSupport {
            o_support: true,
            mixed: false,
        };
    }
    if prod.flags.i_support {
        return i_support;
    }
    let proposes = prod.actions.iter().any(|a| match a {
        Action::Make(m) => {
            m.pref == crate::production::PrefKind::Acceptable
                && matches!(&m.attr, RhsTerm::Const(crate::ast::Constant::Str(s)) if &**s == "operator")
        }
        Action::Call(_) => false,
    });
    if proposes {
        return i_support;
    }
    let wmes = agent.rete.match_wmes(p, t);
    let Some(goal) = goal_of(agent, wmes.iter().copied()) else {
        return i_support;
    };
    let operator = agent.symbols.find_str("operator");
    let selected = wmes.iter().find_map(|&w| {
        let wme = agent.wm.get(w)?;
        (wme.id == goal && Some(wme.attr) == operator && !wme.acceptable).then_some(wme.value)
    });
    let Some(op) = selected else {
        return i_support;
    };
    let on_operator = prod.actions.iter().filter_map(|a| match a {
        Action::Make(m) => Some(match &m.id {
            RhsTerm::Var(v) => agent.rete.binding(p, t, v) == Some(op),
            _ => false,
        }),
        Action::Call(_) => None,
    });
    support_of_actions(agent, on_operator)
}

impl AgentCore {
    /// The support of a pending match: decided when it was queued, or now.
    pub fn is_o_supported(&self, p: ProdId, t: TokId) -> bool {
        match self.matches.support.get(&(p, t)) {
            Some(&o) => o,
            None => crate::decide::support::match_support(self, p, t).o_support,
        }
    }
}

/// The o-support test's last step, given for each make action whether it is on the selected
/// operator: applications are O, operator elaborations I, both I (with 9.6's warning).
fn support_of_actions(agent: &AgentCore, on_operator: impl Iterator<Item = bool>) -> MatchSupport {
    let (mut elaborates, mut applies) = (false, false);
    for on in on_operator {
        if on {
            elaborates = true;
        } else {
            applies = true;
        }
    }
    let mixed = elaborates && applies;
    MatchSupport {
        o_support: applies && !(mixed && agent.settings.warnings),
        mixed,
    }
}

/// [`match_support`] for a rule whose actions are compiled: the same test without names.
fn compiled_support(agent: &AgentCore, rule: &CompiledRule, t: TokId) -> MatchSupport {
    let i_support = MatchSupport {
        o_support: false,
        mixed: false,
    };
    if rule.flags.o_support {
        return MatchSupport {
            o_support: true,
            mixed: false,
        };
    }
    if rule.flags.i_support || rule.proposes || !rule.may_test_operator {
        return i_support;
    }
    if t == TokId::NONE {
        return i_support;
    }
    let row = agent.rete.token_row(t);
    let Some(goal) = compiled_goal(agent, rule, row) else {
        return i_support;
    };
    let operator = agent.top.operator;
    let selected = row.iter().find_map(|&w| {
        let wme = agent.wm.get(w)?;
        (wme.id == goal && wme.attr == operator && !wme.acceptable).then_some(wme.value)
    });
    let Some(op) = selected else {
        return i_support;
    };
    let on_operator = rule.make_ids.iter().map(|b| {
        b.is_some_and(|(depth, field)| {
            let w = agent.rete.wme_at_depth(t, depth);
            w != crate::rete::NIL_WME && agent.rete.field(w, field) == op
        })
    });
    support_of_actions(agent, on_operator)
}
