//! `save` (Soar manual, ch. 9, `save`): the agent's settings and rules as a file of
//! commands that `source` reads back (`save agent`), the learned rules alone (`save
//! chunks`), production memory for `load rete-network` (`rete_net.rs`), the recording of
//! input (`percepts.rs`), and the listing of its forms (`save ?`).

use super::{CmdResult, Ctx, Interpreter};
use crate::agent::LearnMode;
use crate::source::Diagnostic;
use crate::production::Production;

/// `save ?`: 9.6's listing of the forms.
const LISTING: &str = "======================================================
-            Save Sub-Commands and Options           -
======================================================
save [? | help]
------------------------------------------------------
save agent                           <filename>
save chunks                          <filename>
------------------------------------------------------
save percepts                        --open <filename>
save percepts                        [--close --flush]
------------------------------------------------------
save rete-network                    --save <filename>
------------------------------------------------------

For a detailed explanation of sub-commands:  help save";

/// 9.6's pointer to the listing, after an error.
pub(super) const MORE: &str = "Use 'save ?' or 'help save' to learn more about the save command.";

impl Interpreter {
    /// `save agent FILE`, `save chunks FILE`, `save ?`.
    pub(super) fn cmd_save(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let words: Vec<&str> = args.iter().map(String::as_str).collect();
        match words.as_slice() {
            [] => Err(ctx.error(format!("File type is required. \n\n{MORE}"))),
            // 9.6 answers `save ?` as a failure, with the listing as its message.
            ["?" | "help"] => Err(ctx.error(LISTING)),
            ["agent", file] => {
                let text = agent_file(&self.agent.settings, &self.saved_rules(false));
                self.write_file(ctx, file, &text)?;
                Ok("Procedural memory, semantic memory and settings written to file.\n".into())
            }
            ["agent", ..] => Err(ctx.error("Syntax: save agent <filename>")),
            ["chunks", file] => {
                let text = format!("{}\n", self.saved_rules(true));
                self.write_file(ctx, file, &text)?;
                Ok(format!("Chunks written to file {file}."))
            }
            ["chunks", ..] => Err(ctx.error("Syntax: save chunks <filename>")),
            ["rete-network", ..] => self.save_rete_network(ctx, &args[1..]),
            ["percepts", ..] => self.save_percepts(ctx, &args[1..]),
            [_, ..] => Err(ctx.error(
                "Invalid save command.  Use 'save ?' to see a list of valid settings.",
            )),
        }
    }

    /// The rules `save` writes, newest first as `print --full` lists them, each followed by
    /// a blank line, and one more blank line when there are any: the user, default and
    /// template rules and the chunks (`chunks_only`: the chunks alone). Justifications are
    /// left out, as 9.6 leaves them: they cannot be loaded again.
    fn saved_rules(&self, chunks_only: bool) -> String {
        let rules: Vec<&Production> = self
            .agent
            .productions()
            .rev()
            .filter(|p| !chunks_only || p.flags.chunk)
            .collect();
        let mut out = String::new();
        for p in &rules {
            out.push_str(&crate::printer::production_text(p));
            out.push('\n');
        }
        if !rules.is_empty() {
            out.push('\n');
        }
        out
    }

    /// Writes `text` to `file` (relative to the working directory). 9.6 says nothing when
    /// the file cannot be written; rusoar says why.
    pub(super) fn write_file(&self, ctx: &Ctx, file: &str, text: &str) -> Result<(), Diagnostic> {
        let path = self.resolve(file);
        std::fs::write(&path, text).map_err(|e| {
            ctx.error(format!("Could not write {}: {e}", path.display()))
        })
    }
}

/// `save agent`'s file: the settings as commands, the rules, and 9.6's note that semantic
/// memory (which rusoar does not have) was not saved.
fn agent_file(s: &crate::agent::Settings, rules: &str) -> String {
    let on_off = |b: bool| if b { "on" } else { "off" };
    let mode = match s.learn {
        LearnMode::Always => "always",
        LearnMode::Never => "never",
        LearnMode::Only => "only",
        LearnMode::Except => "except",
    };
    let c = &s.chunk;
    format!(
        "# Settings\n\nchunk {mode}\nchunk bottom-only {}\nchunk add-osk {}\n\
         chunk allow-local-negations {}\nchunk add-ltm-links {}\nchunk max-chunks {}\n\
         chunk max-dupes {}\nsoar max-elaborations {}\nsoar max-goal-depth {}\n\
         soar wait-snc {}\n\n# Procedural Memory\n\n{rules}\n\
         # Semantic memory is not enabled.  Did not save.\n",
        on_off(c.bottom_only),
        on_off(c.add_osk),
        on_off(c.allow_local_negations),
        on_off(c.add_ltm_links),
        s.max_chunks,
        s.max_dupes,
        s.max_elaborations,
        s.max_goal_depth,
        on_off(s.wait_snc),
    )
}
