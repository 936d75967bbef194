//! The input phase's side of `save percepts` and `load percepts` (`percepts.rs`): the
//! changes about to be applied are recorded, and the replayed ones are made, as the
//! program that made them did.

use crate::agent::AgentCore;
use crate::inputs::InputChange;
use crate::percepts::{Action, Capture, Replay};
use crate::symbols::SymData;
use crate::value::Value;
use std::path::PathBuf;

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
                InputChange::Add(w, tt) => {
                    let Some(wme) = self.wm.get(w).filter(|x| x.timetag == tt) else {
                        continue;
                    };
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
                InputChange::Remove(w, tt) => match self.wm.get(w).filter(|x| x.timetag == tt) {
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
