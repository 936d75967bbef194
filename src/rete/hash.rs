//! Hashed joins (Doorenbos, section 2.3, as Soar does): a join or negative node whose new
//! WME's identifier must equal a variable bound above it looks up only the WMEs with that
//! identifier (the right index, per alpha memory) and only the tokens with that value (the
//! left index, per token holder). Both indexes are intrusive lists, newest first, so a
//! lookup visits the same WMEs and tokens in the same order as a full scan would, and a
//! removal is constant time however many entries share a value.

use super::tests::Field;
use super::{alloc, AmemId, HashKey, LeftMode, NodeId, Rete, TokId, NIL, NIL_WME};
use crate::symbols::Sym;
use crate::wm::WmeId;

/// Alpha memories up to this size are scanned rather than looked up by identifier.
pub(crate) const SMALL_AMEM: u32 = 4;

/// Token holders up to this many tokens are scanned rather than indexed.
pub(crate) const SMALL_BETA: u32 = 8;

/// A cached key value for "no WME at the key's depth".
pub(crate) const NO_VALUE: Sym = Sym(u32::MAX);

fn some_value(v: Sym) -> Option<Sym> {
    (v != NO_VALUE).then_some(v)
}

/// A left-index bucket: holder, key depth, key field and value, packed into two words (one
/// hash round each: every token of an indexed memory goes in and out under one).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(crate) struct TokKey {
    holder_value: u64,
    depth_field: HashKey,
}

impl TokKey {
    pub(crate) fn new(holder: NodeId, d: u32, f: Field, v: Sym) -> Self {
        TokKey {
            holder_value: (u64::from(holder.raw()) << 32) | u64::from(v.0),
            depth_field: HashKey::new(Some((d, f))),
        }
    }

    /// Whether this bucket is the holder's on key `(d, f)`.
    fn is_key_of(&self, holder: NodeId, d: u32, f: Field) -> bool {
        (self.holder_value >> 32) as u32 == holder.raw() && self.depth_field == HashKey::new(Some((d, f)))
    }
}

/// One token's membership in one left-index bucket.
#[derive(Debug, Clone, Copy)]
pub(crate) struct HEntry {
    pub key: TokKey,
    pub tok: TokId,
    pub prev: u32,
    pub next: u32,
    /// The token's next entry (a holder may be indexed on several keys).
    pub next_of_tok: u32,
}

impl Rete {
    // ------------------------------------------------------------------ right index

    /// Puts alpha-memory entry `e` at the head of its identifier's list.
    pub(crate) fn id_index_insert(&mut self, a: AmemId, id: Sym, e: u32) {
        let head = self.amem_by_id.insert(a, id, e).unwrap_or(NIL);
        self.rm[e as usize].id_next = head;
        self.rm[e as usize].id_prev = NIL;
        if head != NIL {
            self.rm[head as usize].id_prev = e;
        }
    }

    /// Indexes every entry of an alpha memory that has outgrown scanning, oldest first (so
    /// that head insertion leaves the newest at the head).
    pub(crate) fn index_amem(&mut self, a: AmemId) {
        self.amems[a].indexed = true;
        let mut entries = Vec::with_capacity(self.amems[a].count as usize);
        let mut e = self.amems[a].first;
        while e != NIL {
            entries.push(e);
            e = self.rm[e as usize].next;
        }
        for &e in entries.iter().rev() {
            let id = self.rm[e as usize].id;
            self.id_index_insert(a, id, e);
        }
    }

    pub(crate) fn id_index_remove(&mut self, a: AmemId, id: Sym, e: u32) {
        let (prev, next) = (self.rm[e as usize].id_prev, self.rm[e as usize].id_next);
        if prev != NIL {
            self.rm[prev as usize].id_next = next;
        } else if next != NIL {
            self.amem_by_id.insert(a, id, next);
        } else {
            self.amem_by_id.remove(a, id);
        }
        if next != NIL {
            self.rm[next as usize].id_prev = prev;
        }
    }

    /// Pushes onto the scratch stack the WMEs of an alpha memory that node `n` must try
    /// with token `t`, newest first: only those whose identifier is the token's value at
    /// `n`'s key, when it has one.
    #[inline(always)]
    pub(crate) fn push_amem_candidates(&mut self, a: AmemId, n: NodeId, t: TokId) {
        let Some((d, f)) = self.nodes[n].hash.get() else {
            let mut e = self.amems[a].first;
            while e != NIL {
                self.scratch.push(self.rm[e as usize].wme.0);
                e = self.rm[e as usize].next;
            }
            return;
        };
        // Nearly always the token's cached key (its holder's first key is this join's).
        let holder = self.tokens[t].node;
        let Some(id) = self.holder_key_value(holder, t, d, f) else {
            return;
        };
        let am = &self.amems[a];
        if !am.indexed {
            // A few entries: filtering them is cheaper than the hash probe, and gives the
            // same WMEs in the same (newest first) order.
            let mut e = am.first;
            while e != NIL {
                let entry = &self.rm[e as usize];
                if entry.id == id {
                    self.scratch.push(entry.wme.0);
                }
                e = entry.next;
            }
            return;
        }
        let mut e = self.amem_by_id.get(a, id).unwrap_or(NIL);
        while e != NIL {
            let entry = &self.rm[e as usize];
            self.scratch.push(entry.wme.0);
            e = entry.id_next;
        }
    }

    // ------------------------------------------------------------------- left index

    /// Pushes onto the scratch stack the tokens of `holder` that node `n` must try with
    /// WME `w`, newest first: only those whose value at `n`'s key is `w`'s identifier, when
    /// it has one.
    pub(crate) fn push_token_candidates(&mut self, holder: NodeId, n: NodeId, w: WmeId) {
        let Some((d, f)) = self.nodes[n].hash.get() else {
            self.push_all_tokens(holder);
            return;
        };
        let id = self.wme(w).id;
        // A large memory is indexed when a WME first asks for its tokens by value, not
        // as it fills: memories that fill and empty each decision without a WME ever
        // asking (a join over every item of a large store) never pay for an index.
        if self.nodes[holder].left_mode == LeftMode::Scan
            && self.nodes[holder].token_count > SMALL_BETA
        {
            self.choose_left_mode(holder);
        }
        let h = &self.nodes[holder];
        match h.left_mode {
            LeftMode::Indexed => {
                let key = TokKey::new(holder, d, f, id);
                let mut e = self.tok_by_key.get(&key).copied().unwrap_or(NIL);
                while e != NIL {
                    self.scratch.push(self.hentries[e as usize].tok.raw());
                    e = self.hentries[e as usize].next;
                }
            }
            LeftMode::Uniform if h.first_token != TokId::NONE && self.is_first_key(holder, d, f) => {
                // Every token has the head's value: all of them, or none.
                if self.tokens[h.first_token].key == id {
                    self.push_all_tokens(holder);
                }
            }
            _ => {
                // A small memory: its tokens with that value, newest first, as the index
                // has them.
                let cached = self.is_first_key(holder, d, f);
                let mut t = h.first_token;
                while t != TokId::NONE {
                    let v = if cached {
                        some_value(self.tokens[t].key)
                    } else {
                        self.key_value(t, d, f)
                    };
                    if v == Some(id) {
                        self.scratch.push(t.raw());
                    }
                    t = self.tokens[t].next_in_node;
                }
            }
        }
    }

    fn push_all_tokens(&mut self, holder: NodeId) {
        let mut t = self.nodes[holder].first_token;
        while t != TokId::NONE {
            self.scratch.push(t.raw());
            t = self.tokens[t].next_in_node;
        }
    }

    fn is_first_key(&self, holder: NodeId, d: u32, f: Field) -> bool {
        matches!(self.nodes[holder].left_keys.as_slice().first(), Some(k) if k.0 == d && k.1 == f)
    }

    /// A token's value at an index key, if it has a WME at that depth.
    pub(crate) fn key_value(&self, t: TokId, d: u32, f: Field) -> Option<Sym> {
        let wm = self.wme_at_depth(t, d);
        (wm != NIL_WME).then(|| self.field(wm, f))
    }

    /// A holder's token's value at key `(d, f)`: its cached key when that is the holder's
    /// first key (nearly always: most holders have one).
    pub(crate) fn holder_key_value(
        &self,
        holder: NodeId,
        t: TokId,
        d: u32,
        f: Field,
    ) -> Option<Sym> {
        if self.is_first_key(holder, d, f) {
            some_value(self.tokens[t].key)
        } else {
            self.key_value(t, d, f)
        }
    }

    /// Caches a token's value at its holder's first key.
    fn cache_key(&mut self, t: TokId, key: Option<(u32, Field)>) {
        let value = key
            .and_then(|(d, f)| self.key_value(t, d, f))
            .unwrap_or(NO_VALUE);
        self.tokens[t].key = value;
    }

    fn first_key(&self, holder: NodeId) -> Option<(u32, Field)> {
        let k = self.nodes[holder].left_keys.as_slice().first()?;
        Some((k.0, k.1))
    }

    /// Keeps a holder's [`LeftMode`] true as it takes a new token.
    /// (The token's key is cached already: `new_token` reads it off the new row.)
    pub(crate) fn token_added_to_holder(&mut self, holder: NodeId, t: TokId) {
        let h = &self.nodes[holder];
        match h.left_mode {
            LeftMode::Indexed => self.index_token(holder, t),
            LeftMode::Uniform => {
                let older = self.tokens[t].next_in_node;
                if older != TokId::NONE && self.tokens[older].key != self.tokens[t].key {
                    self.index_holder(holder);
                }
            }
            LeftMode::Scan => {}
        }
    }

    /// A memory past scanning size: `Uniform` if it has one key and its tokens share their
    /// value there, otherwise indexed.
    fn choose_left_mode(&mut self, holder: NodeId) {
        let h = &self.nodes[holder];
        if h.left_keys.len() == 1 && h.first_token != TokId::NONE {
            let v = self.tokens[h.first_token].key;
            let mut t = h.first_token;
            while t != TokId::NONE && self.tokens[t].key == v {
                t = self.tokens[t].next_in_node;
            }
            if t == TokId::NONE {
                self.nodes[holder].left_mode = LeftMode::Uniform;
                return;
            }
        }
        self.index_holder(holder);
    }

    fn hentry_insert(&mut self, key: TokKey, t: TokId) {
        let entry = HEntry {
            key,
            tok: t,
            prev: NIL,
            next: NIL,
            next_of_tok: self.tokens[t].hfirst,
        };
        let e = alloc(&mut self.hentries, &mut self.free_hentries, entry);
        let head = self.tok_by_key.insert(key, e).unwrap_or(NIL);
        self.hentries[e as usize].next = head;
        if head != NIL {
            self.hentries[head as usize].prev = e;
        }
        self.tokens[t].hfirst = e;
    }

    fn hentry_unlink(&mut self, e: u32) {
        let HEntry {
            key, prev, next, ..
        } = self.hentries[e as usize];
        if prev != NIL {
            self.hentries[prev as usize].next = next;
        } else if next != NIL {
            self.tok_by_key.insert(key, next);
        } else {
            self.tok_by_key.remove(&key);
        }
        if next != NIL {
            self.hentries[next as usize].prev = prev;
        }
        self.free_hentries.push(e);
    }

    /// Indexes a new token under every key of its holder.
    fn index_token(&mut self, holder: NodeId, t: TokId) {
        for i in 0..self.nodes[holder].left_keys.len() {
            let (d, f, _) = self.nodes[holder].left_keys.as_slice()[i];
            let v = if i == 0 {
                some_value(self.tokens[t].key)
            } else {
                self.key_value(t, d, f)
            };
            if let Some(v) = v {
                self.hentry_insert(TokKey::new(holder, d, f, v), t);
            }
        }
    }

    /// Takes a token out of every index it is in.
    pub(crate) fn unindex_token(&mut self, t: TokId) {
        let mut e = self.tokens[t].hfirst;
        while e != NIL {
            let next = self.hentries[e as usize].next_of_tok;
            self.hentry_unlink(e);
            e = next;
        }
        self.tokens[t].hfirst = NIL;
    }

    /// Gives a holder an index key for a hashed node and indexes its tokens by it (the
    /// holder is a join's parent, or a negative node itself).
    pub(crate) fn add_left_key(&mut self, holder: NodeId, d: u32, f: Field) {
        let keys = &mut self.nodes[holder].left_keys;
        if let Some(k) = keys
            .as_mut_slice()
            .iter_mut()
            .find(|k| k.0 == d && k.1 == f)
        {
            k.2 += 1;
            return;
        }
        keys.push((d, f, 1));
        if keys.len() == 1 {
            self.recache_keys(holder);
        }
        let h = &self.nodes[holder];
        if h.left_mode == LeftMode::Indexed {
            self.index_tokens_on(holder, d, f);
        }
    }

    /// Caches every token's key afresh after the holder's first key changed.
    fn recache_keys(&mut self, holder: NodeId) {
        let key = self.first_key(holder);
        for t in self.node_tokens(holder) {
            self.cache_key(t, key);
        }
    }

    /// Puts a holder's tokens in the left index under one key, oldest first, so that head
    /// insertion leaves the newest at the head.
    fn index_tokens_on(&mut self, holder: NodeId, d: u32, f: Field) {
        for t in self.node_tokens(holder).into_iter().rev() {
            if let Some(v) = self.key_value(t, d, f) {
                self.hentry_insert(TokKey::new(holder, d, f, v), t);
            }
        }
    }

    /// Indexes every token of a holder under every key (it outgrew scanning, or lost its
    /// one shared value).
    pub(crate) fn index_holder(&mut self, holder: NodeId) {
        self.nodes[holder].left_mode = LeftMode::Indexed;
        for i in 0..self.nodes[holder].left_keys.len() {
            let (d, f, _) = self.nodes[holder].left_keys.as_slice()[i];
            self.index_tokens_on(holder, d, f);
        }
    }

    /// Drops one use of a holder's key; the last use drops its index entries.
    pub(crate) fn release_left_key(&mut self, holder: NodeId, d: u32, f: Field) {
        let keys = &mut self.nodes[holder].left_keys;
        let Some(pos) = keys.as_slice().iter().position(|k| k.0 == d && k.1 == f) else {
            return;
        };
        keys.as_mut_slice()[pos].2 -= 1;
        if keys.as_slice()[pos].2 > 0 {
            return;
        }
        keys.remove(pos);
        if pos == 0 {
            self.recache_keys(holder);
        }
        if self.nodes[holder].left_keys.is_empty() {
            self.nodes[holder].left_mode = LeftMode::Scan;
        }
        for t in self.node_tokens(holder) {
            // Rebuild the token's entry chain without this key's entries.
            let mut e = self.tokens[t].hfirst;
            let mut kept = Vec::new();
            while e != NIL {
                let entry = self.hentries[e as usize];
                if entry.key.is_key_of(holder, d, f) {
                    self.hentry_unlink(e);
                } else {
                    kept.push(e);
                }
                e = entry.next_of_tok;
            }
            let mut next = NIL;
            for &k in kept.iter().rev() {
                self.hentries[k as usize].next_of_tok = next;
                next = k;
            }
            self.tokens[t].hfirst = next;
        }
    }
}
