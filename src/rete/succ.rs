//! The linked successors of an alpha memory, walked newest node first (spec §3i: Soar
//! head-inserts a node when it is built, and a relinked node goes back to that place).
//!
//! Every node built on the memory gets the next position, so positions follow creation
//! order; linking and unlinking (Rete/UL, thousands of times a cycle when a shared memory
//! empties and refills) only set and clear a bit. A summary word per 64 words lets the walk
//! skip unlinked stretches, so it costs the linked nodes plus one bit test per 4,096
//! positions.

use super::{NodeId, NIL};

#[derive(Debug, Default)]
pub(crate) struct Successors {
    /// The node at each position (NIL once it is excised).
    ids: Vec<NodeId>,
    /// Bit `p`: the node at position `p` is linked.
    bits: Vec<u64>,
    /// Bit `w`: word `w` of `bits` is not zero.
    summary: Vec<u64>,
}

impl Successors {
    /// Gives a new node the next position (unlinked).
    pub(crate) fn attach(&mut self, n: NodeId) -> u32 {
        let pos = self.ids.len();
        self.ids.push(n);
        if pos / 64 >= self.bits.len() {
            self.bits.push(0);
        }
        if self.bits.len() > self.summary.len() * 64 {
            self.summary.push(0);
        }
        pos as u32
    }

    pub(crate) fn link(&mut self, pos: u32) {
        let (w, b) = (pos as usize / 64, pos % 64);
        self.bits[w] |= 1 << b;
        self.summary[w / 64] |= 1 << (w % 64);
    }

    pub(crate) fn unlink(&mut self, pos: u32) {
        let (w, b) = (pos as usize / 64, pos % 64);
        self.bits[w] &= !(1 << b);
        if self.bits[w] == 0 {
            self.summary[w / 64] &= !(1 << (w % 64));
        }
    }

    /// Forgets an excised node's position.
    pub(crate) fn detach(&mut self, pos: u32) {
        self.unlink(pos);
        self.ids[pos as usize] = NIL;
    }

    pub(crate) fn clear(&mut self) {
        *self = Successors::default();
    }

    /// Appends the linked nodes to `out`, newest first.
    pub(crate) fn push_newest_first(&self, out: &mut Vec<u32>) {
        for (s, &sw) in self.summary.iter().enumerate().rev() {
            let mut sw = sw;
            while sw != 0 {
                let j = 63 - sw.leading_zeros() as usize;
                sw &= !(1 << j);
                let w = s * 64 + j;
                let mut bw = self.bits[w];
                while bw != 0 {
                    let b = 63 - bw.leading_zeros() as usize;
                    bw &= !(1 << b);
                    out.push(self.ids[w * 64 + b]);
                }
            }
        }
    }
}
