//! Random valid agents, drawn from bytes: a small grammar of Soar rules (proposals with
//! every kind of preference, operator comparisons, o-supported applications, elaborations,
//! and rules for substates that return results), rendered as text, sourced, then run a
//! phase at a time with the kernel's invariants checked after each step.
//!
//! The choices come from `arbitrary`'s byte reader rather than a derived AST: a rule is
//! valid only when its variables are bound by the conditions before them and its actions
//! name identifiers the conditions bind, which a context-free derivation cannot promise.
//! Whatever the bytes, the text is an agent the kernel must load without an error; when
//! the bytes run out every further choice is the first one, so generation always ends.
//!
//! The structure-aware fuzz target (`fuzz_targets/random_agent.rs`) feeds it libFuzzer's
//! bytes; `tests/random_agents.rs` includes this same file and feeds it seeded
//! pseudo-random bytes, so the checks also run in `cargo test` on the stable toolchain.

use crate::steps::{Step, Steps};
use arbitrary::{Result, Unstructured};
use rusoar::Agent;
use std::fmt::Write;

/// Attributes the rules share, so that one rule's actions meet another's conditions.
const ATTRS: &[&str] = &["a", "b", "c", "d"];
/// Constants the rules share: strings and numbers (relational tests compare numbers).
const VALUES: &[&str] = &["x", "y", "z", "1", "2", "3.5", "-1"];
/// Operator names.
const NAMES: &[&str] = &["go", "stay", "turn", "wait"];
/// Numeric comparisons for relational tests.
const RELATIONS: &[&str] = &["<", "<=", ">", ">=", "<>"];
/// The most rules an agent has, and the most steps it runs.
const MAX_RULES: u32 = 14;
const MAX_STEPS: u32 = 80;

/// Which states a rule matches.
#[derive(Clone, Copy, PartialEq)]
enum StateKind {
    Top,
    Any,
    Sub,
}

/// The variables a rule's conditions have bound so far.
struct Rule {
    next_var: u32,
    /// Variables bound to identifiers by the positive conditions (the state first).
    ids: Vec<String>,
    /// Variables bound to any value by the positive conditions.
    values: Vec<String>,
    /// `(id, attr, var)` of positive conditions on the state with a variable value: what an
    /// application may remove.
    removable: Vec<(String, String, String)>,
}

impl Rule {
    fn new() -> Rule {
        Rule {
            next_var: 0,
            ids: vec!["<s>".into()],
            values: Vec::new(),
            removable: Vec::new(),
        }
    }

    fn fresh(&mut self) -> String {
        self.next_var += 1;
        format!("<v{}>", self.next_var)
    }
}

fn pick<'a>(u: &mut Unstructured, from: &'a [&'a str]) -> Result<&'a str> {
    Ok(from[u.choose_index(from.len())?])
}

/// A value test of a positive condition: binds at most one variable, which `rule` learns.
fn value_test(
    u: &mut Unstructured,
    rule: &mut Rule,
    id: &str,
    attr: &str,
    depth: u32,
    out: &mut String,
) -> Result<String> {
    Ok(match u.int_in_range(0..=7)? {
        0 | 1 => pick(u, VALUES)?.to_string(),
        2 | 3 => {
            let v = rule.fresh();
            rule.values.push(v.clone());
            if id == "<s>" {
                rule.removable.push((id.into(), attr.into(), v.clone()));
            }
            if depth < 2 && u.ratio(1, 2)? {
                // The value is an object: test its attributes too.
                rule.ids.push(v.clone());
                let sub = conditions_on(u, rule, &v, depth + 1, 1)?;
                out.push_str(&sub);
            }
            v
        }
        4 => format!(
            "{{ {} {} }}",
            pick(u, RELATIONS)?,
            pick(u, &["1", "2", "3.5", "-1"])?
        ),
        5 => format!("<< {} {} >>", pick(u, VALUES)?, pick(u, VALUES)?),
        6 => {
            let v = rule.fresh();
            rule.values.push(v.clone());
            format!("{{ {v} <> {} }}", pick(u, VALUES)?)
        }
        _ => match rule.values.len() {
            0 => pick(u, VALUES)?.to_string(),
            n => rule.values[u.choose_index(n)?].clone(),
        },
    })
}

/// Up to `most` conditions on the identifier variable `id`, positive and negated.
fn conditions_on(
    u: &mut Unstructured,
    rule: &mut Rule,
    id: &str,
    depth: u32,
    most: u32,
) -> Result<String> {
    let mut out = String::new();
    for _ in 0..u.int_in_range(0..=most)? {
        let attr = pick(u, ATTRS)?;
        match u.int_in_range(0..=5)? {
            0..=3 => {
                let mut deeper = String::new();
                let test = value_test(u, rule, id, attr, depth, &mut deeper)?;
                let _ = write!(out, " ({id} ^{attr} {test}){deeper}");
            }
            4 => {
                // A negation; its variable is local to it.
                let value = if u.ratio(1, 2)? {
                    pick(u, VALUES)?.to_string()
                } else {
                    rule.fresh()
                };
                let _ = write!(out, " -({id} ^{attr} {value})");
            }
            _ => {
                // A conjunctive negation through a local object.
                let local = rule.fresh();
                let _ = write!(
                    out,
                    " -{{({id} ^{attr} {local}) ({local} ^{} {})}}",
                    pick(u, ATTRS)?,
                    pick(u, VALUES)?
                );
            }
        }
    }
    Ok(out)
}

/// The state condition and the conditions on it; for a substate also the superstate,
/// bound to `<ss>`.
fn state_conditions(u: &mut Unstructured, rule: &mut Rule, kind: StateKind) -> Result<String> {
    let mut out = match kind {
        StateKind::Top => "(state <s> ^superstate nil)".to_string(),
        StateKind::Any => "(state <s> ^type state)".to_string(),
        StateKind::Sub => {
            rule.ids.push("<ss>".into());
            let impasse = match u.int_in_range(0..=3)? {
                0 => " ^impasse no-change",
                1 => " ^impasse tie",
                2 => " ^attribute state",
                _ => "",
            };
            let above = conditions_on(u, rule, "<ss>", 1, 1)?;
            format!("(state <s> ^superstate <ss>{impasse}){above}")
        }
    };
    out.push_str(&conditions_on(u, rule, "<s>", 0, 3)?);
    Ok(out)
}

/// The attribute of the objects actions make. No condition tests it: a rule that made
/// objects its own conditions (or another rule's) then match would make more on every
/// elaboration cycle, without end, and that growth is the agent's, not a finding.
const MADE: &str = "made";

/// An action's attribute and value: a constant, a bound variable, arithmetic, or an object
/// made by the action (under [`MADE`]).
fn action_value(
    u: &mut Unstructured,
    rule: &mut Rule,
    extra: &mut String,
) -> Result<(&'static str, String)> {
    let attr = pick(u, ATTRS)?;
    Ok(match u.int_in_range(0..=5)? {
        0..=2 => (attr, pick(u, VALUES)?.to_string()),
        3 if !rule.values.is_empty() => (
            attr,
            rule.values[u.choose_index(rule.values.len())?].clone(),
        ),
        4 => {
            let v = rule.fresh();
            let _ = write!(extra, " ({v} ^{} {})", pick(u, ATTRS)?, pick(u, VALUES)?);
            (MADE, v)
        }
        _ => (
            attr,
            format!(
                "({} {} {})",
                pick(u, &["+", "-", "*"])?,
                pick(u, &["1", "2", "3.5"])?,
                pick(u, &["1", "2", "-1"])?
            ),
        ),
    })
}

/// Actions that add (and, for o-supported rules, remove) WMEs on `target`.
fn actions_on(
    u: &mut Unstructured,
    rule: &mut Rule,
    target: &str,
    may_remove: bool,
) -> Result<String> {
    let mut out = String::new();
    for _ in 0..u.int_in_range(1..=2)? {
        if may_remove && !rule.removable.is_empty() && u.ratio(1, 3)? {
            let (id, attr, v) = rule.removable[u.choose_index(rule.removable.len())?].clone();
            if id == target {
                let _ = write!(out, " ({id} ^{attr} {v} -)");
                continue;
            }
        }
        let mut extra = String::new();
        let (attr, value) = action_value(u, rule, &mut extra)?;
        let _ = write!(out, " ({target} ^{attr} {value}){extra}");
    }
    Ok(out)
}

/// A unary preference for the operator `<o>` on the state `<s>`, besides `+`.
fn unary_preference(u: &mut Unstructured) -> Result<&'static str> {
    Ok(match u.int_in_range(0..=9)? {
        0 => " (<s> ^operator <o> >)",
        1 => " (<s> ^operator <o> <)",
        2 => " (<s> ^operator <o> =)",
        3 => " (<s> ^operator <o> = 0.5)",
        4 => " (<s> ^operator <o> !)",
        5 => " (<s> ^operator <o> ~)",
        6 => " (<s> ^operator <o> -)",
        _ => "",
    })
}

fn state_kind(u: &mut Unstructured) -> Result<StateKind> {
    Ok(match u.int_in_range(0..=3)? {
        0 | 1 => StateKind::Top,
        2 => StateKind::Any,
        _ => StateKind::Sub,
    })
}

/// One rule's text, named `name`.
fn rule_text(u: &mut Unstructured, name: &str) -> Result<String> {
    let mut rule = Rule::new();
    let (lhs, rhs) = match u.int_in_range(0..=7)? {
        // Proposal, with a unary preference.
        0 | 1 => {
            let kind = state_kind(u)?;
            let lhs = state_conditions(u, &mut rule, kind)?;
            let mut rhs = format!("(<s> ^operator <o> +) (<o> ^name {})", pick(u, NAMES)?);
            if u.ratio(1, 3)? {
                let _ = write!(rhs, " (<o> ^{} {})", pick(u, ATTRS)?, pick(u, VALUES)?);
            }
            rhs.push_str(unary_preference(u)?);
            (lhs, rhs)
        }
        // A comparison of two proposed operators.
        2 => {
            let lhs = format!(
                "(state <s> ^operator <o1> + ^operator <o2> +) (<o1> ^name {}) (<o2> ^name {})",
                pick(u, NAMES)?,
                pick(u, NAMES)?
            );
            let rhs = match u.int_in_range(0..=5)? {
                0 => "(<s> ^operator <o1> > <o2>)",
                1 => "(<s> ^operator <o1> < <o2>)",
                2 => "(<s> ^operator <o1> = <o2>)",
                3 => "(<s> ^operator <o1> = 0.9)",
                4 => "(<s> ^operator <o2> -)",
                _ => "(<s> ^operator <o1> ~)",
            };
            (lhs, rhs.to_string())
        }
        // An o-supported application, on its own state or (in a substate) on the
        // superstate, which makes a result.
        3 | 4 => {
            let kind = state_kind(u)?;
            let mut lhs = state_conditions(u, &mut rule, kind)?;
            let _ = write!(lhs, " (<s> ^operator <o>) (<o> ^name {})", pick(u, NAMES)?);
            let target = if kind == StateKind::Sub && u.ratio(1, 2)? {
                "<ss>"
            } else {
                "<s>"
            };
            let rhs = actions_on(u, &mut rule, target, true)?;
            (lhs, rhs)
        }
        // An elaboration; in a substate it may elaborate the superstate (a result).
        5 | 6 => {
            let kind = state_kind(u)?;
            let lhs = state_conditions(u, &mut rule, kind)?;
            let target = if kind == StateKind::Sub && u.ratio(1, 2)? {
                "<ss>".to_string()
            } else {
                let n = rule.ids.len();
                rule.ids[u.choose_index(n)?].clone()
            };
            let rhs = actions_on(u, &mut rule, &target, false)?;
            (lhs, rhs)
        }
        // A tie broken from the substate: a preference for an item, made in the superstate.
        _ => {
            let lhs = format!(
                "(state <s> ^impasse tie ^superstate <ss> ^item <i>) (<i> ^name {})",
                pick(u, NAMES)?
            );
            let rhs = match u.int_in_range(0..=3)? {
                0 => "(<ss> ^operator <i> >)",
                1 => "(<ss> ^operator <i> <)",
                2 => "(<ss> ^operator <i> -)",
                _ => "(<ss> ^operator <i> =)",
            };
            (lhs, rhs.to_string())
        }
    };
    Ok(format!("sp {{{name}\n    {lhs}\n-->\n    {rhs}\n}}\n"))
}

/// Draws an agent from `u`.
pub fn random_agent(u: &mut Unstructured) -> Result<Steps> {
    let mut source = String::from("watch 0\n");
    let _ = writeln!(source, "srand {}", u.int_in_range(0..=9)?);
    if u.ratio(1, 2)? {
        source.push_str("chunk always\n");
    }
    if u.ratio(1, 4)? {
        source.push_str("decide indifferent-selection --boltzmann\n");
    }
    // A few objects on the top state for conditions that test the attributes of values.
    source.push_str(
        "sp {objects\n    (state <s> ^superstate nil)\n-->\n    \
         (<s> ^a <x> ^b <y>) (<x> ^b x ^c 1) (<y> ^a y ^d <x>)\n}\n",
    );
    let count = u.int_in_range(1..=MAX_RULES)?;
    let mut rule_names = Vec::new();
    for i in 0..count {
        // Not `r0`: a letter and digits read as an identifier, not a name.
        let name = format!("rule*{i}");
        source.push_str(&rule_text(u, &name)?);
        rule_names.push(name);
    }
    let mut steps = Vec::new();
    for _ in 0..u.int_in_range(1..=MAX_STEPS)? {
        steps.push(match u.int_in_range(0..=40)? {
            0..=29 => Step::Phase,
            30..=36 => Step::Decision,
            37 => Step::Command("init-soar".into()),
            38 => {
                let name = &rule_names[u.choose_index(rule_names.len())?];
                Step::Command(format!("excise {name}"))
            }
            39 => Step::Command("chunk always".into()),
            _ => Step::Command("chunk never".into()),
        });
    }
    Ok(Steps { source, steps })
}

/// Sources `spec` into `agent` and runs its steps, checking the kernel's invariants after
/// each.
pub fn run_random_agent(agent: &mut Agent, spec: &Steps) -> std::result::Result<(), String> {
    crate::steps::run_steps(agent, "random-agent", spec)
}
