//! `epmem --print` and `epmem --viz`: one episode as text, as 9.6 writes them. Each node
//! is `<idN>` (the root `<id0>`), or `@N` where it stood for a long-term identifier; `--print` lists each node's attributes in text order, an
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
        // A node that stood for a long-term identifier is named by it (`@N`).
        let mut names: BTreeMap<i64, String> = BTreeMap::new();
        for e in self.edges_at(t) {
            let (p, a, c) = self.edges.triple(e);
            let name = match self.edges.lti_at(e, t) {
                0 => format!("<id{c}>"),
                lti => {
                    names.insert(c, format!("@{lti}"));
                    format!("@{lti}")
                }
            };
            ep.entry(p)
                .or_default()
                .entry(self.attr_text(a))
                .or_default()
                .push(name);
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
            match names.get(&node) {
                Some(name) => s.push_str(&format!("({name}")),
                None => s.push_str(&format!("(<id{node}>")),
            }
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
        // Each node with the long-term identifier it stood for (0: none).
        let mut nodes: BTreeMap<i64, i64> = BTreeMap::from([(0, 0)]);
        let mut edges = String::new();
        for e in self.edges_at(t) {
            let (p, a, c) = self.edges.triple(e);
            nodes.insert(c, self.edges.lti_at(e, t));
            edges.push_str(&format!(
                "ID_{p} -> ID_{c} [ label=\"{}\" ];\n",
                self.attr_text(a)
            ));
        }
        s.push_str("node [ shape = circle ];\n");
        for (n, _) in nodes.iter().filter(|(_, &lti)| lti == 0) {
            s.push_str(&format!("ID_{n} "));
        }
        s.push_str(";\n");
        // Long-term identifiers are double circles named by their number.
        s.push_str("node [ shape = doublecircle ];\n");
        for (n, lti) in nodes.iter().filter(|(_, &lti)| lti != 0) {
            s.push_str(&format!("ID_{n} [ label=\"@{lti}\" ];\n"));
        }
        s.push('\n');
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
