//! Episodic memory: the input's bytes choose a valid agent that stores episodes and puts
//! commands on its `^epmem` links (`rusoar_fuzz::epmem_agent`), which must load, and which
//! runs a phase at a time between `epmem` commands, with the kernel's invariants checked
//! after every step.
#![no_main]

use libfuzzer_sys::arbitrary::Unstructured;
use libfuzzer_sys::fuzz_target;
use rusoar_fuzz::epmem_agent::{epmem_agent, run_epmem_agent};

fuzz_target!(|data: &[u8]| {
    let mut agent = rusoar_fuzz::bounded_agent();
    let Ok(spec) = epmem_agent(&mut Unstructured::new(data)) else {
        return;
    };
    if let Err(why) = run_epmem_agent(&mut agent, &spec) {
        panic!("{why}\n\nthe agent and its steps:\n{spec}");
    }
});
