//! A justification's negated conditions (Soar manual, ch. 2, "Justifications: Support for
//! results"): 9.6 adds a justification to the rete like a rule, so a result whose
//! justification negates a superstate WME (or a conjunction of them) retracts as soon as
//! such a WME appears. Justifications are not in our network: their negations are kept here
//! as patterns over symbols (the firing's bindings filled in, the negation's own variables
//! left free), and each new WME whose attribute one of them tests is checked against them.

use std::sync::Arc;

use rustc_hash::FxHashMap;

use super::InstTrace;
use crate::ast::Relation;
use crate::production::{Cond, Condition, Term, Test};
use crate::rete::tests::{relation_holds, Op};
use crate::decide::ids::InstId;
use crate::symbols::{Sym, Symbols};
use crate::wm::{Wme, WorkingMemory};

/// A term of a pattern: a symbol, or a variable of the negation itself (by number).
#[derive(Debug, Clone, Copy, PartialEq)]
enum PTerm {
    Sym(Sym),
    Local(usize),
    /// A constant no symbol exists for: nothing can equal it.
    Missing,
}

#[derive(Debug, Clone)]
enum PTest {
    Eq(PTerm),
    Rel(Relation, PTerm),
    AnyOf(Vec<Sym>),
}

#[derive(Debug, Clone)]
struct PCond {
    /// The tests of the id, attribute and value fields.
    fields: [Vec<PTest>; 3],
    acceptable: bool,
}

#[derive(Debug, Clone)]
enum Pattern {
    Pos(PCond),
    Neg(PCond),
    Ncc(Vec<Pattern>),
}

/// One justification's negations.
#[derive(Debug)]
struct Watched {
    inst: InstId,
    serial: u64,
    /// Each negation as the conjunction whose match violates it.
    negations: Vec<Vec<Pattern>>,
    locals: usize,
    /// The constant attribute each of its patterns tests (`None`: not a constant).
    attrs: Vec<Option<Sym>>,
}

impl Watched {
    /// Whether a new WME with attribute `attr` can match one of its patterns.
    fn may_match(&self, attr: Sym) -> bool {
        self.attrs.iter().any(|a| a.is_none_or(|a| a == attr))
    }
}

/// The negations of the live justifications that have any.
#[derive(Debug, Default)]
pub struct WatchedNegations {
    watched: Vec<Watched>,
    /// How many watched patterns test each constant attribute; `any_attr` those that do not.
    attrs: FxHashMap<Sym, u32>,
    any_attr: u32,
}

impl WatchedNegations {
    pub fn is_empty(&self) -> bool {
        self.watched.is_empty()
    }

    pub fn clear(&mut self) {
        *self = WatchedNegations::default();
    }

    /// Watches the negations (conditions of `trace`'s rule) of justification `inst`.
    pub fn watch(
        &mut self,
        inst: InstId,
        serial: u64,
        negations: &[(Arc<InstTrace>, &Condition)],
        syms: &Symbols,
    ) {
        let mut w = Watched {
            inst,
            serial,
            negations: Vec::new(),
            locals: 0,
            attrs: Vec::new(),
        };
        for (trace, c) in negations {
            let mut locals = FxHashMap::default();
            let inner = match c {
                Condition::Negative(x) => vec![Pattern::Pos(pcond(x, trace, &mut locals, syms))],
                Condition::Ncc(cs) => cs
                    .iter()
                    .map(|x| pattern(x, trace, &mut locals, syms))
                    .collect(),
                Condition::Positive(_) => continue,
            };
            w.locals = w.locals.max(locals.len());
            w.negations.push(inner);
        }
        if w.negations.is_empty() {
            return;
        }
        fn walk(p: &[Pattern], out: &mut Vec<Option<Sym>>) {
            for x in p {
                match x {
                    Pattern::Pos(c) | Pattern::Neg(c) => out.push(match c.fields[1].first() {
                        Some(PTest::Eq(PTerm::Sym(s))) => Some(*s),
                        _ => None,
                    }),
                    Pattern::Ncc(cs) => walk(cs, out),
                }
            }
        }
        for n in &w.negations {
            walk(n, &mut w.attrs);
        }
        self.count_attrs(&w, 1);
        self.watched.push(w);
    }

    fn count_attrs(&mut self, w: &Watched, add: i64) {
        for &a in &w.attrs {
            let slot = match a {
                Some(s) => self.attrs.entry(s).or_insert(0),
                None => &mut self.any_attr,
            };
            *slot = (*slot as i64 + add).max(0) as u32;
        }
    }

    /// WME `new` was added: the justifications (instantiation, serial, alpha table) one of
    /// whose negations now matches, with the 9.6 alpha table (see [`alpha_table`]) its
    /// rete would have reached first with `new`. They stop being watched; so do the ones
    /// `alive` says are gone.
    pub fn violated_by(
        &mut self,
        new: &Wme,
        wm: &WorkingMemory,
        syms: &Symbols,
        alive: impl Fn(InstId, u64) -> bool,
    ) -> Vec<(InstId, u64, u8)> {
        let attr = new.attr;
        if self.any_attr == 0 && self.attrs.get(&attr).is_none_or(|&n| n == 0) {
            return Vec::new();
        }
        let mut out = Vec::new();
        let mut keep = Vec::with_capacity(self.watched.len());
        for w in std::mem::take(&mut self.watched) {
            let gone = !alive(w.inst, w.serial);
            let violated = !gone && w.may_match(attr) && {
                let mut binding = vec![None; w.locals];
                w.negations
                    .iter()
                    .any(|n| satisfiable(n, &mut binding, wm, syms))
            };
            if violated {
                let table = w
                    .negations
                    .iter()
                    .filter_map(|n| alpha_table(n, new))
                    .min()
                    .unwrap_or(u8::MAX);
                out.push((w.inst, w.serial, table));
            }
            if gone || violated {
                self.count_attrs(&w, -1);
            } else {
                keep.push(w);
            }
        }
        self.watched = keep;
        out
    }
}

/// The lowest 9.6 alpha hash table among the conditions of `items` whose constant tests
/// `new` passes: `id constant` × 4 + `attr constant` × 2 + `value constant` (a
/// justification's identifiers are constants; the negation's own variables are not).
fn alpha_table(items: &[Pattern], new: &Wme) -> Option<u8> {
    items
        .iter()
        .filter_map(|p| match p {
            Pattern::Pos(c) | Pattern::Neg(c) => {
                if c.acceptable != new.acceptable {
                    return None;
                }
                let mut table = 0;
                for (bit, (tests, field)) in [4u8, 2, 1]
                    .iter()
                    .zip(c.fields.iter().zip([new.id, new.attr, new.value]))
                {
                    match tests.first() {
                        Some(PTest::Eq(PTerm::Sym(s))) if *s == field => table |= bit,
                        Some(PTest::Eq(PTerm::Sym(_) | PTerm::Missing)) => return None,
                        _ => {}
                    }
                }
                Some(table)
            }
            Pattern::Ncc(cs) => alpha_table(cs, new),
        })
        .min()
}

fn pattern(
    c: &Condition,
    trace: &InstTrace,
    locals: &mut FxHashMap<String, usize>,
    syms: &Symbols,
) -> Pattern {
    match c {
        Condition::Positive(x) => Pattern::Pos(pcond(x, trace, locals, syms)),
        Condition::Negative(x) => Pattern::Neg(pcond(x, trace, locals, syms)),
        Condition::Ncc(cs) => {
            Pattern::Ncc(cs.iter().map(|x| pattern(x, trace, locals, syms)).collect())
        }
    }
}

fn pcond(
    c: &Cond,
    trace: &InstTrace,
    locals: &mut FxHashMap<String, usize>,
    syms: &Symbols,
) -> PCond {
    let mut fields: [Vec<PTest>; 3] = Default::default();
    for (out, t) in fields.iter_mut().zip([&c.id, &c.attr, &c.value]) {
        ptests(t, trace, locals, syms, out);
        // Equality first: it binds what the other tests of the field read.
        out.sort_by_key(|t| !matches!(t, PTest::Eq(_)));
    }
    PCond {
        fields,
        acceptable: c.acceptable,
    }
}

fn ptests(
    t: &Test,
    trace: &InstTrace,
    locals: &mut FxHashMap<String, usize>,
    syms: &Symbols,
    out: &mut Vec<PTest>,
) {
    let mut term = |x: &Term| match x {
        Term::Var(v) => match trace.vars.get(v) {
            Some(&(_, s)) => PTerm::Sym(s),
            None => {
                let n = locals.len();
                PTerm::Local(*locals.entry(v.to_string()).or_insert(n))
            }
        },
        Term::Const(k) => syms.find_constant(k).map_or(PTerm::Missing, PTerm::Sym),
    };
    match t {
        Test::Equal(x) => out.push(PTest::Eq(term(x))),
        Test::Relational(rt) => out.push(PTest::Rel(rt.op, term(&rt.term))),
        Test::Disjunction(cs) => out.push(PTest::AnyOf(
            cs.iter().filter_map(|k| syms.find_constant(k)).collect(),
        )),
        Test::Conjunction(ts) => {
            for x in ts.iter() {
                ptests(x, trace, locals, syms, out);
            }
        }
    }
}

/// Whether WMEs exist that match the conjunction `items` from `binding` on (9.6's rete
/// semantics: a negation holds when nothing matches it, a conjunctive negation when its
/// conjunction has no match). `binding` is restored before returning.
fn satisfiable(
    items: &[Pattern],
    binding: &mut Vec<Option<Sym>>,
    wm: &WorkingMemory,
    syms: &Symbols,
) -> bool {
    let Some((first, rest)) = items.split_first() else {
        return true;
    };
    match first {
        Pattern::Pos(c) => matched_then(c, rest, binding, wm, syms),
        Pattern::Neg(c) => {
            !matched_then(c, &[], binding, wm, syms) && satisfiable(rest, binding, wm, syms)
        }
        Pattern::Ncc(cs) => {
            let blocked = satisfiable(cs, binding, wm, syms);
            !blocked && satisfiable(rest, binding, wm, syms)
        }
    }
}

/// Whether a WME matches `c` such that `rest` is then satisfiable; `binding` is restored.
fn matched_then(
    c: &PCond,
    rest: &[Pattern],
    binding: &mut Vec<Option<Sym>>,
    wm: &WorkingMemory,
    syms: &Symbols,
) -> bool {
    for w in candidates(c, binding, wm) {
        let Some(wme) = wm.get(w).copied() else {
            continue;
        };
        let saved = binding.clone();
        let found = wme_matches(c, &wme, binding, syms) && satisfiable(rest, binding, wm, syms);
        *binding = saved;
        if found {
            return true;
        }
    }
    false
}

/// The WMEs that can match `c`: those of its identifier when that is known.
fn candidates(c: &PCond, binding: &[Option<Sym>], wm: &WorkingMemory) -> Vec<crate::wm::WmeId> {
    let id = c.fields[0].iter().find_map(|t| match t {
        PTest::Eq(PTerm::Sym(s)) => Some(*s),
        PTest::Eq(PTerm::Local(i)) => binding[*i],
        _ => None,
    });
    match id {
        Some(id) => wm.of_id(id).collect(),
        None => wm.all(),
    }
}

fn wme_matches(c: &PCond, w: &Wme, binding: &mut [Option<Sym>], syms: &Symbols) -> bool {
    if c.acceptable != w.acceptable {
        return false;
    }
    for (tests, v) in c.fields.iter().zip([w.id, w.attr, w.value]) {
        for t in tests {
            let ok = match t {
                PTest::Eq(PTerm::Local(i)) => match binding[*i] {
                    Some(b) => b == v,
                    None => {
                        binding[*i] = Some(v);
                        true
                    }
                },
                PTest::Eq(PTerm::Sym(s)) => *s == v,
                PTest::Eq(PTerm::Missing) => false,
                PTest::Rel(r, x) => match resolve(*x, binding) {
                    Some(b) => relation_holds(syms, Op::Rel(*r), v, b),
                    None => false,
                },
                PTest::AnyOf(items) => items.contains(&v),
            };
            if !ok {
                return false;
            }
        }
    }
    true
}

fn resolve(t: PTerm, binding: &[Option<Sym>]) -> Option<Sym> {
    match t {
        PTerm::Sym(s) => Some(s),
        PTerm::Local(i) => binding[i],
        PTerm::Missing => None,
    }
}
