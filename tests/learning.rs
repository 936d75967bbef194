//! Chunking, beyond the goldens of tests/conformance.rs: the embedded stdlib loads by name,
//! and a learning agent's second run after `init-soar` uses its chunks.

use rusoar::Agent;

fn run(interp: &mut Agent, cmd: &str) -> String {
    interp
        .source_text("<learning>", cmd)
        .unwrap_or_else(|d| panic!("`{cmd}` failed: {}", d.message()));
    interp.take_output()
}

#[test]
fn stdlib_selection_loads_by_name() {
    let mut interp = Agent::default();
    let out = run(&mut interp, "source <stdlib>/selection.soar");
    assert!(out.contains("Total: 11 productions sourced."), "{out}");
    let rules = run(&mut interp, "print --all");
    assert!(
        rules.contains("selection*propose*evaluate-operator"),
        "{rules}"
    );
}

#[test]
fn lookahead_chunks_remove_the_tie_on_the_second_run() {
    let mut interp = Agent::default();
    interp.set_working_directory(env!("CARGO_MANIFEST_DIR"));
    run(&mut interp, "srand 1");
    run(&mut interp, "source tests/agents/learn-lookahead.soar");
    let first = run(&mut interp, "run 100");
    assert!(first.contains("(operator tie)"), "{first}");
    assert!(first.contains("2 new rules learned."), "{first}");
    let chunks = run(&mut interp, "print --chunks");
    assert_eq!(
        chunks.lines().filter(|l| l.starts_with("chunk*")).count(),
        2
    );
    run(&mut interp, "init-soar");
    let second = run(&mut interp, "run 100");
    assert!(!second.contains("tie"), "{second}");
    assert!(
        second.contains("--> 2 decision cycles executed."),
        "{second}"
    );
    // The chunk that made the tie go tests the operator's proposal and the dead end.
    let rule = run(
        &mut interp,
        "print chunk*selection*compare*failure*worst*t5-2",
    );
    assert!(rule.contains("^operator <o1> +"), "{rule}");
    assert!(rule.contains("^dead-end <t1>"), "{rule}");
}

#[test]
fn learning_off_gives_justifications_that_keep_i_supported_results() {
    let mut interp = Agent::default();
    interp.set_working_directory(env!("CARGO_MANIFEST_DIR"));
    run(&mut interp, "source tests/agents/learn-justification.soar");
    let out = run(&mut interp, "run 100");
    assert!(out.contains("isup kept by its justification"), "{out}");
    let js = run(&mut interp, "print --justifications");
    assert_eq!(js, "justify3 \njustify1 \n");
    assert_eq!(run(&mut interp, "print --chunks"), "");
}

/// `chunk` after a run and after `init-soar`, as the official kernel printed it for the
/// same agent and commands (9.6 resets the counts at `init-soar`).
#[test]
fn chunk_summary_counts_since_init_soar() {
    let mut interp = Agent::default();
    interp.set_working_directory(env!("CARGO_MANIFEST_DIR"));
    run(&mut interp, "source tests/agents/learn-lookahead.soar");
    run(&mut interp, "run 100");
    let rows = |s: &str| -> Vec<String> {
        s.lines()
            .filter(|l| {
                l.starts_with("Chunks") || l.starts_with("Justif") || l.starts_with("Substates")
            })
            .map(str::to_string)
            .collect()
    };
    let after_run = run(&mut interp, "chunk");
    assert!(after_run.contains("When Soar will learn rules                       always\n"));
    assert_eq!(
        rows(&after_run),
        [
            "Chunks learned                                        2",
            "Justifications learned                                0",
            "Substates analyzed                                    2"
        ]
    );
    run(&mut interp, "init-soar");
    run(&mut interp, "run 100");
    assert!(rows(&run(&mut interp, "chunk"))
        .iter()
        .all(|r| r.ends_with(" 0")));
}

/// `chunk ?` lists the settings with the current learning mode in capitals and the limits'
/// values right-aligned (text from the official kernel after the same commands).
#[test]
fn chunk_settings_listing() {
    let mut interp = Agent::default();
    run(&mut interp, "chunk always");
    run(&mut interp, "chunk max-dupes 12");
    run(&mut interp, "chunk max-chunks 7");
    let out = run(&mut interp, "chunk ?");
    assert!(out.contains(
        "\nALWAYS | never | only | except                        When Soar will learn new rules\n"
    ));
    assert!(out.contains(
        "\nmax-chunks                                  7         Maximum chunks that can be learned (per phase)\n"
    ));
    assert!(out.contains(
        "\nmax-dupes                                  12         Maximum duplicate chunks (per rule, per phase)\n"
    ));
    assert!(out.ends_with("For a detailed explanation of these settings:         help chunk\n"));
}

/// 9.6 holds justifications in its rete, negations included: a result whose justification
/// negates a superstate WME goes when that WME appears (checked on soar-sml 9.6.5), and
/// one behind a conjunctive negation goes when the conjunction comes to match.
#[test]
fn justification_retracts_when_its_negated_superstate_wme_appears() {
    let mut interp = Agent::default();
    run(
        &mut interp,
        "sp {init (state <s> ^superstate nil) --> (<s> ^a 1)}\n\
         sp {sub*neg (state <s> ^superstate <ss>) (<ss> ^a 1 -^b 1) --> (<ss> ^r x)}\n\
         sp {sub*ncc (state <s> ^superstate <ss>) (<ss> ^a 1) \
             -{(<ss> ^c <c>) (<c> ^d 1)} --> (<ss> ^t y)}",
    );
    run(&mut interp, "run 2");
    let before = run(&mut interp, "print s1");
    assert!(
        before.contains("^r x") && before.contains("^t y"),
        "{before}"
    );
    run(&mut interp, "wm add S1 b 1");
    run(&mut interp, "wm add S1 c *");
    run(&mut interp, "run 1");
    let after_b = run(&mut interp, "print s1");
    assert!(!after_b.contains("^r x"), "{after_b}");
    assert!(
        after_b.contains("^t y"),
        "the conjunction does not match yet: {after_b}"
    );
    let c = after_b
        .split("^c ")
        .nth(1)
        .and_then(|rest| rest.split_whitespace().next())
        .expect("S1 ^c");
    run(&mut interp, &format!("wm add {c} d 1"));
    run(&mut interp, "run 1");
    let after_d = run(&mut interp, "print s1");
    assert!(!after_d.contains("^t y"), "{after_d}");
}

/// At trace level 5, 9.6 lists a removed substate's standing results as removed, oldest
/// first, before the substate's `<=WM:` lines (soar-sml 9.6.5's trace of this agent).
#[test]
fn removed_substate_lists_its_results_at_trace_5() {
    let mut interp = Agent::default();
    interp.set_working_directory(env!("CARGO_MANIFEST_DIR"));
    run(&mut interp, "srand 1");
    run(
        &mut interp,
        "source tests/agents/justification-negation.soar",
    );
    run(&mut interp, "trace 5");
    let out = run(&mut interp, "run 50");
    let expected = "Replacing it with....\n\
                    - (S1 ^r x +) [level 2] (sub*result*negation)\n\
                    - (S1 ^t y +) [level 2] (sub*result*ncc)\n\
                    <=WM: ";
    assert!(out.contains(expected), "{out}");
}

/// Justifications named like chunks count from 1 again in each run's decisions after
/// `init-soar` (9.6 prints `justify*sub*res*t2-3-1` in the second run of `learn-only`).
#[test]
fn justification_names_count_again_after_init_soar() {
    let mut interp = Agent::default();
    interp.set_working_directory(env!("CARGO_MANIFEST_DIR"));
    run(&mut interp, "srand 1");
    run(&mut interp, "source tests/agents/learn-only.soar");
    run(&mut interp, "watch 0");
    run(&mut interp, "run 100");
    run(&mut interp, "init-soar");
    run(&mut interp, "watch 5");
    let second = run(&mut interp, "run 50");
    assert!(second.contains("(justify*sub*res*t2-3-1)"), "{second}");
    assert!(second.contains("(justify*sub*neg*t2-3-2)"), "{second}");
}

/// `trace -L 2` prints each justification as 9.6 does (the texts below are the official
/// kernel's): its conditions last found first, `state` on each state's first condition;
/// with learning on (`chunk only` here) the rule's relational tests and RHS calls are
/// kept over the symbols, with learning off they are not.
#[test]
fn justifications_print_as_the_official_kernel_prints_them() {
    let text = |agent: &str, after: &str| {
        let mut interp = Agent::default();
        interp.set_working_directory(env!("CARGO_MANIFEST_DIR"));
        run(&mut interp, "srand 1");
        run(&mut interp, &format!("source tests/agents/{agent}.soar"));
        run(&mut interp, after);
        run(&mut interp, "trace -L 2");
        run(&mut interp, "run 50")
    };
    let only = text("learn-only", "echo");
    for want in [
        "sp {justify*sub*res*t3-1\n    :justification ;# not reloadable\n    (state S1 ^num3 2 ^operator O1)\n    (O1 ^name go)\n    -->\n    (S1 ^res 2)\n}",
        "sp {justify*sub*neg*t3-2\n    :justification ;# not reloadable\n    (O1 ^name go)\n    (state S1 ^operator O1 -^prefix object)\n    -->\n    (S1 ^res2 yes)\n}",
    ] {
        assert!(only.contains(want), "{only}");
    }
    let off = text("learn-justification", "echo");
    let want = "sp {justify3\n    :justification ;# not reloadable\n    (O1 ^name go)\n    (state S1 ^operator O1)\n    -->\n    (S1 ^done yes)\n}";
    assert!(off.contains(want), "{off}");
    let conj = text("learn-conjunctions", "chunk only");
    for want in [
        "    (state S1 ^num3 { << 2 3 >> 2 } ^operator O1)\n",
        "    (state S1 ^a { > 1 <> 3 2 } ^b { < 9 3 } ^c { << 4 5 >> >= 1 <=> 4 4 }\n          ^d 4 ^operator O1)\n    (O1 ^name go)\n    -->\n    (S1 ^res2 (+ 2 3 4 4))\n}",
    ] {
        assert!(conj.contains(want), "{conj}");
    }
}
