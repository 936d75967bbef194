//! No input, however broken, may panic or hang: truncated files, random bytes, unbalanced
//! braces and pipes, 10 MB lines, deep nesting. Each must finish quickly and, when it fails,
//! fail with a located diagnostic.

use proptest::prelude::*;
use rusoar::{Agent, Printed};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Runs `text` as commands from `dir`; checks that every error it reports is located.
/// Returns whether it succeeded.
fn run(text: &str, dir: &Path) -> bool {
    let mut interp = Agent::default();
    interp.set_working_directory(dir.to_path_buf());
    let result = interp.source_text("input.soar", text);
    let events = interp.take_printed();
    for e in &events {
        if let Printed::Diagnostic(d) = e {
            if !d.is_warning() {
                assert!(d.location().is_some(), "unlocated error: {}", d.message());
            }
        }
        // Rendering must not panic either (odd spans, odd characters).
        let _ = e.to_string();
    }
    match result {
        Ok(()) => true,
        Err(d) => {
            assert!(d.location().is_some(), "unlocated failure: {}", d.message());
            let _ = d.render();
            false
        }
    }
}

/// Runs `f` and checks it took less than `limit` (generous: a debug build or a busy machine
/// must pass too; a pathological slowdown is orders of magnitude slower).
fn timed<T>(what: &str, limit: Duration, f: impl FnOnce() -> T) -> T {
    let t = Instant::now();
    let r = f();
    let took = t.elapsed();
    assert!(took < limit, "{what} took {took:?}");
    r
}

fn soar_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(Result::ok)
        .map(|e| e.path())
        .collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            soar_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "soar") {
            out.push(p);
        }
    }
}

/// Every byte prefix of two corpus files and of a thesis rule file.
#[test]
fn every_prefix_of_some_files() {
    for rel in [
        "tests/data/parse/1d_dot_paths.soar",
        "tests/data/parse/1e_preferences.soar",
        "rules/CopyWall.soar",
    ] {
        let path = root().join(rel);
        let bytes = std::fs::read(&path).unwrap();
        let dir = path.parent().unwrap();
        timed(rel, Duration::from_secs(20), || {
            for n in 0..=bytes.len() {
                run(&String::from_utf8_lossy(&bytes[..n]), dir);
            }
        });
    }
}

/// A sample of prefixes (every line end, and 50 cuts in between) of every rule file and
/// every corpus file.
#[test]
fn sampled_prefixes_of_every_file() {
    let mut files = Vec::new();
    soar_files(&root().join("rules"), &mut files);
    soar_files(&root().join("tests/data/parse"), &mut files);
    soar_files(&root().join("tests/data/errors"), &mut files);
    assert!(files.len() > 100);
    timed("sampled prefixes", Duration::from_secs(20), || {
        for path in &files {
            let bytes = std::fs::read(path).unwrap();
            let dir = path.parent().unwrap();
            let mut cuts: Vec<usize> = bytes
                .iter()
                .enumerate()
                .filter(|(_, b)| **b == b'\n')
                .map(|(i, _)| i)
                .collect();
            cuts.extend((0..50).map(|k| k * bytes.len() / 50));
            for n in cuts {
                run(&String::from_utf8_lossy(&bytes[..n]), dir);
            }
        }
    });
}

#[test]
fn unbalanced_braces_pipes_and_quotes() {
    let dir = root();
    for text in [
        "{",
        "}",
        "sp {",
        "sp }",
        "sp {a (state <s> ^b c) --> (<s> ^d e)}}",
        "sp {{{{{{{{",
        "sp {a}}}}}}}}",
        "sp {a |",
        "sp {a |}",
        "sp {a ||| (state <s> ^b c) --> (<s> ^d e)}",
        "echo |",
        "echo \"",
        "echo \"\\",
        "echo \\",
        "sp \"a (state <s> ^b |c) --> (<s> ^d e)\"",
        "sp \"a (state <s> ^b \\\"c) --> (<s> ^d e)\"",
        "sp {a (state <s> ^b c) -{ (<s> ^d e) --> (<s> ^f g)}",
        "sp {a (state <s> ^b { <x> ) --> }",
        "sp {a (state <s> ^b << c ) --> }",
        "sp {a (state <s> ^b c) --> (<s> ^d (+ 1 (* 2 }",
        "sp {a \"doc (state <s> ^b c) --> (<s> ^d e)}",
        "sp {a # }\n}",
        "\\\n\\\n\\",
        ";;;;;;",
        "#",
        "\0",
        "sp {\0}",
    ] {
        timed(text, Duration::from_secs(2), || run(text, &dir));
    }
}

const TEN_MB: usize = 10 * 1024 * 1024;

#[test]
fn ten_megabyte_production_of_open_parens_without_closing_brace() {
    let text = format!("sp {{x {}", "(".repeat(TEN_MB));
    let ok = timed("10 MB of ( without }", Duration::from_secs(5), || {
        run(&text, &root())
    });
    assert!(!ok);
}

#[test]
fn ten_megabyte_production_of_open_parens() {
    let text = format!("sp {{x {}}}", "(".repeat(TEN_MB));
    let ok = timed("10 MB of ( in braces", Duration::from_secs(5), || {
        run(&text, &root())
    });
    assert!(!ok);
}

#[test]
fn ten_megabyte_echo_line() {
    let text = format!(
        "echo {}\necho {}",
        "a".repeat(TEN_MB),
        "ab ".repeat(TEN_MB / 30)
    );
    let ok = timed("10 MB echo line", Duration::from_secs(5), || {
        run(&text, &root())
    });
    assert!(ok);
}

#[test]
fn ten_megabyte_comment_and_pipe_lines() {
    let comment = format!("# {}\necho done", "x".repeat(TEN_MB));
    assert!(timed("10 MB comment", Duration::from_secs(5), || run(
        &comment,
        &root()
    )));
    let pipe = format!("sp {{x (state <s> ^a |{}) --> }}", "y".repeat(TEN_MB));
    assert!(!timed("10 MB open pipe", Duration::from_secs(5), || run(
        &pipe,
        &root()
    )));
}

/// A long but valid rule: 50,000 values on one attribute, 20,000 actions.
#[test]
fn very_long_valid_production() {
    let values: String = (0..50_000).map(|i| format!(" v{i}x")).collect();
    let actions: String = (0..20_000).map(|i| format!(" (<s> ^a{i} b)")).collect();
    let text = format!("sp {{long (state <s> ^superstate nil ^v{values}) -->{actions}}}");
    let ok = timed("long production", Duration::from_secs(10), || {
        run(&text, &root())
    });
    assert!(ok);
}

/// Deep nesting of structured values, function calls, negations and condition groups gets
/// a diagnostic, not a stack overflow.
#[test]
fn deep_nesting_is_an_error_not_a_crash() {
    let n = 100_000;
    for (what, text) in [
        (
            "structured values",
            format!(
                "sp {{deep (state <s> ^superstate nil ^a {}b{}) --> (<s> ^c d)}}",
                "(^a ".repeat(n),
                ")".repeat(n)
            ),
        ),
        (
            "function calls",
            format!(
                "sp {{deep (state <s> ^superstate nil) --> (<s> ^a {}1{})}}",
                "(+ 1 ".repeat(n),
                ")".repeat(n)
            ),
        ),
        (
            "negations",
            format!(
                "sp {{deep (state <s> ^superstate nil) {}(<s> ^a b){} --> (<s> ^c d)}}",
                "-{ ".repeat(n),
                " }".repeat(n)
            ),
        ),
        (
            "condition groups",
            format!(
                "sp {{deep (state <s> ^superstate nil) {}(<s> ^a b){} --> (<s> ^c d)}}",
                "{ ".repeat(n),
                " }".repeat(n)
            ),
        ),
    ] {
        let ok = timed(what, Duration::from_secs(5), || run(&text, &root()));
        assert!(!ok, "{what}: a production nested {n} deep loaded");
    }
    // Moderate nesting still loads.
    let text = format!(
        "sp {{nested (state <s> ^superstate nil ^a {}b{}) --> (<s> ^c (+ 1 (+ 2 (+ 3 4))))}}",
        "(^a ".repeat(50),
        ")".repeat(50)
    );
    assert!(run(&text, &root()));
}

/// `source` of a file that sources itself stops at Soar's depth limit with a diagnostic.
#[test]
fn recursive_source_stops() {
    let dir = std::env::temp_dir().join(format!("rusoar-robustness-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("loop.soar"), "source loop.soar\n").unwrap();
    let ok = timed("recursive source", Duration::from_secs(5), || {
        run("source loop.soar", &dir)
    });
    std::fs::remove_dir_all(&dir).ok();
    assert!(!ok);
}

/// Soar-ish words: the tokenizer and the parser meet odd but plausible token sequences.
fn soarish() -> impl Strategy<Value = String> {
    let words = prop::sample::select(vec![
        "sp",
        "{",
        "}",
        "(",
        ")",
        "^",
        "<s>",
        "<x>",
        "state",
        "impasse",
        "-->",
        "-",
        "+",
        "=",
        "<",
        ">",
        "<>",
        "<<",
        ">>",
        "!",
        "~",
        ",",
        ".",
        "|",
        "|a b|",
        "\"",
        "\"doc\"",
        "#",
        "\n",
        ";",
        "\\",
        "1",
        "1.5",
        "1e3",
        ".5",
        "p1",
        "name",
        ":o-support",
        "write",
        "crlf",
        "(+",
        "echo",
        "source",
        "pushd",
        "popd",
        "learn",
        "-off",
        "excise",
        "print",
        "\0",
        "é",
    ]);
    prop::collection::vec(words, 0..120).prop_map(|w| w.join(" "))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn random_bytes_do_not_panic(bytes in prop::collection::vec(any::<u8>(), 0..2000)) {
        let text = String::from_utf8_lossy(&bytes);
        run(&text, &root());
    }

    #[test]
    fn random_soarish_text_does_not_panic(text in soarish()) {
        run(&text, &root());
    }

    #[test]
    fn random_production_bodies_do_not_panic(body in soarish()) {
        let text = format!("sp {{rule (state <s> ^superstate nil) {body}}}");
        run(&text, &root());
        let text = format!("sp {{rule {body} --> (<s> ^a b)}}");
        run(&text, &root());
    }
}
