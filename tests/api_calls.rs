//! Random sequences of calls to the embedding API (the driver of the `api_calls` fuzz
//! target, `fuzz/src/api_calls.rs`) drawn from seeded pseudo-random bytes: no call panics,
//! and the kernel's invariants hold after each.

#[path = "../fuzz/src/api_calls.rs"]
mod api_calls;
mod seeded;

use arbitrary::Unstructured;
use rusoar::Agent;

const SEQUENCES: u64 = 300;
const BYTES: usize = 600;

#[test]
fn random_call_sequences_keep_the_invariants() {
    for seed in 0..SEQUENCES {
        let data = seeded::bytes(seed, BYTES);
        let mut agent = Agent::new("api");
        if let Err(why) = api_calls::run_api_calls(&mut agent, &mut Unstructured::new(&data)) {
            panic!("seed {seed}: {why}");
        }
    }
}

/// Found by the `api_calls` sequences: an input object removed (and collected at the next
/// input phase) could still be given WMEs through its identifier, which then hung in working
/// memory with no link to a state, for good. Adding under it is an error.
#[test]
fn a_removed_input_object_takes_no_more_wmes() {
    let mut agent = Agent::new("api");
    let (handle, object) = {
        let mut io = agent.io();
        let il = io.input_link();
        io.add_object(il, "c").expect("an object on the input-link")
    };
    // While its removal waits for the input phase, the object is still linked.
    agent
        .io()
        .add(object, "a", 1)
        .expect("a WME under a linked object");
    agent.io().remove(handle).expect("the object goes");
    agent
        .run(1, rusoar::RunUnit::Decisions)
        .expect("a decision");
    assert!(agent.children(object).is_empty());
    let late = agent.io().add(object, "a", "late");
    let message = late.expect_err("the object is gone").to_string();
    assert!(message.contains("is not in working memory"), "{message}");
    assert!(agent.io().add_object(object, "b").is_err());
    assert_eq!(agent.check_invariants(), Ok(()));
}

/// Found by the `api_calls` sequences: an input object unlinked by an update stayed in
/// working memory, with no link, until a later phase collected garbage. 9.6 collects it in
/// the input phase: soar-sml 9.6.5, for an object `B1 ^a A1` under `(I2 ^b B1)` destroyed
/// after a decision, traces `<=WM: (15: B1 ^a A1)` then `<=WM: (14: I2 ^b B1)` in the next
/// input phase, and `print b1` finds no B1.
#[test]
fn an_unlinked_input_object_is_collected_in_the_input_phase() {
    let mut agent = Agent::new("api");
    let il = agent.io().input_link();
    let (b, b1) = agent.io().add_object(il, "b").expect("an object");
    agent.io().add_object(b1, "a").expect("an object under it");
    agent
        .run(1, rusoar::RunUnit::Decisions)
        .expect("a decision");
    agent.execute("watch 4").expect("watch");
    agent
        .io()
        .update(b, 2.5)
        .expect("the object's WME takes a number");
    // The rest of the decision, then the input phase.
    agent.run(3, rusoar::RunUnit::Phases).expect("phases");
    let trace = agent.take_output();
    let input = &trace[trace.find("--- Input Phase ---").expect("an input phase")..];
    let input = &input[..input.find("END Input Phase").expect("its end")];
    let removed: Vec<&str> = input.lines().filter(|l| l.starts_with("<=WM")).collect();
    assert_eq!(
        removed,
        ["<=WM: (15: B1 ^a A1)", "<=WM: (14: I2 ^b B1)"],
        "{trace}"
    );
    assert_eq!(agent.check_invariants(), Ok(()));
    let printed = agent.execute("print b1").unwrap_or_else(|e| e.to_string());
    assert!(!printed.contains("^a A1"), "{printed}");
}

/// Found by the `api_calls` sequences: the handle of a WME under an input object that an
/// update replaced could still update it, which put a WME under the collected object.
#[test]
fn handles_below_a_replaced_object_go_stale() {
    let mut agent = Agent::new("api");
    let il = agent.io().input_link();
    let (a, a1) = agent.io().add_object(il, "a").expect("an object");
    let (below, _) = agent.io().add_object(a1, "a").expect("an object under it");
    agent
        .run(1, rusoar::RunUnit::Decisions)
        .expect("a decision");
    agent
        .io()
        .update(a, 3)
        .expect("the object's WME takes a number");
    agent
        .run(1, rusoar::RunUnit::Decisions)
        .expect("a decision");
    let late = agent.io().update(below, 0);
    assert!(late.is_err(), "{late:?}");
    assert_eq!(agent.check_invariants(), Ok(()));
}

/// Found by the `api_calls` fuzz target: a WME added under an input object whose removal
/// was waiting went with the object's garbage at the input phase, but its handle stayed
/// live; its WME's place in working memory then went to a rule's WME, and removing the
/// handle removed that WME instead (`(O1 ^name act)`, with the operator still selected).
/// The handle is stale, and a waiting change leaves a WME with another timetag alone.
#[test]
fn a_handle_whose_wme_was_collected_touches_no_other_wme() {
    let mut agent = Agent::new("api");
    agent
        .execute(
            "sp {propose (state <s> ^superstate nil) --> (<s> ^operator <o> +) (<o> ^name act)}",
        )
        .expect("a rule");
    let il = agent.io().input_link();
    let (object, a1) = agent.io().add_object(il, "a").expect("an object");
    agent
        .run(1, rusoar::RunUnit::Phases)
        .expect("the input phase");
    agent.io().remove(object).expect("the object goes");
    let below = agent.io().add(a1, "b", "x").expect("A1 is still linked");
    // The input phase adds and removes both, the rule proposes, a decision selects.
    agent.run(3, rusoar::RunUnit::Decisions).expect("decisions");
    assert!(agent.io().update(below, 1).is_err());
    assert!(agent.io().remove(below).is_err());
    agent.run(2, rusoar::RunUnit::Decisions).expect("decisions");
    assert_eq!(agent.check_invariants(), Ok(()));
    let op = agent.execute("print --depth 2 s1").expect("print");
    assert!(op.contains("^name act"), "{op}");
}
