//! `gp`: one rule per combination of `[...]` alternatives, named and ordered as soar-sml
//! 9.6.5 names and orders them.

use rusoar::Agent;

#[test]
fn gp_makes_one_rule_per_combination_in_the_official_order() {
    let mut a = Agent::default();
    let stars = a
        .execute("gp {gen (state <s> ^a [b c] ^d [1 2]) --> (<s> ^e [x y])}")
        .unwrap();
    assert_eq!(stars, "********");
    assert_eq!(a.production_count(), 8);
    // (The `*` marks leave the print column off 0, so `print` starts a fresh line.)
    assert_eq!(
        a.execute("print gen*3").unwrap().trim_start(),
        "sp {gen*3\n    (state <s> ^d 2 ^a b)\n    -->\n    (<s> ^e x)\n}\n\n"
    );
    a.execute("gp {g2 (state <s> ^a [ |x y| 3.5 ]) --> (write [hello bye] |[not]|)}")
        .unwrap();
    assert_eq!(
        a.execute("print g2*2").unwrap().trim_start(),
        "sp {g2*2\n    (state <s> ^a 3.500000)\n    -->\n    (write hello |[not]|)\n}\n\n"
    );
    for (bad, message) in [
        (
            "gp {g6 (state <s> ^a [b c) --> (<s> ^c d)}",
            "gp syntax error, unmatched values bracket.",
        ),
        (
            "gp {g7 (state <s> ^a []) --> (<s> ^c d)}",
            "gp can't have empty value collections",
        ),
        ("gp", "Syntax: gp { production_body }"),
    ] {
        assert_eq!(a.execute(bad).unwrap_err().message(), message, "{bad}");
    }
}
