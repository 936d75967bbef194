//! `sp`, `production excise` (Soar manual, ch. 9, `sp`, `print`, `production`).

use super::options::{self, opt};
use super::{CmdResult, Ctx, Interpreter};
use crate::agent::Added;
use crate::commands::tokenizer::WordKind;
use crate::production::{self, CompileOutput, Flags};
use crate::source::Diagnostic;

impl Interpreter {
    /// `sp {...}`: parse, compile with Soar's checks, add. `*` per rule, `#*` on redefinition.
    pub(super) fn cmd_sp(&mut self, ctx: &Ctx) -> CmdResult {
        let Some(body) = ctx.cmd.words.get(1) else {
            return Err(ctx
                .error("Syntax: sp {production_body}")
                .with_label("no production body"));
        };
        if ctx.cmd.words.len() > 2 {
            return Err(Diagnostic::error("Syntax: sp {production_body}")
                .at(ctx.arg_span(1))
                .with_label("the production must be a single {...} word"));
        }
        let file = body.span.file;
        let offset = match body.kind {
            WordKind::Braced => body.content_offset(),
            _ => body.span.start + usize::from(body.kind == WordKind::Quoted),
        };
        let mut warnings = Vec::new();
        let parsed = crate::parser::parse_production(&body.text, file, offset, &mut warnings);
        for w in warnings.drain(..) {
            self.warn(w);
        }
        let ast = match parsed {
            Ok(ast) => ast,
            Err(d) => {
                // A bad name fails before anything else, without "(Ignoring production)".
                if d.message == "Expected symbol for production name" {
                    return Err(d.with_note("Production addition failed."));
                }
                let name = production_name(&body.text);
                return Err(self.sp_failed(d, name.as_deref()));
            }
        };
        let mut out = CompileOutput::default();
        let compiled = production::compile(&ast, &mut out);
        for w in out.warnings {
            self.warn(w);
        }
        let p = match compiled {
            Ok(p) => p,
            Err(d) => return Err(self.sp_failed(d, Some(&ast.name))),
        };
        let name = p.name.clone();
        if p.flags.explain {
            self.print_result(format!("Now watching any chunks formed by rule '{name}'"));
        }
        // The matcher may trace the rule's first matches (`trace --assertions`).
        self.sync_line_start();
        match self.agent.add_production(p) {
            Added::New => {
                self.count_loaded();
                Ok("*".into())
            }
            Added::Replaced => {
                self.report.note_excised(&name);
                self.count_loaded();
                Ok("#*".into())
            }
            Added::Duplicate { of } => {
                self.report.ignored += 1;
                self.warn(
                    Diagnostic::warning(format!(
                        "Ignoring {name} because it is a duplicate of {of} "
                    ))
                    .at(ast.name_span)
                    .with_label("identical to an existing rule"),
                );
                Ok(String::new())
            }
            Added::Rejected { reason, why } => {
                let d = Diagnostic::error(reason).at(ast.name_span).with_label(why);
                Err(self.sp_failed(d, Some(&name)))
            }
        }
    }

    /// A rule that fails to load. Soar excises a rule of the same name as soon as it has
    /// read the name, so a failed redefinition still removes the old rule (`#`).
    fn sp_failed(&mut self, d: Diagnostic, name: Option<&str>) -> Diagnostic {
        let Some(name) = name else {
            return d.with_note("Production addition failed.");
        };
        if self.agent.excise(name) {
            self.report.note_excised(name);
            self.print_result("#".into());
        }
        d.with_note(format!("(Ignoring production {name})"))
            .with_note("Production addition failed.")
    }

    /// Counts a rule for the file being sourced.
    fn count_loaded(&mut self) {
        self.report.added += 1;
        self.report.added_since_summary += 1;
        if let Some(f) = self.source_stack.last() {
            match self.report.per_file.get_mut(f) {
                Some(n) => *n += 1,
                None => {
                    self.report.per_file.insert(f.clone(), 1);
                }
            }
        }
    }

    /// `production excise NAME...|--all`, and the other `production` sub-commands' errors.
    pub(super) fn cmd_production(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        match args.first().map(String::as_str) {
            Some("excise") => self.cmd_excise(ctx, &args[1..]),
            Some("matches") => self.cmd_matches(ctx, &args[1..]),
            Some("firing-counts") => self.cmd_firing_counts(ctx, &args[1..]),
            Some("optimize-attribute") => self.cmd_optimize_attribute(ctx, &args[1..]),
            Some("find") => self.cmd_production_find(ctx, &args[1..]),
            Some("break") => self.cmd_production_break(ctx, &args[1..]),
            Some("watch") => self.cmd_production_watch(ctx, &args[1..]),
            Some("memory-usage") => self.cmd_memory_usage(ctx, &args[1..]),
            Some(_) | None => Err(super::not_yet(ctx, "production")),
        }
    }

    /// `production optimize-attribute [ATTR [N]]` (alias `multi-attributes`): with no
    /// argument the listing; else ATTR (a string constant, whatever it looks like) is
    /// declared to have N values (10 when not given), which the reorderer counts in rules
    /// loaded from then on. Texts as soar-sml 9.6.5 prints them.
    fn cmd_optimize_attribute(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let Some(attr) = args.first() else {
            return Ok(self.agent.multi_attributes.listing(&self.agent.symbols));
        };
        let count = match args.get(1) {
            None => crate::rete::reorder::MultiAttributes::DEFAULT_COUNT,
            Some(n) => match n.parse::<u64>() {
                Ok(n) if n > 0 => n,
                _ => {
                    return Err(Diagnostic::error("Expected non-negative integer.")
                        .at(ctx.arg_span(2))
                        .with_label("a count of at least 1"))
                }
            },
        };
        if args.len() > 2 {
            return Err(ctx.error("Syntax: multi-attributes [symbol [n]]"));
        }
        let sym = self.agent.symbols.str(attr);
        self.agent.multi_attributes.set(sym, count);
        Ok(String::new())
    }

    fn cmd_excise(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        // Soar 8's `excise -all`: 9.6 reads -a -l -l and fails; we accept it with a warning.
        let mut args = args.to_vec();
        if let Some(pos) = args.iter().position(|a| a == "-all") {
            self.warn(
                Diagnostic::warning("Soar 8 spelling `excise -all`: Soar 9.6 rejects it (No such option: l); read as `excise --all`")
                    .at(ctx.cmd.span)
                    .with_label("write `excise --all`"),
            );
            args[pos] = "--all".into();
        }
        let specs = [
            opt('a', "all"),
            opt('c', "chunks"),
            opt('d', "default"),
            opt('n', "never-fired"),
            opt('r', "rl"),
            opt('t', "task"),
            opt('T', "templates"),
            opt('u', "user"),
        ];
        let parsed = options::parse(&args, &specs).map_err(|m| ctx.error(m))?;
        if parsed.has("all") {
            let names: Vec<String> = self.agent.productions().map(|p| p.name.to_string()).collect();
            // 9.6 excises the templates too but leaves them out of its count.
            let templates = self.agent.productions().filter(|p| p.flags.template).count();
            let n = self.agent.excise_all();
            for name in &names {
                self.report.note_excised(name);
            }
            // The live justifications are excised and counted too; their instantiations
            // stay in preference memory, and so do the results they support (checked on
            // soar-sml 9.6.5: agent learn-justification keeps its i-supported `^isup`).
            let justifications = self.agent.excise_justifications();
            return Ok(excised_text(n - templates + justifications));
        }
        if parsed.has("rl") && parsed.options.len() == 1 && parsed.args.is_empty() {
            // The RL rules (Soar manual, ch. 5, "Reinforcement Learning"), newest first;
            // 9.6 marks each with `#`.
            let names: Vec<String> = self
                .agent
                .productions()
                .rev()
                .filter(|p| {
                    self.agent
                        .loaded(&p.name)
                        .is_some_and(|l| self.agent.rl.is_rl_rule(l.id))
                })
                .map(|p| p.name.to_string())
                .collect();
            for name in &names {
                self.agent.excise(name);
                self.report.note_excised(name);
            }
            return Ok(format!("{}{}", "#".repeat(names.len()), excised_text(names.len())));
        }
        if parsed.has("rl") {
            return Err(super::not_yet(ctx, "excise --rl with other options"));
        }
        // The kinds of rule an option names (Soar manual, chapter 9, `excise`): `--task` is
        // every rule but the default ones.
        let kinds: [(&str, RuleKind); 5] = [
            ("chunks", |f: &Flags| f.chunk),
            ("default", |f: &Flags| f.default),
            ("templates", |f: &Flags| f.template),
            ("user", |f: &Flags| !f.chunk && !f.default),
            ("task", |f: &Flags| !f.default),
        ];
        let wanted: Vec<RuleKind> = kinds
            .iter()
            .filter(|(o, _)| parsed.has(o))
            .map(|&(_, k)| k)
            .collect();
        let never_fired = parsed.has("never-fired");
        if !wanted.is_empty() || never_fired {
            let names: Vec<String> = self
                .agent
                .productions()
                .filter(|p| {
                    let fired = self
                        .agent
                        .loaded(&p.name)
                        .is_some_and(|l| self.agent.firing_count(l.id) > 0);
                    wanted.iter().any(|k| k(&p.flags)) || (never_fired && !fired)
                })
                .map(|p| p.name.to_string())
                .collect();
            for name in &names {
                self.agent.excise(name);
                self.report.note_excised(name);
            }
            return Ok(excised_text(names.len()));
        }
        if parsed.args.is_empty() {
            return Err(ctx.error("excise: expected a production name or an option"));
        }
        let mut n = 0;
        for name in &parsed.args {
            if !self.agent.excise(name) {
                return Err(Diagnostic::error("Production not found.")
                    .at(ctx.cmd.span)
                    .with_label(format!("no production named {name}")));
            }
            n += 1;
            // `source` counts these in its "N productions excised." summary.
            self.report.note_excised(name);
        }
        Ok(excised_text(n))
    }
}

/// Whether a rule is of the kind an `excise` option names.
type RuleKind = fn(&Flags) -> bool;

/// `excise`'s result, as 9.6 words it.
fn excised_text(n: usize) -> String {
    format!("{n} production{} excised.", if n == 1 { "" } else { "s" })
}

/// The production name at the start of an `sp` body (a symbol or `|quoted|` constant), as
/// Soar reads it before the rest of the body.
fn production_name(body: &str) -> Option<String> {
    let mut scratch = Vec::new();
    let toks = match crate::lexer::lex(body, 0, 0, &mut scratch) {
        Ok(t) => t,
        Err(e) => crate::lexer::lex(&body[..e.start], 0, 0, &mut scratch).ok()?,
    };
    match toks.first().map(|t| &t.1) {
        Some(crate::lexer::Tok::Sym(s) | crate::lexer::Tok::Quoted(s)) => Some(s.clone()),
        _ => None,
    }
}
