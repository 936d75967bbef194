//! [`Io`]: the input and output links of an agent, as an environment uses them between
//! decisions or from inside the input and output phases.

use super::Error;
use crate::agent::AgentCore as Core;
use crate::io::{InputUpdate, InputWme, OutputCommand, Value};
use crate::symbols::Sym;
use crate::wm::Wme;

/// The input and output links of an agent (Soar manual, chapter 2, "Input and Output").
///
/// [`crate::Agent::io`] gives one between runs; the input- and output-phase hooks
/// ([`crate::Agent::on_input_phase`], [`crate::Agent::on_output_phase`]) get one inside the
/// decision cycle. Input WMEs reach the matcher at the next input phase, as an SML client's
/// do.
pub struct Io<'a> {
    core: &'a mut Core,
}

impl std::fmt::Debug for Io<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Io")
            .field("agent", &self.core.name)
            .finish()
    }
}

impl<'a> Io<'a> {
    pub(crate) fn new(core: &'a mut Core) -> Self {
        Io { core }
    }

    /// The top state's `^io.input-link` identifier.
    pub fn input_link(&self) -> Sym {
        self.core.input_link()
    }

    /// The top state's `^io.output-link` identifier.
    pub fn output_link(&self) -> Sym {
        self.core.output_link()
    }

    /// Adds `(id ^attr value)` to working memory. `id` must be an identifier.
    pub fn add(&mut self, id: Sym, attr: &str, value: impl Into<Value>) -> Result<InputWme, Error> {
        Ok(self.core.add_input(id, attr, value)?)
    }

    /// Adds `(id ^attr <new>)` with a new identifier, and returns both.
    pub fn add_object(&mut self, id: Sym, attr: &str) -> Result<(InputWme, Sym), Error> {
        Ok(self.core.add_input_object(id, attr)?)
    }

    /// Gives an input WME a new value: the old WME goes and a new one comes at the next input
    /// phase. Returns false when nothing changed (the same value, with
    /// [`InputUpdate::SkipIfNoChange`]).
    pub fn update(&mut self, w: InputWme, value: impl Into<Value>) -> Result<bool, Error> {
        Ok(self.core.update_input(w, value)?)
    }

    /// Removes an input WME, and what hangs below it, at the next input phase.
    pub fn remove(&mut self, w: InputWme) -> Result<(), Error> {
        Ok(self.core.remove_input(w)?)
    }

    /// The value an input WME holds.
    pub fn value(&self, w: InputWme) -> Result<Value, Error> {
        Ok(self.core.input_value(w)?)
    }

    /// How [`Io::update`] treats an unchanged value ([`InputUpdate::BlinkIfNoChange`], the
    /// official kernel's default, until set).
    pub fn set_update_mode(&mut self, mode: InputUpdate) {
        self.core.set_input_update(mode);
    }

    /// The commands on the output-link that were not reported before: each is reported
    /// once, however long it stays.
    pub fn new_output_commands(&mut self) -> Vec<OutputCommand> {
        self.core.new_output_commands()
    }

    /// Every command on the output-link.
    pub fn output_commands(&self) -> Vec<OutputCommand> {
        self.core.output_commands()
    }

    /// Adds `^status complete` to a command, as SML environments do. A command can be
    /// marked done once.
    pub fn mark_done(&mut self, cmd: &OutputCommand) -> Result<(), Error> {
        self.core.mark_done(cmd.id)?;
        Ok(())
    }

    /// The WMEs of an identifier, oldest first.
    pub fn children(&self, id: Sym) -> Vec<Wme> {
        children(self.core, id)
    }

    /// Whether identifier `id` has a WME with attribute `attr`.
    pub fn has_attribute(&self, id: Sym, attr: &str) -> bool {
        has_attribute(self.core, id, attr)
    }

    /// A symbol as Soar prints it.
    pub fn text(&self, s: Sym) -> String {
        self.core.symbols.text(s)
    }

    /// A symbol as a [`Value`].
    pub fn value_of(&self, s: Sym) -> Value {
        self.core.value_of(s)
    }

    /// A value as Soar prints it (strings that need them in `|bars|`).
    pub fn value_text(&self, v: &Value) -> String {
        value_text(self.core, v)
    }

    /// Asks the run to stop at the end of this phase (as `stop-soar` does).
    pub fn stop(&mut self) {
        self.core.decider.stop_requested = true;
    }

    /// Decisions made since the agent was created or last initialized.
    pub fn decisions(&self) -> u64 {
        self.core.decider.decisions
    }
}

/// A value as Soar prints it.
pub(crate) fn value_text(core: &Core, v: &Value) -> String {
    match v {
        Value::Int(i) => i.to_string(),
        Value::Float(f) => crate::printer::float_text(*f),
        Value::Str(s) => crate::printer::rereadable(s),
        Value::Id(s) => core.symbols.text(*s),
    }
}

/// The WMEs of `id`, oldest first.
pub(crate) fn children(core: &Core, id: Sym) -> Vec<Wme> {
    core.wm
        .of_id(id)
        .filter_map(|w| core.wm.get(w).copied())
        .collect()
}

/// Whether `id` has a WME with attribute `attr`.
pub(crate) fn has_attribute(core: &Core, id: Sym, attr: &str) -> bool {
    let Some(a) = core.symbols.find_str(attr) else {
        return false;
    };
    core.wm
        .of_id(id)
        .any(|w| core.wm.get(w).is_some_and(|x| x.attr == a))
}
