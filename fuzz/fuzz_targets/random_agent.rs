//! Structure-aware: the input's bytes choose a valid agent (`rusoar_fuzz::random_agent`),
//! which must load, and which runs a phase at a time with the kernel's invariants checked
//! after every step.
#![no_main]

use libfuzzer_sys::arbitrary::Unstructured;
use libfuzzer_sys::fuzz_target;
use rusoar_fuzz::random_agent::{random_agent, run_random_agent};

fuzz_target!(|data: &[u8]| {
    let Ok(spec) = random_agent(&mut Unstructured::new(data)) else {
        return;
    };
    let mut agent = rusoar_fuzz::bounded_agent();
    if let Err(why) = run_random_agent(&mut agent, &spec) {
        panic!("{why}\n\nthe agent and its steps:\n{spec}");
    }
});
