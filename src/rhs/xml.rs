//! `from-st-xml`: working-memory structure from an XML string (9.6 `xmltowme_*`).
//!
//! `(from-st-xml |<root><a>hello</a><b type="integer">42</b></root>|)` makes a new
//! identifier lettered after the root tag and one WME per child element, `^tag value`:
//! a child with children and no `type` becomes a nested identifier; otherwise the value is
//! the `value` attribute or the text, read as an int (`type="integer"`, `stoi`, 0 when it
//! does not parse), a float (`type="double"`, `stof`: single precision, 0 when it does not
//! parse) or a string. A child with `link="X"` instead points at the value of the child
//! with `link-id="X"` (links are added last). Text that is not XML fails silently.

use super::text::{c_strtod, c_strtol};
use super::RhsContext;
use crate::symbols::Sym;

#[derive(Debug, Default)]
struct Element {
    tag: String,
    attrs: Vec<(String, String)>,
    children: Vec<Element>,
    text: Option<String>,
}

impl Element {
    fn attr(&self, name: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(k, _)| k == name)
            .map(|(_, v)| v.as_str())
    }
}

pub(super) fn from_st_xml(args: &[Sym], ctx: &mut RhsContext) -> Result<Sym, String> {
    let Some(&a) = args.first() else {
        return Err(String::new());
    };
    let text = ctx.value_text(a);
    let Some(root) = parse(&text) else {
        return Err(String::new());
    };
    let mut links: Vec<(Sym, Sym, String)> = Vec::new();
    let mut link_map: Vec<(String, Sym)> = Vec::new();
    let id = build(ctx, &root, &mut links, &mut link_map);
    for (from, attr, to) in links {
        if let Some((_, v)) = link_map.iter().find(|(k, _)| *k == to) {
            ctx.module_wmes.push((from, attr, *v));
        }
    }
    Ok(id)
}

fn letter(tag: &str) -> char {
    tag.chars().next().unwrap_or('I')
}

fn build(
    ctx: &mut RhsContext,
    e: &Element,
    links: &mut Vec<(Sym, Sym, String)>,
    link_map: &mut Vec<(String, Sym)>,
) -> Sym {
    // Iterative over the element tree, so deep documents cannot overflow the stack:
    // each frame is (element, its new id, index of the next child, pending child value).
    let root = ctx.symbols.new_id(letter(&e.tag), 0);
    let mut stack: Vec<(&Element, Sym, usize)> = vec![(e, root, 0)];
    // The value of a nested child is known when its frame finishes.
    let mut finished: Option<Sym> = None;
    while let Some(top) = stack.len().checked_sub(1) {
        let (el, id, i) = stack[top];
        if let Some(v) = finished.take() {
            // The child at i - 1 was nested; add its WME now (after its own WMEs).
            let child = &el.children[i - 1];
            add(ctx, id, child, v, link_map);
        }
        if i >= el.children.len() {
            stack.pop();
            finished = stack.last().map(|_| id);
            continue;
        }
        stack[top].2 += 1;
        let child = &el.children[i];
        let attr = ctx.symbols.str(&child.tag);
        if let Some(to) = child.attr("link") {
            links.push((id, attr, to.to_string()));
            continue;
        }
        if child.attr("type").unwrap_or("").is_empty() && !child.children.is_empty() {
            let nested = ctx.symbols.new_id(letter(&child.tag), 0);
            stack.push((child, nested, 0));
            continue;
        }
        let v = leaf_value(ctx, child);
        add(ctx, id, child, v, link_map);
    }
    root
}

fn add(
    ctx: &mut RhsContext,
    id: Sym,
    child: &Element,
    value: Sym,
    link_map: &mut Vec<(String, Sym)>,
) {
    let attr = ctx.symbols.str(&child.tag);
    ctx.module_wmes.push((id, attr, value));
    if let Some(l) = child.attr("link-id") {
        link_map.push((l.to_string(), value));
    }
}

fn leaf_value(ctx: &mut RhsContext, e: &Element) -> Sym {
    let value = e
        .attr("value")
        .map(str::to_string)
        .or_else(|| e.text.clone());
    let Some(value) = value else {
        return ctx.symbols.str("");
    };
    match e.attr("type").unwrap_or("") {
        "double" => {
            // std::stof: a float (single precision), 0 when it does not parse or is out of
            // the float range.
            let trimmed = value.trim_start();
            let has_digits = {
                let t = trimmed.trim_start_matches(['+', '-']);
                let t = t.strip_prefix('.').unwrap_or(t);
                t.starts_with(|c: char| c.is_ascii_digit())
                    || t.get(..3).is_some_and(|p| {
                        p.eq_ignore_ascii_case("inf") || p.eq_ignore_ascii_case("nan")
                    })
            };
            let (d, erange) = c_strtod(&value);
            let f = d as f32;
            let bad = !has_digits
                || erange
                || (d.is_finite() && f.is_infinite())
                || (d != 0.0 && f.is_finite() && f.abs() < f32::MIN_POSITIVE);
            ctx.symbols.float(if bad { 0.0 } else { f64::from(f) })
        }
        "integer" => {
            // std::stoi: strtol, then out of the int range or no digits is 0.
            let digits = value
                .trim_start()
                .trim_start_matches(['+', '-'])
                .starts_with(|c: char| c.is_ascii_digit());
            let v = match c_strtol(&value) {
                Ok(v) if digits && i32::try_from(v).is_ok() => v,
                _ => 0,
            };
            ctx.symbols.int(v)
        }
        _ => ctx.symbols.str(&value),
    }
}

/// A small XML reader: prolog, comments, `<!...>` declarations, CDATA, elements with
/// quoted attributes, self-closing tags and the five named and numeric entities. `None`
/// when the text is not one well-formed element.
fn parse(s: &str) -> Option<Element> {
    let mut p = Parser {
        s: s.as_bytes(),
        i: 0,
    };
    p.misc()?;
    let root = p.element()?;
    p.misc()?;
    (p.i == p.s.len()).then_some(root)
}

struct Parser<'a> {
    s: &'a [u8],
    i: usize,
}

impl Parser<'_> {
    fn starts(&self, t: &str) -> bool {
        self.s[self.i..].starts_with(t.as_bytes())
    }

    fn skip_ws(&mut self) {
        while self.i < self.s.len() && self.s[self.i].is_ascii_whitespace() {
            self.i += 1;
        }
    }

    fn skip_past(&mut self, t: &str) -> Option<()> {
        let k = self.s[self.i..]
            .windows(t.len())
            .position(|w| w == t.as_bytes())?;
        self.i += k + t.len();
        Some(())
    }

    /// White space, comments, processing instructions and declarations.
    fn misc(&mut self) -> Option<()> {
        loop {
            self.skip_ws();
            if self.starts("<?") {
                self.skip_past("?>")?;
            } else if self.starts("<!--") {
                self.skip_past("-->")?;
            } else if self.starts("<!") && !self.starts("<![CDATA[") {
                self.skip_past(">")?;
            } else {
                return Some(());
            }
        }
    }

    fn name(&mut self) -> Option<String> {
        let start = self.i;
        while self.i < self.s.len() {
            let c = self.s[self.i];
            if c.is_ascii_whitespace() || b"/>=<\"'".contains(&c) {
                break;
            }
            self.i += 1;
        }
        (self.i > start).then(|| String::from_utf8_lossy(&self.s[start..self.i]).into_owned())
    }

    fn element(&mut self) -> Option<Element> {
        // Iterative: a stack of open elements.
        let mut open: Vec<Element> = Vec::new();
        loop {
            if !self.starts("<") {
                return None;
            }
            self.i += 1;
            let mut e = Element {
                tag: self.name()?,
                ..Element::default()
            };
            let self_closing = loop {
                self.skip_ws();
                if self.starts("/>") {
                    self.i += 2;
                    break true;
                }
                if self.starts(">") {
                    self.i += 1;
                    break false;
                }
                let k = self.name()?;
                self.skip_ws();
                if !self.starts("=") {
                    return None;
                }
                self.i += 1;
                self.skip_ws();
                let q = *self.s.get(self.i)?;
                if q != b'"' && q != b'\'' {
                    return None;
                }
                self.i += 1;
                let start = self.i;
                while self.i < self.s.len() && self.s[self.i] != q {
                    self.i += 1;
                }
                if self.i >= self.s.len() {
                    return None;
                }
                let raw = std::str::from_utf8(self.s.get(start..self.i)?).ok()?;
                self.i += 1;
                e.attrs.push((k, unescape(raw)?));
            };
            if !self_closing {
                open.push(e);
            } else {
                match open.last_mut() {
                    Some(parent) => parent.children.push(e),
                    None => return Some(e),
                }
            }
            // Content until the next child element or the end tag of the open element.
            loop {
                let cur = open.last_mut()?;
                let start = self.i;
                while self.i < self.s.len() && self.s[self.i] != b'<' {
                    self.i += 1;
                }
                if self.i > start {
                    let raw = std::str::from_utf8(&self.s[start..self.i]).ok()?;
                    cur.text
                        .get_or_insert_with(String::new)
                        .push_str(&unescape(raw)?);
                }
                if self.i >= self.s.len() {
                    return None;
                }
                if self.starts("<![CDATA[") {
                    self.i += 9;
                    let k = self.s[self.i..].windows(3).position(|w| w == b"]]>")?;
                    let raw = std::str::from_utf8(&self.s[self.i..self.i + k]).ok()?;
                    cur.text.get_or_insert_with(String::new).push_str(raw);
                    self.i += k + 3;
                } else if self.starts("<!--") {
                    self.skip_past("-->")?;
                } else if self.starts("<?") {
                    self.skip_past("?>")?;
                } else if self.starts("</") {
                    self.i += 2;
                    let name = self.name()?;
                    self.skip_ws();
                    if !self.starts(">") {
                        return None;
                    }
                    self.i += 1;
                    let done = open.pop()?;
                    if done.tag != name {
                        return None;
                    }
                    match open.last_mut() {
                        Some(parent) => parent.children.push(done),
                        None => return Some(done),
                    }
                } else {
                    break; // a child element
                }
            }
        }
    }
}

fn unescape(s: &str) -> Option<String> {
    let mut out = String::with_capacity(s.len());
    let mut rest = s;
    while let Some(k) = rest.find('&') {
        out.push_str(&rest[..k]);
        rest = &rest[k + 1..];
        let end = rest.find(';')?;
        let ent = &rest[..end];
        let c = match ent {
            "lt" => '<',
            "gt" => '>',
            "amp" => '&',
            "quot" => '"',
            "apos" => '\'',
            _ => {
                let n = if let Some(h) = ent.strip_prefix("#x").or_else(|| ent.strip_prefix("#X")) {
                    u32::from_str_radix(h, 16).ok()?
                } else {
                    ent.strip_prefix('#')?.parse().ok()?
                };
                char::from_u32(n)?
            }
        };
        out.push(c);
        rest = &rest[end + 1..];
    }
    out.push_str(rest);
    Some(out)
}
