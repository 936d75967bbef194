//! The input and output links as an embedding program uses them (Soar manual, chapter 2,
//! "Input and Output"): input WMEs are added, changed and removed between decisions through handles that
//! stay valid until removed, also across `init-soar`; commands the rules put on the
//! output-link are read and marked done.
//!
//! What an SML client sees is the model (the official kernel's `soar_sml` 9.6.5 was run on
//! each case):
//! - an added WME gets its timetag at once and reaches the matcher at the next input phase;
//! - at the input phase the pending additions are applied newest first, then the removals,
//!   newest first, each traced as `=>WM:` or `<=WM:`;
//! - changing a value removes the WME and adds a new one with the new value; with the
//!   default [`InputUpdate::BlinkIfNoChange`] this happens even when the value is the same;
//! - `init-soar` keeps the client's input WMEs: they are added again, walking the tree from
//!   the input-link depth first (each identifier's WMEs in the order they were first made),
//!   and their identifiers are numbered again in that order.

use crate::agent::AgentCore;
pub use crate::inputs::{InputUpdate, InputWme};
pub use crate::value::Value;
use crate::inputs::{InputChange, InputEntry, InputTable};
use crate::symbols::{Sym, SymData};
use crate::wm::{Wme, WmeId};
use rustc_hash::FxHashSet;

/// A misuse of the input and output links.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum IoError {
    /// A WME needs an identifier to hang from, and this symbol is a constant.
    #[error("`{0}` is a constant, not an identifier: input WMEs hang from identifiers")]
    NotAnIdentifier(String),
    /// The handle's WME was removed (by [`crate::Io::remove`], or with the object it hung
    /// from).
    #[error("the input WME was removed: its handle is no longer valid")]
    StaleHandle,
    /// The handle belongs to no input WME of this agent.
    #[error("no input WME has this handle")]
    UnknownHandle,
    /// [`crate::Io::mark_done`] was called twice for one command.
    #[error("output command `{0}` is already marked done")]
    AlreadyDone(String),
    /// A WME was to hang from an identifier that is no longer in working memory (an input
    /// object removed, and collected with what hung below it): nothing links it to a state.
    #[error("`{0}` is not in working memory: input WMEs hang from linked identifiers")]
    Unlinked(String),
}

/// One command the rules placed on the output-link: `(I3 ^name <cmd>)` and its parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct OutputCommand {
    /// The command's identifier (the value of its output-link WME).
    pub id: Sym,
    /// The command's name (the attribute of its output-link WME).
    pub name: String,
    /// The command object's (attribute, value) pairs, oldest first.
    pub params: Vec<(String, Value)>,
}

impl OutputCommand {
    /// The value of parameter `name`, if the command has it.
    pub fn param(&self, name: &str) -> Option<&Value> {
        self.params.iter().find(|(a, _)| a == name).map(|(_, v)| v)
    }

    /// Parameter `name` as an integer.
    pub fn int(&self, name: &str) -> Option<i64> {
        match self.param(name)? {
            Value::Int(i) => Some(*i),
            _ => None,
        }
    }

    /// Parameter `name` as a float; an integer is converted.
    pub fn float(&self, name: &str) -> Option<f64> {
        match self.param(name)? {
            Value::Int(i) => Some(*i as f64),
            Value::Float(f) => Some(*f),
            _ => None,
        }
    }

    /// Parameter `name` as a number: an integer, a float, or a string that reads as one.
    pub fn number(&self, name: &str) -> Option<f64> {
        self.param(name)?.as_number()
    }

    /// Parameter `name` as a string constant.
    pub fn str(&self, name: &str) -> Option<&str> {
        match self.param(name)? {
            Value::Str(s) => Some(s),
            _ => None,
        }
    }

    /// Parameter `name` as an identifier.
    pub fn id(&self, name: &str) -> Option<Sym> {
        match self.param(name)? {
            Value::Id(s) => Some(*s),
            _ => None,
        }
    }
}

impl AgentCore {
    /// The top state's `^io.input-link` identifier (it keeps its handle across `init-soar`).
    pub fn input_link(&self) -> Sym {
        self.top.input_link
    }

    /// The top state's `^io.output-link` identifier.
    pub fn output_link(&self) -> Sym {
        self.top.output_link
    }

    /// A symbol as a [`Value`].
    pub fn value_of(&self, s: Sym) -> Value {
        match self.symbols.get(s) {
            SymData::Int(i) => Value::Int(*i),
            SymData::Float(f) => Value::Float(*f),
            SymData::Str(x) => Value::Str(x.to_string()),
            SymData::Id(_) => Value::Id(s),
        }
    }

    fn value_sym(&mut self, v: &Value) -> Result<Sym, IoError> {
        Ok(match v {
            Value::Int(i) => self.symbols.int(*i),
            Value::Float(f) => self.symbols.float(*f),
            Value::Str(s) => self.symbols.str(s),
            Value::Id(s) => self.identifier(*s)?,
        })
    }

    /// `s` if it is an identifier.
    fn identifier(&self, s: Sym) -> Result<Sym, IoError> {
        if self.symbols.is_id(s) {
            Ok(s)
        } else {
            Err(IoError::NotAnIdentifier(self.symbols.text(s)))
        }
    }

    /// `s` if it is an identifier an input WME may hang from: a state, or one a WME in
    /// working memory points at. A WME under an identifier that was collected would have
    /// no link to a state, and garbage collection (which searches identifiers as they lose
    /// a link) would never take it.
    fn parent(&self, s: Sym) -> Result<Sym, IoError> {
        let id = self.identifier(s)?;
        let is_state = self.symbols.id_data(id).is_some_and(|d| d.is_goal) || id == self.top.state;
        let pointed_at = || {
            self.wm
                .parent_wmes(id)
                .iter()
                .any(|&w| self.wm.get(w).is_some())
        };
        if is_state || pointed_at() {
            Ok(id)
        } else {
            Err(IoError::Unlinked(self.symbols.text(id)))
        }
    }

    /// Adds `(id ^attr value)`: it gets its timetag now and reaches the matcher at the next
    /// input phase (see [`AgentCore::apply_input_changes`]), as an SML client's WMEs do.
    pub fn add_input(
        &mut self,
        id: Sym,
        attr: &str,
        value: impl Into<Value>,
    ) -> Result<InputWme, IoError> {
        let id = self.parent(id)?;
        let value = self.value_sym(&value.into())?;
        let attr = self.symbols.str(attr);
        Ok(self.push_input(id, attr, value, false))
    }

    /// Adds `(id ^attr <new id>)` and returns the new identifier. Its letter is the
    /// attribute's first letter, or `I` when that is not a letter or is `s` (9.6 names an
    /// SML client's `^sonar` object `I4`, keeping `S` for states; soar-sml 9.6.5).
    pub fn add_input_object(&mut self, id: Sym, attr: &str) -> Result<(InputWme, Sym), IoError> {
        let id = self.parent(id)?;
        let child = self.symbols.new_id(input_letter(attr), 1);
        let attr = self.symbols.str(attr);
        Ok((self.push_input(id, attr, child, true), child))
    }

    fn push_input(&mut self, id: Sym, attr: Sym, value: Sym, object: bool) -> InputWme {
        let wme = self.queue_input_add(id, attr, value);
        let value_is_id = self.symbols.is_id(value);
        let entry = InputTable::entry(id, attr, value, wme, object);
        self.inputs.insert(entry, value_is_id)
    }

    fn queue_input_add(&mut self, id: Sym, attr: Sym, value: Sym) -> WmeId {
        let links = self.symbols.is_id(value);
        let w = self.wm.add_typed(id, attr, value, false, links);
        let tt = self.wm.get(w).map_or(0, |x| x.timetag);
        self.inputs.queue.push(InputChange::Add(w, tt));
        w
    }

    /// The WME a queued input change names, if it is still the one with that timetag.
    pub(crate) fn queued_input(&self, w: WmeId, tt: u64) -> Option<&Wme> {
        self.wm.get(w).filter(|x| x.timetag == tt)
    }

    /// The WME of a live input entry, with its timetag; a stale handle when that WME went
    /// with an object garbage collection took.
    fn entry_wme(&self, e: &InputEntry) -> Result<(WmeId, u64), IoError> {
        let w = e.wme.ok_or(IoError::StaleHandle)?;
        match self.wm.get(w) {
            Some(x) if x.id == e.id && x.attr == e.attr && x.value == e.value => {
                Ok((w, x.timetag))
            }
            _ => Err(IoError::StaleHandle),
        }
    }

    fn live_entry(&self, h: InputWme) -> Result<&InputEntry, IoError> {
        match self.inputs.get(h) {
            Ok(Some(e)) => Ok(e),
            Ok(None) => Err(IoError::StaleHandle),
            Err(()) => Err(IoError::UnknownHandle),
        }
    }

    /// The value an input WME holds now.
    pub fn input_value(&self, h: InputWme) -> Result<Value, IoError> {
        let e = self.live_entry(h)?;
        Ok(self.value_of(e.value))
    }

    /// The working-memory element an input WME is now.
    #[cfg(test)]
    pub fn input_wme(&self, h: InputWme) -> Result<WmeId, IoError> {
        let e = self.live_entry(h)?;
        e.wme.ok_or(IoError::StaleHandle)
    }

    /// How [`AgentCore::update_input`] treats an unchanged value.
    pub fn set_input_update(&mut self, mode: InputUpdate) {
        self.inputs.update_mode = mode;
    }

    /// Changes the value of an input WME: a removal and an addition, applied at the next
    /// input phase, as SML does. Returns whether the WME was replaced (not when the value is
    /// unchanged and the mode is [`InputUpdate::SkipIfNoChange`]).
    pub fn update_input(&mut self, h: InputWme, value: impl Into<Value>) -> Result<bool, IoError> {
        let new = self.value_sym(&value.into())?;
        let e = self.live_entry(h)?;
        let (id, attr, old_value, object) = (e.id, e.attr, e.value, e.object);
        let (old, old_tt) = self.entry_wme(e)?;
        if new == old_value && self.inputs.update_mode == InputUpdate::SkipIfNoChange {
            return Ok(false);
        }
        // The WME it hangs from may have gone with an object some other change unlinked.
        self.parent(id)?;
        self.inputs.queue.push(InputChange::Remove(old, old_tt));
        let w = self.queue_input_add(id, attr, new);
        let is_id = [self.symbols.is_id(old_value), self.symbols.is_id(new)];
        self.inputs.set_value(h, new, w, is_id);
        // An object of this table replaced by another value goes as a removed one does,
        // with the handles below it.
        if object && !self.inputs.linked(old_value) {
            self.drop_entries_below(old_value);
        }
        Ok(true)
    }

    /// Removes an input WME at the next input phase; what hangs below it goes with it (the
    /// garbage collection after the input phase takes it from working memory, and the
    /// handles of the WMEs made under it become stale).
    pub fn remove_input(&mut self, h: InputWme) -> Result<(), IoError> {
        let e = self.live_entry(h)?;
        let ((old, tt), object, value) = (self.entry_wme(e)?, e.object, e.value);
        self.inputs.queue.push(InputChange::Remove(old, tt));
        self.inputs.kill(h.slot, self.symbols.is_id(value));
        if object && !self.inputs.linked(value) {
            self.drop_entries_below(value);
        }
        Ok(())
    }

    /// Marks the input WMEs under `root` (made by this table) removed, without queueing
    /// their removal: garbage collection takes them from working memory.
    fn drop_entries_below(&mut self, root: Sym) {
        let mut below = vec![root];
        while let Some(id) = below.pop() {
            for slot in self.inputs.children(id).to_vec() {
                let e = self.inputs.at(slot);
                let (object, value) = (e.object, e.value);
                self.inputs.kill(slot, self.symbols.is_id(value));
                if object && !self.inputs.linked(value) {
                    below.push(value);
                }
            }
        }
    }

    /// Applies the input-link changes made since the last input phase, as 9.6 applies an
    /// SML client's buffered changes there (`do_buffered_wm_changes`, checked with soar-sml
    /// 9.6.5): first every added WME, newest first, then every removed one, newest first,
    /// each traced as `=>WM:` or `<=WM:`. The order decides the order of new matches, so
    /// of firings, identifiers and random choices (`scripts/slam_oracle.py`). An object
    /// the removals unlink goes at once with what hangs below it, its lines before the
    /// removals' (9.6 collects garbage in the input phase too: soar-sml 9.6.5 traces
    /// `<=WM: (15: B1 ^a A1)` before `<=WM: (14: I2 ^b B1)` when `(I2 ^b B1)` is destroyed).
    pub(crate) fn apply_input_changes(&mut self) {
        if self.inputs.queue.is_empty() {
            return;
        }
        let queue = std::mem::take(&mut self.inputs.queue);
        // The passing tokens of the additions with the removals are left out where that
        // changes nothing (rete/doomed.rs).
        let (mut added, mut removed) = (Vec::new(), Vec::new());
        for change in &queue {
            match *change {
                InputChange::Add(w, tt) => added.extend(
                    self.queued_input(w, tt)
                        .map(|x| (x.attr, x.value, x.acceptable)),
                ),
                InputChange::Remove(w, tt) => {
                    if self.queued_input(w, tt).is_some() {
                        removed.push(w);
                    }
                }
            }
        }
        let batch = self.rete.begin_doomed_batch(&added, &removed);
        self.mark_queued_matches();
        for change in queue.iter().rev() {
            let InputChange::Add(w, tt) = *change else {
                continue;
            };
            let Some(wme) = self.queued_input(w, tt).copied() else {
                continue;
            };
            self.match_new_wme(w, &wme);
            self.trace_wme(true, &wme);
        }
        let mut gone = Vec::new();
        for change in queue.iter().rev() {
            let InputChange::Remove(w, tt) = *change else {
                continue;
            };
            if self.queued_input(w, tt).is_some() {
                gone.extend(self.remove_wme(w));
            }
        }
        if batch {
            self.rete.end_doomed_batch();
        }
        if !gone.is_empty() {
            self.collect_garbage();
        }
        for wme in &gone {
            self.trace_wme(false, wme);
        }
    }

    /// After `init-soar` made the top state again: the program's input WMEs are added
    /// again, as an SML client adds them, walking from the input-link depth first, each identifier's WMEs in the order they were made; the objects this table
    /// made are numbered again in that order. WMEs that hung from identifiers the rules
    /// made (a command's `^status`) are gone with them.
    pub(crate) fn reinstate_inputs(&mut self) {
        self.inputs.done.clear();
        self.inputs.output_reported = 0;
        let root = self.top.input_link;
        let mut visited: FxHashSet<Sym> = [root].into_iter().collect();
        let mut kept: FxHashSet<u32> = FxHashSet::default();
        // An explicit stack of (identifier, place in its list of entries), so deep input
        // structures cannot overflow the call stack.
        let mut stack = vec![(root, 0usize)];
        while let Some((id, k)) = stack.pop() {
            let Some(&slot) = self.inputs.children(id).get(k) else {
                continue;
            };
            stack.push((id, k + 1));
            let e = self.inputs.at(slot);
            let (attr, value, object) = (e.attr, e.value, e.object);
            let first_visit = visited.insert(value);
            if object && first_visit {
                self.symbols.renumber_id(value);
            }
            kept.insert(slot);
            let w = self.queue_input_add(id, attr, value);
            self.inputs.set_wme(slot, w);
            if first_visit && self.symbols.is_id(value) {
                stack.push((value, 0));
            }
        }
        for slot in self.inputs.live_slots() {
            if !kept.contains(&slot) {
                let value = self.inputs.at(slot).value;
                self.inputs.kill(slot, self.symbols.is_id(value));
            }
        }
    }

    /// Input WMEs waiting for the next input phase to be added.
    pub(crate) fn pending_input_additions(&self) -> u64 {
        let adds = self.inputs.queue.iter();
        adds.filter(|c| matches!(c, InputChange::Add(..))).count() as u64
    }

    /// A mark that changes when the output-link or a command on it changes: the newest
    /// timetag there and the number of WMEs (for running until output).
    pub(crate) fn output_link_stamp(&self) -> (u64, usize) {
        let mut newest = 0;
        let mut count = 0;
        for w in self.wm.of_id(self.top.output_link) {
            let Some(wme) = self.wm.get(w) else { continue };
            count += 1;
            newest = newest.max(wme.timetag);
            for x in self.wm.of_id(wme.value).filter_map(|x| self.wm.get(x)) {
                count += 1;
                newest = newest.max(x.timetag);
            }
        }
        (newest, count)
    }

    /// Commands on the output-link: each `(I3 ^name <obj>)` object with its parameters.
    pub fn output_commands(&self) -> Vec<OutputCommand> {
        self.output_commands_after(0)
    }

    /// The commands put on the output-link since the last call (or since `init-soar`), as
    /// SML reports new output commands: each once, however long it stays there.
    pub fn new_output_commands(&mut self) -> Vec<OutputCommand> {
        let after = self.inputs.output_reported;
        if let Some(tt) = self
            .wm
            .of_id(self.top.output_link)
            .filter_map(|w| self.wm.get(w).map(|x| x.timetag))
            .max()
        {
            self.inputs.output_reported = self.inputs.output_reported.max(tt);
        }
        self.output_commands_after(after)
    }

    fn output_commands_after(&self, after: u64) -> Vec<OutputCommand> {
        let mut out = Vec::new();
        for w in self.wm.of_id(self.top.output_link) {
            let Some(wme) = self.wm.get(w) else { continue };
            if wme.timetag <= after || !self.symbols.is_id(wme.value) {
                continue;
            }
            let name = self.symbols.plain(wme.attr);
            let params = self
                .wm
                .of_id(wme.value)
                .filter_map(|x| self.wm.get(x))
                .map(|x| (self.symbols.plain(x.attr), self.value_of(x.value)))
                .collect();
            out.push(OutputCommand {
                id: wme.value,
                name,
                params,
            });
        }
        out
    }

    /// Marks a command done with `^status complete`, as SML environments do; a second call
    /// for the same command is an error.
    pub fn mark_done(&mut self, cmd: Sym) -> Result<InputWme, IoError> {
        let cmd = self.identifier(cmd)?;
        if !self.inputs.done.insert(cmd) {
            return Err(IoError::AlreadyDone(self.symbols.text(cmd)));
        }
        self.add_input(cmd, "status", "complete")
    }

}

/// The letter of an input object's identifier for `^attr` (see [`AgentCore::add_input_object`]).
fn input_letter(attr: &str) -> char {
    attr.chars()
        .next()
        .filter(|c| c.is_ascii_alphabetic() && !c.eq_ignore_ascii_case(&'s'))
        .unwrap_or('I')
}

#[cfg(test)]
mod tests {
    use super::*;

    fn text(a: &AgentCore, h: InputWme) -> String {
        let w = a.input_wme(h).unwrap();
        a.symbols.text(a.wm.get(w).unwrap().value)
    }

    #[test]
    fn input_is_matched_and_output_is_read() {
        let mut a = AgentCore::new("t");
        let il = a.input_link();
        let (_, data) = a.add_input_object(il, "currentrobotdata").unwrap();
        let x = a.add_input(data, "X", 100i64).unwrap();
        assert_eq!(text(&a, x), "100");
        let tt = a.wm.get(a.input_wme(x).unwrap()).map(|w| w.timetag);
        assert!(a.update_input(x, 120i64).unwrap());
        // A changed value is a new WME (a new timetag), as SML makes it; the handle stays.
        let tt2 = a.wm.get(a.input_wme(x).unwrap()).map(|w| w.timetag);
        assert_ne!(tt, tt2);
        assert_eq!(text(&a, x), "120");
        let ol = a.output_link();
        let (_, cmd) = a.add_input_object(ol, "move").unwrap();
        a.add_input(cmd, "param1", 300i64).unwrap();
        let cmds = a.output_commands();
        assert_eq!(cmds.len(), 1);
        assert_eq!(cmds[0].name, "move");
        assert_eq!(cmds[0].int("param1"), Some(300));
        assert_eq!(cmds[0].float("param1"), Some(300.0));
        assert_eq!(cmds[0].str("param1"), None);
    }

    #[test]
    fn input_objects_are_named_as_sml_names_them() {
        let mut a = AgentCore::new("t");
        let il = a.input_link();
        let name = |a: &mut AgentCore, attr: &str| {
            let (_, id) = a.add_input_object(il, attr).unwrap();
            a.symbols.text(id)
        };
        // What soar-sml 9.6.5 printed for the same objects on a fresh agent's input-link.
        assert_eq!(name(&mut a, "currentrobotdata"), "C3");
        assert_eq!(name(&mut a, "sonar"), "I4");
        assert_eq!(name(&mut a, "Start"), "I5");
        assert_eq!(name(&mut a, "wallData"), "W1");
        assert_eq!(name(&mut a, "obj"), "O1");
        assert_eq!(name(&mut a, "1abc"), "I6");
    }

    #[test]
    fn new_output_commands_are_reported_once() {
        let mut a = AgentCore::new("t");
        let ol = a.output_link();
        let (_, c1) = a.add_input_object(ol, "move").unwrap();
        a.add_input(c1, "param1", 300i64).unwrap();
        let first = a.new_output_commands();
        assert_eq!(first.len(), 1);
        assert_eq!(first[0].name, "move");
        assert!(a.new_output_commands().is_empty());
        let (_, c2) = a.add_input_object(ol, "turn").unwrap();
        a.add_input(c2, "param1", 40i64).unwrap();
        let second = a.new_output_commands();
        assert_eq!(second.len(), 1);
        assert_eq!(second[0].name, "turn");
        // Both are still on the output-link.
        assert_eq!(a.output_commands().len(), 2);
        // WMEs a program put under the output-link do not outlive `init-soar`.
        a.init_soar();
        a.reinstate_inputs();
        assert!(a.new_output_commands().is_empty());
    }

    #[test]
    fn updates_blink_by_default_and_skip_when_asked() {
        let mut a = AgentCore::new("t");
        let il = a.input_link();
        let (_, data) = a.add_input_object(il, "pose").unwrap();
        let x = a.add_input(data, "X", 1i64).unwrap();
        let y = a.add_input(data, "Y", 2i64).unwrap();
        let wme_y = a.input_wme(y).unwrap();
        // SML's default: the same value is removed and added again.
        assert!(a.update_input(y, 2i64).unwrap());
        assert_ne!(a.input_wme(y).unwrap(), wme_y);
        a.set_input_update(InputUpdate::SkipIfNoChange);
        let wme_y = a.input_wme(y).unwrap();
        assert!(!a.update_input(y, 2i64).unwrap());
        assert_eq!(a.input_wme(y).unwrap(), wme_y);
        assert!(a.update_input(x, 5i64).unwrap());
        assert_eq!(text(&a, x), "5");
        // The old values go at the input phase.
        assert_eq!(a.wm.of_id(data).count(), 4);
        a.apply_input_changes();
        assert_eq!(a.wm.of_id(data).count(), 2);
    }

    #[test]
    fn misuse_is_an_error() {
        let mut a = AgentCore::new("t");
        let il = a.input_link();
        let five = a.symbols.int(5);
        assert!(matches!(
            a.add_input(five, "x", 1i64),
            Err(IoError::NotAnIdentifier(_))
        ));
        assert!(matches!(
            a.add_input(il, "x", Value::Id(five)),
            Err(IoError::NotAnIdentifier(_))
        ));
        let (obj, o) = a.add_input_object(il, "obj").unwrap();
        let below = a.add_input(o, "a", 1i64).unwrap();
        a.remove_input(obj).unwrap();
        assert_eq!(a.remove_input(obj), Err(IoError::StaleHandle));
        assert_eq!(a.update_input(below, 2i64), Err(IoError::StaleHandle));
        assert_eq!(a.input_value(InputWme { slot: 99, generation: 0 }), Err(IoError::UnknownHandle));
        let ol = a.output_link();
        let (_, cmd) = a.add_input_object(ol, "move").unwrap();
        a.mark_done(cmd).unwrap();
        assert!(matches!(a.mark_done(cmd), Err(IoError::AlreadyDone(_))));
    }

    /// A removed WME's place serves the next one; its old handle stays stale, and the table
    /// does not grow with adds and removes.
    #[test]
    fn places_are_reused_and_old_handles_stay_stale() {
        let mut a = AgentCore::new("t");
        let il = a.input_link();
        let first = a.add_input(il, "x", 1i64).unwrap();
        a.remove_input(first).unwrap();
        let second = a.add_input(il, "y", 2i64).unwrap();
        assert_eq!(first.slot, second.slot);
        assert_eq!(a.input_value(first), Err(IoError::StaleHandle));
        assert_eq!(a.input_value(second), Ok(Value::Int(2)));
        for n in 0..100i64 {
            let (obj, o) = a.add_input_object(il, "obj").unwrap();
            a.add_input(o, "n", n).unwrap();
            a.remove_input(obj).unwrap();
        }
        assert!(a.inputs.live_slots().len() == 1);
        let (obj, _) = a.add_input_object(il, "obj").unwrap();
        assert!(obj.slot <= 2, "the table grew to {}", obj.slot);
    }

    /// soar-sml 9.6.5 adds a client's input WMEs again after `init-soar`, depth first from
    /// the input-link, each identifier's WMEs in the order they were made (an updated WME
    /// keeps its place), and names the objects again: `(I2 ^obj O1)`, `(O1 ^a 1)`,
    /// `(I2 ^name m)`, `(I2 ^pos P1)` with timetags 14 to 17.
    #[test]
    fn init_soar_keeps_input_wmes_and_their_handles() {
        let mut a = AgentCore::new("t");
        let il = a.input_link();
        let (_, o) = a.add_input_object(il, "obj").unwrap();
        let name = a.add_input(il, "name", "n").unwrap();
        let x = a.add_input(o, "a", 1i64).unwrap();
        let (_, p) = a.add_input_object(il, "pos").unwrap();
        a.apply_input_changes();
        a.update_input(name, "m").unwrap();
        a.apply_input_changes();
        a.init_soar();
        a.reinstate_inputs();
        assert_eq!(a.input_link(), il);
        let listed: Vec<String> = a
            .inputs
            .queue
            .iter()
            .map(|c| {
                let InputChange::Add(w, _) = *c else {
                    return "removal".into();
                };
                let w = a.wm.get(w).unwrap();
                format!(
                    "({}: {} ^{} {})",
                    w.timetag,
                    a.symbols.text(w.id),
                    a.symbols.text(w.attr),
                    a.symbols.text(w.value)
                )
            })
            .collect();
        assert_eq!(
            listed,
            [
                "(14: I2 ^obj O1)",
                "(15: O1 ^a 1)",
                "(16: I2 ^name m)",
                "(17: I2 ^pos P1)"
            ]
        );
        assert_eq!(a.symbols.text(o), "O1");
        assert_eq!(a.symbols.text(p), "P1");
        assert!(a.update_input(x, 2i64).unwrap());
        assert_eq!(text(&a, x), "2");
    }

    /// 9.6 applies an SML client's changes at the input phase, the added WMEs newest first
    /// and then the removed ones (soar-sml 9.6.5 printed the same trace and firings for this
    /// input, `=>WM` lines newest first, then `<=WM` lines).
    #[test]
    fn input_changes_reach_the_matcher_at_the_input_phase_newest_first() {
        let mut i = crate::commands::Interpreter::new();
        i.run_text(
            "t",
            "sp {p (state <s> ^io.input-link <il>) (<il> ^obj <o> ^crd <c>) (<o> ^a <a>) \
             (<c> ^X <x> ^Y <y>) --> (write |fire | <a> | | <x> | | <y> (crlf))}",
        )
        .unwrap();
        let a = &mut i.agent;
        let il = a.input_link();
        for v in [1i64, 2] {
            let (_, o) = a.add_input_object(il, "obj").unwrap();
            a.add_input(o, "a", v).unwrap();
        }
        let (_, c) = a.add_input_object(il, "crd").unwrap();
        let x = a.add_input(c, "X", 10i64).unwrap();
        let y = a.add_input(c, "Y", 20i64).unwrap();
        // Nothing is matched before the input phase.
        assert!(a.matches.assertions.is_empty());
        i.run_text("t", "watch 4\nrun 1").unwrap();
        let first = i.take_output();
        let fired: Vec<&str> = first.lines().filter(|l| l.starts_with("fire")).collect();
        assert_eq!(fired, ["fire 1 10 20", "fire 2 10 20"], "{first}");
        let adds: Vec<&str> = first.lines().filter(|l| l.starts_with("=>WM")).collect();
        assert!(
            adds[0].contains("^Y 20") && adds[6].contains("^obj"),
            "{first}"
        );
        let a = &mut i.agent;
        a.update_input(x, 11i64).unwrap();
        a.update_input(y, 21i64).unwrap();
        i.run_text("t", "run 1").unwrap();
        let second = i.take_output();
        let input: Vec<&str> = second
            .lines()
            .filter(|l| l.starts_with("=>WM") || l.starts_with("<=WM"))
            .take(4)
            .collect();
        let want = [
            ("=>WM", "^Y 21"),
            ("=>WM", "^X 11"),
            ("<=WM", "^Y 20"),
            ("<=WM", "^X 10"),
        ];
        assert_eq!(input.len(), want.len(), "{second}");
        for (line, (arrow, wme)) in input.iter().zip(want) {
            assert!(line.contains(arrow) && line.contains(wme), "{second}");
        }
        let fired: Vec<&str> = second.lines().filter(|l| l.starts_with("fire")).collect();
        assert_eq!(fired, ["fire 2 11 21", "fire 1 11 21"], "{second}");
    }
}
