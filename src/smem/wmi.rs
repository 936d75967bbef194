//! The working-memory interface of semantic memory (Soar manual, ch. 6, "Semantic Memory",
//! "Working Memory Interface"): each state's `^smem` link holds a `^command` the rules
//! fill and a `^result` the architecture fills. A changed command is processed once: its
//! `^store`s right after the working-memory phase that made them (observed on soar-sml
//! 9.6.5: the `^success` follows the storing rule's WMEs in the same elaboration), the
//! other commands at the output phase. The results of a command go when it changes.

use super::query::{Cue, Math, Want};
use super::store::Val;
use crate::agent::AgentCore;
use crate::symbols::{Sym, SymData};
use crate::decide::recall::RecallPref;
use crate::wm::{Wme, WmeId};
use rustc_hash::FxHashMap;

/// What was last processed on one `^smem` link.
#[derive(Debug, Default)]
struct LinkState {
    /// The command's WMEs (and those of the objects it names), by timetag.
    signature: Vec<u64>,
    /// The preferences of the results on the result link, in the order made: the next
    /// command takes them out, last first (9.6's list of a state's memory results).
    results: Vec<RecallPref>,
    /// The command processed last had a `^store`.
    had_store: bool,
}

/// Each `^smem` link's record, by the link's identifier.
#[derive(Debug, Default)]
pub struct Links {
    by_link: FxHashMap<Sym, LinkState>,
    /// The identifiers a retrieval deeper than one level filled, for `^depth-retrieved`.
    deeper: Vec<Sym>,
}

/// A command's results as 9.6 buffers them before making its instantiation: those on
/// the result link, and the retrieved objects' WMEs.
#[derive(Debug, Default)]
struct Buffered {
    meta: Vec<(Sym, Sym, Sym)>,
    retrieval: Vec<(Sym, Sym, Sym)>,
}

/// A link whose command changed, for the bookkeeping after its results are in working
/// memory.
struct Work {
    state: Sym,
    level: u32,
    link: Sym,
    cmd: Sym,
    res: Sym,
    cmd_wmes: Vec<Wme>,
    made: Vec<RecallPref>,
    /// The timetags of the WMEs of the last command's results on the result link.
    gone_wmes: Vec<u64>,
}

/// A parsed `^command`.
#[derive(Debug, Default)]
struct Command {
    query: Option<Sym>,
    neg_query: Option<Sym>,
    math_query: Option<Sym>,
    retrieve: Option<Sym>,
    stores: Vec<Sym>,
    prohibit: Vec<i64>,
    depth: Option<i64>,
}

impl AgentCore {
    /// An object's WMEs, oldest first.
    fn smem_wmes(&self, id: Sym) -> Vec<Wme> {
        let mut ws: Vec<Wme> = self
            .wm
            .of_id(id)
            .filter_map(|w| self.wm.get(w).copied())
            .collect();
        ws.sort_by_key(|w| w.timetag);
        ws
    }

    /// Processes the `^store` commands after a working-memory phase of an elaboration;
    /// `header` is the elaboration's firing type when the apply phase's headers are
    /// traced (9.6 adds the results in a working-memory phase of their own, with its
    /// header).
    pub(crate) fn smem_after_elaboration(&mut self, header: Option<bool>) {
        if self.smem.enabled {
            self.smem_go(true, header);
        }
    }

    /// Processes every changed command at the output phase.
    pub(crate) fn smem_output_phase(&mut self) {
        if self.smem.enabled {
            self.smem_go(false, None);
        }
    }

    /// [`smem_go_untimed`](Self::smem_go_untimed) under the `_total` timer.
    fn smem_go(&mut self, store_only: bool, header: Option<bool>) {
        let t = self.smem.timer_start(super::timer::TOTAL);
        self.smem_go_untimed(store_only, header);
        self.smem.timers.stop(t);
    }

    /// Gives semantic memory the LTIs with an instance in working memory (an identifier
    /// linked to the LTI with an augmentation of its own), the sources of spreading
    /// activation, before a query.
    pub(crate) fn smem_note_context(&mut self) {
        if !self.smem.params.spreading() {
            return;
        }
        let mut context = std::collections::BTreeSet::new();
        for w in self.wm.all() {
            if let Some(lti) = self.wm.get(w).and_then(|x| self.symbols.lti(x.id)) {
                context.insert(lti);
            }
        }
        self.smem.context = context;
    }

    /// `init-soar`: working memory is new, so are the links' records; the counts of
    /// `smem --stats` start again (observed on soar-sml 9.6.5).
    pub(crate) fn smem_reinitialize(&mut self) {
        self.smem.links = Links::default();
        self.smem.stats = super::SmemStats::default();
        self.smem.timers.reset();
    }

    fn smem_go_untimed(&mut self, store_only: bool, header: Option<bool>) {
        let states: Vec<(Sym, u32)> = self
            .decider
            .goals
            .iter()
            .map(|g| (g.state, g.level))
            .collect();
        // The top state when no goal has been made yet.
        let states = if states.is_empty() {
            vec![(self.top.state, 1)]
        } else {
            states
        };
        let mut work: Vec<Work> = Vec::new();
        for (state, level) in states {
            let Some(link) = self.child_of(state, "smem") else {
                continue;
            };
            let (Some(cmd), Some(res)) =
                (self.child_of(link, "command"), self.child_of(link, "result"))
            else {
                continue;
            };
            let cmd_wmes = self.smem_wmes(cmd);
            let mut signature: Vec<u64> = Vec::new();
            for w in &cmd_wmes {
                signature.push(w.timetag);
                if self.symbols.is_id(w.value) {
                    for c in self.smem_wmes(w.value) {
                        signature.push(c.timetag);
                        if self.symbols.is_id(c.value) {
                            signature.extend(self.smem_wmes(c.value).iter().map(|x| x.timetag));
                        }
                    }
                }
            }
            let store = self.symbols.find_str("store");
            let old = self.smem.links.by_link.entry(link).or_default();
            if old.signature == signature {
                continue;
            }
            // Between phases only a command of stores is processed, and a command with a
            // store that changes takes its results with it (observed on soar-sml 9.6.5);
            // the rest waits for the output phase.
            let all_stores = cmd_wmes.iter().all(|w| Some(w.attr) == store);
            let process = !store_only || (all_stores && !cmd_wmes.is_empty());
            if !process && !old.had_store {
                continue;
            }
            if process {
                old.signature = signature;
                old.had_store = cmd_wmes.iter().any(|w| Some(w.attr) == store);
            } else {
                old.had_store = false;
            }
            let gone = std::mem::take(&mut old.results);
            // The last command's results on the result link go first, last made first;
            // then the new command's preferences come in (9.6's `smem_clear_result`,
            // then its instantiation).
            let gone_wmes = self.clear_recall_results(&gone);
            let mut buffered = Buffered::default();
            if process && !cmd_wmes.is_empty() {
                self.smem_process(cmd, res, level, &cmd_wmes, &mut buffered);
            }
            // 9.6's instantiation lists its preferences in the reverse of its buffers.
            let triples: Vec<(Sym, Sym, Sym)> = buffered
                .meta
                .iter()
                .rev()
                .chain(buffered.retrieval.iter().rev())
                .copied()
                .collect();
            let conditions = self.memory_command_conditions((state, link, cmd, res));
            let made = self.add_recall_prefs(state, &triples, &conditions);
            let meta = made[..buffered.meta.len()].to_vec();
            if !made.is_empty() || !gone_wmes.is_empty() {
                work.push(Work {
                    state,
                    level,
                    link,
                    cmd,
                    res,
                    cmd_wmes,
                    made,
                    gone_wmes,
                });
            }
            self.smem.links.by_link.entry(link).or_default().results = meta;
        }
        if work.is_empty() {
            return;
        }
        if let Some(o_support) = header {
            self.emit(&crate::trace_events::TraceEvent::ChangeWorkingMemory { o_support });
        }
        let newest_before = self.wm.next_timetag();
        self.update_slots();
        for w in work {
            self.forget_gone_results(&w.gone_wmes);
            let fresh: Vec<WmeId> = w
                .made
                .iter()
                .filter_map(|&p| self.recall_wme(p))
                .filter(|&x| self.wm.get(x).is_some_and(|x| x.timetag >= newest_before))
                .collect();
            if fresh.is_empty() {
                continue;
            }
            if self.wma.on() {
                let mut conditions: Vec<WmeId> = [(w.state, w.link), (w.link, w.cmd), (w.link, w.res)]
                    .into_iter()
                    .filter_map(|(id, value)| self.wme_linking(id, value))
                    .collect();
                conditions.extend(w.cmd_wmes.iter().filter_map(|x| self.wm.by_timetag(x.timetag)));
                self.wma_memory_results(&fresh, &conditions);
            }
            let conditions = self.memory_command_conditions((w.state, w.link, w.cmd, w.res));
            self.note_memory_results(w.level, w.res, &fresh, &conditions);
        }
    }

    /// Reads a command; `None` when it is malformed (Soar manual, Semantic Memory: two
    /// retrievals at once, a cue that is not an identifier, a modifier without a query, an
    /// unknown attribute).
    fn smem_command(&self, wmes: &[Wme]) -> Option<Command> {
        let mut c = Command::default();
        for w in wmes {
            let is_id = self.symbols.is_id(w.value);
            let one = |slot: &mut Option<Sym>| {
                if slot.is_some() || !is_id {
                    return false;
                }
                *slot = Some(w.value);
                true
            };
            let ok = match self.symbols.text(w.attr).as_str() {
                "query" => one(&mut c.query),
                "neg-query" => one(&mut c.neg_query),
                "math-query" => one(&mut c.math_query),
                "retrieve" => one(&mut c.retrieve),
                "store" => {
                    c.stores.push(w.value);
                    is_id
                }
                "prohibit" => match self.symbols.lti(w.value) {
                    Some(l) => {
                        c.prohibit.push(l);
                        true
                    }
                    None => false,
                },
                "depth" => match self.symbols.get(w.value) {
                    SymData::Int(n) if *n > 0 && c.depth.is_none() => {
                        c.depth = Some(*n);
                        true
                    }
                    _ => false,
                },
                _ => false,
            };
            if !ok {
                return None;
            }
        }
        let modifiers = c.neg_query.is_some() || c.math_query.is_some() || !c.prohibit.is_empty();
        if (c.query.is_some() && c.retrieve.is_some()) || (modifiers && c.query.is_none()) {
            return None;
        }
        Some(c)
    }

    /// Carries a command out: its results go into `out`, in the order 9.6 buffers them.
    fn smem_process(
        &mut self,
        cmd_id: Sym,
        res: Sym,
        level: u32,
        wmes: &[Wme],
        out: &mut Buffered,
    ) {
        // 9.6.5 answers a malformed command with `^bad-cmd <command>` (observed).
        let t = self.smem.timer_start(super::timer::API);
        let cmd = self.smem_command(wmes);
        self.smem.timers.stop(t);
        let Some(cmd) = cmd else {
            self.smem_result(res, "bad-cmd", cmd_id, out);
            return;
        };
        // Several stores go newest WME first, as 9.6 lists a slot's WMEs; their
        // `^success`es are buffered the other way round.
        let mut stored = Vec::new();
        for &s in cmd.stores.iter().rev() {
            let t = self.smem.timer_start(super::timer::STORAGE);
            let done = self.smem_store_object(s);
            self.smem.timers.stop(t);
            stored.push((s, done));
        }
        for (s, done) in stored.into_iter().rev() {
            match done {
                Ok(()) => self.smem_result(res, "success", s, out),
                Err(e) => self.smem_error(res, s, &e, out),
            }
        }
        let depth = cmd.depth.unwrap_or(1);
        if let Some(q) = cmd.query {
            let cue = self.smem_cue(q, cmd.neg_query, cmd.math_query, &cmd.prohibit);
            self.smem_note_context();
            self.smem.stats.queries += 1;
            let found = self.smem.query_first(&cue, 1).map(|f| f.first().copied());
            match found {
                Ok(Some(lti)) => {
                    let activate = self.smem.params.activate_on_query();
                    let successes: Vec<Sym> = [Some(q), cmd.neg_query].into_iter().flatten().collect();
                    self.smem_answer(res, lti, (level, depth), activate, &successes, out);
                }
                Ok(None) => self.smem_result(res, "failure", q, out),
                Err(e) => self.smem_error(res, q, &e, out),
            }
        }
        if let Some(r) = cmd.retrieve {
            // An identifier that stands for no LTI is a retrieve that fails, uncounted;
            // one that does gets a new identifier for the LTI, with its augmentations
            // (observed on soar-sml 9.6.5).
            let lti = self.symbols.lti(r).unwrap_or(0);
            if lti > 0 {
                self.smem.stats.retrieves += 1;
            }
            let exists = self.smem.store().and_then(|s| s.lti_exists(lti));
            match exists {
                // A retrieve activates the LTI, as a query does (9.6's `install_memory`
                // with activation; observed on soar-sml 9.6.5).
                Ok(true) => self.smem_answer(res, lti, (level, depth), true, &[r], out),
                Ok(false) => self.smem_result(res, "failure", r, out),
                Err(e) => self.smem_error(res, r, &e, out),
            }
        }
    }

    /// A query's or retrieve's answer: a new identifier for the LTI (activated first if
    /// `activate`), its augmentations down to `depth`, then a `^success` for each of
    /// `successes` (a query's cue, then its negative cue), `^retrieved` and the deeper
    /// levels' `^depth-retrieved`.
    fn smem_answer(
        &mut self,
        res: Sym,
        lti: i64,
        (level, depth): (u32, i64),
        activate: bool,
        successes: &[Sym],
        out: &mut Buffered,
    ) {
        let sti = self.symbols.new_id('L', level);
        if let Some(d) = self.symbols.id_data_mut(sti) {
            d.lti = lti;
        }
        let activated = if activate { self.smem.activate(lti) } else { Ok(()) };
        match activated.and_then(|()| self.smem_install(sti, lti, level, depth, out)) {
            Ok(()) => {
                for &x in successes {
                    self.smem_result(res, "success", x, out);
                }
                self.smem_result(res, "retrieved", sti, out);
                self.smem_depth_results(res, out);
            }
            Err(e) => self.smem_error(res, successes[0], &e, out),
        }
    }

    /// A database failure: the message on the print stream and `^failure` of what was
    /// asked.
    fn smem_error(&mut self, res: Sym, asked: Sym, e: &str, out: &mut Buffered) {
        self.fresh_line();
        self.output.push_str(e);
        self.output.push('\n');
        self.smem_result(res, "failure", asked, out);
    }

    /// `(res ^depth-retrieved X)` for each identifier a deeper retrieval filled (observed
    /// on soar-sml 9.6.5).
    fn smem_depth_results(&mut self, res: Sym, out: &mut Buffered) {
        for x in std::mem::take(&mut self.smem.links.deeper) {
            self.smem_result(res, "depth-retrieved", x, out);
        }
    }

    /// `(res ^attr value)` among the results on the result link.
    fn smem_result(&mut self, res: Sym, attr: &str, value: Sym, out: &mut Buffered) {
        let a = self.symbols.str(attr);
        out.meta.push((res, a, value));
    }

    fn smem_sym(&mut self, v: &Val) -> Sym {
        match v {
            Val::Str(s) => self.symbols.str(s),
            Val::Int(i) => self.symbols.int(*i),
            Val::Float(f) => self.symbols.float(*f),
            Val::Lti(_) => self.symbols.str(""),
        }
    }

    fn smem_val(&self, s: Sym) -> Option<Val> {
        match self.symbols.get(s) {
            SymData::Str(x) => Some(Val::Str(x.to_string())),
            SymData::Int(i) => Some(Val::Int(*i)),
            SymData::Float(f) => Some(Val::Float(*f)),
            SymData::Id(d) if d.lti > 0 => Some(Val::Lti(d.lti)),
            SymData::Id(_) => None,
        }
    }

    /// The LTI's augmentations onto `sti`, and those of the LTIs they name down to
    /// `depth` levels (`^depth`; Soar manual, Semantic Memory, "Retrieval Depth").
    fn smem_install(
        &mut self,
        sti: Sym,
        lti: i64,
        level: u32,
        depth: i64,
        out: &mut Buffered,
    ) -> Result<(), String> {
        let t = self.smem.timer_start(super::timer::NCB_RETRIEVAL);
        let done = self.smem_install_below(sti, lti, level, depth, out);
        self.smem.timers.stop(t);
        done
    }

    /// [`smem_install`](Self::smem_install)'s work, untimed.
    fn smem_install_below(
        &mut self,
        sti: Sym,
        lti: i64,
        level: u32,
        depth: i64,
        out: &mut Buffered,
    ) -> Result<(), String> {
        let augs = self.smem.store()?.augs(lti)?;
        let mut children = Vec::new();
        for (a, v) in augs {
            let attr = self.smem_sym(&a);
            let value = match v {
                Val::Lti(l) => {
                    let child = self.symbols.new_id('L', level);
                    if let Some(d) = self.symbols.id_data_mut(child) {
                        d.lti = l;
                    }
                    children.push((child, l));
                    child
                }
                v => self.smem_sym(&v),
            };
            out.retrieval.push((sti, attr, value));
        }
        if depth > 1 {
            for (child, l) in children {
                self.smem.links.deeper.push(child);
                self.smem_install_below(child, l, level, depth - 1, out)?;
            }
        }
        Ok(())
    }

    /// `^store <id>`: the object's WMEs become its LTI's augmentations (an object without
    /// an LTI gets a new one; an identifier value without one gets one too, empty), and
    /// the LTI is activated. 9.6 prints `@` for each object stored.
    fn smem_store_object(&mut self, id: Sym) -> Result<(), String> {
        let lti = match self.symbols.lti(id) {
            Some(l) => l,
            None => {
                let l = self.smem.store()?.new_lti()?;
                if let Some(d) = self.symbols.id_data_mut(id) {
                    d.lti = l;
                }
                l
            }
        };
        self.smem.store()?.remove_augs(lti, None, None)?;
        let trace = self.settings.trace.smem;
        self.output.push('@');
        if trace {
            self.output.push_str(&super::print::trace_replacement(lti));
        }
        // 9.6 files the object's attributes by symbol, in memory order, which is the
        // order the symbols were made in, and each attribute's values as its slot lists
        // them, the newest WME first: that order gives them their symbol numbers, and so
        // the order a retrieval makes their WMEs in (observed on soar-sml 9.6.5).
        let mut wmes = self.smem_wmes(id);
        wmes.sort_by_key(|w| (w.attr, std::cmp::Reverse(w.timetag)));
        for w in wmes {
            let Some(attr) = self.smem_val(w.attr).filter(|a| !matches!(a, Val::Lti(_))) else {
                continue;
            };
            let value = match self.smem_val(w.value) {
                Some(v) => v,
                None => {
                    let l = self.smem.store()?.new_lti()?;
                    if let Some(d) = self.symbols.id_data_mut(w.value) {
                        d.lti = l;
                    }
                    Val::Lti(l)
                }
            };
            if trace {
                self.output.push_str(&super::print::trace_addition(lti, &attr, &value));
            }
            self.smem.store()?.add_aug(lti, &attr, &value)?;
        }
        self.smem.activate_stored(lti)?;
        self.smem.stats.stores += 1;
        let lazy = self.smem.params.lazy_commit();
        self.smem.store()?.commit(lazy)?;
        Ok(())
    }

    /// The cue of a query: its WMEs, a constant asking for itself, an LTI's stand-in for
    /// the LTI, any other identifier for any value; the negative cue and the math tests
    /// (`(<m> ^attr <t>) (<t> ^less 5)`) beside it.
    fn smem_cue(
        &self,
        q: Sym,
        neg: Option<Sym>,
        math: Option<Sym>,
        prohibit: &[i64],
    ) -> Cue {
        let element = |w: &Wme| -> Option<(Val, Want)> {
            let attr = self.smem_val(w.attr)?;
            let want = match self.smem_val(w.value) {
                Some(Val::Lti(l)) => Want::Lti(l),
                Some(v) => Want::Const(v),
                None => Want::Any,
            };
            Some((attr, want))
        };
        let mut cue = Cue {
            prohibit: prohibit.to_vec(),
            ..Cue::default()
        };
        cue.pos = self.smem_wmes(q).iter().filter_map(element).collect();
        if let Some(n) = neg {
            cue.neg = self.smem_wmes(n).iter().filter_map(element).collect();
        }
        if let Some(m) = math {
            for w in self.smem_wmes(m) {
                let Some(attr) = self.smem_val(w.attr) else {
                    continue;
                };
                for t in self.smem_wmes(w.value) {
                    let n = match self.symbols.get(t.value) {
                        SymData::Int(i) => Some(*i as f64),
                        SymData::Float(f) => Some(*f),
                        _ => None,
                    };
                    if let Some(test) = Math::from_word(&self.symbols.text(t.attr), n) {
                        cue.math.push((attr.clone(), test));
                    }
                }
            }
        }
        cue
    }
}
