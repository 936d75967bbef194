//! The tables of 9.6.5's episodic-memory database (schema version 2.0, as the official
//! kernel writes it: observed with `sqlite_master` on a file it made), so that a file
//! written by either kernel opens in the other. Data only.

/// The schema's version, in the `versions` table under `epmem_schema`.
pub const VERSION: &str = "2.0";

/// The statements that make an empty store, in 9.6's order (each `IF NOT EXISTS`, since
/// the `versions` table may be shared with semantic memory).
pub const CREATE: &[&str] = &[
    "CREATE TABLE IF NOT EXISTS versions (system TEXT PRIMARY KEY,version_number TEXT)",
    "CREATE TABLE IF NOT EXISTS epmem_persistent_variables (variable_id INTEGER PRIMARY KEY,variable_value NONE)",
    "CREATE TABLE IF NOT EXISTS epmem_rit_left_nodes (rit_min INTEGER, rit_max INTEGER)",
    "CREATE TABLE IF NOT EXISTS epmem_rit_right_nodes (rit_id INTEGER)",
    "CREATE TABLE IF NOT EXISTS epmem_symbols_type (s_id INTEGER PRIMARY KEY, symbol_type INTEGER)",
    "CREATE TABLE IF NOT EXISTS epmem_symbols_integer (s_id INTEGER PRIMARY KEY, symbol_value INTEGER)",
    "CREATE TABLE IF NOT EXISTS epmem_symbols_float (s_id INTEGER PRIMARY KEY, symbol_value REAL)",
    "CREATE TABLE IF NOT EXISTS epmem_symbols_string (s_id INTEGER PRIMARY KEY, symbol_value TEXT)",
    "CREATE UNIQUE INDEX IF NOT EXISTS symbols_int_const ON epmem_symbols_integer (symbol_value)",
    "CREATE UNIQUE INDEX IF NOT EXISTS symbols_float_const ON epmem_symbols_float (symbol_value)",
    "CREATE UNIQUE INDEX IF NOT EXISTS symbols_str_const ON epmem_symbols_string (symbol_value)",
    "CREATE TABLE IF NOT EXISTS epmem_nodes (n_id INTEGER, lti_id INTEGER)",
    "CREATE TABLE IF NOT EXISTS epmem_episodes (episode_id INTEGER PRIMARY KEY)",
    "CREATE TABLE IF NOT EXISTS epmem_wmes_constant_now (wc_id INTEGER,start_episode_id INTEGER)",
    "CREATE TABLE IF NOT EXISTS epmem_wmes_identifier_now (wi_id INTEGER,start_episode_id INTEGER, lti_id INTEGER)",
    "CREATE TABLE IF NOT EXISTS epmem_wmes_constant_point (wc_id INTEGER,episode_id INTEGER)",
    "CREATE TABLE IF NOT EXISTS epmem_wmes_identifier_point (wi_id INTEGER,episode_id INTEGER, lti_id INTEGER)",
    "CREATE TABLE IF NOT EXISTS epmem_wmes_constant_range (rit_id INTEGER,start_episode_id INTEGER,end_episode_id INTEGER,wc_id INTEGER)",
    "CREATE TABLE IF NOT EXISTS epmem_wmes_identifier_range (rit_id INTEGER,start_episode_id INTEGER,end_episode_id INTEGER,wi_id INTEGER, lti_id INTEGER)",
    "CREATE TABLE IF NOT EXISTS epmem_wmes_constant (wc_id INTEGER PRIMARY KEY AUTOINCREMENT,parent_n_id INTEGER,attribute_s_id INTEGER, value_s_id INTEGER)",
    "CREATE TABLE IF NOT EXISTS epmem_wmes_identifier (wi_id INTEGER PRIMARY KEY AUTOINCREMENT,parent_n_id INTEGER,attribute_s_id INTEGER,child_n_id INTEGER, last_episode_id INTEGER)",
    "CREATE TABLE IF NOT EXISTS epmem_ascii (ascii_num INTEGER PRIMARY KEY, ascii_chr TEXT)",
    "CREATE UNIQUE INDEX IF NOT EXISTS epmem_node_lti ON epmem_nodes (n_id, lti_id)",
    "CREATE INDEX IF NOT EXISTS epmem_lti ON epmem_nodes (lti_id)",
    "CREATE INDEX IF NOT EXISTS epmem_wmes_constant_now_start ON epmem_wmes_constant_now (start_episode_id)",
    "CREATE UNIQUE INDEX IF NOT EXISTS epmem_wmes_constant_now_id_start ON epmem_wmes_constant_now (wc_id,start_episode_id DESC)",
    "CREATE INDEX IF NOT EXISTS epmem_wmes_identifier_now_start ON epmem_wmes_identifier_now (start_episode_id)",
    "CREATE UNIQUE INDEX IF NOT EXISTS epmem_wmes_identifier_now_id_start ON epmem_wmes_identifier_now (wi_id,start_episode_id DESC)",
    "CREATE UNIQUE INDEX IF NOT EXISTS epmem_wmes_constant_point_id_start ON epmem_wmes_constant_point (wc_id,episode_id DESC)",
    "CREATE INDEX IF NOT EXISTS epmem_wmes_constant_point_start ON epmem_wmes_constant_point (episode_id)",
    "CREATE UNIQUE INDEX IF NOT EXISTS epmem_wmes_identifier_point_id_start ON epmem_wmes_identifier_point (wi_id,episode_id DESC)",
    "CREATE INDEX IF NOT EXISTS epmem_wmes_identifier_point_start ON epmem_wmes_identifier_point (episode_id)",
    "CREATE INDEX IF NOT EXISTS epmem_wmes_constant_range_lower ON epmem_wmes_constant_range (rit_id,start_episode_id)",
    "CREATE INDEX IF NOT EXISTS epmem_wmes_constant_range_upper ON epmem_wmes_constant_range (rit_id,end_episode_id)",
    "CREATE UNIQUE INDEX IF NOT EXISTS epmem_wmes_constant_range_id_start ON epmem_wmes_constant_range (wc_id,start_episode_id DESC)",
    "CREATE UNIQUE INDEX IF NOT EXISTS epmem_wmes_constant_range_id_end_start ON epmem_wmes_constant_range (wc_id,end_episode_id DESC,start_episode_id)",
    "CREATE INDEX IF NOT EXISTS epmem_wmes_identifier_range_lower ON epmem_wmes_identifier_range (rit_id,start_episode_id)",
    "CREATE INDEX IF NOT EXISTS epmem_wmes_identifier_range_upper ON epmem_wmes_identifier_range (rit_id,end_episode_id)",
    "CREATE UNIQUE INDEX IF NOT EXISTS epmem_wmes_identifier_range_id_start ON epmem_wmes_identifier_range (wi_id,start_episode_id DESC)",
    "CREATE UNIQUE INDEX IF NOT EXISTS epmem_wmes_identifier_range_id_end_start ON epmem_wmes_identifier_range (wi_id,end_episode_id DESC,start_episode_id)",
    "CREATE UNIQUE INDEX IF NOT EXISTS epmem_wmes_constant_parent_attribute_value ON epmem_wmes_constant (parent_n_id,attribute_s_id,value_s_id)",
    "CREATE INDEX IF NOT EXISTS epmem_wmes_identifier_parent_attribute_last ON epmem_wmes_identifier (parent_n_id,attribute_s_id,last_episode_id)",
    "CREATE UNIQUE INDEX IF NOT EXISTS epmem_wmes_identifier_parent_attribute_child ON epmem_wmes_identifier (parent_n_id,attribute_s_id,child_n_id)",
];

/// The tables `append off` empties (9.6 drops and makes them again); `versions` stays, as
/// semantic memory may share the file.
pub const TABLES: &[&str] = &[
    "epmem_persistent_variables",
    "epmem_rit_left_nodes",
    "epmem_rit_right_nodes",
    "epmem_symbols_type",
    "epmem_symbols_integer",
    "epmem_symbols_float",
    "epmem_symbols_string",
    "epmem_nodes",
    "epmem_episodes",
    "epmem_wmes_constant_now",
    "epmem_wmes_identifier_now",
    "epmem_wmes_constant_point",
    "epmem_wmes_identifier_point",
    "epmem_wmes_constant_range",
    "epmem_wmes_identifier_range",
    "epmem_wmes_constant",
    "epmem_wmes_identifier",
    "epmem_ascii",
];

/// The keys of `epmem_persistent_variables`: the interval tree's state for constant rows
/// (0–3) and for edge rows (4–7), then the next node.
pub mod var {
    /// The first of the four variables of a tree (offset, left root, right root, least
    /// step), for constants (`kind` 0) or edges (1).
    pub const fn tree(kind: usize) -> i64 {
        (kind * 4) as i64
    }
    /// The number the next identifier's node gets.
    pub const NEXT_NODE: i64 = 8;
}

/// The type codes of `epmem_symbols_type`.
pub mod kind {
    pub const STR: i64 = 2;
    pub const INT: i64 = 3;
    pub const FLOAT: i64 = 4;
}

/// The interval tree's offset before its first interval (9.6's `EPMEM_RIT_OFFSET_INIT`).
pub const OFFSET_INIT: i64 = -1;

/// The last episode of an edge that is still in working memory (`last_episode_id`).
pub const OPEN: i64 = i64::MAX;
