//! The memories' retrievals as preferences. 9.6 puts what semantic and episodic memory
//! retrieve into working memory through an instantiation of its own, `|Memory System
//! Recall|`, whose acceptable preferences join their slots as a rule's do: the slots
//! decide the WMEs (and so their timetags), the next command's retrieval removes the
//! preferences on the result link, and the retrieved objects go with the garbage once
//! nothing links them (Soar manual, ch. 6 and 7, "Working Memory Interface").

use super::procedure::PrefType;
pub(crate) use super::state::RecallPref;
use super::state::Preference;
use crate::agent::AgentCore;
use crate::symbols::Sym;


impl AgentCore {
    /// A retrieval's acceptable preferences for `triples`, in the order given (the order
    /// 9.6's preferences trace lists them in), into their slots; o-supported when the last
    /// wave of firings was, as 9.6 prints them. `conditions` are the command's WMEs that
    /// 9.6's instantiation tests (`preferences --wmes` lists them). The WMEs come at the
    /// next [`update_slots`](Self::update_slots). They belong to `state`'s firings: a
    /// substate's go with it, listed among its rules' preferences in the order made.
    pub(crate) fn add_recall_prefs(
        &mut self,
        state: Sym,
        triples: &[(Sym, Sym, Sym)],
        conditions: &[crate::wm::WmeId],
    ) -> Vec<RecallPref> {
        let matched: Option<std::sync::Arc<[crate::wm::Wme]>> = (!triples.is_empty()).then(|| {
            conditions.iter().filter_map(|&w| self.wm.get(w).copied()).collect()
        });
        let tracing = self.settings.trace.preferences;
        let o_support = self.decider.last_wave_o_support;
        let mut made = Vec::with_capacity(triples.len());
        for &(id, attr, value) in triples {
            let pid = self.decider.alloc_pref(Preference {
                kind: PrefType::Acceptable,
                id,
                attr,
                value,
                referent: None,
                number: None,
                o_support,
                inst: None,
                rule: None,
                alive: true,
                freed: false,
                origin: None,
                matched: matched.clone(),
                recall: true,
                links_filed: false,
            });
            made.push((pid, self.decider.pref_serial(pid)));
            self.assert_preference(pid, tracing);
            self.note_goal_pref(Some(state), pid);
        }
        made
    }

    /// Takes recall preferences out of their slots, in the order given, each traced as it
    /// goes (`- (R3 ^success Q1 +) (|Memory System Recall|)`); those already gone (with
    /// their object or state) are passed over.
    pub(crate) fn remove_recall_prefs(&mut self, prefs: &[RecallPref]) {
        for &(pid, serial) in prefs {
            if !self.is_live_recall_pref((pid, serial)) {
                continue;
            }
            let p = &self.decider.prefs[pid];
            let (key, value) = ((p.id, p.attr), p.value);
            let Some(slot) = self.decider.slots.id_of(&key) else {
                continue;
            };
            self.trace_pref('-', pid);
            self.decider.slots.slot_mut(slot).remove(pid, value);
            self.pref_link_removed(pid);
            self.decider.free_pref(pid);
            self.mark_changed(key, Some(slot));
        }
    }

    /// Takes a command's last results on the result link out, last made first (9.6's
    /// `clear_result`); returns the timetags of their WMEs, for
    /// [`forget_gone_results`](Self::forget_gone_results) once the slots are decided.
    pub(crate) fn clear_recall_results(&mut self, gone: &[RecallPref]) -> Vec<u64> {
        let timetags = gone
            .iter()
            .filter(|&&p| self.is_live_recall_pref(p))
            .filter_map(|&p| self.recall_wme(p))
            .filter_map(|w| self.wm.get(w).map(|x| x.timetag))
            .collect();
        let last_first: Vec<RecallPref> = gone.iter().rev().copied().collect();
        self.remove_recall_prefs(&last_first);
        timetags
    }

    /// The results among `timetags` that left working memory no longer need their
    /// origins (a result made again keeps its WME, and its origin).
    pub(crate) fn forget_gone_results(&mut self, timetags: &[u64]) {
        let gone: Vec<u64> = timetags
            .iter()
            .copied()
            .filter(|&t| self.wm.by_timetag(t).is_none())
            .collect();
        self.forget_memory_results(gone);
    }

    /// Whether a recall preference still stands.
    pub(crate) fn is_live_recall_pref(&self, (pid, serial): RecallPref) -> bool {
        pid.index() < self.decider.prefs.len()
            && self.decider.pref_serial(pid) == serial
            && self.decider.prefs[pid].alive
            && self.decider.prefs[pid].recall
    }

    /// The WME a recall preference stands behind, once its slot made it.
    pub(crate) fn recall_wme(&self, (pid, _): RecallPref) -> Option<crate::wm::WmeId> {
        let p = &self.decider.prefs[pid];
        self.decider.slots.get(&(p.id, p.attr))?.wmes.get(&(p.value, false))
    }
}
