//! The error corpus: every file in `tests/data/errors/` holds one mistake (a comment at its top
//! says which). Each is sourced as a user would (`source FILE` from that directory); the
//! snapshot shows the rendered output and the failure. Every error must carry a location
//! (file, line, column) and the interpreter must report failure. Where Soar 9.6 has a
//! message for the mistake, the message is Soar's text (checked against soar-sml 9.6).

use rusoar::commands::{Event, Interpreter};
use rusoar::source::{Diagnostic, Severity};
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

/// The corpus must keep covering many kinds of mistakes: at least 40 files.
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

fn assert_located(interp: &Interpreter, d: &Diagnostic, file: &str) {
    let span = d
        .span
        .unwrap_or_else(|| panic!("{file}: error without a location: {}", d.message));
    let text = interp.sources.text(span.file);
    assert!(
        span.start <= span.end && span.end <= text.len(),
        "{file}: span {span:?} outside its text ({} bytes) for: {}",
        text.len(),
        d.message
    );
    let (line, col) = interp.sources.line_col(span.file, span.start);
    assert!(line >= 1 && col >= 1, "{file}: no line/column");
    assert!(
        !interp.sources.name(span.file).is_empty(),
        "{file}: no file name"
    );
}

fn run_file(path: &Path) -> String {
    let root = env!("CARGO_MANIFEST_DIR");
    let name = path.file_name().unwrap().to_string_lossy().into_owned();
    let mut interp = Interpreter::new();
    interp.set_cwd(path.parent().unwrap().to_path_buf());
    let result = interp.run_text("<test>", &format!("source {name}"));
    let events = interp.take_events();

    // Every error printed on the way, and the failure itself, is located.
    for e in &events {
        if let Event::Diag(d) = e {
            if d.severity == Severity::Error {
                assert_located(&interp, d, &name);
            }
        }
    }
    let failure = match &result {
        Ok(()) => panic!("{name}: sourcing it succeeded, but it holds a mistake"),
        Err(d) => d,
    };
    assert_eq!(failure.severity, Severity::Error, "{name}");
    assert_located(&interp, failure, &name);
    // The failure points into the erroneous file (or a file it sources), not at the
    // `source` command of the test itself.
    let in_file = interp.sources.name(failure.span.unwrap().file);
    assert!(
        in_file.contains("/tests/data/errors/"),
        "{name}: the error points at {in_file}"
    );

    let mut out = String::from("== output ==\n");
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
    out.push_str("\n== failure ==\n");
    out.push_str(&interp.sources.render(failure));
    out.replace(root, "[ROOT]")
}
