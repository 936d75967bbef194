//! Input and output for programs that embed the kernel (issue 4, item 5; spec §2 I/O link):
//! add, change and remove input-link WMEs between decisions, read the commands the rules put
//! on the output-link, and mark them done. The Soar-SLAM loop uses only this API.

use crate::agent::Agent;
use crate::inputs::InputChange;
use crate::symbols::{Sym, SymData};
use crate::wm::WmeId;

/// A value to put on the input-link.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    Int(i64),
    Float(f64),
    Str(String),
    /// An existing identifier.
    Id(Sym),
}

impl From<i64> for Value {
    fn from(v: i64) -> Self {
        Value::Int(v)
    }
}
impl From<f64> for Value {
    fn from(v: f64) -> Self {
        Value::Float(v)
    }
}
impl From<&str> for Value {
    fn from(v: &str) -> Self {
        Value::Str(v.to_string())
    }
}
impl From<Sym> for Value {
    fn from(v: Sym) -> Self {
        Value::Id(v)
    }
}

/// One command the rules placed on the output-link: `(I3 ^name <cmd>)` and its parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct OutputCommand {
    pub id: Sym,
    pub name: String,
    /// (attribute, value) pairs of the command object, as plain text.
    pub params: Vec<(String, Sym)>,
}

impl Agent {
    pub fn input_link(&self) -> Sym {
        self.top.input_link
    }

    pub fn output_link(&self) -> Sym {
        self.top.output_link
    }

    fn value_sym(&mut self, v: &Value) -> Sym {
        match v {
            Value::Int(i) => self.symbols.int(*i),
            Value::Float(f) => self.symbols.float(*f),
            Value::Str(s) => self.symbols.str(s),
            Value::Id(s) => *s,
        }
    }

    /// A new identifier for input structure (letter as Soar would choose for `^attr`).
    pub fn new_input_id(&mut self, letter: char) -> Sym {
        self.symbols.new_id(letter, 1)
    }

    /// Adds `(id ^attr value)`: it gets its timetag now and reaches the matcher at the next
    /// input phase (see [`Agent::apply_input_changes`]), as an SML client's WMEs do.
    pub fn add_input(&mut self, id: Sym, attr: &str, value: impl Into<Value>) -> WmeId {
        let a = self.symbols.str(attr);
        let v = self.value_sym(&value.into());
        self.queue_input_add(id, a, v)
    }

    fn queue_input_add(&mut self, id: Sym, attr: Sym, value: Sym) -> WmeId {
        let links = [self.symbols.is_id(value), self.symbols.is_id(attr)];
        let w = self.wm.add_typed(id, attr, value, false, links);
        self.input_queue.push(InputChange::Add(w));
        w
    }

    /// Applies the input-link changes made since the last input phase, as 9.6 applies an
    /// SML client's buffered changes there (`do_buffered_wm_changes`, checked with soar-sml
    /// 9.6.5): first every added WME, newest first, then every removed one, newest first,
    /// each traced as `=>WM:` or `<=WM:`. The order decides the order of new matches, so
    /// of firings, identifiers and random choices (`scripts/slam_oracle.py`).
    pub(crate) fn apply_input_changes(&mut self) {
        if self.input_queue.is_empty() {
            return;
        }
        let queue = std::mem::take(&mut self.input_queue);
        // The passing tokens of the additions with the removals are left out where that
        // changes nothing (rete/doomed.rs).
        let (mut added, mut removed) = (Vec::new(), Vec::new());
        for change in &queue {
            match *change {
                InputChange::Add(w) => {
                    added.extend(self.wm.get(w).map(|x| (x.attr, x.value, x.acceptable)))
                }
                InputChange::Remove(w) => removed.push(w),
            }
        }
        let batch = self.rete.begin_doomed_batch(&added, &removed);
        for change in queue.iter().rev() {
            let InputChange::Add(w) = *change else {
                continue;
            };
            let Some(wme) = self.wm.get(w).copied() else {
                continue;
            };
            self.match_new_wme(w, &wme);
            self.trace_wme("=>WM: ", &wme);
        }
        for change in queue.iter().rev() {
            let InputChange::Remove(w) = *change else {
                continue;
            };
            if let Some(wme) = self.remove_wme(w) {
                self.trace_wme("<=WM: ", &wme);
            }
        }
        if batch {
            self.rete.end_doomed_batch();
        }
    }

    /// Adds `(id ^attr <new id>)` and returns the new identifier. Its letter is the
    /// attribute's first letter, or `I` when that is not a letter or is `s` (9.6 names an
    /// SML client's `^sonar` object `I4`, keeping `S` for states; soar-sml 9.6.5).
    pub fn add_input_object(&mut self, id: Sym, attr: &str) -> (WmeId, Sym) {
        let letter = attr
            .chars()
            .next()
            .filter(|c| c.is_ascii_alphabetic() && !c.eq_ignore_ascii_case(&'s'))
            .unwrap_or('I');
        let child = self.new_input_id(letter);
        (self.add_input(id, attr, child), child)
    }

    /// Replaces the value of an input WME if it differs (a removal and an addition, applied
    /// at the next input phase, as SML does); returns the WME that holds the new value.
    pub fn update_input(&mut self, w: WmeId, value: impl Into<Value>) -> WmeId {
        let v = value.into();
        let Some(old) = self.wm.get(w).copied() else {
            return w;
        };
        // A WME already on its way out is not replaced twice (its holder was updated or
        // removed before in this phase: the caller holds a stale handle).
        if self.input_queue.contains(&InputChange::Remove(w)) {
            return w;
        }
        let new = self.value_sym(&v);
        if new == old.value {
            return w;
        }
        self.input_queue.push(InputChange::Remove(w));
        self.queue_input_add(old.id, old.attr, new)
    }

    /// [`Agent::update_input`] for several values, in the order given. Returns, for each
    /// change, the WME that now holds the value.
    pub fn update_inputs(&mut self, changes: &[(WmeId, Value)]) -> Vec<WmeId> {
        changes
            .iter()
            .map(|(w, v)| self.update_input(*w, v.clone()))
            .collect()
    }

    /// Removes an input WME at the next input phase and, with the garbage collection
    /// after it, what hangs below it.
    pub fn remove_input(&mut self, w: WmeId) {
        if !self.input_queue.contains(&InputChange::Remove(w)) {
            self.input_queue.push(InputChange::Remove(w));
        }
    }

    /// Commands on the output-link: each `(I3 ^name <obj>)` object with its parameters.
    pub fn output_commands(&self) -> Vec<OutputCommand> {
        self.output_commands_after(0)
    }

    /// The commands put on the output-link since the last call (or since `init-soar`), as
    /// SML reports new output commands: each once, however long it stays there.
    pub fn new_output_commands(&mut self) -> Vec<OutputCommand> {
        let after = self.output_reported;
        if let Some(tt) = self
            .wm
            .of_id(self.top.output_link)
            .filter_map(|w| self.wm.get(w).map(|x| x.timetag))
            .max()
        {
            self.output_reported = self.output_reported.max(tt);
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
                .map(|x| (self.symbols.plain(x.attr), x.value))
                .collect();
            out.push(OutputCommand {
                id: wme.value,
                name,
                params,
            });
        }
        out
    }

    /// Marks a command done with `^status complete`, as SML environments do.
    pub fn mark_done(&mut self, cmd: Sym) -> WmeId {
        self.add_input(cmd, "status", "complete")
    }

    /// A number from a symbol (ints and floats), for reading command parameters.
    pub fn number(&self, s: Sym) -> Option<f64> {
        match self.symbols.get(s) {
            SymData::Int(i) => Some(*i as f64),
            SymData::Float(f) => Some(*f),
            SymData::Str(x) => x.parse().ok(),
            SymData::Id(_) => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn input_is_matched_and_output_is_read() {
        let mut a = Agent::new("t");
        let il = a.input_link();
        let (_, data) = a.add_input_object(il, "currentrobotdata");
        let x = a.add_input(data, "X", 100i64);
        assert_eq!(a.symbols.text(a.wm.get(x).map(|w| w.value).unwrap()), "100");
        let tt = a.wm.get(x).map(|w| w.timetag);
        let x2 = a.update_input(x, 120i64);
        // A changed value is a new WME (a new timetag), as SML makes it.
        assert_ne!(tt, a.wm.get(x2).map(|w| w.timetag));
        assert_eq!(
            a.wm.get(x2).map(|w| a.symbols.text(w.value)),
            Some("120".into())
        );
        let ol = a.output_link();
        let (_, cmd) = a.add_input_object(ol, "move");
        a.add_input(cmd, "param1", 300i64);
        let cmds = a.output_commands();
        assert_eq!(cmds.len(), 1);
        assert_eq!(cmds[0].name, "move");
        assert_eq!(a.number(cmds[0].params[0].1), Some(300.0));
    }

    #[test]
    fn input_objects_are_named_as_sml_names_them() {
        let mut a = Agent::new("t");
        let il = a.input_link();
        let name = |a: &mut Agent, attr: &str| {
            let (_, id) = a.add_input_object(il, attr);
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
        let mut a = Agent::new("t");
        let ol = a.output_link();
        let (_, c1) = a.add_input_object(ol, "move");
        a.add_input(c1, "param1", 300i64);
        let first = a.new_output_commands();
        assert_eq!(first.len(), 1);
        assert_eq!(first[0].name, "move");
        assert!(a.new_output_commands().is_empty());
        let (_, c2) = a.add_input_object(ol, "turn");
        a.add_input(c2, "param1", 40i64);
        let second = a.new_output_commands();
        assert_eq!(second.len(), 1);
        assert_eq!(second[0].name, "turn");
        // Both are still on the output-link.
        assert_eq!(a.output_commands().len(), 2);
        a.init_soar();
        assert!(a.new_output_commands().is_empty());
    }

    #[test]
    fn update_inputs_changes_only_what_differs() {
        let mut a = Agent::new("t");
        let il = a.input_link();
        let (_, data) = a.add_input_object(il, "pose");
        let x = a.add_input(data, "X", 1i64);
        let y = a.add_input(data, "Y", 2i64);
        let tt_y = a.wm.get(y).map(|w| w.timetag);
        let now = a.update_inputs(&[(x, Value::Int(5)), (y, Value::Int(2))]);
        assert_eq!(now[1], y, "an equal value is left alone");
        assert_eq!(a.wm.get(now[1]).map(|w| w.timetag), tt_y);
        let text = |a: &Agent, w: WmeId| a.wm.get(w).map(|w| a.symbols.text(w.value));
        assert_eq!(text(&a, now[0]), Some("5".into()));
        // The old value goes at the input phase; a stale handle is not replaced again.
        assert_eq!(a.wm.of_id(data).count(), 3);
        assert_eq!(a.update_input(x, 7i64), x);
        assert_eq!(a.wm.of_id(data).count(), 3);
        a.apply_input_changes();
        assert_eq!(a.wm.of_id(data).count(), 2);
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
            let (_, o) = a.add_input_object(il, "obj");
            a.add_input(o, "a", v);
        }
        let (_, c) = a.add_input_object(il, "crd");
        let x = a.add_input(c, "X", 10i64);
        let y = a.add_input(c, "Y", 20i64);
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
        a.update_inputs(&[(x, Value::Int(11)), (y, Value::Int(21))]);
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
