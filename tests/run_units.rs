//! `run N -e` steps one elaboration cycle at a time, inside the propose and apply phases,
//! as the official kernel does (checked with soar-sml 9.6.5: the first `run 1 -e` ends the
//! input phase, each later one fires one cycle's rules).

use rusoar::Agent;

#[test]
fn run_e_stops_after_each_elaboration_cycle() {
    let mut interp = Agent::default();
    interp
        .source_text(
            "<test>",
            "sp {init (state <s> ^superstate nil -^name) --> (<s> ^name x)}\n\
             sp {show (state <s> ^name x) --> (write |seen|)}",
        )
        .expect("rules load");
    let mut firings = Vec::new();
    for _ in 0..4 {
        interp.source_text("<test>", "run 1 -e").expect("run");
        firings.push(interp.firings());
    }
    // Input phase, then init, then show (and init retracts), then init again.
    assert_eq!(firings, vec![0, 1, 2, 3]);
    assert_eq!(interp.decisions(), 0, "still in the first propose phase");
}
