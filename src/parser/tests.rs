//! The fast path against the lalrpop parser: on every `sp` body of the repository, on
//! generated rules, on hand-picked tricky syntax and on random near-valid text, both must
//! accept the same bodies, build equal trees (spans included) and report equal warnings;
//! and `parse_production` must return exactly what the lalrpop parser alone returns.

use super::{descent, parse_production, parse_with_lalrpop};
use crate::commands::tokenizer::{Tokenizer, WordKind};
use crate::lexer::Lexer;
use std::path::{Path, PathBuf};

/// Compares the two parsers on one body; returns whether the grammar accepts it.
fn check(body: &str, offset: usize, what: &str) -> bool {
    let mut fast_warnings = Vec::new();
    let fast = descent::parse(Lexer::new(body, offset, 3, &mut fast_warnings), 3);
    let mut lr_warnings = Vec::new();
    let lr = parse_with_lalrpop(body, 3, offset, &mut lr_warnings);
    match (&fast, &lr) {
        (Some(f), Ok(l)) => {
            assert_eq!(f, l, "{what}: different trees for\n{body}");
            assert_eq!(fast_warnings, lr_warnings, "{what}: warnings for\n{body}");
        }
        (None, Err(_)) => {}
        (Some(_), Err(e)) => panic!("{what}: fast path accepts, grammar rejects ({e:?}):\n{body}"),
        (None, Ok(_)) => panic!("{what}: fast path rejects what the grammar accepts:\n{body}"),
    }
    // The entry point: the same result and warnings, whichever parser answered.
    let mut warnings = Vec::new();
    let both = parse_production(body, 3, offset, &mut warnings);
    assert_eq!(both, lr, "{what}: parse_production differs for\n{body}");
    assert_eq!(
        warnings, lr_warnings,
        "{what}: parse_production warnings for\n{body}"
    );
    lr.is_ok()
}

/// The `sp` bodies of a source file, with their file offsets.
fn sp_bodies(text: &str) -> Vec<(String, usize)> {
    Tokenizer::new(text, 0)
        .map_while(Result::ok)
        .filter(|c| c.words.len() == 2 && c.words[0].text == "sp")
        .map(|c| {
            let w = &c.words[1];
            let offset = match w.kind {
                WordKind::Braced => w.content_offset(),
                _ => w.span.start,
            };
            (w.text.clone(), offset)
        })
        .collect()
}

fn soar_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            soar_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "soar") {
            out.push(p);
        }
    }
}

#[test]
fn every_repository_rule_parses_the_same() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    for dir in ["tests", "rules", "stdlib", "examples", "docs", "benches"] {
        soar_files(&root.join(dir), &mut files);
    }
    assert!(files.len() > 100, "found only {} .soar files", files.len());
    let (mut bodies, mut accepted) = (0, 0);
    for f in &files {
        let text = String::from_utf8_lossy(&std::fs::read(f).unwrap()).into_owned();
        for (body, offset) in sp_bodies(&text) {
            bodies += 1;
            accepted += usize::from(check(&body, offset, &f.display().to_string()));
        }
    }
    // Most are good rules; the error corpus supplies the rest.
    assert!(
        accepted > 400 && bodies > accepted,
        "{accepted} of {bodies}"
    );
}

#[test]
fn generated_benchmark_rules_parse_the_same() {
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/scripts/gen_rules.py");
    for kind in ["nomatch", "counter"] {
        let out = std::process::Command::new("python3")
            .args([script, kind, "300"])
            .output()
            .expect("python3 runs scripts/gen_rules.py");
        let text = String::from_utf8(out.stdout).unwrap();
        let bodies = sp_bodies(&text);
        assert_eq!(bodies.len(), 300);
        for (body, offset) in bodies {
            assert!(check(&body, offset, kind));
        }
    }
}

/// Rules the grammar accepts, one tricky construct each.
const GOOD: &[&str] = &[
    "a (state <s> ^a.b.c <x>) --> (<s> ^d e)",
    "a (state <s> ^Start (^X <x> ^Y <y>) + ^b (-^c d)) -->",
    "a (<s> ^a << a |b c| 3 -3 1.5e3 .5 5. state impasse >> ^b << >>) -->",
    "a (<s> ^a { <x> > 3 } ^b { <> <y> <=> 1 <= 2 >= 3 < 4 = 5 state }) -->",
    "a (<s> ^a <b> + -^c -^d.e <f> +) -->",
    "a (state <s>) -{ (<s> ^a <b>) (<b> ^c d) } -(<s> ^e) --> (<s> ^f g)",
    "a { (state <s> ^a <b>) { (<b> ^c d) } } --> (<s> ^f g)",
    "a :o-support :i-support (state <s>) --> (<s> ^x 1)",
    "a \"doc \\\"string\\\"\" :chunk (impasse <i>) -->",
    "|quoted name| (state) --> (write (crlf))",
    "state (impasse) -->",
    "impasse (<s> ^a b) -->",
    "a ({ <s> <> <t> } ^a b) (= <t> ^b c) (<> <u>) (<< a b >> ^c d) (S1 ^x y) (|q| ^x y) (3) -->",
    "a (state <s>) --> (<s> ^a (+ 1 2) ^b (- 3 -2) ^c (|/| 6 3) ^d (exec f |a| <b>))",
    "a (state <s>) --> (exec f |a| <b>) (write (crlf) |x| 1.5) (interrupt) (+ 1)",
    "a (state <s> ^o <o> <p>) --> (<s> ^operator <o> + = <p> + = , <p> > <o> < ~ ! - ^x <p> =)",
    "a (state <s> ^o <o>) --> (<s> ^operator <o> + = 3 ^operator <o> = 2.5 > < = ^b.c.d e)",
    "a (state <s>) --> (<s> ^a <b> +) (S1 ^a b) (<s> ^(concat a b) c ^a.(f) <x>)",
    "a (state <s>) --> (<s>) (<s> ^a state ^impasse impasse)",
    "a (state <s> ^a 99999999999999999999 ^b <c ^d x>) --> (<s> ^a 99999999999999999999)",
    "a (state <s> ^a b;^c d) # comment\n --> ;(<s> ^e f)",
    "a (state <s> ^a.1.5 2.) --> (<s> ^b.1 .5)",
];

/// Rules the grammar rejects; `parse_production` must give the lalrpop diagnostic.
const BAD: &[&str] = &[
    "",
    "   ",
    "p1 (state <s>) -->",
    "<v> (state <s>) -->",
    "3 (state <s>) -->",
    "1.5 (state <s>) -->",
    "a -->",
    "a (state <s>)",
    "a (state state) -->",
    "a (state <s> ^) -->",
    "a (state <s> ^a.) -->",
    "a (state <s> ^a ()) -->",
    "a (state <s> ^a { }) -->",
    "a (state <s> ^a << <x> >>) -->",
    "a (state <s> ^a b -) -->",
    "a (state <s> ^a +) -->",
    "a (state <s> ^a b) { } -->",
    "a (state <s> ^a b) -{ } -->",
    "a (state <s>) - -->",
    "a \"doc\" \"doc\" (state <s>) -->",
    "a :o-support \"doc\" (state <s>) -->",
    "a (state <s>) --> (<s> ^a)",
    "a (state <s>) --> (<s> ^a.b)",
    "a (state <s>) --> (<s> ^a b & c)",
    "a (state <s>) --> (<s> ^a b @)",
    "a (state <s>) --> (<s> ^a b <= c)",
    "a (state <s>) --> (<s> a b)",
    "a (state <s>) --> (state ^a b)",
    "a (state <s>) --> (3 4)",
    "a (state <s>) --> (<s> ^a (<x>))",
    "a (state <s>) --> (<s> ^a b",
    "a (state <s>) --> <s>",
    "a (state <s>) --> (<s> ^a b) )",
    "a (state <s> ^a |unterminated) -->",
    "a \"unterminated (state <s>) -->",
    "a (state <s> ^a b) --> (<s> ^c |open)",
    "a (state <s> ^a b \u{2}) --> (<s> ^c d) |",
    "a (state <s> ^a 99999999999999999999) --> (<s> ^c d) |",
    "a (state <s> ^a b) --> (<s> ^c d) -->",
    "a (state <s> ^a b) (",
];

#[test]
fn tricky_syntax_parses_the_same() {
    for good in GOOD {
        assert!(check(good, 0, "good"), "rejected: {good}");
        assert!(check(good, 1000, "good, offset"));
    }
    for bad in BAD {
        assert!(!check(bad, 7, "bad"), "accepted: {bad}");
    }
    let deep = format!(
        "a (state <s>) --> (<s> ^a {}1{})",
        "(+ ".repeat(300),
        ")".repeat(300)
    );
    assert!(!check(&deep, 0, "deep"));
    let deep = format!(
        "a (state <s>) --> (<s> ^a {}1{})",
        "(+ ".repeat(150),
        ")".repeat(150)
    );
    assert!(check(&deep, 0, "deep"));
}

/// A tiny deterministic generator (xorshift), to build near-valid rules.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    fn chance(&mut self, percent: usize) -> bool {
        self.below(100) < percent
    }
    fn pick<'a>(&mut self, xs: &[&'a str]) -> &'a str {
        xs[self.below(xs.len())]
    }
}

const CONSTS: &[&str] = &[
    "a",
    "b-c",
    "S1",
    "p2",
    "3",
    "-3",
    "+4",
    "1.5",
    "1.5e3",
    ".5",
    "5.",
    "|x y|",
    "||",
    "state",
    "impasse",
    "nil",
    "<bad",
    "bad>",
    "99999999999999999999",
];
const VARS: &[&str] = &["<s>", "<x>", "<o>", "<a-b>"];
const RELS: &[&str] = &["=", "<>", "<", "<=", ">", ">=", "<=>"];
const PREFS: &[&str] = &["+", "-", "!", "~", ">", "<", "=", ","];
const FUNCS: &[&str] = &[
    "write",
    "crlf",
    "+",
    "-",
    "|/|",
    "exec",
    "interrupt",
    "concat",
];
/// Anything a mutation may insert.
const ANY: &[&str] = &[
    "(",
    ")",
    "{",
    "}",
    "^",
    "-",
    "+",
    ".",
    "-->",
    "<<",
    ">>",
    "=",
    "<",
    ">",
    "<>",
    "!",
    "~",
    ",",
    "&",
    "@",
    "state",
    "impasse",
    "<s>",
    "a",
    "p1",
    "3",
    "1.5",
    "|q|",
    "\"doc\"",
    ":o-support",
    "|open",
    "\u{2}",
];

fn gen_test(r: &mut Rng, out: &mut Vec<String>, simple: bool) {
    match r.below(if simple { 4 } else { 5 }) {
        0 => out.push(r.pick(VARS).into()),
        1 => {
            out.push(r.pick(RELS).into());
            let atoms = if r.chance(50) { VARS } else { CONSTS };
            out.push(r.pick(atoms).into());
        }
        2 => {
            out.push("<<".into());
            for _ in 0..r.below(4) {
                out.push(r.pick(CONSTS).into());
            }
            out.push(">>".into());
        }
        3 => out.push(r.pick(CONSTS).into()),
        _ => {
            out.push("{".into());
            for _ in 0..=r.below(3) {
                gen_test(r, out, true);
            }
            out.push("}".into());
        }
    }
}

fn gen_attr_tests(r: &mut Rng, out: &mut Vec<String>, depth: usize) {
    if r.chance(20) {
        out.push("-".into());
    }
    out.push("^".into());
    gen_test(r, out, false);
    for _ in 0..r.below(3) {
        out.push(".".into());
        gen_test(r, out, false);
    }
    for _ in 0..r.below(3) {
        if depth < 3 && r.chance(15) {
            out.push("(".into());
            for _ in 0..=r.below(2) {
                gen_attr_tests(r, out, depth + 1);
            }
            out.push(")".into());
        } else {
            gen_test(r, out, false);
        }
        if r.chance(20) {
            out.push("+".into());
        }
    }
}

fn gen_condition(r: &mut Rng, out: &mut Vec<String>, depth: usize) {
    match r.below(10) {
        0 | 1 if depth < 3 => {
            out.push(if r.chance(50) { "-{" } else { "{" }.into());
            for _ in 0..=r.below(3) {
                gen_condition(r, out, depth + 1);
            }
            out.push("}".into());
        }
        n => {
            if n == 2 {
                out.push("-".into());
            }
            out.push("(".into());
            match r.below(4) {
                0 => out.push("state".into()),
                1 => out.push("impasse".into()),
                _ => {}
            }
            if r.chance(80) {
                gen_test(r, out, false);
            }
            for _ in 0..r.below(4) {
                gen_attr_tests(r, out, 0);
            }
            out.push(")".into());
        }
    }
}

fn gen_rhs_value(r: &mut Rng, out: &mut Vec<String>, depth: usize) {
    match r.below(6) {
        0 if depth < 3 => gen_call(r, out, depth + 1),
        1 | 2 => out.push(r.pick(VARS).into()),
        _ => out.push(r.pick(CONSTS).into()),
    }
}

fn gen_call(r: &mut Rng, out: &mut Vec<String>, depth: usize) {
    out.push("(".into());
    out.push(r.pick(FUNCS).into());
    for _ in 0..r.below(4) {
        gen_rhs_value(r, out, depth);
    }
    out.push(")".into());
}

fn gen_action(r: &mut Rng, out: &mut Vec<String>) {
    if r.chance(25) {
        return gen_call(r, out, 0);
    }
    out.push("(".into());
    let id = if r.chance(80) { r.pick(VARS) } else { "S1" };
    out.push(id.into());
    for _ in 0..r.below(4) {
        out.push("^".into());
        gen_rhs_value(r, out, 0);
        for _ in 0..r.below(3) {
            out.push(".".into());
            gen_rhs_value(r, out, 0);
        }
        gen_rhs_value(r, out, 0);
        for _ in 0..r.below(5) {
            if r.chance(40) {
                gen_rhs_value(r, out, 0);
            } else {
                out.push(r.pick(PREFS).into());
            }
        }
    }
    out.push(")".into());
}

fn gen_production(r: &mut Rng) -> Vec<String> {
    let names = ["a*b", "|q n|", "state", "impasse", "a", "b", "c", "d", "p1"];
    let mut out = vec![r.pick(&names).to_string()];
    if r.chance(20) {
        out.push("\"a \\\" doc\"".into());
    }
    for _ in 0..r.below(3) {
        out.push(r.pick(&[":o-support", ":i-support", ":chunk"]).into());
    }
    for _ in 0..=r.below(4) {
        gen_condition(r, &mut out, 0);
    }
    out.push("-->".into());
    for _ in 0..r.below(4) {
        gen_action(r, &mut out);
    }
    out
}

/// Deletes, repeats, replaces or swaps a few lexemes.
fn mutate(r: &mut Rng, lexemes: &mut Vec<String>) {
    for _ in 0..=r.below(3) {
        if lexemes.is_empty() {
            return;
        }
        let i = r.below(lexemes.len());
        match r.below(4) {
            0 => {
                lexemes.remove(i);
            }
            1 => lexemes.insert(i, lexemes[i].clone()),
            2 => lexemes[i] = r.pick(ANY).into(),
            _ if i + 1 < lexemes.len() => lexemes.swap(i, i + 1),
            _ => lexemes.push(r.pick(ANY).into()),
        }
    }
}

#[test]
fn random_rules_parse_the_same() {
    let mut r = Rng(0x9e37_79b9_7f4a_7c15);
    let (mut accepted, mut total) = (0, 0);
    for _ in 0..20_000 {
        let mut lexemes = gen_production(&mut r);
        if r.chance(50) {
            mutate(&mut r, &mut lexemes);
        }
        // Mostly spaced; sometimes glued, which lexes differently (`^a.b`, `1.5`).
        let mut text = String::new();
        for l in &lexemes {
            if !text.is_empty() && !r.chance(2) {
                text.push(if r.chance(90) { ' ' } else { '\n' });
            }
            text.push_str(l);
        }
        total += 1;
        accepted += usize::from(check(&text, 5, "random"));
    }
    // Both sides of the language are exercised.
    assert!(
        accepted > total / 5 && accepted < total * 4 / 5,
        "{accepted} of {total}"
    );
    eprintln!("{accepted} of {total} accepted");
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig { cases: 300, ..Default::default() })]

    /// The parser on any text, as a production body: an error, never a panic.
    #[test]
    fn random_bytes_as_a_production_do_not_panic(
        bytes in proptest::collection::vec(proptest::prelude::any::<u8>(), 0..2000)
    ) {
        let text = String::from_utf8_lossy(&bytes);
        let mut warnings = Vec::new();
        let _ = parse_production(&text, 0, 0, &mut warnings);
    }
}
