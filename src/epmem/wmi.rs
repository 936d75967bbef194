//! The working-memory interface of episodic memory (Soar manual, ch. 7, "Working Memory
//! Interface"): at the output phase (or before the decision with `phase selection`) an
//! episode is stored when `trigger` or `force` says so, every state's `^present-id` moves
//! on, and each state whose `^epmem.command` changed gets its results: a `retrieve`,
//! `next` or `previous` rebuilds an episode, a `query` searches for one, anything else is
//! `^status bad-cmd`. Results replace the previous command's.

use super::retrieve::Triples;
use crate::agent::AgentCore;
use crate::decide::recall::RecallPref;
use crate::symbols::{Sym, SymData};
use crate::wm::{Wme, WmeId};

/// A state's `^epmem` link: the link, its `^command` and its `^result`.
type Link = (Sym, Sym, Sym);

/// A state with a new command: its link, the state, and the command's WMEs (none when it
/// was emptied).
type NewCommand = (Link, Sym, Option<Vec<Wme>>);

/// A parsed `^command` (9.6's `_epmem_respond_to_cmd_parse`).
#[derive(Debug, Default)]
struct Command {
    retrieve: Option<i64>,
    next: Option<Sym>,
    previous: Option<Sym>,
    query: Option<Sym>,
    neg_query: Option<Sym>,
    before: Option<i64>,
    after: Option<i64>,
    prohibit: Vec<i64>,
}

impl AgentCore {
    /// 9.6's `epmem_go`: stores an episode if one is due, then answers commands.
    pub(crate) fn epmem_go(&mut self) {
        if !self.epmem.params.learning() {
            return;
        }
        let total = self.epmem_timer(super::timer::TOTAL);
        let t = self.epmem_timer(super::timer::INIT);
        self.epmem_attach();
        self.epmem.timers.stop(t);
        let t = self.epmem_timer(super::timer::TRIGGER);
        let due = self.epmem_episode_due();
        self.epmem.timers.stop(t);
        if due {
            let t = self.epmem_timer(super::timer::STORAGE);
            self.epmem_new_episode();
            self.epmem.timers.stop(t);
        }
        self.epmem_respond();
        self.epmem.timers.stop(total);
    }

    /// Starts `timer` if episodic memory's `timers` setting reaches its level.
    fn epmem_timer(&self, timer: crate::memory_timers::Timer) -> crate::memory_timers::Running {
        crate::memory_timers::MemoryTimers::start(timer, self.epmem.params.timers())
    }

    /// The output phase's part.
    pub(crate) fn epmem_output_phase(&mut self) {
        if self.epmem.params.at_output() {
            self.epmem_go();
        }
    }

    /// The decision phase's part, before the selection (`phase selection`).
    pub(crate) fn epmem_selection_phase(&mut self) {
        if !self.epmem.params.at_output() {
            self.epmem_go();
        }
    }

    /// Whether `trigger` or `force` calls for an episode now.
    fn epmem_episode_due(&mut self) -> bool {
        match self.epmem.params.force() {
            "remember" => {
                self.epmem.params.clear_force();
                return true;
            }
            "ignore" => {
                self.epmem.params.clear_force();
                return false;
            }
            _ => {}
        }
        match self.epmem.params.trigger() {
            "dc" => true,
            "output" => {
                let newest = self
                    .wm
                    .of_id(self.top.output_link)
                    .filter_map(|w| self.wm.get(w).map(|x| x.timetag))
                    .max()
                    .unwrap_or(0);
                let due = newest > self.epmem.last_output_time;
                self.epmem.last_output_time = self.epmem.last_output_time.max(newest);
                due
            }
            _ => false,
        }
    }

    /// The states, bottom first, with their `^epmem` links' command and result.
    fn epmem_states(&self) -> Vec<(Sym, Option<Link>)> {
        let mut states: Vec<Sym> = self.decider.goals.iter().map(|g| g.state).collect();
        if states.is_empty() {
            states.push(self.top.state);
        }
        states.reverse();
        states
            .into_iter()
            .map(|s| {
                let link = self.child_of(s, "epmem").and_then(|e| {
                    Some((e, self.child_of(e, "command")?, self.child_of(e, "result")?))
                });
                (s, link)
            })
            .collect()
    }

    /// Moves every state's `^present-id` on to the next episode; the trace shows the
    /// change at the next working-memory phase.
    pub(crate) fn epmem_move_present(&mut self) {
        let time = self.epmem.time();
        let attr = self.symbols.str("present-id");
        let value = self.symbols.int(time);
        for (state, link) in self.epmem_states() {
            let Some((e, _, _)) = link else { continue };
            let old: Vec<WmeId> = self
                .wm
                .of_id(e)
                .filter(|&w| self.wm.get(w).is_some_and(|x| x.attr == attr))
                .collect();
            let w = self.wm.add(e, attr, value, false);
            self.match_wme_now(w, (e, attr, value), false);
            if let Some(x) = self.wm.get(w).copied() {
                self.epmem.present_trace.push((true, x));
            }
            for o in old {
                if let Some(x) = self.wm.get(o).copied() {
                    self.epmem.present_trace.push((false, x));
                    self.remove_wme(o);
                }
                // A substate's own WMEs go with it: the new one takes the old one's place.
                if let Some(g) = self.decider.goals.iter_mut().find(|g| g.state == state) {
                    for x in g.wmes.iter_mut().filter(|x| **x == o) {
                        *x = w;
                    }
                }
            }
        }
    }

    /// A working-memory phase: the `^present-id` WMEs made since the last one are traced,
    /// after the phase's own additions (they are older)...
    pub(crate) fn epmem_trace_present_adds(&mut self) {
        self.epmem_trace_present_kind(true);
    }

    /// ... and the ones they replaced, after the phase's own removals.
    pub(crate) fn epmem_trace_present_removals(&mut self) {
        self.epmem_trace_present_kind(false);
    }

    /// Both, where there is no other change (the input phase).
    pub(crate) fn epmem_trace_present(&mut self) {
        self.epmem_trace_present_adds();
        self.epmem_trace_present_removals();
    }

    fn epmem_trace_present_kind(&mut self, added: bool) {
        if self.epmem.present_trace.is_empty() {
            return;
        }
        let (mine, rest): (Vec<_>, Vec<_>) = std::mem::take(&mut self.epmem.present_trace)
            .into_iter()
            .partition(|c| c.0 == added);
        self.epmem.present_trace = rest;
        self.decider.wme_changes += mine.len() as u64;
        // Both lists go top state first: 9.6 moves the states bottom first and
        // head-inserts its changes (observed on soar-sml 9.6.5: epmem-count's substates).
        for (_, w) in mine.iter().rev() {
            self.trace_wme(added, w);
        }
    }

    /// 9.6's `epmem_respond_to_cmd`: each state whose command changed has its last
    /// results on the result link taken out, then gets its command's results as the
    /// preferences of 9.6's `|Memory System Recall|` instantiation; one working-memory
    /// phase then brings them in (the old episode goes with the garbage).
    fn epmem_respond(&mut self) {
        let mut work: Vec<NewCommand> = Vec::new();
        for (state, link) in self.epmem_states() {
            let Some(link @ (_, cmd, _)) = link else { continue };
            // Every WME under the command, breadth-first.
            let mut seen = vec![cmd];
            let mut queue = std::collections::VecDeque::from([cmd]);
            let mut count = 0;
            let mut newest = 0;
            let mut top_level: Option<Vec<Wme>> = None;
            while let Some(id) = queue.pop_front() {
                let wmes = self.epmem_augs_of(id);
                for w in &wmes {
                    count += 1;
                    newest = newest.max(w.timetag);
                    if self.symbols.is_id(w.value) && !seen.contains(&w.value) {
                        seen.push(w.value);
                        queue.push_back(w.value);
                    }
                }
                top_level.get_or_insert(wmes);
            }
            let info = self.epmem.links.entry(state).or_default();
            let mut new_cue = false;
            if newest > info.last_cmd_time {
                info.last_cmd_time = newest;
                new_cue = true;
            }
            if info.last_cmd_count != count {
                info.last_cmd_count = count;
                new_cue = true;
            }
            if !new_cue {
                continue;
            }
            work.push((link, state, (count > 0).then(|| top_level.unwrap_or_default())));
        }
        if work.is_empty() {
            return;
        }
        let wm_phase = self.epmem_timer(super::timer::WM_PHASE);
        let mut made: Vec<(Sym, Link, Vec<RecallPref>, Vec<u64>)> = Vec::new();
        for ((lnk, cmd, res), state, cmds) in work {
            let link = self.epmem.links.entry(state).or_default();
            let gone = std::mem::take(&mut link.meta);
            link.results.clear();
            let gone_wmes = self.clear_recall_results(&gone);
            let (mut meta, mut retrieval) = (Triples::new(), Triples::new());
            if let Some(cmds) = cmds {
                self.epmem_command(state, res, &cmds, &mut meta, &mut retrieval);
            }
            // 9.6's instantiation lists its preferences in the reverse of its buffers.
            let triples: Triples = meta.iter().rev().chain(retrieval.iter().rev()).copied().collect();
            let conditions = self.memory_command_conditions((state, lnk, cmd, res));
            let prefs = self.add_recall_prefs(state, &triples, &conditions);
            self.epmem.links.entry(state).or_default().meta = prefs[..meta.len()].to_vec();
            made.push((state, (lnk, cmd, res), prefs, gone_wmes));
        }
        let newest_before = self.wm.next_timetag();
        self.update_slots();
        for (state, (lnk, cmd, res), prefs, gone_wmes) in made {
            self.forget_gone_results(&gone_wmes);
            // The results in the order of their triples: the episode's, then the meta
            // results (`print` lists them so).
            let wmes: Vec<WmeId> = prefs.iter().rev().filter_map(|&p| self.recall_wme(p)).collect();
            let fresh: Vec<WmeId> = wmes
                .iter()
                .copied()
                .filter(|&x| self.wm.get(x).is_some_and(|x| x.timetag >= newest_before))
                .collect();
            self.epmem.links.entry(state).or_default().results = wmes;
            // Backtracing goes through the architecture's firing that made them.
            if !fresh.is_empty() {
                let conditions = self.memory_command_conditions((state, lnk, cmd, res));
                let level = self.sym_level(state);
                self.note_memory_results(level, res, &fresh, &conditions);
            }
        }
        self.epmem.timers.stop(wm_phase);
    }

    /// Reads and carries out one state's command.
    fn epmem_command(
        &mut self,
        state: Sym,
        res: Sym,
        cmds: &[Wme],
        meta: &mut Triples,
        retrieval: &mut Triples,
    ) {
        let t = self.epmem_timer(super::timer::API);
        let parsed = self.epmem_parse(cmds);
        self.epmem.timers.stop(t);
        let Some(c) = parsed else {
            let (a, v) = (self.symbols.str("status"), self.symbols.str("bad-cmd"));
            meta.push((res, a, v));
            return;
        };
        if let Some(t) = c.retrieve {
            self.epmem_install(state, res, Some(t), meta, retrieval);
            self.epmem.stats.retrievals += 1;
        } else if let Some(x) = c.next.or(c.previous) {
            let which = if c.next.is_some() { super::timer::NEXT } else { super::timer::PREV };
            let timer = self.epmem_timer(which);
            let last = self.epmem.links.get(&state).and_then(|l| l.last_memory);
            let store = self.epmem.store.as_ref();
            let t = match (last, c.next.is_some()) {
                (Some(l), true) => Some(l + 1).filter(|&t| store.is_some_and(|s| s.valid(t))),
                (Some(l), false) => Some(l - 1).filter(|&t| t >= 1),
                (None, _) => None,
            };
            self.epmem_install(state, res, t, meta, retrieval);
            if c.next.is_some() {
                self.epmem.stats.nexts += 1;
            } else {
                self.epmem.stats.prevs += 1;
            }
            self.epmem.timers.stop(timer);
            let got = self.epmem.links.get(&state).and_then(|l| l.last_memory).is_some();
            let a = self.symbols.str(if got { "success" } else { "failure" });
            meta.push((res, a, x));
        } else if let Some(q) = c.query {
            let t = self.epmem_timer(super::timer::QUERY);
            self.epmem_query(state, res, q, &c, meta, retrieval);
            self.epmem.timers.stop(t);
            self.epmem.stats.queries += 1;
        }
    }

    fn epmem_parse(&self, cmds: &[Wme]) -> Option<Command> {
        let mut c = Command::default();
        // 9.6's paths: 1 retrieve, 2 next/previous, 3 query and its modifiers.
        let mut path = 0;
        for w in cmds {
            let int = match self.symbols.get(w.value) {
                SymData::Int(i) => Some(*i),
                _ => None,
            };
            let is_id = self.symbols.is_id(w.value);
            match self.symbols.text(w.attr).as_str() {
                "retrieve" if path == 0 && int.is_some_and(|i| i > 0) => {
                    c.retrieve = int;
                    path = 1;
                }
                "next" if path == 0 && is_id => {
                    c.next = Some(w.value);
                    path = 2;
                }
                "previous" if path == 0 && is_id => {
                    c.previous = Some(w.value);
                    path = 2;
                }
                "query" if (path == 0 || path == 3) && is_id && c.query.is_none() => {
                    c.query = Some(w.value);
                    path = 3;
                }
                "neg-query" if (path == 0 || path == 3) && is_id && c.neg_query.is_none() => {
                    c.neg_query = Some(w.value);
                    path = 3;
                }
                "before" if (path == 0 || path == 3) && int.is_some() => {
                    let b = int.unwrap_or(0);
                    c.before = Some(c.before.map_or(b, |x| x.min(b)));
                    path = 3;
                }
                "after" if (path == 0 || path == 3) && int.is_some() => {
                    let a = int.unwrap_or(0);
                    c.after = Some(c.after.map_or(a, |x| x.max(a)));
                    path = 3;
                }
                "prohibit" if (path == 0 || path == 3) && int.is_some() => {
                    c.prohibit.push(int.unwrap_or(0));
                    path = 3;
                }
                _ => return None,
            }
        }
        if path == 0 || (path == 3 && c.query.is_none()) {
            return None;
        }
        Some(c)
    }

    fn epmem_query(
        &mut self,
        state: Sym,
        res: Sym,
        q: Sym,
        c: &Command,
        meta: &mut Triples,
        retrieval: &mut Triples,
    ) {
        if let (Some(b), Some(a)) = (c.before, c.after) {
            if b <= a {
                let (s, v) = (self.symbols.str("status"), self.symbols.str("bad-cmd"));
                meta.push((res, s, v));
                return;
            }
        }
        let cue = self.epmem_cue(q, c.neg_query);
        let stats = &mut self.epmem.stats;
        stats.qry_pos = cue.pos_literals;
        stats.qry_neg = cue.neg_literals;
        stats.qry_lits = cue.pos_literals + cue.neg_literals;
        let mut kings = Vec::new();
        let found = self.epmem_search(&cue, c.before, c.after, &c.prohibit, &mut kings);
        if self.settings.trace.epmem {
            for (perfect, graph_matched) in kings {
                self.output.push_str(&format!(
                    "NEW KING (perfect, graph-match): ({perfect}, {graph_matched})\n"
                ));
            }
        }
        let cues = [Some(q), c.neg_query];
        let Some(found) = found else {
            let a = self.symbols.str("failure");
            for x in cues.into_iter().flatten() {
                meta.push((res, a, x));
            }
            return;
        };
        self.epmem.stats.qry_ret = found.episode;
        self.epmem.stats.qry_card = found.cardinality;
        let mut add = |agent: &mut AgentCore, attr: &str, value: Sym| {
            let a = agent.symbols.str(attr);
            meta.push((res, a, value));
        };
        let v = self.symbols.int(cue.leaves as i64);
        add(self, "cue-size", v);
        let v = self.symbols.int(found.cardinality);
        add(self, "match-cardinality", v);
        let v = self.symbols.float(found.score);
        add(self, "match-score", v);
        let v = self.symbols.float(found.score / found.perfect_score);
        add(self, "normalized-match-score", v);
        for x in cues.into_iter().flatten() {
            add(self, "success", x);
        }
        let mut nodes: Vec<(i64, Sym)> = Vec::new();
        if self.epmem.params.graph_match() {
            let v = self.symbols.int(i64::from(found.graph_matched));
            add(self, "graph-match", v);
            if found.graph_matched {
                let level = self.symbols.id_data(res).map_or(1, |d| d.level);
                let mapping = self.symbols.new_id('M', level);
                add(self, "mapping", mapping);
                let (node_attr, cue_attr) = (self.symbols.str("node"), self.symbols.str("cue"));
                for &(cue_sym, node) in &found.bindings {
                    let n = self.symbols.new_id('N', level);
                    meta.push((mapping, node_attr, n));
                    meta.push((n, cue_attr, cue_sym));
                    nodes.push((node, n));
                }
            }
        }
        let ids = self.epmem_install(state, res, Some(found.episode), meta, retrieval);
        nodes.sort_by_key(|&(node, _)| node);
        nodes.dedup_by_key(|x| x.0);
        let retrieved = self.symbols.str("retrieved");
        for (node, n) in nodes {
            if let Some(&x) = ids.get(&node) {
                meta.push((n, retrieved, x));
            }
        }
    }
}
