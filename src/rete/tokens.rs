//! Tokens and their bookkeeping: creation, the tree-based removal of Doorenbos
//! (section 2.5), and the result lists of negative and NCC nodes (sections 2.7 and 2.8).
//! Every list is intrusive (indexes into arenas), so removal is constant time and order is
//! kept.

use super::hash::NO_VALUE;
use super::{
    alloc, Kind, LeftMode, MatchSink, NegResult, NodeId, ResultLinks, Rete, TokId, Token, NIL,
    NIL_WME,
};
use crate::symbols::Symbols;
use crate::wm::WmeId;

impl Rete {
    pub(crate) fn new_token(&mut self, node: NodeId, parent: TokId, wme: WmeId) -> TokId {
        // The root token alone has no parent (`TokId::NONE` is past every token).
        let (depth, parent_row, parent_doomed) = match self.tokens.get(parent.index()) {
            Some(p) => (p.depth + 1, p.row, p.doomed),
            None => (0, 0, false),
        };
        self.tokens_made += 1;
        let head = self.nodes[node].first_token;
        let doomed =
            self.doom.active && (parent_doomed || (wme != NIL_WME && self.wme_doomed(wme)));
        let row = self.alloc_row(parent_row, depth, wme);
        // The value at the holder's first index key, read off the row just written.
        let keyed = !self.nodes[node].left_keys.is_empty();
        let key = match self.nodes[node].left_keys.as_slice().first() {
            Some(&(d, f, _)) if d <= depth => {
                let w = self.rows[(row + d) as usize];
                match self.wmes.get(w.0 as usize).and_then(Option::as_ref) {
                    Some(rw) => rw.field(f),
                    None => NO_VALUE,
                }
            }
            _ => NO_VALUE,
        };
        let mut next_of_wme = TokId::NONE;
        let mut rw_tokens = None;
        if let Some(rw) = self.wmes.get_mut(wme.0 as usize).and_then(Option::as_mut) {
            next_of_wme = rw.tokens;
            rw_tokens = Some(&mut rw.tokens);
        }
        let first_sib = match self.tokens.get(parent.index()) {
            Some(p) => p.first_child,
            None => TokId::NONE,
        };
        let tok = Token {
            node,
            parent,
            wme,
            depth,
            first_child: TokId::NONE,
            next_sib: first_sib,
            prev_sib: TokId::NONE,
            next_in_node: head,
            prev_in_node: TokId::NONE,
            next_of_wme,
            prev_of_wme: TokId::NONE,
            hfirst: NIL,
            row,
            key,
            alive: true,
            doomed,
        };
        // The token's place: a freed one (whose result links were left empty), or a new
        // one at the end, with its result links beside it.
        let t = match self.free_tokens.pop() {
            Some(t) => t,
            None => TokId::new(self.tokens.len() as u32),
        };
        if let Some(slot) = rw_tokens {
            *slot = t;
        }
        if t.index() == self.tokens.len() {
            self.tokens.push(tok);
            self.links.push(ResultLinks::NONE);
        } else {
            self.tokens[t] = tok;
        }
        if head != TokId::NONE {
            self.tokens[head].prev_in_node = t;
        }
        if next_of_wme != TokId::NONE {
            self.tokens[next_of_wme].prev_of_wme = t;
        }
        if parent != TokId::NONE {
            if first_sib != TokId::NONE {
                self.tokens[first_sib].prev_sib = t;
            }
            self.tokens[parent].first_child = t;
        }
        let n = &mut self.nodes[node];
        n.first_token = t;
        n.token_count += 1;
        if keyed {
            self.token_added_to_holder(node, t);
        }
        t
    }

    /// Tokens held by a node, head (newest) first.
    pub(crate) fn node_tokens(&self, n: NodeId) -> Vec<TokId> {
        let mut out = Vec::with_capacity(self.nodes[n].token_count as usize);
        let mut t = self.nodes[n].first_token;
        while t != TokId::NONE {
            out.push(t);
            t = self.tokens[t].next_in_node;
        }
        out
    }

    pub(crate) fn delete_descendants(
        &mut self,
        t: TokId,
        syms: &Symbols,
        sink: &mut dyn MatchSink,
    ) {
        loop {
            let c = self.tokens[t].first_child;
            if c == TokId::NONE {
                break;
            }
            self.delete_token_and_descendants(c, syms, sink);
        }
    }

    /// Removes a token and everything built on it, reporting retracted matches: children
    /// before their parent, each token's children newest first (the order of Doorenbos'
    /// recursive removal), walked without recursion, so that a long chain of conditions
    /// needs no call-stack depth. A token's children are read again after each removal,
    /// as removing one can give another token new children (an NCC's owner).
    pub(crate) fn delete_token_and_descendants(
        &mut self,
        t: TokId,
        syms: &Symbols,
        sink: &mut dyn MatchSink,
    ) {
        let mut cur = t;
        loop {
            let c = self.tokens[cur].first_child;
            if c != TokId::NONE {
                cur = c;
                continue;
            }
            let parent = self.tokens[cur].parent;
            self.delete_token(cur, syms, sink);
            if cur == t {
                return;
            }
            cur = parent;
        }
    }

    /// Removes one token without children.
    fn delete_token(&mut self, t: TokId, syms: &Symbols, sink: &mut dyn MatchSink) {
        let tok = self.tokens[t];
        let node = tok.node;
        if tok.hfirst != NIL {
            self.unindex_token(t);
        }
        // Out of the node's memory.
        if tok.prev_in_node != TokId::NONE {
            self.tokens[tok.prev_in_node].next_in_node = tok.next_in_node;
        } else {
            self.nodes[node].first_token = tok.next_in_node;
        }
        if tok.next_in_node != TokId::NONE {
            self.tokens[tok.next_in_node].prev_in_node = tok.prev_in_node;
        }
        let n = &mut self.nodes[node];
        n.token_count -= 1;
        if n.token_count == 0 {
            // Its last token took its last index entries with it.
            n.left_mode = LeftMode::Scan;
        }
        // Out of its WME's list.
        if tok.wme != NIL_WME {
            if tok.prev_of_wme != TokId::NONE {
                self.tokens[tok.prev_of_wme].next_of_wme = tok.next_of_wme;
            } else if let Some(rw) = self.wmes[tok.wme.0 as usize].as_mut() {
                rw.tokens = tok.next_of_wme;
            }
            if tok.next_of_wme != TokId::NONE {
                self.tokens[tok.next_of_wme].prev_of_wme = tok.prev_of_wme;
            }
        }
        // Out of its parent's children.
        if tok.parent != TokId::NONE {
            if tok.prev_sib != TokId::NONE {
                self.tokens[tok.prev_sib].next_sib = tok.next_sib;
            } else {
                self.tokens[tok.parent].first_child = tok.next_sib;
            }
            if tok.next_sib != TokId::NONE {
                self.tokens[tok.next_sib].prev_sib = tok.prev_sib;
            }
        }
        match self.nodes[node].kind {
            Kind::Negative { .. } => {
                loop {
                    let r = self.links[t].results;
                    if r == NIL {
                        break;
                    }
                    self.remove_neg_result(r);
                }
                if self.nodes[node].token_count == 0 {
                    self.unlink_right(node);
                }
            }
            Kind::Ncc { .. } => loop {
                let r = TokId::new(self.links[t].results);
                if r == TokId::NONE {
                    break;
                }
                self.unlink_ncc_result(t, r);
                self.links[r].owner = TokId::NONE;
                self.delete_token_and_descendants(r, syms, sink);
            },
            Kind::Production { prod } => sink.unmatched(prod, t),
            _ => {}
        }
        if self.nodes[node].token_count == 0 {
            // An empty memory: its joins need no right activations (Rete/UL).
            // (Unlinking on the right leaves the children list as it is.)
            for i in 0..self.nodes[node].children.len() {
                let c = self.nodes[node].children.as_slice()[i];
                if matches!(self.nodes[c].kind, Kind::Join { .. }) {
                    self.unlink_right(c);
                }
            }
        }
        // Only an NCC partner's tokens have an owner (its links go with it).
        if matches!(self.nodes[node].kind, Kind::NccPartner { .. }) {
            let owner = self.links[t].owner;
            if owner != TokId::NONE && self.tokens[owner].alive {
                self.unlink_ncc_result(owner, t);
                if self.links[owner].results == NIL {
                    // The conjunction no longer matches: the owner's match goes on
                    // (Doorenbos, section 2.8).
                    let onode = self.tokens[owner].node;
                    self.activate_children(onode, owner, NIL_WME, syms, sink);
                }
            }
            self.links[t] = ResultLinks::NONE;
        }
        self.tokens[t].alive = false;
        self.free_row(tok.row, tok.depth);
        self.free_tokens.push(t);
    }

    pub(crate) fn add_neg_result(&mut self, owner: TokId, w: WmeId) {
        let tok_head = self.links[owner].results;
        let wme_head = self.wmes[w.0 as usize]
            .as_ref()
            .map_or(NIL, |x| x.neg_results);
        let r = NegResult {
            owner,
            wme: w,
            next_tok: tok_head,
            prev_tok: NIL,
            next_wme: wme_head,
            prev_wme: NIL,
        };
        let id = alloc(&mut self.neg, &mut self.free_neg, r);
        if tok_head != NIL {
            self.neg[tok_head as usize].prev_tok = id;
        }
        self.links[owner].results = id;
        if wme_head != NIL {
            self.neg[wme_head as usize].prev_wme = id;
        }
        if let Some(rw) = self.wmes[w.0 as usize].as_mut() {
            rw.neg_results = id;
        }
    }

    pub(crate) fn remove_neg_result(&mut self, r: u32) {
        let NegResult {
            owner,
            wme,
            next_tok,
            prev_tok,
            next_wme,
            prev_wme,
        } = self.neg[r as usize];
        if prev_tok != NIL {
            self.neg[prev_tok as usize].next_tok = next_tok;
        } else {
            self.links[owner].results = next_tok;
        }
        if next_tok != NIL {
            self.neg[next_tok as usize].prev_tok = prev_tok;
        }
        if prev_wme != NIL {
            self.neg[prev_wme as usize].next_wme = next_wme;
        } else if let Some(rw) = self.wmes[wme.0 as usize].as_mut() {
            rw.neg_results = next_wme;
        }
        if next_wme != NIL {
            self.neg[next_wme as usize].prev_wme = prev_wme;
        }
        self.free_neg.push(r);
    }

    pub(crate) fn add_ncc_result(&mut self, owner: TokId, r: TokId) {
        let head = TokId::new(self.links[owner].results);
        let rt = &mut self.links[r];
        rt.owner = owner;
        rt.next_result = head;
        rt.prev_result = TokId::NONE;
        if head != TokId::NONE {
            self.links[head].prev_result = r;
        }
        self.links[owner].results = r.raw();
    }

    fn unlink_ncc_result(&mut self, owner: TokId, r: TokId) {
        let (prev, next) = (
            self.links[r].prev_result,
            self.links[r].next_result,
        );
        if prev != TokId::NONE {
            self.links[prev].next_result = next;
        } else {
            self.links[owner].results = next.raw();
        }
        if next != TokId::NONE {
            self.links[next].prev_result = prev;
        }
        self.links[r].next_result = TokId::NONE;
        self.links[r].prev_result = TokId::NONE;
    }
}
