//! `save percepts` and `load percepts` (Soar manual, ch. 9, `save` and `load`): the
//! commands that start and stop recording input and replaying it (`percepts.rs` holds the
//! recording and the replay).

use super::options::{self, opt, opt_arg};
use super::{CmdResult, Ctx, Interpreter};
use std::io::Write;

const NOT_OPEN: &str = "File is not open.";
const ALREADY_OPEN: &str = "File is already open.";

impl Interpreter {
    /// `save percepts [-o|--open FILE] [-c|--close] [-f|--flush]`; with no option, whether
    /// a recording is open.
    pub(super) fn save_percepts(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let specs = [opt_arg('o', "open"), opt('c', "close"), opt('f', "flush")];
        let parsed = options::parse(args, &specs)
            .map_err(|m| ctx.error(format!("{m}\n{}", super::save::MORE)))?;
        if let Some(file) = parsed.value("open") {
            if self.agent.capture.is_some() {
                return Err(ctx.error(ALREADY_OPEN));
            }
            let path = self.resolve(file);
            std::fs::File::create(&path)
                .map_err(|e| ctx.error(format!("Open file failed.\n{}: {e}", path.display())))?;
            let seed = self.agent.start_capture(path);
            return Ok(format!("Capturing input with random seed: {seed}"));
        }
        if parsed.has("close") {
            self.write_captured(ctx)?;
            self.agent.capture = None;
            return Ok(String::new());
        }
        if parsed.has("flush") && self.agent.capture.is_some() {
            self.write_captured(ctx)?;
        }
        Ok(open_or_closed(self.agent.capture.is_some()))
    }

    /// Appends what the recording holds to its file.
    fn write_captured(&mut self, ctx: &Ctx) -> Result<(), crate::source::Diagnostic> {
        let Some(capture) = self.agent.capture.as_mut() else {
            return Err(ctx.error(NOT_OPEN));
        };
        let text = std::mem::take(&mut capture.pending);
        std::fs::OpenOptions::new()
            .append(true)
            .open(&capture.path)
            .and_then(|mut f| f.write_all(text.as_bytes()))
            .map_err(|e| ctx.error(format!("Could not write {}: {e}", capture.path.display())))
    }

    /// `load percepts [-o|--open FILE] [-c|--close]`; with no option, whether a replay is
    /// open.
    pub(super) fn load_percepts(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let specs = [opt_arg('o', "open"), opt('c', "close")];
        let parsed = options::parse(args, &specs).map_err(|m| {
            ctx.error(format!(
                "{m}\nUse 'load ?' or 'help load' to learn more about the load command."
            ))
        })?;
        if let Some(file) = parsed.value("open") {
            if self.agent.replay.is_some() {
                return Err(ctx.error(ALREADY_OPEN));
            }
            let path = self.resolve(file);
            let text = std::fs::read_to_string(&path)
                .map_err(|e| ctx.error(format!("Open file failed.\n{}: {e}", path.display())))?;
            let (seed, replay) = crate::percepts::parse(&text).map_err(|bad| {
                ctx.error(format!(
                    "{}:{}: not a line of recorded input: `{}`",
                    path.display(),
                    bad.line,
                    bad.text
                ))
            })?;
            let n = replay.len();
            self.agent.seed_rng(seed);
            self.agent.replay = Some(replay);
            return Ok(format!("Loaded {n} actions."));
        }
        if parsed.has("close") {
            if self.agent.replay.take().is_none() {
                return Err(ctx.error(NOT_OPEN));
            }
            return Ok(String::new());
        }
        Ok(open_or_closed(self.agent.replay.is_some()))
    }
}

fn open_or_closed(open: bool) -> String {
    if open { "open" } else { "closed" }.to_string()
}
