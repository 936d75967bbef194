//! Spreading activation (Soar manual, ch. 6, "Spreading Activation"; the model of Soar
//! 9.6.5): the LTIs that have an instance in working memory are sources, and each spreads
//! to the LTIs it reaches through LTI-valued augmentations. A source's reach is found once
//! by a prioritized traversal (its "fingerprint": each recipient with the amount it got,
//! kept in `smem_likelihoods`, the paths in `smem_likelihood_trajectories`); a query adds
//! the sources' shares to its candidates' base-level activation, and a candidate that got
//! spread is ranked by the activation in `smem_current_spread_activations`.
//!
//! The amounts: a traversal starts with 1 at the source and multiplies by the continue
//! probability at each step and by the edge's weight (1 / the parent's LTI edges); paths
//! stop at the depth limit, after `spreading-limit` steps, or when the amount falls below
//! the baseline. A recipient's spread is Σ over sources of max(f · share, offset), where
//! share is its part of the source's total, f = x / (1 + x) with x = (clock)^−d (the
//! source's weight when working-memory activation does not supply one), and offset = the
//! baseline over the largest possible spread; its activation is its base-level (or, never
//! activated, ln(f)) plus ln(spread) − ln(offset).

use super::schema::ACT_LOW;
use super::store::{exec, row, DbResult, Store};
use rusqlite::{params, OptionalExtension};
use rustc_hash::FxHashMap;
use std::collections::{BTreeMap, BTreeSet};

/// The spreading parameters a calculation reads.
#[derive(Debug, Clone, Copy)]
pub struct Settings {
    pub limit: i64,
    pub depth: i64,
    pub baseline: f64,
    pub continue_probability: f64,
    pub loop_avoidance: bool,
    /// `base-decay`, for the weight of a source and the base of an unactivated LTI.
    pub decay: f64,
}

impl Settings {
    /// The settings as the parameters give them.
    pub fn of(p: &super::params::SmemParams) -> Settings {
        Settings {
            limit: p.number("spreading-limit").trunc() as i64,
            depth: p.number("spreading-depth-limit").trunc() as i64,
            baseline: p.number("spreading-baseline"),
            continue_probability: p.number("spreading-continue-probability"),
            loop_avoidance: p.on("spreading-loop-avoidance"),
            decay: p.base_decay(),
        }
    }

    /// The most spread a source can give, by the depth limit: p(1 + p)^depth.
    fn denominator(&self) -> f64 {
        let p = self.continue_probability;
        let mut d = p;
        for _ in 0..self.depth.max(0) {
            d += d * p;
        }
        d
    }

    /// The spread below which a recipient's share counts as noise.
    pub fn offset(&self) -> f64 {
        self.baseline / self.denominator()
    }

    /// x / (1 + x) for x = clock^−d: a source's weight, and (as its log) the base of an LTI
    /// never activated, as if it had been activated once when the agent began.
    pub fn unused_odds(&self, clock: i64) -> f64 {
        let x = (clock as f64).powf(-self.decay);
        x / (1.0 + x)
    }
}

/// What spreading keeps in memory between queries (as 9.6 does): the sources seen at the
/// last calculation and which recipients each gave to.
#[derive(Debug, Default)]
pub struct Spread {
    /// The LTIs with an instance in working memory when spread was last calculated.
    context: BTreeSet<i64>,
    /// Each source's recipients.
    recipients_of: BTreeMap<i64, BTreeSet<i64>>,
    /// Each recipient's number of sources.
    sources_of: FxHashMap<i64, i64>,
}

/// A binary heap ordered by its key alone, whose ties come out as those of the C++
/// standard library's `priority_queue` (libstdc++'s `push_heap`/`pop_heap`): 9.6 keeps
/// its traversal and its spread candidates in such queues, and the order of equal keys
/// decides which paths a limit cuts and which of two equal LTIs is retrieved.
#[derive(Debug)]
pub struct StdHeap<T> {
    items: Vec<(f64, T)>,
}

impl<T> Default for StdHeap<T> {
    fn default() -> Self {
        StdHeap { items: Vec::new() }
    }
}

impl<T> StdHeap<T> {
    pub fn top(&self) -> Option<&(f64, T)> {
        self.items.first()
    }

    pub fn push(&mut self, key: f64, item: T) {
        self.items.push((key, item));
        let len = self.items.len();
        self.sift_up(len - 1, 0);
    }

    /// Moves the element at `hole` up while its parent's key is smaller.
    fn sift_up(&mut self, mut hole: usize, top: usize) {
        while hole > top {
            let parent = (hole - 1) / 2;
            if self.items[parent].0 < self.items[hole].0 {
                self.items.swap(parent, hole);
                hole = parent;
            } else {
                break;
            }
        }
    }

    pub fn pop(&mut self) -> Option<(f64, T)> {
        let n = self.items.len();
        if n == 0 {
            return None;
        }
        // The last element goes to the hole left by the top, which first sinks to a leaf
        // along the larger children (the right one on a tie).
        self.items.swap(0, n - 1);
        let out = self.items.pop();
        let len = n - 1;
        if len > 1 {
            let mut hole = 0;
            let mut second = 0;
            while second < (len - 1) / 2 {
                second = 2 * (second + 1);
                if self.items[second].0 < self.items[second - 1].0 {
                    second -= 1;
                }
                self.items.swap(hole, second);
                hole = second;
            }
            if len.is_multiple_of(2) && second == (len - 2) / 2 {
                second = 2 * (second + 1);
                self.items.swap(hole, second - 1);
                hole = second - 1;
            }
            self.sift_up(hole, 0);
        }
        out
    }
}

/// What a query's lead cue element asks, by symbol numbers: an attribute, and a constant
/// or LTI value (0 for none).
#[derive(Debug, Clone, Copy)]
pub struct Lead {
    pub attr: i64,
    pub constant: Option<i64>,
    pub lti: Option<i64>,
}

impl Lead {
    /// The condition on `smem_augmentations` (with the table's name `t`), and its values.
    fn condition(&self, t: &str) -> (String, Vec<i64>) {
        match (self.constant, self.lti) {
            (Some(c), _) => (
                format!("{t}attribute_s_id=?1 AND {t}value_constant_s_id=?2 AND {t}value_lti_id=0"),
                vec![self.attr, c],
            ),
            (None, Some(l)) => (
                format!("{t}attribute_s_id=?1 AND {t}value_constant_s_id=0 AND {t}value_lti_id=?2"),
                vec![self.attr, l],
            ),
            (None, None) => (format!("{t}attribute_s_id=?1"), vec![self.attr]),
        }
    }
}

impl Store {
    /// Whether spread activation is kept for an LTI, and its row (base, spread, value).
    pub fn spread_row(&self, lti: i64) -> DbResult<Option<(f64, f64, f64)>> {
        row(
            &self.conn,
            "SELECT activation_base_level, activation_spread, activation_value FROM smem_current_spread_activations WHERE lti_id = ?1",
            [lti],
            |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?)),
        )
        .optional()
        .map_err(super::store::db_error)
    }

    /// The LTIs ranked by spread activation.
    pub fn spread_ltis(&self) -> DbResult<rustc_hash::FxHashSet<i64>> {
        let mut st = self
            .conn
            .prepare_cached("SELECT lti_id FROM smem_current_spread_activations")
            .map_err(super::store::db_error)?;
        let rows = st
            .query_map([], |r| r.get::<_, i64>(0))
            .and_then(Iterator::collect)
            .map_err(super::store::db_error)?;
        Ok(rows)
    }

    /// The LTIs with spread activation that have the lead element, with that activation,
    /// in the order 9.6's statement reads them.
    pub fn spread_candidates(&self, lead: &Lead) -> DbResult<Vec<(i64, f64)>> {
        let (cond, args) = lead.condition("");
        let sql = format!(
            "SELECT smem_augmentations.lti_id, smem_current_spread_activations.activation_value FROM smem_augmentations INNER JOIN smem_current_spread_activations ON smem_augmentations.lti_id = smem_current_spread_activations.lti_id WHERE {cond}"
        );
        let mut st = self.conn.prepare_cached(&sql).map_err(super::store::db_error)?;
        let rows = st
            .query_map(rusqlite::params_from_iter(args), |r| Ok((r.get(0)?, r.get(1)?)))
            .and_then(Iterator::collect)
            .map_err(super::store::db_error)?;
        Ok(rows)
    }

    /// Writes the activation of an LTI that has spread.
    pub fn write_spread_activation(&self, lti: i64, base: f64, spread: f64, value: f64) -> DbResult<()> {
        exec(
            &self.conn,
            "UPDATE smem_current_spread_activations SET activation_base_level = ?2, activation_spread = ?3, activation_value = ?4 WHERE lti_id = ?1",
            params![lti, base, spread, value],
        )
        .map_err(super::store::db_error)?;
        Ok(())
    }

    /// Moves an LTI's activation back from spreading's table to its own row (and, when
    /// asked, to the rank of its augmentations).
    fn spread_restore(&self, lti: i64, set_augs: bool) -> DbResult<()> {
        let Some((base, _, _)) = self.spread_row(lti)? else {
            return Ok(());
        };
        exec(
            &self.conn,
            "DELETE FROM smem_current_spread_activations WHERE lti_id = ?1",
            [lti],
        )
        .map_err(super::store::db_error)?;
        let lti_base = if base == 0.0 { ACT_LOW } else { base };
        exec(
            &self.conn,
            "UPDATE smem_lti SET activation_base_level = ?2, activation_spread = 0.0, activation_value = ?3 WHERE lti_id = ?1",
            params![lti, lti_base, base],
        )
        .map_err(super::store::db_error)?;
        if set_augs {
            self.set_rank_activation(lti, base)?;
        }
        Ok(())
    }

    /// An LTI's children by LTI-valued augmentation, with the edges' weights.
    fn children(&self, lti: i64) -> DbResult<Vec<(i64, f64)>> {
        let mut st = self
            .conn
            .prepare_cached(
                "SELECT value_lti_id, edge_weight FROM smem_augmentations WHERE lti_id=?1 AND value_constant_s_id=0 ORDER BY value_lti_id, edge_weight",
            )
            .map_err(super::store::db_error)?;
        let rows = st
            .query_map([lti], |r| Ok((r.get(0)?, r.get::<_, Option<f64>>(1)?.unwrap_or(0.0))))
            .and_then(Iterator::collect)
            .map_err(super::store::db_error)?;
        Ok(rows)
    }

    /// The traversal from `source`: its paths into `smem_likelihood_trajectories`, what
    /// each recipient got into `smem_likelihoods`, and their sum into
    /// `smem_trajectory_num`.
    fn fingerprint(&self, source: i64, s: &Settings) -> DbResult<()> {
        let e = super::store::db_error;
        for sql in [
            "DELETE FROM smem_likelihood_trajectories WHERE lti_id=?1",
            "DELETE FROM smem_likelihoods WHERE lti_j=?1",
            "DELETE FROM smem_trajectory_num WHERE lti_id=?1",
        ] {
            exec(&self.conn, sql, [source]).map_err(e)?;
        }
        let mut children: FxHashMap<i64, Vec<(i64, f64)>> = FxHashMap::default();
        // A path keeps each LTI with the weight of the edge it came by, as 9.6 compares
        // them for loop avoidance.
        let mut queue: StdHeap<Vec<(i64, f64)>> = StdHeap::default();
        queue.push(1.0, vec![(source, 1.0)]);
        let mut spread: BTreeMap<i64, f64> = BTreeMap::new();
        let mut count = 0i64;
        let mut any = false;
        let p = s.continue_probability;
        while count < s.limit {
            let Some((amount, path)) = queue.pop() else {
                break;
            };
            let Some(&(last, _)) = path.last() else {
                continue;
            };
            let kids = match children.get(&last) {
                Some(k) => k.clone(),
                None => {
                    let k = self.children(last)?;
                    children.insert(last, k.clone());
                    k
                }
            };
            let here = p * amount;
            for (child, weight) in kids {
                if count >= s.limit || here <= s.baseline {
                    break;
                }
                // 9.6's loop avoidance replaces the other tests.
                let good = if s.loop_avoidance {
                    !path.contains(&(child, weight))
                } else {
                    child != 0 && weight >= s.baseline
                };
                if !good {
                    continue;
                }
                *spread.entry(child).or_insert(0.0) += here * weight;
                let mut next = path.clone();
                next.push((child, weight));
                let mut cols = [0i64; 11];
                for (slot, (l, _)) in cols.iter_mut().zip(&next) {
                    *slot = *l;
                }
                exec(
                    &self.conn,
                    "INSERT INTO smem_likelihood_trajectories (lti_id, lti1, lti2, lti3, lti4, lti5, lti6, lti7, lti8, lti9, lti10, valid_bit) VALUES (?1,?2,?3,?4,?5,?6,?7,?8,?9,?10,?11,1)",
                    rusqlite::params_from_iter(cols),
                )
                .map_err(e)?;
                any = true;
                count += 1;
                if (next.len() as i64) < s.depth + 1 && count < s.limit && p * here * weight > s.baseline {
                    queue.push(here * weight, next);
                }
            }
        }
        for (&recipient, &amount) in &spread {
            exec(
                &self.conn,
                "INSERT INTO smem_likelihoods (lti_j,lti_i,num_appearances_i_j) VALUES (?1,?2,?3)",
                params![source, recipient, amount],
            )
            .map_err(e)?;
        }
        if !any {
            exec(
                &self.conn,
                "INSERT INTO smem_likelihood_trajectories (lti_id, lti1, lti2, lti3, lti4, lti5, lti6, lti7, lti8, lti9, lti10, valid_bit) VALUES (?1,0,0,0,0,0,0,0,0,0,0,1)",
                [source],
            )
            .map_err(e)?;
        }
        exec(
            &self.conn,
            "INSERT INTO smem_trajectory_num (lti_id, num_appearances) SELECT lti_j, SUM(num_appearances_i_j) FROM smem_likelihoods WHERE lti_j=?1 GROUP BY lti_j",
            [source],
        )
        .map_err(e)?;
        Ok(())
    }

    /// Whether a source's traversal is missing or was made invalid by a change to the
    /// augmentations it went through.
    fn fingerprint_stale(&self, source: i64) -> DbResult<bool> {
        let e = super::store::db_error;
        let invalid = row(
            &self.conn,
            "SELECT 1 FROM smem_likelihood_trajectories WHERE lti_id=?1 AND valid_bit=0",
            [source],
            |_| Ok(()),
        )
        .optional()
        .map_err(e)?
        .is_some();
        let valid = row(
            &self.conn,
            "SELECT 1 FROM smem_likelihood_trajectories WHERE lti_id=?1 AND valid_bit=1",
            [source],
            |_| Ok(()),
        )
        .optional()
        .map_err(e)?
        .is_some();
        Ok(invalid || !valid)
    }

    /// After `lti` gained an LTI-valued augmentation: the traversals that went on from it
    /// are made again when next needed.
    pub fn invalidate_through(&self, lti: i64) -> DbResult<()> {
        self.invalidate_steps("!=0", [lti])
    }

    /// After the edge `parent` → `child` went: the traversals that used it.
    pub fn invalidate_edge(&self, parent: i64, child: i64) -> DbResult<()> {
        self.invalidate_steps("=?2", [parent, child])
    }

    /// Marks invalid the traversals with a step from LTI `?1` to a next LTI that meets
    /// `next` (an SQL test on the next column).
    fn invalidate_steps<P: rusqlite::Params>(&self, next: &str, params: P) -> DbResult<()> {
        if !self.has_trajectories()? {
            return Ok(());
        }
        let mut cond = vec![format!("(lti_id=?1 AND lti1{next})")];
        for i in 1..10 {
            cond.push(format!("(lti{i}=?1 AND lti{}{next})", i + 1));
        }
        exec(
            &self.conn,
            &format!(
                "UPDATE smem_likelihood_trajectories SET valid_bit=0 WHERE {}",
                cond.join(" OR ")
            ),
            params,
        )
        .map_err(super::store::db_error)?;
        Ok(())
    }

    fn has_trajectories(&self) -> DbResult<bool> {
        if !self.spread_used.get() {
            return Ok(false);
        }
        Ok(row(
            &self.conn,
            "SELECT 1 FROM smem_likelihood_trajectories LIMIT 1",
            [],
            |_| Ok(()),
        )
        .optional()
        .map_err(super::store::db_error)?
        .is_some())
    }

    /// Up to 400 LTIs with the lead element, and whether there were that many (9.6's cheap
    /// look at a query's candidates before it spreads).
    fn lead_ltis(&self, lead: &Lead) -> DbResult<(BTreeSet<i64>, usize)> {
        let (cond, args) = lead.condition("");
        let sql = format!("SELECT lti_id FROM smem_augmentations WHERE {cond} LIMIT 400");
        let mut st = self.conn.prepare_cached(&sql).map_err(super::store::db_error)?;
        let rows: Vec<i64> = st
            .query_map(rusqlite::params_from_iter(args), |r| r.get(0))
            .and_then(Iterator::collect)
            .map_err(super::store::db_error)?;
        let n = rows.len();
        Ok((rows.into_iter().collect(), n))
    }

    fn has_lead(&self, lti: i64, lead: &Lead) -> DbResult<bool> {
        let value = match (lead.constant, lead.lti) {
            (Some(c), _) => super::memo::AugValue::Const(c),
            (None, Some(l)) => super::memo::AugValue::Lti(l),
            (None, None) => super::memo::AugValue::Any,
        };
        self.has_aug(lti, lead.attr, value)
    }
}

impl Spread {
    /// 9.6's calculation before a query: the sources that came into working memory
    /// (`context`) get their fingerprints into `smem_current_spread`, those that left take
    /// theirs out (their recipients without another source go back to their base-level),
    /// and the candidates get their spread activation. Nothing happens unless the lead
    /// element has more than one LTI.
    pub fn calculate(
        &mut self,
        store: &Store,
        s: &Settings,
        context: &BTreeSet<i64>,
        lead: &Lead,
    ) -> DbResult<()> {
        let e = super::store::db_error;
        let (found, rows) = store.lead_ltis(lead)?;
        if rows <= 1 {
            return Ok(());
        }
        store.spread_used.set(true);
        let additions: Vec<i64> = context.difference(&self.context).copied().collect();
        let removals: Vec<i64> = self.context.difference(context).copied().collect();
        self.context = context.clone();
        for &source in &additions {
            if store.fingerprint_stale(source)? {
                store.fingerprint(source, s)?;
            }
        }
        for &source in &additions {
            let mut st = store
                .conn
                .prepare_cached(
                    "SELECT lti_i,num_appearances_i_j,num_appearances FROM smem_likelihoods INNER JOIN smem_trajectory_num ON lti_id=lti_j WHERE lti_j=?1",
                )
                .map_err(e)?;
            let prints: Vec<(i64, f64, f64)> = st
                .query_map([source], |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?)))
                .and_then(Iterator::collect)
                .map_err(e)?;
            drop(st);
            for (recipient, n_ij, n_j) in prints {
                exec(
                    &store.conn,
                    "INSERT OR IGNORE INTO smem_current_spread(lti_id,num_appearances_i_j,num_appearances,sign,lti_source) VALUES (?1,?2,?3,1,?4)",
                    params![recipient, n_ij, n_j, source],
                )
                .map_err(e)?;
                self.recipients_of.entry(source).or_default().insert(recipient);
                *self.sources_of.entry(recipient).or_insert(0) += 1;
            }
        }
        for &source in &removals {
            if let Some(recipients) = self.recipients_of.remove(&source) {
                for r in recipients {
                    let n = self.sources_of.get(&r).copied().unwrap_or(0);
                    if n <= 1 {
                        self.sources_of.remove(&r);
                        store.spread_restore(r, true)?;
                    } else {
                        self.sources_of.insert(r, n - 1);
                    }
                }
            }
            exec(
                &store.conn,
                "DELETE FROM smem_current_spread WHERE lti_source=?1",
                [source],
            )
            .map_err(e)?;
        }
        let candidates: BTreeSet<i64> = if rows >= 400 {
            let mut st = store
                .conn
                .prepare_cached("SELECT lti_id from smem_current_spread")
                .map_err(e)?;
            let all: Vec<i64> = st
                .query_map([], |r| r.get(0))
                .and_then(Iterator::collect)
                .map_err(e)?;
            drop(st);
            let mut kept = BTreeSet::new();
            for l in all {
                if store.has_lead(l, lead)? {
                    kept.insert(l);
                }
            }
            kept
        } else {
            found
        };
        let clock = store.var(super::schema::var::MAX_CYCLE)?;
        let factor = s.unused_odds(clock);
        let offset = s.offset();
        for &c in &candidates {
            store.spread_restore(c, false)?;
            let mut st = store
                .conn
                .prepare_cached(
                    "SELECT num_appearances,num_appearances_i_j FROM smem_current_spread WHERE lti_id = ?1",
                )
                .map_err(e)?;
            let shares: Vec<(f64, f64)> = st
                .query_map([c], |r| Ok((r.get(0)?, r.get(1)?)))
                .and_then(Iterator::collect)
                .map_err(e)?;
            drop(st);
            let mut spread = 0.0;
            for (n_j, n_ij) in shares {
                if n_ij == 0.0 {
                    break;
                }
                let prev_base = match store.spread_row(c)? {
                    Some((b, _, _)) => b,
                    None => store.base_activation(c)?,
                };
                let raw = factor * (n_ij / n_j);
                let more = if raw > offset { raw } else { offset };
                spread = if spread == 0.0 { more } else { more + spread };
                let modified = spread.ln() - offset.ln();
                let base = if prev_base == ACT_LOW || prev_base == 0.0 {
                    factor.ln()
                } else {
                    prev_base
                };
                let kept_base = if prev_base == 0.0 { ACT_LOW } else { prev_base };
                exec(
                    &store.conn,
                    "INSERT OR REPLACE INTO smem_current_spread_activations (lti_id, activation_base_level, activation_spread, activation_value) VALUES (?1,?2,?3,?4)",
                    params![c, kept_base, spread, modified + base],
                )
                .map_err(e)?;
            }
        }
        Ok(())
    }
}
