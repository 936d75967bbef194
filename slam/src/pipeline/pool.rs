//! All-zero vote buffers kept between extractions.
//!
//! A run extracts a few hundred times, and each extraction's Hough accumulator is a grid of
//! about a hundred thousand cells of which only a few per cent get votes. Zeroing a fresh grid
//! each time cost more than the voting; instead the accumulator zeroes the cells it voted (it
//! knows where: see [`Bands`]) and gives the grid back here when dropped.

use std::cell::RefCell;
use std::thread::LocalKey;

/// Most buffers kept per pool (an extraction holds one; a sample kept for the figures holds
/// one more).
const KEEP: usize = 2;

/// A per-thread pool of all-zero buffers.
pub type Pool = RefCell<Vec<Vec<u32>>>;

/// An all-zero buffer of `n` cells from `pool`: one given back earlier, shortened (its tail
/// stays zero) or lengthened (only the new cells are written), or a fresh one.
pub fn take(pool: &'static LocalKey<Pool>, n: usize) -> Vec<u32> {
    let mut buf = pool
        .try_with(|p| p.borrow_mut().pop())
        .ok()
        .flatten()
        .unwrap_or_default();
    buf.resize(n, 0);
    buf
}

/// Gives `buf` back to `pool`; every cell of it must be zero.
pub fn give(pool: &'static LocalKey<Pool>, buf: Vec<u32>) {
    debug_assert!(buf.iter().all(|&v| v == 0));
    // During thread exit the pool may be gone; the buffer is then simply freed.
    let _ = pool.try_with(|p| {
        let mut p = p.borrow_mut();
        if p.len() < KEEP {
            p.push(buf);
        }
    });
}

/// Cells `first..end` of each line (column or row) of a grid that hold votes: the cells outside
/// are zero. Kept as votes are cast, so that the cells voted can be zeroed and scanned
/// without visiting the whole grid. `(u32::MAX, 0)` marks a line without votes, so the bands
/// depend only on where the votes are.
#[derive(Debug, Clone, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
pub struct Bands(Vec<(u32, u32)>);

impl Bands {
    /// Bands for `lines` empty lines.
    pub fn new(lines: usize) -> Self {
        Bands(vec![(u32::MAX, 0); lines])
    }

    /// Notes a vote at `cell` of `line`.
    #[inline]
    pub fn note(&mut self, line: usize, cell: usize) {
        let b = &mut self.0[line];
        let c = cell as u32;
        b.0 = b.0.min(c);
        b.1 = b.1.max(c + 1);
    }

    /// The cells of `line` that may hold votes.
    pub fn get(&self, line: usize) -> std::ops::Range<usize> {
        let (a, b) = self.0[line];
        if a < b {
            a as usize..b as usize
        } else {
            0..0
        }
    }

    /// Zeroes the voted cells of `grid` (`lines` of `len` cells each, line-major).
    pub fn zero(&self, grid: &mut [u32], len: usize) {
        for line in 0..self.0.len() {
            let r = self.get(line);
            grid[line * len + r.start..line * len + r.end].fill(0);
        }
    }
}
