//! Ceilings on a run's growth (`limits`, `Agent::set_limits`): a run that passes one stops
//! with a message and `StopReason::CeilingReached`, and the agent stays usable.

use rusoar::{Agent, Limits, RunUnit, StopReason};

/// Each elaboration cycle adds a thing, for ever (a thing's rule adds the next).
const GROWING: &str = "sp {start (state <s> ^superstate nil) --> (<s> ^thing <t>)}
                       sp {grow (state <s> ^thing <t>) -(<t> ^done) --> (<s> ^thing <n>) (<t> ^done yes)}";

/// Every pair of things is a match: the matcher's partial matches grow with the square of
/// working memory.
const PAIRS: &str = "sp {start (state <s> ^superstate nil) --> (<s> ^thing <t>)}
                     sp {more (state <s> ^thing <t>) -(<t> ^next) --> (<t> ^next <n>) (<s> ^thing <n>)}
                     sp {pair (state <s> ^thing <a> ^thing <b>) --> (<s> ^paired yes)}";

fn growing_agent(rules: &str) -> Agent {
    let mut agent = Agent::default();
    agent.execute(rules).unwrap();
    agent.execute("soar max-elaborations 100000").unwrap();
    agent
}

#[test]
fn a_run_past_its_wme_ceiling_stops_with_a_message_and_can_go_on() {
    let mut agent = growing_agent(GROWING);
    agent.set_limits(Limits {
        wmes: 500,
        ..Limits::default()
    });
    let r = agent.run(1, RunUnit::Forever).unwrap();
    assert_eq!(r.stop, StopReason::CeilingReached);
    let held = agent.wme_count();
    assert!((501..520).contains(&held), "{held} WMEs");
    let trace = agent.take_output();
    assert!(
        trace.contains(&format!(
            "Stopped: working memory holds {held} WMEs, more than its ceiling of 500"
        )),
        "{trace}"
    );
    // Still past it: the next run stops at once.
    let again = agent.run(5, RunUnit::Decisions).unwrap();
    assert_eq!(
        (again.stop, agent.wme_count()),
        (StopReason::CeilingReached, held)
    );
    // Raised, the run goes on from where it stopped.
    agent.set_limits(Limits {
        wmes: 1000,
        ..Limits::default()
    });
    let on = agent.run(1, RunUnit::Forever).unwrap();
    assert_eq!(on.stop, StopReason::CeilingReached);
    assert!(agent.wme_count() > 1000);
    agent.execute("print --depth 1 s1").unwrap();
}

#[test]
fn a_run_past_its_token_ceiling_stops() {
    let mut agent = growing_agent(PAIRS);
    agent.execute("limits --tokens 2000").unwrap();
    let r = agent.run(1, RunUnit::Forever).unwrap();
    assert_eq!(r.stop, StopReason::CeilingReached);
    let trace = agent.take_output();
    assert!(
        trace.contains("partial matches, more than its ceiling of 2000 (limits --tokens)"),
        "{trace}"
    );
    // Far from the quadratic growth it would have without the ceiling.
    assert!(agent.wme_count() < 200, "{} WMEs", agent.wme_count());
}

#[test]
fn a_run_that_learns_its_ceiling_of_chunks_stops() {
    // The look-ahead agent learns two chunks in its first six decisions.
    let mut agent = Agent::default();
    agent
        .execute("source tests/agents/learn-lookahead.soar")
        .unwrap();
    agent.set_limits(Limits {
        chunks: 1,
        ..Limits::default()
    });
    let r = agent.run(30, RunUnit::Decisions).unwrap();
    assert_eq!(r.stop, StopReason::CeilingReached);
    let trace = agent.take_output();
    assert!(
        trace.contains("Stopped: this run learned 1 chunk, its ceiling (limits --chunks)."),
        "{trace}"
    );
    assert!(r.decisions < 6, "{} decisions", r.decisions);
    // A new run counts its own chunks: the second is learned, and the run stops again.
    let again = agent.run(30, RunUnit::Decisions).unwrap();
    assert_eq!(again.stop, StopReason::CeilingReached);
    assert!(agent.execute("print -c").unwrap().matches("chunk*").count() == 2);
}

#[test]
fn the_command_lists_sets_and_refuses_bad_numbers() {
    let mut agent = Agent::default();
    let listing = agent.execute("limits").unwrap();
    assert!(listing.contains("wmes                  none"), "{listing}");
    agent.execute("limits -w 10 --tokens 20 -c 3").unwrap();
    assert_eq!(
        agent.limits(),
        Limits {
            wmes: 10,
            tokens: 20,
            preferences: 0,
            chunks: 3
        }
    );
    let err = agent.execute("limits --wmes lots").unwrap_err().to_string();
    assert!(
        err.contains("limits --wmes takes a whole number of 0 or more, not 'lots'."),
        "{err}"
    );
    assert!(agent.execute("limits 5").is_err());
    agent.execute("limits --wmes 0").unwrap();
    assert_eq!(agent.limits().wmes, 0);
}

/// Ctrl-C while a file is sourced (here a rule sets the interrupt flag during a run in the
/// file): the run stops, the file stops after that command with an error naming it, what
/// was loaded stays loaded, and the agent runs on.
#[test]
fn an_interrupt_while_sourcing_stops_the_file_and_keeps_the_agent_usable() {
    let dir = std::env::temp_dir().join(format!("rusoar-interrupt-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("inner.soar"),
        "sp {press (state <s> ^superstate nil) --> (ctrl-c)}\nrun 5\nsp {later (state <s> ^superstate nil) --> (<s> ^later yes)}\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("main.soar"),
        "source inner.soar\nsp {last (state <s> ^superstate nil) --> (<s> ^last yes)}\n",
    )
    .unwrap();
    let mut agent = Agent::default();
    let flag = agent.interrupt_flag();
    agent.register_rhs_function("ctrl-c", move |_, _| {
        flag.store(true, std::sync::atomic::Ordering::SeqCst);
        Ok(rusoar::Value::Str(String::new()))
    });
    let err = agent
        .source_file(dir.join("main.soar"))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("Interrupted: the rest of this file is not sourced."),
        "{err}"
    );
    let rules = agent.execute("print -a").unwrap();
    assert!(
        rules.contains("press") && !rules.contains("later") && !rules.contains("last"),
        "{rules}"
    );
    // The flag was taken: the agent runs on.
    let r = agent.run(2, RunUnit::Decisions).unwrap();
    assert_eq!(r.stop, StopReason::LimitReached);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The rules of a fuzzed command line: an application whose every firing makes two counts
/// where it rejects one, and rejects the same `^colour` and `^recent` WMEs as every other.
const DOUBLING_APPLICATION: &str = "sp {propose*init (state <s> ^superstate nil -^count) --> (<s> ^operator <o> + =) (<o> ^name init)}
     sp {apply*init (state <s> ^operator.name init) --> (<s> ^count 1 ^colour 0 ^recent <r>) (<r> ^value 0)}
     sp {propose*count (state <s> ^count {<c> < 3000}) --> (<s> ^operator <o> + =) (<o> ^name count)}
     sp {apply*count (state <s> ^operator.name count ^count <c> ^colour <k> ^recent <r>)
        --> (<s> ^count <c> - ^count *(+ <c> 1) ^colour <k> - ^colour (mod (+ <c> 1) 7)
             ^recent <r> - ^recent <n>)
            (<n> ^value (+ <c> 1) ^previous D<r>)}";

/// A fuzzed command line (`fuzz/` `command_line`, a timeout): an application whose every
/// firing makes two counts where it removes one, so that its matches double with each
/// elaboration cycle of one apply phase. Each later `run` went one cycle further before its
/// interrupt was looked at, twice the work of the last, past any time limit. Under a WME
/// ceiling the first run stops at it, and a later run stops before it does anything.
#[test]
fn an_application_that_doubles_each_cycle_stops_at_its_ceiling() {
    let mut agent = growing_agent(DOUBLING_APPLICATION);
    agent.execute("srand 2").unwrap();
    agent.execute("soar max-elaborations 100").unwrap();
    agent.set_limits(Limits {
        wmes: 20_000,
        ..Limits::default()
    });
    let started = std::time::Instant::now();
    let r = agent.run(6, RunUnit::Decisions).unwrap();
    assert_eq!(r.stop, StopReason::CeilingReached);
    let held = agent.wme_count();
    assert!((20_000..60_000).contains(&held), "{held} WMEs");
    for _ in 0..3 {
        let again = agent.run(6, RunUnit::Decisions).unwrap();
        assert_eq!((again.stop, again.firings), (StopReason::CeilingReached, 0));
    }
    assert_eq!(agent.wme_count(), held);
    assert!(
        started.elapsed().as_secs_f64() < 5.0,
        "{:?}",
        started.elapsed()
    );
}

/// The same fuzzed agent traced at level 5: every firing of the last cycle rejects the same
/// `^colour` and `^recent` WMEs, whose preferences go once, so the trace lists each removal
/// once (it listed all of them again for every firing, 56 million lines, as the square of
/// the firings).
#[test]
fn a_wme_many_firings_reject_has_its_removals_traced_once() {
    let mut agent = growing_agent(DOUBLING_APPLICATION);
    agent.execute("srand 2").unwrap();
    agent.execute("watch 5").unwrap();
    agent.set_limits(Limits {
        wmes: 20_000,
        ..Limits::default()
    });
    let r = agent.run(6, RunUnit::Decisions).unwrap();
    assert_eq!(r.stop, StopReason::CeilingReached);
    let text = agent.take_output();
    let removals = text.lines().filter(|l| l.starts_with("- ")).count();
    let firings = text.lines().filter(|l| l.starts_with("Firing ")).count();
    assert!(
        removals <= 4 * firings,
        "{removals} removals for {firings} firings"
    );
}

/// An agent with `rule`, under the ceilings the fuzz targets run with (`fuzz/src/lib.rs`).
fn under_fuzz_ceilings(rule: &str) -> Agent {
    let mut agent = Agent::new("fuzzed");
    agent.execute(rule).unwrap();
    agent.set_limits(Limits {
        wmes: 5_000,
        tokens: 10_000,
        preferences: 10_000,
        ..Limits::default()
    });
    agent
}

/// A fuzzed rule (`fuzz/` `production_parser`, a timeout under the fuzzer's
/// instrumentation): a condition not linked to a state matches every `^io` WME, and each
/// firing on each state makes one more, so its matches grow with the square of working
/// memory (9.6 runs away on it too: `soar_sml` 9.6.5 had not finished `run 3` after 30
/// s). Under the fuzzer's ceilings it stops at its partial matches at once.
#[test]
fn a_rule_on_every_io_wme_of_every_state_stops_at_its_ceiling() {
    let mut agent = under_fuzz_ceilings(
        "sp {io*everywhere (<ss> ^io <io>) (state <s> ^superstate <x>) --> (<s> ^io <n>)}",
    );
    let started = std::time::Instant::now();
    let r = agent.run(3, RunUnit::Decisions).unwrap();
    assert_eq!(r.stop, StopReason::CeilingReached);
    agent.check_invariants().unwrap();
    assert!(
        started.elapsed().as_secs_f64() < 2.0,
        "{:?}",
        started.elapsed()
    );
}

/// Another fuzzed rule (`production_parser`, a timeout under instrumentation): a condition
/// with an identifier alone, `(<nss>)`, matches every WME, and each firing makes one more on
/// the superstate. Under the fuzzer's ceilings it stops at its WMEs.
#[test]
fn a_rule_on_every_wme_stops_at_its_ceiling() {
    let mut agent = under_fuzz_ceilings(
        "sp {every*wme (state <s> ^superstate <ss>) (<nss>) (<x> -^p.3) --> (<ss> ^res3 <n>)}",
    );
    let r = agent.run(3, RunUnit::Decisions).unwrap();
    assert_eq!(r.stop, StopReason::CeilingReached);
    assert!(agent.wme_count() < 6_000, "{} WMEs", agent.wme_count());
    agent.check_invariants().unwrap();
}

/// A fuzzed rule (`production_parser`, out of memory): each firing puts a new object on
/// the superstate under an attribute the rule's conditions join on itself, so one cycle's
/// firings grow with the square of the objects, and the next cycle's additions made
/// hundreds of millions of partial matches before the cycle ended (1.8 GB in 11 s). The
/// preferences' ceiling stops the cycle before its changes reach the matcher.
#[test]
fn firings_past_the_preference_ceiling_stop_before_their_changes_are_matched() {
    let mut agent = under_fuzz_ceilings(
        "sp {square (state <s> ^superstate <ss>) (<ss> ^<v>) (<ss> ^<v> -^missing)
             --> (<ss> ^res1 <v> ^th-tce 500 ^min-position.error 10 0)}",
    );
    let started = std::time::Instant::now();
    let r = agent.run(3, RunUnit::Decisions).unwrap();
    assert_eq!(r.stop, StopReason::CeilingReached);
    assert!(agent.wme_count() < 5_000, "{} WMEs", agent.wme_count());
    agent.check_invariants().unwrap();
    assert!(
        started.elapsed().as_secs_f64() < 2.0,
        "{:?}",
        started.elapsed()
    );
    // Still past it: the next run stops at once, and the agent answers.
    let again = agent.run(1, RunUnit::Decisions).unwrap();
    assert_eq!(again.stop, StopReason::CeilingReached);
    agent.execute("print --depth 1 s1").unwrap();
}

/// Another fuzzed rule (`production_parser`, a timeout under instrumentation): a condition
/// with no test but its identifier, `(<ss> ^<v> -^missing)`, joined with every WME, so the
/// additions of one phase made partial matches as the square of their number (323,193
/// from 568 WMEs) before the phase ended. The rest of the batch waits once the partial
/// matches pass their ceiling, and the run stops there.
#[test]
fn one_phases_additions_stop_at_the_partial_match_ceiling() {
    let mut agent = under_fuzz_ceilings(
        "sp {cross (state <s> ^superstate <ss>) (<x> ^<v> -^missing)
             --> (<ss> ^res2 <v> ^th-tce 500 ^min-position.error 10 0 ^max 1000)}",
    );
    let r = agent.run(3, RunUnit::Decisions).unwrap();
    assert_eq!(r.stop, StopReason::CeilingReached);
    agent.check_invariants().unwrap();
    let trace = agent.take_output();
    let held: u64 = trace
        .split("the matcher holds ")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no partial-match ceiling in {trace}"));
    assert!(held < 20_000, "{held} partial matches");
    // Raised, the run goes on and the waiting WMEs are made.
    let held = agent.wme_count();
    agent.set_limits(Limits::default());
    agent.execute("soar max-elaborations 2").unwrap();
    agent.run(1, RunUnit::Elaborations).unwrap();
    agent.check_invariants().unwrap();
    assert!(agent.wme_count() >= held, "{} < {held}", agent.wme_count());
}

/// A fuzzed rule (`production_parser`, out of memory at load): conditions that test
/// nothing but an identifier, `(<a>)`, each match every WME, so matching the new rule
/// against working memory made their cross product (7.8 million partial matches from 13
/// WMEs, 2 GB, before any run). Under a partial-match ceiling such a rule is refused with
/// a message, and the agent goes on without it.
#[test]
fn a_rule_whose_first_matches_pass_the_ceiling_is_refused() {
    let rule =
        "sp {cross (state <s> ^superstate nil) (<a>) (<b>) (<c>) (<d>) (<e>) --> (<s> ^x y)}";
    let mut agent = Agent::new("fuzzed");
    agent.set_limits(Limits {
        tokens: 10_000,
        ..Limits::default()
    });
    let started = std::time::Instant::now();
    let refused = agent.execute(rule).unwrap_err().to_string();
    assert!(
        refused.contains("not added") && refused.contains("(limits --tokens)"),
        "{refused}"
    );
    assert!(
        started.elapsed().as_secs_f64() < 2.0,
        "{:?}",
        started.elapsed()
    );
    let shown = agent
        .execute("print cross")
        .unwrap_or_else(|e| e.to_string());
    assert!(shown.contains("No production named cross"), "{shown}");
    agent.check_invariants().unwrap();
    agent.run(2, RunUnit::Decisions).unwrap();
    agent.check_invariants().unwrap();
    // Without the ceiling the same rule loads (and matches).
    let mut free = Agent::new("free");
    free.execute(rule).unwrap();
}

/// Every pair of things asks for the same WME: preferences pile up with the square of the
/// things while working memory barely grows, and the preferences ceiling stops the run.
#[test]
fn a_run_past_its_preference_ceiling_stops() {
    let mut agent = growing_agent(PAIRS);
    agent.execute("limits --preferences 3000").unwrap();
    let r = agent.run(1, RunUnit::Forever).unwrap();
    assert_eq!(r.stop, StopReason::CeilingReached);
    let trace = agent.take_output();
    assert!(
        trace.contains("preferences, more than its ceiling of 3000 (limits --preferences)"),
        "{trace}"
    );
    assert!(agent.wme_count() < 300, "{} WMEs", agent.wme_count());
    let listing = agent.execute("limits").unwrap();
    assert!(listing.contains("preferences           3000"), "{listing}");
}

/// Another fuzzed rule of the same shape (`production_parser`, a timeout under
/// instrumentation): its first cycle alone made 8,472 firings and 101,664 preferences.
/// The cycle stops firing once its preferences pass their ceiling.
#[test]
fn one_cycles_firings_stop_at_the_preference_ceiling() {
    let mut agent = under_fuzz_ceilings(
        "sp {square (state <s> ^superstate <ss>) (<ss> ^<v>) (<ss> ^<v> -^missing)
             --> (<ss> ^res2 <v> ^th-tce 500 ^min-position.error 10 0 ^a 1 ^b 2 ^c 3
                  ^d 4 ^e 5 ^f 6 ^g 7 ^h 8)}",
    );
    let r = agent.run(3, RunUnit::Decisions).unwrap();
    assert_eq!(r.stop, StopReason::CeilingReached);
    assert!(r.firings < 2_000, "{} firings", r.firings);
    agent.check_invariants().unwrap();
    let again = agent.run(1, RunUnit::Decisions).unwrap();
    assert_eq!(again.stop, StopReason::CeilingReached);
}

/// A fuzzed command line (`fuzz/` `command_line`, a timeout): an agent whose operator slot
/// gains a proposal each decision. The preference semantics looked each candidate up in
/// all of the slot's preferences, time quadratic in their number for each decision (6.5 s
/// for the fuzzed input); a large slot is indexed now.
#[test]
fn a_slot_that_grows_each_decision_decides_in_linear_time() {
    let mut agent = Agent::default();
    agent
        .execute(
            "sp {init :o-support (state <s> ^superstate nil -^count) --> (<s> ^count 1 ^step 0)}\n\
             sp {propose (state <s> ^step <n>) --> (<s> ^operator <o> + =) (<o> ^n <n>)}\n\
             sp {apply (state <s> ^operator <o> ^count <c>)\n\
                 --> (<s> ^count <c> - ^count (+ <c> 1) ^step <c>)}\n\
             watch 0",
        )
        .unwrap();
    let started = std::time::Instant::now();
    agent.run(2000, RunUnit::Decisions).unwrap();
    // 2,001 values of `^step`, each with its proposal's operator.
    assert!(agent.wme_count() > 6000, "{} WMEs", agent.wme_count());
    assert!(
        started.elapsed().as_secs_f64() < 5.0,
        "{:?}",
        started.elapsed()
    );
}
