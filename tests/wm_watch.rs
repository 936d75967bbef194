//! `wm watch` where the command goldens cannot compare it with the official kernel, and
//! `wm activation`, which rusoar does not build. soar-sml 9.6.5 crashes or hangs at the
//! next `wm watch` after a reset (`-R`) that removed two or more filters; rusoar removes
//! them all and goes on.

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

#[test]
fn wm_activation_says_it_is_not_built() {
    let mut agent = Agent::default();
    for command in ["wm activation", "wm activation --get activation", "wma"] {
        let err = agent.source_text("t", command).unwrap_err();
        let message = err.message();
        assert!(
            message.ends_with(": not yet supported by rusoar") && !message.contains('\n'),
            "`{command}`: {message}"
        );
    }
}
