//! The RETE matcher after Doorenbos, "Production Matching for Large Learning Systems"
//! (CMU-CS-95-113), with left and right unlinking (Rete/UL, ch. 4) so that the cost of a
//! working-memory change does not grow with rules that cannot match it.
//!
//! Alpha memories are keyed on the constant attribute and value of a condition (identifiers
//! are never constants) and the acceptable-preference flag. The beta network has beta
//! memories, join nodes, negative nodes, conjunctive-negation (NCC) nodes with partners, and
//! production nodes; nodes are shared between productions with equal prefixes. New matches
//! and retractions go to a [`MatchSink`] (the seam between matcher and decider).
//!
//! Lists are head-inserted as in Soar (children, alpha-memory successors and items), which
//! is what makes later-created nodes and newer WMEs come first (Soar's `rete.cpp` uses
//! `insert_at_head_of_dll`); that order decides which of several new matches fires first.

mod activate;
pub(crate) mod blocks;
mod build;
mod doomed;
mod hash;
mod id_index;
mod names;
pub mod reorder;
mod reserve;
pub(crate) mod small_list;
mod successors;
pub(crate) mod stats;
mod test_lists;
pub mod tests;
mod tokens;

use blocks::{Arena, Blocks};
pub use build::BuildError;
pub use names::VarBindings;
use names::VarNames;
use rustc_hash::FxHashMap;
use small_list::SmallList;
use tests::{Field, JoinTest};

use crate::ids::{id_type, Id};
use crate::symbols::{Sym, SymData, Symbols};
use crate::wm::WmeId;

/// The end of a list of untyped entries (alpha-memory entries, negative join results, index
/// entries); the typed handles have their own `NONE`, the same value.
pub(crate) const NIL: u32 = u32::MAX;

id_type! {
    /// A beta node: its place in `Rete::nodes`.
    pub struct NodeId;
    index Node;
}

id_type! {
    /// A token (a partial or complete match): its place in `Rete::tokens` and `Rete::links`.
    pub struct TokId;
    index Token, ResultLinks;
}

id_type! {
    /// An alpha memory: its place in `Rete::amems`.
    pub struct AmemId;
    index Amem;
}

/// A production in the network.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ProdId(pub u32);

/// Receives complete matches as they appear and disappear.
pub trait MatchSink {
    fn matched(&mut self, prod: ProdId, token: TokId);
    fn unmatched(&mut self, prod: ProdId, token: TokId);
    /// How many retractions the sink holds (see `Rete::alpha_marks`).
    fn retraction_count(&self) -> usize {
        0
    }
}

/// A sink that ignores everything (for building the network without a consumer).
pub struct NullSink;
impl MatchSink for NullSink {
    fn matched(&mut self, _: ProdId, _: TokId) {}
    fn unmatched(&mut self, _: ProdId, _: TokId) {}
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(crate) struct AlphaKey {
    pub attr: Option<Sym>,
    pub value: Option<Sym>,
    pub acceptable: bool,
}

/// See `Rete::attr_amems`.
#[derive(Debug, Clone, Copy)]
struct AttrAmems {
    /// `(attr, any value)`, by `acceptable as usize`; `AmemId::NONE` when there is none.
    open_value: [AmemId; 2],
    /// How many memories test `(attr, constant value)`.
    valued: u32,
}

impl AttrAmems {
    const NONE: AttrAmems = AttrAmems {
        open_value: [AmemId::NONE; 2],
        valued: 0,
    };
}

#[derive(Debug)]
pub(crate) struct Amem {
    pub key: AlphaKey,
    /// Head of the intrusive list of right-memory entries (newest first).
    pub first: u32,
    pub count: u32,
    /// Linked successors in activation order (threaded through `Rete::succ_links`).
    pub successors: successors::SuccList,
    pub refs: u32,
    /// Whether its entries are in the by-identifier index: a small memory is scanned
    /// instead (see `hash::SMALL_AMEM`), indexed once it grows, and no longer once empty.
    pub indexed: bool,
}

/// A linked successor of an alpha memory, with the first of its tests that reads the new
/// WME alone (against a constant), copied here so that the right activations a WME cannot
/// pass end without touching the node: an alpha memory can have thousands of successors
/// that test one attribute against their own constants (the rules of
/// `scripts/gen_rules.py counter`).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Succ {
    pub node: NodeId,
    pub pre: Option<Prefilter>,
    /// The node's `left_unlinked`, mirrored: a left-unlinked join must relink on every
    /// right activation (Rete/UL), so only a linked one may be skipped.
    pub left_unlinked: bool,
    /// Whether the node tests the new WME alone (see `wme_tests_pass`) beyond `pre`: when
    /// not, a linked join whose prefilter passed has nothing more to check on the WME.
    pub wme_tests: bool,
}

/// A successor's test of one field of the new WME against a constant (see [`Succ`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Prefilter {
    pub field: tests::Field,
    pub op: tests::Op,
    pub constant: Sym,
    /// The constant's value when it is an integer and `op` an ordering (`<`, `<=`, `>`,
    /// `>=`), so that an integer WME value is compared here without reading the symbol
    /// table: the counter rules' thousands of constants would each be a cache miss there.
    pub int_order: Option<i64>,
}

impl Prefilter {
    /// Whether the WME field value `v` (whose integer value is `v_int`, if it has one)
    /// passes; the same answer as `tests::relation_holds`.
    #[inline]
    pub fn passes(&self, syms: &Symbols, v: Sym, v_int: Option<i64>) -> bool {
        use crate::ast::Relation;
        use tests::Op;
        if let (Some(c), Some(x), Op::Rel(r)) = (self.int_order, v_int, self.op) {
            match r {
                Relation::Lt => return x < c,
                Relation::Le => return x <= c,
                Relation::Gt => return x > c,
                Relation::Ge => return x >= c,
                // (Not orderings: `int_order` is never set for them.)
                Relation::Ne | Relation::SameType => {}
            }
        }
        tests::relation_holds(syms, self.op, v, self.constant)
    }
}

/// One WME's membership in one alpha memory.
#[derive(Debug, Clone, Copy)]
pub(crate) struct RmEntry {
    pub wme: WmeId,
    /// The WME's identifier (read here when a small memory is scanned by identifier).
    pub id: Sym,
    pub amem: AmemId,
    pub prev: u32,
    pub next: u32,
    /// Links among the entries of this alpha memory with the same identifier (newest first).
    pub id_prev: u32,
    pub id_next: u32,
}

#[derive(Debug, Clone)]
pub(crate) struct RWme {
    pub id: Sym,
    pub attr: Sym,
    pub value: Sym,
    pub acceptable: bool,
    /// Its entries in alpha memories, in insertion order, NIL-padded: a WME is in at most
    /// four (attribute and value each constant or not), so no heap list is needed.
    pub rm: [u32; 4],
    /// Tokens whose `wme` is this one (intrusive list through `Token::next_of_wme`).
    pub tokens: TokId,
    /// Negative join results naming this WME.
    pub neg_results: u32,
    /// Whether the batch of changes in progress removes it (see `doomed.rs`).
    pub doomed: bool,
    /// Its place in the order WMEs entered the matcher (see [`Rete::entry_order`]).
    pub entered: u64,
}

impl RWme {
    pub(crate) fn field(&self, f: Field) -> Sym {
        match f {
            Field::Id => self.id,
            Field::Attr => self.attr,
            Field::Value => self.value,
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Kind {
    Root,
    Memory,
    /// `tests`: the node's list in [`Rete::test_lists`].
    Join {
        amem: AmemId,
        tests: u32,
        left_unlinked: bool,
        right_unlinked: bool,
    },
    Negative {
        amem: AmemId,
        tests: u32,
        right_unlinked: bool,
    },
    Ncc {
        partner: NodeId,
    },
    /// Its buffer of results that came before their owner is in [`Rete::ncc_buffers`]
    /// (partners are rare, and inline it would widen every node).
    NccPartner {
        ncc: NodeId,
        owner_depth: u32,
    },
    Production {
        prod: ProdId,
    },
}

#[derive(Debug, Clone)]
pub(crate) struct Node {
    pub kind: Kind,
    pub parent: NodeId,
    /// Linked children; the last element is the head.
    pub children: SmallList<NodeId>,
    /// Every child, linked or unlinked (for sharing and excising), as a list through
    /// `next_sibling` (newest first; its order means nothing): no heap list per node.
    pub first_child: NodeId,
    pub next_sibling: NodeId,
    /// Token holders: head of the intrusive list of tokens in this node.
    pub first_token: TokId,
    pub token_count: u32,
    /// Depth of the tokens this node holds (root token: 0).
    pub depth: u32,
    pub alive: bool,
    /// Join and negative nodes: the equality test of the new WME's identifier against a
    /// bound variable, `(depth, field)`, that both sides of the join are hashed on.
    pub hash: HashKey,
    /// Join and negative nodes: where that test is in the node's test list
    /// ([`NO_HASH_TEST`] if none), so that a pair the hash index gave skips it.
    pub hash_test: u8,
    /// Token holders: the `(depth, field)` keys their tokens are indexed by, with the number
    /// of hashed nodes using each.
    pub left_keys: SmallList<(u32, Field, u32)>,
    /// Token holders with keys: how their tokens are found by value (see [`LeftMode`]).
    pub left_mode: LeftMode,
    /// Whether its join and negative children are in [`Rete::share`] (see `build.rs`).
    pub wide: bool,
    /// Join and negative nodes: the nearest ancestor on the same alpha memory (`NONE` if none),
    /// found when the node is built.
    pub same_amem_ancestor: NodeId,
}

/// How a token holder with index keys finds its tokens with a given key value.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum LeftMode {
    /// Its tokens are scanned, each read off its cached key: most memories hold a few
    /// tokens, and indexing each costs more than the scan. A memory is scanned until a
    /// WME asks for its tokens while it holds more than [`hash::SMALL_BETA`], and again
    /// once empty.
    Scan,
    /// One key, and every token has the head token's value there: chains of joins on one
    /// identifier (the robot's `^X`, `^Y`, `^Th` below every wall) make hundreds of tokens
    /// with one value, where a hash index only adds upkeep. A token with another value
    /// makes the memory `Indexed`.
    Uniform,
    /// Every token is in the left index under every key.
    Indexed,
}

// 100,000 rules build 400,000 nodes: each byte here is 0.4 MB.
const _: () = assert!(std::mem::size_of::<Node>() == 80);

/// An optional `(depth, field)` in 4 bytes (depth in the high 30 bits), for [`Node::hash`]
/// and the left index keys.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(crate) struct HashKey(u32);

impl HashKey {
    pub const NONE: HashKey = HashKey(u32::MAX);

    pub fn new(key: Option<(u32, Field)>) -> HashKey {
        match key {
            Some((depth, field)) => HashKey(depth << 2 | field as u32),
            None => HashKey::NONE,
        }
    }

    pub fn get(self) -> Option<(u32, Field)> {
        if self == HashKey::NONE {
            return None;
        }
        // A table read, not a branch: this runs for every hashed activation.
        const FIELDS: [Field; 4] = [Field::Id, Field::Attr, Field::Value, Field::Value];
        Some((self.0 >> 2, FIELDS[(self.0 & 3) as usize]))
    }
}

impl Node {
    fn holds_tokens(&self) -> bool {
        matches!(
            self.kind,
            Kind::Root
                | Kind::Memory
                | Kind::Negative { .. }
                | Kind::Ncc { .. }
                | Kind::Production { .. }
        )
    }
}

#[derive(Debug, Clone, Copy)]
#[repr(align(64))]
pub(crate) struct Token {
    pub node: NodeId,
    pub parent: TokId,
    pub wme: WmeId,
    pub depth: u32,
    pub first_child: TokId,
    pub next_sib: TokId,
    pub prev_sib: TokId,
    pub next_in_node: TokId,
    pub prev_in_node: TokId,
    pub next_of_wme: TokId,
    pub prev_of_wme: TokId,
    /// The first of this token's entries in its holder's hash indexes.
    pub hfirst: u32,
    /// Where its row of WMEs starts in [`Rete::rows`].
    pub row: u32,
    /// The token's value at its holder's first index key (`hash::NO_VALUE` if none), cached:
    /// the holder's joins read it for every pairing (`hash.rs`).
    pub key: Sym,
    pub alive: bool,
    /// Whether it holds a WME the batch of changes in progress removes (see `doomed.rs`).
    pub doomed: bool,
}

// One token, one cache line.
const _: () = assert!(std::mem::size_of::<Token>() == 64);

/// A token's result links, kept beside `Rete::tokens` (at the same index) rather than in
/// the token: only negative and NCC nodes' tokens have results, and only NCC partner
/// tokens an owner, so a token every join reads stays within one cache line (64 bytes).
/// A token that is freed leaves them as [`ResultLinks::NONE`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ResultLinks {
    /// Negative node tokens: head of their join results (in `Rete::neg`). NCC tokens: head
    /// of their results (a [`TokId`]'s raw value).
    pub results: u32,
    /// NCC partner result tokens: their owner, and their links in the owner's result list.
    pub owner: TokId,
    pub next_result: TokId,
    pub prev_result: TokId,
}

impl ResultLinks {
    pub const NONE: ResultLinks = ResultLinks {
        results: NIL,
        owner: TokId::NONE,
        next_result: TokId::NONE,
        prev_result: TokId::NONE,
    };
}

#[derive(Debug, Clone, Copy)]
pub(crate) struct NegResult {
    pub owner: TokId,
    pub wme: WmeId,
    pub next_tok: u32,
    pub prev_tok: u32,
    pub next_wme: u32,
    pub prev_wme: u32,
}

/// The nodes under one share key: nearly always one, so that one needs no list.
#[derive(Debug, Clone)]
pub(crate) enum Shared {
    One(NodeId),
    Many(Vec<NodeId>),
}

impl Shared {
    fn as_slice(&self) -> &[NodeId] {
        match self {
            Shared::One(n) => std::slice::from_ref(n),
            Shared::Many(v) => v,
        }
    }
}

/// What the network knows of a production (kept for every rule, so exactly sized). The
/// network joins the top-level conditions in the order the rule lists them (they come
/// reordered), so no order is kept.
#[derive(Debug, Clone)]
pub struct ProdInfo {
    pub(crate) pnode: NodeId,
    /// The number of positive top-level conditions.
    pub(crate) positives: u32,
    /// Where each variable of the positive conditions is first bound: token depth and field.
    pub bindings: VarBindings,
    /// A hash of the actions with variables as binding places: equal keys under one parent
    /// node mean duplicate rules.
    pub(crate) action_key_hash: u64,
}

pub struct Rete {
    /// Plain vectors, not [`Blocks`]: every activation reads nodes and alpha memories, and
    /// a plain index is the cheapest (5.5 % of a SLAM run's instructions against the first
    /// `Blocks`, 1.6 % against the present one). The price: at 100,000 rules a doubling's
    /// copy can add 18 MB to the load's peak (225–244 MB over runs); the load is no slower.
    pub(crate) nodes: Vec<Node>,
    free_nodes: Vec<NodeId>,
    pub(crate) tokens: Vec<Token>,
    free_tokens: Vec<TokId>,
    /// Each token's result links, by token id (see [`ResultLinks`]).
    pub(crate) links: Vec<ResultLinks>,
    /// Every token's WMEs by depth, from the root's (depth 0) to its own, in one row: a
    /// join test or a key reads any depth at once instead of walking up the parents (a
    /// hot walk: rules join a dozen conditions and test the first one's state last).
    pub(crate) rows: Vec<WmeId>,
    /// Freed rows, by length.
    free_rows: Vec<Vec<u32>>,
    pub(crate) amems: Vec<Amem>,
    free_amems: Vec<AmemId>,
    amem_index: FxHashMap<AlphaKey, AmemId>,
    /// The alpha memories with a constant attribute, by the attribute's symbol index: the
    /// one that leaves the value open (for non-acceptable and acceptable WMEs), and how many
    /// test a constant value too. A new WME finds its memories here without hashing its
    /// key, and looks up `(attr, value)` only when some memory tests a value with its
    /// attribute (most attributes have none).
    attr_amems: Vec<AttrAmems>,
    /// The alpha memories that leave the attribute open, as `attr_amems` keeps them by
    /// attribute: most networks have none, and then a new WME makes no lookup for them.
    attrless_amems: AttrAmems,
    pub(crate) rm: Vec<RmEntry>,
    free_rm: Vec<u32>,
    pub(crate) wmes: Vec<Option<RWme>>,
    pub(crate) neg: Vec<NegResult>,
    free_neg: Vec<u32>,
    pub(crate) prods: Blocks<Option<ProdInfo>>,
    /// Join and negative nodes by (parent, kind, alpha memory, test list), for sharing,
    /// under parents with many children (`Node::wide`).
    pub(crate) share: FxHashMap<(NodeId, u8, AmemId, u32), Shared>,
    /// The distinct test lists of join and negative nodes, each kept once (`shared_tests`).
    pub(crate) test_lists: test_lists::TestLists,
    /// NCC partners' results that came before their owner token, by partner.
    pub(crate) ncc_buffers: FxHashMap<NodeId, Vec<TokId>>,
    /// The tests of the condition being added (a reused buffer, see `build_conditions`).
    test_buf: Vec<JoinTest>,
    /// The variable names of every rule's [`VarBindings`].
    pub(crate) var_names: VarNames,
    /// The names of the variables only actions use (those a rule's actions make), each
    /// stored once; kept apart, so that `debug internal-symbols` lists what it did.
    pub(crate) action_var_names: VarNames,
    /// The rules' lists of where their variables are bound, each once.
    binding_lists: names::BindingLists,
    pub(crate) root: NodeId,
    root_token: TokId,
    /// Alpha-memory entries by identifier: the head of each list (Soar's right hash table).
    pub(crate) amem_by_id: id_index::IdIndex,
    /// Holders' tokens by their value at one `(depth, field)` key: the head of each list
    /// of index entries (Soar's left hash table).
    pub(crate) tok_by_key: FxHashMap<hash::TokKey, u32>,
    pub(crate) hentries: Vec<hash::HEntry>,
    free_hentries: Vec<u32>,
    /// The activations' shared stack of list copies (see `activate.rs`).
    scratch: Vec<u32>,
    /// Left activations waiting their turn: the matcher walks the network depth first
    /// with this stack rather than the call stack, so a rule of thousands of conditions
    /// joined one to the next cannot overflow it (`activate.rs`).
    pending: Vec<activate::Pending>,
    /// The successors of an alpha memory that just emptied (reused buffer).
    emptied_succ: Vec<NodeId>,
    /// The same for alpha-memory successors.
    succ_scratch: Vec<Succ>,
    /// The links of the alpha memories' successor lists, by node.
    succ_links: successors::SuccLinks,
    /// The batch of changes in progress, for leaving out its passing tokens.
    pub(crate) doom: doomed::DoomState,
    /// Counts changes to the network's nodes (summaries of it are kept until it changes).
    pub(crate) network_version: u64,
    /// Counters for the benchmarks and `stats`.
    pub right_activations: u64,
    pub left_activations: u64,
    pub tokens_made: u64,
    /// WMEs added so far: the next one's [`RWme::entered`].
    wmes_entered: u64,
    /// When set, `add_wme` notes before each alpha memory it activates that memory's
    /// 9.6 alpha table (`attr constant` × 2 + `value constant`) and the sink's retraction
    /// count, in `alpha_marks`: justifications are not in our network, and 9.6 reaches
    /// theirs in that table order (see `AgentCore::match_wme_now`).
    pub(crate) mark_alphas: bool,
    pub(crate) alpha_marks: Vec<(u8, usize)>,
    /// The most partial matches a production's first matching may bring the network to
    /// (0: no limit): past it the new nodes stop filling and the production is refused.
    pub(crate) token_budget: usize,
    /// A new node stopped filling at the budget while this production was added.
    fill_aborted: bool,
}

impl Default for Rete {
    fn default() -> Self {
        Self::new()
    }
}

impl Rete {
    pub fn new() -> Self {
        let mut r = Rete {
            nodes: Vec::new(),
            free_nodes: Vec::new(),
            tokens: Vec::new(),
            free_tokens: Vec::new(),
            links: Vec::new(),
            rows: Vec::new(),
            free_rows: Vec::new(),
            amems: Vec::new(),
            free_amems: Vec::new(),
            amem_index: FxHashMap::default(),
            attr_amems: Vec::new(),
            attrless_amems: AttrAmems::NONE,
            rm: Vec::new(),
            free_rm: Vec::new(),
            wmes: Vec::new(),
            neg: Vec::new(),
            free_neg: Vec::new(),
            prods: Blocks::default(),
            share: FxHashMap::default(),
            test_lists: Default::default(),
            ncc_buffers: FxHashMap::default(),
            test_buf: Vec::new(),
            var_names: VarNames::default(),
            action_var_names: VarNames::default(),
            binding_lists: names::BindingLists::default(),
            amem_by_id: id_index::IdIndex::default(),
            tok_by_key: FxHashMap::default(),
            hentries: Vec::new(),
            free_hentries: Vec::new(),
            scratch: Vec::new(),
            pending: Vec::new(),
            succ_scratch: Vec::new(),
            succ_links: successors::SuccLinks::default(),
            emptied_succ: Vec::new(),
            root: NodeId::new(0),
            root_token: TokId::new(0),
            doom: Default::default(),
            network_version: 0,
            right_activations: 0,
            left_activations: 0,
            tokens_made: 0,
            wmes_entered: 0,
            mark_alphas: false,
            token_budget: 0,
            fill_aborted: false,
            alpha_marks: Vec::new(),
        };
        r.root = r.new_node(Kind::Root, NodeId::NONE, 0);
        r.root_token = r.new_token(r.root, TokId::NONE, NIL_WME);
        r
    }

    pub(crate) fn new_node(&mut self, kind: Kind, parent: NodeId, depth: u32) -> NodeId {
        let node = Node {
            kind,
            parent,
            children: SmallList::Empty,
            first_child: NodeId::NONE,
            next_sibling: NodeId::NONE,
            first_token: TokId::NONE,
            token_count: 0,
            depth,
            alive: true,
            hash: HashKey::NONE,
            hash_test: NO_HASH_TEST,
            left_keys: SmallList::Empty,
            left_mode: LeftMode::Scan,
            wide: false,
            same_amem_ancestor: NodeId::NONE,
        };
        self.network_version += 1;
        alloc(&mut self.nodes, &mut self.free_nodes, node)
    }

    pub(crate) fn free_node(&mut self, n: NodeId) {
        self.network_version += 1;
        if let Kind::Join { tests, .. } | Kind::Negative { tests, .. } = self.nodes[n].kind
        {
            self.test_lists.release(tests);
        }
        if let Kind::NccPartner { .. } = self.nodes[n].kind {
            self.ncc_buffers.remove(&n);
        }
        let node = &mut self.nodes[n];
        node.alive = false;
        node.children = SmallList::Empty;
        node.first_child = NodeId::NONE;
        node.next_sibling = NodeId::NONE;
        node.kind = Kind::Memory;
        node.hash = HashKey::NONE;
        node.hash_test = NO_HASH_TEST;
        node.left_keys = SmallList::Empty;
        node.left_mode = LeftMode::Scan;
        node.wide = false;
        self.free_nodes.push(n);
    }

    // ------------------------------------------------------------------ alpha memories

    pub(crate) fn amem_for(&mut self, key: AlphaKey) -> AmemId {
        if let Some(&a) = self.amem_index.get(&key) {
            self.amems[a].refs += 1;
            return a;
        }
        let amem = Amem {
            key,
            first: NIL,
            count: 0,
            successors: successors::SuccList::default(),
            refs: 1,
            indexed: false,
        };
        let id = alloc(&mut self.amems, &mut self.free_amems, amem);
        self.amem_index.insert(key, id);
        let e = self.attr_amems_mut(key.attr);
        match key.value {
            None => e.open_value[usize::from(key.acceptable)] = id,
            Some(_) => e.valued += 1,
        }
        // A new alpha memory starts with every WME that passes its constant tests.
        let matching: Vec<WmeId> = self
            .wmes
            .iter()
            .enumerate()
            .filter_map(|(i, w)| {
                w.as_ref()
                    .filter(|w| key_matches(&key, w))
                    .map(|_| WmeId(i as u32))
            })
            .collect();
        // Oldest first, so that head insertion leaves the newest at the head.
        for w in matching {
            self.amem_insert(id, w);
        }
        id
    }

    pub(crate) fn release_amem(&mut self, a: AmemId) {
        let am = &mut self.amems[a];
        am.refs -= 1;
        if am.refs > 0 {
            return;
        }
        let key = am.key;
        let mut e = am.first;
        while e != NIL {
            let next = self.rm[e as usize].next;
            let w = self.rm[e as usize].wme;
            if let Some(rw) = self.wmes[w.0 as usize].as_mut() {
                rm_slots_remove(&mut rw.rm, e);
                let id = rw.id;
                if self.amems[a].indexed {
                    self.amem_by_id.remove(a, id);
                }
            }
            self.free_rm.push(e);
            e = next;
        }
        self.amem_index.remove(&key);
        let e = self.attr_amems_mut(key.attr);
        match key.value {
            None => e.open_value[usize::from(key.acceptable)] = AmemId::NONE,
            Some(_) => e.valued -= 1,
        }
        let am = &mut self.amems[a];
        am.first = NIL;
        am.count = 0;
        self.succ_links.clear(&mut am.successors);
        self.free_amems.push(a);
    }

    fn amem_insert(&mut self, a: AmemId, w: WmeId) {
        let head = self.amems[a].first;
        let entry = RmEntry {
            wme: w,
            id: self.wme(w).id,
            amem: a,
            prev: NIL,
            next: head,
            id_prev: NIL,
            id_next: NIL,
        };
        let e = alloc(&mut self.rm, &mut self.free_rm, entry);
        if head != NIL {
            self.rm[head as usize].prev = e;
        }
        let am = &mut self.amems[a];
        am.first = e;
        am.count += 1;
        let (indexed, count) = (am.indexed, am.count);
        if let Some(rw) = self.wmes[w.0 as usize].as_mut() {
            rm_slots_push(&mut rw.rm, e);
            let id = rw.id;
            if indexed {
                self.id_index_insert(a, id, e);
            } else if count > hash::SMALL_AMEM {
                self.index_amem(a);
            }
        }
    }

    fn amem_remove_entry(&mut self, e: u32) {
        let RmEntry {
            amem,
            prev,
            next,
            wme,
            ..
        } = self.rm[e as usize];
        if self.amems[amem].indexed {
            if let Some(id) = self.wmes[wme.0 as usize].as_ref().map(|rw| rw.id) {
                self.id_index_remove(amem, id, e);
            }
        }
        if prev != NIL {
            self.rm[prev as usize].next = next;
        } else {
            self.amems[amem].first = next;
        }
        if next != NIL {
            self.rm[next as usize].prev = prev;
        }
        let am = &mut self.amems[amem];
        am.count -= 1;
        if am.count == 0 {
            am.indexed = false;
        }
        self.free_rm.push(e);
    }

    /// WMEs of an alpha memory, head (newest) first.
    pub(crate) fn amem_items(&self, a: AmemId) -> Vec<WmeId> {
        let mut out = Vec::with_capacity(self.amems[a].count as usize);
        let mut e = self.amems[a].first;
        while e != NIL {
            out.push(self.rm[e as usize].wme);
            e = self.rm[e as usize].next;
        }
        out
    }

    // ---------------------------------------------------------------- working memory

    /// Where WME `w` stands in the order WMEs entered the matcher, which is the order 9.6
    /// keeps its WMEs in (`print` of a pattern lists them so); `None` for a WME it does not
    /// hold.
    pub fn entry_order(&self, w: WmeId) -> Option<u64> {
        self.wmes.get(w.0 as usize)?.as_ref().map(|r| r.entered)
    }

    /// Adds a WME and propagates its matches (Doorenbos `add-wme`).
    pub fn add_wme(
        &mut self,
        w: WmeId,
        (id, attr, value): (Sym, Sym, Sym),
        acceptable: bool,
        syms: &Symbols,
        sink: &mut dyn MatchSink,
    ) {
        let idx = w.0 as usize;
        if self.wmes.len() <= idx {
            self.wmes.resize(idx + 1, None);
        }
        self.wmes[idx] = Some(RWme {
            id,
            attr,
            value,
            acceptable,
            rm: [NIL; 4],
            tokens: TokId::NONE,
            neg_results: NIL,
            doomed: false,
            entered: self.wmes_entered,
        });
        self.wmes_entered += 1;
        // Up to four alpha memories can hold it: attribute and value constant or not. They
        // are activated least specific first, as 9.6 walks its alpha hash tables; the order
        // decides which left-unlinked joins relink first, so the order of new matches and
        // of firings (scripts/trace_compare.py: o-reject, random-tokens and missionaries
        // match 9.6 at every trace level with it).
        let targets = self.alpha_targets(attr, value, acceptable);
        if self.mark_alphas {
            self.alpha_marks.clear();
        }
        for &am in targets.iter().take_while(|&&a| a != AmemId::NONE) {
            if self.mark_alphas {
                let key = self.amems[am].key;
                let table = (u8::from(key.attr.is_some()) << 1) | u8::from(key.value.is_some());
                self.alpha_marks.push((table, sink.retraction_count()));
            }
            self.alpha_activation(am, w, syms, sink);
        }
    }

    /// The alpha memories a WME with this attribute and value goes into, `NONE`-padded.
    pub(crate) fn alpha_targets(&self, attr: Sym, value: Sym, acceptable: bool) -> [AmemId; 4] {
        let mut targets = [AmemId::NONE; 4];
        let mut n = 0;
        // Least specific first: open attribute (then its constant values), then the
        // constant attribute (then its constant values).
        let attrless = Some(&self.attrless_amems);
        let with_attr = self.attr_amems.get(attr.0 as usize);
        for (a, e) in [(None, attrless), (Some(attr), with_attr)] {
            let Some(e) = e else { continue };
            let open = e.open_value[usize::from(acceptable)];
            if open != AmemId::NONE {
                targets[n] = open;
                n += 1;
            }
            if e.valued > 0 {
                let key = AlphaKey {
                    attr: a,
                    value: Some(value),
                    acceptable,
                };
                if let Some(&am) = self.amem_index.get(&key) {
                    targets[n] = am;
                    n += 1;
                }
            }
        }
        targets
    }

    /// The `attr_amems` entry of a constant attribute (made if need be), or the attribute-
    /// open memories' entry.
    fn attr_amems_mut(&mut self, attr: Option<Sym>) -> &mut AttrAmems {
        let Some(attr) = attr else {
            return &mut self.attrless_amems;
        };
        let i = attr.0 as usize;
        if self.attr_amems.len() <= i {
            self.attr_amems.resize(i + 1, AttrAmems::NONE);
        }
        &mut self.attr_amems[i]
    }

    fn alpha_activation(&mut self, a: AmemId, w: WmeId, syms: &Symbols, sink: &mut dyn MatchSink) {
        // Left-unlinked joins relink themselves when their right activation comes (lazily, as
        // Doorenbos does): relinking them all first would let a descendant on the same alpha
        // memory see this WME twice.
        self.amem_insert(a, w);
        self.right_activate_successors(a, w, syms, sink);
    }

    /// Removes a WME: out of its alpha memories, its tokens and its negative join results.
    pub fn remove_wme(&mut self, w: WmeId, syms: &Symbols, sink: &mut dyn MatchSink) {
        let Some(rw) = self.wmes.get_mut(w.0 as usize).and_then(|x| x.as_mut()) else {
            return;
        };
        let rm = std::mem::replace(&mut rw.rm, [NIL; 4]);
        for e in rm.into_iter().take_while(|&e| e != NIL) {
            let amem = self.rm[e as usize].amem;
            self.amem_remove_entry(e);
            if self.amems[amem].count == 0 {
                // Empty alpha memory: its joins need no left activations (Rete/UL).
                let mut succ = std::mem::take(&mut self.emptied_succ);
                succ.clear();
                succ.extend(
                    self.succ_links
                        .iter(self.amems[amem].successors)
                        .map(|s| s.node),
                );
                self.unlink_left_all(&succ);
                self.emptied_succ = succ;
            }
        }
        // Tokens built on this WME go, with their descendants.
        loop {
            let t = self.wmes[w.0 as usize]
                .as_ref()
                .map_or(TokId::NONE, |x| x.tokens);
            if t == TokId::NONE {
                break;
            }
            self.delete_token_and_descendants(t, syms, sink);
        }
        // Negative tokens it was blocking may now pass.
        loop {
            let r = self.wmes[w.0 as usize]
                .as_ref()
                .map_or(NIL, |x| x.neg_results);
            if r == NIL {
                break;
            }
            let owner = self.neg[r as usize].owner;
            self.remove_neg_result(r);
            if self.tokens[owner].alive && self.links[owner].results == NIL {
                let node = self.tokens[owner].node;
                self.activate_children(node, owner, NIL_WME, syms, sink);
            }
        }
        self.wmes[w.0 as usize] = None;
    }

    pub(crate) fn wme(&self, w: WmeId) -> &RWme {
        self.wmes[w.0 as usize].as_ref().expect("live wme")
    }

    pub(crate) fn field(&self, w: WmeId, f: Field) -> Sym {
        self.wme(w).field(f)
    }

    // ------------------------------------------------------------------ unlinking

    /// Marks a linked join left-unlinked; false if it was unlinked on either side already
    /// (a join is never unlinked on both sides, Doorenbos, section 4.3).
    fn mark_left_unlinked(&mut self, n: NodeId) -> bool {
        match &mut self.nodes[n].kind {
            Kind::Join {
                left_unlinked,
                right_unlinked,
                ..
            } if !*left_unlinked && !*right_unlinked => {
                *left_unlinked = true;
                self.mirror_left_unlinked(n, true);
                true
            }
            _ => false,
        }
    }

    /// Keeps [`Succ::left_unlinked`] in step with the node's flag.
    pub(crate) fn mirror_left_unlinked(&mut self, n: NodeId, unlinked: bool) {
        let node = &self.nodes[n];
        let (Kind::Join { amem, .. } | Kind::Negative { amem, .. }) = node.kind else {
            return;
        };
        let _ = amem;
        if let Some(s) = self.succ_links.get_mut(n) {
            s.left_unlinked = unlinked;
        }
    }

    /// Takes a join out of its parent's children: its alpha memory is empty.
    fn unlink_left(&mut self, n: NodeId) {
        if self.mark_left_unlinked(n) {
            let parent = self.nodes[n].parent;
            self.nodes[parent].children.retain(|c| *c != n);
        }
    }

    /// `unlink_left` for many joins at once: one pass over each parent's children.
    fn unlink_left_all(&mut self, nodes: &[NodeId]) {
        if nodes.len() <= 8 {
            // Few: each leaves its parent's list on its own (no sets to build).
            for &n in nodes {
                if self.mark_left_unlinked(n) {
                    let parent = self.nodes[n].parent;
                    self.nodes[parent].children.retain(|c| *c != n);
                }
            }
            return;
        }
        let mut by_parent: FxHashMap<NodeId, rustc_hash::FxHashSet<NodeId>> = FxHashMap::default();
        for &n in nodes {
            if self.mark_left_unlinked(n) {
                let parent = self.nodes[n].parent;
                by_parent.entry(parent).or_default().insert(n);
            }
        }
        for (parent, gone) in by_parent {
            self.nodes[parent]
                .children
                .retain(|c| !gone.contains(c));
        }
    }

    fn relink_left(&mut self, n: NodeId) {
        let parent = self.nodes[n].parent;
        if let Kind::Join { left_unlinked, .. } = &mut self.nodes[n].kind {
            if !*left_unlinked {
                return;
            }
            *left_unlinked = false;
        } else {
            return;
        }
        self.mirror_left_unlinked(n, false);
        self.nodes[parent].children.push(n);
    }

    /// Takes a join or negative node out of its alpha memory's successors: it has no tokens
    /// to join with.
    pub(crate) fn unlink_right(&mut self, n: NodeId) {
        let amem = match &mut self.nodes[n].kind {
            Kind::Join {
                amem,
                right_unlinked,
                left_unlinked,
                ..
            } => {
                if *right_unlinked || *left_unlinked {
                    return;
                }
                *right_unlinked = true;
                *amem
            }
            Kind::Negative {
                amem,
                right_unlinked,
                ..
            } => {
                if *right_unlinked {
                    return;
                }
                *right_unlinked = true;
                *amem
            }
            _ => return,
        };
        self.succ_links.remove(&mut self.amems[amem].successors, n);
    }

    /// Puts a node back among its alpha memory's successors.
    pub(crate) fn relink_right(&mut self, n: NodeId, syms: &Symbols) {
        let amem = match &mut self.nodes[n].kind {
            Kind::Join {
                amem,
                right_unlinked,
                ..
            }
            | Kind::Negative {
                amem,
                right_unlinked,
                ..
            } => {
                if !*right_unlinked {
                    return;
                }
                *right_unlinked = false;
                *amem
            }
            _ => return,
        };
        self.link_to_amem(n, amem, syms);
    }

    /// Links a node into its alpha memory's successors where Soar's Rete/UL puts it, when
    /// it is built and whenever it is relinked: just before its nearest linked ancestor on
    /// the same memory (so no descendant sees a new WME twice, Doorenbos, section 4.3.2),
    /// or else at the tail. The order therefore follows linking history, which decides the
    /// firing order of rules matched by one WME: 9.6 activates from the head.
    pub(crate) fn link_to_amem(&mut self, n: NodeId, amem: AmemId, syms: &Symbols) {
        let mut a = self.nodes[n].same_amem_ancestor;
        while a != NodeId::NONE && self.is_right_unlinked(a) {
            a = self.nodes[a].same_amem_ancestor;
        }
        let left_unlinked = matches!(
            self.nodes[n].kind,
            Kind::Join {
                left_unlinked: true,
                ..
            }
        );
        let (pre, wme_tests) = match self.succ_links.known(n) {
            Some(s) => (s.pre, s.wme_tests),
            None => {
                let pre = self.prefilter(n, syms);
                let alone = self.wme_test_count(n);
                (pre, alone > usize::from(pre.is_some()))
            }
        };
        let s = Succ {
            node: n,
            pre,
            left_unlinked,
            wme_tests,
        };
        self.succ_links.insert(&mut self.amems[amem].successors, s, a);
    }

    /// The first test of join or negative node `n` on a field of the new WME against a
    /// constant, if it has one (see [`Succ`]).
    fn prefilter(&self, n: NodeId, syms: &Symbols) -> Option<Prefilter> {
        use crate::ast::Relation;
        use tests::Op;
        self.join_tests(n).iter().find_map(|t| match t {
            JoinTest::Compare {
                field,
                op,
                operand: tests::Operand::Const(c),
            } => {
                let ordering = matches!(
                    op,
                    Op::Rel(Relation::Lt | Relation::Le | Relation::Gt | Relation::Ge)
                );
                let int_order = match syms.get(*c) {
                    SymData::Int(i) if ordering => Some(*i),
                    _ => None,
                };
                Some(Prefilter {
                    field: *field,
                    op: *op,
                    constant: *c,
                    int_order,
                })
            }
            _ => None,
        })
    }

    /// The tests of a join or negative node (none for other kinds), read in place.
    pub(crate) fn join_tests(&self, n: NodeId) -> &[JoinTest] {
        match &self.nodes[n].kind {
            Kind::Join { tests, .. } | Kind::Negative { tests, .. } => self.test_lists.get(*tests),
            _ => &[],
        }
    }

    /// The nearest ancestor of `n` that is a join or negative node on `amem` (none when `n`
    /// is the memory's only user, which spares the walk up a long rule).
    pub(crate) fn find_same_amem_ancestor(&self, n: NodeId, amem: AmemId) -> NodeId {
        if self.amems[amem].refs <= 1 {
            return NodeId::NONE;
        }
        let mut p = self.nodes[n].parent;
        while p != NodeId::NONE {
            match self.nodes[p].kind {
                Kind::Join { amem: m, .. } | Kind::Negative { amem: m, .. } if m == amem => {
                    return p
                }
                Kind::Root => return NodeId::NONE,
                _ => {}
            }
            p = self.nodes[p].parent;
        }
        NodeId::NONE
    }

    pub(crate) fn is_right_unlinked(&self, n: NodeId) -> bool {
        matches!(
            self.nodes[n].kind,
            Kind::Join {
                right_unlinked: true,
                ..
            } | Kind::Negative {
                right_unlinked: true,
                ..
            }
        )
    }

    // ------------------------------------------------------------------- queries

    pub fn production(&self, p: ProdId) -> Option<&ProdInfo> {
        self.prods.get(p.0 as usize).and_then(|x| x.as_ref())
    }

    /// The WMEs a complete match used, for its positive top-level conditions, in the order
    /// the production lists them.
    pub fn match_wmes(&self, p: ProdId, token: TokId) -> Vec<WmeId> {
        let Some(info) = self.production(p) else {
            return Vec::new();
        };
        // The positive conditions are joined in the order listed: the k-th WME of the
        // token's row (negations leave no WME there) is the k-th's.
        let n = info.positives as usize;
        let mut out = Vec::with_capacity(n);
        if token != TokId::NONE {
            let row = self.token_row(token).iter().copied();
            out.extend(row.filter(|&w| w != NIL_WME).take(n));
        }
        out.resize(n, NIL_WME);
        out
    }

    /// The WMEs of a complete match as [`Rete::match_wmes`] lists them, without the
    /// padding for conditions it lacks, and without allocating.
    pub(crate) fn match_row(&self, p: ProdId, token: TokId) -> impl Iterator<Item = WmeId> + '_ {
        let n = self.production(p).map_or(0, |info| info.positives as usize);
        let row: &[WmeId] = if token == TokId::NONE || n == 0 {
            &[]
        } else {
            self.token_row(token)
        };
        row.iter().copied().filter(|&w| w != NIL_WME).take(n)
    }

    /// The WMEs of a token and its ancestors, by token depth (`NIL_WME` where a depth has
    /// none), for reading many bindings of one match.
    pub(crate) fn token_wmes(&self, token: TokId, out: &mut Vec<WmeId>) {
        out.clear();
        if token == TokId::NONE {
            return;
        }
        out.extend_from_slice(self.token_row(token));
    }

    /// A token's row: its and its ancestors' WMEs by depth.
    pub(crate) fn token_row(&self, t: TokId) -> &[WmeId] {
        let tok = &self.tokens[t];
        let start = tok.row as usize;
        &self.rows[start..=start + tok.depth as usize]
    }

    /// Takes a row for a new token at `depth`: its parent's row (at `parent_row`), then
    /// `wme`.
    pub(crate) fn alloc_row(&mut self, parent_row: u32, depth: u32, wme: WmeId) -> u32 {
        let len = depth as usize + 1;
        let row = match self.free_rows.get_mut(len).and_then(Vec::pop) {
            Some(r) => r as usize,
            None => {
                let r = self.rows.len();
                self.rows.resize(r + len, NIL_WME);
                r
            }
        };
        let from = parent_row as usize;
        let d = depth as usize;
        if d > 0 {
            let (src, dst) = if from < row {
                let (a, b) = self.rows.split_at_mut(row);
                (&a[from..from + d], &mut b[..d])
            } else {
                let (a, b) = self.rows.split_at_mut(from);
                (&b[..d], &mut a[row..row + d])
            };
            dst.copy_from_slice(src);
        }
        self.rows[row + d] = wme;
        row as u32
    }

    /// The tokens the matcher holds (partial and complete matches).
    pub(crate) fn token_total(&self) -> usize {
        self.tokens.len() - self.free_tokens.len()
    }

    /// Gives a deleted token's row back.
    pub(crate) fn free_row(&mut self, row: u32, depth: u32) {
        let len = depth as usize + 1;
        if self.free_rows.len() <= len {
            self.free_rows.resize_with(len + 1, Vec::new);
        }
        self.free_rows[len].push(row);
    }

    /// The beta node of each top-level condition of a production, in the rule's order: the
    /// join, negative and NCC nodes above its production node (a condition's node is never
    /// moved, so they are found rather than kept with every rule).
    pub(crate) fn cond_nodes(&self, info: &ProdInfo) -> Vec<NodeId> {
        let mut nodes = Vec::new();
        let mut n = self.nodes[info.pnode].parent;
        while n != NodeId::NONE && n != self.root {
            let node = &self.nodes[n];
            if matches!(node.kind, Kind::Join { .. } | Kind::Negative { .. } | Kind::Ncc { .. }) {
                nodes.push(n);
            }
            n = node.parent;
        }
        nodes.reverse();
        nodes
    }

    /// Where a production's matches hold their distinct condition identifiers (see
    /// `CompiledRule::id_places`): each positive condition's identifier is its WME's, or the
    /// binding its join is hashed on when it has one (an equal symbol read once).
    pub(crate) fn condition_id_places(&self, info: &ProdInfo) -> Vec<(u32, tests::Field)> {
        let mut places = Vec::new();
        for n in self.cond_nodes(info) {
            let node = &self.nodes[n];
            if !matches!(node.kind, Kind::Join { .. }) {
                continue;
            }
            let own = (self.nodes[node.parent].depth + 1, tests::Field::Id);
            let place = node.hash.get().unwrap_or(own);
            if !places.contains(&place) {
                places.push(place);
            }
        }
        places
    }

    /// The WMEs of a token and its ancestors, newest first.
    pub(crate) fn chain_wmes(&self, token: TokId) -> impl Iterator<Item = WmeId> + '_ {
        let mut t = token;
        std::iter::from_fn(move || {
            while t != TokId::NONE {
                let tok = &self.tokens[t];
                t = tok.parent;
                if tok.wme != NIL_WME {
                    return Some(tok.wme);
                }
            }
            None
        })
    }

    /// A binding read off [`Rete::token_wmes`]: the field of the WME at `depth`.
    pub(crate) fn field_at(&self, wmes: &[WmeId], depth: u32, field: Field) -> Option<Sym> {
        let w = *wmes.get(depth as usize)?;
        (w != NIL_WME).then(|| self.field(w, field))
    }

    /// The value of a variable in a complete match.
    pub fn binding(&self, p: ProdId, token: TokId, var: &str) -> Option<Sym> {
        let info = self.production(p)?;
        let &(depth, field) = info.bindings.get(var)?;
        self.bound_value(token, depth, field)
    }

    /// The value a match `token` binds at `(depth, field)` (see `VarBindings`).
    pub fn bound_value(&self, token: TokId, depth: u32, field: Field) -> Option<Sym> {
        let w = self.wme_at_depth(token, depth);
        if w == NIL_WME {
            return None;
        }
        Some(self.field(w, field))
    }

    /// The token made before `t` in the same node (`TokId::NONE` after the oldest).
    pub(crate) fn older_in_node(&self, t: TokId) -> TokId {
        self.tokens[t].next_in_node
    }

    /// The complete matches of a production: its production node's tokens, newest first.
    pub fn matches_of(&self, p: ProdId) -> Vec<TokId> {
        match self.production(p) {
            Some(info) => self.node_tokens(info.pnode),
            None => Vec::new(),
        }
    }

    /// For `matches <rule>`: each top-level condition (index into the rule's conditions), in
    /// the order the network joins them, with the number of partial matches through it.
    pub fn partial_match_counts(&self, p: ProdId, syms: &Symbols) -> Vec<(usize, usize)> {
        let Some(info) = self.production(p) else {
            return Vec::new();
        };
        self.cond_nodes(info)
            .into_iter()
            .enumerate()
            .map(|(i, n)| (i, self.count_matches_at(n, syms)))
            .collect()
    }

    /// For `production memory-usage`: the partial matches 9.6's network holds for a rule.
    /// Each condition's node keeps the matches of the conditions before it (the first, the
    /// network's one empty match), so the count is one plus the matches through every
    /// condition but the last; a negated conjunction of two or more conditions adds the
    /// matches entering each of its own conditions (counted on soar_sml 9.6.5).
    pub fn tokens_held(&self, p: ProdId, syms: &Symbols) -> u64 {
        let Some(info) = self.production(p) else {
            return 0;
        };
        let cond_nodes = self.cond_nodes(info);
        let counts: Vec<u64> = cond_nodes
            .iter()
            .map(|&n| self.count_matches_at(n, syms) as u64)
            .collect();
        let mut total = 1;
        for (j, &n) in cond_nodes.iter().enumerate() {
            let entering = if j == 0 { 1 } else { counts[j - 1] };
            if j + 1 < counts.len() {
                total += counts[j];
            }
            if let Kind::Ncc { partner } = self.nodes[n].kind {
                let inner = self.ncc_condition_counts(n, partner, syms);
                if inner.len() >= 2 {
                    total += entering + inner[..inner.len() - 1].iter().sum::<u64>();
                }
            }
        }
        total
    }

    /// The matches through each condition of a negated conjunction's own branch, top down.
    fn ncc_condition_counts(&self, ncc: NodeId, partner: NodeId, syms: &Symbols) -> Vec<u64> {
        let top = self.nodes[ncc].parent;
        let mut nodes = Vec::new();
        let mut n = self.nodes[partner].parent;
        while n != top && n != NodeId::NONE {
            if matches!(self.nodes[n].kind, Kind::Join { .. } | Kind::Negative { .. } | Kind::Ncc { .. }) {
                nodes.push(n);
            }
            n = self.nodes[n].parent;
        }
        nodes.reverse();
        nodes.iter().map(|&c| self.count_matches_at(c, syms) as u64).collect()
    }

    fn count_matches_at(&self, n: NodeId, syms: &Symbols) -> usize {
        let node = &self.nodes[n];
        if node.holds_tokens() {
            return self.live_tokens(n).len();
        }
        match &node.kind {
            Kind::Join { amem, tests, .. } => {
                // Joins hold nothing: count the pairs that pass.
                let parent = node.parent;
                let depth = self.nodes[parent].depth + 1;
                let items = self.amem_items(*amem);
                let mut c = 0;
                for t in self.live_tokens(parent) {
                    c += items
                        .iter()
                        .filter(|&&w| {
                            self.tests_pass(self.test_lists.get(*tests), t, w, depth, syms)
                        })
                        .count();
                }
                c
            }
            _ => 0,
        }
    }

    /// Number of live beta nodes and alpha memories (for benchmarks and tests).
    #[cfg(feature = "internals")]
    pub fn node_count(&self) -> (usize, usize) {
        let beta = self.nodes.iter().filter(|n| n.alive).count();
        (beta, self.amem_index.len())
    }
}

pub(crate) const NIL_WME: WmeId = WmeId(NIL);

/// `Node::hash_test` of a node that is not hashed.
pub(crate) const NO_HASH_TEST: u8 = u8::MAX;

/// Puts `value` in a free slot of `items` (or a new one) and returns its index: the arenas
/// of nodes, tokens, alpha memories and list entries all allocate this way.
pub(crate) fn alloc<I: Id, T>(items: &mut impl Arena<T>, free: &mut Vec<I>, value: T) -> I {
    match free.pop() {
        Some(i) => {
            items[i.index()] = value;
            i
        }
        None => {
            items.push_item(value);
            I::from_index(items.item_count() - 1)
        }
    }
}

fn rm_slots_push(slots: &mut [u32; 4], e: u32) {
    if let Some(s) = slots.iter_mut().find(|s| **s == NIL) {
        *s = e;
    }
}

/// Removes `e`, keeping the others in order.
fn rm_slots_remove(slots: &mut [u32; 4], e: u32) {
    if let Some(i) = slots.iter().position(|&s| s == e) {
        slots.copy_within(i + 1.., i);
        slots[3] = NIL;
    }
}

fn key_matches(key: &AlphaKey, w: &RWme) -> bool {
    key.acceptable == w.acceptable
        && key.attr.is_none_or(|a| a == w.attr)
        && key.value.is_none_or(|v| v == w.value)
}
