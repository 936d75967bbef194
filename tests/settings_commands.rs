//! `decide` and `chunk` settings as agents write them, with the official kernel's texts
//! (soar-sml 9.6.5 printed each expected result for the same command on a fresh agent).

use rusoar::Agent;

fn learn_mode(agent: &mut Agent) -> String {
    let summary = agent.execute("chunk").unwrap();
    let line = summary
        .lines()
        .find(|l| l.starts_with("When Soar will learn rules"))
        .unwrap_or_default();
    line.split_whitespace()
        .last()
        .unwrap_or_default()
        .to_string()
}

#[test]
fn exploration_parameters_are_read_set_and_checked() {
    let mut a = Agent::default();
    let run = |a: &mut Agent, c: &str| a.execute(c);
    assert_eq!(
        run(&mut a, "decide indifferent-selection --epsilon").unwrap(),
        "0.1\n"
    );
    assert_eq!(
        run(&mut a, "decide indifferent-selection -t").unwrap(),
        "25\n"
    );
    assert_eq!(
        run(&mut a, "decide indifferent-selection --epsilon 0.3").unwrap(),
        ""
    );
    assert_eq!(
        run(&mut a, "decide indifferent-selection -e").unwrap(),
        "0.3\n"
    );
    assert_eq!(
        run(&mut a, "decide indifferent-selection --temperature 2").unwrap(),
        ""
    );
    assert_eq!(
        run(&mut a, "decide indifferent-selection -t").unwrap(),
        "2\n"
    );
    for bad in ["--epsilon 2", "--temperature 0", "--temperature x"] {
        let e = run(&mut a, &format!("decide indifferent-selection {bad}")).unwrap_err();
        assert_eq!(e.message(), "Invalid parameter value.", "{bad}");
    }
    let e = run(
        &mut a,
        "decide indifferent-selection --epsilon-greedy --epsilon 0.2",
    )
    .unwrap_err();
    assert_eq!(
        e.message(),
        "indifferent-selection takes only one option at a time."
    );
    assert_eq!(
        run(&mut a, "decide indifferent-selection --boltzmann").unwrap(),
        ""
    );
    assert_eq!(
        run(&mut a, "decide indifferent-selection").unwrap(),
        "boltzmann\n"
    );
    assert_eq!(
        run(&mut a, "decide set-random-seed 5").unwrap(),
        "Random number generator seed set to 5\n"
    );
}

#[test]
fn chunk_accepts_the_spellings_9_6_accepts() {
    let mut a = Agent::default();
    assert_eq!(
        a.execute("chunk flagged").unwrap(),
        "Learns rules in states: flagged\n\n"
    );
    assert_eq!(learn_mode(&mut a), "only");
    assert_eq!(
        a.execute("chunk unflagged").unwrap(),
        "Learns rules in states: unflagged\n\n"
    );
    assert_eq!(learn_mode(&mut a), "except");
    // 9.6 prints the summary for `chunk --on` and changes nothing; rusoar warns too.
    let out = a.execute("chunk --on").unwrap();
    assert!(out.contains("Explanation-Based Chunking Summary"), "{out}");
    assert!(out.contains("changes nothing in Soar 9.6"), "{out}");
    assert_eq!(learn_mode(&mut a), "except");
}

/// `excise` by kind and `ls` with an argument, as soar-sml 9.6.5 answers them.
#[test]
fn excise_by_kind_and_ls_take_9_6s_arguments() {
    let mut a = Agent::default();
    a.execute(
        "sp {a (state <s> ^superstate nil) --> (<s> ^x 1)}
         sp {b (state <s> ^superstate nil) --> (<s> ^y 1)}",
    )
    .unwrap();
    // (The `*` marks of `sp` end their line first.)
    assert_eq!(
        a.execute("excise --chunks").unwrap().trim_start(),
        "0 productions excised.\n"
    );
    assert_eq!(a.execute("excise -d").unwrap(), "0 productions excised.\n");
    assert_eq!(a.production_count(), 2);
    assert_eq!(a.execute("excise -u").unwrap(), "2 productions excised.\n");
    assert_eq!(a.production_count(), 0);
    assert_eq!(
        a.execute("ls some-dir").unwrap_err().message(),
        "Syntax: ls"
    );
}

#[test]
fn decide_usage_is_the_listing() {
    // 9.6 prints the same listing but reports the command as failed; rusoar reports success.
    let mut a = Agent::default();
    let text = a.execute("decide ?").unwrap();
    assert!(text.contains("decide select                    <operator ID>\n"));
    assert!(text.ends_with("For a detailed explanation of sub-commands:    help decide\n"));
    let e = a.execute("decide nonsense").unwrap_err();
    assert_eq!(
        e.message(),
        "Invalid decide command.  Use 'decide ?' to see a list of valid settings."
    );
}

#[test]
fn singleton_patterns_are_listed_added_and_removed() {
    // 9.6 lists the user patterns in the order of its hash table; rusoar in the order they
    // were added, 9.6's eleven defaults first.
    let mut a = Agent::default();
    let listing = a.execute("chunk singleton").unwrap();
    assert!(listing.starts_with("==== Singleton WME Unification Patterns ====\n"));
    assert!(
        listing.contains("   ---------- user-defined ----------\n   (<any> ^superstate <any>)\n")
    );
    a.execute("chunk singleton state counter constant").unwrap();
    assert!(a.execute("chunk singleton").unwrap().contains(
        "   (<any> ^smem <any>)\n   (<state> ^counter <constant>)\n\n\nTo add a new pattern:"
    ));
    a.execute("chunk singleton -r state counter constant")
        .unwrap();
    assert_eq!(a.execute("chunk singleton").unwrap(), listing);
    let e = a.execute("chunk singleton state counter").unwrap_err();
    assert_eq!(
        e.message(),
        "Wrong number of arguments for the chunk command."
    );
}

#[test]
fn output_log_and_command_to_file_write_files() {
    let dir = std::env::temp_dir().join(format!("rusoar-output-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let log = dir.join("session.log");
    let ctf = dir.join("print.txt");
    let mut a = Agent::default();
    let opened = a.execute(&format!("output log {}", log.display())).unwrap();
    assert_eq!(opened, format!("Log file '{}' open.\n", log.display()));
    a.execute("echo hello").unwrap();
    a.execute("output log --add a note").unwrap();
    assert_eq!(
        a.execute("output log --close").unwrap(),
        "Log file closed.\n"
    );
    assert_eq!(
        a.execute("output log --close").unwrap_err().message(),
        "Log is not open."
    );
    let text = std::fs::read_to_string(&log).unwrap();
    assert!(text.starts_with(&opened), "{text}");
    assert!(text.contains("soar> echo hello\nhello\n"), "{text}");
    assert!(text.contains("a note\n"), "{text}");
    assert!(!text.contains("--close"), "{text}");

    // The command's text goes to the file, not to the print stream.
    let shown = a
        .execute(&format!(
            "output command-to-file {} print s1",
            ctf.display()
        ))
        .unwrap();
    assert_eq!(shown, "");
    let text = std::fs::read_to_string(&ctf).unwrap();
    assert!(text.starts_with("(S1 ^epmem E1"), "{text}");
    a.execute(&format!(
        "output command-to-file -a {} echo more",
        ctf.display()
    ))
    .unwrap();
    assert!(std::fs::read_to_string(&ctf).unwrap().ends_with("more\n\n"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// 9.6 prints `chunk stats` whatever follows it; rusoar prints it and says the rest is
/// not used.
#[test]
fn chunk_stats_says_extra_words_are_not_used() {
    let mut a = Agent::default();
    let out = a.execute("chunk stats extra").unwrap();
    assert!(
        out.contains("Explanation-Based Chunking Statistics"),
        "{out}"
    );
    assert!(out.contains("takes no arguments"), "{out}");
}

/// Setting a `chunk` switch answers as 9.6 does, with no warning: each one acts.
#[test]
fn chunk_settings_answer_as_9_6() {
    let mut a = Agent::default();
    let out = a.execute("chunk add-ltm-links on").unwrap();
    assert_eq!(out, "add-ltm-links is now on\n");
    // allow-opaque off changes nothing in 9.6.5 either (command golden learn-allow-opaque).
    let out = a.execute("chunk allow-opaque off").unwrap();
    assert_eq!(out, "allow-opaque is now off\n");
    // allow-local-negations, bottom-only, add-osk and the singletons act: no such warning.
    let out = a.execute("chunk allow-local-negations off").unwrap();
    assert_eq!(out, "allow-local-negations is now off\n");
    let out = a.execute("chunk add-osk off").unwrap();
    assert_eq!(out, "add-osk is now off\n");
    let out = a
        .execute("chunk automatically-create-singletons off")
        .unwrap();
    assert_eq!(out, "automatically-create-singletons is now off\n");
    let out = a.execute("chunk singleton any foo constant").unwrap();
    assert!(!out.contains("no effect"), "{out}");
}

/// rusoar has no spatial visual system: enabling it is refused with a clear error, and it
/// stays disabled (the rest of `svs` is compared with 9.6 in the command golden `svs`).
#[test]
fn svs_cannot_be_enabled_and_stays_disabled() {
    let mut a = rusoar::Agent::default();
    for on in ["svs --enable", "svs -e", "svs --on"] {
        let err = a.execute(on).unwrap_err();
        assert!(
            err.message().contains("no Spatial Visual System"),
            "{}",
            err.message()
        );
    }
    assert_eq!(
        a.execute("svs").unwrap().trim_end(),
        "Spatial Visual System is disabled."
    );
}
