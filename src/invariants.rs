//! The kernel's consistency checks, for tests and fuzzing: properties that hold between
//! phases of the decision cycle whatever the agent does. A violation names the structure
//! and the element that break it.
//!
//! - Every WME's identifier is linked to a goal, through WMEs (acceptable-preference ones
//!   included) and the identifiers preferences name: garbage collection leaves nothing
//!   unlinked (Soar manual, ch. 2, "Working memory", on the removal of unlinked elements).
//!   Objects below an identifier no WME ever pointed at are the exception: collection
//!   searches only identifiers that lose a link, so an object made by an action whose link
//!   to it failed (`(<v> ^b <new>)` with `<v>` bound to a constant) stays, as in 9.6.
//! - No token of the matcher holds a WME that left working memory.
//! - Each slot's preferences are live and are for that slot's identifier and attribute,
//!   and each WME a slot shows is in working memory with the slot's identifier and
//!   attribute.
//! - Each WME in a goal dependency set is in working memory, the goal it is charged to is
//!   a live substate, and the WME's identifier belongs to a goal above that substate (the
//!   GDS holds only what a substate's reasoning tested higher up; Soar manual, ch. 2, "The
//!   Goal Dependency Set").

use crate::agent::AgentCore;
use crate::rete::NIL_WME;
use crate::symbols::Sym;
use rustc_hash::{FxHashMap, FxHashSet};

impl AgentCore {
    /// Every broken invariant, described; empty when all hold.
    pub(crate) fn invariant_violations(&self) -> Vec<String> {
        let mut out = Vec::new();
        self.check_links(&mut out);
        self.check_tokens(&mut out);
        self.check_slots(&mut out);
        self.check_gds(&mut out);
        out
    }

    fn check_gds(&self, out: &mut Vec<String>) {
        for (&w, &crate::decide::state::GdsMember { goal, .. }) in self.decider.gds.iter() {
            let Some(wme) = self.wm.get(w) else {
                out.push(format!(
                    "goal dependency set of {}: holds a WME no longer in working memory",
                    self.symbols.text(goal)
                ));
                continue;
            };
            let shown = format!(
                "({}: {} ^{} {})",
                wme.timetag,
                self.symbols.text(wme.id),
                self.symbols.text(wme.attr),
                self.symbols.text(wme.value)
            );
            let live = self.decider.goals.iter().skip(1).any(|g| g.state == goal);
            if !live {
                out.push(format!(
                    "goal dependency set: {shown} is charged to {}, which is not a substate",
                    self.symbols.text(goal)
                ));
            } else if self.sym_level(wme.id) > self.sym_level(goal)
                || (self.sym_level(wme.id) == self.sym_level(goal)
                    && self.held_by_preferences(w, wme))
            {
                out.push(format!(
                    "goal dependency set of {}: {shown} is neither from a goal above it nor \
                     the architecture's",
                    self.symbols.text(goal)
                ));
            }
        }
    }

    fn check_links(&self, out: &mut Vec<String>) {
        // A preference links the identifiers it names too (9.6 keeps an object that only a
        // binary preference's referent names, such as `(S1 ^operator O1 > O2)`).
        let mut by_prefs: FxHashMap<Sym, Vec<Sym>> = FxHashMap::default();
        for (_, slot) in self.decider.slots.iter() {
            for &pid in &slot.prefs {
                let p = &self.decider.prefs[pid];
                let named = by_prefs.entry(p.id).or_default();
                named.push(p.value);
                named.extend(p.referent);
            }
        }
        let mut linked: FxHashSet<Sym> = FxHashSet::default();
        let mut stack: Vec<Sym> = self.decider.goals.iter().map(|g| g.state).collect();
        stack.push(self.top.state);
        // Roots besides the goals: objects never linked, and an object whose link failed
        // (it stays, with what it links, as in 9.6).
        let all = self.wm.all();
        for w in all.iter().filter_map(|&w| self.wm.get(w)) {
            if !self.wm.ever_pointed_at(w.id) {
                stack.push(w.id);
            }
            stack.extend(
                [w.id, w.value]
                    .into_iter()
                    .filter(|&x| self.wm.had_failed_link(x)),
            );
        }
        while let Some(id) = stack.pop() {
            if !linked.insert(id) {
                continue;
            }
            let by_wmes = self
                .wm
                .of_id(id)
                .filter_map(|w| self.wm.get(w))
                .map(|w| w.value);
            let named = by_prefs.get(&id).into_iter().flatten().copied();
            for value in by_wmes.chain(named) {
                if self.symbols.is_id(value) && !linked.contains(&value) {
                    stack.push(value);
                }
            }
        }
        for w in all {
            let Some(wme) = self.wm.get(w) else { continue };
            if !linked.contains(&wme.id) {
                out.push(format!(
                    "working memory: ({}: {} ^{} {}) is not linked to any goal",
                    wme.timetag,
                    self.symbols.text(wme.id),
                    self.symbols.text(wme.attr),
                    self.symbols.text(wme.value)
                ));
            }
        }
    }

    fn check_tokens(&self, out: &mut Vec<String>) {
        for (i, tok) in self.rete.tokens.iter().enumerate() {
            if !tok.alive {
                continue;
            }
            let t = crate::rete::TokId::new(i as u32);
            for &w in self.rete.token_row(t) {
                if w != NIL_WME && self.wm.get(w).is_none() {
                    out.push(format!(
                        "matcher: token {i} holds a WME no longer in working memory"
                    ));
                }
            }
        }
    }

    fn check_slots(&self, out: &mut Vec<String>) {
        for ((id, attr), slot) in self.decider.slots.iter() {
            let name = format!("({} ^{})", self.symbols.text(*id), self.symbols.text(*attr));
            for &pid in &slot.prefs {
                let p = &self.decider.prefs[pid];
                if p.freed || !p.alive {
                    out.push(format!("slot {name}: holds a preference that was removed"));
                } else if p.id != *id || p.attr != *attr {
                    out.push(format!(
                        "slot {name}: holds a preference for ({} ^{})",
                        self.symbols.text(p.id),
                        self.symbols.text(p.attr)
                    ));
                }
            }
            for (value, acceptable, w) in slot.wmes.iter() {
                match self.wm.get(w) {
                    Some(wme)
                        if wme.id == *id
                            && wme.attr == *attr
                            && wme.value == value
                            && wme.acceptable == acceptable => {}
                    _ => out.push(format!(
                        "slot {name}: shows {} by a WME that is not in working memory as such",
                        self.symbols.text(value)
                    )),
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::agent::AgentCore;

    #[test]
    fn a_fresh_agent_holds_every_invariant() {
        let core = AgentCore::new("t");
        assert_eq!(core.invariant_violations(), Vec::<String>::new());
    }

    #[test]
    fn an_element_on_an_unlinked_identifier_is_named() {
        let mut core = AgentCore::new("t");
        let loose = core.symbols.new_id('X', 1);
        let (attr, value) = (core.symbols.str("color"), core.symbols.str("red"));
        let thing = core.symbols.str("thing");
        let link = core.add_wme(core.top.state, thing, loose, false);
        core.add_wme(loose, attr, value, false);
        assert_eq!(core.invariant_violations(), Vec::<String>::new());
        // The link goes, and no garbage collection follows.
        core.remove_wme(link);
        let found = core.invariant_violations();
        assert_eq!(found.len(), 1, "{found:?}");
        assert!(found[0].contains("X1 ^color red") && found[0].contains("not linked"));
    }

    #[test]
    fn an_object_nothing_ever_pointed_at_is_not_garbage() {
        let mut core = AgentCore::new("t");
        let loose = core.symbols.new_id('X', 1);
        let (attr, value) = (core.symbols.str("color"), core.symbols.str("red"));
        core.add_wme(loose, attr, value, false);
        assert_eq!(core.invariant_violations(), Vec::<String>::new());
    }

    #[test]
    fn a_dependency_charged_to_the_top_state_is_named() {
        let mut core = AgentCore::new("t");
        let w = core.wm.of_id(core.top.state).next().expect("S1 has WMEs");
        let member = crate::decide::state::GdsMember {
            goal: core.top.state,
            joined: 1,
        };
        core.decider.gds.insert(w, member);
        let found = core.invariant_violations();
        assert_eq!(found.len(), 1, "{found:?}");
        assert!(found[0].contains("charged to S1, which is not a substate"));
    }
}
