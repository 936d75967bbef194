//! The linked successors of each alpha memory, in activation order, as doubly linked
//! lists threaded through one table indexed by node: linking a node before its nearest
//! linked ancestor (or at the tail) and unlinking it are constant-time, which Rete/UL asks
//! for, since a join is unlinked and relinked whenever its parent memory empties and fills
//! (Doorenbos, section 4.3). The entries sit apart from the nodes, so that a walk over an
//! alpha memory's thousands of successors reads only this table.

use super::{NodeId, Succ};

/// A node's place in its alpha memory's list, with the copy of its first WME test.
#[derive(Debug, Clone, Copy)]
struct Link {
    succ: Succ,
    prev: NodeId,
    next: NodeId,
    linked: bool,
    /// `succ` is the node's (set while the node lives, linked or not): its prefilter is
    /// read from its tests once, not at every relink.
    known: bool,
}

/// One alpha memory's list: its ends.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SuccList {
    head: NodeId,
    tail: NodeId,
}

impl Default for SuccList {
    fn default() -> Self {
        SuccList {
            head: NodeId::NONE,
            tail: NodeId::NONE,
        }
    }
}

/// The links of every node that is an alpha memory's successor.
#[derive(Debug, Default)]
pub(crate) struct SuccLinks {
    links: Vec<Link>,
}

impl SuccLinks {
    /// Puts `s` (whose node is unlinked) into `list` just before `before`, a linked node of
    /// the same list, or at the tail when `before` is `NodeId::NONE`.
    pub fn insert(&mut self, list: &mut SuccList, s: Succ, before: NodeId) {
        let n = s.node;
        if self.links.len() <= n.index() {
            self.links.resize(
                n.index() + 1,
                Link {
                    succ: s,
                    prev: NodeId::NONE,
                    next: NodeId::NONE,
                    linked: false,
                    known: false,
                },
            );
        }
        let prev = if before == NodeId::NONE {
            list.tail
        } else {
            self.links[before.index()].prev
        };
        self.links[n.index()] = Link {
            succ: s,
            prev,
            next: before,
            linked: true,
            known: true,
        };
        self.join(list, prev, n);
        self.join(list, n, before);
    }

    /// Makes `b` follow `a` in `list` (`NodeId::NONE` for the list's start or end).
    fn join(&mut self, list: &mut SuccList, a: NodeId, b: NodeId) {
        match a {
            NodeId::NONE => list.head = b,
            a => self.links[a.index()].next = b,
        }
        match b {
            NodeId::NONE => list.tail = a,
            b => self.links[b.index()].prev = a,
        }
    }

    /// Takes `n` out of `list`, if it is linked there.
    pub fn remove(&mut self, list: &mut SuccList, n: NodeId) {
        let Some(link) = self.links.get_mut(n.index()).filter(|l| l.linked) else {
            return;
        };
        link.linked = false;
        let (prev, next) = (link.prev, link.next);
        self.join(list, prev, next);
    }

    /// The entry `n` had when last linked, while the node lives.
    pub fn known(&self, n: NodeId) -> Option<Succ> {
        self.links
            .get(n.index())
            .filter(|l| l.known)
            .map(|l| l.succ)
    }

    /// Takes `n` out of `list` for good: the node is freed, and its id may be reused.
    pub fn forget(&mut self, list: &mut SuccList, n: NodeId) {
        self.remove(list, n);
        if let Some(link) = self.links.get_mut(n.index()) {
            link.known = false;
        }
    }

    /// Empties `list` (its alpha memory goes).
    pub fn clear(&mut self, list: &mut SuccList) {
        let mut n = list.head;
        while n != NodeId::NONE {
            let link = &mut self.links[n.index()];
            link.linked = false;
            link.known = false;
            n = link.next;
        }
        *list = SuccList::default();
    }

    /// The linked entry of `n`, to change its mirrored flags.
    pub fn get_mut(&mut self, n: NodeId) -> Option<&mut Succ> {
        self.links
            .get_mut(n.index())
            .filter(|l| l.linked)
            .map(|l| &mut l.succ)
    }

    /// The successors of `list`, head first.
    pub fn iter(&self, list: SuccList) -> impl Iterator<Item = &Succ> + '_ {
        let mut n = list.head;
        std::iter::from_fn(move || {
            let link = self.links.get(n.index())?;
            n = link.next;
            Some(&link.succ)
        })
    }
}
