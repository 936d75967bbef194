//! The parse corpus: every file in `tests/data/parse/` runs through an [`Interpreter`]; the
//! snapshot shows the input, what the interpreter printed (diagnostics rendered with their
//! carets), whether it failed, the syntax tree of every `sp` as parsed, and every loaded
//! rule as `print` shows it. Each file is named after the feature it covers, with a prefix
//! for its group (`1a` the command tokenizer, `1b` the production lexer, `1c` the `sp`
//! command, `1d` conditions, `1e` actions: `1d_dot_paths.soar`). The expected behaviour was
//! checked against the official kernel (soar-sml 9.6); see the comment at the top of each
//! file.

use crate::ast::{
    Action, Atom, AttrMake, AttrValueTests, CondForOneId, Condition, Constant, FuncCall, Head,
    Pref, RhsValue, Test, ValueTest,
};
use crate::commands::tokenizer::{Tokenizer, WordKind};
use crate::commands::{Event, Interpreter};
use crate::parser::parse_production;
use crate::printer::production_text;
use std::fmt::Write as _;
use std::path::Path;

#[test]
fn parse_corpus() {
    insta::glob!("../../tests/data/parse", "*.soar", |path| {
        let dump = run_file(path);
        let mut settings = insta::Settings::clone_current();
        settings.set_prepend_module_to_snapshot(false);
        settings.set_snapshot_path("../../tests/snapshots");
        settings.set_description("tests/data/parse: input, output, syntax trees and printed rules");
        settings.bind(|| insta::assert_snapshot!(dump));
    });
}

/// Runs one corpus file and renders everything worth reviewing.
fn run_file(path: &Path) -> String {
    let root = env!("CARGO_MANIFEST_DIR");
    let name = path.file_name().unwrap().to_string_lossy().into_owned();
    let text = String::from_utf8_lossy(&std::fs::read(path).unwrap()).into_owned();
    let mut interp = Interpreter::new();
    interp.set_cwd(path.parent().unwrap().to_path_buf());
    let result = interp.run_text(&name, &text);

    let mut out = String::new();
    out.push_str("== input ==\n");
    out.push_str(&text);
    if !text.ends_with('\n') {
        out.push('\n');
    }
    out.push_str("\n== output ==\n");
    let events = interp.take_events();
    for e in &events {
        let r = interp.render(e);
        if matches!(e, Event::Diag(_)) && !out.ends_with('\n') {
            out.push('\n');
        }
        out.push_str(&r);
    }
    if !out.ends_with('\n') {
        out.push('\n');
    }
    out.push_str("\n== result ==\n");
    match &result {
        Ok(()) => out.push_str("ok\n"),
        Err(d) => {
            out.push_str("failed:\n");
            out.push_str(&interp.sources.render(d));
        }
    }

    out.push_str("\n== sp bodies as parsed ==\n");
    out.push_str(
        "(strings quoted, numbers bare; `_` a missing id; binary preferences in brackets)\n",
    );
    for cmd in Tokenizer::new(&text, 0) {
        let Ok(cmd) = cmd else { break };
        if cmd.words.len() != 2 || cmd.words[0].text != "sp" {
            continue;
        }
        let body = &cmd.words[1];
        let offset = match body.kind {
            WordKind::Braced => body.content_offset(),
            _ => body.span.start,
        };
        let line = text[..cmd.span.start].matches('\n').count() + 1;
        let mut warnings = Vec::new();
        match parse_production(&body.text, 0, offset, &mut warnings) {
            Ok(p) => {
                let _ = writeln!(out, "-- line {line}: {}", p.name);
                out.push_str(&dump_production(&p));
            }
            Err(d) => {
                let _ = writeln!(out, "-- line {line}: syntax error: {}", d.message);
            }
        }
    }

    out.push_str("\n== loaded rules (print) ==\n");
    let loaded: Vec<String> = interp.agent.productions().map(production_text).collect();
    if loaded.is_empty() {
        out.push_str("(none)\n");
    }
    for p in loaded {
        out.push_str(&p);
        out.push('\n');
    }
    out.replace(root, "[ROOT]")
}

// ----------------------------------------------------------------------- syntax tree dump
//
// One line per condition and action, in Soar's own notation but showing the tree as
// written: dot paths stay paths, structured values stay nested, preferences stay attached
// to their values. Constants show their type: "string", 7 (integer), 7.0 (float).

fn dump_production(p: &crate::ast::Production) -> String {
    let mut s = format!("name {:?}", p.name);
    if let Some(doc) = &p.doc {
        let _ = write!(s, "  doc {doc:?}");
    }
    if !p.flags.is_empty() {
        let flags: Vec<&str> = p.flags.iter().map(|(f, _)| f.as_str()).collect();
        let _ = write!(s, "  flags {}", flags.join(" "));
    }
    s.push('\n');
    for c in &p.conditions {
        dump_condition(&mut s, c, 1);
    }
    s.push_str("  -->\n");
    for a in &p.actions {
        s.push_str("  ");
        s.push_str(&action_text(a));
        s.push('\n');
    }
    s
}

fn dump_condition(s: &mut String, c: &Condition, depth: usize) {
    let pad = "  ".repeat(depth);
    match c {
        Condition::Positive(c) => {
            let _ = writeln!(s, "{pad}{}", cond_text(c));
        }
        Condition::Negative(c) => {
            let _ = writeln!(s, "{pad}-{}", cond_text(c));
        }
        Condition::Ncc(cs, _) => {
            let _ = writeln!(s, "{pad}-{{");
            for c in cs {
                dump_condition(s, c, depth + 1);
            }
            let _ = writeln!(s, "{pad}}}");
        }
    }
}

fn cond_text(c: &CondForOneId) -> String {
    let mut s = String::from("(");
    match c.head {
        Head::State => s.push_str("state "),
        Head::Impasse => s.push_str("impasse "),
        Head::None => {}
    }
    let mut parts = Vec::new();
    match &c.id_test {
        Some(t) => parts.push(test_text(t)),
        None => parts.push("_".to_string()),
    }
    parts.extend(c.attr_value_tests.iter().map(avt_text));
    s.push_str(&parts.join(" "));
    s.push(')');
    s
}

fn avt_text(a: &AttrValueTests) -> String {
    let path: Vec<String> = a.path.iter().map(test_text).collect();
    let mut s = format!("{}^{}", if a.negated { "-" } else { "" }, path.join("."));
    for v in &a.values {
        s.push(' ');
        match v {
            ValueTest::Test { test, acceptable } => {
                s.push_str(&test_text(test));
                if *acceptable {
                    s.push_str(" +");
                }
            }
            ValueTest::Structured {
                tests, acceptable, ..
            } => {
                let inner: Vec<String> = tests.iter().map(avt_text).collect();
                let _ = write!(s, "({})", inner.join(" "));
                if *acceptable {
                    s.push_str(" +");
                }
            }
        }
    }
    s
}

fn test_text(t: &Test) -> String {
    match t {
        Test::Equal(a, _) => atom_text(a),
        Test::Relational(r, a, _) => format!("{} {}", r.text(), atom_text(a)),
        Test::Disjunction(cs, _) => {
            let mut s = String::from("<< ");
            for c in cs {
                s.push_str(&constant_text(c));
                s.push(' ');
            }
            s.push_str(">>");
            s
        }
        Test::Conjunction(ts, _) => {
            let items: Vec<String> = ts.iter().map(test_text).collect();
            format!("{{ {} }}", items.join(" "))
        }
    }
}

fn atom_text(a: &Atom) -> String {
    match a {
        Atom::Var(v) => v.clone(),
        Atom::Const(c) => constant_text(c),
    }
}

fn constant_text(c: &Constant) -> String {
    match c {
        Constant::Str(s) => format!("{s:?}"),
        Constant::Int(i) => i.to_string(),
        Constant::Float(f) => format!("{f:?}"),
    }
}

fn action_text(a: &Action) -> String {
    match a {
        Action::Make { id, attrs, .. } => {
            let mut s = format!("({}", rhs_text(id));
            for am in attrs {
                s.push(' ');
                s.push_str(&attr_make_text(am));
            }
            s.push(')');
            s
        }
        Action::Call(f) => format!("call {}", call_text(f)),
    }
}

fn attr_make_text(am: &AttrMake) -> String {
    let path: Vec<String> = am.path.iter().map(rhs_text).collect();
    let mut s = format!("^{}", path.join("."));
    for vm in &am.values {
        s.push(' ');
        s.push_str(&rhs_text(&vm.value));
        for p in &vm.prefs {
            s.push(' ');
            s.push_str(&pref_text(p));
        }
    }
    s
}

fn pref_text(p: &Pref) -> String {
    match p {
        Pref::Acceptable => "+".into(),
        Pref::Reject => "-".into(),
        Pref::Require => "!".into(),
        Pref::Prohibit => "~".into(),
        Pref::Best => ">".into(),
        Pref::Worst => "<".into(),
        Pref::Indifferent => "=".into(),
        Pref::Better(v) => format!("[> {}]", rhs_text(v)),
        Pref::Worse(v) => format!("[< {}]", rhs_text(v)),
        Pref::BinaryIndifferent(v) => format!("[= {}]", rhs_text(v)),
        Pref::Numeric(v) => format!("[numeric = {}]", rhs_text(v)),
    }
}

fn rhs_text(v: &RhsValue) -> String {
    match v {
        RhsValue::Var(v, _) => v.clone(),
        RhsValue::Const(c, _) => constant_text(c),
        RhsValue::Call(f) => call_text(f),
    }
}

fn call_text(f: &FuncCall) -> String {
    let mut s = format!("({}", f.name);
    for a in &f.args {
        s.push(' ');
        s.push_str(&rhs_text(a));
    }
    s.push(')');
    s
}
