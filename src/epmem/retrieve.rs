//! Rebuilding an episode in working memory (Soar manual, ch. 7, "Retrieval"; 9.6's
//! `epmem_install_memory`): under a new `^retrieved` identifier, the episode's edges in the
//! order of their parent and child nodes make the identifiers, then its constants hang
//! from them in the order they were first stored.

use super::store::{Constant, Store, ROOT};
use crate::agent::AgentCore;
use crate::symbols::Sym;
use std::collections::BTreeMap;

/// WMEs to add, in order: (identifier, attribute, value).
pub(crate) type Triples = Vec<(Sym, Sym, Sym)>;

impl Store {
    /// The edges of episode `t` in 9.6's order: by parent node, then child node.
    pub fn edges_at(&self, t: i64) -> Vec<i64> {
        let mut edges = self.edges.at(t);
        edges.sort_by_key(|&e| {
            let (p, _, c) = self.edges.triple(e);
            (p, c, e)
        });
        edges
    }
}

impl AgentCore {
    /// A stored constant as a symbol.
    pub(crate) fn epmem_symbol(&mut self, h: i64) -> Sym {
        let c = match self.epmem.store.as_ref() {
            Some(s) => s.constant(h).clone(),
            None => return self.symbols.str(""),
        };
        match c {
            Constant::Str(s) => self.symbols.str(&s),
            Constant::Int(i) => self.symbols.int(i),
            Constant::Float(b) => self.symbols.float(f64::from_bits(b)),
        }
    }

    /// Whether semantic memory holds long-term identifier `lti`.
    fn epmem_lti_exists(&mut self, lti: i64) -> bool {
        self.smem.is_open() && self.smem.store().is_ok_and(|s| s.lti_exists(lti).unwrap_or(false))
    }

    /// Rebuilds episode `t` under `res` (or says `^retrieved no-memory`): the episode's WMEs
    /// go to `retrieval`, the `^retrieved`, `^memory-id` and `^present-id` results to
    /// `meta`. Returns the identifier made for each node, for a graph match's mapping.
    pub(crate) fn epmem_install(
        &mut self,
        state: Sym,
        res: Sym,
        t: Option<i64>,
        meta: &mut Triples,
        retrieval: &mut Triples,
    ) -> BTreeMap<i64, Sym> {
        let level = self.epmem.params.timers();
        let timer = crate::memory_timers::MemoryTimers::start(super::timer::NCB_RETRIEVAL, level);
        let nodes = self.epmem_install_untimed(state, res, t, meta, retrieval);
        self.epmem.timers.stop(timer);
        nodes
    }

    /// [`epmem_install`](Self::epmem_install)'s work, untimed.
    fn epmem_install_untimed(
        &mut self,
        state: Sym,
        res: Sym,
        t: Option<i64>,
        meta: &mut Triples,
        retrieval: &mut Triples,
    ) -> BTreeMap<i64, Sym> {
        let valid = t.is_some_and(|t| self.epmem.store.as_ref().is_some_and(|s| s.valid(t)));
        let link = self.epmem.links.entry(state).or_default();
        let (Some(t), true) = (t, valid) else {
            link.last_memory = None;
            let (a, v) = (self.symbols.str("retrieved"), self.symbols.str("no-memory"));
            meta.push((res, a, v));
            return BTreeMap::new();
        };
        link.last_memory = Some(t);
        let level = self.symbols.id_data(res).map_or(1, |d| d.level);
        let header = self.symbols.new_id('R', level);
        let present = self.epmem.time();
        let retrieved = self.symbols.str("retrieved");
        let memory_id = self.symbols.str("memory-id");
        let present_id = self.symbols.str("present-id");
        let (tv, pv) = (self.symbols.int(t), self.symbols.int(present));
        meta.push((res, retrieved, header));
        meta.push((res, memory_id, tv));
        meta.push((res, present_id, pv));
        let mut ids: BTreeMap<i64, Sym> = BTreeMap::from([(ROOT, header)]);
        let Some(store) = self.epmem.store.as_ref() else {
            return ids;
        };
        // Each edge with the long-term identifier its child stood for (0: none).
        let edges: Vec<(i64, i64, i64, i64)> = store
            .edges_at(t)
            .into_iter()
            .map(|e| {
                let (p, a, c) = store.edges.triple(e);
                (p, a, c, store.edges.lti_at(e, t))
            })
            .collect();
        let consts: Vec<(i64, i64, i64)> = store
            .consts
            .at(t)
            .into_iter()
            .map(|c| store.consts.triple(c))
            .collect();
        let mut count = 0;
        // An edge whose parent is not made yet waits for it (a shared identifier can have
        // a smaller node than its parent's).
        let mut pending = edges;
        loop {
            let before = pending.len();
            let mut waiting = Vec::new();
            for (p, a, c, lti) in pending {
                let Some(&parent) = ids.get(&p) else {
                    waiting.push((p, a, c, lti));
                    continue;
                };
                let attr = self.epmem_symbol(a);
                let child = match ids.get(&c) {
                    Some(&x) => x,
                    None => {
                        let letter = self.symbols.text(attr).chars().next().unwrap_or('I');
                        let level = self.symbols.id_data(parent).map_or(level, |d| d.level);
                        let x = self.symbols.new_id(letter, level);
                        // It links to its long-term identifier again, if semantic memory
                        // still has it.
                        if lti != 0 && self.epmem_lti_exists(lti) {
                            if let Some(d) = self.symbols.id_data_mut(x) {
                                d.lti = lti;
                            }
                        }
                        ids.insert(c, x);
                        x
                    }
                };
                retrieval.push((parent, attr, child));
                count += 1;
            }
            if waiting.is_empty() || waiting.len() == before {
                break;
            }
            pending = waiting;
        }
        for (p, a, v) in consts {
            let Some(&parent) = ids.get(&p) else {
                continue;
            };
            let (attr, value) = (self.epmem_symbol(a), self.epmem_symbol(v));
            retrieval.push((parent, attr, value));
            count += 1;
        }
        self.epmem.stats.ncb_wmes = count;
        ids
    }
}
