//! The parameters of episodic memory as `epmem --get`/`--set` read and write them (Soar
//! manual, ch. 9, `epmem`): their names, 9.6's defaults, the values each accepts, and the
//! listing `epmem` prints. Data only; the memory reads the typed getters.

/// What a parameter accepts.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    /// One of a list of words.
    Words(&'static [&'static str]),
    /// Any text (a path).
    Text,
    /// A number from 0 to 1.
    Fraction,
    /// An integer above 1.
    Count,
    /// The set of excluded attributes: a word toggles its membership.
    Set,
}

const ON_OFF: &[&str] = &["on", "off"];

/// Why `--set` was refused, as 9.6 words it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SetError {
    /// Not a parameter.
    Name,
    /// Not a value the parameter takes.
    Value,
    /// A store setting while the database is open.
    Protected,
}

#[derive(Debug, Clone, PartialEq)]
struct Param {
    name: &'static str,
    kind: Kind,
    value: String,
}

/// Every parameter of `epmem`, with 9.6's defaults.
#[derive(Debug, Clone, PartialEq)]
pub struct EpmemParams {
    params: Vec<Param>,
    /// `exclusions`, in the order they were added.
    exclusions: Vec<String>,
}

/// The parameters that cannot change while the database is open (they shape the store).
const PROTECTED: [&str; 4] = ["lazy-commit", "page-size", "cache-size", "optimization"];

impl Default for EpmemParams {
    fn default() -> Self {
        let p = |name, kind, value: &str| Param {
            name,
            kind,
            value: value.to_string(),
        };
        EpmemParams {
            params: vec![
                p("learning", Kind::Words(ON_OFF), "off"),
                p("phase", Kind::Words(&["output", "selection"]), "output"),
                p("trigger", Kind::Words(&["none", "output", "dc"]), "dc"),
                p("force", Kind::Words(&["remember", "ignore", "off"]), "off"),
                p("exclusions", Kind::Set, ""),
                p("database", Kind::Words(&["memory", "file"]), "memory"),
                p("append", Kind::Words(ON_OFF), "off"),
                p("path", Kind::Text, ""),
                p("lazy-commit", Kind::Words(ON_OFF), "on"),
                p("graph-match", Kind::Words(ON_OFF), "on"),
                p("balance", Kind::Fraction, "1"),
                p("timers", Kind::Words(&["off", "one", "two", "three"]), "off"),
                p(
                    "page-size",
                    Kind::Words(&["1k", "2k", "4k", "8k", "16k", "32k", "64k"]),
                    "8k",
                ),
                p("cache-size", Kind::Count, "10000"),
                p(
                    "optimization",
                    Kind::Words(&["safety", "performance"]),
                    "performance",
                ),
                p(
                    "graph-match-ordering",
                    Kind::Words(&["undefined", "dfs", "mcv"]),
                    "undefined",
                ),
                p("merge", Kind::Words(&["none", "add"]), "none"),
            ],
            exclusions: vec!["epmem".into(), "smem".into()],
        }
    }
}

impl EpmemParams {
    fn find(&self, name: &str) -> Option<&Param> {
        self.params.iter().find(|p| p.name == name)
    }

    /// A parameter's value as `--get` prints it, or `None` for an unknown name.
    pub fn get(&self, name: &str) -> Option<String> {
        let p = self.find(name)?;
        Some(match p.kind {
            Kind::Set => self.exclusions.join(", "),
            Kind::Fraction => format!("{}", p.value.parse::<f64>().unwrap_or(0.0)),
            _ => p.value.clone(),
        })
    }

    /// Sets a parameter; `open` says whether the database is open.
    pub fn set(&mut self, name: &str, value: &str, open: bool) -> Result<(), SetError> {
        let Some(p) = self.params.iter_mut().find(|p| p.name == name) else {
            return Err(SetError::Name);
        };
        let ok = match p.kind {
            Kind::Words(words) => words.contains(&value),
            Kind::Text | Kind::Set => true,
            Kind::Fraction => value
                .trim()
                .parse::<f64>()
                .is_ok_and(|x| (0.0..=1.0).contains(&x)),
            Kind::Count => value.trim().parse::<i64>().is_ok_and(|x| x > 1),
        };
        if !ok {
            return Err(SetError::Value);
        }
        if open && PROTECTED.contains(&name) {
            return Err(SetError::Protected);
        }
        if p.kind == Kind::Set {
            // A word already excluded is let back in (observed on soar-sml 9.6.5).
            match self.exclusions.iter().position(|x| x == value) {
                Some(i) => {
                    self.exclusions.remove(i);
                }
                None => self.exclusions.push(value.to_string()),
            }
        } else {
            p.value = value.to_string();
        }
        Ok(())
    }

    /// `timers` as a level: `off` 0, `one` 1, `two` 2, `three` 3.
    pub fn timers(&self) -> u8 {
        crate::memory_timers::MemoryTimers::level_of(self.word("timers"))
    }

    fn word(&self, name: &str) -> &str {
        self.find(name).map_or("", |p| p.value.as_str())
    }

    pub fn learning(&self) -> bool {
        self.word("learning") == "on"
    }

    /// Episodes are stored and commands answered at the output phase (not before the
    /// decision phase's selection).
    pub fn at_output(&self) -> bool {
        self.word("phase") == "output"
    }

    pub fn trigger(&self) -> &str {
        self.word("trigger")
    }

    pub fn force(&self) -> &str {
        self.word("force")
    }

    /// `force` goes back to `off` once used.
    pub fn clear_force(&mut self) {
        let _ = self.set("force", "off", false);
    }

    pub fn excluded(&self, attr: &str) -> bool {
        self.exclusions.iter().any(|x| x == attr)
    }




    pub fn graph_match(&self) -> bool {
        self.word("graph-match") == "on"
    }

    /// `balance`: below 1, each cue WME weighs its working-memory activation.
    pub fn balance(&self) -> f64 {
        self.word("balance").parse().unwrap_or(1.0)
    }



    /// `epmem` and `epmem ?`: the settings in 9.6's layout.
    pub fn listing(&self) -> String {
        let row = |name: &str| {
            let value = self.get(name).unwrap_or_default();
            let width = 40usize.saturating_sub(name.len() + 1);
            format!("{name}:{value:>width$}\n")
        };
        let mut s = String::new();
        s.push_str("========================================\n");
        s.push_str("        Episodic Memory Settings        \n");
        s.push_str("========================================\n");
        s.push_str(&row("learning"));
        let groups: [(&str, &[&str]); 5] = [
            ("Encoding", &["phase", "trigger", "force", "exclusions"]),
            ("Storage", &["database", "append", "path", "lazy-commit"]),
            ("Retrieval", &["balance", "graph-match", "graph-match-ordering"]),
            (
                "Performance",
                &["page-size", "cache-size", "optimization", "timers"],
            ),
            ("Experimental", &["merge"]),
        ];
        for (title, names) in groups {
            s.push_str(&heading(title));
            for n in names {
                s.push_str(&row(n));
            }
        }
        s.push('\n');
        s
    }
}

/// A 40-column heading: `--------------- Encoding ---------------`.
fn heading(title: &str) -> String {
    let inner = format!(" {title} ");
    let left = (40 - inner.len()) / 2;
    let right = 40 - inner.len() - left;
    format!("{}{inner}{}\n", "-".repeat(left), "-".repeat(right))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exclusions_toggle() {
        let mut p = EpmemParams::default();
        p.set("exclusions", "foo", false).unwrap();
        assert_eq!(p.get("exclusions").unwrap(), "epmem, smem, foo");
        p.set("exclusions", "foo", false).unwrap();
        assert_eq!(p.get("exclusions").unwrap(), "epmem, smem");
        assert!(p.excluded("smem"));
    }

    #[test]
    fn refusals() {
        let mut p = EpmemParams::default();
        assert_eq!(p.set("balance", "2", false), Err(SetError::Value));
        assert_eq!(p.set("cache-size", "0", false), Err(SetError::Value));
        assert_eq!(p.set("nope", "0", false), Err(SetError::Name));
        assert_eq!(p.set("lazy-commit", "off", true), Err(SetError::Protected));
        assert!(p.set("path", "/x", true).is_ok());
    }

    #[test]
    fn headings_are_centred_as_9_6_prints_them() {
        assert_eq!(heading("Encoding"), "--------------- Encoding ---------------\n");
        assert_eq!(heading("Storage"), "--------------- Storage ----------------\n");
        assert_eq!(heading("Retrieval"), "-------------- Retrieval ---------------\n");
    }
}
