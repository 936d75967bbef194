//! Episodic memory (Soar manual, ch. 7, "Episodic Memory"): snapshots of the top state's
//! working memory, stored as they change (`store.rs`, `encode.rs`, `timeline.rs`), rebuilt
//! on request (`retrieve.rs`) and searched by cue (`query.rs`, `walk.rs`) through each
//! state's `^epmem` link (`wmi.rs`). The store lives in memory; with `database file` it is
//! also written to a SQLite file with 9.6's tables (`disk.rs`), which a later agent can
//! open and go on with.

mod cue;
mod disk;
mod encode;
pub mod params;
pub mod print;
mod query;
mod retrieve;
mod rit;
mod schema;
pub mod store;
mod timeline;
mod walk;
mod wmi;

use crate::symbols::Sym;
use crate::wm::{Wme, WmeId};
use rustc_hash::{FxHashMap, FxHashSet};
use std::collections::{BTreeMap, BTreeSet, VecDeque};

/// The counts of `epmem --stats`.
#[derive(Debug, Clone, Copy, Default)]
pub struct EpmemStats {
    pub retrievals: u64,
    pub queries: u64,
    pub nexts: u64,
    pub prevs: u64,
    pub ncb_wmes: u64,
    pub qry_pos: u64,
    pub qry_neg: u64,
    pub qry_ret: i64,
    pub qry_card: i64,
    pub qry_lits: u64,
}

/// What episodic memory knows of working memory between episodes (9.6 keeps it on WMEs and
/// identifiers): which WMEs and identifiers are stored as which rows and nodes, which
/// identifiers got new WMEs, and which rows end at the next episode.
#[derive(Debug, Default)]
pub(crate) struct Encoder {
    /// The row (constant or edge) of each stored WME, by timetag.
    pub wme_row: FxHashMap<u64, i64>,
    /// The node of each stored identifier.
    pub node_of: FxHashMap<Sym, i64>,
    /// The stored WMEs that point at each node, by timetag: a node no WME points at is free
    /// to stand for another identifier.
    pub refs: FxHashMap<i64, Vec<u64>>,
    /// Edges whose WMEs are gone, by `(parent node, attribute)`: (child node, edge), most
    /// recently freed first. A new identifier under the same parent and attribute takes
    /// one, so that the same structure keeps the same nodes.
    pub pools: FxHashMap<(i64, i64), VecDeque<(i64, i64)>>,
    /// The pool each edge in use goes back to.
    pub pool_of: FxHashMap<i64, (i64, i64)>,
    /// Stored identifiers with new WMEs since the last episode.
    pub adds: BTreeSet<Sym>,
    /// Rows whose WMEs went since the last episode (`false`: one came back).
    pub const_removals: BTreeMap<i64, bool>,
    pub edge_removals: BTreeMap<i64, bool>,
    /// Stored identifiers whose link to semantic memory the store has recorded.
    pub lti_known: FxHashSet<Sym>,
}

/// Each state's record of its `^epmem` link.
#[derive(Debug, Default)]
pub(crate) struct LinkState {
    /// The newest timetag and the number of the command's WMEs when last looked at.
    pub last_cmd_time: u64,
    pub last_cmd_count: usize,
    /// The episode retrieved last (for `next` and `previous`).
    pub last_memory: Option<i64>,
    /// The results' WMEs, in the order of their triples (the episode's, then the meta
    /// results).
    pub results: Vec<WmeId>,
    /// The preferences of the results on the result link, in the order made: the next
    /// command takes them out, last first.
    pub meta: Vec<crate::decide::state::RecallPref>,
}

/// Episodic memory's timers and their levels (9.6's names). The level-three timers of
/// the query's and the retrieval's parts, which 9.6.5 lists, time nothing in rusoar.
pub mod timer {
    use crate::memory_timers::Timer;
    /// Episodic memory's work at a phase: the episode and the commands.
    pub const TOTAL: Timer = ("_total", 1);
    /// Reading the commands of `^epmem.command`.
    pub const API: Timer = ("epmem_api", 2);
    /// Making the store.
    pub const INIT: Timer = ("epmem_init", 2);
    /// Putting a retrieved episode in working memory.
    pub const NCB_RETRIEVAL: Timer = ("epmem_ncb_retrieval", 2);
    /// `next` commands.
    pub const NEXT: Timer = ("epmem_next", 2);
    /// `previous` commands.
    pub const PREV: Timer = ("epmem_prev", 2);
    /// Queries.
    pub const QUERY: Timer = ("epmem_query", 2);
    /// Storing an episode.
    pub const STORAGE: Timer = ("epmem_storage", 2);
    /// Deciding whether an episode is due.
    pub const TRIGGER: Timer = ("epmem_trigger", 2);
    /// Adding and removing the commands' results.
    pub const WM_PHASE: Timer = ("epmem_wm_phase", 2);
}

/// The episodic memory of one agent.
#[derive(Debug, Default)]
pub struct Epmem {
    pub params: params::EpmemParams,
    pub stats: EpmemStats,
    /// `epmem --timers`: the time spent in each part ([`timer`]).
    pub timers: crate::memory_timers::MemoryTimers,
    /// The store, made at the first episode or command after learning is on.
    pub(crate) store: Option<store::Store>,
    /// The file the store is written to, with `database file`.
    pub(crate) disk: Option<disk::Disk>,
    pub(crate) encoder: Encoder,
    pub(crate) links: FxHashMap<Sym, LinkState>,
    /// The newest output-link timetag an episode was triggered by (`trigger output`).
    pub(crate) last_output_time: u64,
    /// The `^present-id` changes of the last episode, shown (`=>WM:`, `<=WM:`) at the
    /// next working-memory phase, as 9.6 traces its module WMEs.
    pub(crate) present_trace: Vec<(bool, Wme)>,
}

impl Epmem {
    /// Whether the store is open (9.6's "connected" database).
    pub fn is_open(&self) -> bool {
        self.store.is_some()
    }

    /// The next episode's number (each state's `^present-id`).
    pub fn time(&self) -> i64 {
        self.store.as_ref().map_or(1, |s| s.time)
    }

    /// Where episodic memory's results hold this WME: its place among its command's
    /// results, in triple order (9.6 lists a result's slot in that order).
    pub(crate) fn made(&self, w: WmeId) -> Option<usize> {
        if self.links.is_empty() {
            return None;
        }
        self.links
            .values()
            .find_map(|l| l.results.iter().position(|&x| x == w))
    }

    /// `epmem --backup FILE`: the store as 9.6's database file.
    pub fn backup(&mut self, to: &str) -> Result<(), String> {
        if let Some(d) = self.disk.as_mut() {
            return d.backup(to);
        }
        match &self.store {
            Some(s) => disk::snapshot(s, to),
            None => disk::snapshot(&store::Store::default(), to),
        }
    }

    /// Writes what lazy-commit holds back to the file, if there is one.
    pub fn commit(&mut self) -> Result<(), String> {
        self.disk.as_mut().map_or(Ok(()), |d| d.commit())
    }

    /// The store, for printing.
    pub fn store(&self) -> Option<&store::Store> {
        self.store.as_ref()
    }
}
