//! Working-memory activation where the command goldens do not reach: activation stays out
//! of the way while off (no decay histories, no activations printed), turning it off drops
//! what it kept, and bad input is refused with a message, never a panic.

use rusoar::Agent;

const AGENT: &str = "
sp {propose*init (state <s> ^superstate nil -^name) --> (<s> ^operator <o> +) (<o> ^name init)}
sp {apply*init (state <s> ^operator.name init) --> (<s> ^name test ^keep 5)}
";

fn output(agent: &mut Agent, command: &str) -> String {
    agent
        .source_text("t", command)
        .unwrap_or_else(|e| panic!("`{command}`: {}", e.message()));
    agent.take_output()
}

#[test]
fn while_off_nothing_decays_and_nothing_is_printed() {
    let mut agent = Agent::default();
    output(&mut agent, AGENT);
    output(&mut agent, "run 3");
    assert_eq!(
        output(&mut agent, "wm activation -h 17"),
        "WME has no decay history\n"
    );
    assert!(!output(&mut agent, "print -i s1").contains('['));
}

#[test]
fn turning_it_off_drops_the_histories() {
    let mut agent = Agent::default();
    output(&mut agent, "wma -s activation on");
    output(&mut agent, AGENT);
    output(&mut agent, "run 3");
    assert!(output(&mut agent, "wm activation -h 17").starts_with("history (3/3"));
    assert!(output(&mut agent, "print -i s1").contains("(17: S1 ^name test [0.75])"));
    output(&mut agent, "wm activation -s activation off");
    assert_eq!(
        output(&mut agent, "wm activation -h 17"),
        "WME has no decay history\n"
    );
    assert!(!output(&mut agent, "print -i s1").contains('['));
}

#[test]
fn bad_input_gets_a_message() {
    let mut agent = Agent::default();
    for (command, message) in [
        (
            "wm activation -s decay-rate 7",
            "Invalid value for activation setting.",
        ),
        ("wm activation -s nonsense 1", "Invalid activation setting."),
        ("wm activation -h -", "Invalid timetag."),
        ("wm activation -h 0", "Invalid timetag."),
        (
            "wm activation -S -h 3",
            "wm activation takes only one option at a time.",
        ),
        (
            "wm activation -s max-pow-cache -1",
            "Invalid value for activation setting.",
        ),
    ] {
        let err = agent.source_text("t", command).unwrap_err();
        assert_eq!(err.message(), message, "`{command}`");
    }
}
