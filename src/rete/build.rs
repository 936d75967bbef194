//! Adding productions to the network and excising them (Doorenbos, sections 2.4 and 2.6,
//! chapter 4): conditions are ordered so each joins on bound variables, nodes are shared
//! with existing productions, and a new node is filled with the matches already present (so
//! a rule added while running fires at once where it should).

use super::tests::{Field, JoinTest, Op, Operand};
use super::{
    AlphaKey, AmemId, Kind, MatchSink, NodeId, ProdId, ProdInfo, Rete, Shared, TokId, NIL,
    NIL_WME,
    NO_HASH_TEST,
};
use crate::ast::Head;
use crate::production::{Cond, Condition, Production, Term, Test};
use crate::symbols::{Sym, Symbols};
use rustc_hash::{FxHashMap, FxHashSet};

#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum BuildError {
    #[error("production {0} has no conditions")]
    NoConditions(String),
    /// Identical to a production already in the network.
    #[error("duplicate of production {0:?}")]
    Duplicate(ProdId),
    /// A negation compares with a variable that only a later condition binds: the
    /// reorderer placed it first because the rule's conditions are not all connected.
    /// 9.6 reports the same and then cannot go on; the rule is refused here.
    #[error("Rete build found test of unbound var: {0}")]
    UnboundInNegation(String),
    /// Matching the production against working memory passed the partial-match budget.
    #[error("its matches would take the matcher past {0} partial matches (limits --tokens)")]
    MatchCeiling(usize),
}

/// The first variable that a negation (or a condition of a conjunctive negation) compares
/// with before any condition binds it.
fn unbound_relational(conds: &[Condition], bound: &mut FxHashSet<String>) -> Option<String> {
    fn each_simple<'t>(t: &'t Test, f: &mut dyn FnMut(&'t Test)) {
        match t {
            Test::Conjunction(ts) => ts.iter().for_each(|t| each_simple(t, f)),
            other => f(other),
        }
    }
    fn fields(c: &Cond) -> [&Test; 3] {
        [&c.id, &c.attr, &c.value]
    }
    for c in conds {
        match c {
            Condition::Positive(p) => {
                for t in fields(p) {
                    each_simple(t, &mut |t| {
                        if let Test::Equal(Term::Var(v)) = t {
                            bound.insert(v.to_string());
                        }
                    });
                }
            }
            Condition::Negative(n) => {
                let mut local = bound.clone();
                let mut missing = None;
                for t in fields(n) {
                    for equality in [true, false] {
                        each_simple(t, &mut |t| match t {
                            Test::Equal(Term::Var(v)) if equality => {
                                local.insert(v.to_string());
                            }
                            Test::Relational(rt) if !equality => {
                                if let Term::Var(v) = &rt.term {
                                    if !local.contains(&**v) && missing.is_none() {
                                        missing = Some(v.to_string());
                                    }
                                }
                            }
                            _ => {}
                        });
                    }
                }
                if missing.is_some() {
                    return missing;
                }
            }
            Condition::Ncc(inner) => {
                if let Some(v) = unbound_relational(inner, &mut bound.clone()) {
                    return Some(v);
                }
            }
        }
    }
    None
}

/// The actions and flags of a rule with each variable replaced by where the conditions bind
/// it (or by its order of appearance, for variables the actions create).
/// `bound` tells where a variable is bound.
fn action_key(p: &Production, bound: &dyn Fn(&str) -> Option<(u32, Field)>) -> String {
    use crate::production::{Action, FuncCall, RhsTerm};
    use std::fmt::Write;
    type Bound<'b> = &'b dyn Fn(&str) -> Option<(u32, Field)>;
    fn term<'a>(t: &'a RhsTerm, b: Bound, fresh: &mut Vec<&'a str>, out: &mut String) {
        match t {
            RhsTerm::Var(v) => match b(v.as_str()) {
                Some((d, f)) => {
                    let _ = write!(out, "@{d}.{f:?}");
                }
                None => {
                    let k = fresh.iter().position(|x| x == v).unwrap_or_else(|| {
                        fresh.push(v);
                        fresh.len() - 1
                    });
                    let _ = write!(out, "#{k}");
                }
            },
            RhsTerm::Const(c) => crate::printer::push_constant_text(c, out),
            RhsTerm::Call(f) => call(f, b, fresh, out),
        }
    }
    fn call<'a>(f: &'a FuncCall, b: Bound, fresh: &mut Vec<&'a str>, out: &mut String) {
        out.push('(');
        out.push_str(&f.name);
        for a in &f.args {
            out.push(' ');
            term(a, b, fresh, out);
        }
        out.push(')');
    }
    // The flags as one digit each (a rule's support and kind are part of what it does).
    let f = &p.flags;
    let mut out: String = [
        f.o_support,
        f.i_support,
        f.chunk,
        f.default,
        f.template,
        f.interrupt,
        f.explain,
        f.justification,
    ]
    .iter()
    .map(|&b| if b { '1' } else { '0' })
    .collect();
    let mut fresh = Vec::new();
    for a in &p.actions {
        out.push('|');
        match a {
            Action::Make(m) => {
                for t in [&m.id, &m.attr, &m.value] {
                    term(t, bound, &mut fresh, &mut out);
                    out.push(' ');
                }
                out.push_str(m.pref.symbol());
                // An RL rule's value is what it learns, not what it does: two RL rules that
                // differ only in it are duplicates (observed on 9.6).
                if let Some(r) = m.referent.as_ref().filter(|_| p.rl_value().is_none()) {
                    term(r, bound, &mut fresh, &mut out);
                }
            }
            Action::Call(f) => call(f, bound, &mut fresh, &mut out),
        }
    }
    out
}

/// A hash of an [`action_key`], kept with each rule in its place.
fn action_key_hash(key: &str) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut h = rustc_hash::FxHasher::default();
    key.hash(&mut h);
    h.finish()
}

/// Where the next node attaches: under a token holder, or under a join (whose matches the
/// next holder stores).
#[derive(Debug, Clone, Copy)]
enum Cur {
    Holder(NodeId),
    Join(NodeId),
}

/// Where each variable is first bound, by name borrowed from the rule being built.
type Bindings<'a> = FxHashMap<&'a str, (u32, Field)>;

impl Rete {
    /// Adds a production; its matches against current working memory are reported at once.
    /// `rule_of` gives a loaded rule by its id (to compare a would-be duplicate's actions
    /// with). A rule that would be a duplicate of `twin` is not one when `apart(twin)` says
    /// so (an RL rule whose value differs, with `rl --set chunk-stop off`).
    pub fn add_production<'r>(
        &mut self,
        p: &Production,
        syms: &mut Symbols,
        sink: &mut dyn MatchSink,
        rule_of: &dyn Fn(ProdId) -> Option<&'r Production>,
        apart: &dyn Fn(ProdId) -> bool,
    ) -> Result<ProdId, BuildError> {
        if p.conditions.is_empty() {
            return Err(BuildError::NoConditions(p.name.to_string()));
        }
        let negated = p
            .conditions
            .iter()
            .any(|c| !matches!(c, Condition::Positive(_)));
        if let Some(v) = negated
            .then(|| unbound_relational(&p.conditions, &mut FxHashSet::default()))
            .flatten()
        {
            return Err(BuildError::UnboundInNegation(v));
        }
        let pid = ProdId(self.prods.len() as u32);
        self.fill_aborted = false;
        let mut bindings = Bindings::default();
        let mut positives = 0;
        let cur = self.build_conditions(
            &p.conditions,
            Cur::Holder(self.root),
            &mut bindings,
            syms,
            Some(&mut positives),
        );
        let parent = cur_node(cur);
        // A rule whose conditions share every node with another rule, and whose actions are
        // the same up to variable names, is a duplicate, which Soar ignores with a message.
        // (A rule keeps its key's hash; an equal hash is confirmed on the rules themselves.)
        let key = action_key(p, &|v| bindings.get(v).copied());
        let key_hash = action_key_hash(&key);
        let twin = self
            .all_children(parent)
            .find_map(|c| match self.nodes[c].kind {
                Kind::Production { prod } => self
                    .production(prod)
                    .filter(|i| {
                        i.action_key_hash == key_hash
                            && rule_of(prod).is_some_and(|r| {
                                action_key(r, &|v| i.bindings.get(v).copied()) == key
                            })
                            && !apart(prod)
                    })
                    .map(|_| prod),
                _ => None,
            });
        if let Some(twin) = twin {
            self.fill_aborted = false;
            self.delete_node_and_unused_ancestors(parent, syms, sink);
            return Err(BuildError::Duplicate(twin));
        }
        let depth = self.next_depth(cur);
        let pnode = self.new_node(Kind::Production { prod: pid }, parent, depth);
        self.attach(parent, pnode, true);
        self.prods.push(Some(ProdInfo {
            pnode,
            positives,
            bindings: super::VarBindings::new(bindings, &mut self.var_names, &mut self.binding_lists),
            action_key_hash: key_hash,
        }));
        self.fill_new_node(pnode, syms, sink);
        if std::mem::take(&mut self.fill_aborted) {
            self.excise(pid, syms, sink);
            return Err(BuildError::MatchCeiling(self.token_budget));
        }
        Ok(pid)
    }

    /// Whether a new node's filling has passed the token budget (which it then stops).
    fn fill_over_budget(&mut self) -> bool {
        if self.fill_aborted || (self.token_budget > 0 && self.token_total() > self.token_budget) {
            self.fill_aborted = true;
        }
        self.fill_aborted
    }

    fn next_depth(&self, cur: Cur) -> u32 {
        match cur {
            Cur::Holder(h) => self.nodes[h].depth + 1,
            Cur::Join(j) => self.nodes[self.nodes[j].parent].depth + 1,
        }
    }

    /// The token holder a positive condition joins from. Under a join that is a beta
    /// memory, one per hash key as in Soar (a memory is hashed on the variable its joins
    /// test the identifier against, `key`), so that sibling memories keep Soar's order.
    fn holder_under(&mut self, cur: Cur, key: Option<(u32, Field)>, syms: &Symbols) -> NodeId {
        match cur {
            Cur::Holder(h) => h,
            Cur::Join(j) => {
                let existing = self.all_children(j).find(|&c| {
                    self.nodes[c].kind == Kind::Memory
                        && self.nodes[c].hash.get() == key
                });
                if let Some(m) = existing {
                    return m;
                }
                let depth = self.next_depth(cur);
                let m = self.new_node(Kind::Memory, j, depth);
                self.nodes[m].hash = super::HashKey::new(key);
                self.attach(j, m, true);
                self.fill_new_node(m, syms, &mut super::NullSink);
                m
            }
        }
    }

    /// Soar builds a memory with one join as a single merged node, and splits it into a
    /// memory at the head of its parent's children when a second join is added (merging it
    /// back, again at the head, when one is left). The memory's place among its siblings
    /// (negative nodes, other memories, production nodes) follows those moves.
    fn move_memory_to_head(&mut self, m: NodeId) {
        if self.nodes[m].kind != Kind::Memory {
            return;
        }
        let parent = self.nodes[m].parent;
        let children = &mut self.nodes[parent].children;
        if let Some(pos) = children.as_slice().iter().position(|&c| c == m) {
            children.remove(pos);
            children.push(m);
        }
    }

    /// Whether `m` has exactly one join child (counting stops at two: a memory shared by
    /// thousands of rules is not walked for each new one).
    fn has_one_join_child(&self, m: NodeId) -> bool {
        self.all_children(m)
            .filter(|&c| matches!(self.nodes[c].kind, Kind::Join { .. }))
            .take(2)
            .count()
            == 1
    }

    /// Every child of `n`, linked or not.
    fn all_children(&self, n: NodeId) -> impl Iterator<Item = NodeId> + '_ {
        let mut c = self.nodes[n].first_child;
        std::iter::from_fn(move || {
            let this = c;
            (this != NodeId::NONE).then(|| {
                c = self.nodes[this].next_sibling;
                this
            })
        })
    }

    /// Takes `child` out of its parent's list of all children.
    fn remove_from_all_children(&mut self, parent: NodeId, child: NodeId) {
        let next = self.nodes[child].next_sibling;
        if self.nodes[parent].first_child == child {
            self.nodes[parent].first_child = next;
            return;
        }
        let mut c = self.nodes[parent].first_child;
        while c != NodeId::NONE {
            let after = self.nodes[c].next_sibling;
            if after == child {
                self.nodes[c].next_sibling = next;
                return;
            }
            c = after;
        }
    }

    /// Links `child` under `parent`: at the head of the children (activated first), or at
    /// the tail when `head` is false.
    fn attach(&mut self, parent: NodeId, child: NodeId, head: bool) {
        let first = self.nodes[parent].first_child;
        self.nodes[child].next_sibling = first;
        let p = &mut self.nodes[parent];
        p.first_child = child;
        if head {
            p.children.push(child);
        } else {
            p.children.insert(0, child);
        }
    }

    /// The hash key of an NCC's first condition when it is positive: its subnetwork
    /// starts from the memory that condition would join from, shared with the other
    /// conditions hashed alike below `cur`, as in Soar.
    fn first_hash_key<'a>(
        &mut self,
        inner: &'a [Condition],
        cur: Cur,
        bindings: &Bindings<'a>,
        syms: &mut Symbols,
    ) -> Option<(u32, Field)> {
        let Some(Condition::Positive(c)) = inner.first() else {
            return None;
        };
        let depth = match cur {
            Cur::Holder(h) => self.nodes[h].depth + 1,
            Cur::Join(_) => self.next_depth(cur) + 1,
        };
        let mut local = bindings.clone();
        let mut tests = Vec::new();
        cond_tests(c, depth, &mut local, syms, &mut tests);
        hash_key_of(&tests, depth)
    }

    fn build_conditions<'a>(
        &mut self,
        conds: &'a [Condition],
        mut cur: Cur,
        bindings: &mut Bindings<'a>,
        syms: &mut Symbols,
        mut positives: Option<&mut u32>,
    ) -> Cur {
        // Conditions come in join order: `reorder` put them there.
        for cond in conds {
            match cond {
                Condition::Positive(c) => {
                    // The depth its WME will have: one below the holder it joins from.
                    let depth = match cur {
                        Cur::Holder(h) => self.nodes[h].depth + 1,
                        Cur::Join(_) => self.next_depth(cur) + 1,
                    };
                    // (The tests are built in a reused buffer: most are a list some node
                    // already shares, so they need no allocation of their own.)
                    let mut tests = std::mem::take(&mut self.test_buf);
                    let key = cond_tests(c, depth, bindings, syms, &mut tests);
                    let hk = hash_key_of(&tests, depth);
                    let h = self.holder_under(cur, hk, syms);
                    let j = self.share_or_build_join(h, key, &tests, syms);
                    self.test_buf = tests;
                    cur = Cur::Join(j);
                    if let Some(count) = positives.as_mut() {
                        **count += 1;
                    }
                }
                Condition::Negative(c) => {
                    let parent = cur_node(cur);
                    let depth = self.next_depth(cur);
                    let mut local = bindings.clone();
                    let mut tests = std::mem::take(&mut self.test_buf);
                    let key = cond_tests(c, depth + 1, &mut local, syms, &mut tests);
                    let n = self.share_or_build_negative(parent, depth, key, &tests, syms);
                    self.test_buf = tests;
                    cur = Cur::Holder(n);
                }
                Condition::Ncc(inner) => {
                    let key = self.first_hash_key(inner, cur, bindings, syms);
                    let h = self.holder_under(cur, key, syms);
                    let owner_depth = self.nodes[h].depth + 1;
                    let mut local = bindings.clone();
                    let sub = self.build_conditions(inner, Cur::Holder(h), &mut local, syms, None);
                    let sub_parent = cur_node(sub);
                    let pdepth = self.next_depth(sub);
                    let partner = self.new_node(
                        Kind::NccPartner {
                            ncc: NodeId::NONE,
                            owner_depth,
                        },
                        sub_parent,
                        pdepth,
                    );
                    self.attach(sub_parent, partner, true);
                    let ncc = self.new_node(Kind::Ncc { partner }, h, owner_depth);
                    // The subnetwork is activated before the NCC node (Doorenbos, section 2.8).
                    self.attach(h, ncc, false);
                    if let Kind::NccPartner { ncc: slot, .. } =
                        &mut self.nodes[partner].kind
                    {
                        *slot = ncc;
                    }
                    self.fill_new_node(ncc, syms, &mut super::NullSink);
                    self.fill_new_node(partner, syms, &mut super::NullSink);
                    // Soar moves the subnetwork's top node to the head of its parent's
                    // children, with the NCC node right behind it.
                    self.move_memory_to_head(h);
                    cur = Cur::Holder(ncc);
                }
            }
        }
        cur
    }

    /// The join or negative node under `parent` on `amem` with these tests, if built. A
    /// parent with few children is scanned; a wide one (the memory that thousands of rules
    /// branch from) has its children in the share index.
    fn shared(&self, parent: NodeId, kind: u8, amem: AmemId, tests: &[JoinTest]) -> Option<NodeId> {
        // Equal test lists are stored once: no stored list, no node to share. The share
        // index keys on the list too: thousands of rules can branch from one memory on one
        // alpha memory, differing only in a constant (the rules of
        // `scripts/gen_rules.py counter`).
        let list = self.test_lists.find(tests)?;
        let same = |n: NodeId| self.node_test_list(n) == Some(list);
        if !self.nodes[parent].wide {
            return self.all_children(parent).find(|&c| {
                share_key(&self.nodes[c].kind) == Some((kind, amem)) && same(c)
            });
        }
        let nodes = self.share.get(&(parent, kind, amem, list))?;
        nodes.as_slice().iter().copied().find(|&n| same(n))
    }

    /// Records a new join or negative child `n` of `parent` (already attached) for sharing:
    /// in the share index once the parent has more than [`NARROW`] children.
    fn add_shared(&mut self, parent: NodeId, kind: u8, amem: AmemId, n: NodeId) {
        if self.nodes[parent].wide {
            self.index_shared(parent, kind, amem, n);
            return;
        }
        if self.all_children(parent).take(NARROW + 1).count() <= NARROW {
            return;
        }
        self.nodes[parent].wide = true;
        // Oldest first, as they would have been indexed one by one.
        let mut children: Vec<NodeId> = self.all_children(parent).collect();
        children.reverse();
        for c in children {
            if let Some((k, a)) = share_key(&self.nodes[c].kind) {
                self.index_shared(parent, k, a, c);
            }
        }
    }

    fn index_shared(&mut self, parent: NodeId, kind: u8, amem: AmemId, n: NodeId) {
        use std::collections::hash_map::Entry;
        let Some(list) = self.node_test_list(n) else {
            return;
        };
        match self.share.entry((parent, kind, amem, list)) {
            Entry::Vacant(e) => {
                e.insert(Shared::One(n));
            }
            Entry::Occupied(mut e) => {
                let s = e.get_mut();
                match s {
                    Shared::One(m) => *s = Shared::Many(vec![*m, n]),
                    Shared::Many(v) => v.push(n),
                }
            }
        }
    }

    /// The test list of a join or negative node (see `test_lists.rs`).
    fn node_test_list(&self, n: NodeId) -> Option<u32> {
        match self.nodes[n].kind {
            Kind::Join { tests, .. } | Kind::Negative { tests, .. } => Some(tests),
            _ => None,
        }
    }

    fn remove_shared(&mut self, parent: NodeId, kind: u8, amem: AmemId, n: NodeId) {
        if !self.nodes[parent].wide {
            return;
        }
        let Some(list) = self.node_test_list(n) else {
            return;
        };
        let key = (parent, kind, amem, list);
        let Some(s) = self.share.get_mut(&key) else {
            return;
        };
        match s {
            Shared::One(m) if *m == n => {
                self.share.remove(&key);
            }
            Shared::One(_) => {}
            Shared::Many(v) => {
                v.retain(|&m| m != n);
                if let [one] = v.as_slice() {
                    *s = Shared::One(*one);
                }
            }
        }
    }

    fn share_or_build_join(
        &mut self,
        h: NodeId,
        key: AlphaKey,
        tests: &[JoinTest],
        syms: &Symbols,
    ) -> NodeId {
        let amem = self.amem_for(key);
        if let Some(c) = self.shared(h, 0, amem, tests) {
            self.amems[amem].refs -= 1;
            return c;
        }
        let list = self.test_lists.intern(tests);
        let depth = self.nodes[h].depth;
        if self.has_one_join_child(h) {
            self.move_memory_to_head(h);
        }
        let j = self.new_node(
            Kind::Join {
                amem,
                tests: list,
                left_unlinked: false,
                right_unlinked: false,
            },
            h,
            depth,
        );
        self.attach(h, j, true);
        self.add_shared(h, 0, amem, j);
        self.hash_node(j, h, tests, depth + 1);
        self.nodes[j].same_amem_ancestor = self.find_same_amem_ancestor(j, amem);
        // Rete/UL: a join with an empty parent or an empty alpha memory starts unlinked; an
        // empty parent wins, so thousands of new joins on one alpha memory are not all its
        // successors (the first WME there would unlink each of them in turn). Unlinked on
        // the right, it is not linked first: relinking finds its place afresh.
        if self.nodes[h].token_count == 0 {
            if let Kind::Join { right_unlinked, .. } = &mut self.nodes[j].kind {
                *right_unlinked = true;
            }
        } else {
            self.link_to_amem(j, amem, syms);
            if self.amems[amem].count == 0 {
                self.unlink_left_pub(j);
            }
        }
        j
    }

    fn share_or_build_negative(
        &mut self,
        parent: NodeId,
        depth: u32,
        key: AlphaKey,
        tests: &[JoinTest],
        syms: &Symbols,
    ) -> NodeId {
        let amem = self.amem_for(key);
        if let Some(c) = self.shared(parent, 1, amem, tests) {
            self.amems[amem].refs -= 1;
            return c;
        }
        let list = self.test_lists.intern(tests);
        let n = self.new_node(
            Kind::Negative {
                amem,
                tests: list,
                right_unlinked: false,
            },
            parent,
            depth,
        );
        self.attach(parent, n, true);
        self.add_shared(parent, 1, amem, n);
        self.hash_node(n, n, tests, depth + 1);
        self.nodes[n].same_amem_ancestor = self.find_same_amem_ancestor(n, amem);
        self.link_to_amem(n, amem, syms);
        self.fill_new_node(n, syms, &mut super::NullSink);
        if self.nodes[n].token_count == 0 {
            self.unlink_right(n);
        }
        n
    }

    /// The one shared copy of a list of join tests: most joins test only their identifier
    /// against one binding place, so 100,000 rules hold a handful of distinct lists.
    /// Fills a newly built token holder with the matches its parent already has
    /// (Doorenbos `update-new-node-with-matches-from-above`).
    fn fill_new_node(&mut self, n: NodeId, syms: &Symbols, sink: &mut dyn MatchSink) {
        let parent = self.nodes[n].parent;
        // Nothing to fill from (the common case while loading): no kind to copy, no lists.
        let source = match self.nodes[parent].kind {
            Kind::Join { .. } => self.nodes[parent].parent,
            _ => parent,
        };
        if self.nodes[source].first_token == TokId::NONE {
            return;
        }
        let pkind = self.nodes[parent].kind.clone();
        // Each activation below makes at most one token in the new node, which has no
        // children yet: checking the budget before each bounds the filling.
        match pkind {
            Kind::Root | Kind::Memory => {
                for t in self.node_tokens(parent).into_iter().rev() {
                    if self.fill_over_budget() {
                        return;
                    }
                    self.left_activation(n, t, NIL_WME, syms, sink);
                }
            }
            Kind::Negative { .. } | Kind::Ncc { .. } => {
                for t in self.node_tokens(parent).into_iter().rev() {
                    if self.fill_over_budget() {
                        return;
                    }
                    if self.links[t].results == NIL {
                        self.left_activation(n, t, NIL_WME, syms, sink);
                    }
                }
            }
            Kind::Join { amem, tests, .. } => {
                let grand = self.nodes[parent].parent;
                let depth = self.nodes[grand].depth + 1;
                let items = self.amem_items(amem);
                for t in self.live_tokens(grand).into_iter().rev() {
                    for &w in items.iter().rev() {
                        if self.fill_over_budget() {
                            return;
                        }
                        if self.tokens[t].alive
                            && self.tests_pass(self.test_lists.get(tests), t, w, depth, syms)
                        {
                            self.left_activation(n, t, w, syms, sink);
                        }
                    }
                }
            }
            Kind::NccPartner { .. } | Kind::Production { .. } => {}
        }
    }

    pub(crate) fn unlink_left_pub(&mut self, n: NodeId) {
        let parent = self.nodes[n].parent;
        if let Kind::Join { left_unlinked, .. } = &mut self.nodes[n].kind {
            *left_unlinked = true;
        }
        self.mirror_left_unlinked(n, true);
        self.nodes[parent].children.retain(|c| *c != n);
    }

    /// Removes a production and every node no other production uses; its matches retract.
    pub fn excise(&mut self, pid: ProdId, syms: &Symbols, sink: &mut dyn MatchSink) {
        let Some(info) = self.prods.get_mut(pid.0 as usize).and_then(|x| x.take()) else {
            return;
        };
        self.delete_node_and_unused_ancestors(info.pnode, syms, sink);
    }

    pub(crate) fn delete_node_and_unused_ancestors(
        &mut self,
        n: NodeId,
        syms: &Symbols,
        sink: &mut dyn MatchSink,
    ) {
        let mut n = n;
        loop {
            if n == self.root
                || !self.nodes[n].alive
                || self.nodes[n].first_child != NodeId::NONE
            {
                return;
            }
            let kind = self.nodes[n].kind.clone();
            // Tokens first (an NCC node's tokens take their partner results with them).
            loop {
                let t = self.nodes[n].first_token;
                if t == TokId::NONE {
                    break;
                }
                self.delete_token_and_descendants(t, syms, sink);
            }
            let parent_of = self.nodes[n].parent;
            if let (Kind::Join { .. }, Some((d, f))) = (&kind, self.nodes[n].hash.get()) {
                self.release_left_key(parent_of, d, f);
            }
            match &kind {
                Kind::Join { amem, .. } => self.remove_shared(parent_of, 0, *amem, n),
                Kind::Negative { amem, .. } => self.remove_shared(parent_of, 1, *amem, n),
                _ => {}
            }
            match kind {
                Kind::Join { amem, .. } | Kind::Negative { amem, .. } => {
                    self.succ_links.forget(&mut self.amems[amem].successors, n);
                    self.release_amem(amem);
                }
                _ => {}
            }
            let parent = self.nodes[n].parent;
            self.nodes[parent].children.retain(|c| *c != n);
            self.remove_from_all_children(parent, n);
            self.free_node(n);
            if matches!(kind, Kind::Join { .. }) && self.has_one_join_child(parent) {
                self.move_memory_to_head(parent);
            }
            if let Kind::Ncc { partner } = kind {
                // The partner's branch may now be unused too.
                self.ncc_buffers.remove(&partner);
                self.delete_node_and_unused_ancestors(partner, syms, sink);
            }
            // The partner's branch may already have taken the parent with it.
            if !self.nodes[parent].alive {
                return;
            }
            n = parent;
        }
    }

    /// Hashes join or negative node `n` on its identifier equality test, if it has one
    /// (`new_depth`: the depth of its WME): both its memories are then indexed on that
    /// key (`holder`: the node whose tokens it joins), and a pair the index gives skips
    /// the test (`Node::hash_test`).
    fn hash_node(&mut self, n: NodeId, holder: NodeId, tests: &[JoinTest], new_depth: u32) {
        if let Some((i, (d, f))) = hash_test_of(tests, new_depth) {
            let node = &mut self.nodes[n];
            node.hash = super::HashKey::new(Some((d, f)));
            // Past 255 the place saturates to NO_HASH_TEST (255), and the pair skips test
            // 255 instead: harmless, since only a goal test and identifier equalities with
            // this same WME (`{<x> <x> ...}`, always true) can come before the hash test
            // (`cond_tests` puts identifier equalities first; constants on an identifier
            // are rejected at load).
            node.hash_test = u8::try_from(i).unwrap_or(NO_HASH_TEST);
            self.add_left_key(holder, d, f);
        }
    }
}

/// The test a join or negative node hashes on: its new WME's identifier equal to a variable
/// bound above it (Soar hashes both memories on it, so a WME meets only the tokens it can
/// join). `new_depth` is the depth of the new WME.
fn hash_key_of(tests: &[JoinTest], new_depth: u32) -> Option<(u32, Field)> {
    hash_test_of(tests, new_depth).map(|(_, key)| key)
}

/// [`hash_key_of`] with the test's place in `tests` (the test a hashed pair need not run).
fn hash_test_of(tests: &[JoinTest], new_depth: u32) -> Option<(usize, (u32, Field))> {
    tests.iter().enumerate().find_map(|(i, t)| match t {
        JoinTest::Compare {
            field: Field::Id,
            op: Op::Eq,
            operand: Operand::Bound { depth, field },
        } if *depth < new_depth => Some((i, (*depth, *field))),
        _ => None,
    })
}

/// Children a parent may have before they are indexed for sharing: scanning a few costs
/// less than an index entry for each (most nodes have one child).
const NARROW: usize = 8;

/// How the share index files a node: join (0) or negative (1), and its alpha memory.
fn share_key(kind: &Kind) -> Option<(u8, AmemId)> {
    match kind {
        Kind::Join { amem, .. } => Some((0, *amem)),
        Kind::Negative { amem, .. } => Some((1, *amem)),
        _ => None,
    }
}

fn cur_node(cur: Cur) -> NodeId {
    match cur {
        Cur::Holder(h) | Cur::Join(h) => h,
    }
}

/// The alpha-memory key and join tests of one condition whose WME will sit at `depth`.
/// Variables first met here are bound at (`depth`, field).
fn cond_tests<'a>(
    c: &'a Cond,
    depth: u32,
    bindings: &mut Bindings<'a>,
    syms: &mut Symbols,
    tests: &mut Vec<JoinTest>,
) -> AlphaKey {
    tests.clear();
    let mut key = AlphaKey {
        attr: None,
        value: None,
        acceptable: c.acceptable,
    };
    match c.goal {
        Head::State => tests.push(JoinTest::IsGoal),
        Head::Impasse => tests.push(JoinTest::IsImpasse),
        Head::None => {}
    }
    for (field, test) in [
        (Field::Id, &c.id),
        (Field::Attr, &c.attr),
        (Field::Value, &c.value),
    ] {
        // Equality tests first, so that a variable bound here is usable by the others (two
        // passes over the field keep each kind in its written order).
        for equality in [true, false] {
            for_each_simple(test, &mut |t| {
                if matches!(t, Test::Equal(_)) == equality {
                    add_test(t, field, depth, &mut key, tests, bindings, syms);
                }
            });
        }
    }
    key
}

/// One simple test of a condition's field, as an alpha-memory constant or a join test.
fn add_test<'a>(
    t: &'a Test,
    field: Field,
    depth: u32,
    key: &mut AlphaKey,
    tests: &mut Vec<JoinTest>,
    bindings: &mut Bindings<'a>,
    syms: &mut Symbols,
) {
    match t {
        Test::Equal(Term::Const(k)) => {
            let s = syms.constant(k);
            match field {
                Field::Attr if key.attr.is_none() => key.attr = Some(s),
                Field::Value if key.value.is_none() => key.value = Some(s),
                _ => tests.push(JoinTest::Compare {
                    field,
                    op: Op::Eq,
                    operand: Operand::Const(s),
                }),
            }
        }
        Test::Equal(Term::Var(v)) => match bindings.get(&**v) {
            Some(&(d, f)) => tests.push(JoinTest::Compare {
                field,
                op: Op::Eq,
                operand: Operand::Bound { depth: d, field: f },
            }),
            None => {
                bindings.insert(v, (depth, field));
            }
        },
        Test::Relational(rt) => match &rt.term {
            Term::Var(v) => {
                // A rule whose variable is bound nowhere does not load, the reorderer
                // moves a positive condition's relational tests to where their referents
                // are bound, and `add_production` refuses a negation placed before its
                // referent is bound (`unbound_relational`): the referent is always bound.
                if let Some(&(d, f)) = bindings.get(&**v) {
                    tests.push(JoinTest::Compare {
                        field,
                        op: Op::Rel(rt.op),
                        operand: Operand::Bound { depth: d, field: f },
                    });
                }
            }
            Term::Const(k) => {
                let s = syms.constant(k);
                tests.push(JoinTest::Compare {
                    field,
                    op: Op::Rel(rt.op),
                    operand: Operand::Const(s),
                });
            }
        },
        Test::Disjunction(items) => {
            let items: Vec<Sym> = items.iter().map(|k| syms.constant(k)).collect();
            tests.push(JoinTest::Disjunction { field, items });
        }
        Test::Conjunction(_) => {}
    }
}

/// The simple (non-conjunctive) tests of a field, in order.
fn for_each_simple<'a>(t: &'a Test, f: &mut dyn FnMut(&'a Test)) {
    match t {
        Test::Conjunction(ts) => ts.iter().for_each(|t| for_each_simple(t, f)),
        other => f(other),
    }
}
