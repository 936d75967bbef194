//! Semantic memory worked by random valid agents and commands (the generator of the `smem`
//! fuzz target, `fuzz/src/smem_agent.rs`) drawn from seeded pseudo-random bytes: each
//! agent loads, and the kernel's invariants hold after every step.

mod seeded;
#[path = "../fuzz/src/smem_agent.rs"]
mod smem_agent;
#[path = "../fuzz/src/steps.rs"]
mod steps;

use arbitrary::Unstructured;
use rusoar::Agent;
use smem_agent::{run_smem_agent, smem_agent};

const AGENTS: u64 = 300;
const BYTES: usize = 800;

#[test]
fn random_smem_agents_keep_the_invariants() {
    for seed in 0..AGENTS {
        let data = seeded::bytes(seed, BYTES);
        let spec = smem_agent(&mut Unstructured::new(&data)).expect("bytes make an agent");
        let mut agent = Agent::new("smem");
        if let Err(why) = run_smem_agent(&mut agent, &spec) {
            panic!("seed {seed}: {why}\n\nthe agent and its steps:\n{spec}");
        }
    }
}
