//! Semantic memory worked by random valid agents and commands (the generator of the `smem`
//! fuzz target, `fuzz/src/smem_agent.rs`) drawn from seeded pseudo-random bytes: each
//! agent loads, and the kernel's invariants hold after every step.

#[path = "../fuzz/src/smem_agent.rs"]
mod smem_agent;

use arbitrary::Unstructured;
use rusoar::Agent;
use smem_agent::{run_smem_agent, smem_agent};

const AGENTS: u64 = 300;
const BYTES: usize = 800;

/// Bytes from a 64-bit xorshift generator: the same for a seed on every platform.
fn bytes(seed: u64) -> Vec<u8> {
    let mut x = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    (0..BYTES)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 24) as u8
        })
        .collect()
}

#[test]
fn random_smem_agents_keep_the_invariants() {
    for seed in 0..AGENTS {
        let data = bytes(seed);
        let spec = smem_agent(&mut Unstructured::new(&data)).expect("bytes make an agent");
        let mut agent = Agent::new("smem");
        if let Err(why) = run_smem_agent(&mut agent, &spec) {
            panic!("seed {seed}: {why}\n\nthe agent and its steps:\n{spec}");
        }
    }
}
