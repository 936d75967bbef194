//! The production parser: the body of an `sp {...}` command, as text. Whatever it is, it
//! loads or gives a diagnostic; a rule that loads can be printed, matched and excised.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(body) = std::str::from_utf8(data) else {
        return;
    };
    if body.len() > rusoar_fuzz::MAX_INPUT {
        return;
    }
    let mut agent = rusoar_fuzz::bounded_agent();
    let loaded = agent.execute(&format!("sp {{{body}}}")).is_ok();
    if loaded {
        let _ = agent.execute("print --all");
        let _ = agent.execute("run 3");
        rusoar_fuzz::assert_invariants(&agent);
        let _ = agent.execute("matches");
        let _ = agent.execute("excise --all");
    }
});
