//! Symbols (Soar manual, ch. 3, "Symbols"): interned string constants, 64-bit integers and
//! floats, and identifiers named by a letter and a number with one counter per letter.
//! Equality of symbols is equality of [`Sym`] handles, so int 1 and float 1.0 differ, as in
//! Soar.

use crate::rete::blocks::Blocks;
use rustc_hash::FxHashMap;
use std::cmp::Ordering;

/// A handle to an interned symbol.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Sym(pub(crate) u32);

/// An identifier letter's index (upper-cased; non-letters read as `I`).
fn letter_index(letter: char) -> usize {
    let l = letter.to_ascii_uppercase();
    if l.is_ascii_uppercase() {
        (l as u8 - b'A') as usize
    } else {
        (b'I' - b'A') as usize
    }
}

impl Sym {
    /// Marks a number an identifier letter skipped (see `Symbols::new_id_numbered`).
    const UNNAMED: Sym = Sym(u32::MAX);
}

#[derive(Debug, Clone, PartialEq)]
pub enum SymData {
    Str(arcstr::ArcStr),
    Int(i64),
    Float(f64),
    Id(IdData),
}

/// The filler of the symbol table's slots not yet used (see `Blocks`).
impl Default for SymData {
    fn default() -> Self {
        SymData::Int(0)
    }
}

/// An identifier: `letter` + `number`, plus what the architecture knows of it.
#[derive(Debug, Clone, PartialEq)]
pub struct IdData {
    pub letter: u8,
    pub number: u64,
    /// Goal-stack level (1 = top state); 0 when not yet linked.
    pub level: u32,
    /// A state in the goal stack: `(state <s> ...)` conditions test this.
    pub is_goal: bool,
    /// `(impasse <i> ...)` conditions test this.
    pub is_impasse: bool,
    /// The long-term identifier this one stands for in working memory (`@N`), 0 for none
    /// (Soar manual, Semantic Memory, "Working Memory Interface").
    pub lti: i64,
}

/// An identifier's name (`S12`), written without the formatting machinery: justifications
/// name every identifier they test this way, thousands of times a second.
fn id_text(letter: u8, mut number: u64) -> String {
    let mut digits = [0u8; 20];
    let mut at = digits.len();
    loop {
        at -= 1;
        digits[at] = b'0' + (number % 10) as u8;
        number /= 10;
        if number == 0 {
            break;
        }
    }
    let mut text = String::with_capacity(1 + digits.len() - at);
    text.push(letter as char);
    text.extend(digits[at..].iter().map(|&d| d as char));
    text
}

impl Default for Known {
    /// Placeholders that name no symbol, until `Symbols::new` looks the constants up.
    fn default() -> Self {
        let none = Sym(u32::MAX);
        Known {
            operator: none,
            state: none,
            type_: none,
            superstate: none,
            reward_link: none,
            epmem: none,
            smem: none,
            command: none,
            result: none,
            present_id: none,
            attribute: none,
            impasse: none,
            choices: none,
            multiple: none,
            none,
            quiescence: none,
            t: none,
            item: none,
            item_count: none,
            non_numeric: none,
            non_numeric_count: none,
        }
    }
}

/// The symbol table of one agent. Counters live here and are reset by `init-soar`.
#[derive(Debug, Default)]
pub struct Symbols {
    /// (In fixed-size blocks: a doubling vector would leave up to half its room unused, and
    /// loading 100,000 rules makes 300,000 symbols.)
    table: Blocks<SymData>,
    /// String symbols by a 32-bit hash of their text, so the text is stored once (in
    /// `table`); the few strings whose hash is taken are in `str_clashes`.
    strs: FxHashMap<u32, Sym>,
    /// The rare strings whose hash an earlier string already has, by their text.
    str_clashes: FxHashMap<Box<str>, Sym>,
    ints: FxHashMap<i64, Sym>,
    floats: FxHashMap<u64, Sym>,
    /// Identifiers by letter, then number: `ids[L][n - 1]` is `Ln` (numbers go up by one
    /// from 1 per letter, so a list serves where a hash map would cost every new id an
    /// insert; a learning or SLAM run makes hundreds of thousands).
    ids: [Vec<Sym>; 26],
    /// Identifiers named far past their letter's list (a `wm add` of `Z99999`), by letter
    /// index and number.
    far_ids: FxHashMap<(usize, u64), Sym>,
    counters: [u64; 26],
    /// The constants the decision cycle itself writes and reads, looked up once.
    pub known: Known,
}

/// Constants the architecture uses on every substate and firing (all among the start-up
/// constants, so naming them here changes no symbol's creation order).
#[derive(Debug, Clone, Copy)]
pub struct Known {
    pub operator: Sym,
    pub state: Sym,
    pub type_: Sym,
    pub superstate: Sym,
    pub reward_link: Sym,
    pub epmem: Sym,
    pub smem: Sym,
    pub command: Sym,
    pub result: Sym,
    pub present_id: Sym,
    pub attribute: Sym,
    pub impasse: Sym,
    pub choices: Sym,
    pub multiple: Sym,
    pub none: Sym,
    pub quiescence: Sym,
    pub t: Sym,
    pub item: Sym,
    pub item_count: Sym,
    pub non_numeric: Sym,
    pub non_numeric_count: Sym,
}

impl Symbols {
    /// The symbol table's store, for `stats --memory`, the bytes of its strings' text and
    /// of its hash tables.
    pub(crate) fn memory_pools(&self, pools: &mut Vec<crate::pools::Pool>) -> (usize, usize) {
        use crate::pools::hash_table_bytes;
        pools.push(self.table.pool("symbol"));
        let mut text = 0;
        for i in 0..self.table.len() {
            if let SymData::Str(s) = &self.table[i] {
                text += s.len();
            }
        }
        let hashes = hash_table_bytes::<u32, Sym>(self.strs.capacity())
            + hash_table_bytes::<i64, Sym>(self.ints.capacity())
            + hash_table_bytes::<u64, Sym>(self.floats.capacity());
        (text, hashes)
    }

    /// A symbol table holding the constants the official kernel creates when an agent is made,
    /// in its order (`src/initial_symbols.txt`, read off Soar 9.6.5 by
    /// `scripts/initial_symbols.py`): the condition reorderer breaks ties by creation order.
    pub fn new() -> Self {
        let mut s = Symbols {
            counters: [1; 26],
            ..Default::default()
        };
        for line in include_str!("initial_symbols.txt").lines() {
            if let Some(name) = line.strip_prefix("s:") {
                s.str(&name.replace("\\n", "\n"));
            } else if let Some(n) = line.strip_prefix("i:").and_then(|n| n.parse().ok()) {
                s.int(n);
            }
        }
        s.known = Known {
            operator: s.str("operator"),
            state: s.str("state"),
            type_: s.str("type"),
            superstate: s.str("superstate"),
            reward_link: s.str("reward-link"),
            epmem: s.str("epmem"),
            smem: s.str("smem"),
            command: s.str("command"),
            result: s.str("result"),
            present_id: s.str("present-id"),
            attribute: s.str("attribute"),
            impasse: s.str("impasse"),
            choices: s.str("choices"),
            multiple: s.str("multiple"),
            none: s.str("none"),
            quiescence: s.str("quiescence"),
            t: s.str("t"),
            item: s.str("item"),
            item_count: s.str("item-count"),
            non_numeric: s.str("non-numeric"),
            non_numeric_count: s.str("non-numeric-count"),
        };
        s
    }

    fn push(&mut self, d: SymData) -> Sym {
        let s = Sym(self.table.len() as u32);
        self.table.push(d);
        s
    }

    pub fn str(&mut self, s: &str) -> Sym {
        let h = str_hash(s);
        match self.strs.get(&h) {
            None => {
                let x = self.push(SymData::Str(s.into()));
                self.strs.insert(h, x);
                x
            }
            Some(&x) if self.is_str(x, s) => x,
            Some(_) => {
                if let Some(&x) = self.str_clashes.get(s) {
                    return x;
                }
                let x = self.push(SymData::Str(s.into()));
                self.str_clashes.insert(s.into(), x);
                x
            }
        }
    }

    fn is_str(&self, x: Sym, s: &str) -> bool {
        matches!(&self.table[x.0 as usize], SymData::Str(t) if **t == *s)
    }

    pub fn int(&mut self, i: i64) -> Sym {
        if let Some(&x) = self.ints.get(&i) {
            return x;
        }
        let x = self.push(SymData::Int(i));
        self.ints.insert(i, x);
        x
    }

    /// A float constant. A negative zero becomes `0.0` (adding `0.0` does it): Soar has
    /// one zero, which prints as `0.000000` in `write`, the trace and `print` alike.
    pub fn float(&mut self, f: f64) -> Sym {
        let f = f + 0.0;
        let key = f.to_bits();
        if let Some(&x) = self.floats.get(&key) {
            return x;
        }
        let x = self.push(SymData::Float(f));
        self.floats.insert(key, x);
        x
    }

    /// Interns a parsed constant.
    pub fn constant(&mut self, c: &crate::ast::Constant) -> Sym {
        match c {
            crate::ast::Constant::Str(s) => self.str(s),
            crate::ast::Constant::Int(i) => self.int(*i),
            crate::ast::Constant::Float(f) => self.float(*f),
        }
    }

    /// Looks a parsed constant up without creating it.
    pub fn find_constant(&self, c: &crate::ast::Constant) -> Option<Sym> {
        match c {
            crate::ast::Constant::Str(s) => self.find_str(s),
            crate::ast::Constant::Int(i) => self.ints.get(i).copied(),
            crate::ast::Constant::Float(f) => self.floats.get(&(f + 0.0).to_bits()).copied(),
        }
    }

    /// Looks a string constant up without creating it.
    pub fn find_str(&self, s: &str) -> Option<Sym> {
        match self.strs.get(&str_hash(s)) {
            None => None,
            Some(&x) if self.is_str(x, s) => Some(x),
            Some(_) => self.str_clashes.get(s).copied(),
        }
    }

    /// A new identifier with the next number for `letter` (upper-cased; non-letters use `I`).
    pub fn new_id(&mut self, letter: char, level: u32) -> Sym {
        let number = self.counters[letter_index(letter)];
        self.new_id_numbered(letter, number, level)
    }

    /// A new identifier named by `letter` and `number` (also the `wm add` of an
    /// identifier-shaped value that names none, as 9.6 makes one): the letter's counter
    /// moves past `number`, so the identifiers made next do not take the name again.
    /// Numbers skipped stay unnamed.
    pub fn new_id_numbered(&mut self, letter: char, number: u64, level: u32) -> Sym {
        let slot = letter_index(letter);
        let x = self.push(SymData::Id(IdData {
            letter: b'A' + slot as u8,
            number,
            level,
            is_goal: false,
            is_impasse: false,
            lti: 0,
        }));
        // The letter's next number, nearly always (a firing's new identifiers): pushed at
        // once, without `name_id`'s checks (0.3 % of count-deep's instructions).
        if self.ids[slot].len() as u64 + 1 == number {
            self.ids[slot].push(x);
        } else {
            self.name_id(slot, number, x);
        }
        if number >= self.counters[slot] {
            self.counters[slot] = number.saturating_add(1);
        }
        x
    }

    /// Files identifier `x` as number `number` of letter index `slot`: in the letter's
    /// list (numbers skipped on the way unnamed), or, far past its end, in `far_ids`.
    fn name_id(&mut self, slot: usize, number: u64, x: Sym) {
        /// How many numbers a name may skip and still be listed.
        const MAX_SKIP: u64 = 1 << 16;
        let list = &mut self.ids[slot];
        let len = list.len() as u64;
        let index = number.saturating_sub(1);
        if index < len {
            list[index as usize] = x;
        } else if index - len <= MAX_SKIP {
            list.resize(index as usize, Sym::UNNAMED);
            list.push(x);
        } else {
            self.far_ids.insert((slot, number), x);
        }
    }

    /// Gives an existing identifier the next number for its letter (after `init-soar`, the
    /// identifiers a program keeps are numbered again as they are added again).
    pub fn renumber_id(&mut self, id: Sym) {
        let Some(d) = self.id_data(id) else { return };
        let slot = (d.letter - b'A') as usize;
        let number = self.counters[slot];
        self.counters[slot] = number.saturating_add(1);
        if let Some(d) = self.id_data_mut(id) {
            d.number = number;
        }
        self.name_id(slot, number, id);
    }

    /// The identifier named `S1`, `i2`... if it exists.
    pub fn find_id(&self, name: &str) -> Option<Sym> {
        let b = name.as_bytes();
        if b.len() < 2 || !b[0].is_ascii_alphabetic() {
            return None;
        }
        let n: u64 = name[1..].parse().ok()?;
        let slot = (b[0].to_ascii_uppercase() - b'A') as usize;
        let index = usize::try_from(n.checked_sub(1)?).ok()?;
        match self.ids[slot].get(index) {
            Some(&x) => Some(x).filter(|&x| x != Sym::UNNAMED),
            None => self.far_ids.get(&(slot, n)).copied(),
        }
    }

    /// `init-soar`: identifier counters start again at 1, as in the official kernel.
    pub fn reset_id_counters(&mut self) {
        self.counters = [1; 26];
        for list in &mut self.ids {
            list.clear();
        }
        self.far_ids.clear();
    }

    /// Every symbol, in the order they were made.
    pub fn all(&self) -> impl Iterator<Item = Sym> + '_ {
        (0..self.table.len()).map(|i| Sym(i as u32))
    }

    pub fn get(&self, s: Sym) -> &SymData {
        &self.table[s.0 as usize]
    }

    pub fn id_data(&self, s: Sym) -> Option<&IdData> {
        match self.get(s) {
            SymData::Id(d) => Some(d),
            _ => None,
        }
    }

    pub fn id_data_mut(&mut self, s: Sym) -> Option<&mut IdData> {
        match &mut self.table[s.0 as usize] {
            SymData::Id(d) => Some(d),
            _ => None,
        }
    }

    pub fn is_id(&self, s: Sym) -> bool {
        matches!(self.get(s), SymData::Id(_))
    }

    pub fn is_goal(&self, s: Sym) -> bool {
        self.id_data(s).is_some_and(|d| d.is_goal)
    }

    /// The LTI an identifier stands for, if any.
    pub fn lti(&self, s: Sym) -> Option<i64> {
        self.id_data(s).map(|d| d.lti).filter(|&l| l > 0)
    }

    pub fn is_impasse(&self, s: Sym) -> bool {
        self.id_data(s).is_some_and(|d| d.is_impasse)
    }

    /// Rereadable text, as `print` shows a symbol (`|P1|`, floats with 6 decimals; Soar
    /// manual, ch. 3, "Symbols").
    pub fn text(&self, s: Sym) -> String {
        match self.get(s) {
            SymData::Str(x) => crate::printer::rereadable(x),
            SymData::Int(i) => i.to_string(),
            SymData::Float(f) => crate::printer::float_text(*f),
            SymData::Id(d) => id_text(d.letter, d.number),
        }
    }

    /// Plain text with no bars, as `write` and `exec` see a symbol (Soar manual, ch. 3,
    /// "Right-hand side Functions").
    pub fn plain(&self, s: Sym) -> String {
        match self.get(s) {
            SymData::Str(x) => x.to_string(),
            _ => self.text(s),
        }
    }

    /// Soar's `compare_symbols` (rete.cpp): numbers numerically, strings by strcmp,
    /// identifiers by letter then number; any type mismatch is "less" (`Less`).
    pub fn compare(&self, a: Sym, b: Sym) -> Ordering {
        use SymData::*;
        match (self.get(a), self.get(b)) {
            (Int(x), Int(y)) => x.cmp(y),
            (Int(x), Float(y)) => (*x as f64).partial_cmp(y).unwrap_or(Ordering::Less),
            (Float(x), Int(y)) => x.partial_cmp(&(*y as f64)).unwrap_or(Ordering::Less),
            (Float(x), Float(y)) => x.partial_cmp(y).unwrap_or(Ordering::Less),
            (Str(x), Str(y)) => x.as_bytes().cmp(y.as_bytes()),
            (Id(x), Id(y)) => (x.letter, x.number).cmp(&(y.letter, y.number)),
            _ => Ordering::Less,
        }
    }

    /// `<=>`: the same kind of symbol (int and float differ).
    pub fn same_type(&self, a: Sym, b: Sym) -> bool {
        std::mem::discriminant(self.get(a)) == std::mem::discriminant(self.get(b))
    }

}

fn str_hash(s: &str) -> u32 {
    use std::hash::{Hash, Hasher};
    let mut h = rustc_hash::FxHasher::default();
    s.hash(&mut h);
    let h = h.finish();
    (h ^ (h >> 32)) as u32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interning_and_types() {
        let mut s = Symbols::new();
        assert_eq!(s.str("a"), s.str("a"));
        assert_ne!(s.int(1), s.float(1.0));
        let (one, two, two_f) = (s.int(1), s.int(2), s.float(2.0));
        assert!(s.same_type(one, two));
        assert!(!s.same_type(one, two_f));
    }

    #[test]
    fn strings_with_the_same_hash_stay_apart() {
        let mut s = Symbols::new();
        let a = s.str("clash-a");
        // Force a clash: "clash-b" finds the slot of its hash taken by "clash-a".
        s.strs.insert(str_hash("clash-b"), a);
        let b = s.str("clash-b");
        assert_ne!(a, b);
        assert_eq!(s.str("clash-b"), b);
        assert_eq!(s.find_str("clash-b"), Some(b));
        assert_eq!(s.find_str("clash-a"), Some(a));
        assert_eq!(s.plain(b), "clash-b");
    }

    #[test]
    fn id_counters_per_letter() {
        let mut s = Symbols::new();
        let i1 = s.new_id('i', 1);
        let s1 = s.new_id('s', 1);
        let i2 = s.new_id('x', 1);
        let q = s.new_id('<', 1);
        assert_eq!(s.text(i1), "I1");
        assert_eq!(s.text(s1), "S1");
        assert_eq!(s.text(i2), "X1");
        assert_eq!(s.text(q), "I2");
        assert_eq!(s.find_id("s1"), Some(s1));
        s.reset_id_counters();
        let again = s.new_id('s', 1);
        assert_eq!(s.text(again), "S1");
    }

    #[test]
    fn named_ids_skip_numbers_and_move_the_counter() {
        let mut s = Symbols::new();
        let z9 = s.new_id_numbered('z', 9, 1);
        assert_eq!(s.text(z9), "Z9");
        assert_eq!(s.find_id("Z9"), Some(z9));
        assert_eq!(s.find_id("Z3"), None);
        let z10 = s.new_id('z', 1);
        assert_eq!(s.text(z10), "Z10");
        let z3 = s.new_id_numbered('z', 3, 1);
        assert_eq!(s.find_id("z3"), Some(z3));
        // Far past the list: kept apart, and the counter still moves past it.
        let far = s.new_id_numbered('z', 1 << 40, 1);
        assert_eq!(s.find_id(&format!("Z{}", 1u64 << 40)), Some(far));
        let next = s.new_id('z', 1);
        assert_eq!(s.find_id(&format!("Z{}", (1u64 << 40) + 1)), Some(next));
        let max = s.new_id_numbered('z', u64::MAX, 1);
        assert_eq!(s.find_id(&format!("Z{}", u64::MAX)), Some(max));
        s.reset_id_counters();
        assert_eq!(s.find_id("Z9"), None);
        let z1 = s.new_id('z', 1);
        assert_eq!(s.text(z1), "Z1");
    }

    #[test]
    fn mixed_type_comparison_is_less() {
        let mut s = Symbols::new();
        let abc = s.str("abc");
        let five = s.int(5);
        assert_eq!(s.compare(abc, five), Ordering::Less);
        assert_eq!(s.compare(five, abc), Ordering::Less);
        let f = s.float(2.5);
        assert_eq!(s.compare(f, five), Ordering::Less);
        assert_eq!(s.compare(five, f), Ordering::Greater);
    }
}
