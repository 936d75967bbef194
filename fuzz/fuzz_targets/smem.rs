//! Semantic memory. An input that starts with `{` is knowledge-base text as it is: it is
//! given to `smem --add`, `smem --query` and `smem --remove`, which load it or give an
//! error, never panic. Any other input's bytes choose a valid agent that works semantic
//! memory (`rusoar_fuzz::smem_agent`), which must load, and which runs a phase at a time
//! with the kernel's invariants checked after every step.
#![no_main]

use libfuzzer_sys::arbitrary::Unstructured;
use libfuzzer_sys::fuzz_target;
use rusoar_fuzz::smem_agent::{run_smem_agent, smem_agent};

fuzz_target!(|data: &[u8]| {
    let mut agent = rusoar_fuzz::bounded_agent();
    if data.first() == Some(&b'{') {
        let Ok(text) = std::str::from_utf8(data) else {
            return;
        };
        if !rusoar_fuzz::confined(text) {
            return;
        }
        let _ = agent.execute("smem --enable");
        for command in [
            "smem --add",
            "smem --query",
            "print @",
            "smem --remove",
            "print @",
        ] {
            let _ = agent.execute(&format!("{command} {text}"));
        }
        let _ = agent.execute("run 5");
        let _ = agent.take_output();
        rusoar_fuzz::assert_invariants(&agent);
        return;
    }
    let Ok(spec) = smem_agent(&mut Unstructured::new(data)) else {
        return;
    };
    if let Err(why) = run_smem_agent(&mut agent, &spec) {
        panic!("{why}\n\nthe agent and its steps:\n{spec}");
    }
});
