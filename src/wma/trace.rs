//! The WMA trace (`trace -a`, 9.6's `TRACE_WMA_SYSPARAM`): a line when a WME gets a decay
//! element (`add`), when it loses it (`remove`, right after the WME's `<=WM:` line), and,
//! at the end of each decision, one per element referenced in it with its count of
//! references (`activate`). 9.6 prints those in the order of the WMEs' memory addresses,
//! which `addresses.rs` replays.

use crate::agent::AgentCore;
use crate::symbols::{Sym, SymData};
use crate::wm::Wme;

impl AgentCore {
    /// `WMA @D: add TT ID ATTR VALUE` for a WME that just got its decay element.
    pub(crate) fn wma_trace_add(&mut self, wme: &Wme) {
        if !self.settings.trace.wma {
            return;
        }
        let d = self.decider.d_cycle_count;
        let mut line = format!("WMA @{d}: add {} ", wme.timetag);
        // 9.6 writes each field into one reused buffer and has no case for an identifier
        // in the attribute or value: such a field repeats what the buffer held (the
        // identifier's number, or the field before).
        let mut held = String::new();
        if let Some(id) = self.symbols.id_data(wme.id) {
            line.push(id.letter as char);
            held = id.number.to_string();
            line.push_str(&held);
        }
        for field in [wme.attr, wme.value] {
            if let Some(text) = constant_text(self, field) {
                held = text;
            }
            line.push(' ');
            line.push_str(&held);
        }
        line.push('\n');
        self.output.push_str(&line);
    }

    /// A WME with a decay element left working memory: its `remove` line comes right
    /// after the WME's `<=WM:` line, which may be printed later with its phase's others.
    pub(crate) fn wma_trace_removal(&mut self, timetag: u64) {
        if !self.settings.trace.wma || self.wma.element(timetag).is_none_or(|e| e.removed) {
            return;
        }
        if self.removed_wmes.is_some() {
            self.wma.removal_lines.push(timetag);
        } else {
            self.wma_removal_line(timetag);
        }
    }

    /// The `remove` line of a WME whose `<=WM:` line was just printed, if one is waiting.
    pub(crate) fn wma_flush_removal_line(&mut self, timetag: u64) {
        if let Some(i) = self.wma.removal_lines.iter().position(|&t| t == timetag) {
            self.wma.removal_lines.swap_remove(i);
            self.wma_removal_line(timetag);
        }
    }

    /// Every `remove` line still waiting for its `<=WM:` line.
    pub(crate) fn wma_flush_removal_lines(&mut self) {
        for tt in std::mem::take(&mut self.wma.removal_lines) {
            self.wma_removal_line(tt);
        }
    }

    pub(super) fn wma_removal_line(&mut self, timetag: u64) {
        let d = self.decider.d_cycle_count;
        self.output.push_str(&format!("WMA @{d}: remove {timetag}\n"));
    }

    /// `WMA @D: activate TT N` for each element referenced in the decision.
    pub(crate) fn wma_trace_activations(&mut self, counts: &[(u64, u64)]) {
        let d = self.decider.d_cycle_count;
        for &(tt, n) in counts {
            self.output.push_str(&format!("WMA @{d}: activate {tt} {n}\n"));
        }
    }
}

/// A constant as 9.6's trace writes it (floats with 16 significant digits); `None` for an
/// identifier.
fn constant_text(agent: &AgentCore, s: Sym) -> Option<String> {
    match agent.symbols.get(s) {
        SymData::Str(t) => Some(t.to_string()),
        SymData::Int(i) => Some(i.to_string()),
        SymData::Float(f) => Some(crate::printer::constants::c_general(*f, 16)),
        SymData::Id(_) => None,
    }
}
