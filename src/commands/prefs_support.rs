//! The support forms of `preferences` (Soar manual, ch. 9, `preferences`): the WMEs that
//! point at an identifier that is not a state, each with the preferences behind it, and
//! `--object`, every slot of an object with its architecture and input WMEs. They follow
//! 9.6's picture of an object: its slots (the ones rules made preferences in, a state's
//! operator slot, and the memories' link WMEs), the WMEs the architecture made for a state
//! and its impasse, and input WMEs (everything else: the io link and what the environment or
//! `wm add` added). Checked against soar-sml 9.6.5.

use super::prefs::{Detail, SECTIONS};
use super::Interpreter;
use crate::decide::procedure::PrefType;
use crate::symbols::Sym;
use crate::wm::{Wme, WmeId};

use crate::decide::state::{STATE_ARCH_ATTRS, STATE_MODULE_ATTRS};
/// The same on the episodic and semantic memories' link objects.
const EPMEM_MODULE_ATTRS: [&str; 3] = ["command", "result", "present-id"];
const SMEM_MODULE_ATTRS: [&str; 2] = ["command", "result"];

/// Where a WME comes from, as 9.6 tells it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Origin {
    /// Made from a slot's preferences (or the operator a state selected).
    Preference,
    /// A state's architecture WME that stands for a preference (an impasse's `^item` and
    /// `^non-numeric`).
    ArchWithPreference,
    /// Another architecture WME of a state.
    Arch,
    /// A memory's link WME (in a slot, without preferences).
    Module,
    /// Everything else: input.
    Input,
}

impl Interpreter {
    /// The states: the top state and each substate.
    fn states(&self) -> Vec<Sym> {
        let agent = &self.agent;
        let mut out = vec![agent.top.state];
        out.extend(
            agent
                .decider
                .goals
                .iter()
                .map(|g| g.state)
                .filter(|s| *s != agent.top.state),
        );
        out
    }

    /// The module attributes 9.6 gives `id` slots for, oldest first.
    fn module_attrs(&self, id: Sym) -> &'static [&'static str] {
        let agent = &self.agent;
        if agent.symbols.is_goal(id) {
            return &STATE_MODULE_ATTRS;
        }
        let link_of = |attr: &str| {
            let a = agent.symbols.find_str(attr);
            self.states().into_iter().any(|s| {
                agent
                    .wm
                    .of_id(s)
                    .filter_map(|w| agent.wm.get(w))
                    .any(|w| Some(w.attr) == a && w.value == id)
            })
        };
        if link_of("epmem") {
            &EPMEM_MODULE_ATTRS
        } else if link_of("smem") {
            &SMEM_MODULE_ATTRS
        } else {
            &[]
        }
    }

    fn is_module_attr(&self, id: Sym, attr: Sym) -> bool {
        let text = self.agent.symbols.text(attr);
        self.module_attrs(id).contains(&text.as_str())
    }

    /// Has 9.6 a slot for (id, attr)? A state's operator slot always, the memories' links,
    /// and any slot rules made preferences in.
    pub(super) fn has_slot(&self, id: Sym, attr: Sym) -> bool {
        let agent = &self.agent;
        (attr == agent.top.operator && agent.symbols.is_goal(id))
            || self.is_module_attr(id, attr)
            || agent.decider.slots.get(&(id, attr)).is_some()
    }

    pub(super) fn origin_of(&self, w: WmeId, wme: &Wme) -> Origin {
        let agent = &self.agent;
        if agent.held_by_preferences(w, wme) {
            return Origin::Preference;
        }
        if agent.symbols.is_goal(wme.id) {
            let attr = agent.symbols.text(wme.attr);
            if matches!(attr.as_str(), "item" | "non-numeric") {
                return Origin::ArchWithPreference;
            }
            if STATE_ARCH_ATTRS.contains(&attr.as_str()) {
                return Origin::Arch;
            }
        }
        if self.is_module_attr(wme.id, wme.attr) {
            return Origin::Module;
        }
        Origin::Input
    }

    /// `preferences ID` for an identifier that is not a state: each WME whose value it is,
    /// in 9.6's order (the order WMEs entered its matcher, newest first), with the
    /// preferences for it in that WME's slot.
    pub(super) fn value_support(&self, id: Sym, detail: Detail) -> String {
        let agent = &self.agent;
        let mut wmes: Vec<(WmeId, Wme)> = Vec::new();
        for &w in agent.wm.parent_wmes(id) {
            if let Some(wme) = agent.wm.get(w) {
                if wme.value == id && !wmes.iter().any(|(x, _)| *x == w) {
                    wmes.push((w, *wme));
                }
            }
        }
        wmes.sort_by_key(|(w, wme)| std::cmp::Reverse(self.matcher_entry(*w, wme)));
        let mut out = String::new();
        for (w, wme) in wmes {
            out.push_str(&format!(
                "Support for ({}: {} ^{} {})\n",
                wme.timetag,
                agent.symbols.text(wme.id),
                agent.symbols.text(wme.attr),
                agent.symbols.text(wme.value)
            ));
            match self.origin_of(w, &wme) {
                Origin::Preference => out.push_str(&self.value_prefs(&wme, detail)),
                Origin::ArchWithPreference => {
                    out.push_str("    This is an arch-wme and has no prefs.\n")
                }
                Origin::Arch | Origin::Module | Origin::Input => {
                    out.push_str("    This is an input-wme and has no prefs.\n")
                }
            }
        }
        out
    }

    /// When a WME entered the matcher, as an order key: a substate's architecture WMEs
    /// enter together, newest first, after the last of them was made.
    fn matcher_entry(&self, w: WmeId, wme: &Wme) -> (u64, std::cmp::Reverse<u64>) {
        for g in &self.agent.decider.goals {
            if g.wmes.contains(&w) {
                let last = g
                    .wmes
                    .iter()
                    .filter_map(|&x| self.agent.wm.get(x))
                    .map(|x| x.timetag)
                    .max()
                    .unwrap_or(wme.timetag);
                return (last, std::cmp::Reverse(wme.timetag));
            }
        }
        (wme.timetag, std::cmp::Reverse(0))
    }

    /// The preferences in a WME's slot for its value, by type; an acceptable one with the
    /// value and chance 9.6 prints for it there. (9.6 reckons that chance among the
    /// candidates of the slot's last decision from the slot's first acceptable preference
    /// on, so it need not be a share of anything; rusoar reckons it the same way.)
    fn value_prefs(&self, wme: &Wme, detail: Detail) -> String {
        let prefs = self.slot_prefs(wme.id, wme.attr);
        let is_context = wme.attr == self.agent.top.operator && self.agent.symbols.is_goal(wme.id);
        let cands = if is_context {
            self.candidates(&prefs).unwrap_or_default()
        } else {
            Vec::new()
        };
        let head = prefs.iter().find(|p| p.kind == PrefType::Acceptable);
        let among: Vec<f64> = match head {
            Some(h) => match cands.iter().position(|(c, _)| c.value == h.value) {
                Some(i) => cands[i..].iter().map(|(_, v)| *v).collect(),
                None => vec![0.0],
            },
            None => Vec::new(),
        };
        let mut out = String::new();
        for (kind, _) in SECTIONS {
            for p in prefs.iter().filter(|p| p.kind == kind && p.value == wme.value) {
                if kind == PrefType::Acceptable {
                    let value = cands
                        .iter()
                        .find(|(c, _)| c.value == p.value)
                        .map_or(0.0, |(_, v)| *v);
                    let total: f64 = among.iter().sum();
                    let chance = if total > 0.0 {
                        value / total
                    } else {
                        1.0 / among.len().max(1) as f64
                    };
                    out.push_str(&self.candidate_line(p, value, chance));
                } else {
                    out.push_str(&self.pref_line(p));
                }
                out.push_str(&self.source_lines(p, detail));
            }
        }
        out
    }

    /// `preferences --object ID`: each of the object's slots (newest first, as 9.6 lists
    /// them) with its preferences, then its architecture and input WMEs, newest first.
    pub(super) fn object_listing(&self, id: Sym, detail: Detail) -> String {
        let agent = &self.agent;
        let is_goal = agent.symbols.is_goal(id);
        let op = agent.top.operator;
        let mut attrs: Vec<Sym> = agent
            .decider
            .slots
            .keys_of(id)
            .into_iter()
            .map(|(_, a)| a)
            .filter(|&a| !(self.is_module_attr(id, a) || is_goal && a == op))
            .rev()
            .collect();
        // The slots made with the object come last: a state's operator slot, then the
        // memories' links, newest first.
        if is_goal {
            attrs.push(op);
        }
        for name in self.module_attrs(id).iter().rev() {
            if let Some(a) = agent.symbols.find_str(name) {
                if agent
                    .wm
                    .of_id(id)
                    .filter_map(|w| agent.wm.get(w))
                    .any(|w| w.attr == a)
                {
                    attrs.push(a);
                }
            }
        }
        let id_text = agent.symbols.text(id);
        let mut out = String::new();
        for attr in attrs {
            let attr_text = agent.symbols.text(attr);
            if attr == op {
                out.push_str(&format!("Preferences for {id_text} ^{attr_text}:"));
            } else {
                out.push_str(&format!("Support for {id_text} ^{attr_text}:\n"));
            }
            let prefs = self.slot_prefs(id, attr);
            let context = is_goal && attr == op;
            for (kind, heading) in SECTIONS {
                let of_kind: Vec<_> = prefs.iter().filter(|p| p.kind == kind).collect();
                if of_kind.is_empty() {
                    continue;
                }
                if context {
                    out.push_str(&format!("\n{heading}:\n"));
                }
                for p in of_kind {
                    out.push_str(&self.pref_line(p));
                    out.push_str(&self.source_lines(p, detail));
                }
            }
        }
        let mut arch = Vec::new();
        let mut input = Vec::new();
        for w in agent.wm.of_id(id) {
            let Some(wme) = agent.wm.get(w).copied() else {
                continue;
            };
            match self.origin_of(w, &wme) {
                Origin::Arch | Origin::ArchWithPreference => arch.push(wme),
                Origin::Input => input.push(wme),
                Origin::Preference | Origin::Module => {}
            }
        }
        for (list, heading) in [(arch, "Arch-created wmes"), (input, "Input (IO) wmes")] {
            if list.is_empty() {
                continue;
            }
            let mut list = list;
            list.sort_by_key(|w| std::cmp::Reverse(w.timetag));
            out.push_str(&format!("{heading} for {id_text} :\n"));
            for w in list {
                let activation = agent.wme_activation(&w);
                crate::trace_text::wme_text_activated(&mut out, &agent.symbols, &w, activation);
                out.push('\n');
            }
        }
        out
    }
}
