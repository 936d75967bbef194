//! Semantic memory (Soar manual, ch. 6, "Semantic Memory"): a long-term store of
//! identifiers (LTIs, written `@N`) and their augmentations, kept in SQLite with 9.6.5's
//! schema. This module owns the store and what the `smem` command and the working-memory
//! interface (`wmi.rs`) do with it: adding and removing knowledge, cue-based queries with
//! the activation that breaks their ties, and printing.

mod memo;
pub mod params;
mod print;
pub mod query;
mod schema;
pub mod spread;
pub mod store;
pub mod text;
pub mod wmi;

use crate::memory_timers::{MemoryTimers, Running, Timer};
use params::{Mode, SmemParams, UpdatePolicy};
use store::{DbResult, Store, Val};
use text::{Clause, Item, Node};

/// The counts of `smem --stats`.
#[derive(Debug, Clone, Copy, Default)]
pub struct SmemStats {
    pub retrieves: u64,
    pub queries: u64,
    pub stores: u64,
    pub act_updates: u64,
}

/// The semantic memory of one agent.
#[derive(Debug, Default)]
pub struct Smem {
    pub params: SmemParams,
    pub enabled: bool,
    /// The database, opened at its first use.
    store: Option<Store>,
    pub stats: SmemStats,
    /// `smem --timers`: the time spent in each part ([`timer`]).
    pub timers: MemoryTimers,
    /// Whether `print @` writes floats with sixteen decimals: 9.6's number stream turns
    /// to fixed notation once it has written an activation, and stays so.
    print_fixed: bool,
    /// The working-memory interface's record of each state's commands and results.
    pub(crate) links: wmi::Links,
    /// Spreading activation's record of its sources.
    spread: spread::Spread,
    /// The LTIs with an instance in working memory (the sources of spreading), as the
    /// caller of a query last gave them.
    pub context: std::collections::BTreeSet<i64>,
}

/// Semantic memory's timers and their levels (9.6's names; the spreading timers 9.6.5
/// lists time nothing in rusoar, which spreads within the query).
pub mod timer {
    use crate::memory_timers::Timer;
    /// The processing of the working-memory commands at a phase.
    pub const TOTAL: Timer = ("_total", 1);
    /// Reading the commands of `^smem.command`.
    pub const API: Timer = ("smem_api", 2);
    /// Opening the database.
    pub const INIT: Timer = ("smem_init", 2);
    /// Putting a retrieved LTI's augmentations in working memory.
    pub const NCB_RETRIEVAL: Timer = ("smem_ncb_retrieval", 2);
    /// Queries.
    pub const QUERY: Timer = ("smem_query", 2);
    /// Stores, and `smem --add`.
    pub const STORAGE: Timer = ("smem_storage", 2);
    /// Activation updates.
    pub const ACTIVATION: Timer = ("three_activation", 3);
}

impl Smem {
    /// Starts `timer` if the `timers` setting reaches its level.
    pub fn timer_start(&self, timer: Timer) -> Running {
        MemoryTimers::start(timer, self.timers_level())
    }

    /// The `timers` setting as a level (0 for `off`).
    pub fn timers_level(&self) -> u8 {
        self.params.timers()
    }

    /// Whether the database is open (its store settings are then fixed).
    pub fn is_open(&self) -> bool {
        self.store.is_some()
    }

    /// Whether long-term identifier `@lti` exists (the store is opened if semantic memory
    /// is on; a memory never opened holds none).
    pub fn lti_exists(&mut self, lti: i64) -> bool {
        if !self.enabled && !self.is_open() {
            return false;
        }
        self.store()
            .and_then(|s| s.lti_exists(lti))
            .unwrap_or(false)
    }

    /// Writes what lazy-commit holds back to the file, if the store is open.
    pub fn commit(&mut self) -> DbResult<()> {
        let lazy = self.params.lazy_commit();
        match self.store.as_mut() {
            Some(s) => s.commit(lazy),
            None => Ok(()),
        }
    }

    /// The store, opened on first use.
    pub fn store(&mut self) -> DbResult<&mut Store> {
        if self.store.is_none() {
            let t = self.timer_start(timer::INIT);
            let opened = Store::open(&self.params);
            self.timers.stop(t);
            self.store = Some(opened?);
        }
        match self.store.as_mut() {
            Some(s) => Ok(s),
            None => Err("smem: the database is not open".into()),
        }
    }

    /// `smem --add`: stores the clauses, merging with the LTIs named `@N`. Variables get
    /// new LTIs in the order their clauses come (a variable seen only as a value, after
    /// them). Returns 9.6's printed text: an `@` per clause and, with `trace` (`trace
    /// --smem`), a line for each augmentation.
    pub fn add(&mut self, clauses: &[Clause], trace: bool) -> DbResult<String> {
        let t = self.timer_start(timer::STORAGE);
        let done = self.add_untimed(clauses, trace);
        self.timers.stop(t);
        done
    }

    fn add_untimed(&mut self, clauses: &[Clause], trace: bool) -> DbResult<String> {
        let store = self.store()?;
        let mut vars: Vec<(String, i64)> = Vec::new();
        let mut order: Vec<&Node> = clauses.iter().map(|c| &c.id).collect();
        for c in clauses {
            for (_, values) in &c.augs {
                order.extend(values.iter().filter_map(|v| match v {
                    Item::Node(n) => Some(n),
                    Item::Const(_) => None,
                }));
            }
        }
        for n in order {
            match n {
                Node::Var(v) if !vars.iter().any(|(name, _)| name == v) => {
                    let id = store.new_lti()?;
                    vars.push((v.clone(), id));
                }
                Node::Lti(id) => store.make_lti(*id)?,
                Node::Var(_) => {}
            }
        }
        let lti_of = |n: &Node| match n {
            Node::Lti(id) => *id,
            Node::Var(v) => vars
                .iter()
                .find(|(name, _)| name == v)
                .map_or(0, |(_, id)| *id),
        };
        let mut marks = String::new();
        for c in clauses {
            let id = lti_of(&c.id);
            marks.push('@');
            for (attr, values) in &c.augs {
                for v in values {
                    let value = match v {
                        Item::Const(k) => k.clone(),
                        Item::Node(n) => Val::Lti(lti_of(n)),
                    };
                    // 9.6 traces an augmentation the LTI already has too.
                    if trace {
                        marks.push_str(&print::trace_addition(id, attr, &value));
                    }
                    store.add_aug(id, attr, &value)?;
                }
            }
        }
        let lazy = self.params.lazy_commit();
        self.store()?.commit(lazy)?;
        Ok(marks)
    }

    /// Activates an LTI by the activation mode (Soar manual, Semantic Memory,
    /// "Retrieval") at the time of semantic memory's own clock, which counts activations
    /// (9.6's `smem_max_cycle`, kept in the store; a decision without one does not advance
    /// it): recency takes the time, frequency the count of activations, base-level the
    /// log-odds of Σ (now − t + 1)^−d over the last ten (`base_level`), to which an LTI
    /// that has spread adds it (`spread.rs`).
    pub fn activate(&mut self, lti: i64) -> DbResult<()> {
        let t = self.timer_start(timer::ACTIVATION);
        let done = self.touch(lti, true);
        self.timers.stop(t);
        done
    }

    /// 9.6's activation of an LTI (`lti_activate`): with `add_access` an access at the
    /// clock's time, which then advances; without, the activation recomputed at the
    /// clock's time, no access added (what a `^store` does: observed on soar-sml 9.6.5, a
    /// stored LTI counts an activation update but no access). An activation with nothing
    /// to go on (no access yet) is taken as one access when the agent began: ln(f) for
    /// f = x / (1 + x), x = clock^−d.
    fn touch(&mut self, lti: i64, add_access: bool) -> DbResult<()> {
        let mode = self.params.mode();
        let decay = self.params.base_decay();
        let inhibition = self.params.inhibition();
        let autocommit = !self.params.lazy_commit() && self.params.in_file();
        let spreading = self.params.spreading();
        let settings = spread::Settings::of(&self.params);
        let store = self.store()?;
        let clock = store.var(schema::var::MAX_CYCLE)?.max(1);
        let mut record = store.record(lti)?;
        // `at` is the time the base-level sum is taken at, less one.
        let (now, at) = if add_access {
            store.set_var(schema::var::MAX_CYCLE, clock + 1)?;
            if mode == Mode::BaseLevel && self.params.update_policy() == UpdatePolicy::Incremental {
                self.touch_incremental(clock)?;
            }
            record.total += 1.0;
            record.last = clock;
            if record.first == 0 {
                record.first = clock;
            }
            record.history.insert(0, clock);
            record.history.truncate(10);
            (clock, clock)
        } else {
            (clock, clock - 1)
        };
        let value = match mode {
            Mode::Recency => now as f64,
            Mode::Frequency => record.total,
            Mode::BaseLevel => base_level(&record.history, at, decay, inhibition),
        };
        let store = self.store()?;
        let unused = settings.unused_odds(store.var(schema::var::MAX_CYCLE)?).ln();
        let base = if value == schema::ACT_LOW || value == 0.0 {
            unused
        } else {
            value
        };
        // An LTI that has spread keeps its activation with it: the new base-level plus the
        // spread it has (9.6's `lti_activate`).
        let with_spread = if spreading { store.spread_row(lti)? } else { None };
        if let Some((_, spread, _)) = with_spread {
            let offset = settings.offset();
            let modified = if spread == 0.0 || spread < offset {
                0.0
            } else {
                spread.ln() - offset.ln()
            };
            store.write_access(lti, record)?;
            store.write_spread_activation(lti, value, spread, base + modified)?;
        } else {
            store.write_activation(lti, record, value, base)?;
        }
        // Without lazy-commit a file has each change as soon as it is made, as with 9.6;
        // the store otherwise holds part of an activation back until the next commit.
        if autocommit {
            store.commit(false)?;
        }
        self.stats.act_updates += 1;
        Ok(())
    }

    /// The incremental update policy, at an access at `time`: each LTI last activated a
    /// threshold's age before has its activation computed again (9.6's `lti_activate`).
    fn touch_incremental(&mut self, time: i64) -> DbResult<()> {
        for age in self.params.incremental_threshes() {
            if age > 0 && time - age > 0 {
                for lti in self.store()?.ltis_last_activated_at(time - age)? {
                    self.touch(lti, false)?;
                }
            }
        }
        Ok(())
    }

    /// The naive update policy, before a query's walk: the activation of each LTI the walk
    /// may visit is computed again, in the order of their numbers.
    pub(crate) fn touch_all(&mut self, ltis: &[i64]) -> DbResult<()> {
        for &lti in ltis {
            self.touch(lti, false)?;
        }
        Ok(())
    }

    /// A `^store`'s activation of the stored LTI (no access added).
    pub fn activate_stored(&mut self, lti: i64) -> DbResult<()> {
        self.touch(lti, false)
    }

    /// `print @N`: one LTI (`None` when it does not exist).
    pub fn print_lti(&mut self, lti: i64) -> DbResult<Option<String>> {
        let spreading = self.params.spreading();
        let mut fixed = self.print_fixed;
        let store = self.store()?;
        if !store.lti_exists(lti)? {
            return Ok(None);
        }
        let text = print::lti(store, lti, spreading, &mut fixed)?;
        self.print_fixed = fixed;
        Ok(Some(text))
    }

    /// `print @`: every LTI.
    pub fn print_all(&mut self) -> DbResult<String> {
        let spreading = self.params.spreading();
        let mut fixed = self.print_fixed;
        let store = self.store()?;
        let mut s = String::new();
        for lti in store.ltis()? {
            s.push_str(&print::lti(store, lti, spreading, &mut fixed)?);
        }
        self.print_fixed = fixed;
        Ok(s)
    }

    /// `smem --export`: the store (or one LTI) as an `smem --add` command.
    pub fn export(&mut self, only: Option<i64>) -> DbResult<String> {
        let store = self.store()?;
        let ltis = match only {
            Some(l) => vec![l],
            None => store.ltis()?,
        };
        let mut s = String::from("smem --add {\n");
        for lti in ltis {
            s.push_str(&print::export_clause(store, lti)?);
        }
        s.push_str("}\n");
        Ok(s)
    }

    /// `smem --remove`: augmentations by attribute (and value), or all of an LTI's.
    /// Fails on an LTI that does not exist.
    pub fn remove(&mut self, clauses: &[Clause]) -> Result<String, String> {
        let store = self.store()?;
        for c in clauses {
            let Node::Lti(id) = c.id else {
                return Err("Error: Invalid LTI.".into());
            };
            if !store.lti_exists(id)? {
                return Err("Error: No LTI found for that id.".into());
            }
            if c.augs.is_empty() {
                store.remove_augs(id, None, None)?;
            }
            for (attr, values) in &c.augs {
                if values.is_empty() {
                    store.remove_augs(id, Some(attr), None)?;
                }
                for v in values {
                    let value = match v {
                        Item::Const(k) => k.clone(),
                        Item::Node(Node::Lti(l)) => Val::Lti(*l),
                        Item::Node(Node::Var(_)) => continue,
                    };
                    store.remove_augs(id, Some(attr), Some(&value))?;
                }
            }
        }
        let lazy = self.params.lazy_commit();
        self.store()?.commit(lazy)?;
        Ok("@".repeat(clauses.len()))
    }
}

/// Base-level activation as 9.6.5 computes it (Soar manual, Semantic Memory, "Base-level
/// activation"): the sum s of (now − t + 1)^−d over the ten most recent activation times,
/// given as the log-odds ln(s / (1 + s)). The older activations add nothing: 9.6.5 reads a
/// full history as longer than ten and so never adds its approximation of them (observed
/// on soar-sml 9.6.5 with twelve activations).
///
/// With `inhibition` (`base-inhibition on`), an LTI accessed r ticks ago is held back, as
/// 9.6.5 does, by the log-odds of i = 1 / (1 + 10 / r): ln(i / (1 + i)), which is ln(1/12)
/// right after its access and fades towards ln(1/2) as it ages.
fn base_level(history: &[i64], now: i64, decay: f64, inhibition: bool) -> f64 {
    let sum: f64 = history
        .iter()
        .map(|&t| ((now + 1 - t) as f64).powf(-decay))
        .sum();
    if sum <= 0.0 {
        return schema::ACT_LOW;
    }
    let odds = (sum / (1.0 + sum)).ln();
    match history.first() {
        Some(&last) if inhibition && now + 1 != last => {
            let i = 1.0 / (1.0 + 10.0 / (now + 1 - last) as f64);
            odds + (i / (1.0 + i)).ln()
        }
        _ => odds,
    }
}
