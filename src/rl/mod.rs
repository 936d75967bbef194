//! Reinforcement learning (Soar manual, ch. 5, "Reinforcement Learning"): the state it
//! keeps. RL rules are the rules whose right-hand side is a single numeric-indifferent
//! preference with a constant value (section "RL Rules", [`Production::rl_value`]); each
//! keeps its value split in an expected current reward and an expected future reward, and
//! a count of its updates. Each state keeps the RL rules of its last selected RL operator,
//! the reward collected since, the decisions without an RL operator (a gap), and its
//! eligibility traces.
//!
//! `update.rs` collects rewards and updates the rules on the agent; `gq.rs` weighs the
//! GQ(λ) policies' traces; `template.rs` makes the
//! RL rules of `:template` rules' matches; `params.rs` holds the parameters of the `rl`
//! command; `apoptosis.rs` decays learned rules' activations so that unused ones go.

mod apoptosis;
mod forgetting;
mod gq;
pub mod params;
mod template;
mod trace_graph;
mod trace_record;
mod update;
mod update_log;

pub(crate) use update_log::update_line;

use crate::production::Production;
use crate::rete::ProdId;
use crate::symbols::Sym;
use rustc_hash::FxHashMap;
use std::collections::BTreeMap;

/// What an RL rule has learned.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RuleValue {
    /// Expected current reward: starts at 0.
    pub ecr: f64,
    /// Expected future reward: starts at the rule's value.
    pub efr: f64,
    /// Updates so far (`print --rl` shows them).
    pub updates: f64,
    /// The delta-bar-delta decay's own rate (log) and its trace.
    pub dbd_beta: f64,
    pub dbd_h: f64,
    /// The GQ(λ) policies' secondary weight (starts at 0).
    pub gq_weight: f64,
}

/// One state's learning data (9.6 keeps it on the state).
#[derive(Debug, Clone, Default)]
pub struct GoalData {
    /// The RL rules whose preferences were for the operator last selected with any, with
    /// repeats when one rule gave several.
    pub prev_rules: Vec<ProdId>,
    /// The reward collected since the last update, discounted by its age.
    pub reward: f64,
    /// Decisions since the last RL operator (temporal extension).
    pub gap_age: u32,
    /// Decisions spent below this state (with `hrl-discount`).
    pub hrl_age: u32,
    /// Eligibility traces by rule, in rule order.
    pub traces: BTreeMap<ProdId, f64>,
    /// The GQ(λ) importance ratio of the operator last selected with RL rules (set
    /// whenever `prev_rules` is).
    pub rho: f64,
    /// Where the state is in its level's RL trace (`None`: at the root).
    pub trace_node: Option<usize>,
}

/// The statistics `rl --stats` prints.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct RlStats {
    pub update_error: f64,
    pub total_reward: f64,
    pub global_reward: f64,
}

/// Reinforcement learning's parameters, rules and per-state data.
#[derive(Debug, Clone, Default)]
pub struct RlState {
    pub params: params::RlParams,
    /// The loaded RL rules and their values.
    pub rules: FxHashMap<ProdId, RuleValue>,
    /// Per state, by its identifier.
    pub goals: FxHashMap<Sym, GoalData>,
    pub stats: RlStats,
    /// The importance ratio of the operator the last decision selected (GQ(λ)).
    pub selected_rho: f64,
    /// The rule each template match shape made; forgotten whenever a rule
    /// is excised.
    pub template_rules: FxHashMap<(ProdId, Vec<u64>), ProdId>,
    /// The number of the last rule a template made (`rl*<template>*<n>`); `init-soar`
    /// keeps it.
    pub template_count: u64,
    /// Reused buffers for a template match's shape and the identifiers it has met.
    shape_scratch: Vec<u64>,
    shape_ids: Vec<Sym>,
    /// The decay of learned rules while `apoptosis` is on; made with the decay and
    /// threshold of the moment it is turned on (they cannot change while it is on).
    pub rule_decay: Option<apoptosis::RuleDecay>,
    /// The RL trace of each goal level (`rl -t`).
    pub trace: trace_graph::RlTrace,
}

impl RlState {
    /// Notes a rule just loaded: an RL rule starts with its value as expected future reward.
    pub fn rule_added(&mut self, id: ProdId, p: &Production) {
        if let Some(v) = p.rl_value() {
            self.rules.insert(
                id,
                RuleValue {
                    ecr: 0.0,
                    efr: v,
                    updates: 0.0,
                    dbd_beta: -3.0,
                    dbd_h: 0.0,
                    gq_weight: 0.0,
                },
            );
        }
    }

    /// Forgets an excised rule (states that remember it pass over it).
    pub fn rule_excised(&mut self, id: ProdId) {
        self.rules.remove(&id);
        self.template_rules.clear();
        if let Some(decay) = &mut self.rule_decay {
            decay.remove(id);
        }
    }

    /// Sets a parameter of the `rl` command, as 9.6 does: turning apoptosis on starts the
    /// decay of learned rules, off drops it; its decay and threshold are fixed while on.
    pub fn set_param(&mut self, name: &str, word: &str) -> Result<(), params::SetError> {
        let apoptosis_on = self.params.apoptosis != params::Apoptosis::None;
        if apoptosis_on && matches!(name, "apoptosis-decay" | "apoptosis-thresh") {
            return Err(params::SetError::Protected);
        }
        self.params.set(name, word)?;
        match (apoptosis_on, self.params.apoptosis != params::Apoptosis::None) {
            (false, true) => {
                self.rule_decay = Some(apoptosis::RuleDecay::new(
                    self.params.apoptosis_decay,
                    self.params.apoptosis_thresh,
                ))
            }
            (true, false) => self.rule_decay = None,
            _ => {}
        }
        Ok(())
    }

    /// How many times a rule is named among the states' last RL rules.
    pub fn references_from_states(&self, id: ProdId) -> usize {
        self.goals
            .values()
            .map(|g| g.prev_rules.iter().filter(|&&r| r == id).count())
            .sum()
    }

    /// Whether apoptosis follows this learned rule's use (9.6: every chunk under
    /// `chunks`; an RL chunk only while it has had no update and no state names it).
    pub fn apoptosis_tracks(&self, id: ProdId) -> bool {
        use params::Apoptosis;
        match self.rules.get(&id) {
            None => self.params.apoptosis == Apoptosis::Chunks,
            Some(v) => {
                self.params.apoptosis != Apoptosis::None
                    && v.updates as i64 == 0
                    && self.references_from_states(id) == 0
            }
        }
    }

    pub fn is_rl_rule(&self, id: ProdId) -> bool {
        self.rules.contains_key(&id)
    }

    /// `init-soar`: the states' data and the statistics start again; the rules keep what
    /// they learned.
    pub fn reinitialize(&mut self) {
        self.goals.clear();
        self.stats = RlStats::default();
    }
}
