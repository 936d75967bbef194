//! `debug`: the kernel's debugging aids (Soar manual, chapter 9, `debug`): `time` runs a
//! command under a clock, `allocate` lists the stores or gives one room ahead of a run,
//! `internal-symbols` lists the symbol table, and `port` (the SML listener's port) is
//! answered with why rusoar has none. The texts and errors are 9.6's (soar-sml 9.6.5).

use super::tokenizer::{Command, Word, WordKind};
use super::{CmdResult, Ctx, Interpreter};
use crate::printer::constants::c_general;
use crate::source::Span;
use crate::symbols::SymData;

/// How deep `debug time` may nest (as `source` does, a bound instead of the stack's end).
const MAX_TIMED_DEPTH: usize = 100;

/// 9.6's bytes per memory-pool block: `debug allocate POOL N` makes room for N of them.
const BLOCK_BYTES: usize = 32 * 1024;

const SUMMARY: &str = "The debug command contains low-level technical debugging commands.\n\n\
                       Use 'debug ?' to learn more about the debug command.\n";

const LISTING: &str = "\
======================================================================
                     Debug Commands and Settings                      
======================================================================
allocate [pool blocks]         Allocates extra memory to a memory pool
internal-symbols                                   Prints symbol table
port                                             Prints listening port
time <command> [args]           Executes command and prints time spent
";

impl Interpreter {
    pub(super) fn cmd_debug(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let Some(sub) = args.first() else {
            return Ok(SUMMARY.into());
        };
        let rest = &args[1..];
        let count_error = |n: usize| {
            ctx.error(format!("Debug| Invalid number of parameters ({n}) to command {sub}."))
                .with_note("Syntax: Debug [command]")
        };
        match sub.as_str() {
            "?" => Ok(LISTING.into()),
            "time" => self.debug_time(ctx, rest),
            "allocate" => match rest {
                [] => Ok(self.memory_pool_table()),
                [pool, blocks] => self.debug_allocate(ctx, pool, blocks),
                _ => Err(count_error(rest.len())),
            },
            "internal-symbols" if rest.is_empty() => Ok(self.internal_symbols()),
            "port" if rest.is_empty() => Err(ctx
                .error("rusoar listens on no port")
                .with_note("the kernel runs inside the program that embeds it (the REPL, Rust, or Python's rusoar.sml); 9.6's SML socket listener has no counterpart")),
            "internal-symbols" | "port" => Err(count_error(rest.len())),
            other => Err(ctx
                .error(format!("Debug| Invalid command: {other}."))
                .with_note("Syntax: Debug [command]")),
        }
    }

    /// `debug time COMMAND [ARGS...]`: what the command prints, then `(SECONDSs) real`,
    /// the seconds in C++'s default form (six significant digits), as 9.6 prints them.
    /// `timed` is the command's words as expanded: the words typed keep their places, and
    /// those an alias put before them (`alias t debug time echo`) stand at the first word.
    fn debug_time(&mut self, ctx: &Ctx, timed: &[String]) -> CmdResult {
        if timed.is_empty() {
            return Err(ctx.error("You must submit a command that you'd like timed."));
        }
        if self.timed_depth >= MAX_TIMED_DEPTH {
            return Err(ctx.error(format!(
                "debug time: nested more than {MAX_TIMED_DEPTH} deep"
            )));
        }
        let typed = &ctx.cmd.words[1..];
        let typed = &typed[typed.len().saturating_sub(timed.len())..];
        let at = ctx.cmd.words[0].span;
        let mut words: Vec<Word> = timed[..timed.len() - typed.len()]
            .iter()
            .map(|text| Word {
                text: text.clone(),
                span: at,
                kind: WordKind::Bare,
            })
            .collect();
        words.extend_from_slice(typed);
        let (first, last) = (words[0].span, words[words.len() - 1].span);
        let command = Command {
            span: Span::new(first.file, first.start, last.end),
            words,
        };
        let start = std::time::Instant::now();
        self.timed_depth += 1;
        let result = self.execute(&command);
        self.timed_depth -= 1;
        let clock = format!("\n({}s) real", c_general(start.elapsed().as_secs_f64(), 6));
        match result {
            Ok(text) => Ok(text + &clock),
            Err(d) => {
                self.print_result(clock);
                Err(d)
            }
        }
    }

    /// `debug allocate POOL BLOCKS`: room for `BLOCKS` of 9.6's 32-kilobyte blocks more in
    /// the store named `POOL` (its whole name, as `debug allocate` lists it).
    fn debug_allocate(&mut self, ctx: &Ctx, pool: &str, blocks: &str) -> CmdResult {
        let n: i64 = blocks
            .parse()
            .map_err(|_| ctx.error("Expected an integer (number of blocks)."))?;
        let n = usize::try_from(n)
            .ok()
            .filter(|&n| n > 0)
            .ok_or_else(|| ctx.error("Expected a positive integer (number of blocks)."))?;
        let bad_pool = || {
            ctx.error(format!(
                "Could not allocate memory.  Probably a bad pool name: {pool}"
            ))
        };
        let report = self.memory_report();
        let item_size = report
            .pools
            .iter()
            .find(|p| p.name == pool)
            .map(|p| p.item_size)
            .ok_or_else(bad_pool)?;
        let items = n.saturating_mul(BLOCK_BYTES / item_size.max(1));
        match self.agent.reserve_pool(pool, items) {
            Some(Ok(())) => Ok(format!("{pool} blocks increased by {n}\n")),
            Some(Err(e)) => Err(ctx.error(format!("Could not allocate memory: {e}"))),
            None => Err(bad_pool().with_note(format!(
                "rusoar's store `{pool}` grows a block at a time and takes no room ahead"
            ))),
        }
    }

    /// `debug internal-symbols`: the symbol table by kind, in 9.6's sections; each symbol
    /// in the order it was made (9.6 lists its hash tables' order, with its reference
    /// counts, which rusoar does not keep). The identifiers are those in working memory,
    /// the variables the names loaded rules use.
    fn internal_symbols(&self) -> String {
        let (syms, wm) = (&self.agent.symbols, &self.agent.wm);
        let mut sections: [Vec<String>; 4] = Default::default();
        for s in syms.all() {
            let kind = match syms.get(s) {
                SymData::Str(_) => 0,
                SymData::Int(_) => 1,
                SymData::Float(_) => 2,
                // The identifiers in working memory (the table keeps every one made).
                SymData::Id(_) if wm.has_wmes(s) || !wm.parent_wmes(s).is_empty() => 3,
                SymData::Id(_) => continue,
            };
            sections[kind].push(syms.plain(s));
        }
        let titles = [
            "Symbolic Constants",
            "Integer Constants",
            "Floating-Point Constants",
            "Identifiers",
        ];
        let mut out = String::new();
        for (title, names) in titles.iter().zip(&sections) {
            out.push_str(&format!("\n--- {title}: ---\n"));
            for n in names {
                out.push_str(n);
                out.push('\n');
            }
        }
        out.push_str("\n--- Variables: ---\n");
        for v in self.agent.rete.variable_names() {
            out.push_str(&v);
            out.push('\n');
        }
        out
    }
}
