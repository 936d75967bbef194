//! What the network is made of, for `stats --rete` and `stats --memory` (Soar manual,
//! ch. 9, `stats`).
//!
//! 9.6 counts its beta nodes by type. It keeps a beta memory per hash key below the node
//! of a rule's previous condition (or below its dummy top node, for first conditions), and
//! folds a memory with a single child, a positive join, into one "mem-pos" node; beside the
//! actual counts it reports what they would be without that folding. rusoar's network
//! joins first conditions from the root, and a condition after a negation or an NCC from
//! that node, with no memory between: [`Rete::node_counts`] counts the memories 9.6 would
//! hold there. A node is "unhashed" when its join has no identifier-equality test to index
//! its memories on (a rule's first condition, or one not linked to the conditions before
//! it). Justifications are not in rusoar's network (see `AgentCore::match_wme_now`): their
//! nodes, which 9.6 counts, are not counted.

use super::{Kind, NodeId, Rete};
use crate::pools::{hash_table_bytes, Pool};

/// Beta nodes by 9.6's node types.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct NodeCounts {
    pub unhashed_memory: u64,
    pub memory: u64,
    pub unhashed_mem_pos: u64,
    pub mem_pos: u64,
    pub unhashed_negative: u64,
    pub negative: u64,
    pub unhashed_positive: u64,
    pub positive: u64,
    pub dummy_top: u64,
    pub ncc: u64,
    pub ncc_partner: u64,
    pub production: u64,
}

impl NodeCounts {
    /// The counts with every mem-pos node split into its memory and its positive join.
    pub fn unmerged(&self) -> NodeCounts {
        NodeCounts {
            unhashed_memory: self.unhashed_memory + self.unhashed_mem_pos,
            memory: self.memory + self.mem_pos,
            unhashed_mem_pos: 0,
            mem_pos: 0,
            unhashed_positive: self.unhashed_positive + self.unhashed_mem_pos,
            positive: self.positive + self.mem_pos,
            ..*self
        }
    }

    pub fn total(&self) -> u64 {
        self.unhashed_memory
            + self.memory
            + self.unhashed_mem_pos
            + self.mem_pos
            + self.unhashed_negative
            + self.negative
            + self.unhashed_positive
            + self.positive
            + self.dummy_top
            + self.ncc
            + self.ncc_partner
            + self.production
    }
}

impl Rete {
    /// The node a join's memory hangs from in 9.6: a positive condition's memory sits
    /// below the node of the condition before it (a join, a negative node, a conjunctive
    /// negation) or below the dummy top node. rusoar joins from the memory below such a
    /// join, or from the root, a negative node or an NCC node itself; the memory that
    /// rusoar keeps below a join for an NCC's subnetwork is not one of 9.6's, whose
    /// subnetwork's first join has its memory below that join too.
    fn memory_parent(&self, join: NodeId) -> NodeId {
        let parent = self.nodes[join].parent;
        match self.nodes[parent].kind {
            Kind::Memory => self.nodes[parent].parent,
            _ => parent,
        }
    }

    /// The live beta nodes by 9.6's node types (see the module comment). 9.6 keeps one
    /// memory per hash key below a node, shared by the joins with that key; a memory with
    /// a single join is folded into a mem-pos node.
    pub fn node_counts(&self) -> NodeCounts {
        let mut c = NodeCounts::default();
        // 9.6's memories: (the node above, the joins' hash key) → how many joins.
        let mut memories: rustc_hash::FxHashMap<(NodeId, super::HashKey), u64> =
            Default::default();
        for (i, node) in self.nodes.iter().enumerate() {
            if !node.alive {
                continue;
            }
            let hashed = node.hash.get().is_some();
            let pick = |hashed_count: &mut u64, unhashed_count: &mut u64| {
                if hashed {
                    *hashed_count += 1;
                } else {
                    *unhashed_count += 1;
                }
            };
            match node.kind {
                Kind::Root => c.dummy_top += 1,
                // Counted through their joins.
                Kind::Memory => {}
                Kind::Join { .. } => {
                    let above = self.memory_parent(NodeId::from_index(i));
                    *memories.entry((above, node.hash)).or_default() += 1;
                }
                Kind::Negative { .. } => pick(&mut c.negative, &mut c.unhashed_negative),
                Kind::Ncc { .. } => c.ncc += 1,
                Kind::NccPartner { .. } => c.ncc_partner += 1,
                Kind::Production { .. } => c.production += 1,
            }
        }
        for ((_, key), joins) in memories {
            let hashed = key.get().is_some();
            match (joins, hashed) {
                (1, true) => c.mem_pos += 1,
                (1, false) => c.unhashed_mem_pos += 1,
                (n, true) => {
                    c.memory += 1;
                    c.positive += n;
                }
                (n, false) => {
                    c.unhashed_memory += 1;
                    c.unhashed_positive += n;
                }
            }
        }
        c
    }
    /// Room for `items` more in the store `memory_pools` names `pool` (`debug allocate`);
    /// `None` for a name that is not the network's.
    pub(crate) fn reserve_pool(
        &mut self,
        pool: &str,
        items: usize,
    ) -> Option<Result<(), std::collections::TryReserveError>> {
        Some(match pool {
            "rete node" => self.nodes.try_reserve(items),
            "token" => self.tokens.try_reserve(items),
            "token links" => self.links.try_reserve(items),
            "token rows" => self.rows.try_reserve(items),
            "alpha mem" => self.amems.try_reserve(items),
            "right mem" => self.rm.try_reserve(items),
            "rete wme" => self.wmes.try_reserve(items),
            "neg result" => self.neg.try_reserve(items),
            "hash entry" => self.hentries.try_reserve(items),
            _ => return None,
        })
    }

    /// The network's stores, for `stats --memory`, and the bytes of its hash tables.
    pub(crate) fn memory_pools(&self, pools: &mut Vec<Pool>) -> usize {
        pools.push(Pool::of_vec::<super::Node>("rete node", self.nodes.capacity()));
        pools.push(Pool::of_vec::<super::Token>("token", self.tokens.capacity()));
        pools.push(Pool::of_vec::<super::ResultLinks>("token links", self.links.capacity()));
        pools.push(Pool::of_vec::<crate::wm::WmeId>("token rows", self.rows.capacity()));
        pools.push(Pool::of_vec::<super::Amem>("alpha mem", self.amems.capacity()));
        pools.push(Pool::of_vec::<super::RmEntry>("right mem", self.rm.capacity()));
        pools.push(Pool::of_vec::<Option<super::RWme>>("rete wme", self.wmes.capacity()));
        pools.push(Pool::of_vec::<super::NegResult>("neg result", self.neg.capacity()));
        pools.push(Pool::of_vec::<super::hash::HEntry>("hash entry", self.hentries.capacity()));
        self.amem_by_id.bytes()
            + hash_table_bytes::<super::hash::TokKey, u32>(self.tok_by_key.capacity())
            + hash_table_bytes::<super::AlphaKey, super::AmemId>(self.amem_index.capacity())
            + hash_table_bytes::<(NodeId, u8, super::AmemId, u32), super::Shared>(
                self.share.capacity(),
            )
    }
}
