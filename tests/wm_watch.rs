//! `wm watch` where the command goldens cannot compare it with the official kernel:
//! soar-sml 9.6.5 crashes or hangs at the next `wm watch` after a reset (`-R`) that
//! removed two or more filters; rusoar removes them all and goes on.

use rusoar::Agent;

fn output(agent: &mut Agent, command: &str) -> String {
    agent
        .source_text("t", command)
        .unwrap_or_else(|e| panic!("`{command}`: {}", e.message()));
    agent.take_output()
}

#[test]
fn a_reset_removes_every_filter_of_its_kind() {
    let mut agent = Agent::default();
    output(&mut agent, "wm watch -a -t adds S1 * *");
    output(&mut agent, "wm watch -a -t both * name *");
    output(&mut agent, "wm watch -a -t removes * * 5");
    assert_eq!(
        output(&mut agent, "wm watch -R -t adds"),
        "Removed: (* ^name *) adds removes\nRemoved: (S1 ^* *) adds \n"
    );
    assert_eq!(
        output(&mut agent, "wm watch -l"),
        "wme filter: (* ^* 5)  removes\n"
    );
    assert_eq!(
        output(&mut agent, "wm watch -R"),
        "Removed: (* ^* 5)  removes\n"
    );
    assert_eq!(output(&mut agent, "wm watch -l"), "");
}
