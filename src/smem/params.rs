//! The parameters of semantic memory as `smem --get`/`--set` read and write them (Soar
//! manual, ch. 9, `smem`): their names, 9.6's defaults, the values each accepts, and the
//! listing `smem ?` prints. Data only; the memory reads the typed getters.

/// What a parameter accepts.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    /// One of a list of words.
    Words(&'static [&'static str]),
    /// Any text (a path).
    Text,
    /// A number, kept as 9.6 reads it: the leading number of the text, 0 without one.
    Number,
    /// A number above zero; anything else is refused.
    Positive,
    /// `page-size`: one of SQLite's page sizes, written with `k`.
    PageSize,
    /// `base-incremental-threshes`: the thresholds of the incremental update policy.
    Threshes,
}

const ON_OFF: &[&str] = &["on", "off"];

/// A parameter: name, kind, and value as `--get` prints it.
#[derive(Debug, Clone, PartialEq)]
struct Param {
    name: &'static str,
    kind: Kind,
    value: String,
}

/// Why `--set` was refused, as 9.6 words it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SetError {
    /// Not a parameter: `Invalid SMem parameter.`
    Name,
    /// Not a value the parameter takes: `Invalid setting for SMem parameter.`
    Value,
    /// A store setting while the database is open.
    Protected,
    /// `spreading on` while `activation-mode` is not `base-level`.
    SpreadingNeedsBaseLevel,
    /// `activation-mode` while spreading is on.
    ModeWhileSpreading,
    /// A setting of the spreading model while spreading is on.
    SpreadingLocked,
}

/// The spreading settings 9.6 fixes while spreading is on (the fingerprints already made
/// depend on them).
const SPREAD_LOCKED: [&str; 6] = [
    "spreading-limit",
    "spreading-depth-limit",
    "spreading-baseline",
    "spreading-continue-probability",
    "spreading-loop-avoidance",
    "spreading-wma-source",
];

/// Every parameter of `smem`, with 9.6's defaults.
#[derive(Debug, Clone, PartialEq)]
pub struct SmemParams {
    params: Vec<Param>,
}

/// The parameters whose numbers are integers.
const INTEGERS: [&str; 4] = ["thresh", "cache-size", "spreading-limit", "spreading-depth-limit"];

/// The parameters that cannot change while the database is open (they shape the store).
const PROTECTED: [&str; 7] = [
    "database",
    "path",
    "page-size",
    "cache-size",
    "optimization",
    "spreading-limit",
    "spreading-depth-limit",
];

impl Default for SmemParams {
    fn default() -> Self {
        let p = |name, kind, value: &str| Param {
            name,
            kind,
            value: value.to_string(),
        };
        SmemParams {
            params: vec![
                p("learning", Kind::Words(ON_OFF), "off"),
                p("database", Kind::Words(&["memory", "file"]), "memory"),
                p("append", Kind::Words(ON_OFF), "on"),
                p("path", Kind::Text, ""),
                p("lazy-commit", Kind::Words(ON_OFF), "on"),
                p(
                    "optimization",
                    Kind::Words(&["safety", "performance"]),
                    "performance",
                ),
                p("cache-size", Kind::Positive, "10000"),
                p("page-size", Kind::PageSize, "8k"),
                p("timers", Kind::Words(&["off", "one", "two", "three"]), "off"),
                p("thresh", Kind::Number, "100"),
                p(
                    "activation-mode",
                    Kind::Words(&["recency", "frequency", "base-level"]),
                    "recency",
                ),
                p("activate-on-query", Kind::Words(ON_OFF), "on"),
                p("base-decay", Kind::Positive, "0.5"),
                p(
                    "base-update-policy",
                    Kind::Words(&["stable", "naive", "incremental"]),
                    "stable",
                ),
                p("base-incremental-threshes", Kind::Threshes, "10"),
                p("base-inhibition", Kind::Words(ON_OFF), "off"),
                p("spreading", Kind::Words(ON_OFF), "off"),
                p("spreading-limit", Kind::Number, "300"),
                p("spreading-depth-limit", Kind::Number, "10"),
                p("spreading-baseline", Kind::Positive, "0.0001"),
                p("spreading-continue-probability", Kind::Positive, "0.9"),
                p("spreading-loop-avoidance", Kind::Words(ON_OFF), "off"),
                p("spreading-edge-updating", Kind::Words(ON_OFF), "off"),
                p("spreading-wma-source", Kind::Words(ON_OFF), "off"),
                p("spreading-edge-update-factor", Kind::Positive, "0.99"),
            ],
        }
    }
}

/// The leading number of a text, as C's `strtod` reads it (0 without one).
fn leading_number(text: &str) -> f64 {
    let t = text.trim_start();
    let mut end = 0;
    let mut best = 0.0;
    for (i, _) in t.char_indices().skip(1).chain(std::iter::once((t.len(), ' '))) {
        if let Ok(x) = t[..i].parse::<f64>() {
            if !t[..i].ends_with(['e', 'E', '+', '-']) {
                best = x;
                end = i;
            }
        }
    }
    if end == 0 {
        0.0
    } else {
        best
    }
}

/// A number as `--get` prints it (the shortest text that reads back as it).
fn number_text(x: f64) -> String {
    format!("{x}")
}

impl SmemParams {
    fn find(&self, name: &str) -> Option<&Param> {
        self.params.iter().find(|p| p.name == name)
    }

    /// A parameter's value as `--get` prints it, or `None` for an unknown name.
    pub fn get(&self, name: &str) -> Option<String> {
        let p = self.find(name)?;
        Some(match p.kind {
            // The integer parameters keep the integer part (9.6 reads them as integers).
            Kind::Number | Kind::Positive if INTEGERS.contains(&p.name) => {
                number_text(leading_number(&p.value).trunc())
            }
            Kind::Number | Kind::Positive => number_text(leading_number(&p.value)),
            Kind::Threshes => p.value.replace(',', ", "),
            _ => p.value.clone(),
        })
    }

    /// Sets a parameter; `open` says whether the database is open.
    pub fn set(&mut self, name: &str, value: &str, open: bool) -> Result<(), SetError> {
        let Some(kind) = self.find(name).map(|p| p.kind) else {
            return Err(SetError::Name);
        };
        let ok = match kind {
            Kind::Words(words) => words.contains(&value),
            Kind::Text | Kind::Number => true,
            Kind::Positive => value.trim().parse::<f64>().is_ok_and(|x| x > 0.0),
            Kind::PageSize => ["1k", "2k", "4k", "8k", "16k", "32k", "64k"].contains(&value),
            Kind::Threshes => true,
        };
        if !ok {
            return Err(SetError::Value);
        }
        // Spreading adds to base-level activation, so 9.6 ties the two settings.
        if name == "spreading" && value == "on" && self.mode() != Mode::BaseLevel {
            return Err(SetError::SpreadingNeedsBaseLevel);
        }
        if name == "activation-mode" && self.spreading() {
            return Err(SetError::ModeWhileSpreading);
        }
        if SPREAD_LOCKED.contains(&name) && self.spreading() {
            return Err(SetError::SpreadingLocked);
        }
        if open && PROTECTED.contains(&name) {
            return Err(SetError::Protected);
        }
        let Some(p) = self.params.iter_mut().find(|p| p.name == name) else {
            return Err(SetError::Name);
        };
        p.value = match p.kind {
            // 9.6 adds the list's first number to its thresholds, if it is a new one
            // above zero (observed on soar-sml 9.6.5: `1,2,3` after `10` gives `10, 1`).
            Kind::Threshes => {
                let n = leading_number(value) as i64;
                let known = p.value.split(',').any(|x| x == n.to_string());
                if n > 0 && !known {
                    format!("{},{n}", p.value)
                } else {
                    p.value.clone()
                }
            }
            _ => value.to_string(),
        };
        Ok(())
    }

    fn word(&self, name: &str) -> &str {
        self.find(name).map_or("", |p| p.value.as_str())
    }

    /// A number parameter as 9.6 reads it.
    pub fn number(&self, name: &str) -> f64 {
        self.find(name).map_or(0.0, |p| leading_number(&p.value))
    }

    /// Whether an on/off parameter is on.
    pub fn on(&self, name: &str) -> bool {
        self.word(name) == "on"
    }

    /// `database file`: the store is the file at `path`.
    pub fn in_file(&self) -> bool {
        self.word("database") == "file"
    }

    pub fn path(&self) -> &str {
        self.word("path")
    }

    pub fn append(&self) -> bool {
        self.on("append")
    }

    pub fn lazy_commit(&self) -> bool {
        self.on("lazy-commit")
    }

    pub fn safety(&self) -> bool {
        self.word("optimization") == "safety"
    }

    pub fn cache_size(&self) -> i64 {
        self.number("cache-size") as i64
    }

    /// The page size in bytes.
    pub fn page_size(&self) -> i64 {
        leading_number(self.word("page-size")) as i64 * 1024
    }

    pub fn activate_on_query(&self) -> bool {
        self.on("activate-on-query")
    }

    pub fn mode(&self) -> Mode {
        match self.word("activation-mode") {
            "frequency" => Mode::Frequency,
            "base-level" => Mode::BaseLevel,
            _ => Mode::Recency,
        }
    }

    pub fn base_decay(&self) -> f64 {
        self.number("base-decay")
    }

    /// `timers` as a level: `off` 0, `one` 1, `two` 2, `three` 3.
    pub fn timers(&self) -> u8 {
        crate::memory_timers::MemoryTimers::level_of(self.word("timers"))
    }

    /// `base-update-policy`: when base-level activations are computed again.
    pub fn update_policy(&self) -> UpdatePolicy {
        match self.word("base-update-policy") {
            "naive" => UpdatePolicy::Naive,
            "incremental" => UpdatePolicy::Incremental,
            _ => UpdatePolicy::Stable,
        }
    }

    /// `base-incremental-threshes`, ascending: the ages (on semantic memory's clock) at
    /// which the incremental policy recomputes an LTI's activation.
    pub fn incremental_threshes(&self) -> Vec<i64> {
        let mut t: Vec<i64> = self
            .word("base-incremental-threshes")
            .split(',')
            .filter_map(|x| x.trim().parse().ok())
            .collect();
        t.sort_unstable();
        t.dedup();
        t
    }

    /// `base-inhibition on`: a recently accessed LTI's base-level activation is lowered.
    pub fn inhibition(&self) -> bool {
        self.on("base-inhibition")
    }

    /// `spreading on`: LTIs in working memory spread activation to the LTIs they reach.
    pub fn spreading(&self) -> bool {
        self.on("spreading")
    }

    /// `smem ?`: the settings and sub-commands, in 9.6's layout.
    pub fn listing(&self, enabled: bool) -> String {
        let row = |name: &str, value: &str, what: &str| {
            let width = 55usize.saturating_sub(name.len());
            format!("{name}{value:>width$}   {what}\n")
        };
        let v = |name: &str| self.get(name).unwrap_or_default();
        let mut s = String::new();
        s.push_str("=======================================================\n");
        s.push_str("-      Semantic Memory Sub-Commands and Options       -\n");
        s.push_str("=======================================================\n");
        s.push_str(&row("enabled", if enabled { "on" } else { "off" }, ""));
        s.push_str(&row(
            "database",
            &v("database"),
            "Store database in memory or file",
        ));
        s.push_str(&row("append", &v("append"), "Append or overwrite after init"));
        s.push_str(&row("path", &v("path"), "Path to database on disk"));
        s.push_str("-------------------------------------------------------\n");
        for (a, b, c) in [
            ("smem [? | help]", "", "Print this help screen"),
            (
                "smem [--enable | --disable ]",
                "",
                "Enable/disable semantic memory",
            ),
            (
                "smem [--get | --set]",
                "<option> [<value>]",
                "Print or set value of an SMem parameter",
            ),
            (
                "smem --add",
                "{ (id ^attr value)* }",
                "Add concepts to semantic memory",
            ),
            ("smem --backup", "<filename>", "Saves a copy of database"),
            ("smem --clear", "", "Deletes all semantic knowledge"),
            (
                "smem --export",
                "<filename> [<LTI>]",
                "Export database to text file",
            ),
            ("smem --init", "", "Reinitialize semantic memory store"),
            (
                "smem --query",
                "{(cue)* [<num>]}",
                "Query for concepts in semantic store matching cue",
            ),
            (
                "smem --remove",
                "{ (id [^attr [value]])* }",
                "Remove semantic memory structures",
            ),
        ] {
            s.push_str(&row(a, b, c));
        }
        s.push_str("------------------------ Printing ---------------------\n");
        s.push_str(&row("print", "@", "Print all of semantic memory"));
        s.push_str(&row("print", "<LTI>", "Print specific semantic memory"));
        s.push_str(&row(
            "smem --history",
            "<LTI>",
            "Print activation history for some LTM",
        ));
        s.push_str("---------------------- Activation --------------------\n");
        for (name, what) in [
            ("activation-mode", "recency, frequency, base-level"),
            ("activate-on-query", "on, off"),
            (
                "base-decay",
                "Decay parameter for base-level activation computation",
            ),
            ("base-update-policy", "stable, naive, incremental"),
            ("base-incremental-threshes", "integer > 0"),
            ("thresh", "integer >= 0"),
            ("base-inhibition", "on, off"),
        ] {
            s.push_str(&row(name, &v(name), what));
        }
        s.push_str("------------ Experimental Spreading Activation --------\n");
        for (name, what) in [
            ("spreading", "on, off"),
            ("spreading-limit", "integer > 0"),
            ("spreading-depth-limit", "integer > 0"),
            ("spreading-baseline", "1 > decimal > 0"),
            ("spreading-continue-probability", "1 > decimal > 0"),
            ("spreading-loop-avoidance", "on, off"),
            ("spreading-edge-updating", "on, off"),
            ("spreading-wma-source", "on, off"),
            ("spreading-edge-update-factor", "1 > decimal > 0"),
        ] {
            s.push_str(&row(name, &v(name), what));
        }
        s.push_str("------------- Database Optimization Settings ----------\n");
        for (name, what) in [
            ("lazy-commit", "Delay writing semantic store until exit"),
            ("optimization", "safety, performance"),
            ("cache-size", "Number of memory pages used for SQLite cache"),
            ("page-size", "Size of each memory page used"),
        ] {
            s.push_str(&row(name, &v(name), what));
        }
        s.push_str("----------------- Timers and Statistics ---------------\n");
        s.push_str(&row(
            "timers <detail>",
            &v("timers"),
            "How detailed timers should be (use --set)",
        ));
        s.push_str(&row(
            "smem --timers",
            "[<timer>]",
            "Print timer summary or specific statistic",
        ));
        s.push_str(&row(
            "smem --stats",
            "[<stat>]",
            "Print statistic summary or specific statistic",
        ));
        s.push_str("                  ---------------------\n");
        s.push_str("Detail: off, one, two, three\n");
        s.push_str("Timers: smem_api, smem_hash, smem_init, smem_query,\n");
        s.push_str("        smem_ncb_retrieval, three_activation\n");
        s.push_str("        smem_storage, _total\n");
        s.push_str("Stats:  act_updates, db-lib-version, edges, mem-usage,\n");
        s.push_str("        mem-high, nodes, queries, retrieves, stores\n");
        s.push_str("-------------------------------------------------------\n");
        s.push('\n');
        s.push_str(&row(
            "For a detailed explanation of these settings:",
            "",
            "help smem",
        ));
        s
    }
}

/// How an LTI's activation is computed (`activation-mode`; Soar manual, Semantic Memory,
/// "Retrieval").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// The time of the last activation.
    Recency,
    /// The number of activations.
    Frequency,
    /// The log-odds of Σ (now − t + 1)^−d over the activation history.
    BaseLevel,
}

/// When base-level activations are computed again (`base-update-policy`; Soar manual,
/// Semantic Memory, "Retrieval").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UpdatePolicy {
    /// Only when the LTI itself is activated.
    Stable,
    /// Also every candidate of a query's walk, just before it.
    Naive,
    /// Also, at each activation, the LTIs last activated a threshold's age ago.
    Incremental,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_as_9_6_reads_them() {
        assert_eq!(leading_number("1.5"), 1.5);
        assert_eq!(leading_number("abc"), 0.0);
        assert_eq!(leading_number("12x"), 12.0);
        assert_eq!(leading_number("1e-2"), 0.01);
    }

    #[test]
    fn set_and_get() {
        let mut p = SmemParams::default();
        assert_eq!(p.set("base-decay", "0", false), Err(SetError::Value));
        assert_eq!(p.set("nope", "0", false), Err(SetError::Name));
        assert_eq!(p.set("path", "/x", true), Err(SetError::Protected));
        p.set("base-incremental-threshes", "1,2,3", false).unwrap();
        assert_eq!(p.get("base-incremental-threshes").unwrap(), "10, 1");
        p.set("base-decay", "1e-2", false).unwrap();
        assert_eq!(p.get("base-decay").unwrap(), "0.01");
    }
}
