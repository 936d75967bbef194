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
        "chunk [always|never|only|except]\nchunk ?\nchunk max-chunks [n]\nchunk max-dupes [n]\n\nShows or sets when Soar learns rules, and the learning limits; `chunk` alone prints the summary, `chunk ?` every setting.",
    ),
    ("debug", "debug allocate|internal-symbols|port|time ...\n\nKernel debugging aids."),
    (
        "decide",
        "decide indifferent-selection [-b|-g|-f|-l|-x] [-e value] [-t value]\ndecide numeric-indifferent-mode [--avg|--sum]\ndecide srand [seed]\ndecide select|predict ...\n\nSettings of the decision procedure: the exploration policy and its parameters, and the random seed.",
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
        "learn [-e|--on] [-d|--off] [-o|--only] [-E|--except] [-l|--list] ...\n\nDeprecated spelling of `chunk`: shows or sets when Soar learns rules.",
    ),
    (
        "load",
        "load file [-v] path        (alias: source)\nload library|percepts|rete-network ...\n\nRuns the commands of a file, from the file's directory; stops at the first failing command.",
    ),
    ("ls", "ls\n\nLists the files of the working directory."),
    (
        "output",
        "output [print-depth n|warnings on|off|agent-writes on|off|...]\n\nSettings of what Soar prints.",
    ),
    ("popd", "popd\n\nReturns to the directory saved by the last pushd."),
    (
        "preferences",
        "preferences [id [attribute]] [-n|--none] [-N|--names] [-t|--timetags] [-w|--wmes] [-o|--object]\n\nLists the preferences for a slot (default: S1 ^operator).",
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
        "run [count] [-d|-e|-p|-o] [-s] [-u|-n] [-g]\n\nRuns the decision cycle: `count` decisions (-d, the default when a count is given), elaborations (-e), phases (-p) or output cycles (-o). With no count and no unit it runs until the agent halts, or until Ctrl-C in the REPL. `run 1` stops before the next apply phase.",
    ),
    ("save", "save ...\n\nSaves agent state (not implemented in rusoar)."),
    ("smem", "smem ...\n\nSemantic memory (not implemented in rusoar)."),
    (
        "soar",
        "soar init|stop|version\nsoar max-elaborations|max-goal-depth|max-nil-output-cycles|stop-phase|wait-snc [value]\n\nReinitializes the agent (init), stops a run (stop), or shows and sets the kernel's settings.",
    ),
    ("sp", "sp {name [\"doc\"] [:flags] conditions --> actions}\n\nLoads a rule; a rule with the same name is replaced."),
    ("stats", "stats\n\nPrints counts of rules, decisions, elaboration cycles, firings and working memory."),
    ("svs", "svs ...\n\nSpatial visual system (not implemented in rusoar)."),
    (
        "trace",
        "trace [0-5]\n\nSets how much of the run is traced: 0 nothing, 1 decisions, 2 phases, 3 rule firings, 4 working-memory changes, 5 preferences.",
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
