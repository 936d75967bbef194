//! The manual pages against the code: every command and alias has a page, each page's
//! synopsis is the command's usage text, no line is wider than 80 columns, and every option
//! and sub-command word the command parsers accept is on the page of its command. The
//! accepted words are read from the parsers' source (`src/commands/*.rs`), so a parser that
//! gains an option fails this test until its page documents it. A page may document options
//! that no parser accepts yet (marked "(not yet built)").

use super::*;
use std::collections::BTreeSet;

/// The usage of each command of [`COMMANDS`]: one line per form its parser takes. Each
/// page's synopsis must be these lines.
const USAGE: &[(&str, &str)] = &[
    ("alias", "alias\nalias name\nalias name words...\nalias -r|--remove name"),
    ("cd", "cd [directory]"),
    ("chunk", "chunk\nchunk ?|help\nchunk stats\nchunk always|never|only|except\nchunk max-chunks|max-dupes [n]\nchunk naming-style [numbered|rule]\nchunk bottom-only|interrupt|explain-interrupt|warning-interrupt [on|off]\nchunk automatically-create-singletons|add-ltm-links|add-osk [on|off]\nchunk allow-local-negations|allow-opaque [on|off]\nchunk singleton [-r|--remove] [type attribute type]"),
    ("debug", "debug\ndebug ?\ndebug allocate [pool blocks]\ndebug internal-symbols\ndebug port\ndebug time command [args...]"),
    ("decide", "decide\ndecide ?|help\ndecide indifferent-selection [-b|-g|-f|-l|-x|-s]\ndecide indifferent-selection -e|-t [value]\ndecide indifferent-selection -p epsilon|temperature [exponential|linear]\ndecide indifferent-selection -r epsilon|temperature exponential|linear [rate]\ndecide indifferent-selection -a [on|off]\ndecide numeric-indifferent-mode [-a|--avg|-s|--sum]\ndecide select [operator-id]\ndecide predict\ndecide srand|set-random-seed [seed]"),
    ("dirs", "dirs"),
    ("echo", "echo [-n|--nonewline] words..."),
    ("epmem", "epmem\nepmem ?|help\nepmem -e|--enable\nepmem -d|--disable\nepmem -g|--get parameter\nepmem -s|--set parameter value\nepmem -i|--init\nepmem -p|--print episode\nepmem -v|--viz episode\nepmem -b|--backup file\nepmem -S|--stats [statistic]\nepmem -t|--timers [timer]"),
    ("exit", "exit"),
    ("explain", "explain\nexplain ?\nexplain all|justifications|only-chunk-identities [on|off]\nexplain record [rule]\nexplain list-chunks|list-justifications\nexplain chunk name|id\nexplain formation|constraints|identity|stats\nexplain instantiation n|wm-trace|explanation-trace"),
    ("file-system", "file-system ..."),
    ("gp", "gp {name conditions --> actions}"),
    ("help", "help [command]"),
    ("learn", "learn [-l] [-e|-d|-o] [-a|-b] [-n|-N] [-p|-P]"),
    ("limits", "limits [-w|--wmes n] [-t|--tokens n] [-p|--preferences n] [-c|--chunks n]"),
    ("load", "load file [-a|-d|-v] path\nload library|percepts|rete-network ..."),
    ("ls", "ls"),
    ("output", "output\noutput ?\noutput enabled|callbacks|console|echo-commands|warnings|agent-writes [on|off]\noutput agent-logs channel [on|off]\noutput print-depth [n]\noutput log [-A|--append] file\noutput log --add text\noutput log --close\noutput command-to-file [-a|--append] file command..."),
    ("popd", "popd"),
    ("preferences", "preferences [--none|-n|-N|--names|-t|--timetags|-w|--wmes] [id [attribute]]\npreferences -o|--object [id]"),
    ("print", "print [options] id|timetag|rule|pattern\nprint [-f|-n|-F] -a|-u|-c|-j|-D|-T|-r\nprint -s|--stack [-S|-o]\nprint --gds"),
    ("production", "production excise -a|-c|-d|-n|-r|-t|-T|-u\nproduction excise name...\nproduction firing-counts [n] [name...]\nproduction matches [-a|-r] [-n|-c|-t|-w] [name]\nproduction find [-l|-r] [-c|-n] [-s] pattern\nproduction watch [-e|-d] [name]\nproduction break [-c|-s name]\nproduction optimize-attribute [attribute [n]]\nproduction memory-usage [-c|-d|-j|-T|-u] [n | name]"),
    ("pushd", "pushd directory"),
    ("pwd", "pwd"),
    ("rl", "rl\nrl -g|--get parameter\nrl -s|--set parameter value\nrl -S|--stats [statistic]\nrl -t|--trace [print|clear|init] [level]"),
    ("run", "run [count] [-d|-e|-p|-o|-f|-g] [-s] [-u|-n]"),
    ("save", "save ?|help\nsave agent file\nsave chunks file\nsave rete-network -s|--save file\nsave percepts [-o|--open file] [-c|--close] [-f|--flush]"),
    ("smem", "smem\nsmem ?|help\nsmem -e|--enable\nsmem -d|--disable\nsmem -g|--get parameter\nsmem -s|--set parameter value\nsmem -a|--add {(id ^attr value ...) ...}\nsmem -q|--query {(id ^attr value ...)} [count]\nsmem -r|--remove {(lti [^attr [value]]) ...}\nsmem -x|--export file [lti]\nsmem -b|--backup file\nsmem -i|--init\nsmem -c|--clear\nsmem -h|--history lti\nsmem -S|--stats [statistic]\nsmem -t|--timers [timer]"),
    ("soar", "soar\nsoar ?\nsoar init|stop|version\nsoar max-elaborations|max-goal-depth|max-nil-output-cycles [n]\nsoar max-dc-time|max-gp|max-memory-usage [n]\nsoar stop-phase [input|propose|apply|output]\nsoar wait-snc|timers|keep-all-top-oprefs|tcl [on|off]"),
    ("sp", "sp {name [\"doc\"] [:flags] conditions --> actions}"),
    ("stats", "stats [-s|-d|-a|-m|-l|-r|-M|-R|-t|-T|-c|-C] [-S column]"),
    ("svs", "svs\nsvs -e|--enable|--on|-d|--disable|--off\nsvs --enable-in-substates|--disable-in-substates\nsvs path ..."),
    ("trace", "trace [0-5]\ntrace -l|--level 0-5\ntrace flags [remove|0]\ntrace -L|--learning 0-2\ntrace -n|-t|-f\ntrace -N|--none"),
    ("visualize", "visualize\nvisualize ?\nvisualize wm [id [depth]]\nvisualize smem [lti [depth]]\nvisualize epmem episode\nvisualize identity_graph|ebc_analysis\nvisualize setting [value]"),
    ("wm", "wm add id [^]attribute value [+]\nwm remove timetag\nwm watch -a|-r [-t adds|removes|both] id attribute value\nwm watch [-l|-R] [-t adds|removes|both]\nwm activation\nwm activation -g|--get parameter\nwm activation -s|--set parameter value\nwm activation -S|--stats [forgotten-wmes]\nwm activation -h|--history timetag"),
];

fn usage(command: &str) -> Option<&'static str> {
    USAGE.iter().find(|(c, _)| *c == command).map(|(_, u)| *u)
}

/// Which page documents the words parsed in each function or constant of the command
/// sources: (file, item, command). An empty command marks an item whose words are not one
/// command's options (the interpreter's dispatch of command names, the host name of
/// `stats`).
const ITEMS: &[(&str, &str, &str)] = &[
    ("chunk.rs", "cmd_chunk", "chunk"),
    ("chunk.rs", "chunk_singleton", "chunk"),
    ("debug.rs", "cmd_debug", "debug"),
    ("decide.rs", "from_name", "decide"),
    ("decide.rs", "cmd_decide", "decide"),
    ("decide.rs", "indifferent_selection", "decide"),
    ("decide.rs", "numeric_indifferent_mode", "decide"),
    ("files.rs", "cmd_load", "load"),
    ("files.rs", "cmd_source", "load"),
    ("help.rs", "listed", ""),
    ("limits.rs", "cmd_limits", "limits"),
    ("memory.rs", "cmd_wm", "wm"),
    ("memory.rs", "cmd_matches", "production"),
    ("mod.rs", "execute_command", ""),
    ("mod.rs", "cmd_echo", "echo"),
    ("output.rs", "cmd_output", "output"),
    ("output.rs", "output_log", "output"),
    ("output.rs", "on_off", "output"),
    ("output.rs", "command_to_file", "output"),
    ("prefs.rs", "cmd_preferences", "preferences"),
    ("prefs_support.rs", "origin_of", ""),
    ("print_cmd.rs", "cmd_print", "print"),
    ("print_cmd.rs", "context_variable", "print"),
    ("production_find.rs", "cmd_production_find", "production"),
    ("production_find.rs", "cmd_production_break", "production"),
    ("production_find.rs", "cmd_production_watch", "production"),
    ("rules.rs", "cmd_production", "production"),
    ("memory_usage.rs", "cmd_memory_usage", "production"),
    ("rules.rs", "cmd_excise", "production"),
    ("rl.rs", "cmd_rl", "rl"),
    ("rl.rs", "rl_trace_command", "rl"),
    ("smem.rs", "cmd_smem", "smem"),
    ("epmem.rs", "cmd_epmem", "epmem"),
    ("running.rs", "cmd_run", "run"),
    ("svs.rs", "cmd_svs", "svs"),
    ("visualize.rs", "switch", "visualize"),
    ("explain.rs", "cmd_explain", "explain"),
    ("explain.rs", "switch", "explain"),
    ("visualize.rs", "visualization", ""),
    ("visualize.rs", "resolve", "visualize"),
    ("visualize.rs", "cmd_visualize", "visualize"),
    ("visualize.rs", "visualize_setting", "visualize"),
    ("stats.rs", "SPECS", "stats"),
    ("wm_watch.rs", "cmd_wm_watch", "wm"),
    ("wm_activation.rs", "cmd_wm_activation", "wm"),
    ("stats.rs", "host_name", ""),
    ("save.rs", "cmd_save", "save"),
    ("rete_net.rs", "save_rete_network", "save"),
    ("percepts.rs", "save_percepts", "save"),
    ("percepts.rs", "load_percepts", "load"),
    ("rete_net.rs", "load_rete_network", "load"),
    ("settings.rs", "LEARN_SOAR8", "learn"),
    ("settings.rs", "cmd_learn", "learn"),
    ("settings.rs", "cmd_soar", "soar"),
    ("settings.rs", "on_off_soar", "soar"),
    ("settings.rs", "cmd_alias", "alias"),
    ("tracing.rs", "FLAGS", "trace"),
    ("tracing.rs", "OTHER", "trace"),
    ("tracing.rs", "flag_mut", "trace"),
    ("tracing.rs", "parse", "trace"),
];

/// A word a parser accepts: an option (`-x`, `--long`) or a sub-command or value word.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
enum Accepted {
    Option(String),
    Word(String),
}

fn is_word_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '-' || c == '_'
}

/// Whether `text` holds `token` with no word character on either side.
fn has_token(text: &str, token: &str) -> bool {
    text.match_indices(token).any(|(i, _)| {
        let before = text[..i].chars().next_back();
        let after = text[i + token.len()..].chars().next();
        !before.is_some_and(is_word_char) && !after.is_some_and(is_word_char)
    })
}

fn is_option_literal(s: &str) -> bool {
    let body = s.strip_prefix("--").or_else(|| s.strip_prefix('-'));
    body.is_some_and(|b| {
        b.starts_with(|c: char| c.is_ascii_alphabetic()) && b.chars().all(is_word_char)
    })
}

fn is_word_literal(s: &str) -> bool {
    s == "?"
        || (s.starts_with(|c: char| c.is_ascii_lowercase())
            && s.chars().all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-'))
}

/// The words accepted in one source file, by the function or constant they are in: option
/// pairs (`'x', "long"`), option literals (`"-x"`, `"--long"`) and the words a `match`
/// compares against (`Some("word")`, `"word" =>`, `"a" | "b"`). Comments, and the unit
/// tests at the end of the file, are left out.
fn accepted_words(source: &str) -> Vec<(String, Accepted)> {
    let source = source.split("#[cfg(test)]").next().unwrap_or_default();
    let chars: Vec<char> = source.chars().collect();
    let text = |a: usize, b: usize| chars[a..b.min(chars.len())].iter().collect::<String>();
    let next_code = |mut j: usize| {
        while j < chars.len() && chars[j].is_whitespace() {
            j += 1;
        }
        j
    };
    let prev_code = |j: usize| chars[..j].iter().rev().find(|c| !c.is_whitespace()).copied();
    let mut out = Vec::new();
    let mut item = String::new();
    let mut pending_short: Option<(char, usize)> = None;
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c == '/' && chars.get(i + 1) == Some(&'/') {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
            continue;
        }
        if c == '\'' {
            // A character literal ('x', '\n'), or a lifetime.
            let end = if chars.get(i + 1) == Some(&'\\') {
                (i + 2..chars.len()).find(|&j| chars[j] == '\'')
            } else if chars.get(i + 2) == Some(&'\'') {
                Some(i + 2)
            } else {
                None
            };
            match end {
                Some(e) => {
                    let next = next_code(e + 1);
                    if e == i + 2 && chars.get(next) == Some(&',') {
                        pending_short = Some((chars[i + 1], next_code(next + 1)));
                    }
                    i = e + 1;
                }
                None => i += 1,
            }
            continue;
        }
        if c == '"' {
            let start = i + 1;
            let mut j = start;
            while j < chars.len() && chars[j] != '"' {
                j += if chars[j] == '\\' { 2 } else { 1 };
            }
            let lit = text(start, j);
            let after = next_code(j + 1);
            let follows = text(after, after + 2);
            let short = pending_short.take().filter(|&(_, at)| at == i);
            if let Some((short, _)) = short {
                if lit.chars().all(is_word_char) && !lit.is_empty() {
                    out.push((item.clone(), Accepted::Option(format!("-{short}"))));
                    out.push((item.clone(), Accepted::Option(format!("--{lit}"))));
                }
            } else if is_option_literal(&lit) {
                out.push((item.clone(), Accepted::Option(lit)));
            } else if is_word_literal(&lit) {
                let before = prev_code(i);
                let in_some = text(i.saturating_sub(5), i) == "Some(";
                if in_some || follows == "=>" || follows.starts_with('|') || before == Some('|') {
                    out.push((item.clone(), Accepted::Word(lit)));
                }
            }
            i = j + 1;
            continue;
        }
        // `long_only("name")`.
        if text(i, i + 11) == "long_only(\"" {
            let start = i + 11;
            let end = (start..chars.len()).find(|&j| chars[j] == '"').unwrap_or(start);
            out.push((item.clone(), Accepted::Option(format!("--{}", text(start, end)))));
            i = end + 1;
            continue;
        }
        let at_word_start = i == 0 || !is_word_char(chars[i - 1]);
        for kw in ["fn ", "const "] {
            if at_word_start && text(i, i + kw.len()) == kw {
                let start = i + kw.len();
                let end = (start..chars.len())
                    .find(|&j| !(chars[j].is_alphanumeric() || chars[j] == '_'))
                    .unwrap_or(start);
                item = text(start, end);
            }
        }
        i += 1;
    }
    out
}

/// The lines of a page under `heading`, up to the next heading (a line that starts with a
/// capital letter at the first column).
fn section(page: &str, heading: &str) -> String {
    let mut lines = page.lines().skip_while(|l| *l != heading);
    if lines.next().is_none() {
        return String::new();
    }
    let body: Vec<&str> = lines
        .take_while(|l| !l.starts_with(|c: char| c.is_ascii_uppercase()))
        .collect();
    body.join("\n")
}

#[test]
fn every_command_has_a_page_and_a_usage() {
    for c in COMMANDS {
        assert!(usage(c).is_some(), "no usage for {c}");
        assert!(page(c).is_some(), "no page for {c}");
    }
    assert_eq!(USAGE.len(), COMMANDS.len());
    assert_eq!(PAGES.len(), COMMANDS.len());
}

#[test]
fn every_alias_leads_to_a_page() {
    let aliases = Aliases::default();
    for name in aliases.names() {
        let target = &aliases.get(name).unwrap()[0];
        assert!(page(target).is_some(), "alias {name}: no page for {target}");
        // An alias that starts a command name gets 9.6's answer for prefixes instead.
        if listed().any(|c| c.starts_with(name)) {
            continue;
        }
        let Help::Page(text) = help_for(name, &aliases) else {
            panic!("help {name}: no page");
        };
        assert!(text.contains(page(target).unwrap()), "help {name}");
    }
}

#[test]
fn each_synopsis_is_the_usage_text() {
    for (name, usage) in USAGE {
        let page = page(name).unwrap();
        let synopsis = section(page, "SYNOPSIS");
        let lines: Vec<&str> = synopsis.lines().filter(|l| !l.is_empty()).collect();
        let expected: Vec<String> = usage.lines().map(|l| format!("  {l}")).collect();
        assert_eq!(lines, expected, "synopsis of {name}");
    }
}

#[test]
fn pages_fit_in_80_columns_and_name_their_command() {
    for (name, page) in PAGES {
        assert!(page.starts_with(&format!("{name} - ")), "first line of {name}");
        for (k, line) in page.lines().enumerate() {
            assert!(line.chars().count() <= 80, "{name}.txt:{}: too wide", k + 1);
            assert!(!line.ends_with(' '), "{name}.txt:{}: trailing space", k + 1);
        }
        for heading in ["SYNOPSIS", "DESCRIPTION", "SEE ALSO"] {
            assert!(!section(page, heading).trim().is_empty(), "{name}: no {heading}");
        }
    }
}

#[test]
fn every_parsed_option_is_on_its_page() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/src/commands");
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "rs"))
        .collect();
    files.sort();
    let mut missing = BTreeSet::new();
    let mut used = BTreeSet::new();
    let mut checked = 0;
    for path in files {
        let file = path.file_name().unwrap().to_string_lossy().to_string();
        let source = std::fs::read_to_string(&path).unwrap();
        for (item, accepted) in accepted_words(&source) {
            let Some((_, _, command)) = ITEMS.iter().find(|(f, i, _)| *f == file && *i == item)
            else {
                missing.insert(format!("{file}: `{item}` parses {accepted:?}; add it to ITEMS"));
                continue;
            };
            used.insert((file.clone(), item.clone()));
            if command.is_empty() {
                continue;
            }
            let page = page(command).unwrap();
            checked += 1;
            let ok = match &accepted {
                Accepted::Option(o) => has_token(&section(page, "OPTIONS"), o),
                // A word a parser compares may be an option's long name (`"system" =>`).
                Accepted::Word(w) => has_token(page, w) || has_token(page, &format!("--{w}")),
            };
            if !ok {
                missing.insert(format!("{command}: {accepted:?} ({file}: `{item}`)"));
            }
        }
    }
    for (file, item, _) in ITEMS {
        if !used.contains(&(file.to_string(), item.to_string())) {
            missing.insert(format!("{file}: `{item}` is in ITEMS but parses nothing"));
        }
    }
    assert!(checked > 200, "only {checked} words found in the parsers");
    assert!(missing.is_empty(), "not on the pages:\n{}", missing.into_iter().collect::<Vec<_>>().join("\n"));
}

#[test]
fn the_scanner_reads_pairs_literals_and_match_words() {
    let src = "fn a() { let s = [opt('x', \"long\"), long_only(\"on\")]; }\n\
               fn b() { match w { Some(\"sub\") => 1, \"v1\" | \"v2\" => 2, \"-r\" => 3 } }\n\
               // fn c() { Some(\"comment\") }\n";
    let got = accepted_words(src);
    let o = |s: &str| Accepted::Option(s.into());
    let w = |s: &str| Accepted::Word(s.into());
    assert_eq!(
        got,
        vec![
            ("a".into(), o("-x")),
            ("a".into(), o("--long")),
            ("a".into(), o("--on")),
            ("b".into(), w("sub")),
            ("b".into(), w("v1")),
            ("b".into(), w("v2")),
            ("b".into(), o("-r")),
        ]
    );
}

#[test]
fn aliases_prefixes_and_unknown_names() {
    let a = Aliases::default();
    let Help::Page(h) = help_for("step", &a) else {
        panic!()
    };
    assert!(h.starts_with("step is an alias for `run -d`.\n\nrun - "), "{h}");
    assert!(h.contains("\nALIASES\n"), "{h}");
    let Help::Page(h) = help_for("prod", &a) else {
        panic!()
    };
    assert!(h.starts_with("production - "), "{h}");
    assert_eq!(
        help_for("l", &a),
        Help::Ambiguous(
            "I'm not sure which help page you want.  Did you mean load or ls?".into()
        )
    );
    assert_eq!(help_for("no-such-thing", &a), Help::Unknown);
    assert_eq!(help_for("", &a), Help::Unknown);
}
