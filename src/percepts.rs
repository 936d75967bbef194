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
//! negated timetag of the WME).

use crate::agent::AgentCore;
use crate::inputs::{InputChange, InputWme};
use crate::symbols::{Sym, SymData};
use crate::value::Value;
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
enum Action {
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
    actions: Vec<(u64, i64, Action)>,
    next: usize,
    /// The input WMEs made so far, by tag.
    made: FxHashMap<i64, InputWme>,
    /// The identifiers made so far, by the name the file gives them.
    ids: FxHashMap<String, Sym>,
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

impl AgentCore {
    /// Starts recording input to `path`: a seed drawn from the agent's generator seeds it
    /// and heads the file. Returns the seed.
    pub(crate) fn start_capture(&mut self, path: PathBuf) -> u32 {
        let seed = self.rng.next_u32();
        self.seed_rng(seed);
        self.capture = Some(Capture {
            path,
            pending: format!("{seed}\n"),
        });
        seed
    }

    /// Records the input changes about to be applied at this input phase.
    pub(crate) fn capture_input_changes(&mut self) {
        let Some(capture) = self.capture.as_mut() else {
            return;
        };
        let dc = self.decider.d_cycle_count;
        for change in &self.inputs.queue {
            let line = match *change {
                InputChange::Add(w) => {
                    let Some(wme) = self.wm.get(w) else { continue };
                    let (value, kind) = match self.symbols.get(wme.value) {
                        SymData::Int(i) => (i.to_string(), "int"),
                        SymData::Float(_) => (self.symbols.text(wme.value), "float"),
                        SymData::Str(s) => (s.to_string(), "string"),
                        SymData::Id(_) => (self.symbols.text(wme.value), "id"),
                    };
                    format!(
                        "{dc} -{} add-wme {} {} {value} {kind}\n",
                        wme.timetag,
                        self.symbols.text(wme.id),
                        self.symbols.text(wme.attr),
                    )
                }
                InputChange::Remove(w) => match self.wm.get(w) {
                    Some(wme) => format!("{dc} -{} remove-wme\n", wme.timetag),
                    None => continue,
                },
            };
            capture.pending.push_str(&line);
        }
    }

    /// Applies the replayed changes of this decision, as the program that made them did.
    /// A change that cannot be made (an identifier the file never made, a removal of
    /// nothing) is skipped with a warning on the print stream.
    pub(crate) fn replay_input_changes(&mut self) {
        let Some(mut replay) = self.replay.take() else {
            return;
        };
        let dc = self.decider.d_cycle_count;
        while let Some((at, tag, action)) = replay.actions.get(replay.next).cloned() {
            if at > dc {
                break;
            }
            replay.next += 1;
            if let Err(why) = self.replay_one(&mut replay, tag, &action) {
                self.output
                    .push_str(&format!("Warning: load percepts: {why}\n"));
            }
        }
        self.replay = Some(replay);
    }

    fn replay_one(&mut self, replay: &mut Replay, tag: i64, action: &Action) -> Result<(), String> {
        match action {
            Action::Remove => {
                let h = replay
                    .made
                    .remove(&tag)
                    .ok_or_else(|| format!("no WME {tag} to remove"))?;
                self.remove_input(h).map_err(|e| e.to_string())
            }
            Action::Add {
                id,
                attr,
                value,
                kind,
            } => {
                let parent = replay
                    .ids
                    .get(id)
                    .copied()
                    .or_else(|| self.symbols.find_id(id))
                    .ok_or_else(|| format!("no identifier {id}"))?;
                let h = if kind == "id" {
                    let (h, child) = self
                        .add_input_object(parent, attr)
                        .map_err(|e| e.to_string())?;
                    replay.ids.insert(value.clone(), child);
                    h
                } else {
                    let v = match kind.as_str() {
                        "int" => Value::Int(value.parse().map_err(|_| format!("bad int {value}"))?),
                        "float" => {
                            Value::Float(value.parse().map_err(|_| format!("bad float {value}"))?)
                        }
                        _ => Value::Str(value.clone()),
                    };
                    self.add_input(parent, attr, v).map_err(|e| e.to_string())?
                };
                replay.made.insert(tag, h);
                Ok(())
            }
        }
    }
}
