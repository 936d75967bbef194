//! `epmem --print` and `epmem --viz`: one episode as text, as 9.6 writes them. Each node
//! is `<idN>` (the root `<id0>`); `--print` lists each node's attributes in text order, an
//! attribute's identifier values before its constants; `--viz` is Graphviz text.

use super::store::{Store, ACCEPTABLE};
use std::collections::BTreeMap;

impl Store {
    fn attr_text(&self, a: i64) -> String {
        if a == ACCEPTABLE {
            "operator*".into()
        } else {
            self.text(a)
        }
    }

    /// `epmem --print N` (empty for an episode that is not stored).
    pub fn print_episode(&self, t: i64) -> String {
        if !self.valid(t) {
            return String::new();
        }
        let mut ep: BTreeMap<i64, BTreeMap<String, Vec<String>>> = BTreeMap::new();
        for e in self.edges_at(t) {
            let (p, a, c) = self.edges.triple(e);
            ep.entry(p)
                .or_default()
                .entry(self.attr_text(a))
                .or_default()
                .push(format!("<id{c}>"));
        }
        for c in self.consts.at(t) {
            let (p, a, v) = self.consts.triple(c);
            ep.entry(p)
                .or_default()
                .entry(self.attr_text(a))
                .or_default()
                .push(self.text(v));
        }
        let mut s = String::new();
        for (node, attrs) in ep {
            s.push_str(&format!("(<id{node}>"));
            for (attr, values) in attrs {
                s.push_str(&format!(" ^{attr}"));
                for v in values {
                    s.push(' ');
                    s.push_str(&v);
                }
            }
            s.push_str(")\n");
        }
        s
    }

    /// `epmem --viz N`.
    pub fn visualize_episode(&self, t: i64) -> String {
        if !self.valid(t) {
            return String::new();
        }
        let mut s = String::from("digraph epmem {\n");
        let mut nodes: BTreeMap<i64, ()> = BTreeMap::from([(0, ())]);
        let mut edges = String::new();
        for e in self.edges_at(t) {
            let (p, a, c) = self.edges.triple(e);
            nodes.insert(c, ());
            edges.push_str(&format!(
                "ID_{p} -> ID_{c} [ label=\"{}\" ];\n",
                self.attr_text(a)
            ));
        }
        s.push_str("node [ shape = circle ];\n");
        for n in nodes.keys() {
            s.push_str(&format!("ID_{n} "));
        }
        s.push_str(";\n");
        s.push_str("node [ shape = doublecircle ];\n\n");
        s.push_str(&edges);
        let (mut consts, mut links) = (String::new(), String::new());
        for c in self.consts.at(t) {
            let (p, a, v) = self.consts.triple(c);
            links.push_str(&format!(
                "ID_{p} -> C_{c} [ label=\"{}\" ];\n",
                self.attr_text(a)
            ));
            consts.push_str(&format!("C_{c} [ label=\"{}\" ];\n", self.text(v)));
        }
        s.push_str("node [ shape = plaintext ];\n");
        s.push_str(&consts);
        s.push_str(&links);
        s.push_str("\n}\n");
        s
    }
}
