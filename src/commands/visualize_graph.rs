//! The Graphviz text of `visualize wm` and `visualize smem` (Soar manual, ch. 9,
//! `visualize`): memory as objects, each an identifier (or a long-term identifier) with its
//! augmentations. As records, an object is a table of its constant-valued augmentations
//! and its identifier-valued ones are edges; as nodes, every identifier is a circle and
//! every constant a box of its own. The shapes, attributes and text follow soar-sml 9.6.5;
//! objects come breadth first from the identifier asked for, each object's augmentations as
//! `print` orders them (9.6 follows its own memory's order there).

use crate::agent::AgentCore;
use crate::smem::store::{DbResult, Store, Val};
use crate::symbols::Sym;
use crate::trace::sorted_wmes;
use crate::wm::{Wme, WmeId};
use std::collections::{HashSet, VecDeque};

/// How an object is drawn (`visualize memory-format`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MemoryFormat {
    /// One circle per identifier, one box per constant.
    Node,
    /// One table per object.
    Record,
}

/// The value of one augmentation.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// An identifier (or long-term identifier): an edge to its object.
    Object(String),
    /// A state, drawn without an edge when states are kept apart (`separate-states`): a
    /// row of the record, and nothing in the node form, as 9.6 draws it.
    State(String),
    /// A constant: as `print` writes it (`|two words|`, `2.500000`) and as plain text.
    Constant { shown: String, plain: String },
}

/// One object: its name and its augmentations in order.
#[derive(Debug, Clone, PartialEq)]
pub struct Object {
    pub name: String,
    pub augs: Vec<(String, Value)>,
}

/// What `visualize wm` draws and from where.
pub struct WmView<'a> {
    /// The identifier to start from, or all of working memory.
    pub root: Option<Sym>,
    /// Levels of objects below and including the root (at least 1).
    pub depth: usize,
    /// Whether a WME is drawn.
    pub shown: &'a dyn Fn(WmeId, &Wme) -> bool,
    /// Draw no edge to a state.
    pub separate_states: bool,
}

/// The objects of working memory that `view` asks for.
pub fn wm_objects(agent: &AgentCore, view: &WmView) -> Vec<Object> {
    let Some(root) = view.root else {
        // Every object with something to draw, in the order of its oldest WME.
        let mut wmes: Vec<_> = agent
            .wm
            .all()
            .into_iter()
            .filter_map(|w| agent.wm.get(w).copied())
            .collect();
        wmes.sort_by_key(|w| w.timetag);
        let mut seen = HashSet::new();
        return wmes
            .iter()
            .filter(|w| seen.insert(w.id))
            .map(|w| wm_object(agent, view, w.id).0)
            .filter(|o| !o.augs.is_empty())
            .collect();
    };
    let mut out = Vec::new();
    let mut seen = HashSet::from([root]);
    let mut frontier = VecDeque::from([(root, 1usize)]);
    while let Some((id, level)) = frontier.pop_front() {
        let (object, children) = wm_object(agent, view, id);
        if level < view.depth {
            for child in children {
                if seen.insert(child) {
                    frontier.push_back((child, level + 1));
                }
            }
        }
        // An object with nothing to draw is left out.
        if !object.augs.is_empty() {
            out.push(object);
        }
    }
    out
}

/// One identifier's object, and the identifiers its WMEs lead to, drawn or not (9.6's
/// walk goes on through a state's links and the memories' links).
fn wm_object(agent: &AgentCore, view: &WmView, id: Sym) -> (Object, Vec<Sym>) {
    let symbols = &agent.symbols;
    let mut children = Vec::new();
    let mut augs = Vec::new();
    let handles: std::collections::HashMap<u64, WmeId> = agent
        .wm
        .of_id(id)
        .filter_map(|x| agent.wm.get(x).map(|w| (w.timetag, x)))
        .collect();
    for w in sorted_wmes(agent, id) {
        if symbols.is_id(w.value) {
            children.push(w.value);
        }
        let shown = handles
            .get(&w.timetag)
            .is_some_and(|&x| (view.shown)(x, &w));
        if !shown {
            continue;
        }
        // A state kept apart has no edge.
        let value = if symbols.is_goal(w.value) && view.separate_states {
            Value::State(symbols.text(w.value))
        } else if symbols.is_id(w.value) {
            Value::Object(symbols.text(w.value))
        } else {
            Value::Constant {
                shown: symbols.text(w.value),
                plain: symbols.plain(w.value),
            }
        };
        augs.push((symbols.plain(w.attr), value));
    }
    let object = Object {
        name: symbols.text(id),
        augs,
    };
    (object, children)
}

/// The objects of semantic memory: every long-term identifier, or those within `depth`
/// levels of `root`.
pub fn smem_objects(store: &Store, root: Option<i64>, depth: usize) -> DbResult<Vec<Object>> {
    let object = |lti: i64| -> DbResult<(Object, Vec<i64>)> {
        let mut children = Vec::new();
        let mut augs = Vec::new();
        for (attr, value) in store.augs(lti)? {
            let value = match value {
                Val::Lti(l) => {
                    children.push(l);
                    Value::Object(format!("@{l}"))
                }
                Val::Str(x) => Value::Constant {
                    shown: crate::printer::rereadable(&x),
                    plain: x,
                },
                Val::Int(i) => Value::Constant {
                    shown: i.to_string(),
                    plain: i.to_string(),
                },
                Val::Float(f) => Value::Constant {
                    shown: crate::printer::float_text(f),
                    plain: crate::printer::float_text(f),
                },
            };
            let attr = match attr {
                Val::Str(x) => x,
                Val::Int(i) => i.to_string(),
                Val::Float(f) => crate::printer::float_text(f),
                Val::Lti(l) => format!("@{l}"),
            };
            augs.push((attr, value));
        }
        let name = format!("@{lti}");
        Ok((Object { name, augs }, children))
    };
    let Some(root) = root else {
        return store
            .ltis()?
            .into_iter()
            .map(|l| object(l).map(|o| o.0))
            .collect();
    };
    let mut out = Vec::new();
    let mut seen = HashSet::from([root]);
    let mut frontier = VecDeque::from([(root, 1usize)]);
    while let Some((lti, level)) = frontier.pop_front() {
        let (o, children) = object(lti)?;
        if level < depth {
            for child in children {
                if seen.insert(child) {
                    frontier.push_back((child, level + 1));
                }
            }
        }
        out.push(o);
    }
    Ok(out)
}

/// The Graphviz text of `objects`, with `line_style` as the edges' `splines`.
pub fn graph_text(objects: &[Object], format: MemoryFormat, line_style: &str) -> String {
    let mut s = format!(
        "digraph g {{\n   node [shape = \"box\" fontsize = \"16\"];\n   edge [];\n   graph [ rankdir = \"TD\" splines = \"{}\"];\n",
        quoted(line_style)
    );
    match format {
        MemoryFormat::Record => {
            for o in objects {
                record(&mut s, o);
            }
            for o in objects {
                for (attr, v) in &o.augs {
                    if let Value::Object(to) = v {
                        edge(&mut s, &o.name, to, attr);
                    }
                }
            }
        }
        MemoryFormat::Node => {
            // Each constant is a box of its own, named by its text and a running count.
            let mut boxes = 0usize;
            for o in objects {
                node(&mut s, &o.name, "circle", &o.name);
                for (attr, v) in &o.augs {
                    match v {
                        Value::Object(to) => edge(&mut s, &o.name, to, attr),
                        Value::State(_) => continue,
                        Value::Constant { plain, .. } => {
                            boxes += 1;
                            let name = format!("{plain}{boxes}");
                            node(&mut s, &name, "box", plain);
                            edge(&mut s, &o.name, &name, attr);
                        }
                    }
                    // In this form a blank line follows each edge.
                    s.push('\n');
                }
            }
        }
    }
    s.push_str("}\n");
    s
}

/// An object as a table: its name, then a row per constant (and state) value.
fn record(s: &mut String, o: &Object) {
    s.push_str(&format!(
        "   \"{}\" [\n      colorscheme=\"X11\"\n      penwidth = \"0\"\n      label = <<TABLE BORDER=\"0\" CELLBORDER=\"1\" CELLSPACING=\"0\" CELLPADDING=\"4\">\n                <TR> <TD COLSPAN=\"3\">{}</TD> </TR>\n",
        quoted(&o.name),
        html(&o.name)
    ));
    for (attr, v) in &o.augs {
        let text = match v {
            Value::Object(_) => continue,
            Value::State(name) => name,
            Value::Constant { shown, .. } => shown,
        };
        s.push_str(&format!(
            "                <TR> <TD  > {}</TD><TD  > {}</TD> </TR>\n",
            html(attr),
            html(text)
        ));
    }
    s.push_str("              </TABLE>\n              >\n   ];\n\n\n");
}

fn node(s: &mut String, name: &str, shape: &str, label: &str) {
    s.push_str(&format!(
        "   \"{}\" [\n      colorscheme=\"X11\"\n      shape = \"{shape}\"\n      label = \"{}\"\n   ];\n\n\n",
        quoted(name),
        quoted(label)
    ));
}

fn edge(s: &mut String, from: &str, to: &str, attr: &str) {
    s.push_str(&format!(
        "\"{}\":s -> \"{}\":n [label = \"{}\"]\n",
        quoted(from),
        quoted(to),
        quoted(attr)
    ));
}

/// Text inside a Graphviz quoted string.
fn quoted(text: &str) -> String {
    text.replace('\\', "\\\\").replace('"', "\\\"")
}

/// Text inside a Graphviz HTML label. (9.6 writes it as it is, so a `<` or `&` in a
/// constant makes a file `dot` cannot read; rusoar escapes them.)
fn html(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn constant(text: &str) -> Value {
        Value::Constant {
            shown: text.into(),
            plain: text.into(),
        }
    }

    #[test]
    fn a_record_holds_constants_and_edges_follow_every_record() {
        let objects = vec![
            Object {
                name: "S1".into(),
                augs: vec![
                    ("thing".into(), Value::Object("T1".into())),
                    ("count".into(), constant("3")),
                ],
            },
            Object {
                name: "T1".into(),
                augs: vec![("link".into(), Value::State("S1".into()))],
            },
        ];
        let text = graph_text(&objects, MemoryFormat::Record, "polyline");
        assert!(text.contains("<TR> <TD  > count</TD><TD  > 3</TD> </TR>"));
        assert!(text.contains("<TR> <TD  > link</TD><TD  > S1</TD> </TR>"));
        let t1 = text.find("\"T1\" [").unwrap();
        let edge = text.find("\"S1\":s -> \"T1\":n [label = \"thing\"]").unwrap();
        assert!(edge > t1, "edges come after the records");
        assert!(!text.contains("-> \"S1\""), "no edge to a separate state");
    }

    #[test]
    fn nodes_number_their_constants_and_skip_separate_states() {
        let objects = vec![Object {
            name: "S1".into(),
            augs: vec![
                ("a".into(), constant("x")),
                ("b".into(), constant("x")),
                ("up".into(), Value::State("S2".into())),
            ],
        }];
        let text = graph_text(&objects, MemoryFormat::Node, "ortho");
        assert!(text.contains("splines = \"ortho\""));
        assert!(text.contains("\"S1\":s -> \"x1\":n [label = \"a\"]\n\n"));
        assert!(text.contains("\"S1\":s -> \"x2\":n [label = \"b\"]\n\n"));
        assert!(!text.contains("S2"));
    }

    #[test]
    fn markup_in_a_constant_is_escaped() {
        let objects = vec![Object {
            name: "S1".into(),
            augs: vec![("a".into(), constant("<b>&\"q\""))],
        }];
        let record = graph_text(&objects, MemoryFormat::Record, "polyline");
        assert!(record.contains("&lt;b&gt;&amp;\"q\""));
        let node = graph_text(&objects, MemoryFormat::Node, "polyline");
        assert!(node.contains("label = \"<b>&\\\"q\\\"\""));
    }
}
