//! The WMA trace (`trace -a`, 9.6's `TRACE_WMA_SYSPARAM`): a line when a WME gets a decay
//! element (`add`), when it loses it (`remove`, right after the WME's `<=WM:` line), and,
//! at the end of each decision, one per element referenced in it with its count of
//! references (`activate`). 9.6 prints those in the order of the WMEs' memory addresses;
//! rusoar prints them in timetag order.

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

    fn wma_removal_line(&mut self, timetag: u64) {
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
        SymData::Float(f) => Some(general_16(*f)),
        SymData::Id(_) => None,
    }
}

/// C++'s `ostream << setprecision(16) << x` (printf's `%.16g`).
fn general_16(x: f64) -> String {
    if !x.is_finite() {
        return if x.is_nan() { "nan".into() } else if x > 0.0 { "inf".into() } else { "-inf".into() };
    }
    if x == 0.0 {
        return if x.is_sign_negative() { "-0".into() } else { "0".into() };
    }
    let sci = format!("{x:.15e}");
    let (mantissa, exp) = sci.split_once('e').unwrap_or((&sci, "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    let trim = |s: &str| -> String {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s.to_string()
        }
    };
    if (-4..16).contains(&exp) {
        trim(&format!("{x:.*}", (15 - exp) as usize))
    } else {
        let sign = if exp < 0 { '-' } else { '+' };
        format!("{}e{sign}{:02}", trim(mantissa), exp.abs())
    }
}

#[cfg(test)]
mod tests {
    use super::general_16;

    #[test]
    fn floats_have_sixteen_significant_digits_as_in_cpp_streams() {
        assert_eq!(general_16(2.5), "2.5");
        assert_eq!(general_16(0.1), "0.1");
        assert_eq!(general_16(1.0 / 3.0), "0.3333333333333333");
        assert_eq!(general_16(100.0), "100");
        assert_eq!(general_16(1e20), "1e+20");
        assert_eq!(general_16(-0.00001), "-1e-05");
    }
}
