//! The kernel's table handles. Each names an item by its place in one table (a `Vec` whose
//! freed places are reused) and is a `u32` in its own type, declared with [`id_type!`], so
//! that the handles of two tables cannot be mixed up; in memory each is its `u32`.

/// A handle that is an index into its table (for code that allocates in any table).
pub trait Id: Copy {
    /// The handle of the item at `i`.
    fn from_index(i: usize) -> Self;
    /// The item's index in its table.
    fn index(self) -> usize;
}

/// The untyped list entries (alpha-memory entries, negative join results, index entries).
impl Id for u32 {
    #[inline(always)]
    fn from_index(i: usize) -> Self {
        i as u32
    }
    #[inline(always)]
    fn index(self) -> usize {
        self as usize
    }
}

/// Declares a handle type: `id_type!(/// doc  pub struct NodeId; index Node;)`. The
/// optional `index` list names the item types whose `Vec`s and slices it indexes
/// (`nodes[n]`).
macro_rules! id_type {
    // Indexing only, declared beside the item type (when the id's module must not name it).
    (index $name:ident => $item:ty) => {
        $crate::ids::id_type!(@index $name, [$item]);
        $crate::ids::id_type!(@index $name, Vec<$item>);
    };
    (
        $(#[$meta:meta])*
        $vis:vis struct $name:ident;
        $(index $($item:ty),+ $(,)?;)?
    ) => {
        $(#[$meta])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
        #[repr(transparent)]
        $vis struct $name(u32);

        // (Not every table uses every constructor or the sentinel.)
        #[allow(dead_code)]
        impl $name {
            /// No item: the end of a list, or a link not set.
            pub const NONE: $name = $name(u32::MAX);

            /// The handle whose raw value is `raw`.
            #[inline(always)]
            pub const fn new(raw: u32) -> Self {
                $name(raw)
            }

            /// The handle of the item at `i`.
            #[inline(always)]
            pub const fn from_index(i: usize) -> Self {
                $name(i as u32)
            }

            /// The item's index in its table.
            #[inline(always)]
            pub const fn index(self) -> usize {
                self.0 as usize
            }

            /// The raw value (for lists and keys that hold handles of several kinds).
            #[inline(always)]
            pub const fn raw(self) -> u32 {
                self.0
            }
        }

        impl $crate::ids::Id for $name {
            #[inline(always)]
            fn from_index(i: usize) -> Self {
                $name::from_index(i)
            }
            #[inline(always)]
            fn index(self) -> usize {
                $name::index(self)
            }
        }

        $($(
            $crate::ids::id_type!(@index $name, [$item]);
            $crate::ids::id_type!(@index $name, Vec<$item>);
        )+)?
    };
    (@index $name:ident, $table:ty) => {
        impl ::std::ops::Index<$name> for $table {
            type Output = <$table as ::std::ops::Index<usize>>::Output;
            #[inline(always)]
            fn index(&self, i: $name) -> &Self::Output {
                &self[i.index()]
            }
        }

        impl ::std::ops::IndexMut<$name> for $table {
            #[inline(always)]
            fn index_mut(&mut self, i: $name) -> &mut Self::Output {
                &mut self[i.index()]
            }
        }
    };
}

pub(crate) use id_type;
