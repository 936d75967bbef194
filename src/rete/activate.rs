//! Activations (Doorenbos, sections 2.3 to 2.8): right activations of joins and negative
//! nodes by a new WME, left activations of every node kind by a new token, and the join
//! tests.
//!
//! This is the matcher's hot path, so it allocates nothing once warm: the lists an
//! activation walks (children, alpha-memory candidates, token candidates) are copied onto
//! one shared scratch stack (`Rete::scratch`) and each activation pops its part when done.
//! The copy keeps the old snapshot semantics exactly (a list that changes during the
//! activation is still walked as it was), which keeps every iteration order as it was.

use super::tests::{relation_holds, Field, JoinTest, Op, Operand};
use super::{AmemId, Kind, MatchSink, NodeId, Rete, TokId, NIL, NIL_WME};
use crate::symbols::{SymData, Symbols};
use crate::wm::WmeId;

impl Rete {
    /// Runs every test of a join or negative node on token `t` (the parent's) and WME `w`.
    /// `new_depth` is the depth of the token that would hold `w`.
    pub(crate) fn tests_pass(
        &self,
        tests: &[JoinTest],
        t: TokId,
        w: WmeId,
        new_depth: u32,
        syms: &Symbols,
    ) -> bool {
        self.tests_pass_but(tests, usize::MAX, t, w, new_depth, syms)
    }

    /// `tests_pass`, leaving out the test at `skip`: the identifier equality the pair's
    /// hash index lookup already made.
    #[inline(always)]
    fn tests_pass_but(
        &self,
        tests: &[JoinTest],
        skip: usize,
        t: TokId,
        w: WmeId,
        new_depth: u32,
        syms: &Symbols,
    ) -> bool {
        for (i, test) in tests.iter().enumerate() {
            if i == skip {
                continue;
            }
            let ok = match test {
                JoinTest::Compare { field, op, operand } => {
                    let a = self.field(w, *field);
                    let b = match operand {
                        Operand::Const(c) => *c,
                        Operand::Bound { depth, field } => {
                            if *depth == new_depth {
                                self.field(w, *field)
                            } else {
                                let wm = self.wme_at_depth(t, *depth);
                                if wm == NIL_WME {
                                    return false;
                                }
                                self.field(wm, *field)
                            }
                        }
                    };
                    // Equality, nearly every join test, without the call.
                    match op {
                        Op::Eq => a == b,
                        _ => relation_holds(syms, *op, a, b),
                    }
                }
                JoinTest::Disjunction { field, items } => items.contains(&self.field(w, *field)),
                JoinTest::IsGoal => syms.is_goal(self.wme(w).id),
                JoinTest::IsImpasse => syms.is_impasse(self.wme(w).id),
            };
            if !ok {
                return false;
            }
        }
        true
    }

    /// The tests of node `n` that read only the new WME (constants, disjunctions, goal and
    /// impasse tests, fields of the WME itself): when one fails, no token can pair with the
    /// WME, so a right activation ends before it looks for tokens.
    fn wme_tests_pass(&self, n: NodeId, w: WmeId, new_depth: u32, syms: &Symbols) -> bool {
        self.join_tests(n)
            .iter()
            .filter(|test| reads_wme_alone(test, new_depth))
            .all(|test| match test {
                JoinTest::Compare {
                    field,
                    op,
                    operand: Operand::Const(c),
                } => relation_holds(syms, *op, self.field(w, *field), *c),
                JoinTest::Compare {
                    field,
                    op,
                    operand: Operand::Bound { field: bf, .. },
                } => relation_holds(syms, *op, self.field(w, *field), self.field(w, *bf)),
                JoinTest::Disjunction { field, items } => {
                    items.contains(&self.field(w, *field))
                }
                JoinTest::IsGoal => syms.is_goal(self.wme(w).id),
                JoinTest::IsImpasse => syms.is_impasse(self.wme(w).id),
            })
    }

    /// How many tests of join or negative node `n` read the new WME alone (those
    /// `wme_tests_pass` runs), for its alpha-memory successor entry.
    pub(crate) fn wme_test_count(&self, n: NodeId) -> usize {
        let new_depth = match self.nodes[n].kind {
            Kind::Join { .. } => self.nodes[self.nodes[n].parent].depth + 1,
            _ => self.nodes[n].depth + 1,
        };
        self.join_tests(n)
            .iter()
            .filter(|test| reads_wme_alone(test, new_depth))
            .count()
    }

    /// The tests of join or negative node `n` (read in place, not cloned) on a pair its
    /// candidate lists gave.
    #[inline(always)]
    fn node_tests_pass(&self, n: NodeId, t: TokId, w: WmeId, new_depth: u32, s: &Symbols) -> bool {
        let skip = self.nodes[n].hash_test as usize;
        self.tests_pass_but(self.join_tests(n), skip, t, w, new_depth, s)
    }

    /// The WME of the ancestor token (of `t`, inclusive) at `depth`.
    pub(crate) fn wme_at_depth(&self, t: TokId, depth: u32) -> WmeId {
        if t == TokId::NONE {
            return NIL_WME;
        }
        let tok = &self.tokens[t];
        if depth > tok.depth {
            return NIL_WME;
        }
        self.rows[(tok.row + depth) as usize]
    }

    /// Right-activates the linked successors of alpha memory `a` with its new WME `w`, in
    /// their list order (see `link_to_amem`).
    pub(crate) fn right_activate_successors(
        &mut self,
        a: AmemId,
        w: WmeId,
        syms: &Symbols,
        sink: &mut dyn MatchSink,
    ) {
        // The successors this WME can reach, snapshotted first (activations relink and
        // unlink successors). A linked join whose test on the WME alone fails is left out:
        // no token can pair with it, and its right activation would change nothing else
        // (its parent has tokens while it is linked on both sides).
        let rw = self.wme(w);
        let fields = [rw.id, rw.attr, rw.value];
        let value = rw.value;
        // The value's integer, read from the symbol table once and only if a successor
        // compares it with an integer (identifiers and attributes are left to the full test).
        let mut value_int: Option<Option<i64>> = None;
        let base = self.succ_scratch.len();
        for s in self.succ_links.iter(self.amems[a].successors) {
            if let (Some(pre), false) = (&s.pre, s.left_unlinked) {
                let int = match pre.field {
                    Field::Value if pre.int_order.is_some() => {
                        *value_int.get_or_insert_with(|| match syms.get(value) {
                            SymData::Int(i) => Some(*i),
                            _ => None,
                        })
                    }
                    _ => None,
                };
                if !pre.passes(syms, fields[pre.field as usize], int) {
                    continue;
                }
            }
            self.succ_scratch.push(*s);
        }
        for i in base..self.succ_scratch.len() {
            let s = self.succ_scratch[i];
            if self.nodes[s.node].alive {
                // A linked join passed its prefilter above: with no other test of the WME
                // alone, checking them again would change nothing.
                let checked = !s.left_unlinked && !s.wme_tests;
                self.right_activation(s.node, w, checked, syms, sink);
            }
        }
        self.succ_scratch.truncate(base);
    }

    /// `checked`: the node's tests of the WME alone are known to pass.
    fn right_activation(
        &mut self,
        n: NodeId,
        w: WmeId,
        checked: bool,
        syms: &Symbols,
        sink: &mut dyn MatchSink,
    ) {
        self.right_activations += 1;
        match self.nodes[n].kind {
            Kind::Join { left_unlinked, .. } => {
                let parent = self.nodes[n].parent;
                if left_unlinked {
                    self.relink_left(n);
                }
                if self.nodes[parent].token_count == 0 {
                    self.unlink_right(n);
                    return;
                }
                let depth = self.nodes[parent].depth + 1;
                if !checked && !self.wme_tests_pass(n, w, depth, syms) {
                    return;
                }
                let blockable = matches!(
                    self.nodes[parent].kind,
                    Kind::Negative { .. } | Kind::Ncc { .. }
                );
                let base = self.scratch.len();
                self.push_token_candidates(parent, n, w);
                for i in base..self.scratch.len() {
                    let t = TokId::new(self.scratch[i]);
                    if blockable && self.links[t].results != NIL {
                        continue;
                    }
                    if self.doom.active && self.tokens[t].doomed && self.may_skip_doomed(n)
                    {
                        continue;
                    }
                    if self.tokens[t].alive
                        && self.wmes[w.0 as usize].is_some()
                        && self.node_tests_pass(n, t, w, depth, syms)
                    {
                        self.activate_children(n, t, w, syms, sink);
                    }
                }
                self.scratch.truncate(base);
            }
            Kind::Negative { .. } => {
                let depth = self.nodes[n].depth + 1;
                if !checked && !self.wme_tests_pass(n, w, depth, syms) {
                    return;
                }
                let base = self.scratch.len();
                self.push_token_candidates(n, n, w);
                for i in base..self.scratch.len() {
                    let t = TokId::new(self.scratch[i]);
                    if !self.tokens[t].alive || self.wmes[w.0 as usize].is_none() {
                        continue;
                    }
                    if self.node_tests_pass(n, t, w, depth, syms) {
                        if self.links[t].results == NIL {
                            self.delete_descendants(t, syms, sink);
                        }
                        self.add_neg_result(t, w);
                    }
                }
                self.scratch.truncate(base);
            }
            _ => {}
        }
    }

    /// Left-activates the linked children of `n` with (parent token `t`, WME `w`), head first.
    pub(crate) fn activate_children(
        &mut self,
        n: NodeId,
        t: TokId,
        w: WmeId,
        syms: &Symbols,
        sink: &mut dyn MatchSink,
    ) {
        let children = self.nodes[n].children.as_slice();
        if children.len() == 1 {
            // The common case needs no copy of the list.
            let c = children[0];
            if self.child_may_activate(c, t, w) {
                self.left_activation(c, t, w, syms, sink);
            }
            return;
        }
        let base = self.scratch.len();
        self.scratch.extend(children.iter().rev().map(|c| c.raw()));
        for i in base..self.scratch.len() {
            let c = NodeId::new(self.scratch[i]);
            if !self.nodes[c].alive || !self.tokens[t].alive {
                continue;
            }
            if w != NIL_WME && self.wmes[w.0 as usize].is_none() {
                break;
            }
            self.left_activation(c, t, w, syms, sink);
        }
        self.scratch.truncate(base);
    }

    fn child_may_activate(&self, c: NodeId, t: TokId, w: WmeId) -> bool {
        self.nodes[c].alive
            && self.tokens[t].alive
            && (w == NIL_WME || self.wmes[w.0 as usize].is_some())
    }

    /// Left-activates `n` with (parent token `t`, WME `w`), and everything below it,
    /// depth first. Memories and joins hand their children to the `pending` stack instead
    /// of calling down, so the walk needs no call-stack depth however long a chain of
    /// conditions is. Each waiting activation is checked when its turn comes, as a
    /// recursive walk would check it then; what a call from here pushed is all done when
    /// it returns (negative and NCC nodes rely on that).
    pub(crate) fn left_activation(
        &mut self,
        n: NodeId,
        t: TokId,
        w: WmeId,
        syms: &Symbols,
        sink: &mut dyn MatchSink,
    ) {
        let base = self.pending.len();
        self.left_activation_one(n, t, w, syms, sink);
        while self.pending.len() > base {
            match self.pending.pop().expect("above base") {
                Pending::Child(c, t, w) => {
                    if self.child_may_activate(c, t, w) {
                        self.left_activation_one(c, t, w, syms, sink);
                    }
                }
                Pending::Candidate(n, t, wm) => {
                    let batch = self.doom.active;
                    if batch
                        && (self.tokens[t].doomed || self.wme_doomed(wm))
                        && self.may_skip_doomed(n)
                    {
                        continue;
                    }
                    let depth = self.tokens[t].depth + 1;
                    if self.wmes[wm.0 as usize].is_some()
                        && self.tokens[t].alive
                        && self.node_tests_pass(n, t, wm, depth, syms)
                    {
                        self.pass_down(n, t, wm, syms, sink);
                    }
                }
            }
        }
    }

    /// The left activations of the children of `n` with (`t`, `w`): a lone child's runs at
    /// once, as it would if pushed (it would be popped next); several are queued. The
    /// child's own activation queues what lies below it, so the call stack stays shallow.
    #[inline(always)]
    fn pass_down(
        &mut self,
        n: NodeId,
        t: TokId,
        w: WmeId,
        syms: &Symbols,
        sink: &mut dyn MatchSink,
    ) {
        if let &[c] = self.nodes[n].children.as_slice() {
            if self.child_may_activate(c, t, w) {
                self.left_activation_one(c, t, w, syms, sink);
            }
        } else {
            self.push_children(n, t, w);
        }
    }

    /// Queues the left activations of the children of `n` with (`t`, `w`), to run head
    /// first: the head of a node's children is the last of its list, and the stack pops
    /// the last first (the order of `activate_children`).
    fn push_children(&mut self, n: NodeId, t: TokId, w: WmeId) {
        let children = self.nodes[n].children.as_slice();
        self.pending
            .extend(children.iter().map(|&c| Pending::Child(c, t, w)));
    }

    fn left_activation_one(
        &mut self,
        n: NodeId,
        t: TokId,
        w: WmeId,
        syms: &Symbols,
        sink: &mut dyn MatchSink,
    ) {
        self.left_activations += 1;
        match self.nodes[n].kind {
            Kind::Root => {}
            Kind::Memory => {
                let nt = self.new_token(n, t, w);
                self.pass_down(n, nt, NIL_WME, syms, sink);
            }
            Kind::Join {
                amem,
                right_unlinked,
                ..
            } => {
                if right_unlinked {
                    self.relink_right(n, syms);
                    if self.amems[amem].count == 0 {
                        self.unlink_left(n);
                        return;
                    }
                }
                // Pushed last first, so that the stack pops them in the order found.
                let base = self.scratch.len();
                self.push_amem_candidates(amem, n, t);
                while self.scratch.len() > base {
                    let w = WmeId(self.scratch.pop().expect("above base"));
                    self.pending.push(Pending::Candidate(n, t, w));
                }
            }
            Kind::Negative { .. } | Kind::Ncc { .. } | Kind::NccPartner { .. } => {
                self.left_activation_cold(n, t, w, syms, sink)
            }
            Kind::Production { prod } => {
                let nt = self.new_token(n, t, w);
                sink.matched(prod, nt);
            }
        }
    }

    /// The left activations of negative and NCC nodes, kept out of `left_activation` so
    /// that its hot arms (memories, joins, productions) stay small.
    #[inline(never)]
    fn left_activation_cold(
        &mut self,
        n: NodeId,
        t: TokId,
        w: WmeId,
        syms: &Symbols,
        sink: &mut dyn MatchSink,
    ) {
        match self.nodes[n].kind {
            Kind::Negative {
                amem,
                right_unlinked,
                ..
            } => {
                if right_unlinked {
                    self.relink_right(n, syms);
                }
                let nt = self.new_token(n, t, w);
                let depth = self.tokens[nt].depth + 1;
                let base = self.scratch.len();
                self.push_amem_candidates(amem, n, nt);
                for i in base..self.scratch.len() {
                    let wm = WmeId(self.scratch[i]);
                    if self.node_tests_pass(n, nt, wm, depth, syms) {
                        self.add_neg_result(nt, wm);
                    }
                }
                self.scratch.truncate(base);
                if self.links[nt].results == NIL {
                    self.activate_children(n, nt, NIL_WME, syms, sink);
                }
            }
            Kind::Ncc { partner } => {
                let nt = self.new_token(n, t, w);
                // Results the subnetwork found before this token existed (Doorenbos, section 2.8):
                // those whose ancestor above the subnetwork is this token's parent.
                let owner_depth = match self.nodes[partner].kind {
                    Kind::NccPartner { owner_depth, .. } => owner_depth,
                    _ => 0,
                };
                let buffered = self.ncc_buffers.remove(&partner).unwrap_or_default();
                let mut keep = Vec::new();
                for r in buffered {
                    if !self.tokens[r].alive {
                        continue;
                    }
                    if self.result_owner_parent(r, owner_depth) == t {
                        self.add_ncc_result(nt, r);
                    } else {
                        keep.push(r);
                    }
                }
                if !keep.is_empty() {
                    self.ncc_buffers.insert(partner, keep);
                }
                if self.links[nt].results == NIL {
                    self.activate_children(n, nt, NIL_WME, syms, sink);
                }
            }
            Kind::NccPartner {
                ncc, owner_depth, ..
            } => {
                let r = self.new_token(n, t, w);
                // The owner is the NCC token whose parent is the result's ancestor above the
                // subnetwork.
                let owner_parent = self.result_owner_parent(r, owner_depth);
                let owner = self.find_ncc_owner(ncc, owner_parent);
                match owner {
                    Some(o) => {
                        let had = self.links[o].results != NIL;
                        self.add_ncc_result(o, r);
                        if !had {
                            self.delete_descendants(o, syms, sink);
                        }
                    }
                    None => {
                        self.ncc_buffers.entry(n).or_default().push(r);
                    }
                }
            }
            _ => {}
        }
    }

    /// The tokens of a holder that its children see: a negative or NCC node's tokens that
    /// have results are blocked (Doorenbos, section 2.7).
    pub(crate) fn live_tokens(&self, n: NodeId) -> Vec<TokId> {
        let mut toks = self.node_tokens(n);
        if matches!(
            self.nodes[n].kind,
            Kind::Negative { .. } | Kind::Ncc { .. }
        ) {
            toks.retain(|t| self.links[*t].results == NIL);
        }
        toks
    }

    fn result_owner_parent(&self, r: TokId, owner_depth: u32) -> TokId {
        let mut x = r;
        while x != TokId::NONE && self.tokens[x].depth > owner_depth {
            x = self.tokens[x].parent;
        }
        if x != TokId::NONE {
            self.tokens[x].parent
        } else {
            TokId::NONE
        }
    }

    fn find_ncc_owner(&self, ncc: NodeId, owner_parent: TokId) -> Option<TokId> {
        let mut t = self.nodes[ncc].first_token;
        while t != TokId::NONE {
            if self.tokens[t].parent == owner_parent {
                return Some(t);
            }
            t = self.tokens[t].next_in_node;
        }
        None
    }
}

/// Whether a join test reads the new WME alone: a constant, a disjunction, a goal or
/// impasse test, or a comparison with another field of the WME itself (the token that
/// would hold it is at `new_depth`).
fn reads_wme_alone(test: &JoinTest, new_depth: u32) -> bool {
    !matches!(
        test,
        JoinTest::Compare {
            operand: Operand::Bound { depth, .. },
            ..
        } if *depth != new_depth
    )
}

/// A left activation on the matcher's `pending` stack.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Pending {
    /// Left-activate the node with (token, WME), if both are still alive.
    Child(NodeId, TokId, WmeId),
    /// A WME of a join's alpha memory, to be tested against the token and, when it passes,
    /// to activate the join's children.
    Candidate(NodeId, TokId, WmeId),
}
