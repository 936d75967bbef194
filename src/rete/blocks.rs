//! A growable array kept in fixed-size blocks, for the tables that grow with the rules
//! loaded (productions, the symbol table). A doubling `Vec` copies everything when it grows
//! and for a moment holds both copies: at 100,000 rules that is most of the load's page
//! faults. Blocks are never moved. Each block is a whole array, filled with `T::default()`
//! when it is made, so an index needs one bounds check (the block), not two.

use std::ops::{Index, IndexMut};

/// Items per block (a power of two, so an index splits with a shift and a mask).
const SHIFT: u32 = 12;
const BLOCK: usize = 1 << SHIFT;

#[derive(Debug, Clone)]
pub(crate) struct Blocks<T> {
    /// Items `0..len`; the rest of the last block holds fillers.
    blocks: Vec<Box<[T; BLOCK]>>,
    len: usize,
}

impl<T> Default for Blocks<T> {
    fn default() -> Self {
        Blocks {
            blocks: Vec::new(),
            len: 0,
        }
    }
}

impl<T: Default + Clone> Blocks<T> {
    pub fn push(&mut self, value: T) {
        if self.len.is_multiple_of(BLOCK) {
            let block: Box<[T]> = vec![T::default(); BLOCK].into_boxed_slice();
            let Ok(block) = <Box<[T; BLOCK]>>::try_from(block) else {
                unreachable!("a block has BLOCK items");
            };
            self.blocks.push(block);
        }
        let i = self.len;
        self[i] = value;
        self.len += 1;
    }
}

impl<T> Blocks<T> {
    pub fn len(&self) -> usize {
        self.len
    }

    /// The store as `stats --memory` lists it: its blocks of [`BLOCK`] items.
    pub fn pool(&self, name: &'static str) -> crate::pools::Pool {
        crate::pools::Pool {
            name,
            item_size: std::mem::size_of::<T>(),
            per_block: BLOCK,
            blocks: self.blocks.len(),
        }
    }

    pub fn get(&self, i: usize) -> Option<&T> {
        (i < self.len).then(|| &self[i])
    }

    pub fn get_mut(&mut self, i: usize) -> Option<&mut T> {
        (i < self.len).then(|| &mut self[i])
    }
}

impl<T> Index<usize> for Blocks<T> {
    type Output = T;
    fn index(&self, i: usize) -> &T {
        debug_assert!(i < self.len, "index past the end");
        &self.blocks[i >> SHIFT][i & (BLOCK - 1)]
    }
}

impl<T> IndexMut<usize> for Blocks<T> {
    fn index_mut(&mut self, i: usize) -> &mut T {
        &mut self.blocks[i >> SHIFT][i & (BLOCK - 1)]
    }
}

/// What [`super::alloc`] needs of an arena.
pub(crate) trait Arena<T>: IndexMut<usize, Output = T> {
    fn push_item(&mut self, value: T);
    fn item_count(&self) -> usize;
}

impl<T> Arena<T> for Vec<T> {
    fn push_item(&mut self, value: T) {
        self.push(value);
    }
    fn item_count(&self) -> usize {
        self.len()
    }
}

impl<T: Default + Clone> Arena<T> for Blocks<T> {
    fn push_item(&mut self, value: T) {
        self.push(value);
    }
    fn item_count(&self) -> usize {
        self.len
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indexes_across_blocks() {
        let mut b = Blocks::default();
        for i in 0..(BLOCK * 2 + 3) {
            b.push(i);
        }
        assert_eq!(b.len(), BLOCK * 2 + 3);
        assert_eq!(b[BLOCK + 1], BLOCK + 1);
        b[BLOCK * 2] = 7;
        assert_eq!(b.get(BLOCK * 2), Some(&7));
        assert_eq!(b.get(BLOCK * 2 + 3), None);
    }
}
