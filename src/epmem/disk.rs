//! Episodic memory in a SQLite file with 9.6.5's tables (`schema.rs`; Soar manual, ch. 9,
//! `epmem`, the `database`, `path`, `append` and `lazy-commit` settings). rusoar searches
//! and rebuilds episodes from its own rows (`store.rs`); the file holds the same rows, as
//! 9.6 writes them, written as each episode is stored and read back when the file is
//! opened with `append on`. Every failure is a message naming the file, never a panic.

use super::params::EpmemParams;
use super::rit::Tree;
use super::schema::{self, kind, var, OPEN};
use super::store::{Constant, Rows, Store, ROOT};
use rusqlite::{params, Connection, OptionalExtension};

/// A database failure, as the text to print.
pub type DbResult<T> = Result<T, String>;

/// The most episodes a file may number (far beyond any run, and far from overflow).
const MAX_EPISODE: i64 = 1 << 40;

/// The most row numbers a table may skip (rows are kept by number, gaps included).
const MAX_GAP: i64 = 1 << 20;

/// The rows' two kinds, in the file's order: constants, then edges.
const CONST: usize = 0;
const EDGE: usize = 1;

/// The tables of each kind: rows, open ranges, single episodes, closed ranges, the row's
/// column, and the column of an edge's long-term identifier (`0` for constants).
struct Tables {
    now: &'static str,
    point: &'static str,
    range: &'static str,
    id: &'static str,
    lti: &'static str,
}

const TABLES: [Tables; 2] = [
    Tables {
        now: "epmem_wmes_constant_now",
        point: "epmem_wmes_constant_point",
        range: "epmem_wmes_constant_range",
        id: "wc_id",
        lti: "0",
    },
    Tables {
        now: "epmem_wmes_identifier_now",
        point: "epmem_wmes_identifier_point",
        range: "epmem_wmes_identifier_range",
        id: "wi_id",
        lti: "lti_id",
    },
];

/// A long-term identifier column (NULL, as 9.6 leaves some, is none).
fn lti_of(r: &rusqlite::Row<'_>, i: usize) -> rusqlite::Result<i64> {
    Ok(r.get::<_, Option<i64>>(i)?.unwrap_or(0))
}

/// What one episode changed, for the file: the rows whose range started at it, and the
/// ranges that ended before it, as (row, first episode, last episode), for constants and
/// for edges.
#[derive(Debug, Default)]
pub struct Changes {
    pub started: [Vec<i64>; 2],
    pub ended: [Vec<(i64, i64, i64)>; 2],
}

/// An open file.
pub struct Disk {
    conn: Connection,
    path: String,
    lazy: bool,
    /// How many constants, rows of each kind and nodes the file holds.
    constants: usize,
    rows: [usize; 2],
    nodes: i64,
    /// How many of the store's later links of nodes to long-term identifiers it holds.
    later_ltis: usize,
    trees: [Tree; 2],
}

impl std::fmt::Debug for Disk {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Disk").field("path", &self.path).finish_non_exhaustive()
    }
}

impl Disk {
    /// A file that holds nothing of the store yet (the root and `operator*` come with the
    /// tables).
    fn new(conn: Connection, path: &str, lazy: bool) -> Disk {
        Disk {
            conn,
            path: path.to_string(),
            lazy,
            constants: 2,
            rows: [0, 0],
            nodes: 1,
            later_ltis: 0,
            trees: [Tree::default(); 2],
        }
    }

    /// Opens the file the parameters name: emptied first unless `append` is on, its tables
    /// made if missing. A file that is not a database, is locked, or holds another schema
    /// version is refused with a message naming it.
    pub fn open(p: &EpmemParams) -> DbResult<(Disk, Store)> {
        let path = p.get("path").unwrap_or_default();
        if path.is_empty() {
            return Err("Episodic memory database error: no path is set (epmem --set path FILE).".into());
        }
        let fail = |e: rusqlite::Error| format!("Episodic memory database error in {path}: {e}");
        let conn = Connection::open(&path).map_err(fail)?;
        // A file another program holds is refused at once, as 9.6 does, not waited for.
        conn.busy_timeout(std::time::Duration::ZERO).map_err(fail)?;
        let mut pragmas = format!(
            "PRAGMA page_size = {}; PRAGMA cache_size = {};",
            page_bytes(&p.get("page-size").unwrap_or_default()),
            p.get("cache-size").unwrap_or_default()
        );
        if p.get("optimization").as_deref() == Some("performance") {
            // 9.6's "performance": no waiting on the disk and no journal.
            pragmas.push_str(
                "PRAGMA synchronous = OFF; PRAGMA journal_mode = OFF; PRAGMA locking_mode = EXCLUSIVE;",
            );
        }
        conn.execute_batch(&pragmas).map_err(fail)?;
        let version: Option<String> = {
            let has_versions: i64 = conn
                .query_row(
                    "SELECT count(*) FROM sqlite_master WHERE type='table' AND name='versions'",
                    [],
                    |r| r.get(0),
                )
                .map_err(fail)?;
            if has_versions > 0 {
                conn.query_row(
                    "SELECT version_number FROM versions WHERE system='epmem_schema'",
                    [],
                    |r| r.get(0),
                )
                .optional()
                .map_err(fail)?
            } else {
                None
            }
        };
        if let Some(v) = &version {
            if v != schema::VERSION {
                return Err(format!(
                    "Episodic memory database error: {path} has episodic memory schema version {v}; this kernel reads {}.",
                    schema::VERSION
                ));
            }
        }
        let append = p.get("append").as_deref() == Some("on");
        let lazy = p.get("lazy-commit").as_deref() != Some("off");
        let mut disk = Disk::new(conn, &path, lazy);
        disk.create(!append).map_err(fail)?;
        disk.check_numbers()?;
        let mut store = Store::default();
        disk.load(&mut store).map_err(fail)?;
        disk.close_open_ranges(&mut store).map_err(fail)?;
        store.consts.reindex();
        store.edges.reindex();
        if lazy {
            // 9.6 holds the agent's whole life in one transaction, committed on close.
            disk.conn.execute_batch("BEGIN").map_err(fail)?;
        }
        Ok((disk, store))
    }

    /// Makes the tables, after dropping them when the file is to be emptied.
    fn create(&mut self, empty: bool) -> rusqlite::Result<()> {
        let tx = self.conn.transaction()?;
        if empty {
            for t in schema::TABLES {
                tx.execute(&format!("DROP TABLE IF EXISTS {t}"), [])?;
            }
        }
        for s in schema::CREATE {
            tx.execute(s, [])?;
        }
        tx.execute(
            "INSERT OR REPLACE INTO versions (system, version_number) VALUES ('epmem_schema', ?1)",
            [schema::VERSION],
        )?;
        for (id, name) in [(0, "root"), (1, "operator*")] {
            tx.execute(
                "INSERT OR IGNORE INTO epmem_symbols_type (s_id, symbol_type) VALUES (?1, ?2)",
                params![id, kind::STR],
            )?;
            tx.execute(
                "INSERT OR IGNORE INTO epmem_symbols_string (s_id, symbol_value) VALUES (?1, ?2)",
                params![id, name],
            )?;
        }
        for c in b'A'..=b'Z' {
            tx.execute(
                "INSERT OR IGNORE INTO epmem_ascii (ascii_num, ascii_chr) VALUES (?1, ?2)",
                params![c as i64, (c as char).to_string()],
            )?;
        }
        // 9.6 adds the root's row at each opening (a NULL never collides in the index).
        tx.execute("INSERT INTO epmem_nodes (n_id, lti_id) VALUES (?1, NULL)", [ROOT])?;
        for k in [CONST, EDGE] {
            for (i, v) in Tree::default().vars().into_iter().enumerate() {
                tx.execute(
                    "INSERT OR IGNORE INTO epmem_persistent_variables (variable_id, variable_value) VALUES (?1, ?2)",
                    params![var::tree(k) + i as i64, v],
                )?;
            }
        }
        tx.execute(
            "INSERT OR IGNORE INTO epmem_persistent_variables (variable_id, variable_value) VALUES (?1, 1)",
            [var::NEXT_NODE],
        )?;
        tx.commit()
    }

    /// Refuses a file whose numbers the store cannot hold: rows are kept by number, so a
    /// number far past the rows there are, an episode out of any count, or a range outside
    /// the stored episodes would make a damaged file cost memory without end.
    fn check_numbers(&self) -> DbResult<()> {
        let fail = |e: rusqlite::Error| format!("Episodic memory database error in {}: {e}", self.path);
        let refuse = |what: String| {
            format!(
                "Episodic memory database error: {} holds {what}, which this kernel cannot read.",
                self.path
            )
        };
        let one = |sql: &str| -> DbResult<(i64, i64, i64)> {
            self.conn
                .query_row(sql, [], |r| {
                    Ok((r.get(0)?, r.get::<_, Option<i64>>(1)?.unwrap_or(1), r.get::<_, Option<i64>>(2)?.unwrap_or(0)))
                })
                .map_err(fail)
        };
        let (_, first, last) = one("SELECT count(*), min(episode_id), max(episode_id) FROM epmem_episodes")?;
        if first < 1 || last > MAX_EPISODE {
            return Err(refuse(format!("episodes numbered {first} to {last}")));
        }
        for (table, id, least) in [
            ("epmem_symbols_type", "s_id", 0),
            ("epmem_wmes_constant", "wc_id", 1),
            ("epmem_wmes_identifier", "wi_id", 1),
        ] {
            let (count, min, max) = one(&format!("SELECT count(*), min({id}), max({id}) FROM {table}"))?;
            if min < least || max - count > MAX_GAP {
                return Err(refuse(format!("{count} rows of {table} numbered {min} to {max}")));
            }
        }
        for t in &TABLES {
            let bad = format!(
                "SELECT count(*), 0, 0 FROM {} WHERE start_episode_id < 1 OR end_episode_id < start_episode_id OR end_episode_id > {last}",
                t.range
            );
            let points = format!("SELECT count(*), 0, 0 FROM {} WHERE episode_id < 1 OR episode_id > {last}", t.point);
            let open = format!("SELECT count(*), 0, 0 FROM {} WHERE start_episode_id < 1 OR start_episode_id > {last}", t.now);
            for (sql, table) in [(bad, t.range), (points, t.point), (open, t.now)] {
                let (n, _, _) = one(&sql)?;
                if n > 0 {
                    return Err(refuse(format!("{n} rows of {table} outside its episodes 1 to {last}")));
                }
            }
        }
        Ok(())
    }

    /// Reads the file into `store`: its constants, rows, ranges, episodes and variables.
    fn load(&mut self, store: &mut Store) -> rusqlite::Result<()> {
        let mut q = self.conn.prepare(
            "SELECT t.s_id, t.symbol_type, i.symbol_value, f.symbol_value, s.symbol_value \
             FROM epmem_symbols_type t \
             LEFT JOIN epmem_symbols_integer i ON i.s_id = t.s_id \
             LEFT JOIN epmem_symbols_float f ON f.s_id = t.s_id \
             LEFT JOIN epmem_symbols_string s ON s.s_id = t.s_id \
             WHERE t.s_id > 1 ORDER BY t.s_id",
        )?;
        let mut rows = q.query([])?;
        while let Some(r) = rows.next()? {
            let id: i64 = r.get(0)?;
            let c = match r.get::<_, i64>(1)? {
                kind::INT => Constant::Int(r.get::<_, Option<i64>>(2)?.unwrap_or(0)),
                kind::FLOAT => Constant::Float(r.get::<_, Option<f64>>(3)?.unwrap_or(0.0).to_bits()),
                _ => Constant::Str(r.get::<_, Option<String>>(4)?.unwrap_or_default()),
            };
            store.load_constant(id, c);
        }
        drop(rows);
        drop(q);
        self.constants = store.constant_count();
        for (k, sql) in [
            "SELECT wc_id, parent_n_id, attribute_s_id, value_s_id FROM epmem_wmes_constant ORDER BY wc_id",
            "SELECT wi_id, parent_n_id, attribute_s_id, child_n_id FROM epmem_wmes_identifier ORDER BY wi_id",
        ]
        .into_iter()
        .enumerate()
        {
            let rows_of = if k == CONST { &mut store.consts } else { &mut store.edges };
            let mut q = self.conn.prepare(sql)?;
            let mut rows = q.query([])?;
            while let Some(r) = rows.next()? {
                rows_of.load(r.get(0)?, (r.get(1)?, r.get(2)?, r.get(3)?));
            }
            self.rows[k] = rows_of.count();
            let t = &TABLES[k];
            let mut ranges: Vec<(i64, i64, i64, i64)> = Vec::new();
            for sql in [
                format!("SELECT {}, start_episode_id, end_episode_id, {} FROM {}", t.id, t.lti, t.range),
                format!("SELECT {}, episode_id, episode_id, {} FROM {}", t.id, t.lti, t.point),
            ] {
                let mut q = self.conn.prepare(&sql)?;
                let mut rows = q.query([])?;
                while let Some(r) = rows.next()? {
                    ranges.push((r.get(0)?, r.get(1)?, r.get(2)?, lti_of(r, 3)?));
                }
            }
            ranges.sort_unstable();
            for (row, start, end, lti) in ranges {
                if row >= 1 && row as usize <= rows_of.count() {
                    rows_of.life_mut(row).ranges.push((start, end));
                    rows_of.set_lti(row, start, lti);
                }
            }
            for row in 1..=rows_of.count() as i64 {
                rows_of.life_mut(row).ended = true;
            }
        }
        let last: Option<i64> =
            self.conn
                .query_row("SELECT MAX(episode_id) FROM epmem_episodes", [], |r| r.get(0))?;
        store.time = last.unwrap_or(0) + 1;
        store.next_node = self.var(var::NEXT_NODE)?.unwrap_or(1).max(1);
        self.nodes = store.next_node;
        for k in [CONST, EDGE] {
            let mut v = Tree::default().vars();
            for (i, x) in v.iter_mut().enumerate() {
                if let Some(val) = self.var(var::tree(k) + i as i64)? {
                    *x = val;
                }
            }
            self.trees[k] = Tree::from_vars(v);
        }
        Ok(())
    }

    /// The rows still open when the file was closed end at its last episode (9.6 does this
    /// on every opening): the agent's working memory is stored afresh at the next episode.
    fn close_open_ranges(&mut self, store: &mut Store) -> rusqlite::Result<()> {
        let last = store.time - 1;
        let tx = self.conn.transaction()?;
        for k in [CONST, EDGE] {
            let t = &TABLES[k];
            let open: Vec<(i64, i64, i64)> = {
                let sql = format!("SELECT {}, start_episode_id, {} FROM {}", t.id, t.lti, t.now);
                let mut q = tx.prepare(&sql)?;
                let rows = q.query_map([], |r| Ok((r.get(0)?, r.get(1)?, lti_of(r, 2)?)))?;
                rows.collect::<rusqlite::Result<_>>()?
            };
            let rows_of = if k == CONST { &mut store.consts } else { &mut store.edges };
            for (row, start, lti) in open {
                let start = start.min(last);
                Self::end_range(&tx, &mut self.trees[k], k, (row, start, last), lti)?;
                if row >= 1 && row as usize <= rows_of.count() {
                    let life = rows_of.life_mut(row);
                    life.ranges.push((start, last));
                    life.ranges.sort_unstable();
                    rows_of.set_lti(row, start, lti);
                }
            }
            tx.execute(&format!("DELETE FROM {}", t.now), [])?;
        }
        Self::write_trees(&tx, &self.trees)?;
        tx.commit()
    }

    /// Writes a range that ended: one episode is a point, more a range filed in the tree.
    /// `lti`: an edge's long-term identifier in the range (0: none).
    fn end_range(
        conn: &Connection,
        tree: &mut Tree,
        k: usize,
        (row, start, end): (i64, i64, i64),
        lti: i64,
    ) -> rusqlite::Result<()> {
        if start == end {
            if k == CONST {
                conn.prepare_cached("INSERT INTO epmem_wmes_constant_point (wc_id, episode_id) VALUES (?1, ?2)")?
                    .execute(params![row, start])?;
            } else {
                conn.prepare_cached(
                    "INSERT INTO epmem_wmes_identifier_point (wi_id, episode_id, lti_id) VALUES (?1, ?2, ?3)",
                )?
                .execute(params![row, start, lti])?;
            }
        } else {
            let node = tree.insert(start, end);
            if k == CONST {
                conn.prepare_cached(
                    "INSERT INTO epmem_wmes_constant_range (rit_id, start_episode_id, end_episode_id, wc_id) VALUES (?1, ?2, ?3, ?4)",
                )?
                .execute(params![node, start, end, row])?;
            } else {
                conn.prepare_cached(
                    "INSERT INTO epmem_wmes_identifier_range (rit_id, start_episode_id, end_episode_id, wi_id, lti_id) VALUES (?1, ?2, ?3, ?4, ?5)",
                )?
                .execute(params![node, start, end, row, lti])?;
            }
        }
        if k == EDGE {
            conn.prepare_cached("UPDATE epmem_wmes_identifier SET last_episode_id = ?1 WHERE wi_id = ?2")?
                .execute(params![end, row])?;
        }
        Ok(())
    }

    /// Writes a range that starts at `episode` and is still open.
    fn start_range(conn: &Connection, k: usize, row: i64, episode: i64, lti: i64) -> rusqlite::Result<()> {
        if k == CONST {
            conn.prepare_cached("INSERT INTO epmem_wmes_constant_now (wc_id, start_episode_id) VALUES (?1, ?2)")?
                .execute(params![row, episode])?;
        } else {
            conn.prepare_cached(
                "INSERT INTO epmem_wmes_identifier_now (wi_id, start_episode_id, lti_id) VALUES (?1, ?2, ?3)",
            )?
            .execute(params![row, episode, lti])?;
        }
        if k == EDGE {
            conn.prepare_cached("UPDATE epmem_wmes_identifier SET last_episode_id = ?1 WHERE wi_id = ?2")?
                .execute(params![OPEN, row])?;
        }
        Ok(())
    }

    fn var(&self, key: i64) -> rusqlite::Result<Option<i64>> {
        self.conn
            .query_row(
                "SELECT variable_value FROM epmem_persistent_variables WHERE variable_id = ?1",
                [key],
                |r| r.get(0),
            )
            .optional()
    }

    fn set_var(conn: &Connection, key: i64, value: i64) -> rusqlite::Result<()> {
        conn.prepare_cached(
            "INSERT OR REPLACE INTO epmem_persistent_variables (variable_id, variable_value) VALUES (?1, ?2)",
        )?
        .execute(params![key, value])?;
        Ok(())
    }

    fn write_trees(conn: &Connection, trees: &[Tree; 2]) -> rusqlite::Result<()> {
        for k in [CONST, EDGE] {
            for (i, v) in trees[k].vars().into_iter().enumerate() {
                Self::set_var(conn, var::tree(k) + i as i64, v)?;
            }
        }
        Ok(())
    }

    /// Writes episode `episode`: the constants, nodes and rows it made, the ranges that
    /// ended before it and those that start at it.
    pub fn record(&mut self, store: &Store, episode: i64, ch: &Changes) -> DbResult<()> {
        let r = self.write_episode(store, episode, ch);
        r.map_err(|e| format!("Episodic memory database error in {}: {e}", self.path))
    }

    fn write_episode(&mut self, store: &Store, episode: i64, ch: &Changes) -> rusqlite::Result<()> {
        if !self.lazy {
            self.conn.execute_batch("BEGIN")?;
        }
        self.write_new(store)?;
        let before = self.trees;
        for k in [CONST, EDGE] {
            let t = &TABLES[k];
            let rows = if k == CONST { &store.consts } else { &store.edges };
            for &(row, start, end) in &ch.ended[k] {
                self.conn
                    .prepare_cached(&format!("DELETE FROM {} WHERE {} = ?1", t.now, t.id))?
                    .execute([row])?;
                let lti = rows.lti_at(row, start);
                Self::end_range(&self.conn, &mut self.trees[k], k, (row, start, end), lti)?;
            }
            for &row in &ch.started[k] {
                Self::start_range(&self.conn, k, row, episode, rows.lti_at(row, episode))?;
            }
        }
        self.conn
            .prepare_cached("INSERT INTO epmem_episodes (episode_id) VALUES (?1)")?
            .execute([episode])?;
        if self.trees != before {
            Self::write_trees(&self.conn, &self.trees)?;
        }
        if !self.lazy {
            self.conn.execute_batch("COMMIT")?;
        }
        Ok(())
    }

    /// Writes the constants, nodes and rows the store made since the last episode.
    fn write_new(&mut self, store: &Store) -> rusqlite::Result<()> {
        for h in self.constants..store.constant_count() {
            let h = h as i64;
            let (code, table) = match store.constant(h) {
                Constant::Str(_) => (kind::STR, "epmem_symbols_string"),
                Constant::Int(_) => (kind::INT, "epmem_symbols_integer"),
                Constant::Float(_) => (kind::FLOAT, "epmem_symbols_float"),
            };
            self.conn
                .prepare_cached("INSERT INTO epmem_symbols_type (s_id, symbol_type) VALUES (?1, ?2)")?
                .execute(params![h, code])?;
            let sql = format!("INSERT INTO {table} (s_id, symbol_value) VALUES (?1, ?2)");
            let mut q = self.conn.prepare_cached(&sql)?;
            match store.constant(h) {
                Constant::Str(s) => q.execute(params![h, s])?,
                Constant::Int(i) => q.execute(params![h, i])?,
                Constant::Float(b) => q.execute(params![h, f64::from_bits(*b)])?,
            };
        }
        self.constants = store.constant_count();
        for n in self.nodes..store.next_node {
            let lti = store.node_ltis.get(&n).copied().unwrap_or(0);
            self.conn
                .prepare_cached("INSERT INTO epmem_nodes (n_id, lti_id) VALUES (?1, ?2)")?
                .execute([n, lti])?;
        }
        for &(n, lti) in store.later_ltis.iter().skip(self.later_ltis) {
            self.conn
                .prepare_cached("INSERT OR REPLACE INTO epmem_nodes (n_id, lti_id) VALUES (?1, ?2)")?
                .execute([n, lti])?;
        }
        self.later_ltis = store.later_ltis.len();
        if store.next_node != self.nodes {
            Self::set_var(&self.conn, var::NEXT_NODE, store.next_node)?;
            self.nodes = store.next_node;
        }
        self.write_rows(&store.consts, CONST)?;
        self.write_rows(&store.edges, EDGE)
    }

    fn write_rows(&mut self, rows: &Rows, k: usize) -> rusqlite::Result<()> {
        for id in self.rows[k] + 1..=rows.count() {
            let (parent, attr, value) = rows.triple(id as i64);
            if k == CONST {
                self.conn
                    .prepare_cached(
                        "INSERT INTO epmem_wmes_constant (wc_id, parent_n_id, attribute_s_id, value_s_id) VALUES (?1, ?2, ?3, ?4)",
                    )?
                    .execute(params![id as i64, parent, attr, value])?;
            } else {
                self.conn
                    .prepare_cached(
                        "INSERT INTO epmem_wmes_identifier (wi_id, parent_n_id, attribute_s_id, child_n_id, last_episode_id) VALUES (?1, ?2, ?3, ?4, ?5)",
                    )?
                    .execute(params![id as i64, parent, attr, value, OPEN])?;
            }
        }
        self.rows[k] = rows.count();
        Ok(())
    }

    /// Writes what lazy-commit holds back, and goes on holding back.
    pub fn commit(&mut self) -> DbResult<()> {
        let fail = |e: rusqlite::Error| format!("Episodic memory database error in {}: {e}", self.path);
        if !self.conn.is_autocommit() {
            self.conn.execute_batch("COMMIT").map_err(fail)?;
        }
        if self.lazy {
            self.conn.execute_batch("BEGIN").map_err(fail)?;
        }
        Ok(())
    }

    /// `epmem --backup FILE`: a copy of the file as it stands, what lazy-commit holds back
    /// included.
    pub fn backup(&mut self, to: &str) -> DbResult<()> {
        let fail = |e: rusqlite::Error| format!("Episodic memory database error: cannot back up to {to}: {e}");
        if !self.conn.is_autocommit() {
            self.conn.execute_batch("COMMIT").map_err(fail)?;
        }
        let r = copy_to(&self.conn, to).map_err(fail);
        if self.lazy {
            self.conn.execute_batch("BEGIN").map_err(fail)?;
        }
        r
    }
}

/// `epmem --backup FILE` of a store kept in memory: the file 9.6 would hold for it. Closed
/// ranges are filed in the order they ended, as they were when the episodes were stored.
pub fn snapshot(store: &Store, to: &str) -> DbResult<()> {
    let fail = |e: rusqlite::Error| format!("Episodic memory database error: cannot back up to {to}: {e}");
    let conn = Connection::open_in_memory().map_err(fail)?;
    let mut disk = Disk::new(conn, to, false);
    disk.write_all(store).map_err(fail)?;
    copy_to(&disk.conn, to).map_err(fail)
}

impl Disk {
    fn write_all(&mut self, store: &Store) -> rusqlite::Result<()> {
        self.create(true)?;
        self.conn.execute_batch("BEGIN")?;
        self.write_new(store)?;
        let mut ch = Changes::default();
        let mut opened: [Vec<(i64, i64)>; 2] = [Vec::new(), Vec::new()];
        for (k, rows) in [(CONST, &store.consts), (EDGE, &store.edges)] {
            for row in 1..=rows.count() as i64 {
                let life = rows.life(row);
                ch.ended[k].extend(life.ranges.iter().map(|&(s, e)| (row, s, e)));
                if let Some(s) = life.now {
                    opened[k].push((row, s));
                }
            }
            ch.ended[k].sort_unstable_by_key(|&(row, _, end)| (end, row));
        }
        for k in [CONST, EDGE] {
            let rows = if k == CONST { &store.consts } else { &store.edges };
            for &(row, start, end) in &ch.ended[k] {
                let lti = rows.lti_at(row, start);
                Self::end_range(&self.conn, &mut self.trees[k], k, (row, start, end), lti)?;
            }
            for &(row, start) in &opened[k] {
                Self::start_range(&self.conn, k, row, start, rows.lti_at(row, start))?;
            }
        }
        for e in 1..store.time {
            self.conn
                .prepare_cached("INSERT INTO epmem_episodes (episode_id) VALUES (?1)")?
                .execute([e])?;
        }
        Self::write_trees(&self.conn, &self.trees)?;
        self.conn.execute_batch("COMMIT")
    }
}

/// Copies a database to a file, replacing it (as 9.6's backup does).
pub fn copy_to(conn: &Connection, to: &str) -> rusqlite::Result<()> {
    if std::path::Path::new(to).exists() {
        if let Err(e) = std::fs::remove_file(to) {
            return Err(rusqlite::Error::ToSqlConversionFailure(Box::new(e)));
        }
    }
    conn.execute("VACUUM INTO ?1", [to])?;
    Ok(())
}

/// What lazy-commit held back is written when the file closes (`init-soar`, `epmem
/// --init`, the agent's end).
impl Drop for Disk {
    fn drop(&mut self) {
        if !self.conn.is_autocommit() {
            // Nothing can be reported from here; a failing commit leaves the file as it
            // was at the last commit.
            let _ = self.conn.execute_batch("COMMIT");
        }
    }
}

/// The bytes of a `page-size` setting (`8k` is 8192).
fn page_bytes(setting: &str) -> i64 {
    setting
        .trim_end_matches('k')
        .parse::<i64>()
        .map_or(8192, |k| k * 1024)
}
