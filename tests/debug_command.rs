//! `debug`: what the command goldens (`tests/commands/debug.cmds`) cannot compare with 9.6,
//! whose symbol listing follows its hash tables and whose stores are its own.

use rusoar::Agent;

fn agent() -> Agent {
    let mut a = Agent::default();
    a.execute("watch 0").unwrap();
    a
}

#[test]
fn internal_symbols_lists_each_kind_in_its_section() {
    let mut a = agent();
    a.execute("sp {a (state <s> ^superstate nil) --> (<s> ^x 1.5 ^y 42 ^|two words| <n>)}")
        .unwrap();
    a.execute("run 1").unwrap();
    let text = a.execute("debug internal-symbols").unwrap();
    let section = |title: &str| -> Vec<String> {
        let head = format!("--- {title}: ---\n");
        let start = text
            .find(&head)
            .unwrap_or_else(|| panic!("no {title} in {text}"))
            + head.len();
        let body = &text[start..];
        let end = body.find("\n--- ").unwrap_or(body.len());
        body[..end].lines().map(str::to_string).collect()
    };
    assert!(section("Symbolic Constants").contains(&"two words".to_string()));
    assert!(section("Integer Constants").contains(&"42".to_string()));
    assert!(section("Floating-Point Constants")
        .iter()
        .any(|f| f.starts_with("1.5")));
    let ids = section("Identifiers");
    assert!(
        ids.contains(&"S1".to_string()) && ids.contains(&"N1".to_string()),
        "{ids:?}"
    );
    assert_eq!(section("Variables"), vec!["<s>".to_string()]);
    // An identifier that left working memory is not listed.
    a.execute("init-soar").unwrap();
    let text = a.execute("debug internal-symbols").unwrap();
    assert!(!text.lines().any(|l| l == "N1"), "{text}");
}

#[test]
fn allocate_lists_the_stores_and_makes_room_in_one() {
    let mut a = agent();
    let listing = a.execute("debug allocate").unwrap();
    assert!(listing.starts_with("Memory pool statistics:"), "{listing}");
    let row = |text: &str, name: &str| -> Vec<usize> {
        let line = text
            .lines()
            .find(|l| l.trim_start().starts_with(name) && l.len() > 15 && l[..15].trim() == name)
            .unwrap_or_else(|| panic!("no row {name} in {text}"));
        line[15..]
            .split_whitespace()
            .map(|n| n.parse().unwrap())
            .collect()
    };
    let before = row(&listing, "token");
    assert_eq!(
        a.execute("debug allocate token 3").unwrap(),
        "token blocks increased by 3\n"
    );
    let after = row(&a.execute("debug allocate").unwrap(), "token");
    // Room for three 32-kilobyte blocks more than it holds.
    assert!(
        after[1] >= 3 * 32 * 1024 / before[0],
        "{before:?} -> {after:?}"
    );
    assert_eq!(
        a.execute("debug allocate {rete node} 1").unwrap(),
        "rete node blocks increased by 1\n"
    );
    let err = a.execute("debug allocate symbol 1").unwrap_err();
    assert!(
        err.message().contains("bad pool name: symbol"),
        "{}",
        err.message()
    );
}

#[test]
fn port_says_why_there_is_none_and_the_listing_names_every_command() {
    let mut a = agent();
    let err = a.execute("debug port").unwrap_err();
    assert!(err.message().contains("no port"), "{}", err.message());
    let listing = a.execute("debug ?").unwrap();
    for sub in ["allocate", "internal-symbols", "port", "time"] {
        assert!(
            listing.lines().any(|l| l.starts_with(sub)),
            "{sub} in {listing}"
        );
    }
}

#[test]
fn a_timed_command_that_fails_prints_the_time_then_fails() {
    let mut a = agent();
    let err = a.execute("debug time no-such-command").unwrap_err();
    assert!(
        err.message().contains("No such command"),
        "{}",
        err.message()
    );
    let ok = a.execute("debug time echo hi").unwrap();
    assert!(
        ok.starts_with("hi\n\n(") && ok.trim_end().ends_with("s) real"),
        "{ok:?}"
    );
}

#[test]
fn the_aliases_of_the_subcommands_reach_them() {
    let mut a = agent();
    let timed = a.execute("time echo hi there").unwrap();
    assert!(timed.starts_with("hi there\n\n("), "{timed:?}");
    assert_eq!(
        a.execute("allocate wme 1").unwrap(),
        "wme blocks increased by 1\n"
    );
    assert!(a
        .execute("internal-symbols")
        .unwrap()
        .contains("--- Identifiers: ---"));
}

/// An alias may hold the timed command's first words (`alias t debug time echo`), and one
/// that names itself (`alias t debug time t`) must end with an error, not a stack overflow.
#[test]
fn a_timed_alias_runs_its_own_words_and_one_naming_itself_is_an_error() {
    let mut a = agent();
    a.execute("alias t debug time echo").unwrap();
    let timed = a.execute("t hi").unwrap();
    assert!(timed.starts_with("hi\n\n("), "{timed:?}");
    a.execute("alias t debug time t").unwrap();
    let err = a.execute("t").unwrap_err();
    assert!(err.message().contains("nested"), "{}", err.message());
}

#[test]
fn room_the_machine_cannot_give_is_a_clear_error() {
    let mut a = agent();
    let err = a.execute("debug allocate wme 999999999999999").unwrap_err();
    assert!(
        err.message().starts_with("Could not allocate memory"),
        "{}",
        err.message()
    );
    // The agent goes on.
    assert_eq!(
        a.execute("debug allocate wme 1").unwrap(),
        "wme blocks increased by 1\n"
    );
}
