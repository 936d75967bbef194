//! `production find`, `production break` and `production watch` (Soar manual, ch. 9,
//! `production`). Texts and error messages as the official 9.6 kernel prints them.

use super::options::{self, opt};
use super::{CmdResult, Ctx, Interpreter};
use crate::production::{Cond, Condition, Term, Test};
use crate::source::Diagnostic;

impl Interpreter {
    /// `production find [-lrcns] CONDITIONS`: the rules, newest first, with conditions the
    /// pattern's conditions match (a variable binds to one of the rule's variables, `*`
    /// matches anything, a constant itself). As in 9.6, `--rhs` searches the conditions too,
    /// and options that name neither side (`-c`, `-n`, `-s` alone) search nothing.
    pub(super) fn cmd_production_find(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let specs = [
            opt('c', "chunks"),
            opt('l', "lhs"),
            opt('n', "nochunks"),
            opt('r', "rhs"),
            opt('s', "show-bindings"),
        ];
        let parsed = options::parse(args, &specs).map_err(|m| ctx.error(m))?;
        if parsed.args.is_empty() {
            return Err(ctx.error("No pattern specified."));
        }
        let text = parsed.args.join(" ");
        let pattern = match find_pattern(&text) {
            Ok(p) => p,
            Err(m) => return Ok(format!("{m}\nError: not a valid condition list.\nNo matches.\n")),
        };
        let search = parsed.options.is_empty() || parsed.has("lhs") || parsed.has("rhs");
        let mut out = String::new();
        if search {
            for p in self.agent.productions().rev() {
                if (parsed.has("chunks") && !p.flags.chunk)
                    || (parsed.has("nochunks") && p.flags.chunk)
                {
                    continue;
                }
                let rule_conds: Vec<&Cond> = p
                    .conditions
                    .iter()
                    .filter_map(|c| match c {
                        Condition::Positive(c) => Some(c),
                        _ => None,
                    })
                    .collect();
                let Some(bindings) = match_all(&pattern, &rule_conds, &mut Vec::new()) else {
                    continue;
                };
                if parsed.has("show-bindings") {
                    out.push_str(&format!("{}, with bindings:\n", p.name));
                    for (v, r) in bindings.iter().rev() {
                        out.push_str(&format!("   ({v} -> {r})\n"));
                    }
                } else {
                    out.push_str(&p.name);
                    out.push('\n');
                }
            }
        }
        if out.is_empty() {
            out.push_str("No matches.\n");
        }
        Ok(out)
    }

    /// `production break [-c|-s] [NAME]`: with no argument the rules with a break; `-s`
    /// sets one (a run stops after the phase in which the rule gets a new match, see
    /// `decide/breaks.rs`), `-c` clears it.
    pub(super) fn cmd_production_break(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let specs = [opt('c', "clear"), opt('s', "set")];
        let parsed = options::parse(args, &specs).map_err(|m| ctx.error(m))?;
        if parsed.options.len() > 1 {
            return Err(ctx.error("pbreak takes only one option at a time."));
        }
        if !parsed.options.is_empty() && parsed.args.len() != 1 {
            return Err(ctx.error("pbreak --set/--clear takes exactly one argument."));
        }
        let Some(name) = parsed.args.first() else {
            // The rules with a break, one a line, newest rule first (as 9.6 lists them).
            return Ok(self
                .agent
                .productions()
                .rev()
                .filter(|p| self.agent.break_rules.contains_key(p.name.as_str()))
                .map(|p| format!("{}\n", p.name))
                .collect());
        };
        if parsed.args.len() > 1 {
            return Err(ctx.error("pbreak --set/--clear takes exactly one argument."));
        }
        // A name without an option sets its break, as in 9.6.
        if !self.agent.set_break(name, !parsed.has("clear")) {
            return Err(ctx.error(format!("Production not found: {name}")));
        }
        Ok(String::new())
    }

    /// `production watch [-e|-d] [NAME]`: a watched rule's firings are traced (`Firing
    /// NAME`) whatever the trace settings; with no name, the watched rules, newest first.
    pub(super) fn cmd_production_watch(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let specs = [opt('d', "disable"), opt('e', "enable")];
        // 9.6 knows the options by their letters only.
        if let Some(long) = args.iter().find_map(|a| a.strip_prefix("--")) {
            return Err(ctx.error(format!("No such option: {long}")));
        }
        let parsed = options::parse(args, &specs).map_err(|m| ctx.error(m))?;
        if parsed.args.len() > 1 {
            return Err(ctx.error("Too many parameters"));
        }
        let Some(name) = parsed.args.first() else {
            let watched: Vec<&str> = self
                .agent
                .productions()
                .rev()
                .map(|p| p.name.as_str())
                .filter(|n| self.agent.watched_rules.contains(*n))
                .collect();
            if watched.is_empty() {
                return Ok("No watched productions found.".into());
            }
            return Ok(watched.iter().map(|n| format!("\n{n}")).collect());
        };
        if self.agent.production(name).is_none() {
            return Err(ctx.error("Production not found."));
        }
        // The last of `-e`/`-d` counts; a name alone enables.
        let disable = parsed.options.last().is_some_and(|(o, _)| *o == "disable");
        if disable {
            self.agent.watched_rules.remove(name.as_str());
        } else {
            self.agent.watched_rules.insert(name.clone());
        }
        Ok(String::new())
    }
}

/// The conditions of a `production find` pattern, or the parser's message.
fn find_pattern(text: &str) -> Result<Vec<Cond>, String> {
    let body = format!("production*find {text}\n-->");
    let mut warnings: Vec<Diagnostic> = Vec::new();
    let ast = crate::parser::parse_production(&body, usize::MAX, 0, &mut warnings)
        .map_err(|d| d.message.clone())?;
    let conds = crate::production::compile_conditions(&ast).map_err(|d| d.message.clone())?;
    conds
        .into_iter()
        .map(|c| match c {
            Condition::Positive(c) => Ok(c),
            _ => Err("production find: only positive conditions can be searched for".into()),
        })
        .collect()
}

/// Bindings from the pattern's variables to the rule's, oldest first.
type Bindings = Vec<(arcstr::ArcStr, arcstr::ArcStr)>;

/// A way for every pattern condition to match one of the rule's conditions, with the
/// bindings it makes (backtracking over the choices).
fn match_all(pattern: &[Cond], rule: &[&Cond], bindings: &mut Bindings) -> Option<Bindings> {
    let Some((first, rest)) = pattern.split_first() else {
        return Some(bindings.clone());
    };
    for c in rule {
        let before = bindings.len();
        if c.acceptable == first.acceptable
            && test_matches(&first.id, &c.id, bindings)
            && test_matches(&first.attr, &c.attr, bindings)
            && test_matches(&first.value, &c.value, bindings)
        {
            if let Some(b) = match_all(rest, rule, bindings) {
                return Some(b);
            }
        }
        bindings.truncate(before);
    }
    None
}

/// Whether a pattern test matches a rule's test: `*` anything; a variable one of the rule's
/// variables (the same one each time); a constant the same constant. Other tests, and tests
/// against the rule's relational, disjunctive or conjunctive tests, match nothing (as in
/// 9.6).
fn test_matches(pattern: &Test, rule: &Test, bindings: &mut Bindings) -> bool {
    let Test::Equal(p) = pattern else {
        return false;
    };
    if matches!(p, Term::Const(crate::ast::Constant::Str(s)) if &**s == "*") {
        return true;
    }
    let Test::Equal(r) = rule else {
        return false;
    };
    match (p, r) {
        (Term::Var(pv), Term::Var(rv)) => match bindings.iter().find(|(v, _)| v == pv) {
            Some((_, bound)) => bound == rv,
            None => {
                bindings.push((pv.clone(), rv.clone()));
                true
            }
        },
        (Term::Const(pc), Term::Const(rc)) => pc == rc,
        _ => false,
    }
}
