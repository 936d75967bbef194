//! Any text typed at the command line: every command, alias and option of the command
//! language, with whatever arguments, in any order. The agent must answer each with a
//! result or an error, never a panic, keep the kernel's invariants and stay usable.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if !rusoar_fuzz::confined(text) {
        return;
    }
    let mut agent = rusoar_fuzz::bounded_agent();
    agent.source_text_keep_going("fuzz", text);
    let _ = agent.take_output();
    rusoar_fuzz::assert_invariants(&agent);
    // Whatever happened, the agent still answers.
    let _ = agent.execute("print --depth 2 s1");
    let _ = agent.execute("stats");
});
