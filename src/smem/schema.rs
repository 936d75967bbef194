//! The tables of 9.6.5's semantic-memory database (schema version 3.0, as the official
//! kernel writes it: observed with `sqlite_master` on a file it made), so that a file
//! written by either kernel opens in the other. Data only.

/// The schema's version, in the `versions` table under `smem_schema`.
pub const VERSION: &str = "3.0";

/// The statements that make an empty store, in 9.6's order.
pub const CREATE: &[&str] = &[
    "CREATE TABLE versions (system TEXT PRIMARY KEY,version_number TEXT)",
    "CREATE TABLE smem_persistent_variables (variable_id INTEGER PRIMARY KEY,variable_value INTEGER)",
    "CREATE TABLE smem_symbols_type (s_id INTEGER PRIMARY KEY, symbol_type INTEGER)",
    "CREATE TABLE smem_symbols_integer (s_id INTEGER PRIMARY KEY, symbol_value INTEGER)",
    "CREATE TABLE smem_symbols_float (s_id INTEGER PRIMARY KEY, symbol_value REAL)",
    "CREATE TABLE smem_symbols_string (s_id INTEGER PRIMARY KEY, symbol_value TEXT)",
    "CREATE TABLE smem_lti (lti_id INTEGER PRIMARY KEY, total_augmentations INTEGER, activation_base_level REAL, activations_total REAL, activations_last INTEGER, activations_first INTEGER, activation_spread REAL, activation_value REAL, lti_augmentations INTEGER)",
    "CREATE TABLE smem_lti_alias (alias TEXT PRIMARY KEY, lti_id INTEGER)",
    "CREATE TABLE smem_activation_history (lti_id INTEGER PRIMARY KEY, t1 INTEGER, t2 INTEGER, t3 INTEGER, t4 INTEGER, t5 INTEGER, t6 INTEGER, t7 INTEGER, t8 INTEGER, t9 INTEGER, t10 INTEGER, touch1 REAL, touch2 REAL, touch3 REAL, touch4 REAL, touch5 REAL, touch6 REAL, touch7 REAL, touch8 REAL, touch9 REAL, touch10 REAL)",
    "CREATE TABLE smem_augmentations (lti_id INTEGER, attribute_s_id INTEGER, value_constant_s_id INTEGER, value_lti_id INTEGER, activation_value REAL, edge_weight REAL)",
    "CREATE TABLE smem_attribute_frequency (attribute_s_id INTEGER PRIMARY KEY, edge_frequency INTEGER)",
    "CREATE TABLE smem_wmes_constant_frequency (attribute_s_id INTEGER, value_constant_s_id INTEGER, edge_frequency INTEGER)",
    "CREATE TABLE smem_wmes_lti_frequency (attribute_s_id INTEGER, value_lti_id INTEGER, edge_frequency INTEGER)",
    "CREATE TABLE smem_ascii (ascii_num INTEGER PRIMARY KEY, ascii_chr TEXT)",
    "CREATE TABLE smem_prohibited (lti_id INTEGER PRIMARY KEY, prohibited INTEGER, dirty INTEGER)",
    "CREATE TABLE smem_constants_store (smem_act_max REAL, smem_act_low REAL)",
    "CREATE TABLE smem_likelihood_trajectories (lti_id INTEGER, lti1 INTEGER, lti2 INTEGER, lti3 INTEGER, lti4 INTEGER, lti5 INTEGER, lti6 INTEGER, lti7 INTEGER, lti8 INTEGER, lti9 INTEGER, lti10 INTEGER, valid_bit INTEGER)",
    "CREATE TABLE smem_likelihoods (lti_j INTEGER, lti_i INTEGER, num_appearances_i_j REAL, PRIMARY KEY (lti_j, lti_i)) WITHOUT ROWID",
    "CREATE TABLE smem_trajectory_num (lti_id INTEGER PRIMARY KEY, num_appearances REAL)",
    "CREATE TABLE smem_current_spread (lti_id INTEGER, num_appearances_i_j REAL, num_appearances REAL, lti_source INTEGER, sign INTEGER, PRIMARY KEY (lti_source, lti_id)) WITHOUT ROWID",
    "CREATE TABLE smem_uncommitted_spread (lti_id INTEGER, num_appearances_i_j REAL, num_appearances REAL, lti_source INTEGER, sign INTEGER, PRIMARY KEY (lti_source, lti_id)) WITHOUT ROWID",
    "CREATE TABLE smem_committed_spread (lti_id INTEGER, num_appearances_i_j REAL, num_appearances REAL, lti_source INTEGER, PRIMARY KEY (lti_source, lti_id)) WITHOUT ROWID",
    "CREATE TABLE smem_current_spread_activations (lti_id INTEGER PRIMARY KEY, activation_base_level REAL, activation_spread REAL, activation_value REAL)",
    "CREATE TABLE smem_to_delete (lti_id INTEGER PRIMARY KEY)",
    "CREATE TABLE smem_invalid_parents (lti_id INTEGER PRIMARY KEY) WITHOUT ROWID",
    "CREATE UNIQUE INDEX smem_symbols_int_const ON smem_symbols_integer (symbol_value)",
    "CREATE UNIQUE INDEX smem_symbols_float_const ON smem_symbols_float (symbol_value)",
    "CREATE UNIQUE INDEX smem_symbols_str_const ON smem_symbols_string (symbol_value)",
    "CREATE INDEX smem_lti_t ON smem_lti (activations_last)",
    "CREATE INDEX smem_augmentations_parent_attr_val_lti ON smem_augmentations (lti_id, attribute_s_id, value_constant_s_id, value_lti_id, edge_weight)",
    "CREATE INDEX smem_augmentations_attr_val_lti_cycle ON smem_augmentations (attribute_s_id, value_constant_s_id, value_lti_id, activation_value)",
    "CREATE INDEX smem_augmentations_attr_cycle ON smem_augmentations (attribute_s_id, activation_value)",
    "CREATE UNIQUE INDEX smem_wmes_constant_frequency_attr_val ON smem_wmes_constant_frequency (attribute_s_id, value_constant_s_id)",
    "CREATE UNIQUE INDEX smem_ct_lti_attr_val ON smem_wmes_lti_frequency (attribute_s_id, value_lti_id)",
    "CREATE INDEX smem_augmentations_parent_val_lti ON smem_augmentations (lti_id, value_constant_s_id, value_lti_id, edge_weight)",
    "CREATE INDEX trajectory_lti ON smem_likelihood_trajectories (lti_id, valid_bit)",
    "CREATE INDEX lti_t1 ON smem_likelihood_trajectories (lti_id, lti1) WHERE lti1 != 0",
    "CREATE INDEX lti_t2 ON smem_likelihood_trajectories (lti1, lti2) WHERE lti2 != 0",
    "CREATE INDEX lti_t3 ON smem_likelihood_trajectories (lti2, lti3) WHERE lti3 != 0",
    "CREATE INDEX lti_t4 ON smem_likelihood_trajectories (lti3, lti4) WHERE lti4 != 0",
    "CREATE INDEX lti_t5 ON smem_likelihood_trajectories (lti4, lti5) WHERE lti5 != 0",
    "CREATE INDEX lti_t6 ON smem_likelihood_trajectories (lti5, lti6) WHERE lti6 != 0",
    "CREATE INDEX lti_t7 ON smem_likelihood_trajectories (lti6, lti7) WHERE lti7 != 0",
    "CREATE INDEX lti_t8 ON smem_likelihood_trajectories (lti7, lti8) WHERE lti8 != 0",
    "CREATE INDEX lti_t9 ON smem_likelihood_trajectories (lti8, lti9) WHERE lti9 != 0",
    "CREATE INDEX lti_t10 ON smem_likelihood_trajectories (lti9, lti10) WHERE lti10 != 0",
    "CREATE INDEX lti_t12 ON smem_likelihood_trajectories (lti_id, lti1) WHERE lti2=0",
    "CREATE INDEX lti_t23 ON smem_likelihood_trajectories (lti_id, lti2) WHERE lti3=0",
    "CREATE INDEX lti_t34 ON smem_likelihood_trajectories (lti_id, lti3) WHERE lti4=0",
    "CREATE INDEX lti_t45 ON smem_likelihood_trajectories (lti_id, lti4) WHERE lti5=0",
    "CREATE INDEX lti_t56 ON smem_likelihood_trajectories (lti_id, lti5) WHERE lti6=0",
    "CREATE INDEX lti_t67 ON smem_likelihood_trajectories (lti_id, lti6) WHERE lti7=0",
    "CREATE INDEX lti_t78 ON smem_likelihood_trajectories (lti_id, lti7) WHERE lti8=0",
    "CREATE INDEX lti_t89 ON smem_likelihood_trajectories (lti_id, lti8) WHERE lti9=0",
    "CREATE INDEX lti_t910 ON smem_likelihood_trajectories (lti_id, lti9) WHERE lti10=0",
    "CREATE INDEX lti_tid10 ON smem_likelihood_trajectories (lti_id, lti10) WHERE lti10!=0",
    "CREATE INDEX lti_source ON smem_uncommitted_spread (lti_source)",
];

/// The activation an augmentation has before its LTI is first activated (9.6's
/// `smem_act_low`, kept in `smem_constants_store`).
pub const ACT_LOW: f64 = -1_000_000_000.0;

/// The persistent variables' keys in `smem_persistent_variables`.
pub mod var {
    /// The activation clock (the next activation's time).
    pub const MAX_CYCLE: i64 = 0;
    /// How many LTIs the store holds.
    pub const NODES: i64 = 1;
    /// How many augmentations it holds.
    pub const EDGES: i64 = 2;
    /// The `thresh` parameter the store was written with.
    pub const THRESH: i64 = 3;
    /// The activation mode it was written with (0 recency, 1 frequency, 2 base-level).
    pub const MODE: i64 = 4;
}

/// The type codes of `smem_symbols_type`.
pub mod kind {
    pub const STR: i64 = 2;
    pub const INT: i64 = 3;
    pub const FLOAT: i64 = 4;
}
