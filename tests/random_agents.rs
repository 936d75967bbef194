//! Random valid agents (the generator of the structure-aware fuzz target,
//! `fuzz/src/random_agent.rs`) drawn from seeded pseudo-random bytes: each loads, and the
//! kernel's invariants hold after every phase of its run.

#[path = "../fuzz/src/random_agent.rs"]
mod random_agent;
mod seeded;
#[path = "../fuzz/src/steps.rs"]
mod steps;

use arbitrary::Unstructured;
use random_agent::{random_agent, run_random_agent};
use rusoar::Agent;

/// How many agents, and how many bytes each is drawn from (enough for the largest ones).
const AGENTS: u64 = 1500;
const BYTES: usize = 1500;

#[test]
fn random_agents_keep_the_invariants_after_every_phase() {
    for seed in 0..AGENTS {
        let data = seeded::bytes(seed, BYTES);
        let spec = random_agent(&mut Unstructured::new(&data)).expect("bytes make an agent");
        let mut agent = Agent::new("random");
        if let Err(why) = run_random_agent(&mut agent, &spec) {
            panic!("seed {seed}: {why}\n\nthe agent and its steps:\n{spec}");
        }
    }
}

#[test]
fn the_generator_makes_varied_agents() {
    // Without variety the test above would check little: the agents differ, and between
    // them use every kind of rule the generator knows.
    let all: Vec<String> = (0..40)
        .map(|seed| {
            random_agent(&mut Unstructured::new(&seeded::bytes(seed, BYTES)))
                .unwrap()
                .source
        })
        .collect();
    let text = all.join("\n");
    for part in [
        "^superstate nil",
        "^superstate <ss>",
        "^impasse tie",
        "-{(",
        " -(",
        "<< ",
        "{ <",
        "(<s> ^operator <o> !)",
        "(<s> ^operator <o1> > <o2>)",
        "(<ss> ^operator <i>",
        "chunk always",
        " -)",
    ] {
        assert!(text.contains(part), "no agent has {part:?}");
    }
    let distinct: std::collections::HashSet<&String> = all.iter().collect();
    assert!(
        distinct.len() > 35,
        "only {} distinct agents",
        distinct.len()
    );
}
