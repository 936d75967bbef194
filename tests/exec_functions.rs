//! `exec` calling functions that the embedding program registers (Soar manual, ch. 3,
//! "User-defined functions and interface commands as RHS actions"): the text form gets the
//! arguments' texts concatenated; a numeric form, when registered, gets the numbers instead
//! whenever the arguments are numbers between comma separators.

use rusoar::Agent;

fn run_with(rule_rhs: &str) -> String {
    let mut i = Agent::default();
    i.register_sml_rhs_function("f", |_, args| format!("text[{args}]"));
    assert!(i.register_sml_rhs_numeric_form("f", |n| {
        (n.len() == 2).then(|| format!("num[{},{}]", n[0], n[1]))
    }));
    i.source_text(
        "t",
        &format!(
            "watch 0\nsp {{t (state <s> ^superstate nil) --> (<s> ^r {rule_rhs})}}\nrun 1\n\
             print s1"
        ),
    )
    .unwrap();
    i.take_output()
}

#[test]
fn the_numeric_form_gets_the_numbers_of_comma_separated_arguments() {
    assert!(run_with("(exec f 3000 |, | -1.5)").contains("^r |num[3000,-1.5]|"));
}

#[test]
fn other_arguments_go_to_the_text_form() {
    // No separator: the text form reads one field "3000-1.500000".
    assert!(run_with("(exec f 3000 -1.5)").contains("^r |text[3000-1.500000]|"));
    // A word among the arguments.
    assert!(run_with("(exec f 3000 |, | x)").contains("^r |text[3000, x]|"));
    // The numeric form declines (three numbers): the text form answers.
    assert!(run_with("(exec f 1 |,| 2 |,| 3)").contains("^r |text[1,2,3]|"));
}

#[test]
fn a_numeric_form_needs_a_registered_function_and_goes_with_it() {
    let mut i = Agent::default();
    assert!(!i.register_sml_rhs_numeric_form("g", |_| Some("num".into())));
    i.register_sml_rhs_function("g", |_, _| "text".into());
    assert!(i.register_sml_rhs_numeric_form("g", |_| Some("num".into())));
    // Registering the text form again drops the old numeric form.
    i.register_sml_rhs_function("g", |_, _| "new".into());
    i.source_text(
        "t",
        "watch 0\nsp {t (state <s> ^superstate nil) --> (<s> ^r (exec g 1 |, | 2))}\nrun 1\n\
         print s1",
    )
    .unwrap();
    assert!(i.take_output().contains("^r new"));
}
