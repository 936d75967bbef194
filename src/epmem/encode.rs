//! Storing an episode (Soar manual, ch. 7, "Episodic Storage"): only what changed since the
//! last one. Working memory's journal says which WMEs came and went; the identifiers that
//! got new WMEs are walked breadth-first into their new structure, and each new WME gets a
//! row (reusing the node and edge of an identifier that stood at the same place before),
//! while the rows of WMEs that went end their ranges.

use super::disk::{Changes, Disk};
use super::store::{Constant, Store, ACCEPTABLE, ROOT};
use super::Encoder;
use crate::agent::AgentCore;
use crate::decide::state::{STATE_ARCH_ATTRS as IMPASSE_ATTRS, STATE_MODULE_ATTRS as MODULE_ATTRS};
use crate::symbols::{Sym, SymData};
use crate::wm::{Wme, WmeId};
use rustc_hash::{FxHashMap, FxHashSet};
use std::collections::VecDeque;

/// An edge reserved for a WME whose value's node is known before its level is stored.
struct Reservation {
    edge: Option<i64>,
    attr: i64,
}

impl AgentCore {
    /// Opens the store on first use: the top state is the root, and its WMEs are the first
    /// episode's news (9.6's `epmem_init_db`).
    pub(crate) fn epmem_attach(&mut self) {
        if self.epmem.store.is_some() {
            return;
        }
        self.epmem.encoder = Encoder::default();
        let store = self.epmem_open_store();
        // Edges the file already holds are free for the identifiers stored afresh, each
        // `(parent, attribute)` pool newest first.
        let enc = &mut self.epmem.encoder;
        for id in 1..=store.edges.count() as i64 {
            let (parent, attr, child) = store.edges.triple(id);
            enc.pools.entry((parent, attr)).or_default().push_front((child, id));
        }
        self.epmem.store = Some(store);
        self.epmem.encoder.node_of.insert(self.top.state, ROOT);
        self.epmem.encoder.adds.insert(self.top.state);
        self.wm.keep_journal(true);
    }

    /// The store `database` names: a new one in memory, or the file's. A file that cannot
    /// be used is reported, and episodic memory goes on in memory (as 9.6 does).
    fn epmem_open_store(&mut self) -> Store {
        if self.epmem.params.get("database").as_deref() != Some("file") {
            return Store::default();
        }
        match Disk::open(&self.epmem.params) {
            Ok((disk, store)) => {
                self.epmem.disk = Some(disk);
                store
            }
            Err(e) => {
                self.fresh_line();
                self.output.push_str(&e);
                self.output.push_str("\n...Switching to memory-based database.\n");
                let _ = self.epmem.params.set("database", "memory", false);
                Store::default()
            }
        }
    }

    /// Closes the store (`init-soar`, `epmem --init`): one in memory is gone, a file keeps
    /// what was written to it.
    pub(crate) fn epmem_close(&mut self) {
        self.epmem.disk = None;
        self.epmem.store = None;
        self.epmem.encoder = Encoder::default();
        self.epmem.links.clear();
        self.epmem.last_output_time = 0;
        self.wm.keep_journal(false);
    }

    /// An identifier's WMEs in the order 9.6 lists them: the architecture's, then input
    /// (newest first, but on a long-term identifier's object), then each slot (newest slot first; in a slot, newest WME first, acceptable
    /// preferences after the rest), the operator slot and the memories' links last.
    pub(crate) fn epmem_augs_of(&self, id: Sym) -> Vec<Wme> {
        let is_state = self.symbols.id_data(id).is_some_and(|d| d.is_goal);
        let mut wmes: Vec<(WmeId, Wme)> = self
            .wm
            .of_id(id)
            .filter_map(|w| self.wm.get(w).map(|x| (w, *x)))
            .collect();
        wmes.sort_by_key(|(_, w)| std::cmp::Reverse(w.timetag));
        let (mut impasse, mut input, mut module) = (Vec::new(), Vec::new(), Vec::new());
        let mut by_attr: FxHashMap<Sym, Vec<Wme>> = FxHashMap::default();
        for (w, wme) in &wmes {
            if self.held_by_preferences(*w, wme) {
                by_attr.entry(wme.attr).or_default().push(*wme);
                continue;
            }
            let attr = self.symbols.text(wme.attr);
            if is_state && IMPASSE_ATTRS.contains(&attr.as_str()) {
                impasse.push(*wme);
            } else if is_state && MODULE_ATTRS.contains(&attr.as_str()) {
                module.push(*wme);
            } else {
                input.push(*wme);
            }
        }
        // The WMEs a semantic-memory retrieval put on a long-term identifier's object come
        // in the order they were made (seen with 9.6.5), the others newest first.
        if self.symbols.lti(id).is_some() {
            input.reverse();
        }
        let operator = self.symbols.find_str("operator");
        let mut out = impasse;
        out.append(&mut input);
        let slot_wmes = |attr: Sym, by_attr: &mut FxHashMap<Sym, Vec<Wme>>, out: &mut Vec<Wme>| {
            if let Some(list) = by_attr.remove(&attr) {
                out.extend(list.iter().filter(|w| !w.acceptable));
                out.extend(list.iter().filter(|w| w.acceptable));
            }
        };
        for (_, attr) in self.decider.slots.keys_of(id).into_iter().rev() {
            if is_state && Some(attr) == operator {
                continue;
            }
            slot_wmes(attr, &mut by_attr, &mut out);
        }
        if let Some(op) = operator {
            slot_wmes(op, &mut by_attr, &mut out);
        }
        // WMEs held by a slot the listing missed, newest first.
        let mut rest: Vec<Wme> = by_attr.into_values().flatten().collect();
        rest.sort_by_key(|w| std::cmp::Reverse(w.timetag));
        out.append(&mut rest);
        module.sort_by_key(|w| std::cmp::Reverse(w.timetag));
        out.append(&mut module);
        out
    }

    fn epmem_constant(&self, s: Sym) -> Constant {
        match self.symbols.get(s) {
            SymData::Str(x) => Constant::Str(x.to_string()),
            SymData::Int(i) => Constant::Int(*i),
            SymData::Float(f) => Constant::Float(f.to_bits()),
            SymData::Id(_) => Constant::Str(self.symbols.text(s)),
        }
    }

    /// The number of a WME's attribute (acceptable preferences share one).
    fn epmem_attr_hash(&mut self, w: &Wme) -> i64 {
        if w.acceptable {
            return ACCEPTABLE;
        }
        let c = self.epmem_constant(w.attr);
        self.epmem.store.as_mut().map_or(0, |s| s.hash(c))
    }

    /// Reads working memory's journal: new WMEs of stored identifiers mark them for the
    /// walk; WMEs that went end their rows, and an identifier no stored WME points at any
    /// more is forgotten with its WMEs (9.6 does this as the changes happen).
    fn epmem_read_journal(&mut self) {
        for (added, w) in self.wm.take_journal() {
            let enc = &mut self.epmem.encoder;
            if added {
                if let Some(&n) = enc.node_of.get(&w.value) {
                    enc.refs.entry(n).or_default().push(w.timetag);
                }
                if enc.node_of.contains_key(&w.id) {
                    enc.adds.insert(w.id);
                }
            } else {
                let mut gone = VecDeque::new();
                self.epmem_unstore(&w, &mut gone);
                while let Some(id) = gone.pop_front() {
                    // The top state is the episode's root: a substate's `^superstate`
                    // pointed at it, but nothing stored needs to for it to stay.
                    if id == self.top.state {
                        continue;
                    }
                    if self.epmem.encoder.node_of.remove(&id).is_some() {
                        for x in self.epmem_augs_of(id) {
                            self.epmem_unstore(&x, &mut gone);
                        }
                    }
                }
            }
        }
    }

    /// A stored WME leaves the record: its row ends at the next episode, its edge goes back
    /// to its pool, and its value loses a reference.
    fn epmem_unstore(&mut self, w: &Wme, gone: &mut VecDeque<Sym>) {
        let is_id = self.symbols.is_id(w.value);
        let enc = &mut self.epmem.encoder;
        let row = enc.wme_row.remove(&w.timetag);
        if !is_id {
            if let Some(r) = row {
                enc.const_removals.insert(r, true);
            }
            return;
        }
        let node = enc.node_of.get(&w.value).copied();
        if let Some(e) = row {
            enc.edge_removals.insert(e, true);
            if let Some(key) = enc.pool_of.remove(&e) {
                let child = node.unwrap_or(-1);
                enc.pools.entry(key).or_default().push_front((child, e));
            }
        }
        if let Some(n) = node {
            if let Some(refs) = enc.refs.get_mut(&n) {
                if let Some(i) = refs.iter().position(|&t| t == w.timetag) {
                    refs.swap_remove(i);
                    if refs.is_empty() {
                        gone.push_front(w.value);
                    }
                }
            }
        }
    }

    /// Stores an episode (9.6's `epmem_new_episode`).
    pub(crate) fn epmem_new_episode(&mut self) {
        self.epmem_attach();
        self.epmem_read_journal();
        let time = self.epmem.time();
        let mut new_consts: Vec<i64> = Vec::new();
        let mut new_edges: Vec<i64> = Vec::new();
        let mut edge_ltis: Vec<(i64, i64)> = Vec::new();
        let mut visited: FxHashSet<Sym> = FxHashSet::default();
        let mut reservations: FxHashMap<u64, Reservation> = FxHashMap::default();
        let mut new_ids: FxHashSet<Sym> = FxHashSet::default();
        let starts: Vec<Sym> = self.epmem.encoder.adds.iter().copied().collect();
        for start in starts {
            let Some(&node) = self.epmem.encoder.node_of.get(&start) else {
                continue;
            };
            let mut queue: VecDeque<(Sym, i64)> = VecDeque::from([(start, node)]);
            while let Some((sym, parent)) = queue.pop_front() {
                if !visited.insert(sym) {
                    continue;
                }
                let wmes = self.epmem_augs_of(sym);
                let mut level = Level {
                    parent,
                    queue: &mut queue,
                    visited: &visited,
                    reservations: &mut reservations,
                    new_ids: &mut new_ids,
                    new_consts: &mut new_consts,
                    new_edges: &mut new_edges,
                    edge_ltis: &mut edge_ltis,
                };
                self.epmem_store_level(&wmes, &mut level);
            }
        }
        let Some(store) = self.epmem.store.as_mut() else {
            return;
        };
        for &c in &new_consts {
            store.consts.open(c, time);
        }
        for &e in &new_edges {
            store.edges.open(e, time);
        }
        for &(e, lti) in &edge_ltis {
            store.edges.set_lti(e, time, lti);
        }
        let mut changes = Changes {
            started: [new_consts, new_edges],
            ended: [Vec::new(), Vec::new()],
        };
        let enc = &mut self.epmem.encoder;
        for (k, (rows, removals)) in [
            (&mut store.consts, &mut enc.const_removals),
            (&mut store.edges, &mut enc.edge_removals),
        ]
        .into_iter()
        .enumerate()
        {
            for (&r, &ended) in removals.iter() {
                if !ended {
                    continue;
                }
                if let Some(start) = rows.life(r).now {
                    changes.ended[k].push((r, start, time - 1));
                }
                rows.close(r, time - 1);
                rows.life_mut(r).ended = true;
            }
            removals.clear();
        }
        enc.adds.clear();
        store.time = time + 1;
        if let Some(disk) = self.epmem.disk.as_mut() {
            if let Err(e) = disk.record(store, time, &changes) {
                self.fresh_line();
                self.output.push_str(&e);
                self.output.push('\n');
            }
        }
        self.epmem_move_present();
    }

    /// Stores one identifier's new WMEs (9.6's `_epmem_store_level`): first the edges of
    /// values whose nodes are known are reserved, then each WME gets its row.
    fn epmem_store_level(&mut self, wmes: &[Wme], lv: &mut Level<'_>) {
        for w in wmes {
            if self.epmem.encoder.wme_row.contains_key(&w.timetag) {
                continue;
            }
            let Some(&child) = self.epmem.encoder.node_of.get(&w.value) else {
                continue;
            };
            if !self.symbols.is_id(w.value) || self.epmem_excluded(w) {
                continue;
            }
            let attr = self.epmem_attr_hash(w);
            let pool = self.epmem.encoder.pools.entry((lv.parent, attr)).or_default();
            let edge = pool
                .iter()
                .position(|&(c, _)| c == child)
                .and_then(|i| pool.remove(i))
                .map(|(_, e)| e);
            lv.reservations.insert(w.timetag, Reservation { edge, attr });
        }
        for w in wmes {
            if self.epmem.encoder.wme_row.contains_key(&w.timetag) || self.epmem_excluded(w) {
                continue;
            }
            if self.symbols.is_id(w.value) {
                self.epmem_note_lti(w.value);
                self.epmem_store_edge(w, lv);
            } else {
                self.epmem_store_constant(w, lv);
            }
        }
    }

    /// A stored identifier seen linked to semantic memory for the first time: the store
    /// records its node's link (9.6's `update_node`).
    fn epmem_note_lti(&mut self, id: Sym) {
        let lti = self.symbols.lti(id).unwrap_or(0);
        let enc = &mut self.epmem.encoder;
        if lti == 0 || enc.lti_known.contains(&id) {
            return;
        }
        if let (Some(&node), Some(store)) = (enc.node_of.get(&id), self.epmem.store.as_mut()) {
            enc.lti_known.insert(id);
            store.later_ltis.push((node, lti));
        }
    }

    fn epmem_excluded(&self, w: &Wme) -> bool {
        !w.acceptable && self.epmem.params.excluded(&self.symbols.text(w.attr))
    }

    fn epmem_store_edge(&mut self, w: &Wme, lv: &mut Level<'_>) {
        let known = self.epmem.encoder.node_of.contains_key(&w.value);
        let mut edge = None;
        let key;
        if known {
            let child = self.epmem.encoder.node_of[&w.value];
            match lv.reservations.remove(&w.timetag) {
                Some(r) => {
                    key = (lv.parent, r.attr);
                    edge = r.edge;
                }
                None => {
                    // A value shared at this level: an exact match from the pool.
                    key = (lv.parent, self.epmem_attr_hash(w));
                    let pool = self.epmem.encoder.pools.entry(key).or_default();
                    edge = pool
                        .iter()
                        .position(|&(c, _)| c == child)
                        .and_then(|i| pool.remove(i))
                        .map(|(_, e)| e);
                }
            }
        } else {
            lv.new_ids.insert(w.value);
            key = (lv.parent, self.epmem_attr_hash(w));
            let enc = &mut self.epmem.encoder;
            let pool = enc.pools.entry(key).or_default();
            let free = pool
                .iter()
                .position(|(c, _)| enc.refs.get(c).is_none_or(|r| r.is_empty()));
            if let Some((child, e)) = free.and_then(|i| pool.remove(i)) {
                edge = Some(e);
                enc.node_of.insert(w.value, child);
            }
        }
        let lti = self.symbols.lti(w.value).unwrap_or(0);
        let enc = &mut self.epmem.encoder;
        let Some(store) = self.epmem.store.as_mut() else {
            return;
        };
        let edge = match edge {
            Some(e) => {
                enc.edge_removals.insert(e, false);
                let life = store.edges.life_mut(e);
                if life.ended {
                    life.ended = false;
                    lv.new_edges.push(e);
                    lv.edge_ltis.push((e, lti));
                }
                e
            }
            None => {
                let child = match enc.node_of.get(&w.value) {
                    Some(&n) => n,
                    None => {
                        let n = store.next_node;
                        store.next_node += 1;
                        enc.node_of.insert(w.value, n);
                        if lti != 0 {
                            store.node_ltis.insert(n, lti);
                            enc.lti_known.insert(w.value);
                        }
                        n
                    }
                };
                enc.refs.entry(child).or_default();
                let e = store.edges.add((lv.parent, key.1, child));
                lv.new_edges.push(e);
                lv.edge_ltis.push((e, lti));
                e
            }
        };
        enc.pool_of.insert(edge, key);
        enc.wme_row.insert(w.timetag, edge);
        let child = enc.node_of[&w.value];
        if lv.new_ids.contains(&w.value) {
            enc.refs.entry(child).or_default().push(w.timetag);
        }
        if !lv.visited.contains(&w.value) {
            lv.queue.push_back((w.value, child));
        }
    }

    fn epmem_store_constant(&mut self, w: &Wme, lv: &mut Level<'_>) {
        let attr = self.epmem_attr_hash(w);
        let value = self.epmem_constant(w.value);
        let enc = &mut self.epmem.encoder;
        let Some(store) = self.epmem.store.as_mut() else {
            return;
        };
        let value = store.hash(value);
        let triple = (lv.parent, attr, value);
        let row = match store.consts.find(&triple) {
            Some(c) => {
                enc.const_removals.insert(c, false);
                let life = store.consts.life_mut(c);
                if life.ended {
                    life.ended = false;
                    lv.new_consts.push(c);
                }
                c
            }
            None => {
                let c = store.consts.add(triple);
                lv.new_consts.push(c);
                c
            }
        };
        enc.wme_row.insert(w.timetag, row);
    }
}

/// The walk's state while one identifier's WMEs are stored.
struct Level<'a> {
    parent: i64,
    queue: &'a mut VecDeque<(Sym, i64)>,
    visited: &'a FxHashSet<Sym>,
    reservations: &'a mut FxHashMap<u64, Reservation>,
    new_ids: &'a mut FxHashSet<Sym>,
    new_consts: &'a mut Vec<i64>,
    new_edges: &'a mut Vec<i64>,
    /// New edges' ranges with the long-term identifier their child stands for.
    edge_ltis: &'a mut Vec<(i64, i64)>,
}
