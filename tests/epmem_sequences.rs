//! Episodic memory worked by random valid agents and commands (the generator of the `epmem`
//! fuzz target, `fuzz/src/epmem_agent.rs`) drawn from seeded pseudo-random bytes: each
//! agent loads, and the kernel's invariants hold after every step.

#[path = "../fuzz/src/epmem_agent.rs"]
mod epmem_agent;
mod seeded;
#[path = "../fuzz/src/steps.rs"]
mod steps;

use arbitrary::Unstructured;
use epmem_agent::{epmem_agent, run_epmem_agent};
use rusoar::Agent;

const AGENTS: u64 = 300;
const BYTES: usize = 800;

#[test]
fn random_epmem_agents_keep_the_invariants() {
    for seed in 0..AGENTS {
        let data = seeded::bytes(seed, BYTES);
        let spec = epmem_agent(&mut Unstructured::new(&data)).expect("bytes make an agent");
        let mut agent = Agent::new("epmem");
        if let Err(why) = run_epmem_agent(&mut agent, &spec) {
            panic!("seed {seed}: {why}\n\nthe agent and its steps:\n{spec}");
        }
    }
}
