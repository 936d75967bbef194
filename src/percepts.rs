//! Recording and replaying input (Soar manual, ch. 9, `save percepts` and `load percepts`):
//! the input-link changes a program makes, written decision by decision, and applied again
//! at the same decisions from the file. The file's first line is the random seed the
//! recording started with (drawn from the agent's generator, which is then seeded with it),
//! so that a replay makes the same random choices; each other line is one change:
//!
//! ```text
//! DECISION TAG add-wme ID ATTRIBUTE VALUE TYPE
//! DECISION TAG remove-wme
//! ```
//!
//! with `TYPE` one of `string`, `int`, `float`, `id`; `TAG` names the change so that its
//! removal can refer to it (9.6 writes its client's negative timetags there, rusoar the
//! negated timetag of the WME). The input phase records and replays (`percepts_phase.rs`).

use crate::inputs::InputWme;
use crate::symbols::Sym;
use rustc_hash::FxHashMap;
use std::path::PathBuf;

/// An input recording in progress.
#[derive(Debug)]
pub(crate) struct Capture {
    pub(crate) path: PathBuf,
    /// The lines not written to the file yet.
    pub(crate) pending: String,
}

/// One recorded change.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Action {
    Add {
        id: String,
        attr: String,
        value: String,
        kind: String,
    },
    Remove,
}

/// A replay in progress: the changes still to apply, and what earlier ones made.
#[derive(Debug, Default)]
pub(crate) struct Replay {
    /// (decision, tag, change), in the file's order.
    pub(crate) actions: Vec<(u64, i64, Action)>,
    pub(crate) next: usize,
    /// The input WMEs made so far, by tag.
    pub(crate) made: FxHashMap<i64, InputWme>,
    /// The identifiers made so far, by the name the file gives them.
    pub(crate) ids: FxHashMap<String, Sym>,
}

/// A line of a percepts file that cannot be read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BadLine {
    pub line: usize,
    pub text: String,
}

/// Reads a percepts file: its seed and its changes.
pub(crate) fn parse(text: &str) -> Result<(u32, Replay), BadLine> {
    let bad = |line: usize, text: &str| BadLine {
        line,
        text: text.to_string(),
    };
    let mut lines = text.lines().enumerate();
    let seed = match lines.next() {
        Some((_, l)) => l.trim().parse::<u32>().map_err(|_| bad(1, l))?,
        None => return Err(bad(1, "")),
    };
    let mut replay = Replay::default();
    for (i, line) in lines {
        if line.trim().is_empty() {
            continue;
        }
        let words: Vec<&str> = line.split_whitespace().collect();
        let (Some(dc), Some(tag)) = (
            words.first().and_then(|w| w.parse::<u64>().ok()),
            words.get(1).and_then(|w| w.parse::<i64>().ok()),
        ) else {
            return Err(bad(i + 1, line));
        };
        let action = match &words[2..] {
            ["remove-wme"] => Action::Remove,
            ["add-wme", id, attr, value @ .., kind] if !value.is_empty() => Action::Add {
                id: id.to_string(),
                attr: attr.to_string(),
                value: value.join(" "),
                kind: kind.to_string(),
            },
            _ => return Err(bad(i + 1, line)),
        };
        replay.actions.push((dc, tag, action));
    }
    Ok((seed, replay))
}

impl Replay {
    /// How many changes the file holds.
    pub(crate) fn len(&self) -> usize {
        self.actions.len()
    }
}
