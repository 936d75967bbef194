//! The error corpus: every file in `tests/data/errors/` holds one mistake (a comment at its top
//! says which). Each is sourced as a user would (`source FILE` from that directory); the
//! snapshot shows the rendered output and the failure. Every error must carry a location
//! (file, line, column) and the interpreter must report failure. Where Soar 9.6 has a
//! message for the mistake, the message is Soar's text (checked against soar-sml 9.6).

use rusoar::{Agent, Error, Printed};
use std::path::Path;

#[test]
fn error_corpus() {
    insta::glob!("data/errors/*.soar", |path| {
        let dump = run_file(path);
        let mut settings = insta::Settings::clone_current();
        settings.set_prepend_module_to_snapshot(false);
        settings.set_description("tests/data/errors: one mistake per file, sourced");
        settings.bind(|| insta::assert_snapshot!(dump));
    });
}

/// The corpus is big enough to be worth counting: at least 45 kinds of mistake.
#[test]
fn error_corpus_has_enough_cases() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/errors");
    let n = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(Result::ok)
        .filter(|e| e.path().extension().is_some_and(|x| x == "soar"))
        .count();
    assert!(n >= 45, "only {n} error cases");
}

fn assert_located(e: &Error, file: &str) {
    let at = e
        .location()
        .unwrap_or_else(|| panic!("{file}: error without a location: {}", e.message()));
    assert!(at.line >= 1 && at.column >= 1, "{file}: no line/column");
    assert!(!at.name.is_empty(), "{file}: no file name");
}

fn run_file(path: &Path) -> String {
    let root = env!("CARGO_MANIFEST_DIR");
    let name = path.file_name().unwrap().to_string_lossy().into_owned();
    let mut agent = Agent::default();
    agent.set_working_directory(path.parent().unwrap().to_path_buf());
    let result = agent.source_text("<test>", &format!("source {name}"));
    let printed = agent.take_printed();

    // Every error printed on the way, and the failure itself, is located.
    for p in &printed {
        if let Printed::Diagnostic(e) = p {
            if !e.is_warning() {
                assert_located(e, &name);
            }
        }
    }
    let failure = match &result {
        Ok(()) => panic!("{name}: sourcing it succeeded, but it holds a mistake"),
        Err(e) => e,
    };
    assert!(!failure.is_warning(), "{name}");
    assert_located(failure, &name);
    // The failure points into the erroneous file (or a file it sources), not at the
    // `source` command of the test itself.
    let in_file = &failure.location().unwrap().name;
    assert!(
        in_file.contains("/tests/data/errors/"),
        "{name}: the error points at {in_file}"
    );

    let mut out = String::from("== output ==\n");
    for p in &printed {
        if matches!(p, Printed::Diagnostic(_)) && !out.ends_with('\n') {
            out.push('\n');
        }
        out.push_str(&p.to_string());
    }
    if !out.ends_with('\n') {
        out.push('\n');
    }
    out.push_str("\n== failure ==\n");
    out.push_str(&failure.render());
    out.replace(root, "[ROOT]")
}
