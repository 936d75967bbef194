//! The episodic store (Soar manual, ch. 7, "Episodic Memory", "Episodic Storage"): not a
//! copy of working memory per episode but each WME's intervals of existence. A WME with a
//! constant value is a *constant* row `(parent node, attribute, value)`; one with an
//! identifier value is an *edge* row `(parent node, attribute, child node)`, the child
//! being a node that stands for the identifier. Each row keeps the episodes it was in as
//! closed ranges plus the open one it is in now. Rows are numbered as 9.6 numbers them,
//! which fixes the order in which episodes are printed and rebuilt.

use super::timeline::Timeline;
use rustc_hash::FxHashMap;

/// The node of the top state: every episode hangs from it.
pub const ROOT: i64 = 0;

/// The attribute an acceptable-preference WME is stored under (9.6 prints it
/// `operator*`); constant 0 is the root's name, `root`.
pub const ACCEPTABLE: i64 = 1;

/// A constant as the store keeps it.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum Constant {
    Str(String),
    Int(i64),
    /// The float's bits (floats are kept exactly).
    Float(u64),
}

/// The episodes one row was in.
#[derive(Debug, Clone, Default)]
pub struct Life {
    /// Closed ranges of episodes, oldest first.
    pub ranges: Vec<(i64, i64)>,
    /// The start of the range it is in now, while it is in working memory.
    pub now: Option<i64>,
    /// The last thing done to the row was to end its range (9.6's "max" flag): a WME that
    /// shows it again starts a new range.
    pub ended: bool,
}

/// One row: `(parent node, attribute, value or child node)`.
pub type Triple = (i64, i64, i64);

/// A table of rows (constants or edges), numbered from 1 in the order they are made.
#[derive(Debug, Default)]
pub struct Rows {
    pub triples: Vec<Triple>,
    pub lives: Vec<Life>,
    /// The rows by `(parent, attribute)`, for queries.
    pub by_parent: FxHashMap<(i64, i64), Vec<i64>>,
    /// The rows by `(attribute, value)` (a constant's value, an edge's child), for the
    /// rows a query can match under any parent.
    pub by_attr_value: FxHashMap<(i64, i64), Vec<i64>>,
    /// The rows by attribute.
    pub by_attr: FxHashMap<i64, Vec<i64>>,
    /// Constants only: the row of a triple (edges may repeat a triple).
    index: FxHashMap<Triple, i64>,
    /// The rows of each episode, kept beside `lives` as ranges open and close.
    timeline: Timeline,
    /// Edges only: the long-term identifier (`@N`) the child stood for in the range that
    /// started at an episode, by (row, first episode); absent for none.
    ltis: FxHashMap<(i64, i64), i64>,
}

impl Rows {
    /// Adds a row; its number.
    pub fn add(&mut self, t: Triple) -> i64 {
        self.triples.push(t);
        self.lives.push(Life::default());
        let id = self.triples.len() as i64;
        self.by_parent.entry((t.0, t.1)).or_default().push(id);
        self.by_attr_value.entry((t.1, t.2)).or_default().push(id);
        self.by_attr.entry(t.1).or_default().push(id);
        self.index.entry(t).or_insert(id);
        id
    }

    /// Adds the row a file numbers `id`; rows the file skipped are kept as rows that
    /// nothing matches, so that the numbers stay the file's.
    pub fn load(&mut self, id: i64, t: Triple) {
        while (self.triples.len() as i64) < id - 1 {
            self.add((-1, -1, -1));
        }
        self.add(t);
    }

    /// How many rows there are.
    pub fn count(&self) -> usize {
        self.triples.len()
    }

    /// The first row with this triple.
    pub fn find(&self, t: &Triple) -> Option<i64> {
        self.index.get(t).copied()
    }

    pub fn triple(&self, id: i64) -> Triple {
        self.triples[(id - 1) as usize]
    }

    pub fn life(&self, id: i64) -> &Life {
        &self.lives[(id - 1) as usize]
    }

    /// A row's life to change. Ranges changed here, not through [`Rows::open`] and
    /// [`Rows::close`], are not in the episodes' index until [`Rows::reindex`].
    pub fn life_mut(&mut self, id: i64) -> &mut Life {
        &mut self.lives[(id - 1) as usize]
    }

    /// Files every row's ranges in the episodes' index again, for lives set directly
    /// (a store read back from elsewhere).
    pub fn reindex(&mut self) {
        let mut timeline = Timeline::default();
        for (k, life) in self.lives.iter().enumerate() {
            let id = k as i64 + 1;
            for &(start, end) in &life.ranges {
                timeline.open(id, start);
                timeline.close(id, end);
            }
            if let Some(start) = life.now {
                timeline.open(id, start);
            }
        }
        self.timeline = timeline;
    }

    /// Row `id` enters working memory at episode `start`: its open range begins.
    pub fn open(&mut self, id: i64, start: i64) {
        self.life_mut(id).now = Some(start);
        self.timeline.open(id, start);
    }

    /// Row `id` left working memory after episode `end`: its open range, if any, closes.
    pub fn close(&mut self, id: i64, end: i64) {
        let life = self.life_mut(id);
        if let Some(start) = life.now.take() {
            life.ranges.push((start, end));
            self.timeline.close(id, end);
        }
    }

    /// Records that row `id`'s range starting at episode `start` links its child to
    /// long-term identifier `lti` (0: none).
    pub fn set_lti(&mut self, id: i64, start: i64, lti: i64) {
        if lti != 0 {
            self.ltis.insert((id, start), lti);
        }
    }

    /// The long-term identifier row `id`'s child stood for in episode `t` (0: none), as
    /// 9.6 keeps it with each range.
    pub fn lti_at(&self, id: i64, t: i64) -> i64 {
        if self.ltis.is_empty() {
            return 0;
        }
        let life = self.life(id);
        let start = match life.now {
            Some(s) if s <= t => Some(s),
            _ => life.ranges.iter().find(|&&(s, e)| s <= t && t <= e).map(|&(s, _)| s),
        };
        start.and_then(|s| self.ltis.get(&(id, s)).copied()).unwrap_or(0)
    }

    /// The rows in episode `t`, by number.
    pub fn at(&self, t: i64) -> Vec<i64> {
        let mut rows = Vec::new();
        self.timeline.at(t, &mut rows);
        rows.sort_unstable();
        rows
    }
}

/// The store: the symbol table, the rows, and the clock of episodes.
#[derive(Debug)]
pub struct Store {
    hash: FxHashMap<Constant, i64>,
    constants: Vec<Constant>,
    pub consts: Rows,
    pub edges: Rows,
    /// The next node for an identifier.
    pub next_node: i64,
    /// The next episode (9.6's `time` statistic): episodes are 1 to `time - 1`.
    pub time: i64,
    /// The long-term identifier of each node made for an identifier that had one.
    pub node_ltis: FxHashMap<i64, i64>,
    /// (node, long-term identifier) for stored identifiers found linked to semantic memory
    /// after their node was made, in the order found (9.6 adds an `epmem_nodes` row).
    pub later_ltis: Vec<(i64, i64)>,
}

impl Default for Store {
    fn default() -> Self {
        Store {
            hash: FxHashMap::default(),
            constants: vec![Constant::Str("root".into()), Constant::Str("operator*".into())],
            consts: Rows::default(),
            edges: Rows::default(),
            next_node: 1,
            time: 1,
            node_ltis: FxHashMap::default(),
            later_ltis: Vec::new(),
        }
    }
}

impl Store {
    /// The number of a constant, made on first use.
    pub fn hash(&mut self, c: Constant) -> i64 {
        if let Some(&h) = self.hash.get(&c) {
            return h;
        }
        let h = self.constants.len() as i64;
        self.constants.push(c.clone());
        self.hash.insert(c, h);
        h
    }

    /// Adds the constant a file numbers `id` (numbers it skipped stand for nothing).
    pub fn load_constant(&mut self, id: i64, c: Constant) {
        while (self.constants.len() as i64) < id {
            self.constants.push(Constant::Str(String::new()));
        }
        if id as usize == self.constants.len() {
            self.constants.push(c.clone());
            self.hash.entry(c).or_insert(id);
        }
    }

    /// How many constants there are (numbered from 0).
    pub fn constant_count(&self) -> usize {
        self.constants.len()
    }

    /// The number of a constant the store has seen.
    pub fn find_hash(&self, c: &Constant) -> Option<i64> {
        self.hash.get(c).copied()
    }

    pub fn constant(&self, h: i64) -> &Constant {
        &self.constants[h as usize]
    }

    /// Whether `t` is a stored episode.
    pub fn valid(&self, t: i64) -> bool {
        t >= 1 && t < self.time
    }

    /// A constant as `epmem --print` writes it.
    pub fn text(&self, h: i64) -> String {
        match self.constant(h) {
            Constant::Str(s) => s.clone(),
            Constant::Int(i) => i.to_string(),
            Constant::Float(bits) => real_text(f64::from_bits(*bits)),
        }
    }
}

/// A float as 9.6 prints it from its database: SQLite's text of a REAL, 15 significant
/// digits in C's `%g` style, with a decimal point always (`2.5`, `1.0`, `1.0e+20`).
pub fn real_text(f: f64) -> String {
    if !f.is_finite() {
        return if f.is_nan() { String::new() } else if f > 0.0 { "Inf".into() } else { "-Inf".into() };
    }
    let g = crate::printer::constants::c_general(f, 15);
    // SQLite always writes a REAL's decimal point, in the mantissa when there is an exponent.
    let split = g.find('e').unwrap_or(g.len());
    let (mantissa, exponent) = g.split_at(split);
    if mantissa.contains('.') {
        g
    } else {
        format!("{mantissa}.0{exponent}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floats_print_as_sqlite_writes_reals() {
        assert_eq!(real_text(2.5), "2.5");
        assert_eq!(real_text(1.0), "1.0");
        assert_eq!(real_text(-0.125), "-0.125");
        assert_eq!(real_text(1e20), "1.0e+20");
        assert_eq!(real_text(1.5e-7), "1.5e-07");
        assert_eq!(real_text(0.1 + 0.2), "0.3");
        assert_eq!(real_text(123456.789), "123456.789");
    }

    #[test]
    fn lives_set_directly_are_found_after_a_reindex() {
        let mut rows = Rows::default();
        for v in 0..4 {
            rows.add((0, 1, v));
        }
        rows.open(1, 1);
        rows.close(1, 3);
        rows.life_mut(2).ranges.push((2, 2));
        rows.life_mut(3).now = Some(3);
        assert_eq!(rows.at(2), [1]);
        rows.reindex();
        assert_eq!(rows.at(2), [1, 2]);
        assert_eq!(rows.at(3), [1, 3]);
        assert_eq!(rows.at(9), [3]);
    }
}
