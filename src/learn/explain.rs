//! The explainer's records (Soar manual, ch. 4, "Explaining Learned Procedural Knowledge",
//! and ch. 9, `explain`): which learned rules it keeps a record of. With `all`, every chunk;
//! with `record RULE`, the chunks a rule's firings give (and, in turn, theirs); with
//! `justifications`, justifications too. Records are numbered in one sequence (`c 1`,
//! `c 2`, ...) and go at `init-soar`, as in soar-sml 9.6.5.

/// One learned rule the explainer recorded.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Recorded {
    pub name: String,
    /// Its number among the records (`c N`).
    pub id: u64,
    pub is_chunk: bool,
}

/// `explain`'s settings and records.
#[derive(Debug, Clone)]
pub struct Explainer {
    /// `explain all`: record every chunk.
    pub all: bool,
    /// `explain justifications`: record justifications too.
    pub justifications: bool,
    /// `explain only-chunk-identities`.
    pub only_chunk_identities: bool,
    /// The rules `explain record` named, oldest first.
    pub recorded_rules: Vec<String>,
    /// Those rules and the chunks learned from their firings (which are watched in turn),
    /// oldest first.
    pub watched: Vec<String>,
    /// The records, oldest first.
    pub records: Vec<Recorded>,
    next_id: u64,
}

impl Default for Explainer {
    fn default() -> Self {
        Explainer {
            all: false,
            justifications: false,
            only_chunk_identities: true,
            recorded_rules: Vec::new(),
            watched: Vec::new(),
            records: Vec::new(),
            next_id: 0,
        }
    }
}

impl Explainer {
    /// `explain record RULE`.
    pub fn watch(&mut self, rule: &str) {
        if !self.recorded_rules.iter().any(|r| r == rule) {
            self.recorded_rules.push(rule.to_string());
        }
        if !self.watched.iter().any(|r| r == rule) {
            self.watched.push(rule.to_string());
        }
    }

    /// A rule was learned from a firing of `base`: recorded if the settings ask for it.
    /// (9.6 records nothing while learning is off.)
    pub fn note_learned(&mut self, name: &str, base: &str, is_chunk: bool) {
        let watched = self.watched.iter().any(|r| r == base);
        let wanted = if is_chunk {
            self.all || watched
        } else {
            self.justifications && (self.all || watched)
        };
        if !wanted {
            return;
        }
        if is_chunk && watched && !self.watched.iter().any(|r| r == name) {
            self.watched.push(name.to_string());
        }
        self.next_id += 1;
        self.records.push(Recorded {
            name: name.to_string(),
            id: self.next_id,
            is_chunk,
        });
    }

    /// The record a word names: a rule's name or a record's number.
    pub fn find(&self, word: &str) -> Option<&Recorded> {
        let id = word.parse::<u64>().ok();
        self.records
            .iter()
            .find(|r| r.name == word || Some(r.id) == id)
    }

    /// `init-soar`: the records go; the settings and the watched rules stay.
    pub fn reset_for_init(&mut self) {
        self.records.clear();
        self.next_id = 0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_watched_rules_chunks_are_recorded_and_watched_in_turn() {
        let mut e = Explainer::default();
        e.watch("sub*a");
        e.note_learned("chunk*sub*a*t3-1", "sub*a", true);
        e.note_learned("chunk*sub*b*t3-2", "sub*b", true);
        e.note_learned("chunk*x*t4-1", "chunk*sub*a*t3-1", true);
        let names: Vec<&str> = e.records.iter().map(|r| r.name.as_str()).collect();
        assert_eq!(names, ["chunk*sub*a*t3-1", "chunk*x*t4-1"]);
        assert_eq!(e.records[1].id, 2);
        assert_eq!(e.find("2").map(|r| r.name.as_str()), Some("chunk*x*t4-1"));
    }

    #[test]
    fn justifications_need_their_setting_and_share_the_numbers() {
        let mut e = Explainer {
            all: true,
            ..Explainer::default()
        };
        e.note_learned("justify*a*t3-1", "a", false);
        assert!(e.records.is_empty());
        e.justifications = true;
        e.note_learned("justify*a*t3-2", "a", false);
        e.note_learned("chunk*a*t3-3", "a", true);
        assert_eq!(e.find("justify*a*t3-2").map(|r| r.id), Some(1));
        assert_eq!(e.find("chunk*a*t3-3").map(|r| r.id), Some(2));
        e.reset_for_init();
        assert!(e.records.is_empty());
    }
}
