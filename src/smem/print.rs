//! How 9.6 prints semantic memory: `print @N` and `smem --query`'s answers as
//! `(@N ^attr value ... [+activation])`, attributes in text order with the values of one
//! attribute together, and `smem --export`'s clauses (checked on soar-sml 9.6.5).

use super::store::{DbResult, Store, Val};
use crate::printer::constants::{c_general, rereadable};
use std::collections::BTreeMap;

/// A value as `print @` shows it. 9.6 writes numbers through one stream that keeps its
/// settings: sixteen significant digits, and once something has written a number in fixed
/// notation there (an activation does), sixteen decimals from then on (`fixed`).
fn value_text(v: &Val, fixed: bool) -> String {
    match v {
        Val::Str(s) => rereadable(s),
        Val::Int(i) => i.to_string(),
        Val::Float(f) if fixed => format!("{f:.16}"),
        Val::Float(f) => c_general(*f, 16),
        Val::Lti(l) => format!("@{l}"),
    }
}

/// A value as `smem --export` writes it: a float with six decimals.
fn export_text(v: &Val) -> String {
    match v {
        Val::Float(f) => format!("{f:.6}"),
        v => value_text(v, true),
    }
}

/// `trace --smem`'s line for an augmentation as it is stored: `=>SMEM: (@N ^attr value)`,
/// or `=>SMEM: (N ^attr M)` when the value is an LTI (9.6 writes both numbers bare then).
pub fn trace_addition(lti: i64, attr: &Val, value: &Val) -> String {
    match value {
        Val::Lti(l) => format!("=>SMEM: ({lti} ^{} {l})\n", export_text(attr)),
        v => format!("=>SMEM: (@{lti} ^{} {})\n", export_text(attr), export_text(v)),
    }
}

/// `trace --smem`'s line as a store replaces an LTI's augmentations.
pub fn trace_replacement(lti: i64) -> String {
    format!("<=SMEM: (@{lti} ^* *)\n")
}

/// The augmentations grouped by attribute text, attributes in order, values as stored.
fn grouped(
    store: &Store,
    lti: i64,
    text: impl Fn(&Val) -> String,
) -> DbResult<BTreeMap<String, Vec<String>>> {
    let mut by_attr: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for (a, v) in store.augs(lti)? {
        by_attr.entry(text(&a)).or_default().push(text(&v));
    }
    Ok(by_attr)
}

/// `(@N ^attr value ... [+A.AAA])` and a newline; with spreading on, an LTI that has
/// spread shows its activation with the spread. The activation is written in fixed
/// notation, which the stream keeps (`fixed` is set).
pub fn lti(store: &Store, lti: i64, spreading: bool, fixed: &mut bool) -> DbResult<String> {
    let mut s = format!("(@{lti}");
    let floats_fixed = *fixed;
    for (a, values) in grouped(store, lti, |v| value_text(v, floats_fixed))? {
        s.push_str(&format!(" ^{a}"));
        for v in values {
            s.push(' ');
            s.push_str(&v);
        }
    }
    let spread = if spreading { store.spread_row(lti)? } else { None };
    let act = match spread {
        Some((_, _, value)) => value,
        None => store.shown_activation(lti)?,
    };
    s.push_str(&format!(" [{act:+.3}])\n"));
    *fixed = true;
    Ok(s)
}

/// One clause of `smem --export` (none for an LTI without augmentations).
pub fn export_clause(store: &Store, lti: i64) -> DbResult<String> {
    let by_attr = grouped(store, lti, export_text)?;
    if by_attr.is_empty() {
        return Ok(String::new());
    }
    let mut s = format!("(@{lti}");
    for (a, values) in by_attr {
        for v in values {
            s.push_str(&format!(" ^{a} {v}"));
        }
    }
    s.push_str(")\n");
    Ok(s)
}
