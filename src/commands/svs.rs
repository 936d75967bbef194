//! `svs`: the spatial visual system's switch (Soar manual, chapter 8, "Spatial Visual
//! System"). 9.6 starts with it disabled; rusoar has no spatial visual system, so it stays
//! disabled: the status and the switches answer as 9.6's do, enabling it is refused with a
//! clear error, and any other form gets 9.6's answer for a disabled system (soar-sml 9.6.5).

use super::{CmdResult, Ctx, Interpreter};

impl Interpreter {
    pub(super) fn cmd_svs(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let in_substates = &mut self.agent.settings.svs_in_substates;
        match args.first().map(String::as_str) {
            None => Ok("Spatial Visual System is disabled.".into()),
            Some("-d" | "--disable" | "--off") if args.len() == 1 => {
                Ok("Spatial Visual System is already disabled. ".into())
            }
            Some("-e" | "--enable" | "--on") if args.len() == 1 => Err(ctx
                .error("rusoar has no Spatial Visual System: it stays disabled")
                .with_note("agents that only switch it off load and run; scene graphs, filters and the ^svs link are not built")),
            Some("--enable-in-substates") if args.len() == 1 => Ok(substates_switch(in_substates, true)),
            Some("--disable-in-substates") if args.len() == 1 => {
                Ok(substates_switch(in_substates, false))
            }
            Some(_) => Err(ctx.error(
                "Spatial Visual System is currently disabled.  Please enable to execute SVS commands.",
            )),
        }
    }
}

/// `--enable-in-substates` (`on`) or `--disable-in-substates`: 9.6's message, and the
/// setting changed.
fn substates_switch(setting: &mut bool, on: bool) -> String {
    let word = if on { "enabled" } else { "disabled" };
    let text = if *setting == on {
        format!("Spatial Visual System is already {word} in substates. ")
    } else {
        format!("Spatial Visual System {word} in substates. ")
    };
    *setting = on;
    text
}
