//! Singletons in chunking (Soar manual, ch. 4, "Chunking", and ch. 9, `chunk singleton`):
//! which superstate WMEs chunking takes to be the only one of their kind, so that two
//! conditions on one have their values unified.

use super::settings::ElementType;

impl crate::agent::AgentCore {
    /// Whether chunking unifies the values of two conditions that test `wme` in a
    /// superstate (Soar manual, ch. 4, "Chunking", singletons): the architecture's own
    /// singletons (a state's `^superstate`, `^type`, `^impasse`, `^attribute`, memory links,
    /// and its selected `^operator`), a user pattern the WME fits, and with
    /// `automatically-create-singletons` on every other WME whose attribute is a string.
    pub(crate) fn is_singleton(&self, wme: &crate::wm::Wme) -> bool {
        let symbols = &self.symbols;
        let known = &symbols.known;
        if symbols.is_goal(wme.id) {
            if wme.attr == known.operator {
                return !wme.acceptable;
            }
            let architectural = ["superstate", "type", "impasse", "attribute", "reward-link", "epmem", "smem"];
            if let crate::symbols::SymData::Str(a) = symbols.get(wme.attr) {
                if architectural.contains(&&**a) {
                    return true;
                }
            }
        }
        let crate::symbols::SymData::Str(attr) = symbols.get(wme.attr) else {
            return false;
        };
        let settings = &self.settings.chunk;
        match settings.singletons.iter().find(|p| *p.attribute == **attr) {
            Some(p) => self.fits(wme.id, p.id) && self.fits(wme.value, p.value),
            None => settings.automatically_create_singletons,
        }
    }

    /// Whether symbol `s` is of element type `t`.
    fn fits(&self, s: crate::symbols::Sym, t: ElementType) -> bool {
        let is_id = self.symbols.is_id(s);
        let is_state = self.symbols.is_goal(s);
        match t {
            ElementType::Any => true,
            ElementType::Constant => !is_id,
            ElementType::State => is_state,
            ElementType::Operator => is_id && self.is_operator(s),
            ElementType::Identifier => is_id && !is_state && !self.is_operator(s),
        }
    }

    /// Whether identifier `s` is an operator: a value of some state's `^operator`.
    fn is_operator(&self, s: crate::symbols::Sym) -> bool {
        let op = self.symbols.known.operator;
        self.decider.goals.iter().any(|g| {
            self.decider.slots.get(&(g.state, op)).is_some_and(|slot| {
                slot.wmes.contains_key(&(s, true)) || slot.wmes.contains_key(&(s, false))
            })
        })
    }
}
