//! One agent: its symbols, working memory, RETE network, rules and settings. The decision
//! cycle consumes the match set queued here.

use crate::production::Production;
use crate::rete::{MatchSink, ProdId, Rete, TokId};
use crate::symbols::{Sym, Symbols};
use crate::wm::{Wme, WmeId, WorkingMemory};
use indexmap::IndexMap;

/// When Soar learns (`chunk always|never|only|except`; Soar manual, chapter 4, "Procedural
/// Knowledge Learning").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LearnMode {
    Always,
    Never,
    Only,
    Except,
}

impl LearnMode {
    pub fn word(self) -> &'static str {
        match self {
            LearnMode::Always => "always",
            LearnMode::Never => "never",
            LearnMode::Only => "only",
            LearnMode::Except => "except",
        }
    }
}

/// Kernel settings with 9.6's defaults (Soar manual, chapter 9, "The Soar User Interface": `soar`,
/// `chunk`, `trace`, `output`, `decide`).
#[derive(Debug, Clone)]
pub struct Settings {
    /// Ceilings on a run's growth (`limits`); none by default.
    pub limits: crate::decide::limits::Limits,
    pub learn: LearnMode,
    pub max_chunks: i64,
    pub max_dupes: i64,
    /// `chunk`'s other settings: naming, interrupts, singletons and the rest.
    pub chunk: crate::learn::settings::ChunkSettings,
    pub max_elaborations: i64,
    pub max_goal_depth: i64,
    pub max_nil_output_cycles: i64,
    pub wait_snc: bool,
    /// What the trace shows: `trace N` sets the flags of levels 1 to N, `trace -p` etc. one
    /// each.
    pub trace: TraceFlags,
    pub warnings: bool,
    /// `output agent-writes`: whether `write` (and `log`, `trace`) print.
    pub agent_writes: bool,
    /// `output enabled`: off, the trace and the text of the commands 9.6 prints through
    /// the agent (`print`, `preferences`, `matches`, the summaries) are dropped.
    pub output_enabled: bool,
    /// `output console`: 9.6 also copies its output to the process's standard output;
    /// kept and listed (rusoar's command line prints everything already).
    pub output_console: bool,
    /// `output callbacks`: off, print listeners are not called.
    pub output_callbacks: bool,
    /// `output echo-commands`: kept and listed (9.6 echoes commands to a debugger).
    pub echo_commands: bool,
    /// `output agent-logs N off`: the channels of the `log` function turned off, as bits 1
    /// to 100.
    pub log_channels_off: u128,
    /// `output print-depth`: `print`'s depth when none is given.
    pub print_depth: usize,
    /// `trace -L`: 0 nothing, 1 the names of learned rules, 2 the rules too.
    pub learning_trace: u8,
    /// `decide indifferent-selection`: how an indifferent tie is broken (Soar manual,
    /// `decide` in "The Soar command language").
    pub exploration: Exploration,
    /// `decide numeric-indifferent-mode`: how numeric preferences for one operator combine.
    pub numeric_mode: crate::decide::procedure::NumericMode,
    /// `decide indifferent-selection --epsilon`: epsilon-greedy's chance of a random choice.
    pub epsilon: f64,
    /// `decide indifferent-selection --temperature`: Boltzmann's temperature.
    pub temperature: f64,
    /// `soar timers`: whether `stats` measures where the time goes.
    pub timers: bool,
    /// `soar stop-phase`: a run of decisions stops before this phase (apply by default).
    pub stop_phase: crate::decide::state::Phase,
    /// `soar max-dc-time`: a run stops when one decision takes longer than this many
    /// seconds (0: never).
    pub max_dc_time: i64,
    /// `soar max-memory-usage`: 9.6's threshold for a memory warning, in bytes; kept and
    /// listed (9.6 itself acts on it only in a special build).
    pub max_memory_usage: i64,
    /// `soar max-gp`: the most rules one `gp` may generate.
    pub max_gp: i64,
    /// `soar keep-all-top-oprefs`: keep every preference of an o-supported WME on the top
    /// state (9.6 frees them otherwise); kept and listed.
    pub keep_all_top_oprefs: bool,
    /// `svs --enable-in-substates` / `--disable-in-substates` (kept; rusoar has no spatial
    /// visual system, which stays disabled).
    pub svs_in_substates: bool,
    /// `decide indifferent-selection --auto-reduce`: lower epsilon and the temperature
    /// after each decision phase, each by its own reduction.
    pub auto_reduce: bool,
    /// How `--auto-reduce` lowers epsilon.
    pub epsilon_reduction: Reduction,
    /// How `--auto-reduce` lowers the temperature.
    pub temperature_reduction: Reduction,
}

/// How `decide indifferent-selection --auto-reduce` lowers an exploration parameter: the
/// policy in use, and a rate for each policy (`--reduction-policy`, `--reduction-rate`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reduction {
    pub policy: ReductionPolicy,
    /// The factor of the exponential policy, in [0, 1]; 1 by default (no change).
    pub exponential_rate: f64,
    /// The step of the linear policy, at least 0; 0 by default (no change).
    pub linear_rate: f64,
}

impl Default for Reduction {
    fn default() -> Self {
        Reduction {
            policy: ReductionPolicy::Exponential,
            exponential_rate: 1.0,
            linear_rate: 0.0,
        }
    }
}

impl Reduction {
    /// The parameter after one decision: scaled by the exponential rate, or lowered by
    /// the linear step and kept at 0 or above.
    pub fn apply(&self, value: f64) -> f64 {
        match self.policy {
            ReductionPolicy::Exponential => value * self.exponential_rate,
            ReductionPolicy::Linear => (value - self.linear_rate).max(0.0),
        }
    }
}

/// The reduction policies of `decide indifferent-selection --auto-reduce`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ReductionPolicy {
    /// The parameter is multiplied by the rate, the default.
    Exponential,
    /// The rate is subtracted from the parameter.
    Linear,
}

impl ReductionPolicy {
    /// The policy's name, as `decide` prints it.
    pub fn name(self) -> &'static str {
        match self {
            ReductionPolicy::Exponential => "exponential",
            ReductionPolicy::Linear => "linear",
        }
    }

    /// The policy named `name`.
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "exponential" => Some(ReductionPolicy::Exponential),
            "linear" => Some(ReductionPolicy::Linear),
            _ => None,
        }
    }
}

/// The exploration policies of `decide indifferent-selection`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Exploration {
    /// `--boltzmann`.
    Boltzmann,
    /// `--epsilon-greedy`.
    EpsilonGreedy,
    /// `--first`.
    First,
    /// `--last`.
    Last,
    /// `--softmax`, the default.
    #[default]
    Softmax,
}

impl Exploration {
    /// The policy's name, as `decide indifferent-selection` prints it.
    pub fn name(self) -> &'static str {
        match self {
            Exploration::Boltzmann => "boltzmann",
            Exploration::EpsilonGreedy => "epsilon-greedy",
            Exploration::First => "first",
            Exploration::Last => "last",
            Exploration::Softmax => "softmax",
        }
    }

    /// The policy named `name` (its long option without dashes).
    pub fn from_name(name: &str) -> Option<Self> {
        Some(match name {
            "boltzmann" => Exploration::Boltzmann,
            "epsilon-greedy" => Exploration::EpsilonGreedy,
            "first" => Exploration::First,
            "last" => Exploration::Last,
            "softmax" => Exploration::Softmax,
            _ => return None,
        })
    }
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            limits: crate::decide::limits::Limits::default(),
            learn: LearnMode::Never,
            max_chunks: 50,
            max_dupes: 3,
            chunk: Default::default(),
            max_elaborations: 100,
            max_goal_depth: 100,
            max_nil_output_cycles: 15,
            wait_snc: false,
            trace: TraceFlags::level(1),
            warnings: true,
            agent_writes: true,
            print_depth: 1,
            learning_trace: 0,
            exploration: Exploration::default(),
            numeric_mode: crate::decide::procedure::NumericMode::Sum,
            epsilon: 0.1,
            temperature: 25.0,
            timers: true,
            output_enabled: true,
            output_console: false,
            output_callbacks: true,
            echo_commands: false,
            log_channels_off: 0,
            stop_phase: crate::decide::state::Phase::Apply,
            max_dc_time: 0,
            max_memory_usage: 100_000_000,
            max_gp: 20_000,
            keep_all_top_oprefs: false,
            svs_in_substates: true,
            auto_reduce: false,
            epsilon_reduction: Reduction::default(),
            temperature_reduction: Reduction::default(),
        }
    }
}

/// How `trace --nowmes`, `--timetags` and `--fullwmes` show the WMEs of a firing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum WmeDetail {
    #[default]
    None,
    Timetags,
    Full,
}

/// 9.6's trace settings (`trace` with no arguments lists them): one flag per kind of
/// message. Levels 0 to 5 are shorthands for groups of these (Soar manual, `trace`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct TraceFlags {
    /// Level 1 (`-d`): decision lines and new states.
    pub decisions: bool,
    /// Level 2 (`-p`): the phase headers.
    pub phases: bool,
    /// Level 2 (`-C`).
    pub chunk_warnings: bool,
    /// Level 2 (`-g`): states removed by a GDS violation.
    pub gds: bool,
    /// Level 2 (`-o`): operators removed by the consistency check (`REMOVING: ...`).
    pub consistency: bool,
    /// Level 3 (`-D`): firings and retractions of default rules (the selection space).
    pub default_rules: bool,
    /// Level 3 (`-u`): firings and retractions of user rules.
    pub user_rules: bool,
    /// Level 3 (`-c`): firings of chunks.
    pub chunks: bool,
    /// Level 3 (`-j`): firings of justifications.
    pub justifications: bool,
    /// Level 3 (`-T`): firings of templates.
    pub templates: bool,
    /// Level 3 (`-W`): the inner elaboration headers (`--- Inner Elaboration Phase ...`).
    pub waterfall: bool,
    /// Level 4 (`-w`): `=>WM:` and `<=WM:` lines.
    pub wmes: bool,
    /// Level 5 (`-r`): the preferences of traced firings and retractions.
    pub preferences: bool,
    /// `--nowmes`, `--timetags`, `--fullwmes`: the matched WMEs after `Firing`.
    pub wme_detail: WmeDetail,
    /// `-A`: assertions of rules and preferences (not printed yet).
    pub assertions: bool,
    /// `-b`: chunking's dependency analysis.
    pub backtracing: bool,
    /// `-G`: WMEs joining a goal dependency set.
    pub gds_wmes: bool,
    /// `-i`: numeric preference calculations (9.6 prints nothing for them).
    pub indifferent: bool,
    /// `-R`: reinforcement learning updates.
    pub rl: bool,
    /// `-e`: each new best episode of an episodic memory query.
    pub epmem: bool,
    /// `-s`: augmentations as semantic memory stores them.
    pub smem: bool,
    /// `-a`: working-memory activation and forgetting.
    pub wma: bool,
}

impl TraceFlags {
    /// The flags of `trace N`: those of levels 1 to N on, the other level flags off (the
    /// additional ones are left alone by [`TraceFlags::set_level`]).
    pub fn level(n: u8) -> Self {
        let mut t = TraceFlags::default();
        t.set_level(n);
        t
    }

    /// `trace N`: level 0 turns everything off, including the additional messages; other
    /// levels set the level flags only.
    pub fn set_level(&mut self, n: u8) {
        if n == 0 {
            *self = TraceFlags::default();
            return;
        }
        self.decisions = true;
        let l2 = n >= 2;
        self.phases = l2;
        self.chunk_warnings = l2;
        self.gds = l2;
        self.consistency = l2;
        let l3 = n >= 3;
        self.default_rules = l3;
        self.user_rules = l3;
        self.chunks = l3;
        self.justifications = l3;
        self.templates = l3;
        self.waterfall = l3;
        self.wmes = n >= 4;
        self.preferences = n >= 5;
    }

    /// The highest level whose flags are all on (for code that only knows levels).
    pub fn level_number(&self) -> u8 {
        if !self.decisions {
            0
        } else if !(self.phases && self.gds) {
            1
        } else if !(self.user_rules && self.default_rules && self.chunks) {
            2
        } else if !self.wmes {
            3
        } else if !self.preferences {
            4
        } else {
            5
        }
    }

    /// Are the firings of some kind of rule traced?
    pub fn any_firings(&self) -> bool {
        self.user_rules
            || self.default_rules
            || self.chunks
            || self.justifications
            || self.templates
    }

    /// Are firings and retractions of a rule with these flags traced?
    pub fn firings_of(&self, flags: &crate::production::Flags) -> bool {
        if flags.justification {
            self.justifications
        } else if flags.chunk {
            self.chunks
        } else if flags.template {
            self.templates
        } else if flags.default {
            self.default_rules
        } else {
            self.user_rules
        }
    }
}

/// What adding a production did.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Added {
    New,
    /// A rule of the same name existed and was excised first (`#*`).
    Replaced,
    /// Identical to an existing rule under another name: not added.
    Duplicate {
        of: String,
    },
    /// The network cannot test the rule as its conditions were ordered, or its matches
    /// would pass the partial-match ceiling: not added.
    Rejected {
        reason: String,
        /// What a diagnostic's label says of it.
        why: &'static str,
    },
}

/// Pending changes to the match set, as the decision cycle will consume them:
/// new matches are head-inserted (the newest is last here) and fired from the head.
#[derive(Debug, Default)]
pub struct MatchSet {
    pub assertions: Vec<(ProdId, TokId)>,
    pub retractions: Vec<(ProdId, TokId)>,
    /// The rules with a break (`production break --set`): a new match of one is noted in
    /// `break_hits`, which the decision cycle reports and which stops the run.
    pub breaks: std::collections::HashSet<ProdId>,
    pub break_hits: Vec<ProdId>,
    /// Each pending assertion's support, decided once at match time (Soar manual, chapter 2, on
    /// o-support).
    pub support: crate::decide::by_token::ByToken<bool>,
    /// The same matches as `assertions`, with their place there (a hint: a queue rebuilt
    /// without [`MatchSet::reindex`] is searched): most retracted matches have fired, and
    /// finding that out must not mean a scan of the queue. Whoever takes a match off
    /// `assertions` calls [`MatchSet::taken`].
    pending: crate::decide::by_token::ByToken<u32>,
    /// How many entries of `assertions` are [`MatchSet::GONE`].
    gone: usize,
}

impl MatchSet {
    /// What a match that went before it fired leaves in `assertions`: taking it out at once
    /// would shift the rest of the queue, and an input phase that changes a pose cancels
    /// hundreds of matches it made a moment before (see `io.rs` on the order of input changes). Readers skip it.
    pub const GONE: (ProdId, TokId) = (ProdId(u32::MAX), TokId::NONE);

    /// Whether a match is queued (not yet fired, not gone).
    pub fn has_assertions(&self) -> bool {
        self.assertions.len() > self.gone
    }

    /// The queue without its gone entries.
    pub fn compact(&mut self) {
        if self.gone > 0 {
            self.assertions.retain(|&x| x != Self::GONE);
            self.gone = 0;
            self.reindex();
        }
    }

    /// Records each queued match's place, after the queue was rebuilt.
    pub fn reindex(&mut self) {
        for (i, &k) in self.assertions.iter().enumerate() {
            if k != Self::GONE {
                self.pending.insert(k, i as u32);
            }
        }
    }

    /// A match left the queue (it fired or was taken over).
    pub fn taken(&mut self, p: ProdId, t: TokId) {
        self.pending.remove(&(p, t));
    }

    /// Empties the queue and the retractions (`init-soar`).
    pub fn clear(&mut self) {
        self.assertions.clear();
        self.gone = 0;
        self.retractions.clear();
        self.support.clear();
        self.pending.clear();
    }
}

impl MatchSink for MatchSet {
    fn matched(&mut self, p: ProdId, t: TokId) {
        if !self.breaks.is_empty() && self.breaks.contains(&p) {
            self.break_hits.push(p);
        }
        self.pending.insert((p, t), self.assertions.len() as u32);
        self.assertions.push((p, t));
    }
    fn retraction_count(&self) -> usize {
        self.retractions.len()
    }
    fn unmatched(&mut self, p: ProdId, t: TokId) {
        // A match that goes before it fired simply leaves the queue.
        let place = self.pending.remove(&(p, t)).and_then(|i| {
            let i = i as usize;
            if self.assertions.get(i) == Some(&(p, t)) {
                Some(i)
            } else {
                self.assertions.iter().rposition(|x| *x == (p, t))
            }
        });
        if let Some(i) = place {
            self.assertions[i] = Self::GONE;
            self.gone += 1;
            self.support.remove(&(p, t));
            if self.gone > 64 && self.gone * 2 > self.assertions.len() {
                self.compact();
            }
        } else {
            self.retractions.push((p, t));
        }
    }
}

/// A loaded rule: its compiled form and its place in the network.
#[derive(Debug, Clone)]
pub struct Loaded {
    /// Shared so that a firing holds its rule without copying it.
    pub production: std::sync::Arc<Production>,
    pub id: ProdId,
}

/// A rule as the key of the rules by name: its own name, not a copy of it.
#[derive(Debug, Clone)]
struct ByName(std::sync::Arc<Production>);

impl std::hash::Hash for ByName {
    fn hash<H: std::hash::Hasher>(&self, h: &mut H) {
        // As a `str` hashes, so that lookups by `&str` find it.
        self.0.name.as_str().hash(h);
    }
}

impl PartialEq for ByName {
    fn eq(&self, other: &Self) -> bool {
        self.0.name == other.0.name
    }
}

impl Eq for ByName {}

impl std::borrow::Borrow<str> for ByName {
    fn borrow(&self) -> &str {
        &self.0.name
    }
}

/// The identifiers of the top state and its io link.
#[derive(Debug, Clone, Copy)]
pub struct TopState {
    pub state: Sym,
    pub io: Sym,
    pub input_link: Sym,
    pub output_link: Sym,
    /// The `operator` attribute (a predefined symbol), looked up once.
    pub operator: Sym,
}

/// A program's hook at the input or output phase.
pub type PhaseCallback = Box<dyn FnMut(&mut AgentCore)>;

pub struct AgentCore {
    pub name: String,
    pub symbols: Symbols,
    pub wm: WorkingMemory,
    pub rete: Rete,
    pub matches: MatchSet,
    productions: IndexMap<ByName, Loaded, rustc_hash::FxBuildHasher>,
    /// The same rules by network id, for firing without a lookup by name.
    by_id: Vec<Option<std::sync::Arc<Production>>>,
    pub settings: Settings,
    /// The seed given to `srand`, if any.
    pub seed: Option<u32>,
    pub top: TopState,
    /// The decision cycle's memory: instantiations, preferences, slots, goals, counters.
    pub decider: crate::decide::state::DecideState,
    /// Soar's random numbers (`srand`, exploration, `rand-int`).
    pub rng: crate::rng::Mt19937,
    /// Trace and `write` output not yet taken by the front end.
    pub output: String,
    /// Whether the print stream stood at the start of a line when `output` was last taken
    /// (9.6 starts some trace lines on a fresh line only).
    pub output_line_start: bool,
    /// The default trace listener: writes the trace events as 9.6's text into `output`.
    /// Set from outside (Ctrl-C) to stop a run within its current elaboration cycle.
    pub(crate) interrupt: Option<std::sync::Arc<std::sync::atomic::AtomicBool>>,
    pub(crate) trace_text: crate::trace_text::TraceText96,
    /// While set, `<=WM:` trace lines are collected here and printed in 9.6's order at the
    /// end of the working-memory phase.
    pub(crate) removed_wmes: Option<Vec<crate::wm::Wme>>,
    /// `wm watch`: which `=>WM:` and `<=WM:` lines the trace shows.
    pub(crate) wme_filters: crate::wme_filters::WmeFilters,
    /// The `<=WM:` lines of substates an operator removal takes away in this phase, each
    /// with its place in 9.6's listing (see `trace_removed_wmes`).
    pub(crate) substate_removals: Vec<(crate::decide::state::SubstateLine, crate::wm::Wme)>,
    /// Whether those substates went for their GDS (9.6 lists them in another order).
    pub(crate) substates_by_gds: bool,
    /// For a GDS removal: the timetag of the WME whose removal took the substates, and
    /// the slots of the preferences the substates' firings made, in the order 9.6 removes
    /// those preferences (see `trace_removed_wmes`).
    pub(crate) gds_trigger: Option<u64>,
    pub(crate) substate_slot_order: Vec<(Sym, Sym)>,
    /// Rust functions the embedding program registered for `exec`.
    pub rhs_registry: crate::rhs::Registry,
    /// Called at the input phase of every decision (the environment's hook).
    pub input_callback: Option<PhaseCallback>,
    /// The program's input WMEs and the input-link changes waiting for the next input
    /// phase (`io.rs`).
    pub(crate) inputs: crate::inputs::InputTable,
    /// `save percepts`: the input being recorded.
    pub(crate) capture: Option<crate::percepts::Capture>,
    /// `load percepts`: the recorded input being replayed.
    pub(crate) replay: Option<crate::percepts::Replay>,
    /// Called at the output phase of every decision.
    pub output_callback: Option<PhaseCallback>,
    /// Chunking's state and counters.
    pub learn: crate::learn::LearnState,
    /// Reinforcement learning's parameters, RL rules and per-state data.
    pub rl: crate::rl::RlState,
    /// Semantic memory: its store, settings and working-memory interface.
    pub smem: crate::smem::Smem,
    /// Episodic memory: its store, settings and working-memory interface.
    pub epmem: crate::epmem::Epmem,
    /// Working-memory activation: its settings, decay histories and forgetting.
    pub wma: crate::wma::Wma,
    /// The program's event listeners.
    pub(crate) events: crate::events::EventListeners,
    /// `multi-attributes`: what the reorderer expects of declared attributes.
    pub(crate) multi_attributes: crate::rete::reorder::MultiAttributes,
    /// Rules whose firings are traced whatever the trace settings (`production watch`).
    pub(crate) watched_rules: std::collections::HashSet<String>,
    /// `production break`: the rules with a break, in the order they were set, each with
    /// its count of match-time interrupts (1 when set; 9.6 prints it with each interrupt).
    pub(crate) break_rules: IndexMap<String, u64>,
}

impl AgentCore {
    pub fn new(name: impl Into<String>) -> Self {
        let mut symbols = Symbols::new();
        let mut wm = WorkingMemory::new();
        let mut rete = Rete::new();
        let mut matches = MatchSet::default();
        let top = create_top_state(&mut symbols, &mut wm, &mut rete, &mut matches, None);
        AgentCore {
            name: name.into(),
            symbols,
            wm,
            rete,
            matches,
            productions: IndexMap::default(),
            by_id: Vec::new(),
            settings: Settings::default(),
            seed: None,
            top,
            decider: crate::decide::state::DecideState::new(),
            rng: crate::rng::Mt19937::default(),
            output: String::new(),
            output_line_start: false,
            interrupt: None,
            trace_text: crate::trace_text::TraceText96,
            removed_wmes: None,
            wme_filters: Default::default(),
            substate_removals: Vec::new(),
            substates_by_gds: false,
            gds_trigger: None,
            substate_slot_order: Vec::new(),
            rhs_registry: crate::rhs::Registry::new(),
            input_callback: None,
            inputs: crate::inputs::InputTable::default(),
            capture: None,
            replay: None,
            output_callback: None,
            learn: crate::learn::LearnState::default(),
            rl: crate::rl::RlState::default(),
            smem: crate::smem::Smem::default(),
            epmem: crate::epmem::Epmem::default(),
            wma: crate::wma::Wma::default(),
            events: crate::events::EventListeners::default(),
            multi_attributes: Default::default(),
            watched_rules: Default::default(),
            break_rules: Default::default(),
        }
    }

    /// Room for `items` more in the store `stats --memory` names `pool` (`debug
    /// allocate`), or the allocator's refusal; `None` for a store that grows a block at a
    /// time (the symbol table) or for no store of that name.
    pub(crate) fn reserve_pool(
        &mut self,
        pool: &str,
        items: usize,
    ) -> Option<Result<(), std::collections::TryReserveError>> {
        match pool {
            "instantiation" => Some(self.decider.insts.try_reserve(items)),
            "preference" => Some(self.decider.prefs.try_reserve(items)),
            _ => self
                .wm
                .reserve_pool(pool, items)
                .or_else(|| self.rete.reserve_pool(pool, items)),
        }
    }

    /// Adds a rule: a same-named rule is excised first; an identical body is ignored. The
    /// rule's matches against working memory are queued at once.
    pub fn add_production(&mut self, p: Production) -> Added {
        let by_value = !self.rl.params.chunk_stop;
        self.add_production_by_value(p, by_value)
    }

    /// [`AgentCore::add_production`]; with `by_value`, an RL rule whose value differs from
    /// its twin's is not a duplicate (`rl --set chunk-stop off`, observed on 9.6: the twin's
    /// value is the one it has learned so far).
    pub fn add_production_by_value(&mut self, mut p: Production, by_value: bool) -> Added {
        // 9.6 creates a rule's constants as it parses it, then reorders its conditions
        // (`production_reorder.cpp` in the official kernel); the network joins them in that order and `print` shows it.
        crate::rete::reorder::intern_in_text_order(&mut p, &mut self.symbols);
        let conds = p.take_conditions();
        // A learned rule's actions come in its results' order, as 9.6 makes them.
        if !(p.flags.chunk || p.flags.justification) {
            crate::rete::reorder::reorder_actions(&conds, &mut p.actions);
        }
        let mut conds =
            crate::rete::reorder::reorder_owned(conds, &self.symbols, &self.multi_attributes);
        if p.flags.chunk || p.flags.justification {
            crate::rete::reorder::equality_first(&mut conds);
        }
        self.rete.share_var_names(&mut conds);
        self.rete.share_action_var_names(&mut p.actions);
        // Kept for the rule's lifetime: no spare room (100,000 rules, 10 % less memory).
        conds.shrink_to_fit();
        p.conditions = conds.into();
        let replaced = self.excise(&p.name);
        let value = p.rl_value().filter(|_| by_value);
        let by_id = &self.by_id;
        let apart = |twin: ProdId| {
            value.is_some_and(|v| {
                by_id
                    .get(twin.0 as usize)
                    .and_then(|t| t.as_ref())
                    .and_then(|t| t.rl_value())
                    .is_some_and(|w| w != v)
            })
        };
        self.rete.token_budget = usize::try_from(self.settings.limits.tokens).unwrap_or(usize::MAX);
        let rule_of = |id: ProdId| by_id.get(id.0 as usize).and_then(|t| t.as_deref());
        let added =
            self.rete
                .add_production(&p, &mut self.symbols, &mut self.matches, &rule_of, &apart);
        self.rete.token_budget = 0;
        let id = match added {
            Ok(id) => id,
            Err(crate::rete::BuildError::Duplicate(of)) => {
                return Added::Duplicate {
                    of: self.production_name(of).to_string(),
                };
            }
            Err(crate::rete::BuildError::NoConditions(_)) => {
                return Added::Duplicate { of: String::new() };
            }
            Err(e @ crate::rete::BuildError::UnboundInNegation(_)) => {
                return Added::Rejected {
                    reason: e.to_string(),
                    why: "its conditions are not all connected",
                };
            }
            Err(e @ crate::rete::BuildError::MatchCeiling(_)) => {
                return Added::Rejected {
                    reason: format!("Rule {} not added: {e}", p.name),
                    why: "a ceiling on the matcher refuses it",
                };
            }
        };
        let production = std::sync::Arc::new(p);
        let slot = id.0 as usize;
        if self.by_id.len() <= slot {
            self.by_id.resize(slot + 1, None);
        }
        self.by_id[slot] = Some(production.clone());
        self.rl.rule_added(id, &production);
        self.productions
            .insert(ByName(production.clone()), Loaded { production, id });
        // 9.6's matcher queues the new rule's matches as it builds the rule.
        self.trace_queued_matches_now();
        if replaced {
            Added::Replaced
        } else {
            Added::New
        }
    }

    pub fn excise(&mut self, name: &str) -> bool {
        match self.productions.shift_remove(name) {
            Some(l) => {
                self.watched_rules.remove(name);
                self.break_rules.shift_remove(name);
                self.matches.breaks.remove(&l.id);
                self.by_id[l.id.0 as usize] = None;
                self.rl.rule_excised(l.id);
                self.rete.excise(l.id, &self.symbols, &mut self.matches);
                true
            }
            None => false,
        }
    }

    /// Whether an identifier is still in working memory: a goal, or an object with WMEs
    /// or one a WME links to. One that garbage collection took is gone, as 9.6 frees it.
    pub(crate) fn id_in_memory(&self, id: Sym) -> bool {
        self.symbols.is_goal(id) || self.wm.has_wmes(id) || !self.wm.parent_wmes(id).is_empty()
    }

    /// The identifier a name such as `S1` names, if it is still in working memory.
    pub(crate) fn live_id(&self, name: &str) -> Option<Sym> {
        self.symbols.find_id(name).filter(|&id| self.id_in_memory(id))
    }

    /// Takes the live justifications out of the rules' listing (`excise --all`), their
    /// instantiations left as they are; returns how many there were.
    pub fn excise_justifications(&mut self) -> usize {
        let n = self.learn.justifications.len();
        self.learn.justifications.clear();
        n
    }

    pub fn excise_all(&mut self) -> usize {
        let names: Vec<String> = self.productions.keys().map(|k| k.0.name.to_string()).collect();
        for n in &names {
            self.excise(n);
        }
        names.len()
    }

    /// Changes a loaded rule where it is (an RL rule's learned value, at every update): the
    /// same name, network node and place in the listings. The rule's two other handles are
    /// set aside while `edit` runs, so that the rule is changed in place rather than copied
    /// (a copy is made only while something else, a listing say, still holds the rule).
    /// Returns whether the rule is loaded.
    pub(crate) fn edit_production(&mut self, id: ProdId, edit: impl FnOnce(&mut Production)) -> bool {
        use indexmap::map::MutableKeys;
        use std::sync::{Arc, LazyLock};
        /// What stands in the rule's other places while it changes.
        static SET_ASIDE: LazyLock<Arc<Production>> = LazyLock::new(|| {
            Arc::new(Production {
                name: arcstr::ArcStr::new(),
                doc: None,
                flags: crate::production::Flags::default(),
                conditions: Arc::new([]),
                actions: Box::new([]),
                span: crate::source::Span::default(),
            })
        });
        let Some(Some(mut rule)) = self.by_id.get_mut(id.0 as usize).map(Option::take) else {
            return false;
        };
        let index = self.productions.get_index_of(rule.name.as_str());
        if let Some((key, loaded)) = index.and_then(|i| self.productions.get_index_mut2(i)) {
            key.0 = SET_ASIDE.clone();
            loaded.production = SET_ASIDE.clone();
        }
        edit(Arc::make_mut(&mut rule));
        if let Some((key, loaded)) = index.and_then(|i| self.productions.get_index_mut2(i)) {
            key.0 = rule.clone();
            loaded.production = rule.clone();
        }
        self.by_id[id.0 as usize] = Some(rule);
        true
    }

    pub fn production(&self, name: &str) -> Option<&Production> {
        self.productions.get(name).map(|l| &*l.production)
    }

    /// A rule, shared (for firing it while the agent changes).
    pub fn production_arc(&self, name: &str) -> Option<std::sync::Arc<Production>> {
        self.productions.get(name).map(|l| l.production.clone())
    }

    /// A rule by its network id, shared.
    pub fn production_by_id(&self, id: ProdId) -> Option<std::sync::Arc<Production>> {
        self.by_id.get(id.0 as usize).and_then(|p| p.clone())
    }

    pub fn loaded(&self, name: &str) -> Option<&Loaded> {
        self.productions.get(name)
    }

    /// Rules in load order.
    pub fn productions(&self) -> impl DoubleEndedIterator<Item = &Production> {
        self.productions.values().map(|l| &*l.production)
    }

    /// Reserves room for `rules` more rules in the tables that grow with them (see
    /// `commands/load_forecast.rs`).
    pub(crate) fn reserve_for_rules(&mut self, rules: usize) {
        self.rete.reserve_for_rules(rules);
        // Too large a forecast to reserve: the tables grow as they go.
        let _ = self.productions.try_reserve(rules);
        let _ = self.by_id.try_reserve(rules);
    }

    pub fn production_count(&self) -> usize {
        self.productions.len()
    }

    /// The name of a production in the network.
    pub fn production_name(&self, id: ProdId) -> &str {
        self.by_id
            .get(id.0 as usize)
            .and_then(Option::as_ref)
            .map_or("?", |p| p.name.as_str())
    }

    /// Registers a Rust function callable from rules as `(exec name args...)` or `(name
    /// args...)`: it receives the agent's name and the arguments joined with no separator,
    /// and returns the string the rule gets (SML's `exec`).
    pub fn register_rhs_function(
        &mut self,
        name: &str,
        f: impl FnMut(&str, &str) -> String + 'static,
    ) {
        self.rhs_registry.register(name, Box::new(f));
    }

    /// Gives the function registered as `name` a numeric form (see
    /// [`crate::rhs::Registry::register_numeric`]); false when `name` is not registered.
    pub fn register_rhs_numeric(
        &mut self,
        name: &str,
        f: impl FnMut(&[f64]) -> Option<String> + 'static,
    ) -> bool {
        self.rhs_registry.register_numeric(name, Box::new(f))
    }

    /// Seeds the agent's random numbers, as `srand N` does.
    pub fn seed_rng(&mut self, seed: u32) {
        self.seed = Some(seed);
        self.rng.seed(seed);
    }

    /// Adds a WME now (as `wm add` and the input phase do) and matches it.
    pub fn add_wme(&mut self, id: Sym, attr: Sym, value: Sym, acceptable: bool) -> WmeId {
        let links = self.symbols.is_id(value);
        let w = self.wm.add_typed(id, attr, value, acceptable, links);
        self.match_wme_now(w, (id, attr, value), acceptable);
        w
    }

    /// The value of `id ^attr` (the first such WME): how the memories find their links.
    pub(crate) fn child_of(&self, id: Sym, attr: &str) -> Option<Sym> {
        let a = self.symbols.find_str(attr)?;
        self.wm
            .of_id(id)
            .filter_map(|w| self.wm.get(w))
            .find(|w| w.attr == a)
            .map(|w| w.value)
    }

    /// A WME of `id` whose value is `value` (the first found).
    pub(crate) fn wme_linking(&self, id: Sym, value: Sym) -> Option<WmeId> {
        self.wm
            .of_id(id)
            .find(|&w| self.wm.get(w).is_some_and(|x| x.value == value && !x.acceptable))
    }

    /// Matches a WME in the network and against the justifications' negations, which
    /// retract in 9.6's place among the rules' retractions (see `justification_wme_added`).
    pub(crate) fn match_wme_now(&mut self, w: WmeId, fields: (Sym, Sym, Sym), acceptable: bool) {
        self.rete.mark_alphas = self.watches_justification_negations();
        self.rete
            .add_wme(w, fields, acceptable, &self.symbols, &mut self.matches);
        self.trace_queued_matches_now();
        self.justification_wme_added(w);
        if self.events.any() {
            if let Some(wme) = self.wm.get(w).copied() {
                self.events
                    .send(&crate::events::AgentEvent::WmeAdded(wme));
            }
        }
    }

    /// Tells the listeners that rule `p` fired (or, with `retracted`, that it retracted).
    pub(crate) fn send_rule_event(&mut self, p: ProdId, retracted: bool) {
        if !self.events.any() {
            return;
        }
        let mut events = std::mem::take(&mut self.events);
        let rule = self.production_name(p);
        events.send(&if retracted {
            crate::events::AgentEvent::Retracted { rule }
        } else {
            crate::events::AgentEvent::Fired { rule }
        });
        self.events = events;
    }

    /// Matches a WME already in working memory (a buffered addition reaching the matcher).
    pub(crate) fn match_new_wme(&mut self, w: WmeId, wme: &Wme) {
        self.match_wme_now(w, (wme.id, wme.attr, wme.value), wme.acceptable);
    }

    pub fn remove_wme(&mut self, w: WmeId) -> Option<Wme> {
        let timetag = self.wm.get(w)?.timetag;
        self.unmatch_wme(w, timetag);
        self.remove_wme_leaving_matcher(w)
    }

    /// Takes a WME out of the matcher, after [`Self::remove_wme_leaving_matcher`] took it
    /// out of working memory (or as part of [`Self::remove_wme`]): its matches retract.
    pub(crate) fn unmatch_wme(&mut self, w: WmeId, timetag: u64) {
        let rule_retractions = self.matches.retractions.len();
        self.rete.remove_wme(w, &self.symbols, &mut self.matches);
        self.trace_queued_matches_now();
        self.justification_wme_removed(w, timetag, rule_retractions);
    }

    /// Takes a WME out of working memory but leaves it in the matcher, for a caller that
    /// calls [`Self::unmatch_wme`] for it before anything is added: 9.6 hands a phase's
    /// removals to its matcher in an order of their own (see `wm_phase.rs`).
    pub(crate) fn remove_wme_leaving_matcher(&mut self, w: WmeId) -> Option<Wme> {
        let wme = self.wm.remove(w)?;
        if self.wma.on() {
            self.wma_wme_removed(&wme);
            // (A working-memory phase lets its removals go at its end: `trace_removed_wmes`.)
            if self.removed_wmes.is_none() {
                let next = self.wm.next_timetag();
                self.wma.address_freed(wme.timetag, next);
            }
        }
        if self.events.any() {
            self.events
                .send(&crate::events::AgentEvent::WmeRemoved(wme));
        }
        // Most removals happen with no substate, so with an empty GDS: no hash probe then.
        if !self.decider.gds.is_empty() {
            if let Some(goal) = self.decider.gds.remove(&w).map(|m| m.goal) {
                self.leave_gds(goal);
                if self.gds_watches_removal(&wme) {
                    self.decider.gds_invalid.push(goal);
                }
            }
        }
        if !self.decider.gds_orphans.is_empty() {
            self.decider.gds_orphans.remove(&w);
        }
        // What it pointed at may now be unlinked: garbage collection looks there. A WME
        // is no link to a goal, which only its own removal unlinks (as in 9.6).
        if self.symbols.id_data(wme.value).is_some_and(|d| !d.is_goal) {
            self.decider.gc_candidates.push(wme.value);
        }
        Some(wme)
    }
}

/// Creates the top state as Soar does: `I1`–`I3` first, then `S1` and its WMEs
/// with timetags 1–13 in Soar's order. After `init-soar` (`old` is the top state before it),
/// the io link's identifiers are the same symbols, numbered again, so that a program's
/// handles on them stay valid.
pub(crate) fn create_top_state(
    symbols: &mut Symbols,
    wm: &mut WorkingMemory,
    rete: &mut Rete,
    sink: &mut MatchSet,
    old: Option<TopState>,
) -> TopState {
    let [io, input_link, output_link] = match old {
        Some(old) => [old.io, old.input_link, old.output_link].map(|id| {
            symbols.renumber_id(id);
            id
        }),
        None => [(); 3].map(|()| symbols.new_id('I', 1)),
    };
    let state = symbols.new_id('S', 1);
    if let Some(d) = symbols.id_data_mut(state) {
        d.is_goal = true;
    }
    let reward = symbols.new_id('R', 1);
    let epmem = symbols.new_id('E', 1);
    let ep_cmd = symbols.new_id('C', 1);
    let ep_res = symbols.new_id('R', 1);
    let smem = symbols.new_id('L', 1);
    let sm_cmd = symbols.new_id('C', 1);
    let sm_res = symbols.new_id('R', 1);
    let one = symbols.int(1);
    let s = |symbols: &mut Symbols, x: &str| symbols.str(x);
    let triples = [
        (state, s(symbols, "type"), s(symbols, "state")),
        (state, s(symbols, "superstate"), s(symbols, "nil")),
        (state, s(symbols, "reward-link"), reward),
        (state, s(symbols, "epmem"), epmem),
        (epmem, s(symbols, "command"), ep_cmd),
        (epmem, s(symbols, "result"), ep_res),
        (epmem, s(symbols, "present-id"), one),
        (state, s(symbols, "smem"), smem),
        (smem, s(symbols, "command"), sm_cmd),
        (smem, s(symbols, "result"), sm_res),
        (state, s(symbols, "io"), io),
        (io, s(symbols, "input-link"), input_link),
        (io, s(symbols, "output-link"), output_link),
    ];
    let added: Vec<(WmeId, (Sym, Sym, Sym))> = triples
        .into_iter()
        .map(|t| (wm.add(t.0, t.1, t.2, false), t))
        .collect();
    // The matcher takes them as 9.6 buffers them: the state's WMEs, then the io link's,
    // each group newest first (9.6's `=>WM:` lines show that order).
    let (state_wmes, io_wmes) = added.split_at(added.len() - 3);
    for &(w, t) in state_wmes.iter().rev().chain(io_wmes.iter().rev()) {
        rete.add_wme(w, t, false, symbols, sink);
    }
    TopState {
        state,
        io,
        input_link,
        output_link,
        operator: symbols.str("operator"),
    }
}
