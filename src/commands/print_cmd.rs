//! The `print` command (Soar manual, ch. 9, `print`): rules by name or by kind, the goal
//! stack, the goal dependency sets, and working memory by identifier, timetag, context
//! variable or WME pattern. Texts and error messages as the official 9.6 kernel prints them.

use super::options::{self, opt, opt_arg};
use super::{CmdResult, Ctx, Interpreter};
use crate::agent::AgentCore;
use crate::production::Production;
use crate::symbols::Sym;
use crate::trace::{print_object_at, sym_shown, wme_line};
use crate::wm::{Wme, WmeId};

const NO_ARGUMENT: &str =
    "No argument allowed when printing all/chunks/defaults/GDS/justifications/rl/template/user/stack.";

/// How `print` shows working memory.
#[derive(Debug, Clone, Copy)]
struct WmStyle {
    depth: usize,
    internal: bool,
    tree: bool,
    varprint: bool,
    exact: bool,
}

/// How a listed or named rule is shown: `--full` or `--name` (the later one wins) and
/// `--filename`.
#[derive(Debug, Clone, Copy)]
struct RuleStyle {
    full: Option<bool>,
    filename: bool,
    /// `--internal`: each condition and action on a line of its own.
    internal: bool,
}

impl Interpreter {
    /// `print [options] [rule | identifier | timetag | context variable | (pattern)]`.
    pub(super) fn cmd_print(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let specs = [
            opt('a', "all"),
            opt('c', "chunks"),
            opt('D', "defaults"),
            opt('j', "justifications"),
            opt('u', "user"),
            opt('r', "rl"),
            opt('T', "template"),
            opt('f', "full"),
            opt('F', "filename"),
            opt('n', "name"),
            opt('i', "internal"),
            opt('t', "tree"),
            opt('e', "exact"),
            opt('s', "stack"),
            opt('o', "operators"),
            opt('S', "states"),
            opt('v', "varprint"),
            opt('g', "gds"),
            opt_arg('d', "depth"),
        ];
        // The depth is checked as the options are read, before any later bad option and
        // before the target (9.6: `wmes`, which is `print -depth 0 -internal`, fails with
        // the depth message).
        let bad_depth = |p: &options::Parsed| {
            p.value("depth")
                .is_some_and(|d| d.parse::<usize>().is_err())
        };
        let parsed = match options::parse(args, &specs) {
            Ok(p) => p,
            Err(m) => {
                let read_before_error = (0..args.len())
                    .rev()
                    .find_map(|k| options::parse(&args[..k], &specs).ok());
                if read_before_error.as_ref().is_some_and(bad_depth) {
                    return Err(ctx.error("Non-negative depth expected."));
                }
                return Err(ctx.error(m));
            }
        };
        if bad_depth(&parsed) {
            return Err(ctx.error("Non-negative depth expected."));
        }
        if parsed.has("exact") && (parsed.has("depth") || parsed.has("tree")) {
            return Err(ctx.error("No depth/tree flags allowed when printing exact."));
        }
        if parsed.has("stack") {
            if !parsed.args.is_empty() {
                return Err(ctx.error(NO_ARGUMENT));
            }
            return Ok(super::printing::print_stack(
                &self.agent,
                parsed.has("states"),
                parsed.has("operators"),
            ));
        }
        if parsed.has("states") || parsed.has("operators") {
            return Err(ctx.error(
                "Options --operators (-o) and --states (-S) are only valid when printing the stack.",
            ));
        }
        if parsed.args.is_empty() && (parsed.has("depth") || parsed.has("tree")) {
            return Err(ctx.error(
                "Syntax: print [options] [production_name]\nprint [options] identifier|timetag|pattern",
            ));
        }
        let rule_style = RuleStyle {
            // `--internal` lists rules in full too (observed on 9.6).
            full: parsed
                .options
                .iter()
                .rev()
                .find_map(|(o, _)| match *o {
                    "full" => Some(true),
                    "name" => Some(false),
                    _ => None,
                })
                .or(parsed.has("internal").then_some(true)),
            filename: parsed.has("filename"),
            internal: parsed.has("internal"),
        };
        let kinds = ["all", "user", "chunks", "defaults", "justifications", "rl", "template"];
        let listing = kinds.iter().any(|k| parsed.has(k));
        let mut out = String::new();
        if parsed.has("gds") {
            if !parsed.args.is_empty() {
                return Err(ctx.error(NO_ARGUMENT));
            }
            out.push_str(&gds_listing(&self.agent));
        }
        if listing && !parsed.args.is_empty() {
            return Err(ctx.error(NO_ARGUMENT));
        }
        if parsed.args.is_empty() {
            // With no kind named, every rule (9.6: `print` alone is `print --all`).
            let wanted = |k: &str| !listing || parsed.has("all") || parsed.has(k);
            out.push_str(&self.rule_listing(&wanted, rule_style));
            // `--rl` lists the RL rules again after the other kinds (as 9.6 does).
            if parsed.has("rl") {
                out.push_str(&self.rl_listing(rule_style));
            }
            return Ok(out);
        }
        let style = WmStyle {
            depth: match parsed.value("depth") {
                Some(d) => d
                    .parse::<usize>()
                    .map_err(|_| ctx.error("Non-negative depth expected."))?,
                None => self.agent.settings.print_depth,
            },
            internal: parsed.has("internal"),
            tree: parsed.has("tree"),
            varprint: parsed.has("varprint"),
            exact: parsed.has("exact"),
        };
        if parsed.args.len() > 1 || parsed.args[0].starts_with('(') {
            // Several words are one WME pattern.
            return Ok(self.print_pattern(&parsed.args.join(" "), style));
        }
        let target = &parsed.args[0];
        // `print |a quoted name|`: the word keeps its pipes; the rule name does not.
        let unquoted;
        let name = match target.strip_prefix('|').and_then(|t| t.strip_suffix('|')) {
            Some(inner) => {
                unquoted = inner.replace("\\|", "|").replace("\\\\", "\\");
                &unquoted
            }
            None => target,
        };
        if let Some(p) = self.agent.production(name) {
            return Ok(self.rule_text(p, rule_style, true));
        }
        if let Some(j) = self
            .agent
            .learn
            .justifications
            .iter()
            .find(|j| j.name() == *name)
        {
            let production = j.production(&self.agent.symbols);
            return Ok(self.rule_text(&production, rule_style, true));
        }
        if let Some(var) = target.strip_prefix('<').and_then(|t| t.strip_suffix('>')) {
            return Ok(match context_variable(&self.agent, var) {
                Ok(Some(id)) => self.print_id(id, style),
                Ok(None) => format!("There is no current <{var}>.\n"),
                Err(()) => "Expected identifier (or context variable)\n".to_string(),
            });
        }
        if let Some(id) = self.agent.live_id(target) {
            return Ok(self.print_id(id, style));
        }
        if let Some(lti) = target.strip_prefix('@') {
            // Semantic memory (Soar manual, ch. 9, `print`): `@` is all of it, `@N` one LTI.
            let smem = &mut self.agent.smem;
            let text = if lti.is_empty() {
                smem.print_all()
            } else {
                let n = lti.parse::<i64>().unwrap_or(0);
                smem.print_lti(n).map(|t| {
                    t.unwrap_or_else(|| format!("LTI @{n} not found in semantic memory."))
                })
            };
            return text.map_err(|e| ctx.error(e));
        }
        if let Ok(tt) = target.parse::<u64>() {
            // A timetag prints the object its WME belongs to.
            let id = self
                .agent
                .wm
                .by_timetag(tt)
                .and_then(|w| self.agent.wm.get(w))
                .map(|w| w.id);
            return Ok(match id {
                Some(id) => self.print_id(id, style),
                None => format!("No wme {tt} in working memory."),
            });
        }
        if crate::lexer::is_identifier_shaped(target) {
            return Ok(format!(
                "There is no identifier {}.",
                target.to_ascii_uppercase()
            ));
        }
        Ok(format!("No production named {target}\n"))
    }

    /// An object: `--exact` and `--internal` show one WME per line, `--tree` one WME per
    /// line under the WME leading to it, else the object with `--depth` levels below it.
    fn print_id(&self, id: Sym, style: WmStyle) -> String {
        self.print_id_at(id, style, self.print_column())
    }

    /// [`Self::print_id`] starting at column `col` of the print stream.
    fn print_id_at(&self, id: Sym, style: WmStyle, col: usize) -> String {
        let agent = &self.agent;
        if style.tree {
            return super::printing::print_tree(
                agent,
                id,
                style.depth,
                style.internal,
                style.varprint,
            );
        }
        print_object_at(
            agent,
            id,
            style.depth,
            style.internal,
            style.varprint,
            col,
        )
    }

    /// `print (id ^attr value [+])`: each WME that matches, with `--exact` alone, else the
    /// object it belongs to, once per WME. A malformed pattern prints 9.6's message.
    fn print_pattern(&self, text: &str, style: WmStyle) -> String {
        let pattern = match parse_pattern(&self.agent, text) {
            Ok(p) => p,
            Err(message) => return format!("{message}\n"),
        };
        // 9.6 walks its WMEs in the order they entered its matcher.
        let agent = &self.agent;
        let mut found: Vec<(u64, &Wme)> = agent
            .wm
            .all()
            .into_iter()
            .filter_map(|w| {
                let wme = agent.wm.get(w).filter(|wme| pattern.matches(wme))?;
                Some((agent.rete.entry_order(w).unwrap_or(u64::MAX), wme))
            })
            .collect();
        found.sort_by_key(|f| f.0);
        let mut out = String::new();
        if !style.exact {
            // Each object after the first starts a line.
            for (i, (_, wme)) in found.into_iter().enumerate() {
                let col = if i == 0 { self.print_column() } else { 0 };
                out.push_str(&self.print_id_at(wme.id, style, col));
            }
            return out;
        }
        // `--exact` groups the WMEs by object, the objects in the order their identifiers
        // were made (9.6 orders them by address, which follows that order in a fresh run).
        found.sort_by_key(|f| f.1.id);
        for group in found.chunk_by(|a, b| a.1.id == b.1.id) {
            if style.internal {
                for (_, wme) in group {
                    out.push_str(&wme_line(agent, wme, true, style.varprint));
                    out.push('\n');
                }
                continue;
            }
            out.push('(');
            out.push_str(&sym_shown(agent, group[0].1.id, style.varprint));
            for (_, wme) in group {
                out.push_str(&format!(
                    " ^{} {}{}",
                    sym_shown(agent, wme.attr, style.varprint),
                    sym_shown(agent, wme.value, style.varprint),
                    if wme.acceptable { " +" } else { "" }
                ));
            }
            out.push_str(")\n");
        }
        out
    }

    /// The rules of the kinds `wanted` selects, kind by kind in 9.6's order (default
    /// rules, user rules, templates, justifications, chunks), each kind newest first
    /// (observed on soar-sml 9.6.5, whatever order the options name the kinds in).
    fn rule_listing(&self, wanted: &dyn Fn(&str) -> bool, style: RuleStyle) -> String {
        let mut s = String::new();
        for kind in ["defaults", "user", "template", "justifications", "chunks"] {
            if !wanted(kind) {
                continue;
            }
            if kind == "justifications" {
                for j in self.agent.learn.justifications.iter().rev() {
                    let production = j.production(&self.agent.symbols);
                    s.push_str(&self.rule_text(&production, style, false));
                }
                continue;
            }
            for p in self.agent.productions().rev().filter(|p| p.kind_word() == kind) {
                s.push_str(&self.rule_text(p, style, false));
            }
        }
        s
    }

    /// `print --rl`: the RL rules, newest first, as [`Self::rule_text`] lists them.
    fn rl_listing(&self, style: RuleStyle) -> String {
        let mut s = String::new();
        for p in self.agent.productions().rev() {
            if self.rl_values(p).is_some() {
                s.push_str(&self.rule_text(p, style, false));
            }
        }
        s
    }

    /// An RL rule's number of updates and value as 9.6 lists them after its name (six
    /// decimals, then the value as the rule holds it; under the delta-bar-delta decay
    /// mode, its rate's log and trace before them); `None` for other rules.
    fn rl_values(&self, p: &Production) -> Option<String> {
        let id = self.agent.loaded(&p.name)?.id;
        let v = self.agent.rl.rules.get(&id)?;
        let value = match p.actions.first() {
            Some(crate::production::Action::Make(m)) => match &m.referent {
                Some(crate::production::RhsTerm::Const(c)) => {
                    crate::printer::constants::constant_text(c)
                }
                _ => String::new(),
            },
            _ => String::new(),
        };
        let fixed = |x: f64| crate::rhs::c_fixed(x, 6);
        Some(
            if self.agent.rl.params.decay_mode == crate::rl::params::DecayMode::DeltaBarDelta {
                // With delta-bar-delta, the rule's own rate (its log) and trace come first.
                format!(
                    "{} {} {} {value}",
                    fixed(v.dbd_beta),
                    fixed(v.dbd_h),
                    fixed(v.updates)
                )
            } else {
                format!("{} {value}", fixed(v.updates))
            },
        )
    }

    /// One rule: its text (`--full`, the default for a rule named alone), or its name;
    /// `--filename` adds the file it was loaded from.
    fn rule_text(&self, p: &Production, style: RuleStyle, named: bool) -> String {
        let file = || self.rule_file(p);
        if style.full.unwrap_or(named) {
            let mut s = String::new();
            if style.filename {
                s.push_str(&format!("# source file: {}\n", file()));
            }
            s.push_str(&crate::printer::production_text_as(p, style.internal));
            s.push('\n');
            s
        } else {
            // Justifications are listed by their bare names.
            let name = if self.agent.production(&p.name).is_some() {
                crate::printer::rereadable(&p.name)
            } else {
                p.name.to_string()
            };
            // An RL rule shows what it learned (Soar manual, ch. 5, "Reinforcement
            // Learning").
            let tail = match self.rl_values(p) {
                Some(values) => format!(" {values}"),
                None => String::new(),
            };
            if style.filename {
                format!("{}: {name} {tail}\n", file())
            } else {
                format!("{name} {tail}\n")
            }
        }
    }

    /// The file a rule was sourced from, or 9.6's `_unknown_` for one typed or learned.
    fn rule_file(&self, p: &Production) -> String {
        let name = self.sources.name(p.span.file);
        if self
            .report
            .per_file
            .contains_key(std::path::Path::new(name))
        {
            name.to_string()
        } else {
            "_unknown_".to_string()
        }
    }
}

/// `<s>`, `<o>`, `<ss>`, `<so>`, `<ts>`: the bottom state, its operator, the state above it
/// and that state's operator, the top state. `Ok(None)` when there is none; `Err` for any
/// other variable.
pub(super) fn context_variable(agent: &AgentCore, var: &str) -> Result<Option<Sym>, ()> {
    let goals = &agent.decider.goals;
    let bottom = goals.last();
    let above = goals.len().checked_sub(2).and_then(|i| goals.get(i));
    Ok(match var.to_ascii_lowercase().as_str() {
        "s" => Some(bottom.map_or(agent.top.state, |g| g.state)),
        "o" => bottom.and_then(|g| g.operator).map(|(o, _)| o),
        "ss" => above.map(|g| g.state),
        "so" => above.and_then(|g| g.operator).map(|(o, _)| o),
        "ts" => Some(agent.top.state),
        _ => return Err(()),
    })
}

/// One field of a WME pattern: `*`, or a symbol (`None` when no such symbol exists, so
/// nothing matches).
#[derive(Debug, Clone, Copy)]
enum Field {
    Any,
    Is(Option<Sym>),
}

impl Field {
    fn matches(self, s: Sym) -> bool {
        match self {
            Field::Any => true,
            Field::Is(x) => x == Some(s),
        }
    }
}

struct Pattern {
    id: Field,
    attr: Field,
    value: Field,
    acceptable: bool,
}

impl Pattern {
    fn matches(&self, w: &Wme) -> bool {
        self.id.matches(w.id)
            && self.attr.matches(w.attr)
            && self.value.matches(w.value)
            && self.acceptable == w.acceptable
    }
}

/// The words of a pattern: `(`, `)`, `^` and `+` alone, other runs of characters whole.
fn pattern_tokens(text: &str) -> Vec<String> {
    let mut toks = Vec::new();
    let mut cur = String::new();
    for c in text.chars() {
        if c.is_whitespace() || "()^".contains(c) {
            if !cur.is_empty() {
                toks.push(std::mem::take(&mut cur));
            }
            if !c.is_whitespace() {
                toks.push(c.to_string());
            }
        } else {
            cur.push(c);
        }
    }
    if !cur.is_empty() {
        toks.push(cur);
    }
    toks
}

/// Reads `(id ^attr value [+])` with 9.6's messages for what is missing.
fn parse_pattern(agent: &AgentCore, text: &str) -> Result<Pattern, String> {
    let toks = pattern_tokens(text);
    let mut it = toks.iter().map(String::as_str).peekable();
    match it.next() {
        Some("(") => {}
        Some(other) => {
            return Err(format!(
                "Expected '(' to begin wme pattern not string '{other}' or char ' '"
            ))
        }
        None => return Err("Expected '(' to begin wme pattern".into()),
    }
    let id = field(agent, it.next())?;
    if it.next() != Some("^") {
        return Err("Expected ^ in wme pattern".into());
    }
    let attr = field(agent, it.next())?;
    let value = field(agent, it.next())?;
    let acceptable = it.next_if_eq(&"+").is_some();
    if it.next() != Some(")") || it.next().is_some() {
        return Err("Expected ')' to end wme pattern".into());
    }
    Ok(Pattern {
        id,
        attr,
        value,
        acceptable,
    })
}

fn field(agent: &AgentCore, tok: Option<&str>) -> Result<Field, String> {
    const NOT_A_SYMBOL: &str = "Expected identifier or constant in wme pattern";
    let Some(tok) = tok else {
        return Err(NOT_A_SYMBOL.into());
    };
    if tok == "*" {
        return Ok(Field::Any);
    }
    if matches!(tok, "(" | ")" | "^" | "+") || tok.contains('.') && tok.parse::<f64>().is_err()
    {
        return Err(NOT_A_SYMBOL.into());
    }
    if let Some(var) = tok.strip_prefix('<').and_then(|t| t.strip_suffix('>')) {
        return match context_variable(agent, var) {
            Ok(Some(s)) => Ok(Field::Is(Some(s))),
            Ok(None) => Err(format!("There is no current <{var}>.")),
            Err(()) => Err("Expected identifier (or context variable)".into()),
        };
    }
    let symbols = &agent.symbols;
    if crate::lexer::is_identifier_shaped(tok) {
        return Ok(Field::Is(symbols.find_id(tok)));
    }
    let constant = if crate::lexer::is_int_lexeme(tok) {
        tok.parse::<i64>().ok().map(crate::ast::Constant::Int)
    } else {
        None
    };
    let constant = constant.or_else(|| {
        tok.parse::<f64>()
            .ok()
            .filter(|_| tok.contains('.'))
            .map(crate::ast::Constant::Float)
    });
    let constant = constant.unwrap_or_else(|| {
        let s = tok
            .strip_prefix('|')
            .and_then(|t| t.strip_suffix('|'))
            .unwrap_or(tok);
        crate::ast::Constant::Str(s.into())
    });
    Ok(Field::Is(symbols.find_constant(&constant)))
}

/// `print --gds`: each WME of a goal dependency set, then each goal's set (9.6 lists both in
/// its rete's order; rusoar by timetag). A goal whose set is made but empty gets its header
/// alone.
fn gds_listing(agent: &AgentCore) -> String {
    let mut s = String::from(
        "********************* Current GDS **************************\nstepping thru all wmes in rete, looking for any that are in a gds...\n",
    );
    // 9.6 steps through its WMEs newest in its matcher first, then lists each set newest
    // member first.
    let members: Vec<(Wme, Sym, WmeId, u64)> = agent
        .decider
        .gds
        .iter()
        .filter_map(|(w, m)| agent.wm.get(*w).map(|x| (*x, m.goal, *w, m.joined)))
        .collect();
    let mut stepped: Vec<(Option<u64>, String)> = members
        .iter()
        .map(|(w, g, id, _)| {
            let line = format!(
                "  For Goal  {}  {}\n",
                agent.symbols.text(*g),
                wme_line(agent, w, true, false)
            );
            (agent.rete.entry_order(*id), line)
        })
        .collect();
    stepped.extend(agent.decider.gds_orphans.iter().filter_map(|&id| {
        let w = agent.wm.get(id)?;
        let line = format!("  Old GDS value {}\n", wme_line(agent, w, true, false));
        Some((agent.rete.entry_order(id), line))
    }));
    stepped.sort_by_key(|m| std::cmp::Reverse(m.0));
    for (_, line) in stepped {
        s.push_str(&line);
    }
    s.push_str("************************************************************\n");
    let goals: Vec<Sym> = if agent.decider.goals.is_empty() {
        vec![agent.top.state]
    } else {
        agent.decider.goals.iter().map(|g| g.state).collect()
    };
    for g in goals {
        let mut mine: Vec<(&Wme, u64)> = members
            .iter()
            .filter(|m| m.1 == g)
            .map(|m| (&m.0, m.3))
            .collect();
        mine.sort_by_key(|m| std::cmp::Reverse(m.1));
        let name = agent.symbols.text(g);
        if !agent.decider.gds_sizes.contains_key(&g) {
            s.push_str(&format!("  For Goal  {name}  : No GDS for this goal.\n"));
        } else {
            s.push_str(&format!("  For Goal  {name}  \n"));
            for (w, _) in mine {
                s.push_str(&format!("                {}\n", wme_line(agent, w, true, false)));
            }
        }
    }
    s.push_str("************************************************************\n");
    s
}
