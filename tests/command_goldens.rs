//! The command goldens (`scripts/command_goldens.py`): each command of
//! tests/commands/NAME.cmds, given in order to one fresh agent, prints what the official
//! kernel printed for it (tests/golden/commands/NAME.txt), or fails with its message.
//! The differences allowed: the product's name in the title of the `soar` summary, the
//! identity counts of `chunk stats`, and rusoar's warnings (9.6 prints none there).

use rusoar::Agent;
use std::path::Path;

/// `(command, expected)` pairs of a golden: the text, or `!!! MESSAGE` for a failure.
fn golden_blocks(text: &str) -> Vec<(String, String)> {
    let mut blocks: Vec<(String, String)> = Vec::new();
    for line in text.split_inclusive('\n') {
        match line.strip_prefix(">>> ") {
            Some(cmd) => blocks.push((cmd.trim_end_matches('\n').to_string(), String::new())),
            None => match blocks.last_mut() {
                Some((_, body)) => body.push_str(line),
                None => panic!("golden text before its first command: {line:?}"),
            },
        }
    }
    blocks
}

/// The text with the `soar` summary's title (`Soar 9.6.50 Summary`, `rusoar 0.1.0
/// Summary`) made neutral.
fn neutral_title(text: &str) -> String {
    text.split_inclusive('\n')
        .map(|line| {
            let t = line.trim_end_matches('\n');
            if t.starts_with("- ") && t.ends_with(" -") && t.contains(" Summary ") {
                "- Summary -\n"
            } else {
                line
            }
        })
        .collect()
}

/// The text with the counts of `chunk stats`' identity rows made neutral: 9.6 counts
/// identities by its own bookkeeping (identity sets made and merged as each substate rule
/// fires, in an order that differs from run to run on some agents), which rusoar's
/// learner does not keep; docs/conformance.md lists the difference.
fn neutral_identity_counts(text: &str) -> String {
    const ROWS: [&str; 4] = [
        "Identities created ",
        "Identity propagations ",
        "Identity propagations blocked ",
        "Identities joined ",
    ];
    text.split_inclusive('\n')
        .map(|line| match ROWS.iter().find(|r| line.starts_with(*r)) {
            Some(r) => format!("{r}#\n"),
            None => line.to_string(),
        })
        .collect()
}

/// The text without rusoar's own warnings (about what 9.6 silently accepts, where 9.6
/// prints nothing): each `warning: ...` line, the source excerpt under it and the blank
/// line that ends it.
fn without_warnings(text: &str) -> String {
    let mut out = String::new();
    let mut lines = text.split_inclusive('\n').peekable();
    while let Some(line) = lines.next() {
        if !line.starts_with("warning: ") {
            out.push_str(line);
            continue;
        }
        while let Some(next) = lines.peek() {
            let t = next.trim_start_matches(|c: char| c.is_ascii_digit() || c == ' ');
            if t.starts_with('│') || t.starts_with('┌') {
                lines.next();
            } else {
                break;
            }
        }
        if lines.peek().is_some_and(|l| l.trim().is_empty()) {
            lines.next();
        }
    }
    out
}

/// What rusoar prints for one command, in the golden's form: the repository's absolute
/// path, which differs from machine to machine, is written `<repo>` as in the goldens.
fn rusoar_text(agent: &mut Agent, command: &str) -> String {
    let root = format!("{}/", env!("CARGO_MANIFEST_DIR"));
    let text = match agent.execute(command) {
        Ok(text) => {
            let mut text = without_warnings(&text);
            if !text.is_empty() && !text.ends_with('\n') {
                text.push('\n');
            }
            text
        }
        Err(e) => format!("!!! {}\n", e.message().lines().next().unwrap_or_default()),
    };
    text.replace(&root, "<repo>/")
}

#[test]
fn commands_print_what_the_official_kernel_prints() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files: Vec<_> = std::fs::read_dir(dir.join("tests/commands"))
        .expect("tests/commands")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "cmds"))
        .collect();
    files.sort();
    assert!(!files.is_empty(), "no command files");
    let mut failures = Vec::new();
    for file in &files {
        let name = file.file_stem().unwrap().to_string_lossy().to_string();
        let golden = dir
            .join("tests/golden/commands")
            .join(format!("{name}.txt"));
        let golden = std::fs::read_to_string(&golden)
            .unwrap_or_else(|e| panic!("{}: {e}", golden.display()));
        let mut agent = Agent::new(&name);
        for (command, expected) in golden_blocks(&golden) {
            let got = rusoar_text(&mut agent, &command);
            let neutral = |t: &str| neutral_identity_counts(&neutral_title(t));
            if neutral(&got) != neutral(&expected) {
                failures.push(format!(
                    "{name}: `{command}`\n--- official\n{expected}--- rusoar\n{got}"
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
