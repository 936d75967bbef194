//! `help` and `help <command>`: the command list of 9.6 and a short usage per command,
//! written for rusoar. An alias is explained by its expansion.

use super::aliases::Aliases;
use super::COMMANDS;

/// One usage text per command of [`COMMANDS`]: synopsis lines, then what the command does.
const USAGE: &[(&str, &str)] = &[
    (
        "alias",
        "alias [name [words...]]\nalias -r name\n\nLists the aliases, shows one, defines `name` as the given words, or removes it (-r).",
    ),
    ("cd", "cd [directory]\n\nChanges the working directory (no argument: the starting one)."),
    (
        "chunk",
        "chunk [always|never|only|except]\nchunk ?\nchunk max-chunks|max-dupes [n]\nchunk naming-style [numbered|rule]\nchunk bottom-only|interrupt|explain-interrupt|warning-interrupt [on|off]\nchunk automatically-create-singletons|add-ltm-links|add-osk [on|off]\nchunk allow-local-negations|allow-opaque [on|off]\nchunk singleton [-r] [type attribute type]\n\nShows or sets when Soar learns rules and how: `chunk` alone prints the summary, `chunk ?` every setting with its value. `interrupt` stops a run after a rule is learned; `bottom-only` keeps a state from learning once a state below it has; `singleton` lists, adds or removes the patterns of WMEs unique in a state.",
    ),
    ("debug", "debug allocate|internal-symbols|port|time ...\n\nKernel debugging aids."),
    (
        "decide",
        "decide\ndecide ?\ndecide indifferent-selection [-b|-g|-f|-l|-x|-s]\ndecide indifferent-selection -e|-t [value]\ndecide indifferent-selection -p epsilon|temperature [exponential|linear]\ndecide indifferent-selection -r epsilon|temperature exponential|linear [rate]\ndecide indifferent-selection -a [on|off]\ndecide numeric-indifferent-mode [--avg|--sum]\ndecide select [operator-id]\ndecide predict\ndecide set-random-seed [seed]     (alias: srand)\n\nSettings of the decision procedure: the exploration policy and its parameters, their reduction after each decision (-a), how numeric preferences combine, and the random seed. `select` makes the next decision take a proposed operator; `predict` says what the next decision will do.",
    ),
    ("dirs", "dirs\n\nPrints the directory stack, current directory first."),
    ("echo", "echo [-n|--nonewline] words...\n\nPrints the words joined by single spaces, then a newline."),
    ("epmem", "epmem ...\n\nEpisodic memory (not implemented in rusoar)."),
    ("exit", "exit\n\nLeaves rusoar (in the REPL: like Ctrl-D)."),
    ("explain", "explain ...\n\nExplanations of learned rules (not implemented in rusoar)."),
    ("file-system", "file-system ...\n\nThe file-system commands of 9.6 (cd, dirs, ls, popd, pushd, pwd)."),
    ("gp", "gp {name conditions --> actions}\n\nGenerates one rule per combination of the [a b ...] alternatives in the body."),
    ("help", "help [command]\n\nLists the commands, or shows how to use one of them (an alias is explained by its expansion)."),
    (
        "learn",
        "learn [-l] [-e|-d|-o] [-a|-b] [-n|-N] [-p|-P]\n\nDeprecated spelling of `chunk`: the summary, when Soar learns rules (-e always, -d never, -o only), bottom-only (-b on, -a off), local negations (-n, -N) and operator selection knowledge (-p, -P).",
    ),
    (
        "load",
        "load file [-d] path        (alias: source)\nload library|percepts|rete-network ...\n\nRuns the commands of a file, from the file's directory; stops at the first failing command. -d leaves out the summary of rules sourced.",
    ),
    ("ls", "ls\n\nLists the files of the working directory."),
    (
        "output",
        "output\noutput ?\noutput enabled|callbacks|console|echo-commands|warnings|agent-writes [on|off]\noutput agent-logs channel on|off\noutput print-depth [n]\noutput log [-A] file | --add text | --close\noutput command-to-file [-a] file command...\n\nSettings of what Soar prints and where: everything (enabled), what rules write, the channels of the log function, print's default depth, a log file of the commands and what they printed, one command's text to a file.",
    ),
    ("popd", "popd\n\nReturns to the directory saved by the last pushd."),
    (
        "preferences",
        "preferences [id [attribute]] [-n|--names]\n\nLists the preferences for a slot (default: the lowest state's ^operator), with the selection probabilities of an operator slot; -n names the rule behind each.",
    ),
    (
        "print",
        "print [options] id|timetag|rule\nprint -a|-u|-c|-j|-D\nprint -s|--stack\n\nPrints working-memory objects (-d/--depth n, -i/--internal, -t/--tree), rules by name, rule lists (newest first), or the goal stack.",
    ),
    (
        "production",
        "production excise [-a|--all] [name...]\nproduction firing-counts [n|name...]\nproduction matches [name]\nproduction find|break|watch|memory-usage|optimize-attribute ...\n\nOperations on rules: remove them, count their firings, list their matches.",
    ),
    ("pushd", "pushd directory\n\nSaves the working directory on the stack and changes to `directory`."),
    ("pwd", "pwd\n\nPrints the working directory."),
    ("rl", "rl ...\n\nReinforcement learning (not implemented in rusoar)."),
    (
        "run",
        "run [count] [-d|-e|-p|-o] [-s] [-u|-n]\n\nRuns the decision cycle: `count` decisions (-d, the default when a count is given), elaborations (-e), phases (-p) or output cycles (-o). With no count and no unit it runs until the agent halts, or until Ctrl-C in the REPL. Decisions are counted at the stop phase (`soar stop-phase`, apply by default): `run 1` stops before the next apply phase, `run 0` goes on to it.",
    ),
    ("save", "save ...\n\nSaves agent state (not implemented in rusoar)."),
    ("smem", "smem ...\n\nSemantic memory (not implemented in rusoar)."),
    (
        "soar",
        "soar\nsoar ?\nsoar init|stop|version\nsoar max-elaborations|max-goal-depth|max-nil-output-cycles|max-dc-time|max-gp|max-memory-usage [n]\nsoar stop-phase [input|propose|apply|output]\nsoar wait-snc|timers|keep-all-top-oprefs|tcl [on|off]\n\nReinitializes the agent (init), stops a run (stop), or shows and sets the kernel's settings; `soar` alone prints the summary, `soar ?` every setting.",
    ),
    ("sp", "sp {name [\"doc\"] [:flags] conditions --> actions}\n\nLoads a rule; a rule with the same name is replaced."),
    (
        "stats",
        "stats [-s|-d|-a|-m|-r|-l|-M|-R|-t|-T|-c|-C] [-S N]\n\nPrints counts of rules, decisions, elaboration cycles, firings and working memory (-s, the default), the decisions made (-d), the agent's counters (-a), the kernel's stores (-m), the rete's nodes by type (-r), the chunking statistics (-l, as `chunk stats`), or the largest time, WM changes and firings of one decision cycle (-M; -R zeroes them). -t keeps each cycle's figures, -c prints them (-S N sorts by column N: 1 cycle, 2 time, 3 WM changes, 4 firings; negative for descending), -C prints them as comma-separated values, -T stops and clears them.",
    ),
    ("svs", "svs ...\n\nSpatial visual system (not implemented in rusoar)."),
    (
        "trace",
        "trace [0-5]\ntrace [flags]\n\nSets how much of the run is traced: 0 nothing, 1 decisions, 2 phases, 3 rule firings, 4 working-memory changes, 5 preferences; single flags (-d, -p, -w, -r, -L 0-2, --timetags, --fullwmes, ...) set one kind each. `trace` alone lists every setting.",
    ),
    ("visualize", "visualize ...\n\nGraph output of memories (not implemented in rusoar)."),
    (
        "wm",
        "wm add id attribute value\nwm remove timetag\nwm activation|watch ...\n\nAdds or removes a working-memory element by hand.",
    ),
];

/// The usage text of a real command name.
pub fn usage(command: &str) -> Option<&'static str> {
    USAGE.iter().find(|(c, _)| *c == command).map(|(_, u)| *u)
}

/// `help` with no argument: the command list, as 9.6 prints it (`learn` and `exit` work
/// but are not listed there either).
pub fn listing() -> String {
    let mut s = String::from("Soar 9.6 Command List (rusoar):\n\n");
    for c in COMMANDS.iter().filter(|c| !matches!(**c, "learn" | "exit")) {
        s.push_str(c);
        s.push('\n');
    }
    s.push_str("\nTo read an in-depth description of the command:               help <command>\n");
    s.push_str("To get a quick summary of sub-command and settings:           <command> ?\n");
    s.push_str("\nNote:  Many previous Soar commands are now sub-commands. To locate a help \n");
    s.push_str("       entry, try 'help <old command name>'.");
    s
}

/// `help NAME`: the usage of a command, or of the command an alias expands to; `None` when
/// `name` is neither (9.6: `No such command 'NAME'.`).
pub fn help_for(name: &str, aliases: &Aliases) -> Option<String> {
    if let Some(u) = usage(name) {
        return Some(format!("{name}: {u}\n"));
    }
    let expansion = aliases.get(name)?;
    let target = expansion.first()?;
    let mut s = format!("{name} is an alias for `{}`.\n", expansion.join(" "));
    if let Some(u) = usage(target) {
        s.push_str(&format!("\n{target}: {u}\n"));
    }
    Some(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_command_has_a_usage() {
        for c in COMMANDS {
            assert!(usage(c).is_some(), "no usage for {c}");
        }
        assert_eq!(USAGE.len(), COMMANDS.len());
    }

    #[test]
    fn aliases_are_explained_by_their_expansion() {
        let a = Aliases::default();
        let h = help_for("step", &a).unwrap();
        assert!(h.starts_with("step is an alias for `run -d`.\n"), "{h}");
        assert!(h.contains("\nrun: run [count]"), "{h}");
        assert!(help_for("no-such-thing", &a).is_none());
    }
}
