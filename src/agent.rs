//! One agent: its rules and settings. Working memory, the RETE and the decision cycle join
//! here as their issues land; for now the agent keeps the production set that `sp`, `print`
//! and `excise` work against.

use crate::production::Production;
use indexmap::IndexMap;

/// When Soar learns (spec §4; `chunk always|never|only|except`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LearnMode {
    Always,
    Never,
    Only,
    Except,
}

impl LearnMode {
    pub fn word(self) -> &'static str {
        match self {
            LearnMode::Always => "always",
            LearnMode::Never => "never",
            LearnMode::Only => "only",
            LearnMode::Except => "except",
        }
    }
}

/// Kernel settings with 9.6's defaults (spec §3a, §4, §6a).
#[derive(Debug, Clone)]
pub struct Settings {
    pub learn: LearnMode,
    pub max_chunks: i64,
    pub max_dupes: i64,
    pub max_elaborations: i64,
    pub max_goal_depth: i64,
    pub max_nil_output_cycles: i64,
    pub wait_snc: bool,
    pub trace_level: u8,
    pub warnings: bool,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            learn: LearnMode::Never,
            max_chunks: 50,
            max_dupes: 3,
            max_elaborations: 100,
            max_goal_depth: 100,
            max_nil_output_cycles: 15,
            wait_snc: false,
            trace_level: 1,
            warnings: true,
        }
    }
}

/// What adding a production did (spec §1c).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Added {
    New,
    /// A rule of the same name existed and was excised first (`#*`).
    Replaced,
    /// Identical to an existing rule under another name: not added.
    Duplicate {
        of: String,
    },
}

pub struct Agent {
    pub name: String,
    productions: IndexMap<String, Production>,
    /// Canonical body text (name and variable names erased) to rule name.
    bodies: IndexMap<String, String>,
    pub settings: Settings,
    /// The exploration policy named by `indifferent-selection` (softmax by default, spec §3h).
    pub settings_policy: String,
    /// The seed given to `srand`, if any.
    pub seed: Option<u32>,
}

impl Agent {
    pub fn new(name: impl Into<String>) -> Self {
        Agent {
            name: name.into(),
            productions: IndexMap::new(),
            bodies: IndexMap::new(),
            settings: Settings::default(),
            settings_policy: "softmax".to_string(),
            seed: None,
        }
    }

    /// Adds a rule: a same-named rule is excised first; an identical body is ignored.
    pub fn add_production(&mut self, p: Production) -> Added {
        let replaced = self.excise(&p.name);
        let key = canonical_body(&p);
        if let Some(of) = self.bodies.get(&key) {
            return Added::Duplicate { of: of.clone() };
        }
        self.bodies.insert(key, p.name.clone());
        self.productions.insert(p.name.clone(), p);
        if replaced {
            Added::Replaced
        } else {
            Added::New
        }
    }

    pub fn excise(&mut self, name: &str) -> bool {
        match self.productions.shift_remove(name) {
            Some(p) => {
                self.bodies.shift_remove(&canonical_body(&p));
                true
            }
            None => false,
        }
    }

    pub fn excise_all(&mut self) -> usize {
        let n = self.productions.len();
        self.productions.clear();
        self.bodies.clear();
        n
    }

    pub fn production(&self, name: &str) -> Option<&Production> {
        self.productions.get(name)
    }

    /// Rules in load order.
    pub fn productions(&self) -> impl DoubleEndedIterator<Item = &Production> {
        self.productions.values()
    }

    pub fn production_count(&self) -> usize {
        self.productions.len()
    }
}

/// The rule's printed body with its name removed and variables renamed in order of first
/// appearance, so that two rules that differ only in those compare equal.
pub fn canonical_body(p: &Production) -> String {
    let mut copy = p.clone();
    copy.name = String::new();
    copy.doc = None;
    let text = crate::printer::production_text(&copy);
    let mut names: IndexMap<String, usize> = IndexMap::new();
    let mut out = String::with_capacity(text.len());
    let mut word = String::new();
    let flush = |word: &mut String, out: &mut String, names: &mut IndexMap<String, usize>| {
        if crate::lexer::is_variable(word) && !word.contains(' ') {
            let n = names.len();
            let id = *names.entry(word.clone()).or_insert(n);
            out.push_str(&format!("<{id}>"));
        } else {
            out.push_str(word);
        }
        word.clear();
    };
    for c in text.chars() {
        if c.is_whitespace() || c == '(' || c == ')' || c == '{' || c == '}' {
            flush(&mut word, &mut out, &mut names);
            out.push(c);
        } else {
            word.push(c);
        }
    }
    flush(&mut word, &mut out, &mut names);
    out
}
