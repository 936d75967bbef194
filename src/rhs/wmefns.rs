//! Functions over working memory: `size`, `sum`, `product`, the `set-*` statistics over a
//! multi-valued attribute, and `deep-copy`.

use super::{arity_error, RhsContext};
use crate::symbols::{Sym, SymData};
use crate::wm::{Wme, WmeId};
use rustc_hash::{FxHashMap, FxHashSet};

/// The slot WMEs and input WMEs of `id` (see [`super::WmeOrder`]).
fn wmes_of(ctx: &RhsContext, id: Sym) -> (Vec<Wme>, Vec<Wme>) {
    let (slots, input) = match ctx.wme_order {
        Some(order) => order(id),
        None => (default_order(ctx, id), Vec::new()),
    };
    let get = |v: Vec<WmeId>| {
        v.into_iter()
            .filter_map(|w| ctx.wm.get(w).copied())
            .collect()
    };
    (get(slots), get(input))
}

/// Without the caller's order: every non-acceptable WME of `id` is a slot WME; slots (one per
/// attribute) by their oldest WME, WMEs in a slot newest first. That is 9.6's order for
/// structure built in one firing: the kernel creates the slots of one firing's preferences
/// in reverse action order, pushing each on the front of the list, and head-inserts WMEs.
fn default_order(ctx: &RhsContext, id: Sym) -> Vec<WmeId> {
    // (attribute, oldest timetag, (timetag, WME) of each WME)
    type Slot = (Sym, u64, Vec<(u64, WmeId)>);
    let mut slots: Vec<Slot> = Vec::new();
    for w in ctx.wm.of_id(id) {
        let Some(x) = ctx.wm.get(w) else { continue };
        if x.acceptable {
            continue;
        }
        match slots.iter_mut().find(|s| s.0 == x.attr) {
            Some(s) => {
                s.1 = s.1.min(x.timetag);
                s.2.push((x.timetag, w));
            }
            None => slots.push((x.attr, x.timetag, vec![(x.timetag, w)])),
        }
    }
    slots.sort_by_key(|s| s.1);
    slots
        .into_iter()
        .flat_map(|(_, _, mut ws)| {
            ws.sort_by_key(|w| std::cmp::Reverse(w.0));
            ws.into_iter().map(|(_, w)| w)
        })
        .collect()
}

/// `size` (count), `sum` and `product` of the values of all slot WMEs of an identifier.
/// 9.6 reads every value as an int (`w->value->ic->value`, cast to a 32-bit `int`): an
/// int is itself, a float contributes the low 32 bits of its IEEE pattern, an identifier
/// its number; a string contributes the low bits of a pointer in 9.6, 0 here.
pub(super) fn size_sum_product(
    name: &str,
    args: &[Sym],
    ctx: &mut RhsContext,
) -> Result<Sym, String> {
    let Some(&id) = args.first() else {
        return Err(arity_error(name, 1));
    };
    if !ctx.symbols.is_id(id) {
        return Err(format!(
            "Error: non-symbol ({}) passed to {name} function",
            ctx.y(id)
        ));
    }
    let (wmes, _) = wmes_of(ctx, id);
    let as_int = |s: Sym| -> i32 {
        match ctx.symbols.get(s) {
            SymData::Int(i) => *i as i32,
            SymData::Float(f) => f.to_bits() as i32,
            SymData::Id(d) => d.number as i32,
            SymData::Str(_) => 0,
        }
    };
    let r: i32 = match name {
        "size" => wmes.len() as i32,
        "sum" => wmes
            .iter()
            .fold(0i32, |a, w| a.wrapping_add(as_int(w.value))),
        _ => wmes
            .iter()
            .fold(1i32, |a, w| a.wrapping_mul(as_int(w.value))),
    };
    Ok(ctx.symbols.int(i64::from(r)))
}

/// The values the `set-*` functions reduce: `(set-f id attr [attr2 [attr3]])` walks
/// `id ^attr`, then each value's `^attr2`, then `^attr3`. `Err` is 9.6's error string
/// (returned as the function's value, not as an error).
fn set_values(args: &[Sym], ctx: &RhsContext) -> Result<Vec<Sym>, &'static str> {
    const NOT_ID: &str = "|ERROR: First parameter needs to be an identifier.|";
    let Some(&set) = args.first() else {
        return Err(NOT_ID); // 9.6 dereferences a null argument list here.
    };
    if !ctx.symbols.is_id(set) {
        return Err(NOT_ID);
    }
    let Some(&attr) = args.get(1) else {
        return Ok(Vec::new());
    };
    let named = |id: Sym, attr: Sym| -> Vec<Sym> {
        if !ctx.symbols.is_id(id) {
            return Vec::new();
        }
        wmes_of(ctx, id)
            .0
            .into_iter()
            .filter(|w| w.attr == attr)
            .map(|w| w.value)
            .collect()
    };
    let mut level = named(set, attr);
    for &a in args.iter().skip(2).take(2) {
        level = level.into_iter().flat_map(|v| named(v, a)).collect();
    }
    Ok(level)
}

pub(super) fn set_function(name: &str, args: &[Sym], ctx: &mut RhsContext) -> Result<Sym, String> {
    let values = match set_values(args, ctx) {
        Ok(v) => v,
        Err(e) => return Ok(ctx.symbols.str(e)),
    };
    if name == "set-count" {
        return Ok(ctx.symbols.int(values.len() as i64));
    }
    let nums: Vec<f64> = values
        .iter()
        .filter_map(|v| match ctx.symbols.get(*v) {
            SymData::Int(i) => Some(*i as f64),
            SymData::Float(f) => Some(*f),
            _ => None,
        })
        .collect();
    if nums.is_empty() {
        return Ok(ctx.symbols.str("NaN"));
    }
    let count = nums.len() as f64;
    let sum = || nums.iter().fold(0.0, |a, x| a + x);
    let (min, max) = nums.iter().fold((f64::MAX, -f64::MAX), |(lo, hi), &x| {
        (if x < lo { x } else { lo }, if x > hi { x } else { hi })
    });
    let r = match name {
        "set-sum" => sum(),
        "set-multiply" => nums.iter().fold(1.0, |a, x| a * x),
        "set-min" => min,
        "set-max" => max,
        "set-range" => max - min,
        "set-mean" => sum() / count,
        _ => {
            let mean = sum() / count;
            let sq = nums.iter().fold(0.0, |a, x| a + (x - mean) * (x - mean));
            (sq / count).sqrt()
        }
    };
    Ok(ctx.symbols.float(r))
}

/// `deep-copy id`: a new identifier `D<n>` and a copy of everything reachable from `id`
/// (each reachable identifier copied once, with its own letter), recorded in
/// [`RhsContext::deep_copy_wmes`]. A non-identifier gives the string `*symbol not id*`.
/// Identifiers are numbered in 9.6's walk order: the slots of an id in order, each WME's
/// attribute then value copied (and walked) before the WME itself is recorded.
pub(super) fn deep_copy(args: &[Sym], ctx: &mut RhsContext) -> Result<Sym, String> {
    let Some(&base) = args.first() else {
        return Err(arity_error("deep-copy", 1));
    };
    if !ctx.symbols.is_id(base) {
        return Ok(ctx.symbols.str("*symbol not id*"));
    }
    // A second argument (newer kernels; the 9.6 parser allows one) names an identifier
    // whose attributes are not copied.
    let mut prohibited: FxHashSet<Sym> = FxHashSet::default();
    if let Some(&ex) = args.get(1) {
        if ctx.symbols.is_id(ex) {
            prohibited.extend(wmes_of(ctx, ex).0.iter().map(|w| w.attr));
        }
    }
    let root = ctx.symbols.new_id('D', 0);
    ctx.deep_copy_wmes.clear();

    struct Frame {
        parent: Sym,
        wmes: Vec<Wme>,
        i: usize,
        stage: u8,
        attr: Sym,
        value: Sym,
    }
    let mut processed: FxHashMap<Sym, Sym> = FxHashMap::default();
    let mut stack: Vec<Frame> = Vec::new();
    // Entering an id (9.6's recursive helper, made iterative so deep structures cannot
    // overflow the stack).
    let enter = |ctx: &RhsContext,
                 processed: &mut FxHashMap<Sym, Sym>,
                 stack: &mut Vec<Frame>,
                 id: Sym,
                 copy: Sym| {
        if processed.contains_key(&id) {
            return;
        }
        processed.insert(id, copy);
        let (slots, input) = wmes_of(ctx, id);
        let wmes = slots
            .into_iter()
            .chain(input)
            .filter(|w| !prohibited.contains(&w.attr))
            .collect();
        stack.push(Frame {
            parent: copy,
            wmes,
            i: 0,
            stage: 0,
            attr: copy,
            value: copy,
        });
    };
    enter(ctx, &mut processed, &mut stack, base, root);
    while let Some(top) = stack.len().checked_sub(1) {
        let f = &stack[top];
        if f.i >= f.wmes.len() {
            stack.pop();
            continue;
        }
        let w = f.wmes[f.i];
        match f.stage {
            0 | 1 => {
                let orig = if f.stage == 0 { w.attr } else { w.value };
                let mut copy = orig;
                let mut walk = false;
                if let Some(letter) = ctx.symbols.id_data(orig).map(|d| d.letter) {
                    copy = match processed.get(&orig) {
                        Some(&c) => c,
                        None => {
                            walk = true;
                            ctx.symbols.new_id(letter as char, 0)
                        }
                    };
                }
                let f = &mut stack[top];
                if f.stage == 0 {
                    f.attr = copy;
                } else {
                    f.value = copy;
                }
                f.stage += 1;
                if walk {
                    enter(ctx, &mut processed, &mut stack, orig, copy);
                }
            }
            _ => {
                let f = &mut stack[top];
                let triple = (f.parent, f.attr, f.value);
                f.i += 1;
                f.stage = 0;
                ctx.deep_copy_wmes.push(triple);
            }
        }
    }
    Ok(root)
}
