//! The kernel's consistency checks hold after every decision of every test agent and
//! benchmark agent, and after `init-soar` (the checks: `Agent::check_invariants`).

use rusoar::Agent;

fn agents() -> Vec<std::path::PathBuf> {
    let mut files: Vec<_> = ["tests/agents", "tests/agents/long", "benches/agents"]
        .iter()
        .flat_map(|d| std::fs::read_dir(d).expect("the folder is readable"))
        .map(|e| e.expect("a folder entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "soar"))
        .collect();
    files.sort();
    files
}

#[test]
fn invariants_hold_after_every_decision() {
    for file in agents() {
        let mut agent = Agent::default();
        agent.execute("srand 1\nwatch 0").expect("settings");
        agent.source_file(&file).expect("the agent loads");
        for d in 0..150 {
            agent.execute("run 1").expect("a decision runs");
            if let Err(v) = agent.check_invariants() {
                panic!(
                    "{}: after decision {}:\n{}",
                    file.display(),
                    d + 1,
                    v.join("\n")
                );
            }
            if agent.is_halted() {
                break;
            }
        }
        agent.init_soar().expect("init-soar");
        if let Err(v) = agent.check_invariants() {
            panic!("{}: after init-soar:\n{}", file.display(), v.join("\n"));
        }
    }
}

/// Found by the `source_files` fuzz target: an object that only a binary preference's
/// referent names stays in working memory, as in 9.6 (`(B1 ^name b)` is still printed
/// there after the run), and counts as linked.
#[test]
fn an_object_named_only_by_a_preference_is_linked() {
    let mut agent = Agent::default();
    agent
        .execute(
            "sp {p (state <s> ^superstate nil) --> (<s> ^operator <a> +) \
             (<s> ^operator <a> > <b>) (<a> ^name a) (<b> ^name b)}\nwatch 0\nrun 3",
        )
        .expect("the agent runs");
    assert_eq!(agent.execute("print b1").expect("print"), "(B1 ^name b)\n");
    assert_eq!(agent.check_invariants(), Ok(()));
}

/// Found by the random-agent generator: an action on a variable bound to a constant
/// (`(<v1> ^b <v2>)` with `<v1>` = 3.5) fails, and the new object `<v2>` it would have
/// linked stays in working memory with no link, as in 9.6 (soar_sml 9.6.5 prints
/// `(V1 ^a y)` after the same decision): garbage collection only searches identifiers that
/// lose a link. Such an object is not reported as unlinked.
#[test]
fn an_object_whose_link_failed_stays_and_is_no_violation() {
    let mut agent = Agent::default();
    agent
        .execute(
            "sp {link (state <s> ^type state) -(<s> ^a z) (<s> ^a <v1>) -(<v1> ^b 1) \
             --> (<v1> ^c <v1>) (<v1> ^b <v2>) (<v2> ^a y)}\n\
             sp {number (state <s> ^type state) --> (<s> ^d 3.5) (<s> ^a (* 3.5 1))}\n\
             watch 0\nrun 1",
        )
        .expect("the agent runs");
    assert_eq!(agent.execute("print v1").expect("print"), "(V1 ^a y)\n");
    assert_eq!(agent.check_invariants(), Ok(()));
}

/// Found by the `production_parser` fuzz target: the object of a failed link that its own
/// structure points back at (`(<v2> ^a <v3>) (<v3> ^c <v2>)`) stays too, as in 9.6
/// (soar_sml 9.6.5 prints `(V2 ^c V1)` after the same decision), and is no violation.
#[test]
fn a_cycle_whose_link_failed_stays_and_is_no_violation() {
    let mut agent = Agent::default();
    agent
        .execute(
            "sp {link (state <s> ^type state) -(<s> ^a z) (<s> ^a <v1>) -(<v1> ^b 1) \
             --> (<v1> ^b <v2>) (<v2> ^a <v3>) (<v3> ^c <v2>)}\n\
             sp {number (state <s> ^type state) --> (<s> ^a (* 3.5 1))}\n\
             watch 0\nrun 1",
        )
        .expect("the agent runs");
    assert_eq!(agent.execute("print v2").expect("print"), "(V2 ^c V1)\n");
    assert_eq!(agent.check_invariants(), Ok(()));
}

/// Found by the `command_line` fuzz target: `wm remove` of the WME that alone linked a
/// substate's `^epmem` object left the object's WMEs in working memory, linked to no goal.
/// 9.6 collects the object at once (`soar_sml` 9.6.5: `print e3` then says there is no
/// identifier E3; command golden `wm-remove-link`).
#[test]
fn removing_the_link_of_an_object_takes_the_object_with_it() {
    let mut agent = Agent::default();
    agent
        .execute("wm add s1 color red\nwatch 0\nrun 300")
        .expect("the agent runs");
    let link = agent.execute("print --internal s72").expect("print");
    let tt = link
        .lines()
        .find(|l| l.contains("^epmem E72"))
        .and_then(|l| l.trim_start_matches('(').split(':').next())
        .expect("S72 has its ^epmem link")
        .to_string();
    agent
        .execute(&format!("wm remove {tt}"))
        .expect("wm remove");
    assert_eq!(agent.check_invariants(), Ok(()));
    assert_eq!(
        agent.execute("print e72").expect("print"),
        "There is no identifier E72.\n"
    );
}

/// An identifier garbage collection took is gone: `wm add` on it is refused, as 9.6
/// refuses it, rather than hanging a WME on an unlinked object (a fuzzed command script).
#[test]
fn wm_add_refuses_an_identifier_that_was_collected() {
    let mut agent = Agent::default();
    agent
        .execute(
            "sp {top*init (state <s> ^superstate nil -^a) --> (<s> ^a 2 ^obj <x>) (<x> ^name thing)}\n\
             run 1",
        )
        .expect("the agent runs");
    assert_eq!(agent.check_invariants(), Ok(()));
    let err = agent.execute("wm add x1 color red").unwrap_err();
    assert_eq!(err.message(), "Invalid identifier");
    // As a value it links the object again, as in 9.6.
    agent.execute("wm add s1 color x1").expect("wm add");
    assert_eq!(agent.check_invariants(), Ok(()));
}

/// `wm remove` of a WME a rule supports takes it out of its slot as well as out of working
/// memory, and a later change to the slot makes it again, as 9.6 does (a fuzzed command
/// script left the slot showing a WME that was gone).
#[test]
fn wm_remove_of_a_supported_wme_leaves_its_slot_agreeing() {
    let mut agent = Agent::default();
    agent
        .execute(
            "sp {init (state <s> ^superstate nil) --> (<s> ^a b ^a c)}\n\
             sp {op (state <s> ^superstate nil) --> (<s> ^operator <o> +) (<o> ^name x)}\n\
             sp {ap (state <s> ^operator.name x) --> (<s> ^a d)}\n\
             run 2 -p",
        )
        .expect("the agent runs");
    agent.execute("wm remove 16").expect("wm remove");
    assert_eq!(agent.check_invariants(), Ok(()));
    agent.execute("run 3 -p").expect("the agent runs");
    assert_eq!(agent.check_invariants(), Ok(()));
    let printed = agent.execute("print -i s1").expect("print");
    assert!(printed.contains("(19: S1 ^a b)"), "{printed}");
    assert!(printed.contains("(20: S1 ^a d)"), "{printed}");
}
