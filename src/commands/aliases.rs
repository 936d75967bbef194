//! Soar 9.6's default alias table (as `alias` lists it on the official kernel). Only the
//! first word of a command is looked up, by exact match.

use indexmap::IndexMap;

pub const DEFAULT_ALIASES: &[(&str, &str)] = &[
    ("?", "help"),
    ("a", "alias"),
    ("add-wme", "wm add"),
    ("allocate", "debug allocate"),
    ("aw", "wm add"),
    ("c", "explain chunk"),
    ("capture-input", "save percepts"),
    ("chdir", "cd"),
    ("chunk-name-format", "chunk naming-style"),
    ("cli", "soar tcl"),
    ("clog", "output log"),
    ("command-to-file", "output command-to-file"),
    ("cs", "chunk stats"),
    ("ctf", "output command-to-file"),
    ("d", "run -d"),
    ("default-wme-depth", "output print-depth"),
    ("dir", "ls"),
    ("e", "run -e"),
    ("echo-commands", "output echo-commands"),
    ("ef", "explain formation"),
    ("ei", "explain identities"),
    ("es", "explain stats"),
    ("et", "explain explanation-trace"),
    ("ex", "production excise"),
    ("excise", "production excise"),
    ("fc", "production firing-counts"),
    ("firing-counts", "production firing-counts"),
    ("gds_print", "print --gds"),
    ("gp-max", "soar max-gp"),
    ("i", "explain instantiation"),
    ("indifferent-selection", "decide indifferent-selection"),
    ("inds", "decide indifferent-selection"),
    ("init", "soar init"),
    ("init-soar", "soar init"),
    ("internal-symbols", "debug internal-symbols"),
    ("interrupt", "soar stop"),
    ("is", "soar init"),
    ("load-library", "load library"),
    ("man", "help"),
    ("matches", "production matches"),
    ("max-chunks", "chunk max-chunks"),
    ("max-dc-time", "soar max-dc-time"),
    ("max-elaborations", "soar max-elaborations"),
    ("max-goal-depth", "soar max-goal-depth"),
    ("max-memory-usage", "soar max-memory-usage"),
    ("max-nil-output-cycles", "soar max-nil-output-cycles"),
    ("memories", "production memory-usage"),
    ("multi-attributes", "production optimize-attribute"),
    (
        "numeric-indifferent-mode",
        "decide numeric-indifferent-mode",
    ),
    ("p", "print"),
    ("pbreak", "production break"),
    ("pc", "print --chunks"),
    ("port", "debug port"),
    ("predict", "decide predict"),
    ("production-find", "production find"),
    ("ps", "print --stack"),
    ("pw", "production watch"),
    ("pwatch", "production watch"),
    ("quit", "exit"),
    ("r", "run"),
    ("remove-wme", "wm remove"),
    ("replay-input", "load percepts"),
    ("rete-net", "load rete-network"),
    ("rn", "load rete-network"),
    ("rw", "wm remove"),
    ("s", "run 1"),
    ("select", "decide select"),
    ("set-default-depth", "output print-depth"),
    ("set-stop-phase", "soar stop-phase"),
    ("soarnews", "soar"),
    ("source", "load file"),
    ("srand", "decide srand"),
    ("ss", "soar stop"),
    ("st", "stats"),
    ("step", "run -d"),
    ("stop", "soar stop"),
    ("stop-soar", "soar stop"),
    ("tcl", "soar tcl"),
    ("time", "debug time"),
    ("timers", "soar timers"),
    ("topd", "pwd"),
    ("un", "alias -r"),
    ("unalias", "alias -r"),
    ("varprint", "print -v -d 100"),
    ("verbose", "trace -A"),
    ("version", "soar version"),
    ("w", "trace"),
    ("waitsnc", "soar wait-snc"),
    ("warnings", "output warnings"),
    ("watch", "trace"),
    ("watch-wmes", "wm watch"),
    ("wma", "wm activation"),
    ("wmes", "print -depth 0 -internal"),
    ("wt", "explain wm-trace"),
];

/// The alias table: name to the words it expands to.
#[derive(Debug, Clone)]
pub struct Aliases {
    map: IndexMap<String, Vec<String>>,
}

impl Default for Aliases {
    fn default() -> Self {
        let map = DEFAULT_ALIASES
            .iter()
            .map(|(k, v)| (k.to_string(), v.split(' ').map(str::to_string).collect()))
            .collect();
        Aliases { map }
    }
}

impl Aliases {
    pub fn get(&self, name: &str) -> Option<&[String]> {
        self.map.get(name).map(Vec::as_slice)
    }
    /// The alias names, in the order they were defined.
    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.map.keys().map(String::as_str)
    }
    pub fn set(&mut self, name: &str, expansion: Vec<String>) {
        self.map.insert(name.to_string(), expansion);
    }
    pub fn remove(&mut self, name: &str) -> bool {
        self.map.shift_remove(name).is_some()
    }
    /// The `alias` listing, sorted by name as 9.6 prints it.
    pub fn listing(&self) -> String {
        let mut names: Vec<&String> = self.map.keys().collect();
        names.sort();
        let width = names.iter().map(|n| n.len()).max().unwrap_or(0).max(24);
        let mut s = String::from(
            "===========================================\n               Soar Aliases                \n===========================================\n",
        );
        for n in names {
            s.push_str(&format!("{:<width$} = {}\n", n, self.map[n].join(" ")));
        }
        s
    }
}
