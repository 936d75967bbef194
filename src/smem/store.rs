//! The store of semantic memory: a SQLite database with 9.6.5's tables (`schema.rs`), in
//! memory or in a file (Soar manual, Semantic Memory, "Semantic Memory Storage"). Long-term
//! identifiers (LTIs) are rows of `smem_lti`, their augmentations rows of
//! `smem_augmentations`, and constants are kept once in the symbol tables. Every method
//! answers with a plain error text on a database failure, never a panic.

pub use super::memo::AugValue;
use super::memo::{AugEntry, CountKey, Memo, Rank, Record, WALK_ROWS};
use super::params::SmemParams;
use super::schema::{self, kind, var};
use rusqlite::{params, Connection, OptionalExtension};
use rustc_hash::FxHashMap;
use std::cell::RefCell;
use std::collections::BTreeMap;

/// A value in semantic memory: a constant or an LTI.
#[derive(Debug, Clone, PartialEq)]
pub enum Val {
    Str(String),
    Int(i64),
    Float(f64),
    Lti(i64),
}

/// `Connection::execute` through the statement cache: the same few statements run once
/// per augmentation, so parsing them each time would cost more than running them.
pub(super) fn exec<P: rusqlite::Params>(conn: &Connection, sql: &str, p: P) -> rusqlite::Result<usize> {
    conn.prepare_cached(sql)?.execute(p)
}

/// `Connection::query_row` through the statement cache.
pub(super) fn row<T, P, F>(conn: &Connection, sql: &str, p: P, f: F) -> rusqlite::Result<T>
where
    P: rusqlite::Params,
    F: FnOnce(&rusqlite::Row<'_>) -> rusqlite::Result<T>,
{
    conn.prepare_cached(sql)?.query_row(p, f)
}

/// A database failure, as text for the command's error.
pub type DbResult<T> = Result<T, String>;

fn db<T>(r: rusqlite::Result<T>) -> DbResult<T> {
    r.map_err(db_error)
}

pub(super) fn db_error(e: rusqlite::Error) -> String {
    format!("semantic memory database error: {e}")
}

/// An open store.
pub struct Store {
    pub(super) conn: Connection,
    /// Whether spreading has made traversals in this store (only then do changes to the
    /// augmentations look for the traversals they invalidate).
    pub(super) spread_used: std::cell::Cell<bool>,
    /// Where new LTI numbers are looked for (9.6 takes the lowest free number from here).
    next_lti: i64,
    /// Symbol numbers already looked up, both ways. A symbol row is never changed once
    /// written and only `clear` deletes them, so these stay true; every query and
    /// retrieval needs them, and a map lookup is far cheaper than a statement.
    sym_ids: RefCell<FxHashMap<SymKey, i64>>,
    sym_vals: RefCell<FxHashMap<i64, Val>>,
    /// Copies of the rows a retrieval reads, kept beside the database (`memo.rs`).
    memo: RefCell<Memo>,
}

/// A constant as a map key (floats by their bits, as the symbol table's unique index
/// tells them apart).
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
enum SymKey {
    Str(String),
    Int(i64),
    Float(u64),
}

impl std::fmt::Debug for Store {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Store").finish_non_exhaustive()
    }
}

impl Store {
    /// Opens the store the parameters name, making its tables if it has none. A file that
    /// is not a database, or a database without 9.6's tables that already holds others,
    /// is refused with a message that says so.
    pub fn open(p: &SmemParams) -> DbResult<Store> {
        let conn = if p.in_file() {
            if p.path().is_empty() {
                return Err("smem: no database path is set (smem --set path FILE)".into());
            }
            db(Connection::open(p.path()))?
        } else {
            db(Connection::open_in_memory())?
        };
        let page = p.page_size();
        let cache = p.cache_size();
        // 9.6's `optimization performance` writes without syncing and without a rollback
        // journal; `safety` keeps SQLite's defaults. Neither changes what the file holds.
        let (sync, journal) = if p.safety() {
            ("FULL", "DELETE")
        } else {
            ("OFF", "OFF")
        };
        let setup = format!(
            "PRAGMA page_size = {page}; PRAGMA cache_size = {cache}; PRAGMA synchronous = {sync}; PRAGMA journal_mode = {journal};"
        );
        conn.execute_batch(&setup).map_err(|e| not_a_database(p, &e))?;
        conn.set_prepared_statement_cache_capacity(64);
        // Without the planner's stability guarantee, this SQLite re-plans a statement each
        // time a value bound in an equality changes (its estimate of how many rows match
        // a small integer): every retrieval then parses its statements again, which costs
        // more than running them. The plans here do not depend on the values.
        db(conn.set_db_config(rusqlite::config::DbConfig::SQLITE_DBCONFIG_ENABLE_QPSG, true))?;
        let mut store = Store {
            conn,
            next_lti: 1,
            sym_ids: RefCell::default(),
            sym_vals: RefCell::default(),
            memo: RefCell::default(),
            spread_used: std::cell::Cell::new(false),
        };
        let tables: i64 = store
            .conn
            .query_row(
                "SELECT count(*) FROM sqlite_master WHERE type='table'",
                [],
                |r| r.get(0),
            )
            .map_err(|e| not_a_database(p, &e))?;
        let version: Option<String> = if tables > 0 {
            store
                .conn
                .query_row(
                    "SELECT version_number FROM versions WHERE system='smem_schema'",
                    [],
                    |r| r.get(0),
                )
                .optional()
                .unwrap_or(None)
        } else {
            None
        };
        match version {
            Some(v) if v == schema::VERSION => {
                if !p.append() {
                    store.clear()?;
                }
            }
            Some(v) => {
                return Err(format!(
                    "smem: the database {} has semantic memory schema {v}; this kernel reads {}",
                    p.path(),
                    schema::VERSION
                ))
            }
            None if tables > 0 => {
                return Err(format!(
                    "smem: {} is a database without semantic memory's tables",
                    p.path()
                ))
            }
            None => store.create()?,
        }
        let traversals = db(store
            .conn
            .query_row("SELECT 1 FROM smem_likelihood_trajectories LIMIT 1", [], |_| Ok(()))
            .optional())?;
        store.spread_used.set(traversals.is_some());
        if p.lazy_commit() {
            db(store.conn.execute_batch("BEGIN"))?;
        }
        Ok(store)
    }

    fn create(&mut self) -> DbResult<()> {
        let tx = db(self.conn.transaction())?;
        for s in schema::CREATE {
            db(tx.execute(s, []))?;
        }
        db(tx.execute(
            "INSERT INTO versions (system, version_number) VALUES ('smem_schema', ?1)",
            [schema::VERSION],
        ))?;
        for c in b'A'..=b'Z' {
            db(tx.execute(
                "INSERT INTO smem_ascii (ascii_num, ascii_chr) VALUES (?1, ?2)",
                params![c as i64, (c as char).to_string()],
            ))?;
        }
        db(tx.execute(
            "INSERT INTO smem_constants_store (smem_act_max, smem_act_low) VALUES (?1, ?2)",
            params![i64::MAX as f64, schema::ACT_LOW],
        ))?;
        db(tx.commit())?;
        for (k, v) in [
            (var::MAX_CYCLE, 1),
            (var::NODES, 0),
            (var::EDGES, 0),
            (var::THRESH, 100),
            (var::MODE, 0),
        ] {
            self.set_var(k, v)?;
        }
        self.write_pending()
    }

    /// Commits what a lazy-commit store holds back, and starts holding back again.
    pub fn commit(&mut self, lazy: bool) -> DbResult<()> {
        self.write_pending()?;
        if !self.conn.is_autocommit() {
            db(self.conn.execute_batch("COMMIT"))?;
        }
        if lazy {
            db(self.conn.execute_batch("BEGIN"))?;
        }
        Ok(())
    }

    /// `smem --clear`: every LTI and constant goes; the clock starts again. Spreading's
    /// tables stay, as with 9.6.5 (observed: a source still in working memory spreads to
    /// the new LTIs of the old numbers).
    pub fn clear(&mut self) -> DbResult<()> {
        for t in [
            "smem_symbols_type",
            "smem_symbols_integer",
            "smem_symbols_float",
            "smem_symbols_string",
            "smem_lti",
            "smem_lti_alias",
            "smem_activation_history",
            "smem_augmentations",
            "smem_attribute_frequency",
            "smem_wmes_constant_frequency",
            "smem_wmes_lti_frequency",
            "smem_prohibited",
        ] {
            db(exec(&self.conn, &format!("DELETE FROM {t}"), []))?;
        }
        for (k, v) in [(var::MAX_CYCLE, 1), (var::NODES, 0), (var::EDGES, 0)] {
            self.set_var(k, v)?;
        }
        self.next_lti = 1;
        self.sym_ids.borrow_mut().clear();
        self.sym_vals.borrow_mut().clear();
        self.memo.borrow_mut().clear();
        Ok(())
    }

    /// A persistent variable (0 when the store has none).
    pub fn var(&self, key: i64) -> DbResult<i64> {
        if let Some(&v) = self.memo.borrow().vars.get(&key) {
            return Ok(v);
        }
        let v: Option<i64> = db(row(
            &self.conn,
            "SELECT variable_value FROM smem_persistent_variables WHERE variable_id=?1",
            [key],
            |r| r.get(0),
        )
        .optional())?;
        // Only a row is remembered, so that setting a missing variable to 0 writes it.
        if let Some(v) = v {
            self.memo.borrow_mut().vars.insert(key, v);
        }
        Ok(v.unwrap_or(0))
    }

    /// Sets a persistent variable; the database has it at the next commit (`write_vars`).
    pub fn set_var(&self, key: i64, value: i64) -> DbResult<()> {
        let mut memo = self.memo.borrow_mut();
        if memo.vars.insert(key, value) != Some(value) && !memo.dirty_vars.contains(&key) {
            memo.dirty_vars.push(key);
        }
        Ok(())
    }

    /// Writes what the memo holds back: the activations' copies on the augmentation rows
    /// and the variables.
    fn write_pending(&self) -> DbResult<()> {
        let mut pending: Vec<(i64, f64)> = {
            let mut memo = self.memo.borrow_mut();
            memo.overlay.clear();
            memo.pending.drain().collect()
        };
        pending.sort_by_key(|&(lti, _)| lti);
        for (lti, value) in pending {
            db(exec(
                &self.conn,
                "UPDATE smem_augmentations SET activation_value=?2 WHERE lti_id=?1",
                params![lti, value],
            ))?;
        }
        self.write_vars()
    }

    /// Writes the variables set since the last time.
    fn write_vars(&self) -> DbResult<()> {
        let dirty = std::mem::take(&mut self.memo.borrow_mut().dirty_vars);
        for key in dirty {
            let value = self.memo.borrow().vars.get(&key).copied().unwrap_or(0);
            db(exec(
                &self.conn,
                "INSERT OR REPLACE INTO smem_persistent_variables (variable_id, variable_value) VALUES (?1, ?2)",
                [key, value],
            ))?;
        }
        Ok(())
    }

    fn bump_var(&self, key: i64, by: i64) -> DbResult<()> {
        self.set_var(key, self.var(key)? + by)
    }

    /// A constant's symbol number, made when `create` asks for it and it is missing.
    pub fn symbol(&self, v: &Val, create: bool) -> DbResult<Option<i64>> {
        let key = match v {
            Val::Str(x) => SymKey::Str(x.clone()),
            Val::Int(i) => SymKey::Int(*i),
            Val::Float(f) => SymKey::Float(f.to_bits()),
            Val::Lti(_) => return Ok(None),
        };
        if let Some(&id) = self.sym_ids.borrow().get(&key) {
            return Ok(Some(id));
        }
        let found = self.symbol_row(v, create)?;
        if let Some(id) = found {
            self.sym_ids.borrow_mut().insert(key, id);
        }
        Ok(found)
    }

    fn symbol_row(&self, v: &Val, create: bool) -> DbResult<Option<i64>> {
        let (table, type_code) = match v {
            Val::Str(_) => ("smem_symbols_string", kind::STR),
            Val::Int(_) => ("smem_symbols_integer", kind::INT),
            Val::Float(_) => ("smem_symbols_float", kind::FLOAT),
            Val::Lti(_) => return Ok(None),
        };
        let find = format!("SELECT s_id FROM {table} WHERE symbol_value=?1");
        let found: Option<i64> = db(match v {
            Val::Str(s) => row(&self.conn, &find, [s], |r| r.get(0)).optional(),
            Val::Int(i) => row(&self.conn, &find, [i], |r| r.get(0)).optional(),
            Val::Float(f) => row(&self.conn, &find, [f], |r| r.get(0)).optional(),
            Val::Lti(_) => Ok(None),
        })?;
        if found.is_some() || !create {
            return Ok(found);
        }
        db(exec(&self.conn, 
            "INSERT INTO smem_symbols_type (s_id, symbol_type) VALUES (NULL, ?1)",
            [type_code],
        ))?;
        let id = self.conn.last_insert_rowid();
        let insert = format!("INSERT INTO {table} (s_id, symbol_value) VALUES (?1, ?2)");
        db(match v {
            Val::Str(s) => exec(&self.conn, &insert, params![id, s]),
            Val::Int(i) => exec(&self.conn, &insert, params![id, i]),
            Val::Float(f) => exec(&self.conn, &insert, params![id, f]),
            Val::Lti(_) => Ok(0),
        })?;
        Ok(Some(id))
    }

    /// The constant a symbol number stands for.
    pub fn constant(&self, s_id: i64) -> DbResult<Val> {
        if let Some(v) = self.sym_vals.borrow().get(&s_id) {
            return Ok(v.clone());
        }
        let (v, known) = self.constant_row(s_id)?;
        if known {
            self.sym_vals.borrow_mut().insert(s_id, v.clone());
        }
        Ok(v)
    }

    /// The constant of a symbol row, and whether the row exists.
    fn constant_row(&self, s_id: i64) -> DbResult<(Val, bool)> {
        let t: Option<i64> = db(row(&self.conn, 
                "SELECT symbol_type FROM smem_symbols_type WHERE s_id=?1",
                [s_id],
                |r| r.get(0),
            )
            .optional())?;
        let q = |table: &str| format!("SELECT symbol_value FROM {table} WHERE s_id=?1");
        Ok((match t {
            Some(kind::INT) => Val::Int(db(row(&self.conn, &q("smem_symbols_integer"), [s_id], |r| r.get(0)))?),
            Some(kind::FLOAT) => Val::Float(db(row(&self.conn, &q("smem_symbols_float"), [s_id], |r| r.get(0)))?),
            _ => Val::Str(
                db(row(&self.conn, &q("smem_symbols_string"), [s_id], |r| r.get(0))
                    .optional())?
                .unwrap_or_default(),
            ),
        }, t.is_some()))
    }

    pub fn lti_exists(&self, id: i64) -> DbResult<bool> {
        Ok(db(row(&self.conn, "SELECT 1 FROM smem_lti WHERE lti_id=?1", [id], |_| Ok(()))
            .optional())?
        .is_some())
    }

    /// Makes LTI `id` (empty) unless it exists.
    pub fn make_lti(&mut self, id: i64) -> DbResult<()> {
        if self.lti_exists(id)? {
            return Ok(());
        }
        db(exec(&self.conn, 
            "INSERT INTO smem_lti (lti_id, total_augmentations, activation_base_level, activations_total, activations_last, activations_first, lti_augmentations) VALUES (?1, 0, 0.0, 0.0, 0, 0, 0)",
            [id],
        ))?;
        db(exec(&self.conn, 
            "INSERT OR REPLACE INTO smem_prohibited (lti_id, prohibited, dirty) VALUES (?1, 0, 0)",
            [id],
        ))?;
        self.bump_var(var::NODES, 1)
    }

    /// A new LTI: the lowest free number from where the last one was found.
    pub fn new_lti(&mut self) -> DbResult<i64> {
        let mut id = self.next_lti.max(1);
        while self.lti_exists(id)? {
            id += 1;
        }
        self.next_lti = id + 1;
        self.make_lti(id)?;
        Ok(id)
    }

    /// Every LTI, by number.
    pub fn ltis(&self) -> DbResult<Vec<i64>> {
        let mut st = db(self.conn.prepare_cached("SELECT lti_id FROM smem_lti ORDER BY lti_id"))?;
        let rows = db(st.query_map([], |r| r.get(0)))?;
        rows.map(db).collect()
    }

    /// The LTIs last activated at `time`, by number (what the incremental update policy
    /// recomputes; 9.6 reads them by its index on that time).
    pub fn ltis_last_activated_at(&self, time: i64) -> DbResult<Vec<i64>> {
        let mut st = db(self
            .conn
            .prepare_cached("SELECT lti_id FROM smem_lti WHERE activations_last=?1 ORDER BY lti_id"))?;
        let rows = db(st.query_map([time], |r| r.get(0)))?;
        rows.map(db).collect()
    }

    /// An LTI's augmentations in 9.6's order: by the attribute's symbol number, then the
    /// value's (the order of 9.6's index on them; observed in the order of retrieved WMEs).
    pub fn augs(&self, lti: i64) -> DbResult<Vec<(Val, Val)>> {
        let rows = self.with_aug_rows(lti, <[AugEntry]>::to_vec)?;
        rows.into_iter()
            .map(|e| {
                let (a, c, l) = e.row;
                let attr = self.constant(a)?;
                let value = if l != 0 {
                    Val::Lti(l)
                } else {
                    self.constant(c)?
                };
                Ok((attr, value))
            })
            .collect()
    }

    /// `f` of an LTI's augmentations by symbol numbers, in the order of `augs`; read from
    /// the database once, then from the memo until they change.
    fn with_aug_rows<T>(&self, lti: i64, f: impl FnOnce(&[AugEntry]) -> T) -> DbResult<T> {
        if let Some(rows) = self.memo.borrow().augs.get(&lti) {
            return Ok(f(rows));
        }
        let mut st = db(self.conn.prepare_cached(
            "SELECT attribute_s_id, value_constant_s_id, value_lti_id, rowid, activation_value FROM smem_augmentations WHERE lti_id=?1 ORDER BY attribute_s_id, value_constant_s_id, value_lti_id",
        ))?;
        let rows: Vec<AugEntry> = db(st
            .query_map([lti], |r| {
                Ok(AugEntry {
                    row: (r.get(0)?, r.get(1)?, r.get(2)?),
                    rowid: r.get(3)?,
                    act: r.get(4)?,
                })
            })
            .and_then(Iterator::collect))?;
        let mut rows = rows;
        if let Some(&v) = self.memo.borrow().pending.get(&lti) {
            for e in &mut rows {
                e.act = Some(v);
            }
        }
        let out = f(&rows);
        self.memo.borrow_mut().augs.insert(lti, rows);
        Ok(out)
    }

    /// Adds an augmentation unless the LTI has it; true if it was added.
    pub fn add_aug(&mut self, lti: i64, attr: &Val, value: &Val) -> DbResult<bool> {
        // The walks' overlay holds an LTI's rows as they are; rows change only after it.
        self.write_pending()?;
        let Some(a) = self.symbol(attr, true)? else {
            return Ok(false);
        };
        let (c, l) = match value {
            Val::Lti(l) => {
                self.make_lti(*l)?;
                (0, *l)
            }
            v => (self.symbol(v, true)?.unwrap_or(0), 0),
        };
        let exists = db(row(&self.conn, 
                "SELECT 1 FROM smem_augmentations WHERE lti_id=?1 AND attribute_s_id=?2 AND value_constant_s_id=?3 AND value_lti_id=?4",
                [lti, a, c, l],
                |_| Ok(()),
            )
            .optional())?;
        if exists.is_some() {
            return Ok(false);
        }
        let act: Option<f64> = db(row(&self.conn, 
            "SELECT activation_value FROM smem_lti WHERE lti_id=?1",
            [lti],
            |r| r.get(0),
        ))?;
        db(exec(&self.conn,
            "INSERT INTO smem_augmentations (lti_id, attribute_s_id, value_constant_s_id, value_lti_id, activation_value, edge_weight) VALUES (?1, ?2, ?3, ?4, ?5, ?6)",
            params![lti, a, c, l, act.unwrap_or(schema::ACT_LOW), if l != 0 { 1.0 } else { 0.0 }],
        ))?;
        self.count_aug(lti, a, c, l, 1)?;
        if l != 0 {
            // Each LTI edge of an LTI that gains one weighs 1 / its LTI edges (9.6's fan).
            let n: i64 = db(row(
                &self.conn,
                "SELECT lti_augmentations FROM smem_lti WHERE lti_id=?1",
                [lti],
                |r| r.get(0),
            ))?;
            if n > 1 {
                db(exec(
                    &self.conn,
                    "UPDATE smem_augmentations SET edge_weight=?2 WHERE lti_id=?1 AND value_constant_s_id=0",
                    params![lti, 1.0 / n as f64],
                ))?;
            }
            self.invalidate_through(lti)?;
        }
        Ok(true)
    }

    /// Keeps the counts 9.6 keeps beside an augmentation (the LTI's, the attribute's and
    /// the WME's frequencies, the edge count) as one is added (`by` 1) or removed (-1).
    fn count_aug(&self, lti: i64, a: i64, c: i64, l: i64, by: i64) -> DbResult<()> {
        self.memo.borrow_mut().augs_changed(lti, (a, c, l));
        let lti_aug = i64::from(l != 0) * by;
        db(exec(&self.conn, 
            "UPDATE smem_lti SET total_augmentations = total_augmentations + ?2, lti_augmentations = lti_augmentations + ?3 WHERE lti_id=?1",
            [lti, by, lti_aug],
        ))?;
        let bump = |table: &str, key: &str, args: &[i64]| -> DbResult<()> {
            let cond: Vec<String> = key
                .split(',')
                .enumerate()
                .map(|(i, k)| format!("{k}=?{}", i + 2))
                .collect();
            let n = db(exec(&self.conn, 
                &format!(
                    "UPDATE {table} SET edge_frequency = edge_frequency + ?1 WHERE {}",
                    cond.join(" AND ")
                ),
                rusqlite::params_from_iter(std::iter::once(by).chain(args.iter().copied())),
            ))?;
            if n == 0 && by > 0 {
                let holes: Vec<String> = (0..=args.len()).map(|i| format!("?{}", i + 1)).collect();
                db(exec(&self.conn, 
                    &format!(
                        "INSERT INTO {table} ({key},edge_frequency) VALUES ({})",
                        holes.join(",")
                    ),
                    rusqlite::params_from_iter(args.iter().copied().chain(std::iter::once(1))),
                ))?;
            }
            // Only a decrement can bring a count to zero, and only this row's.
            if by < 0 {
                db(exec(
                    &self.conn,
                    &format!(
                        "DELETE FROM {table} WHERE {} AND edge_frequency <= 0",
                        cond.join(" AND ")
                    ),
                    rusqlite::params_from_iter(std::iter::once(0).chain(args.iter().copied())),
                ))?;
            }
            Ok(())
        };
        bump("smem_attribute_frequency", "attribute_s_id", &[a])?;
        if l != 0 {
            bump(
                "smem_wmes_lti_frequency",
                "attribute_s_id,value_lti_id",
                &[a, l],
            )?;
        } else {
            bump(
                "smem_wmes_constant_frequency",
                "attribute_s_id,value_constant_s_id",
                &[a, c],
            )?;
        }
        self.bump_var(var::EDGES, by)
    }

    /// Removes the augmentations of `lti` with attribute `attr` (all when `None`) and, when
    /// given, value `value`; how many went.
    pub fn remove_augs(&mut self, lti: i64, attr: Option<&Val>, value: Option<&Val>) -> DbResult<usize> {
        self.write_pending()?;
        let mut st = db(self.conn.prepare_cached(
            "SELECT rowid, attribute_s_id, value_constant_s_id, value_lti_id FROM smem_augmentations WHERE lti_id=?1",
        ))?;
        let rows: Vec<(i64, i64, i64, i64)> = db(st
            .query_map([lti], |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?, r.get(3)?)))
            .and_then(Iterator::collect))?;
        drop(st);
        let a = match attr {
            Some(x) => match self.symbol(x, false)? {
                Some(a) => Some(a),
                None => return Ok(0),
            },
            None => None,
        };
        let v = match value {
            Some(Val::Lti(l)) => Some((0, *l)),
            Some(x) => match self.symbol(x, false)? {
                Some(c) => Some((c, 0)),
                None => return Ok(0),
            },
            None => None,
        };
        let mut gone = 0;
        for (rowid, ra, rc, rl) in rows {
            if a.is_some_and(|a| a != ra) || v.is_some_and(|v| v != (rc, rl)) {
                continue;
            }
            db(exec(&self.conn, "DELETE FROM smem_augmentations WHERE rowid=?1", [rowid]))?;
            self.count_aug(lti, ra, rc, rl, -1)?;
            if rl != 0 {
                self.invalidate_edge(lti, rl)?;
            }
            gone += 1;
        }
        Ok(gone)
    }
    /// How many augmentations have `attr` and, when given, `value`: 9.6's frequency
    /// counts, kept beside the augmentations, so this costs one lookup.
    pub fn aug_count(&self, attr: &Val, value: Option<&Val>) -> DbResult<i64> {
        let Some(a) = self.symbol(attr, false)? else {
            return Ok(0);
        };
        let key = match value {
            None => (a, None),
            Some(Val::Lti(l)) => (a, Some((0, *l))),
            Some(v) => match self.symbol(v, false)? {
                None => return Ok(0),
                Some(c) => (a, Some((c, 0))),
            },
        };
        if let Some(&n) = self.memo.borrow().counts.get(&key) {
            return Ok(n);
        }
        let n = self.aug_count_row(a, value)?;
        self.memo.borrow_mut().counts.insert(key, n);
        Ok(n)
    }

    /// `aug_count` from the frequency tables.
    fn aug_count_row(&self, a: i64, value: Option<&Val>) -> DbResult<i64> {
        let n: Option<i64> = match value {
            None => db(row(
                &self.conn,
                "SELECT edge_frequency FROM smem_attribute_frequency WHERE attribute_s_id=?1",
                [a],
                |r| r.get(0),
            )
            .optional())?,
            Some(Val::Lti(l)) => db(row(
                &self.conn,
                "SELECT edge_frequency FROM smem_wmes_lti_frequency WHERE attribute_s_id=?1 AND value_lti_id=?2",
                [a, *l],
                |r| r.get(0),
            )
            .optional())?,
            Some(v) => match self.symbol(v, false)? {
                None => return Ok(0),
                Some(c) => db(row(
                    &self.conn,
                    "SELECT edge_frequency FROM smem_wmes_constant_frequency WHERE attribute_s_id=?1 AND value_constant_s_id=?2",
                    [a, c],
                    |r| r.get(0),
                )
                .optional())?,
            },
        };
        Ok(n.unwrap_or(0))
    }

    /// Walks the LTIs with an augmentation `attr` (and `value` when given), most activated
    /// first and, among equals, the one whose augmentation was written last (the order
    /// retrieval answers in: 9.6 reads the index on the augmentations' copy of their LTI's
    /// activation backwards, and SQLite breaks the index's ties by row number), until
    /// `visit` says stop. Reading the index in its own order costs no sort, so the first
    /// answers cost no look at the rest.
    pub fn walk_ranked(
        &self,
        attr: &Val,
        value: Option<&Val>,
        mut visit: impl FnMut(i64) -> DbResult<bool>,
    ) -> DbResult<()> {
        let Some(a) = self.symbol(attr, false)? else {
            return Ok(());
        };
        let (sql, b, key): (&str, Option<i64>, CountKey) = match value {
            None => (
                "SELECT lti_id, rowid, activation_value FROM smem_augmentations WHERE attribute_s_id=?1 ORDER BY activation_value DESC",
                None,
                (a, None),
            ),
            Some(Val::Lti(l)) => (
                "SELECT lti_id, rowid, activation_value FROM smem_augmentations WHERE attribute_s_id=?1 AND value_constant_s_id=0 AND value_lti_id=?2 ORDER BY activation_value DESC",
                Some(*l),
                (a, Some((0, *l))),
            ),
            Some(v) => match self.symbol(v, false)? {
                None => return Ok(()),
                Some(c) => (
                    "SELECT lti_id, rowid, activation_value FROM smem_augmentations WHERE attribute_s_id=?1 AND value_constant_s_id=?2 AND value_lti_id=0 ORDER BY activation_value DESC",
                    Some(c),
                    (a, Some((c, 0))),
                ),
            },
        };
        // An attribute alone can come with several values per LTI: each LTI once.
        let mut seen = FxHashMap::default();
        let mut visit = |lti: i64| -> DbResult<bool> {
            if b.is_none() && seen.insert(lti, ()).is_some() {
                return Ok(false);
            }
            visit(lti)
        };
        if self.memo.borrow().walks.contains_key(&key) {
            return self.walk_remembered(key, visit);
        }
        let mut st = db(self.conn.prepare_cached(sql))?;
        let mut rows = match b {
            Some(b) => db(st.query([a, b]))?,
            None => db(st.query([a]))?,
        };
        // The rows of the LTIs activated since the last commit come from the overlay, at
        // their new rank, between the database's rows; their rows there are out of date.
        let (mut overlay, pending) = {
            let memo = self.memo.borrow();
            let over: Vec<(Rank, i64)> = memo
                .overlay
                .get(&key)
                .map(|m| m.iter().rev().map(|(&r, &l)| (r, l)).collect())
                .unwrap_or_default();
            (over.into_iter().peekable(), !memo.pending.is_empty())
        };
        // The rows read, kept when the walk reaches the end.
        let mut read = Some(BTreeMap::new());
        let mut step = |rank: Rank, lti: i64, read: &mut Option<BTreeMap<Rank, i64>>| {
            if let Some(m) = read.as_mut() {
                m.insert(rank, lti);
                if m.len() > WALK_ROWS {
                    *read = None;
                }
            }
            visit(lti)
        };
        while let Some(r) = db(rows.next())? {
            let lti: i64 = db(r.get(0))?;
            if pending && self.memo.borrow().pending.contains_key(&lti) {
                continue;
            }
            let rank = Rank::new(db(r.get(2))?, db(r.get(1))?);
            while let Some(&(over, o_lti)) = overlay.peek() {
                if over < rank {
                    break;
                }
                overlay.next();
                if step(over, o_lti, &mut read)? {
                    return Ok(());
                }
            }
            if step(rank, lti, &mut read)? {
                return Ok(());
            }
        }
        for (over, o_lti) in overlay {
            if step(over, o_lti, &mut read)? {
                return Ok(());
            }
        }
        if let Some(m) = read {
            self.memo.borrow_mut().walks.insert(key, m);
        }
        Ok(())
    }

    /// `walk_ranked` over a remembered walk, from the highest rank down. Each step looks
    /// the next rank up again, as `visit` may read what the memo holds.
    fn walk_remembered(
        &self,
        key: CountKey,
        mut visit: impl FnMut(i64) -> DbResult<bool>,
    ) -> DbResult<()> {
        let mut below: Option<Rank> = None;
        loop {
            let next = {
                let memo = self.memo.borrow();
                let Some(walk) = memo.walks.get(&key) else {
                    return Ok(());
                };
                match below {
                    None => walk.iter().next_back(),
                    Some(r) => walk.range(..r).next_back(),
                }
                .map(|(&r, &l)| (r, l))
            };
            let Some((rank, lti)) = next else {
                return Ok(());
            };
            if visit(lti)? {
                return Ok(());
            }
            below = Some(rank);
        }
    }

    /// Whether `lti` has an augmentation `attr` (with `value` when given). Symbols are
    /// looked up by the caller once per cue element, as `attr`'s and `value`'s numbers.
    pub fn has_aug(&self, lti: i64, a: i64, value: AugValue) -> DbResult<bool> {
        self.with_aug_rows(lti, |rows| Memo::has(rows, a, value))
    }

    /// An LTI's activation as `print` shows it (0 for one never activated).
    pub fn shown_activation(&self, lti: i64) -> DbResult<f64> {
        self.lti_real(lti, "SELECT activation_value FROM smem_lti WHERE lti_id=?1")
    }

    /// `activation_base_level` of an LTI (0 for one never activated).
    pub fn base_activation(&self, lti: i64) -> DbResult<f64> {
        self.lti_real(lti, "SELECT activation_base_level FROM smem_lti WHERE lti_id=?1")
    }

    /// A real column of an LTI's row, read by `sql` (0 when empty or the LTI is unknown).
    fn lti_real(&self, lti: i64, sql: &str) -> DbResult<f64> {
        let v: Option<Option<f64>> = db(row(
            &self.conn,
            sql,
            [lti],
            |r| r.get(0),
        )
        .optional())?;
        Ok(v.flatten().unwrap_or(0.0))
    }

    /// The activation the augmentations of an LTI are ranked by (the lowest for one never
    /// activated).
    pub fn rank_activation(&self, lti: i64) -> DbResult<f64> {
        self.with_aug_rows(lti, |rows| {
            rows.first().and_then(|e| e.act).unwrap_or(schema::ACT_LOW)
        })
    }

    /// Sets the activation an LTI's augmentations are ranked by; the rows have it at the
    /// next commit.
    pub fn set_rank_activation(&self, lti: i64, value: f64) -> DbResult<()> {
        let rows = self.with_aug_rows(lti, <[AugEntry]>::to_vec)?;
        self.memo.borrow_mut().activation_changed(lti, &rows, value);
        Ok(())
    }

    /// Writes an LTI's access record (count, times, history) but not its activation, for an
    /// LTI whose activation is kept with its spread.
    pub fn write_access(&self, lti: i64, record: Record) -> DbResult<()> {
        db(exec(
            &self.conn,
            "UPDATE smem_lti SET activations_total=?2, activations_last=?3, activations_first=?4 WHERE lti_id=?1",
            params![lti, record.total, record.last, record.first],
        ))?;
        self.write_history(lti, &record.history)?;
        self.memo.borrow_mut().records.insert(lti, record);
        Ok(())
    }

    /// The activation record of an LTI: its activations, the last and first times, and the
    /// times of the last ten (read from the database once, then kept up to date by
    /// `write_activation`).
    pub fn record(&self, lti: i64) -> DbResult<Record> {
        if let Some(r) = self.memo.borrow().records.get(&lti) {
            return Ok(r.clone());
        }
        let (total, last, first) = db(row(
            &self.conn,
            "SELECT activations_total, activations_last, activations_first FROM smem_lti WHERE lti_id=?1",
            [lti],
            |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?)),
        ))?;
        let times: Option<Vec<Option<i64>>> = db(row(
            &self.conn,
            "SELECT t1,t2,t3,t4,t5,t6,t7,t8,t9,t10 FROM smem_activation_history WHERE lti_id=?1",
            [lti],
            |r| (0..10).map(|i| r.get(i)).collect(),
        )
        .optional())?;
        let history = times
            .unwrap_or_default()
            .into_iter()
            .flatten()
            .filter(|&t| t > 0)
            .collect();
        let record = Record {
            total,
            last,
            first,
            history,
        };
        self.memo.borrow_mut().records.insert(lti, record.clone());
        Ok(record)
    }

    /// Writes an activation: the LTI's record and its history; its augmentations' copy of
    /// the value (which the retrieval's order reads) waits in the memo until the next
    /// commit (`write_pending`).
    pub fn write_activation(&self, lti: i64, record: Record, base: f64, value: f64) -> DbResult<()> {
        let history = &record.history;
        let rows = self.with_aug_rows(lti, <[AugEntry]>::to_vec)?;
        self.memo.borrow_mut().activation_changed(lti, &rows, value);
        db(exec(&self.conn, 
            "UPDATE smem_lti SET activations_total=?2, activations_last=?3, activations_first=?4, activation_base_level=?5, activation_spread=0.0, activation_value=?6 WHERE lti_id=?1",
            params![lti, record.total, record.last, record.first, base, value],
        ))?;
        self.write_history(lti, history)?;
        self.memo.borrow_mut().records.insert(lti, record);
        Ok(())
    }

    fn write_history(&self, lti: i64, history: &[i64]) -> DbResult<()> {
        // An LTI gets its history row with its first access.
        if history.is_empty() {
            return Ok(());
        }
        let mut t = [0i64; 10];
        for (slot, h) in t.iter_mut().zip(history) {
            *slot = *h;
        }
        db(exec(&self.conn,
            "INSERT OR REPLACE INTO smem_activation_history (lti_id,t1,t2,t3,t4,t5,t6,t7,t8,t9,t10,touch1,touch2,touch3,touch4,touch5,touch6,touch7,touch8,touch9,touch10) VALUES (?1,?2,?3,?4,?5,?6,?7,?8,?9,?10,?11,1,1,1,1,1,1,1,1,1,1)",
            params![lti, t[0], t[1], t[2], t[3], t[4], t[5], t[6], t[7], t[8], t[9]],
        ))?;
        Ok(())
    }

    /// How many LTIs and augmentations the store holds.
    pub fn counts(&self) -> DbResult<(i64, i64)> {
        Ok((self.var(var::NODES)?, self.var(var::EDGES)?))
    }

    /// The bytes the database takes (pages in use times the page size).
    pub fn bytes(&self) -> DbResult<i64> {
        let pages: i64 = db(row(&self.conn, "PRAGMA page_count", [], |r| r.get(0)))?;
        let size: i64 = db(row(&self.conn, "PRAGMA page_size", [], |r| r.get(0)))?;
        Ok(pages * size)
    }

    /// `smem --backup FILE`: a copy of the database, made with SQLite's `VACUUM INTO`.
    pub fn backup(&mut self, path: &str, lazy: bool) -> DbResult<()> {
        self.commit(false)?;
        let r = db(exec(&self.conn, "VACUUM INTO ?1", [path]));
        if lazy {
            db(self.conn.execute_batch("BEGIN"))?;
        }
        r.map(|_| ())
    }
}

/// What lazy-commit held back is written when the store closes (Soar manual, ch. 9,
/// `smem`: `lazy-commit` delays writing until exit), and so are the persistent variables.
impl Drop for Store {
    fn drop(&mut self) {
        let _ = self.write_pending();
        if !self.conn.is_autocommit() {
            // Nothing can be reported from here; a failing commit leaves the file as it
            // was at the last commit.
            let _ = self.conn.execute_batch("COMMIT");
        }
    }
}

/// The error for a file SQLite cannot read as a database (or cannot open, or that another
/// program holds locked).
fn not_a_database(p: &SmemParams, e: &rusqlite::Error) -> String {
    format!("smem: cannot use {} as a semantic memory database: {e}", p.path())
}
