//! `explain`: what the command goldens (`tests/commands/explain*.cmds`) leave out, where
//! rusoar answers with an error of its own: a recorded rule cannot be explained yet.

use rusoar::Agent;

#[test]
fn a_recorded_rule_is_listed_and_explaining_it_is_refused_clearly() {
    let mut a = Agent::default();
    a.execute("watch 0").unwrap();
    a.execute(&format!(
        "source {}/tests/agents/learn-conjunctions.soar",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    a.execute("explain all on").unwrap();
    a.execute("run").unwrap();
    let list = a.execute("explain list-chunks").unwrap();
    assert!(
        list.contains("   chunk*sub*disjunction*t3-1 (c 1)\n"),
        "{list}"
    );
    for form in ["explain chunk 1", "explain chunk*sub*disjunction*t3-1"] {
        let e = a.execute(form).unwrap_err();
        assert_eq!(
            e.message(),
            "rusoar cannot explain the formation of chunk*sub*disjunction*t3-1 yet",
            "{form}"
        );
    }
    // Nothing was chosen, so the browsing sub-commands still ask for a rule.
    let e = a.execute("explain formation").unwrap_err();
    assert!(
        e.message().starts_with("Please first specify the chunk"),
        "{}",
        e.message()
    );
    a.execute("init-soar").unwrap();
    assert_eq!(
        a.execute("explain list-chunks").unwrap().trim_end(),
        "No chunks have been recorded."
    );
}
