//! The condition reorderer: rules whose conditions 9.6 reorders, and the order `print`
//! shows afterwards, as the official kernel (soar-sml 9.6.5) printed it for the same rules
//! loaded in the same order into a fresh agent.

use rusoar::Agent;

fn printed(rules: &[&str], name: &str) -> String {
    let mut i = Agent::default();
    for r in rules {
        i.source_text("rule", r).unwrap();
    }
    i.take_output();
    i.source_text("print", &format!("print {name}")).unwrap();
    // The `*` each rule printed leaves the column off 0, so print starts a fresh line.
    i.take_output().trim_start_matches('\n').to_string()
}

#[test]
fn tied_conditions_go_newest_constant_first() {
    let out = printed(
        &["sp {rule-1 (state <s> ^aa <x> ^bb <y> ^cc <z>) --> (write hi)}"],
        "rule-1",
    );
    assert_eq!(
        out,
        "sp {rule-1\n    (state <s> ^cc <z> ^bb <y> ^aa <x>)\n    -->\n    (write hi)\n}\n\n"
    );
}

#[test]
fn the_lookahead_prefers_a_condition_that_makes_the_next_one_cheap() {
    let rules = [
        "sp {rule-1 (state <s> ^aa <x> ^bb <y> ^cc <z>) --> (write hi)}",
        "sp {rule-3 (state <s> ^aa <x> ^bb <y>) (<x> ^dd <q>) (<y> ^ee 1) --> (write hi)}",
    ];
    assert_eq!(
        printed(&rules, "rule-3"),
        "sp {rule-3\n    (state <s> ^bb <y> ^aa <x>)\n    (<y> ^ee 1)\n    (<x> ^dd <q>)\n    \
         -->\n    (write hi)\n}\n\n"
    );
}

#[test]
fn negations_win_cost_one_ties_and_relational_tests_move_to_their_referent() {
    let rules = [
        "sp {rule-1 (state <s> ^aa <x> ^bb <y> ^cc <z>) --> (write hi)}",
        "sp {rule-4 (state <s> ^name foo ^aa <x> -^zz ^bb {<y> > <x>}) --> (write hi)}",
        "sp {rule-e (state <s> ^aa <x> ^bb 3 ^cc 4 -^dd 1 -^ee 2) --> (write hi)}",
    ];
    assert_eq!(
        printed(&rules, "rule-4"),
        "sp {rule-4\n    (state <s> ^name foo -^zz <z*1> ^bb <y> ^aa { < <y> <x> })\n    -->\n    \
         (write hi)\n}\n\n"
    );
    assert_eq!(
        printed(&rules, "rule-e"),
        "sp {rule-e\n    (state <s> ^cc 4 -^ee 2 -^dd 1 ^bb 3 ^aa <x>)\n    -->\n    (write hi)\n}\n\n"
    );
}

#[test]
fn start_up_constants_are_older_than_a_rules_own() {
    // `superstate` and the small integers exist before any rule is loaded.
    let rules = [
        "sp {rule-5 (state <s> ^superstate <ss> ^aa <x>) (<ss> ^operator <o>) (<o> ^name bar) --> (write hi)}",
        "sp {rule-c (state <s> ^aa 8 ^aa 2) --> (write hi)}",
        "sp {rule-a (state <s> ^aa 1234 ^aa 5678) --> (write hi)}",
    ];
    assert!(printed(&rules, "rule-5").contains("(state <s> ^aa <x> ^superstate <ss>)"));
    assert!(printed(&rules, "rule-c").contains("(state <s> ^aa 8 ^aa 2)"));
    assert!(printed(&rules, "rule-a").contains("(state <s> ^aa 5678 ^aa 1234)"));
}

#[test]
fn an_ncc_goes_where_its_variables_are_bound_and_non_root_state_tests_go() {
    let rules = [
        "sp {rule-a (state <s> ^aa <x> ^cc <z>) (<x> ^bb 1) --> (write hi)}",
        "sp {rule-b (state <s> ^aa <x> ^cc <z>) (<x> ^bb 1) -{(<z> ^dd <q>) (<q> ^ee 2)} --> (write hi)}",
        "sp {rule-e (state <s> ^aa <x>) (state <x> ^bb <y>) --> (write hi)}",
    ];
    assert_eq!(
        printed(&rules, "rule-b"),
        "sp {rule-b\n    (state <s> ^cc <z> ^aa <x>)\n   -{ (<z> ^dd <q>)\n      (<q> ^ee 2)}\n    \
         (<x> ^bb 1)\n    -->\n    (write hi)\n}\n\n"
    );
    assert_eq!(
        printed(&rules, "rule-e"),
        "sp {rule-e\n    (state <s> ^aa <x>)\n    (<x> ^bb <y>)\n    -->\n    (write hi)\n}\n\n"
    );
}

#[test]
fn several_set_aside_tests_come_back_in_their_order() {
    let out = printed(
        &["sp {rule-d (state <s> ^aa { > 1 < 5 <x> } ^bb { <y> <> <x> > 2 }) --> (write hi)}"],
        "rule-d",
    );
    assert!(
        out.contains("(state <s> ^bb { > 2 <y> } ^aa { > 1 < 5 <> <y> <x> })"),
        "{out}"
    );
}

/// `multi-attributes` prices a condition on a declared attribute by its expected count once
/// the state is bound. soar-sml 9.6.5 orders these rules as below with the declarations
/// (`^c <z> ^b <y> ^a <x>` and `^b <y> ^a <x>` without them), and lists the declarations
/// newest first.
#[test]
fn multi_attributes_change_the_order_as_in_the_official_kernel() {
    let rules = [
        "multi-attributes b 50",
        "multi-attributes c",
        "sp {rule1 (state <s> ^a <x>) (<s> ^b <y>) (<s> ^c <z>) --> (write <x> <y> <z>)}",
        "sp {rule2 (state <s> ^b <y> ^a <x>) (<y> ^c <z> ^d <w>) (<x> ^b <v>) --> (write <x>)}",
    ];
    assert_eq!(
        printed(&rules, "rule1"),
        "sp {rule1\n    (state <s> ^a <x> ^c <z> ^b <y>)\n    -->\n    (write <x> <y> <z>)\n}\n\n"
    );
    assert_eq!(
        printed(&rules, "rule2"),
        "sp {rule2\n    (state <s> ^a <x> ^b <y>)\n    (<y> ^d <w> ^c <z>)\n    (<x> ^b <v>)\n    -->\n    (write <x>)\n}\n\n"
    );
    let mut agent = Agent::default();
    assert_eq!(
        agent.execute("multi-attributes").unwrap(),
        "No optimized attributes found.Value\tSymbol\n"
    );
    agent.execute("multi-attributes foo 5\nmulti-attributes bar\nmulti-attributes 3 4\nmulti-attributes foo 7").unwrap();
    assert_eq!(
        agent.execute("multi-attributes").unwrap(),
        "Value\tSymbol\n4\t|3|\n10\tbar\n7\tfoo\n"
    );
    let e = agent.execute("multi-attributes foo 0").unwrap_err();
    assert_eq!(e.message(), "Expected non-negative integer.");
}

/// When a rule's conditions are not all connected, the reorderer can place a negation before
/// the condition that binds a variable the negation compares with. 9.6 then reports "Rete
/// build found test of unbound var" (and can no longer run); rusoar refuses the rule with
/// that message and keeps the agent usable. The same negation after its binding loads.
#[test]
fn a_negation_comparing_with_a_later_binding_is_refused() {
    let mut agent = Agent::default();
    let err = agent
        .source_text(
            "rule",
            "sp {t (state <s> ^<at> x) (<a> ^a0 <a>) (<b> ^a0 <b>) \
             -(<s> ^a0 {<> <b> <a>}) --> (write hi)}",
        )
        .unwrap_err();
    assert!(
        err.to_string()
            .contains("Rete build found test of unbound var: <b>"),
        "{err}"
    );
    agent.take_output();
    let _ = agent.source_text("print", "print --all");
    assert!(!agent.take_output().contains("sp {t"));
    agent
        .source_text(
            "rule",
            "sp {u (state <s> ^b <b> ^a0 <a>) -(<s> ^a0 {<> <b> <a>}) --> (write hi)}",
        )
        .unwrap();
}
