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
        let depth = if parent == NIL {
            0
        } else {
            self.tokens[parent as usize].depth + 1
        };
        self.tokens_made += 1;
        let head = self.nodes[node as usize].first_token;
        let doomed = self.doom.active
            && ((parent != NIL && self.tokens[parent as usize].doomed)
                || (wme != NIL_WME && self.wme_doomed(wme)));
        let tok = Token {
            node,
            parent,
            wme,
            depth,
            first_child: NIL,
            next_sib: NIL,
            prev_sib: NIL,
            next_in_node: head,
            prev_in_node: NIL,
            next_of_wme: NIL,
            prev_of_wme: NIL,
            hfirst: NIL,
            row: 0,
            key: NO_VALUE,
            alive: true,
            doomed,
        };
        let row = self.alloc_row(parent, depth, wme);
        let t = alloc(&mut self.tokens, &mut self.free_tokens, tok);
        if self.links.len() <= t as usize {
            self.links.resize(t as usize + 1, ResultLinks::NONE);
        }
        self.tokens[t as usize].row = row;
        if head != NIL {
            self.tokens[head as usize].prev_in_node = t;
        }
        let n = &mut self.nodes[node as usize];
        n.first_token = t;
        n.token_count += 1;
        if parent != NIL {
            let first = self.tokens[parent as usize].first_child;
            self.tokens[t as usize].next_sib = first;
            if first != NIL {
                self.tokens[first as usize].prev_sib = t;
            }
            self.tokens[parent as usize].first_child = t;
        }
        if wme != NIL_WME {
            if let Some(rw) = self.wmes[wme.0 as usize].as_mut() {
                let first = rw.tokens;
                rw.tokens = t;
                self.tokens[t as usize].next_of_wme = first;
                if first != NIL {
                    self.tokens[first as usize].prev_of_wme = t;
                }
            }
        }
        if !self.nodes[node as usize].left_keys.is_empty() {
            self.token_added_to_holder(node, t);
        }
        t
    }

    /// Tokens held by a node, head (newest) first.
    pub(crate) fn node_tokens(&self, n: NodeId) -> Vec<TokId> {
        let mut out = Vec::with_capacity(self.nodes[n as usize].token_count as usize);
        let mut t = self.nodes[n as usize].first_token;
        while t != NIL {
            out.push(t);
            t = self.tokens[t as usize].next_in_node;
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
            let c = self.tokens[t as usize].first_child;
            if c == NIL {
                break;
            }
            self.delete_token_and_descendants(c, syms, sink);
        }
    }

    /// Removes a token and everything built on it, reporting retracted matches.
    pub(crate) fn delete_token_and_descendants(
        &mut self,
        t: TokId,
        syms: &Symbols,
        sink: &mut dyn MatchSink,
    ) {
        self.delete_descendants(t, syms, sink);
        let tok = self.tokens[t as usize];
        let node = tok.node;
        if tok.hfirst != NIL {
            self.unindex_token(t);
        }
        // Out of the node's memory.
        if tok.prev_in_node != NIL {
            self.tokens[tok.prev_in_node as usize].next_in_node = tok.next_in_node;
        } else {
            self.nodes[node as usize].first_token = tok.next_in_node;
        }
        if tok.next_in_node != NIL {
            self.tokens[tok.next_in_node as usize].prev_in_node = tok.prev_in_node;
        }
        let n = &mut self.nodes[node as usize];
        n.token_count -= 1;
        if n.token_count == 0 {
            // Its last token took its last index entries with it.
            n.left_mode = LeftMode::Scan;
        }
        // Out of its WME's list.
        if tok.wme != NIL_WME {
            if tok.prev_of_wme != NIL {
                self.tokens[tok.prev_of_wme as usize].next_of_wme = tok.next_of_wme;
            } else if let Some(rw) = self.wmes[tok.wme.0 as usize].as_mut() {
                rw.tokens = tok.next_of_wme;
            }
            if tok.next_of_wme != NIL {
                self.tokens[tok.next_of_wme as usize].prev_of_wme = tok.prev_of_wme;
            }
        }
        // Out of its parent's children.
        if tok.parent != NIL {
            if tok.prev_sib != NIL {
                self.tokens[tok.prev_sib as usize].next_sib = tok.next_sib;
            } else {
                self.tokens[tok.parent as usize].first_child = tok.next_sib;
            }
            if tok.next_sib != NIL {
                self.tokens[tok.next_sib as usize].prev_sib = tok.prev_sib;
            }
        }
        match self.nodes[node as usize].kind {
            Kind::Negative { .. } => {
                loop {
                    let r = self.links[t as usize].results;
                    if r == NIL {
                        break;
                    }
                    self.remove_neg_result(r);
                }
                if self.nodes[node as usize].token_count == 0 {
                    self.unlink_right(node);
                }
            }
            Kind::Ncc { .. } => loop {
                let r = self.links[t as usize].results;
                if r == NIL {
                    break;
                }
                self.unlink_ncc_result(t, r);
                self.links[r as usize].owner = NIL;
                self.delete_token_and_descendants(r, syms, sink);
            },
            Kind::Production { prod } => sink.unmatched(prod, t),
            _ => {}
        }
        if self.nodes[node as usize].token_count == 0 {
            // An empty memory: its joins need no right activations (Rete/UL).
            // (Unlinking on the right leaves the children list as it is.)
            for i in 0..self.nodes[node as usize].children.len() {
                let c = self.nodes[node as usize].children.as_slice()[i];
                if matches!(self.nodes[c as usize].kind, Kind::Join { .. }) {
                    self.unlink_right(c);
                }
            }
        }
        // Only an NCC partner's tokens have an owner (its links go with it).
        if matches!(self.nodes[node as usize].kind, Kind::NccPartner { .. }) {
            let owner = self.links[t as usize].owner;
            if owner != NIL && self.tokens[owner as usize].alive {
                self.unlink_ncc_result(owner, t);
                if self.links[owner as usize].results == NIL {
                    // The conjunction no longer matches: the owner's match goes on
                    // (Doorenbos, section 2.8).
                    let onode = self.tokens[owner as usize].node;
                    self.activate_children(onode, owner, NIL_WME, syms, sink);
                }
            }
            self.links[t as usize] = ResultLinks::NONE;
        }
        self.tokens[t as usize].alive = false;
        self.free_row(tok.row, tok.depth);
        self.free_tokens.push(t);
    }

    pub(crate) fn add_neg_result(&mut self, owner: TokId, w: WmeId) {
        let tok_head = self.links[owner as usize].results;
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
        self.links[owner as usize].results = id;
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
            self.links[owner as usize].results = next_tok;
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
        let head = self.links[owner as usize].results;
        let rt = &mut self.links[r as usize];
        rt.owner = owner;
        rt.next_result = head;
        rt.prev_result = NIL;
        if head != NIL {
            self.links[head as usize].prev_result = r;
        }
        self.links[owner as usize].results = r;
    }

    fn unlink_ncc_result(&mut self, owner: TokId, r: TokId) {
        let (prev, next) = (
            self.links[r as usize].prev_result,
            self.links[r as usize].next_result,
        );
        if prev != NIL {
            self.links[prev as usize].next_result = next;
        } else {
            self.links[owner as usize].results = next;
        }
        if next != NIL {
            self.links[next as usize].prev_result = prev;
        }
        self.links[r as usize].next_result = NIL;
        self.links[r as usize].prev_result = NIL;
    }
}
