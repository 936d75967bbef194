//! The kernel's storage as `stats --memory` reports it (Soar manual, ch. 9, `stats`). 9.6
//! allocates its structures from fixed-size memory pools; rusoar keeps each kind of item
//! in a growable array (or in fixed-size blocks, `rete/blocks.rs`), which this report
//! lists in 9.6's layout: one row per array, its item size, the items one block (the
//! array's room) holds, and the number of blocks. Data only: each store describes itself.

/// One store of items of one kind.
#[derive(Debug, Clone, PartialEq)]
pub struct Pool {
    pub name: &'static str,
    pub item_size: usize,
    pub per_block: usize,
    pub blocks: usize,
}

impl Pool {
    /// A growable array of `T` with room for `capacity` items: one block of that room, or
    /// none while it has none.
    pub fn of_vec<T>(name: &'static str, capacity: usize) -> Pool {
        Pool {
            name,
            item_size: std::mem::size_of::<T>(),
            per_block: capacity,
            blocks: usize::from(capacity > 0),
        }
    }

    /// The bytes the store holds.
    pub fn bytes(&self) -> usize {
        self.item_size * self.per_block * self.blocks
    }
}

/// The bytes of a hash table with room for `capacity` entries of `K` and `V` (plus one
/// control byte each, as in hashbrown).
pub fn hash_table_bytes<K, V>(capacity: usize) -> usize {
    capacity * (std::mem::size_of::<(K, V)>() + 1)
}

/// What `stats --memory` reports: the stores, the text of string constants, and the hash
/// tables.
#[derive(Debug, Clone, Default)]
pub struct MemoryReport {
    pub pools: Vec<Pool>,
    pub string_bytes: usize,
    pub hash_table_bytes: usize,
}
