//! Reinforcement learning where the command goldens (`tests/commands/rl*.cmds`, compared
//! with the official kernel) do not reach: apoptosis's modes over a longer run, the RL
//! trace after a clear in the middle of a run, and what an RL rule learned surviving a
//! save and a reload as its printed text.

use rusoar::Agent;

/// What a command printed, without the line break that ends a line of `sp`'s marks.
fn output(agent: &mut Agent, command: &str) -> String {
    agent
        .source_text("t", command)
        .unwrap_or_else(|e| panic!("`{command}`: {}", e.message()));
    agent.take_output().trim_start_matches('\n').to_string()
}

/// The chunks an agent holds, by name.
fn chunks(agent: &mut Agent) -> usize {
    output(agent, "print -c")
        .lines()
        .filter(|l| l.starts_with("chunk*"))
        .count()
}

#[test]
fn apoptosis_forgets_unused_chunks_and_rl_chunks_spares_the_others() {
    // 20 chunks, of which 3 keep firing (tests/commands/rl-apoptosis.cmds has the trace).
    let run = |mode: &str| {
        let mut agent = Agent::default();
        output(&mut agent, "chunk always");
        output(&mut agent, &format!("rl --set apoptosis {mode}"));
        output(
            &mut agent,
            "source tests/commands/agents/apoptosis-numbers.soar",
        );
        output(&mut agent, "run 200");
        chunks(&mut agent)
    };
    // As the official kernel keeps them (soar_sml 9.6.5): all but the 3 in use go under
    // `chunks`; `rl-chunks` forgets only RL rules, and these chunks are none.
    assert_eq!(run("chunks"), 3);
    assert_eq!(run("rl-chunks"), 20);
    assert_eq!(run("none"), 20);
}

#[test]
fn the_rl_trace_survives_a_clear_in_the_middle_of_a_run() {
    let mut agent = Agent::default();
    output(&mut agent, "srand 1");
    output(
        &mut agent,
        "source tests/commands/agents/rl-left-right.soar",
    );
    output(&mut agent, "rl --set learning on");
    output(&mut agent, "rl --set trace on");
    output(&mut agent, "run 2");
    output(&mut agent, "rl -t clear");
    output(&mut agent, "run");
    // The cleared tree is gone; the goals keep recording where nothing prints them until
    // `rl -t init` sends them back to a root (as soar_sml 9.6.5 prints it).
    assert_eq!(output(&mut agent, "rl -t"), "# RL Trace, Goal Level 1:\n");
    output(&mut agent, "rl -t init");
    output(&mut agent, "init-soar");
    output(&mut agent, "run");
    assert!(output(&mut agent, "rl -t").contains("^name initialize\\n- (2)"));
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
