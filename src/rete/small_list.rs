//! A list that keeps one element inline: a node's linked children and a holder's index keys
//! are nearly always none or one, and a `Vec` would cost every node 24 bytes and every
//! non-empty list a heap block (100,000 rules build about 800,000 nodes).

#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) enum SmallList<T> {
    #[default]
    Empty,
    One(T),
    /// (Boxed, so that the list is two words; once many, it stays a vector.)
    #[allow(clippy::box_collection)]
    Many(Box<Vec<T>>),
}

impl<T: Copy + PartialEq> SmallList<T> {
    pub fn as_slice(&self) -> &[T] {
        match self {
            SmallList::Empty => &[],
            SmallList::One(x) => std::slice::from_ref(x),
            SmallList::Many(v) => v,
        }
    }

    pub fn as_mut_slice(&mut self) -> &mut [T] {
        match self {
            SmallList::Empty => &mut [],
            SmallList::One(x) => std::slice::from_mut(x),
            SmallList::Many(v) => v,
        }
    }

    pub fn len(&self) -> usize {
        self.as_slice().len()
    }

    pub fn is_empty(&self) -> bool {
        matches!(self, SmallList::Empty) || self.len() == 0
    }

    /// Inserts `x` at `i`, as `Vec::insert` does.
    pub fn insert(&mut self, i: usize, x: T) {
        match self {
            SmallList::Empty => *self = SmallList::One(x),
            SmallList::One(y) => {
                let y = *y;
                let v = if i == 0 { vec![x, y] } else { vec![y, x] };
                *self = SmallList::Many(Box::new(v));
            }
            SmallList::Many(v) => v.insert(i, x),
        }
    }

    pub fn push(&mut self, x: T) {
        self.insert(self.len(), x);
    }

    /// Removes and returns the element at `i`, keeping the others in order.
    pub fn remove(&mut self, i: usize) -> T {
        match self {
            SmallList::Many(v) => v.remove(i),
            _ => {
                let x = self.as_slice()[i];
                *self = SmallList::Empty;
                x
            }
        }
    }

    pub fn retain(&mut self, mut keep: impl FnMut(&T) -> bool) {
        match self {
            SmallList::Empty => {}
            SmallList::One(x) => {
                if !keep(x) {
                    *self = SmallList::Empty;
                }
            }
            SmallList::Many(v) => v.retain(keep),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::SmallList;

    #[test]
    fn behaves_as_a_vec() {
        let mut l = SmallList::default();
        let mut v = Vec::new();
        for (i, x) in [(0, 1), (0, 2), (2, 3), (1, 4), (4, 5)] {
            l.insert(i, x);
            v.insert(i, x);
            assert_eq!(l.as_slice(), v.as_slice());
        }
        l.retain(|&x| x != 4);
        v.retain(|&x| x != 4);
        assert_eq!(l.as_slice(), v.as_slice());
        assert_eq!(l.remove(1), v.remove(1));
        assert_eq!(l.as_slice(), v.as_slice());
        let mut one = SmallList::One(7);
        one.push(8);
        assert_eq!(one.as_slice(), [7, 8]);
        let mut one = SmallList::One(7);
        assert_eq!(one.remove(0), 7);
        assert!(one.is_empty());
        one.retain(|_| false);
        assert!(one.is_empty());
    }
}
