//! `save rete-network --save FILE` and `load rete-network --load FILE` (Soar manual, ch. 9,
//! `save` and `load`): production memory written to a file and read back in place of the
//! rules loaded, followed by an `init-soar`. 9.6 writes its network's binary image; rusoar
//! writes its rules as `sp` text under a header line of its own, so that a file of one
//! kernel is never mistaken for the other's.

use super::options::{self, opt_arg};
use super::{CmdResult, Ctx, Event, Interpreter};

/// The first line of a rete-network file written by rusoar.
const HEADER: &str = "# rusoar rete-network 1";

impl Interpreter {
    /// `save rete-network -s|--save FILE`.
    pub(super) fn save_rete_network(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let parsed = options::parse(args, &[opt_arg('s', "save")])
            .map_err(|m| ctx.error(format!("{m}\n{}", super::save::MORE)))?;
        let (Some(file), true) = (parsed.value("save"), parsed.args.is_empty()) else {
            return Err(ctx.error("Invalid syntax for that command."));
        };
        let mut text = format!("{HEADER}\n");
        // Oldest first, so that loading gives the rules their order again.
        for p in self.agent.productions() {
            text.push_str(&crate::printer::production_text(p));
        }
        self.write_file(ctx, file, &text)?;
        Ok(String::new())
    }

    /// `load rete-network -l|--load FILE`: every rule is excised (a `#` each), the file's rules
    /// take their place, and the agent is reinitialized.
    pub(super) fn load_rete_network(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let parsed = options::parse(args, &[opt_arg('l', "load")])
            .map_err(|m| ctx.error(format!("{m}\nUse 'load ?' or 'help load' to learn more about the load command.")))?;
        let (Some(file), true) = (parsed.value("load"), parsed.args.is_empty()) else {
            return Err(ctx.error("Invalid syntax for that command."));
        };
        let path = self.resolve(file);
        let bytes = std::fs::read(&path)
            .map_err(|e| ctx.error(format!("Open file failed.\n{}: {e}", path.display())))?;
        let text = String::from_utf8(bytes).unwrap_or_default();
        let Some(rules) = text
            .strip_prefix(HEADER)
            .and_then(|t| t.strip_prefix('\n'))
        else {
            return Err(ctx.error(format!(
                "{} is not a rete-network file saved by rusoar (it does not read the binary files of Soar 9.6)",
                path.display()
            )));
        };
        let excised = self.agent.excise_all();
        // The rules print no `*` marks, as in 9.6 (nor join an open line of marks).
        let open_marks = std::mem::replace(&mut self.after_star, false);
        let start = self.event_count();
        let loaded = self.run_text(&path.display().to_string(), rules);
        let events = self.take_events_from(start);
        if let Err(d) = loaded {
            self.after_star = open_marks;
            // Keep what the file's rules printed (warnings) before the failure.
            self.events
                .extend(events.into_iter().filter(|e| !matches!(e, Event::Text(_))));
            return Err(d.with_note(format!("while loading {}", path.display())));
        }
        self.events
            .extend(events.into_iter().filter(|e| !matches!(e, Event::Text(_))));
        self.after_star = open_marks;
        if excised > 0 {
            self.print_result("#".repeat(excised));
        }
        self.reinitialize();
        Ok(String::new())
    }
}
