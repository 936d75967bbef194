//! `preferences ID ATTR`: every preference type in 9.6's section order and line format, and
//! the selection probabilities of the operator slot. The expected text is what soar-sml
//! 9.6.5 prints for the same rule.

use rusoar::Agent;

const RULE: &str = "sp {p (state <s> ^superstate nil) --> (<s> ^operator <a> + = > <b>) \
    (<s> ^operator <b> + < ) (<s> ^operator <c> + ~ = 3) (<s> ^operator <d> + - >) \
    (<s> ^operator <e> ! = <a>) (<a> ^name a) (<b> ^name b) (<c> ^name c) (<d> ^name d) \
    (<e> ^name e) (<s> ^thing x + -)}";

fn run_commands(commands: &str) -> String {
    let mut interp = Agent::default();
    interp.source_text("<test>", RULE).expect("rule loads");
    interp.source_text("<test>", "run 1").expect("run");
    let _ = interp.take_output();
    interp
        .source_text("<test>", commands)
        .expect("command runs");
    interp.take_output()
}

#[test]
fn operator_slot_lists_every_type_in_soar_order() {
    let expected = "\nPreferences for S1 ^operator:\n\nacceptables:\n  A1 (a) +  :I \n  \
        B1 (b) +  :I \n  C3 (c) +  :I \n  D1 (d) +  :I \n\nrequires:\n  E2 (e) !  :I \n\n\
        rejects:\n  D1 (d) -  :I \n\nprohibits:\n  C3 (c) ~  :I \n\nunary indifferents:\n  \
        A1 (a) =  :I \n\nbests:\n  D1 (d) >  :I \n\nworsts:\n  B1 (b) <  :I \n\n\
        binary indifferents:\n  E2 (e) = A1 (a) :I \n\nbetters:\n  A1 (a) > B1 (b) :I \n\n\
        numeric indifferents:\n  C3 (c) = 3 :I \n\nselection probabilities:\n  \
        E2 (e) !  = 0. :I (100.00%)\n";
    assert_eq!(run_commands("preferences S1 operator"), expected);
}

#[test]
fn names_add_the_rule_under_each_preference() {
    let text = run_commands("preferences S1 operator --names");
    assert!(text.contains("  A1 (a) +  :I \n    From p\n\n  B1 (b) +  :I \n"));
}

#[test]
fn unknown_slot_is_an_error() {
    let mut interp = Agent::default();
    let err = interp
        .source_text("<test>", "preferences S1 foo")
        .expect_err("no such slot");
    assert!(err
        .message()
        .starts_with("Could not find prefs for the id,attribute pair: S1 foo"));
}
