//! Large inputs reach limits or finish, never exhaust the stack: printing a chain of
//! 10,000 objects to its full depth (its text grows with the square of the length: each
//! level is indented two more spaces), collecting a chain of a million, and a rule of
//! thousands of conditions joined one to the next. The tests run on the test harness's
//! threads, whose stacks are smaller than a program's main thread.

use rusoar::{Agent, RunUnit};

/// `(I2 ^next X1) (X1 ^next X2) ... ` on the input-link, `n` long; the handle of the first.
fn chain(agent: &mut Agent, n: usize) -> rusoar::InputWme {
    let mut io = agent.io();
    let mut at = io.input_link();
    let mut first = None;
    for _ in 0..n {
        let (w, next) = io.add_object(at, "next").expect("a link of the chain");
        first.get_or_insert(w);
        at = next;
    }
    first.expect("a chain of at least one")
}

#[test]
fn printing_a_chain_of_10000_objects_to_full_depth() {
    let n = 10_000;
    let mut agent = Agent::new("limits");
    chain(&mut agent, n);
    agent.run(1, RunUnit::Phases).expect("the input phase");
    let printed = agent.execute("print --depth 100000 i2").expect("print");
    assert_eq!(printed.matches("^next").count(), n);
    // The last object, at the deepest indentation (its line wraps there).
    assert!(printed.trim_end().ends_with(&format!("^next N{n})")));
}

#[test]
fn collecting_a_chain_of_a_million_objects() {
    let mut agent = Agent::new("limits");
    let before = agent.wme_count();
    let first = chain(&mut agent, 1_000_000);
    agent.run(1, RunUnit::Phases).expect("the input phase");
    assert_eq!(agent.wme_count(), before + 1_000_000);
    agent.io().remove(first).expect("the chain goes");
    // The rest of this decision, then the input phase that removes the chain.
    agent.run(2, RunUnit::Decisions).expect("decisions");
    assert_eq!(agent.check_invariants(), Ok(()));
    // The substate of the state no-change is all that is new.
    let left = agent.execute("print --depth 2 i2").expect("print");
    assert!(!left.contains("^next"), "{left}");
    assert!(agent.wme_count() < before + 100, "{}", agent.wme_count());
}

#[test]
fn a_rule_of_5000_conditions_joined_in_a_chain() {
    let n: usize = std::env::var("N").map_or(5000, |v| v.parse().unwrap());
    let conditions: String = (0..n)
        .map(|i| format!(" (<v{i}> ^next <v{}>)", i + 1))
        .collect();
    let mut agent = Agent::new("limits");
    agent
        .execute(&format!(
            "sp {{long (state <s> ^superstate nil ^io.input-link.next <v0>){conditions} \
             --> (<s> ^reached <v{n}>)}}"
        ))
        .expect("the rule loads");
    chain(&mut agent, n + 1);
    agent.run(1, RunUnit::Decisions).expect("a decision");
    assert!(agent.has_attribute(agent.top_state(), "reached"));
    let printed = agent.execute("print long").expect("print the rule");
    assert_eq!(printed.matches("^next").count(), n + 1);
    agent.execute("matches long").expect("matches");
    agent.execute("excise long").expect("excise");
    assert_eq!(agent.check_invariants(), Ok(()));
}

/// A substate whose operators each replace the WME the last one made: every firing's
/// record holds the one before it (for backtracing), 100,000 long. `init-soar` lets the
/// whole chain go (9.6.5 holds it too: 1.3 GB at 200,000 decisions).
#[test]
fn letting_go_of_a_substate_chain_of_100000_firings() {
    let mut agent = Agent::new("limits");
    agent
        .execute(
            "sp {init*propose (state <s> ^superstate <ss>) (<ss> ^superstate nil) -(<s> ^last)
                --> (<s> ^operator <o> +) (<o> ^name init)}
             sp {init*apply (state <s> ^operator.name init) --> (<s> ^last <l>) (<l> ^n 0)}
             sp {step*propose (state <s> ^superstate <ss> ^last <l>) (<ss> ^superstate nil)
                --> (<s> ^operator <o> +) (<o> ^name step ^from <l>)}
             sp {step*apply (state <s> ^operator <o> ^last <l>) (<o> ^name step ^from <l>) (<l> ^n <c>)
                --> (<s> ^last <l> -) (<s> ^last <m>) (<m> ^n (+ <c> 1))}",
        )
        .expect("the rules");
    agent.run(100_000, RunUnit::Decisions).expect("the run");
    let last = agent.execute("print (s2 ^last *)").expect("print");
    assert!(last.contains("^last"), "{last}");
    agent.execute("init-soar").expect("init-soar");
    assert_eq!(
        agent
            .run(2, RunUnit::Decisions)
            .expect("a run after")
            .decisions,
        2
    );
}
