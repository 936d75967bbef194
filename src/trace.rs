//! Soar 9.6's print formats for working memory (the `print` command, Soar manual chapter
//! 9): `print <id>` objects with attributes sorted and wrapped at 80 columns, `print -i`
//! one WME per line with timetags, and `matches <rule>` partial-match listings.

use rustc_hash::FxHashSet;
use crate::agent::AgentCore;
use crate::decide::PendingRetraction;
use crate::decide::state::SubstateLine;
use crate::printer::{cond_text, cond_text_with};
use crate::production::{test_text, Condition};
use crate::symbols::Sym;
use crate::trace_events::TraceEvent;
use crate::wm::{Wme, WmeId};

/// `(tt: id ^attr value[ +])`, with its activation when working-memory activation is on.
pub fn wme_internal(agent: &AgentCore, w: &Wme) -> String {
    let mut out = String::new();
    let activation = agent.wme_activation(w);
    crate::trace_text::wme_text_activated(&mut out, &agent.symbols, w, activation);
    out
}

/// A symbol as `print` shows it; with `--varprint`, identifiers as variables (`<S1>`).
pub fn sym_shown(agent: &AgentCore, s: Sym, varprint: bool) -> String {
    if varprint && agent.symbols.is_id(s) {
        format!("<{}>", agent.symbols.text(s))
    } else {
        agent.symbols.text(s)
    }
}

/// One WME on a line of its own: `(id ^attr value[ +])`, with `internal` its timetag first
/// (`(tt: id ^attr value)`), with `varprint` identifiers as variables.
pub fn wme_line(agent: &AgentCore, w: &Wme, internal: bool, varprint: bool) -> String {
    let tt = if internal {
        format!("{}: ", w.timetag)
    } else {
        String::new()
    };
    // 9.6 prints a WME's activation wherever it prints its timetag (`print_wme`).
    let activation = match agent.wme_activation(w).filter(|_| internal) {
        Some(a) => format!(" [{}]", crate::wma::activation_text(a)),
        None => String::new(),
    };
    format!(
        "({tt}{} ^{} {}{activation}{})",
        sym_shown(agent, w.id, varprint),
        sym_shown(agent, w.attr, varprint),
        sym_shown(agent, w.value, varprint),
        if w.acceptable { " +" } else { "" }
    )
}

/// The WMEs of an object as `print` orders them: by attribute text, newest first on ties,
/// but episodic memory's results oldest first (9.6 lists them in the order it made them).
pub fn sorted_wmes(agent: &AgentCore, id: Sym) -> Vec<Wme> {
    let ids: Vec<crate::wm::WmeId> = agent.wm.of_id(id).collect();
    let n = ids.len();
    let mut ws: Vec<(Vec<u8>, bool, u64, Wme)> = ids
        .into_iter()
        .enumerate()
        .filter_map(|(i, w)| {
            let wme = *agent.wm.get(w)?;
            let place = agent.epmem.made(w);
            let made_by_epmem = place.is_some();
            let rank = match place {
                Some(k) => k as u64,
                None => (n - i) as u64,
            };
            Some((
                agent.symbols.text(wme.attr).into_bytes(),
                made_by_epmem,
                rank,
                wme,
            ))
        })
        .collect();
    ws.sort_by(|a, b| (&a.0, a.1, a.2).cmp(&(&b.0, b.1, b.2)));
    ws.into_iter().map(|x| x.3).collect()
}

/// `print <id>` with `--depth` and `--internal` (children indented two spaces per level, each
/// identifier printed once at its shallowest depth), when the output stream is already at
/// column `start_col`: 9.6 counts the first line's width from there, so a print after a trace line wraps earlier (observed on
/// the official kernel), even right after `(S1`.
pub fn print_object_at(
    agent: &AgentCore,
    id: Sym,
    depth: usize,
    internal: bool,
    varprint: bool,
    start_col: usize,
) -> String {
    let mut out = String::new();
    let mut seen = std::collections::HashSet::new();
    let mut frontier = std::collections::VecDeque::from([(id, 0usize)]);
    // Breadth first, so an identifier prints at its shallowest depth.
    let mut order = Vec::new();
    while let Some((x, d)) = frontier.pop_front() {
        if !seen.insert(x) {
            continue;
        }
        order.push((x, d));
        if d + 1 < depth {
            // An identifier as attribute is printed below its object too, before the value
            // (as 9.6 prints it).
            for w in sorted_wmes(agent, x) {
                for v in [w.attr, w.value] {
                    if agent.symbols.is_id(v) && !seen.contains(&v) {
                        frontier.push_back((v, d + 1));
                    }
                }
            }
        }
    }
    // Print depth-first in the breadth-first ownership, as Soar lists children after parents.
    let owners: std::collections::HashMap<Sym, usize> =
        order.iter().map(|(x, d)| (*x, *d)).collect();
    let mut printed = std::collections::HashSet::new();
    let mut col = start_col;
    // Depth first with a stack of its own, not the call stack: a chain of objects may be
    // as long as working memory. An identifier is checked when its turn comes, so the
    // order is that of a recursive walk.
    let mut stack = vec![(id, 0usize)];
    while let Some((x, level)) = stack.pop() {
        let children = print_one(
            agent,
            x,
            level,
            (internal, varprint),
            &mut printed,
            &mut out,
            &mut col,
        );
        if level + 1 < depth {
            let owned = children
                .into_iter()
                .filter(|&v| agent.symbols.is_id(v) && owners.get(&v) == Some(&(level + 1)));
            let from = stack.len();
            stack.extend(owned.map(|v| (v, level + 1)));
            stack[from..].reverse();
        }
    }
    out
}

/// Prints one object at `level` (none when it was printed or has no WMEs) and returns its
/// WMEs' attributes and values in the order printed, for the walk to go on below it.
fn print_one(
    agent: &AgentCore,
    id: Sym,
    level: usize,
    (internal, varprint): (bool, bool),
    printed: &mut std::collections::HashSet<Sym>,
    out: &mut String,
    // The stream's column where the first line starts (0 after it).
    col: &mut usize,
) -> Vec<Sym> {
    if !printed.insert(id) {
        return Vec::new();
    }
    // An identifier with no WMEs prints nothing, at the top too (9.6 prints an empty text).
    let wmes = sorted_wmes(agent, id);
    if wmes.is_empty() {
        return Vec::new();
    }
    let indent = "  ".repeat(level);
    if internal {
        for w in &wmes {
            out.push_str(&indent);
            out.push_str(&wme_line(agent, w, true, varprint));
            out.push('\n');
        }
    } else {
        let mut line = format!("{indent}({}", sym_shown(agent, id, varprint));
        // 9.6 measures the line without the brackets `--varprint` adds (observed).
        let mut width = indent.len() + 1 + agent.symbols.text(id).len();
        for w in &wmes {
            // A value that stands for an LTI shows it: `L3 (@1)` (Soar manual, Semantic
            // Memory; the form 9.6.5 prints).
            let lti = agent
                .symbols
                .lti(w.value)
                .map_or(String::new(), |l| format!(" (@{l})"));
            let item = format!(
                " ^{} {}{lti}{}",
                sym_shown(agent, w.attr, varprint),
                sym_shown(agent, w.value, varprint),
                if w.acceptable { " +" } else { "" }
            );
            let item_width = format!(
                " ^{} {}{lti}{}",
                agent.symbols.text(w.attr),
                agent.symbols.text(w.value),
                if w.acceptable { " +" } else { "" }
            )
            .len();
            // 9.6 wraps when the item would reach column 79, also before the first attribute
            // (`(I4` alone on its line); checked against the official kernel at both edges.
            if *col + width + item_width >= 79 {
                out.push_str(&line);
                out.push('\n');
                *col = 0;
                // Continuation lines start 7 columns in, under the first attribute
                // (observed).
                line = format!("{indent}       {}", &item[1..]);
                width = indent.len() + 7 + item_width - 1;
            } else {
                line.push_str(&item);
                width += item_width;
            }
        }
        line.push(')');
        out.push_str(&line);
        out.push('\n');
    }
    *col = 0;
    wmes.iter().flat_map(|w| [w.attr, w.value]).collect()
}

/// `matches <rule>` (`production matches`): each condition with its partial-match count;
/// from the first condition with none, `>>>>` marks where matching stops.
pub fn matches_listing(agent: &AgentCore, name: &str) -> Option<String> {
    let loaded = agent.loaded(name)?;
    let counts = agent.rete.partial_match_counts(loaded.id, &agent.symbols);
    let mut out = String::new();
    let mut stopped = false;
    let mut goal_shown = std::collections::HashSet::new();
    for (i, count) in counts {
        let cond = &loaded.production.conditions[i];
        let text = match cond {
            Condition::Ncc(inner) => {
                let mut s = String::from("    -{\n");
                for c in inner {
                    s.push_str("          ");
                    s.push_str(&cond_text(c));
                    s.push('\n');
                }
                s.push_str(&format!("{} }}", counted(count, &mut stopped).trim_end()));
                out.push_str(&s);
                out.push('\n');
                continue;
            }
            Condition::Positive(c) | Condition::Negative(c) => {
                let first = goal_shown.insert(test_text(&c.id));
                cond_text_with(cond, first)
            }
        };
        out.push_str(&counted(count, &mut stopped));
        out.push_str(&text);
        out.push('\n');
    }
    let complete = agent.rete.matches_of(loaded.id).len();
    out.push_str(&format!("\n{complete} complete matches.\n"));
    Some(out)
}

fn counted(count: usize, stopped: &mut bool) -> String {
    if *stopped {
        "     ".to_string()
    } else if count == 0 {
        *stopped = true;
        ">>>> ".to_string()
    } else {
        format!("{count:>4} ")
    }
}

/// `matches` with no rule: the pending assertions and retractions, with their goals.
pub fn pending_matches(agent: &AgentCore) -> String {
    let mut o = String::from("O Assertions:\n");
    let mut i = String::from("I Assertions:\n");
    for &(p, t) in &agent.matches.assertions {
        if (p, t) == crate::agent::MatchSet::GONE {
            continue;
        }
        let line = format!(
            "  {}  [{}] \n",
            agent.production_name(p),
            goal_text(agent, p, t)
        );
        if agent.is_o_supported(p, t) {
            o.push_str(&line);
        } else {
            i.push_str(&line);
        }
    }
    // In the order the next elaboration cycle takes them, each with the goal of the
    // firing it takes back (`NIL` once that goal is gone).
    let mut r = String::from("Retractions:\n");
    let retractions = &agent.matches.retractions;
    let mut justified = agent.decider.justification_retractions.clone();
    let mut order = Vec::new();
    agent.pending_retractions(retractions.len(), &mut justified, &mut order);
    for pending in order {
        let (name, inst) = match pending {
            PendingRetraction::Rule(at) => {
                let (p, t) = retractions[at];
                let inst = agent.decider.inst_by_token.get(&(p, t)).copied();
                (agent.production_name(p).to_string(), inst)
            }
            PendingRetraction::Justification(i) => {
                let serial = agent.decider.insts[i].serial;
                let Some(j) = agent.learn.justifications.iter().find(|j| j.serial == serial)
                else {
                    continue;
                };
                (j.name().to_string(), Some(i))
            }
        };
        let goal = inst.map_or_else(|| "NIL".to_string(), |i| inst_goal_text(agent, i));
        r.push_str(&format!("  {name}  [{goal}] \n"));
    }
    format!("{o}{i}{r}")
}

fn inst_goal_text(agent: &AgentCore, i: crate::decide::state::InstId) -> String {
    match agent.decider.insts[i].goal.filter(|&g| agent.symbols.is_goal(g)) {
        Some(g) => agent.symbols.text(g),
        None => "NIL".into(),
    }
}

fn goal_text(agent: &AgentCore, p: crate::rete::ProdId, t: crate::rete::TokId) -> String {
    match crate::decide::support::match_goal(agent, p, t) {
        Some(g) => agent.symbols.text(g),
        None => "NIL".into(),
    }
}

/// The WMEs of a complete match, for `matches -w`.
pub fn match_wme_lines(agent: &AgentCore, ws: &[WmeId]) -> String {
    ws.iter()
        .filter_map(|w| agent.wm.get(*w))
        .map(|w| wme_internal(agent, w))
        .collect::<Vec<_>>()
        .join("\n ")
}

/// The level a preference is traced at: 9.6 prints the level of the instantiation's goal
/// (a result made in a substate says `[level 2]` though its id is on the top state), also
/// once the instantiation has retracted and an o-supported preference outlives it.
fn pref_level(agent: &AgentCore, p: &crate::decide::state::Preference) -> u32 {
    let s = &agent.symbols;
    let goal_level = match p.inst {
        Some(i) => agent.decider.insts[i]
            .goal
            .and_then(|g| s.id_data(g))
            .map(|d| d.level),
        None => p.origin.as_ref().map(|o| o.trace.level).filter(|&l| l > 0),
    };
    goal_level.unwrap_or_else(|| s.id_data(p.id).map_or(1, |d| d.level))
}

/// The justification or rule whose firing made a preference. An o-supported preference
/// keeps naming its justification after the justification retracted (9.6 keeps the
/// justification while its preferences live; soar-sml 9.6.5, agent long/fifteen-puzzle,
/// trace 5: `(E7 ^symbolic-value failure +  :O ) [level 2] (justify1)`).
pub(crate) fn pref_rule<'a>(
    agent: &'a AgentCore,
    p: &'a crate::decide::state::Preference,
) -> Option<&'a str> {
    let justification = p
        .inst
        .map(|i| agent.decider.insts[i].serial)
        .filter(|&serial| serial != 0)
        .and_then(|serial| agent.learn.justification_names.get(&serial));
    if let Some(name) = justification {
        return Some(name.as_str());
    }
    if p.recall {
        return Some("|Memory System Recall|");
    }
    if let Some(o) = p.origin.as_ref().filter(|o| p.inst.is_none() && o.trace.prod.is_none()) {
        return Some(&o.trace.name);
    }
    p.inst
        .map(|i| agent.decider.insts[i].prod)
        .or(p.rule)
        .map(|prod| agent.production_name(prod))
}

impl AgentCore {
    /// Does the print stream stand at the start of a line? (What is still in `output`
    /// decides; when it has been taken, the front end's record of it.)
    pub(crate) fn at_line_start(&self) -> bool {
        match self.output.as_bytes().last() {
            Some(&b) => b == b'\n',
            None => self.output_line_start,
        }
    }

    /// A newline unless the print stream is at the start of a line (9.6's fresh line).
    pub(crate) fn fresh_line(&mut self) {
        if !self.at_line_start() {
            self.output.push('\n');
        }
    }

    /// Sends a trace event to the 9.6 text listener, which appends its text to `output`.
    /// Callers build events only when the trace setting that shows them is on.
    pub(crate) fn emit(&mut self, event: &TraceEvent<'_>) {
        // A break's interrupt comes before what follows its match (9.6 prints it at once).
        self.report_break_hits();
        self.trace_text
            .write(&mut self.output, self.output_line_start, &self.symbols, event);
    }

    /// Writes a trace event that borrows the agent's memories into `out`, the print
    /// stream set aside for the while (`std::mem::take`, which does not allocate).
    pub(crate) fn write_event(&self, out: &mut String, event: &TraceEvent<'_>) {
        self.trace_text
            .write(out, self.output_line_start, &self.symbols, event);
    }

    /// A phase header of trace level 2 (`trace -p`).
    pub(crate) fn trace_phase(&mut self, event: TraceEvent<'_>) {
        if self.settings.trace.phases {
            self.emit(&event);
        }
    }

    /// `+ (pref) (rule)` or `- ...` on a line of its own (`trace -r`).
    pub(crate) fn trace_pref(&mut self, sign: char, pid: crate::decide::state::PrefId) {
        if !self.settings.trace.preferences {
            return;
        }
        let mut out = std::mem::take(&mut self.output);
        self.write_pref_event(&mut out, self.output_line_start, sign == '+', pid);
        self.output = out;
    }

    /// `+ ... ALREADY SUPPORTED ON TOP LEVEL.  IGNORING.` for a preference not added.
    pub(crate) fn trace_ignored_pref(&mut self, pid: crate::decide::state::PrefId) {
        if !self.settings.trace.preferences {
            return;
        }
        let mut out = std::mem::take(&mut self.output);
        let pref = &self.decider.prefs[pid];
        let event = TraceEvent::IgnoredPreference {
            pref,
            level: pref_level(self, pref),
            rule: pref_rule(self, pref),
        };
        self.trace_text.write(&mut out, self.output_line_start, &self.symbols, &event);
        self.output = out;
    }

    /// Writes the `Preference` event of `pid` into `out`; `line_start` as for
    /// [`TraceText96::write`](crate::trace_text::TraceText96::write).
    pub(crate) fn write_pref_event(
        &self,
        out: &mut String,
        line_start: bool,
        added: bool,
        pid: crate::decide::state::PrefId,
    ) {
        let pref = &self.decider.prefs[pid];
        let event = TraceEvent::Preference {
            added,
            pref,
            level: pref_level(self, pref),
            rule: pref_rule(self, pref),
        };
        self.trace_text.write(out, line_start, &self.symbols, &event);
    }

    /// `=>WM: (tt: id ^attr value)` when `added`, else `<=WM: ...` (`trace -w`), when the
    /// `wm watch` filters let it through.
    pub(crate) fn trace_wme(&mut self, added: bool, w: &Wme) {
        if !added {
            if let Some(buffer) = self.removed_wmes.as_mut() {
                buffer.push(*w);
                return;
            }
        }
        if self.settings.trace.wmes && self.wme_filters.passes(w, added) {
            let activation = self.wme_activation(w);
            self.emit(&TraceEvent::Wme {
                added,
                wme: w,
                activation,
            });
        }
        if !added && !self.wma.removal_lines.is_empty() {
            self.wma_flush_removal_line(w.timetag);
        }
    }
}

/// The trace of the decision cycle's steps (`trace`): elaboration headers, retractions, new
/// preferences, operators removed by the consistency check.
impl AgentCore {
    /// `--- Inner Elaboration Phase, active level N goal S ---` (`-W`) before the firings
    /// at one goal of an elaboration cycle; `None` when only retractions of goals that are
    /// gone are pending (9.6 has no active goal then).
    pub(crate) fn trace_inner_elaboration(&mut self, level: Option<u32>) {
        if !self.settings.trace.waterfall {
            return;
        }
        let event = match level {
            Some(l) => {
                let goal = self
                    .decider
                    .goals
                    .iter()
                    .find(|g| g.level == l)
                    .map_or(self.top.state, |g| g.state);
                TraceEvent::InnerElaboration {
                    level: l,
                    goal: Some(goal),
                }
            }
            None => TraceEvent::InnerElaboration {
                level: 0,
                goal: None,
            },
        };
        self.emit(&event);
    }

    /// `Retracting rule` (`-u` and the like) and the preferences that go with it (`-r`).
    /// An o-supported instantiation, or one that made no preferences, has nothing to
    /// retract: 9.6 prints nothing for it, nor for a justification.
    pub(crate) fn trace_retraction(&mut self, inst: crate::decide::state::InstId) {
        if self.decider.insts[inst].serial != 0 {
            self.trace_justification_retraction(inst);
            return;
        }
        let (prod, quiet) = {
            let i = &self.decider.insts[inst];
            // Firings in a substate that is gone retract silently too (checked on 9.6).
            let goal_gone = i
                .goal
                .is_some_and(|g| !self.decider.goals.iter().any(|x| x.state == g));
            (
                i.prod,
                i.o_support || i.prefs.is_empty() || i.serial != 0 || goal_gone,
            )
        };
        if quiet {
            return;
        }
        let name = self.production_name(prod).to_string();
        let traced = self
            .production_arc(&name)
            .is_some_and(|p| self.settings.trace.firings_of(&p.flags));
        if traced {
            self.emit(&TraceEvent::Retraction { rule: &name });
            // The WMEs it fired on, as listed then: the match's token is gone by now.
            match self.decider.traced_match_wmes.remove(&inst) {
                Some(wmes) => self.emit_match_wmes(&wmes, true),
                None => {
                    let i = &self.decider.insts[inst];
                    let wmes = self.match_wme_list(i.prod, i.token);
                    self.emit_match_wmes(&wmes, true);
                }
            }
        }
        let listed = traced && self.settings.trace.wme_detail != crate::agent::WmeDetail::None;
        self.trace_retracted_prefs(inst, listed);
    }

    /// A retracting instantiation's preferences, newest first: each listed (with
    /// `--timetags` or `--fullwmes`, when `listed`), then its `-` line if it is i-supported
    /// (preferences trace), one preference after the other as 9.6 prints them.
    fn trace_retracted_prefs(&mut self, inst: crate::decide::state::InstId, listed: bool) {
        let removals = self.settings.trace.preferences;
        if !listed && !removals {
            return;
        }
        let prefs = self.decider.insts[inst].prefs.clone();
        for pid in prefs.into_iter().rev() {
            if listed {
                self.trace_instantiation_prefs(&[pid]);
            }
            let p = &self.decider.prefs[pid];
            if removals && p.alive && !p.o_support {
                self.trace_pref('-', pid);
            }
        }
    }

    /// A justification retracting (a superstate negation matched, or a WME it tests went):
    /// `Retracting justify1` with the firings trace, then its results' `-` lines with the
    /// preferences trace, as 9.6 prints them; no match WMEs (checked on 9.6).
    fn trace_justification_retraction(&mut self, inst: crate::decide::state::InstId) {
        let i = &self.decider.insts[inst];
        if i.o_support || i.prefs.is_empty() {
            return;
        }
        let serial = i.serial;
        let Some(j) = self
            .learn
            .justifications
            .iter()
            .find(|j| j.serial == serial)
        else {
            return;
        };
        let traced = self.settings.trace.firings_of(&j.flags());
        let listed = traced && self.settings.trace.wme_detail != crate::agent::WmeDetail::None;
        if traced {
            let mut out = std::mem::take(&mut self.output);
            let event = TraceEvent::Retraction { rule: j.name() };
            self.write_event(&mut out, &event);
            self.output = out;
            if listed {
                // The WMEs it was built on (kept when it was made), then its preferences.
                let wmes = self
                    .decider
                    .traced_match_wmes
                    .remove(&inst)
                    .unwrap_or_default();
                self.emit_match_wmes(&wmes, true);
            }
        }
        self.trace_retracted_prefs(inst, listed);
    }

    /// The removals the o-supported rejects of one elaboration cycle's firings make, in
    /// firing and action order (before the cycle's other preferences are added, checked
    /// on 9.6: water-jug, o-reject and blocks-world at trace 5). A preference two rejects
    /// take is removed, and traced, once.
    pub(crate) fn trace_o_reject_removals(&mut self, new_prefs: &[crate::decide::state::PrefId]) {
        use crate::decide::procedure::PrefType;
        let mut gone: FxHashSet<crate::decide::state::PrefId> = FxHashSet::default();
        for &pid in new_prefs.iter() {
            let p = &self.decider.prefs[pid];
            if !(p.kind == PrefType::Reject && p.o_support) {
                continue;
            }
            let (key, value) = ((p.id, p.attr), p.value);
            let removed: Vec<_> = self
                .decider
                .slots
                .get(&key)
                .map(|slot| {
                    slot.prefs
                        .iter()
                        .rev()
                        .copied()
                        .filter(|&x| x != pid && self.decider.prefs[x].value == value)
                        .filter(|&x| gone.insert(x))
                        .collect()
                })
                .unwrap_or_default();
            for r in removed {
                self.trace_pref('-', r);
            }
        }
    }

    /// `REMOVING: Operator from context slot (proposal no longer matches): (wme)` (`-o`).
    pub(crate) fn trace_operator_removal(&mut self, key: (Sym, Sym), op: Sym) {
        let w = self
            .decider
            .slots
            .get(&key)
            .and_then(|s| s.wmes.get(&(op, true)))
            .and_then(|w| self.wm.get(w).copied());
        let activation = w.as_ref().and_then(|w| self.wme_activation(w));
        self.emit(&TraceEvent::OperatorRemoval {
            wme: w.as_ref(),
            activation,
        });
    }
}

impl AgentCore {
    /// `Removing state S2 because element in GDS changed. WME: (...)` (`-g`), before the
    /// working-memory changes of the cycle that take a WME out of a substate's GDS: once
    /// for the highest such goal (the ones below it go with it), naming the first such
    /// WME in the order the slot decisions remove them (9.6's order).
    pub(crate) fn trace_gds_removals(&mut self, removes: &[(crate::wm::WmeId, u64)]) {
        let mut reported: Option<u32> = None;
        for &(w, tt) in removes.iter() {
            let Some(wme) = self
                .wm
                .get(w)
                .copied()
                .filter(|x| x.timetag == tt && self.gds_watches_removal(x))
            else {
                continue;
            };
            let Some(goal) = self.decider.gds.get(&w).map(|m| m.goal) else {
                continue;
            };
            let level = self.symbols.id_data(goal).map_or(0, |d| d.level);
            if reported.is_some_and(|l| l <= level) {
                continue;
            }
            reported = Some(level);
            let activation = self.wme_activation(&wme);
            self.emit(&TraceEvent::GdsRemoval {
                goal,
                wme: &wme,
                activation,
            });
        }
    }
}

impl AgentCore {
    /// With `trace --timetags` or `--fullwmes`, the WMEs a traced firing or retraction
    /// matched, after its `Firing`/`Retracting` line and before its actions run: ` 16 14`
    /// or one ` (16: S1 ^operator O1)` a line, then ` -->`. (9.6 lists them in its
    /// reordered condition order, ours in the written order; and its `--fullwmes` prints
    /// some as `WME with time tag 16`.)
    /// Returns the WMEs listed, for the retraction to list again.
    pub(crate) fn trace_match_wmes(
        &mut self,
        p: crate::rete::ProdId,
        t: crate::rete::TokId,
    ) -> Vec<Wme> {
        let detail = self.settings.trace.wme_detail;
        if detail == crate::agent::WmeDetail::None {
            return Vec::new();
        }
        let wmes = self.match_wme_list(p, t);
        self.emit_match_wmes(&wmes, false);
        wmes
    }

    /// The WMEs of a match that are still in working memory, in the rule's order.
    pub(crate) fn match_wme_list(&self, p: crate::rete::ProdId, t: crate::rete::TokId) -> Vec<Wme> {
        self.rete
            .match_wmes(p, t)
            .into_iter()
            .filter_map(|w| self.wm.get(w).copied())
            .collect()
    }

    fn emit_match_wmes(&mut self, wmes: &[Wme], retracting: bool) {
        let detail = self.settings.trace.wme_detail;
        if detail != crate::agent::WmeDetail::None {
            self.emit(&TraceEvent::MatchWmes {
                wmes,
                full: detail == crate::agent::WmeDetail::Full,
                retracting,
            });
        }
    }

    /// The instantiation's preferences, one a line, newest first (with `--timetags` or
    /// `--fullwmes`), after its actions ran.
    pub(crate) fn trace_instantiation_prefs(&mut self, prefs: &[crate::decide::state::PrefId]) {
        if self.settings.trace.wme_detail == crate::agent::WmeDetail::None {
            return;
        }
        // At the level of the goal its instantiation matched (a result made in a substate
        // says `[level 2]`, as in 9.6), with no rule.
        let mut out = std::mem::take(&mut self.output);
        for &pid in prefs.iter().rev() {
            let pref = &self.decider.prefs[pid];
            let level = pref_level(self, pref);
            self.write_event(&mut out, &TraceEvent::InstantiationPreference { pref, level });
        }
        self.output = out;
    }
}

impl AgentCore {
    /// The `<=WM:` lines of one working-memory phase in 9.6's order (what is removed does
    /// not change, only the order it is listed in). 9.6 head-inserts its removals, so it
    /// lists them in the reverse of the order it made them: garbage first (newest first),
    /// then the operator slots' `+` WMEs oldest first with a selected operator right after
    /// its `+` WME, then the WMEs the slot decisions removed in the order their slots
    /// changed (the `decided` part of the buffer). Checked with scripts/trace_compare.py.
    pub(crate) fn trace_removed_wmes(&mut self, decided: std::ops::Range<usize>) {
        let Some(wmes) = self.removed_wmes.take() else {
            return;
        };
        let substates = std::mem::take(&mut self.substate_removals);
        let by_gds = std::mem::take(&mut self.substates_by_gds);
        let trigger = self.gds_trigger.take();
        let slot_order = std::mem::take(&mut self.substate_slot_order);
        let wmes: Vec<(usize, Wme)> = wmes.into_iter().enumerate().collect();
        let op = self.symbols.find_str("operator");
        let context = |agent: &AgentCore, w: &Wme| Some(w.attr) == op && agent.symbols.is_goal(w.id);
        // Each operator's `+` WME's timetag, by (state, operator).
        let plus: Vec<((Sym, Sym), u64)> = wmes
            .iter()
            .filter(|(_, w)| w.acceptable && context(self, w))
            .map(|(_, w)| ((w.id, w.value), w.timetag))
            .collect();
        // When an operator removal takes substates away, 9.6 lists the memories' structure
        // and the substates' slot WMEs before the garbage, their operator `+` WMEs before
        // the goals', then their impasse WMEs, and the selected operators after those
        // (checked on soar-sml 9.6.5: substate-results, learn-justification,
        // tests/data/traces/substate.soar). When a GDS change takes them: the memories'
        // structure, the rest of the garbage (newest first), the goals' operator WMEs, the
        // substates' operator `+` WMEs, the slot decisions made before the WME that took
        // them, the WMEs of the slots the substates' preferences were in (slot by slot in
        // the order those preferences go, each slot's oldest first), that WME and the
        // decisions after it, their impasse WMEs, their selected operators (agents gds,
        // learn-lookahead, long/fifteen-puzzle, long/factorization).
        let with_substates = !substates.is_empty();
        let trigger_at = trigger.and_then(|tt| {
            wmes.iter()
                .find(|(i, w)| decided.contains(i) && w.timetag == tt)
                .map(|&(i, _)| i)
        });
        let in_slot = |w: &Wme| slot_order.iter().position(|&k| k == (w.id, w.attr));
        let rank = |agent: &AgentCore, (i, w): &(usize, Wme)| -> (u8, i64, u8) {
            if !context(agent, w) {
                if by_gds {
                    if decided.contains(i) {
                        match trigger_at {
                            Some(t) if *i < t => (3, *i as i64, 0),
                            _ => (6, *i as i64, 0),
                        }
                    } else if let Some(k) = in_slot(w) {
                        (4, k as i64, 0)
                    } else {
                        // Right after the memories' structure, newest first.
                        (0, (1 << 48) - w.timetag as i64, 0)
                    }
                } else if decided.contains(i) {
                    (10, *i as i64, 0)
                } else {
                    // The garbage, as its collection listed it.
                    (2, *i as i64, 0)
                }
            } else {
                let tt = plus
                    .iter()
                    .find(|(k, _)| *k == (w.id, w.value))
                    .map_or(w.timetag, |&(_, tt)| tt);
                match (with_substates && !by_gds, w.acceptable) {
                    (true, false) => (9, tt as i64, 0),
                    _ if by_gds => (1, tt as i64, u8::from(!w.acceptable)),
                    _ => (5, tt as i64, u8::from(!w.acceptable)),
                }
            }
        };
        let mut lines: Vec<((u8, i64, u8), Wme)> =
            wmes.iter().map(|x| (rank(self, x), x.1)).collect();
        for (k, (place, w)) in substates.into_iter().enumerate() {
            let k = k as i64;
            let r = match (place, by_gds) {
                (SubstateLine::Memories, _) => (0, k, 0),
                (SubstateLine::Other, false) => (1, -(w.timetag as i64), 0),
                (SubstateLine::OperatorPlus, false) => (3, w.timetag as i64, 0),
                (SubstateLine::OperatorPlus, true) => (2, w.timetag as i64, 0),
                (SubstateLine::Other, true) => match in_slot(&w) {
                    Some(s) => (4, s as i64, 0),
                    None => (0, (1 << 48) - w.timetag as i64, 0),
                },
                (SubstateLine::Impasse, _) => (7, k, 0),
                (SubstateLine::Selected, _) => (8, k, 0),
            };
            lines.push((r, w));
        }
        // Within a slot, oldest first (a stable sort: the rest keep the order listed).
        lines.sort_by_key(|(r, w)| (*r, if r.0 == 4 && by_gds { w.timetag } else { 0 }));
        // 9.6 lets the phase's removed WMEs go in this order too, after the phase's new
        // ones were made (the WMA trace's order of addresses follows).
        let next = self.wm.next_timetag();
        for (_, w) in lines {
            self.trace_wme(false, &w);
            if self.wma.on() {
                self.wma.address_freed(w.timetag, next);
            }
        }
        if self.wma.on() {
            self.wma_release_holders();
        }
    }
}
