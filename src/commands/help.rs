//! `help` and `help <command>`: the command list of 9.6, and a manual page per command
//! written for rusoar. The pages are the text files of `docs/help/`, built into the binary;
//! the unit tests check each page's synopsis, and that every option the command parsers
//! accept is on its page.

use super::aliases::Aliases;
use super::COMMANDS;

/// One manual page per command: `docs/help/NAME.txt`.
macro_rules! page {
    ($name:literal) => {
        ($name, include_str!(concat!("../../docs/help/", $name, ".txt")))
    };
}

const PAGES: &[(&str, &str)] = &[
    page!("alias"),
    page!("cd"),
    page!("chunk"),
    page!("debug"),
    page!("decide"),
    page!("dirs"),
    page!("echo"),
    page!("epmem"),
    page!("exit"),
    page!("explain"),
    page!("file-system"),
    page!("gp"),
    page!("help"),
    page!("learn"),
    page!("limits"),
    page!("load"),
    page!("ls"),
    page!("output"),
    page!("popd"),
    page!("preferences"),
    page!("print"),
    page!("production"),
    page!("pushd"),
    page!("pwd"),
    page!("rl"),
    page!("run"),
    page!("save"),
    page!("smem"),
    page!("soar"),
    page!("sp"),
    page!("stats"),
    page!("svs"),
    page!("trace"),
    page!("visualize"),
    page!("wm"),
];

/// The manual page of a real command name.
fn page(command: &str) -> Option<&'static str> {
    PAGES.iter().find(|(c, _)| *c == command).map(|(_, p)| *p)
}

/// The commands `help` lists: 9.6's list (it leaves out `learn` and `exit`, which work all
/// the same); rusoar's own `limits` has a page but is not in 9.6's list.
fn listed() -> impl Iterator<Item = &'static str> {
    COMMANDS
        .iter()
        .copied()
        .filter(|c| !matches!(*c, "learn" | "exit" | "limits"))
}

/// `help` with no argument: the command list, as 9.6 prints it, then rusoar's own command.
pub fn listing() -> String {
    let mut s = String::from("Soar 9.6 Command List (rusoar):\n\n");
    for c in listed() {
        s.push_str(c);
        s.push('\n');
    }
    s.push_str("\nTo read an in-depth description of the command:               help <command>\n");
    s.push_str("To get a quick summary of sub-command and settings:           <command> ?\n");
    s.push_str("\nNote:  Many previous Soar commands are now sub-commands. To locate a help \n");
    s.push_str("       entry, try 'help <old command name>'.");
    s.push_str("\n\nrusoar's own command: limits (ceilings on a run's growth).");
    s
}

/// What `help NAME` answers.
#[derive(Debug, PartialEq)]
pub enum Help {
    /// A manual page.
    Page(String),
    /// A prefix of several commands: 9.6's question, which is not a failure.
    Ambiguous(String),
    /// Neither a command, an alias nor a command prefix (9.6: `No such command 'NAME'.`).
    Unknown,
}

/// `help NAME`. A command name gives its page. As in 9.6, a unique prefix of a listed
/// command gives that command's page, and a prefix of several asks which one (so the
/// one-letter aliases `c`, `d`, `e`, `p`, `s` get 9.6's question). Any other alias gives the
/// page of the command it expands to, under a line saying so. Each page ends with the
/// aliases that lead to its command, from the alias table in use.
pub fn help_for(name: &str, aliases: &Aliases) -> Help {
    if let Some(p) = page(name) {
        return Help::Page(with_aliases(name, p, aliases));
    }
    let hits: Vec<&str> = if name.is_empty() {
        Vec::new()
    } else {
        listed().filter(|c| c.starts_with(name)).collect()
    };
    match hits.as_slice() {
        [] => {}
        [one] => return Help::Page(with_aliases(one, page(one).unwrap_or_default(), aliases)),
        [first @ .., last] => {
            return Help::Ambiguous(format!(
                "I'm not sure which help page you want.  Did you mean {} or {last}?",
                first.join(", ")
            ))
        }
    }
    let Some(expansion) = aliases.get(name) else {
        return Help::Unknown;
    };
    let head = format!("{name} is an alias for `{}`.\n", expansion.join(" "));
    let target = expansion.first().map(String::as_str).unwrap_or_default();
    Help::Page(match page(target) {
        Some(p) => format!("{head}\n{}", with_aliases(target, p, aliases)),
        None => head,
    })
}

/// A page followed by the aliases whose expansion starts with `command`.
fn with_aliases(command: &str, page: &str, aliases: &Aliases) -> String {
    let mut names: Vec<&str> = aliases
        .names()
        .filter(|a| aliases.get(a).and_then(|e| e.first()).is_some_and(|c| c == command))
        .collect();
    let mut s = page.to_string();
    if names.is_empty() {
        return s;
    }
    names.sort_unstable();
    let width = names.iter().map(|n| n.len()).max().unwrap_or(0);
    s.push_str("\nALIASES\n");
    for n in names {
        let expansion = aliases.get(n).unwrap_or_default().join(" ");
        s.push_str(&format!("  {n:<width$}  {expansion}\n"));
    }
    s
}

#[cfg(test)]
mod tests;
