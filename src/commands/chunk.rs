//! `chunk` (Soar manual, ch. 9, `chunk`): when to learn, the per-phase limits, naming, the
//! interrupts, the singleton patterns and the other EBC switches, with the official
//! kernel's texts (soar-sml 9.6.5).

use super::on_off;
use super::settings::int_setting;
use super::{CmdResult, Ctx, Interpreter};
use crate::agent::LearnMode;
use crate::learn::settings::{ElementType, NamingStyle, Singleton};
use crate::source::Diagnostic;

/// Soar's message for a bad value of a `chunk` setting.
const CHUNK_INVALID: &str =
    "Invalid argument for chunking command. Use 'chunk ?' to see a list of valid settings.";

impl Interpreter {
    pub(super) fn cmd_chunk(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let s = &mut self.agent.settings;
        let value = args.get(1).map(String::as_str);
        let invalid = || {
            Diagnostic::error(CHUNK_INVALID)
                .at(ctx.arg_span(args.len().saturating_sub(1)))
                .with_label("not a chunk setting")
        };
        match args.first().map(String::as_str) {
            None => Ok(super::chunk_listing::summary(&self.agent)),
            Some("?" | "help") => Ok(super::chunk_listing::settings(&self.agent)),
            Some(
                w @ ("always" | "never" | "only" | "except" | "on" | "off" | "flagged"
                | "unflagged"),
            ) => {
                // `chunk on` and `chunk flagged` mean `only` in 9.6, `unflagged` `except`.
                s.learn = match w {
                    "always" => LearnMode::Always,
                    "never" | "off" => LearnMode::Never,
                    "only" | "on" | "flagged" => LearnMode::Only,
                    _ => LearnMode::Except,
                };
                // 9.6 echoes the old spellings with an extra newline.
                let shown = match w {
                    "off" | "flagged" | "unflagged" => format!("{w}\n"),
                    _ => s.learn.word().to_string(),
                };
                Ok(format!("Learns rules in states: {shown}\n"))
            }
            // 9.6 takes `chunk --on`, `chunk -e`... for `chunk`: it prints the summary and
            // changes nothing (soar-sml 9.6.5). So does rusoar, and says so.
            Some(w) if w.starts_with('-') => {
                let word = w.to_string();
                self.warn(
                    Diagnostic::warning(format!(
                        "`chunk {word}` changes nothing in Soar 9.6 (it prints the summary): write `chunk always|never|only|except`"
                    ))
                    .at(ctx.arg_span(0))
                    .with_label("an option `chunk` ignores"),
                );
                Ok(super::chunk_listing::summary(&self.agent))
            }
            Some("max-chunks") => int_setting(
                ctx,
                &args[1..],
                "max-chunks",
                &mut s.max_chunks,
                CHUNK_INVALID,
                |n| format!("max-chunks is now {n}\n"),
            ),
            Some("max-dupes") => int_setting(
                ctx,
                &args[1..],
                "max-dupes",
                &mut s.max_dupes,
                CHUNK_INVALID,
                |n| format!("max-dupes is now {n}\n"),
            ),
            Some("naming-style") => {
                let style = &mut s.chunk.naming_style;
                let word = |st: NamingStyle| match st {
                    NamingStyle::Numbered => "numbered",
                    NamingStyle::Rule => "rule",
                };
                match value {
                    None => Ok(format!("naming-style is {}\n", word(*style))),
                    Some("numbered") => {
                        *style = NamingStyle::Numbered;
                        Ok("naming-style is now numbered\n".into())
                    }
                    Some("rule") => {
                        *style = NamingStyle::Rule;
                        Ok("naming-style is now rule\n".into())
                    }
                    Some(_) => Err(invalid()),
                }
            }
            // 9.6 answers with a result, not printed text: a sourced file's `chunk
            // singleton` shows nothing.
            Some("singleton") => self.chunk_singleton(ctx, &args[1..]).map(|answer| {
                if self.source_stack.is_empty() {
                    answer
                } else {
                    String::new()
                }
            }),
            Some("stats") => {
                // 9.6 prints the table whatever follows `stats`; rusoar does too, and says
                // that the rest was not used.
                if args.len() > 1 {
                    self.warn(
                        Diagnostic::warning("`chunk stats` takes no arguments: the rest is not used")
                            .at(ctx.arg_span(1))
                            .with_label("not used"),
                    );
                }
                Ok(super::chunk_stats::chunk_stats(&self.agent))
            }
            Some(name) => {
                let Some(switch) = s.chunk.switch(name) else {
                    return Err(invalid());
                };
                match value {
                    None => Ok(format!("{name} is {}\n", on_off(*switch))),
                    Some(v @ ("on" | "off")) => {
                        *switch = v == "on";
                        Ok(format!("{name} is now {v}\n"))
                    }
                    Some(_) => Err(invalid()),
                }
            }
        }
    }

    /// `chunk singleton`: lists the patterns; `TYPE ATTR TYPE` adds one, `-r TYPE ATTR
    /// TYPE` removes one.
    fn chunk_singleton(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let singletons = &mut self.agent.settings.chunk.singletons;
        let (remove, words) = match args.first().map(String::as_str) {
            Some("-r" | "--remove") => (true, &args[1..]),
            _ => (false, args),
        };
        if words.is_empty() && !remove {
            return Ok(singleton_listing(singletons));
        }
        let [id, attribute, value] = words else {
            return Err(ctx.error("Wrong number of arguments for the chunk command."));
        };
        let id = ElementType::from_word(id).ok_or_else(|| {
            ctx.error("Invalid pattern type for identifier element of singleton.  Must be any, constant, identifier, operator, or state.")
        })?;
        let value = ElementType::from_word(value).ok_or_else(|| {
            ctx.error("Invalid pattern type for value element of singleton.  Must be any, constant, identifier, operator, or state.")
        })?;
        let pattern = Singleton {
            id,
            attribute: attribute.clone(),
            value,
        };
        let text = pattern_text(&pattern);
        let singletons = &mut self.agent.settings.chunk.singletons;
        if remove {
            return Ok(match singletons.iter().position(|p| *p == pattern) {
                Some(i) => {
                    singletons.remove(i);
                    format!("Removed. Will no longer unify conditions in super-states that match a WME\n         that fits the pattern:  {text}\n\n")
                }
                None => format!("Could not find pattern {text}.  Did not remove.\n"),
            });
        }
        // One pattern per attribute: a new one replaces the old.
        let mut out = String::new();
        if let Some(i) = singletons.iter().position(|p| p.attribute == *attribute) {
            singletons.remove(i);
            out = format!("Clearing previous singleton for {attribute}.\n");
        }
        singletons.push(pattern);
        out.push_str(&format!(
            "Will unify conditions in super-states that match a WME that fits the pattern:  {text}\n"
        ));
        Ok(out)
    }
}

/// `(<any> ^superstate <any>)`.
fn pattern_text(p: &Singleton) -> String {
    format!("(<{}> ^{} <{}>)", p.id.word(), p.attribute, p.value.word())
}

/// `chunk singleton`: the architecture's patterns, then the user's.
fn singleton_listing(user: &[Singleton]) -> String {
    let mut out = String::from(SINGLETONS_BUILT_IN);
    for p in user {
        out.push_str("   ");
        out.push_str(&pattern_text(p));
        out.push('\n');
    }
    out.push_str(SINGLETONS_FOOTER);
    out
}

const SINGLETONS_BUILT_IN: &str = "\
==== Singleton WME Unification Patterns ====
----------------- Local --------------------
   (<state> ^superstate <state>)

-------------- Super-state -----------------
   (<state> ^superstate <any>)
   (<state> ^operator   <operator>)                   (unless condition only tests operator proposal)
   (<state> ^type       <constant>)
   (<state> ^impasse    <constant>)
   (<state> ^smem       <identifier>)
   (<state> ^epmem      <identifier>)
   ---------- user-defined ----------
";

const SINGLETONS_FOOTER: &str = "

To add a new pattern:    chunk singleton    <type> attribute <type>
To remove a pattern:     chunk singleton -r <type> attribute <type>

   Valid types:          [ any | constant | identifier | operator | state ]  
";
