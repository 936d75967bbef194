//! Reinforcement learning where the command goldens (`tests/commands/rl*.cmds`, compared
//! with the official kernel) cannot check it: the parts of Soar-RL rusoar does not build
//! answer with one error line that names them, and leave the parameters as they were; and
//! what an RL rule learned survives a save and a reload as its printed text.

use rusoar::Agent;

/// What a command printed, without the line break that ends a line of `sp`'s marks.
fn output(agent: &mut Agent, command: &str) -> String {
    agent
        .source_text("t", command)
        .unwrap_or_else(|e| panic!("`{command}`: {}", e.message()));
    agent.take_output().trim_start_matches('\n').to_string()
}

fn refused(agent: &mut Agent, command: &str) -> String {
    let err = agent
        .source_text("t", command)
        .expect_err("the command should be refused");
    let message = err.message().to_string();
    assert!(
        message.ends_with("not yet supported by rusoar") && !message.contains('\n'),
        "`{command}`: {message}"
    );
    message
}

#[test]
fn what_is_not_built_is_refused_by_name() {
    let mut agent = Agent::default();
    for (command, names) in [
        ("rl --set apoptosis chunks", "apoptosis"),
        ("rl --set apoptosis rl-chunks", "apoptosis"),
        ("rl --set trace on", "trace"),
        ("rl --trace", "graph"),
        ("rl -t", "graph"),
    ] {
        let message = refused(&mut agent, command);
        assert!(message.contains(names), "`{command}`: {message}");
    }
    // Nothing was set.
    assert_eq!(output(&mut agent, "rl -g apoptosis"), "none\n");
    assert_eq!(output(&mut agent, "rl -g trace"), "off\n");
}

#[test]
fn a_learned_value_is_saved_with_the_rule() {
    let mut agent = Agent::default();
    output(&mut agent, "srand 1");
    output(
        &mut agent,
        "source tests/commands/agents/rl-left-right.soar",
    );
    output(&mut agent, "rl --set learning on");
    output(&mut agent, "run");
    // As the official kernel learns it (tests/golden/commands/rl-left-right.txt).
    assert_eq!(
        output(&mut agent, "print --rl"),
        "left-right*rl*right  0.000000 0\nleft-right*rl*left  1.000000 -0.570000\n"
    );
    let text = output(&mut agent, "print left-right*rl*left");
    assert!(text.contains("(<s> ^operator <o> = -0.570000)"), "{text}");

    let mut fresh = Agent::default();
    output(&mut fresh, &text);
    assert_eq!(
        output(&mut fresh, "print --rl"),
        "left-right*rl*left  0.000000 -0.570000\n"
    );
}

#[test]
fn with_chunk_stop_off_only_rules_of_the_same_value_are_duplicates() {
    // As in 9.6: `f` loads; `Ignoring g because it is a duplicate of e`; with chunk-stop on
    // again, `Ignoring h because it is a duplicate of f`.
    let mut agent = Agent::default();
    output(&mut agent, "rl --set chunk-stop off");
    for rule in [
        "sp {e (state <s> ^operator <o> +) --> (<s> ^operator <o> = 1.5)}",
        "sp {f (state <s> ^operator <o> +) --> (<s> ^operator <o> = -3)}",
        "sp {g (state <s> ^operator <o> +) --> (<s> ^operator <o> = 1.5)}",
    ] {
        let _ = agent.source_text("t", rule);
    }
    agent.take_output();
    assert_eq!(
        output(&mut agent, "print --rl"),
        "f  0.000000 -3\ne  0.000000 1.500000\n"
    );
    output(&mut agent, "rl --set chunk-stop on");
    let _ = agent.source_text(
        "t",
        "sp {h (state <s> ^operator <o> +) --> (<s> ^operator <o> = 7)}",
    );
    agent.take_output();
    assert_eq!(
        output(&mut agent, "print --rl"),
        "f  0.000000 -3\ne  0.000000 1.500000\n"
    );
}

#[test]
fn rl_rules_that_differ_only_in_their_value_are_duplicates() {
    // As in 9.6: `Ignoring f because it is a duplicate of e`.
    let mut agent = Agent::default();
    output(
        &mut agent,
        "sp {e (state <s> ^operator <o> +) --> (<s> ^operator <o> = 1.5)}",
    );
    let _ = agent.source_text(
        "t",
        "sp {f (state <s> ^operator <o> +) --> (<s> ^operator <o> = -3)}",
    );
    agent.take_output();
    assert_eq!(output(&mut agent, "print --rl"), "e  0.000000 1.500000\n");
}

#[test]
fn a_template_with_a_negation_makes_rules_that_test_the_bound_values() {
    // 9.6 crashes on this template; rusoar makes each arm's rule, its negation testing the
    // arm's value.
    let mut agent = Agent::default();
    output(
        &mut agent,
        "sp {propose (state <s> ^superstate nil -^pulled) --> (<s> ^operator <o1> +, <o2> +) (<o1> ^arm 1) (<o2> ^arm 2)}
         sp {tpl :template (state <s> ^operator <o> + -^blocked <a>) (<o> ^arm <a>) --> (<s> ^operator <o> = 0)}
         sp {apply (state <s> ^operator.arm <a>) --> (<s> ^pulled <a>) (halt)}
         rl --set learning on
         run",
    );
    let one = output(&mut agent, "print rl*tpl*1");
    let two = output(&mut agent, "print rl*tpl*2");
    let (first, second) = if one.contains("^arm 1") {
        (one, two)
    } else {
        (two, one)
    };
    assert!(first.contains("-^blocked 1"), "{first}");
    assert!(
        second.contains("^arm 2") && second.contains("-^blocked 2"),
        "{second}"
    );
    assert_eq!(output(&mut agent, "print --rl").lines().count(), 2);
}
