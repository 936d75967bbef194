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
//! command.

mod gq;
pub mod params;
mod template;
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
