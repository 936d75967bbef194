//! The counts `chunk stats` reports (Soar manual, ch. 9, `chunk`, "Chunking Statistics"):
//! what the learner did since the last `init-soar`, which clears them as 9.6 does.

use crate::ast::Head;
use crate::production::{Condition, Production, Test};

/// Learning's work and outcomes since the last `init-soar`.
#[derive(Debug, Default, Clone)]
pub struct ChunkStats {
    /// Rule firings and item instantiations backtraced through (each once per episode).
    pub firings_backtraced: u64,
    /// Instantiations made for learned rules' results (a chunk's or a justification's).
    pub learned_instantiations: u64,
    /// The stand-ins for an impasse's `^item` and `^non-numeric` WMEs: 9.6 makes one
    /// instantiation for each, every time it brings an impasse's items up to date, so that
    /// backtracing through an item reaches the acceptable preference behind it.
    pub item_instantiations: u64,
    /// Relational, disjunctive and state tests in the positive conditions of chunks.
    pub operational_constraints: u64,
    /// Relational tests met on local conditions (constraints EBC carries to the chunk).
    pub constraints_collected: u64,
    /// Those carried over into a chunk's conditions.
    pub constraints_enforced: u64,
    /// Conditions dropped from a learned rule because another one says the same.
    pub conditions_merged: u64,
    /// Chunks and justifications whose reasoning tested the absence of substate knowledge.
    pub local_negation_chunks: u64,
    pub local_negation_justifications: u64,
    /// The architecture's instantiations behind memories' retrievals.
    pub retrieval_instantiations: u64,
    /// Rules built from reasoning that went through a memory's retrieval.
    pub ltm_chunks: u64,
    pub ltm_justifications: u64,
    /// Identities of the firings backtraced for chunks (one per variable of each firing).
    pub identities_created: u64,
    /// Fields where an action's identity met the condition that tested its result.
    pub identity_propagations: u64,
    /// Such meetings where the condition tested a literal instead (the identity stops).
    pub identity_propagations_blocked: u64,
    /// Identity sets that became one.
    pub identities_joined: u64,
    pub duplicates: u64,
    pub tested_quiescence: u64,
    pub no_grounds: u64,
    pub max_chunks: u64,
    pub max_dupes: u64,
}

impl ChunkStats {
    /// The identity work of a backtrace that a chunk is built from (justifications keep
    /// their symbols and work with no identities).
    pub(crate) fn note_identities(&mut self, bt: &super::backtrace::Backtrace) {
        self.identities_created += bt.identities as u64;
        self.identity_propagations += bt.propagations as u64;
        self.identity_propagations_blocked += bt.propagations_blocked as u64;
        self.identities_joined += bt.joins as u64;
        self.constraints_collected += (bt.constraints.len() + bt.literal_constraints) as u64;
    }
}

/// The tests of a chunk's positive conditions beyond equality: relational tests,
/// disjunctions and the mark of the state it matches in.
pub(crate) fn operational_constraints(prod: &Production) -> u64 {
    fn extra(t: &Test) -> u64 {
        match t {
            Test::Equal(_) => 0,
            Test::Relational(..) | Test::Disjunction(_) => 1,
            Test::Conjunction(ts) => ts.iter().map(extra).sum(),
        }
    }
    prod.conditions
        .iter()
        .map(|c| match c {
            Condition::Positive(x) => {
                extra(&x.id) + extra(&x.attr) + extra(&x.value) + u64::from(x.goal != Head::None)
            }
            _ => 0,
        })
        .sum()
}
