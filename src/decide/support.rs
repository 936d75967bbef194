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
    let operator = agent.top.operator;
    let on_operator = |op: Sym| -> Vec<bool> {
        prod.actions
            .iter()
            .filter_map(|a| match a {
                Action::Make(m) => Some(match &m.id {
                    RhsTerm::Var(v) => agent.rete.binding(p, t, v) == Some(op),
                    _ => false,
                }),
                Action::Call(_) => None,
            })
            .collect()
    };
    let selected = |u: TokId| {
        let wmes = agent.rete.match_wmes(p, u);
        let goal = goal_of(agent, wmes.iter().copied())?;
        wmes.iter().find_map(|&w| {
            let wme = agent.wm.get(w)?;
            (wme.id == goal && wme.attr == operator && !wme.acceptable).then_some(wme.value)
        })
    };
    support_over_matches(agent, t, selected, |op| on_operator(op).into_iter())
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

/// The o-support test's last step, as 9.6's matcher takes it when it queues a new match
/// `t`: over every complete match of the rule, `t` first, then the older ones (9.6 walks its
/// production node's tokens, the newest at the head). For each that tests its goal's
/// selected operator (`selected`), each make action is an elaboration when its object, as
/// the new match binds it, is that operator, and an application otherwise; one application
/// makes the new match O. A match that both elaborates and applies turns it back to I
/// (with 9.6's warning, when warnings are on). So a rule that only elaborates an operator
/// gets O for a new match while another of its matches holds another goal's operator, as in
/// 9.6 (observed on the official kernel with the default selection rules in stacked
/// substates).
fn support_over_matches<I: Iterator<Item = bool>>(
    agent: &AgentCore,
    t: TokId,
    selected: impl Fn(TokId) -> Option<Sym>,
    on_operator: impl Fn(Sym) -> I,
) -> MatchSupport {
    let mut support = MatchSupport {
        o_support: false,
        mixed: false,
    };
    let mut u = t;
    let mut looked = 0;
    while u != TokId::NONE {
        if let Some(op) = selected(u) {
            let mut elaborates = false;
            for on in on_operator(op) {
                if on {
                    elaborates = true;
                } else {
                    support.o_support = true;
                }
            }
            if support.o_support && elaborates {
                support.mixed = true;
                if agent.settings.warnings {
                    support.o_support = false;
                }
            }
        }
        // An O match stays O unless a later match elaborates its own operator, which
        // needs one of the new match's objects to be some goal's selected operator.
        if u == t
            && support.o_support
            && !agent.decider.goals.iter().any(|g| {
                g.operator
                    .is_some_and(|(op, _)| on_operator(op).any(|on| on))
            })
        {
            return support;
        }
        // (A rule with thousands of matches is not walked for each new one: past this
        // many, the older matches are left out.)
        looked += 1;
        if looked == MATCHES_LOOKED_AT {
            break;
        }
        u = agent.rete.older_in_node(u);
    }
    support
}

/// How many of a rule's matches [`support_over_matches`] looks at for a new one.
const MATCHES_LOOKED_AT: usize = 256;

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
    let operator = agent.top.operator;
    let selected = |u: TokId| {
        let row = agent.rete.token_row(u);
        let goal = compiled_goal(agent, rule, row)?;
        row.iter().find_map(|&w| {
            let wme = agent.wm.get(w)?;
            (wme.id == goal && wme.attr == operator && !wme.acceptable).then_some(wme.value)
        })
    };
    let on_operator = |op: Sym| {
        rule.make_ids.iter().map(move |b| {
            b.is_some_and(|(depth, field)| {
                let w = agent.rete.wme_at_depth(t, depth);
                w != crate::rete::NIL_WME && agent.rete.field(w, field) == op
            })
        })
    };
    support_over_matches(agent, t, selected, on_operator)
}
