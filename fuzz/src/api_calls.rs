//! Random sequences of calls to the embedding API, drawn from bytes: input WMEs added,
//! updated and removed (on live and on stale handles and identifiers), runs of every unit,
//! `init-soar`, rules sourced and excised, host functions registered and unregistered,
//! output commands read and marked done, phase hooks and listeners added and removed. A
//! call may fail with an error, never panic, and the kernel's invariants hold after each.
//!
//! The `api_calls` fuzz target feeds it libFuzzer's bytes; `tests/api_calls.rs` includes
//! this same file and feeds it seeded pseudo-random bytes.

use arbitrary::{Result, Unstructured};
use rusoar::{Agent, InputUpdate, InputWme, ListenerId, RhsArg, RunUnit, Symbol, Value};

/// Rules that read the input-link, call the host functions `f1` and `f2`, write commands on
/// the output-link, remove the ones marked done, and halt on request.
const RULES: &[(&str, &str)] = &[
    (
        "api*propose",
        "(state <s> ^io.input-link.<a> <v>) --> (<s> ^operator <o> +) (<o> ^name act ^v <v>)",
    ),
    (
        "api*apply",
        "(state <s> ^operator <o> ^io.output-link <ol>) (<o> ^name act ^v <v>) \
         --> (<ol> ^cmd <c>) (<c> ^v <v> ^r (exec f1 <v>))",
    ),
    (
        "api*elaborate",
        "(state <s> ^io.input-link <il>) (<il> ^<a> <v>) --> (<s> ^seen (f2 <v> 1))",
    ),
    (
        "api*clean",
        "(state <s> ^operator <o> ^io.output-link <ol>) (<ol> ^cmd <c>) (<c> ^status complete) \
         --> (<ol> ^cmd <c> -)",
    ),
    (
        "api*deep",
        "(state <s> ^io.input-link <il>) (<il> ^<a> <x>) (<x> ^<b> <y>) --> (<s> ^deep <y>)",
    ),
    ("api*halt", "(state <s> ^io.input-link.stop yes) --> (halt)"),
];

const ATTRS: &[&str] = &["a", "b", "stop", "c"];
const FUNCTIONS: &[&str] = &["f1", "f2", "f3"];
const COMMANDS: &[&str] = &[
    "print --depth 4 s1",
    "stats",
    "matches api*propose",
    "preferences s1 operator --names",
    "print --gds",
    "excise --all",
    "chunk always",
];

/// The most calls a sequence makes.
const MAX_CALLS: u32 = 60;

struct Driver {
    inputs: Vec<InputWme>,
    objects: Vec<Symbol>,
    listeners: Vec<ListenerId>,
    log: Vec<String>,
}

fn value(u: &mut Unstructured, d: &Driver, agent: &Agent) -> Result<Value> {
    Ok(match u.int_in_range(0..=5)? {
        0 => Value::Int(u.int_in_range(-3..=3)?),
        1 => Value::Float(f64::from(u.int_in_range(-4..=4)?) / 2.0),
        2 => Value::Str("yes".into()),
        3 => Value::Str(["x", "", "with space", "|"][u.choose_index(4)?].into()),
        4 if !d.objects.is_empty() => Value::Id(d.objects[u.choose_index(d.objects.len())?]),
        _ => Value::Id(agent.top_state()),
    })
}

fn object(u: &mut Unstructured, d: &Driver, agent: &mut Agent) -> Result<Symbol> {
    Ok(if d.objects.is_empty() || u.ratio(1, 3)? {
        agent.io().input_link()
    } else {
        d.objects[u.choose_index(d.objects.len())?]
    })
}

fn input(u: &mut Unstructured, d: &Driver) -> Result<Option<InputWme>> {
    Ok(if d.inputs.is_empty() {
        None
    } else {
        Some(d.inputs[u.choose_index(d.inputs.len())?])
    })
}

/// A host function that answers, fails, or answers with its arguments' count.
fn register(u: &mut Unstructured, agent: &mut Agent) -> Result<String> {
    let name = FUNCTIONS[u.choose_index(FUNCTIONS.len())?];
    Ok(match u.int_in_range(0..=3)? {
        0 => {
            agent.register_rhs_function(name, |_, args: &[RhsArg]| {
                Ok(Value::Int(args.len() as i64))
            });
            format!("register {name} (count)")
        }
        1 => {
            agent.register_rhs_function(name, |_, _| Err("refused".into()));
            format!("register {name} (error)")
        }
        2 => {
            agent.register_rhs_function(name, |call, args| {
                Ok(match args.first() {
                    Some(RhsArg::Id(id)) => Value::Id(*id),
                    _ => Value::Str(call.agent_name().to_string()),
                })
            });
            format!("register {name} (identity)")
        }
        _ => {
            agent.register_sml_rhs_function(name, |_, args| format!("<{args}>"));
            format!("register {name} (sml)")
        }
    })
}

fn call(u: &mut Unstructured, d: &mut Driver, agent: &mut Agent) -> Result<String> {
    Ok(match u.int_in_range(0..=20)? {
        0 | 1 => {
            let id = object(u, d, agent)?;
            let attr = ATTRS[u.choose_index(ATTRS.len())?];
            let v = value(u, d, agent)?;
            let what = format!("add {} ^{attr} {v:?}", agent.text(id));
            if let Ok(w) = agent.io().add(id, attr, v) {
                d.inputs.push(w);
            }
            what
        }
        2 => {
            let id = object(u, d, agent)?;
            let attr = ATTRS[u.choose_index(ATTRS.len())?];
            let what = format!("add object {} ^{attr}", agent.text(id));
            if let Ok((w, o)) = agent.io().add_object(id, attr) {
                d.inputs.push(w);
                d.objects.push(o);
            }
            what
        }
        3 => match input(u, d)? {
            Some(w) => {
                let v = value(u, d, agent)?;
                let what = format!("update {w:?} to {v:?}");
                let _ = agent.io().update(w, v);
                what
            }
            None => "no update".into(),
        },
        4 => match input(u, d)? {
            Some(w) => {
                let _ = agent.io().remove(w);
                let _ = agent.io().value(w);
                format!("remove {w:?}")
            }
            None => "no removal".into(),
        },
        5..=8 => {
            let n = u.int_in_range(1..=3)?;
            let unit = [
                RunUnit::Phases,
                RunUnit::Decisions,
                RunUnit::Elaborations,
                RunUnit::Output,
            ][u.choose_index(4)?];
            let _ = agent.run(n, unit);
            format!("run {n} {unit:?}")
        }
        9 => {
            let _ = agent.init_soar();
            "init-soar".into()
        }
        10 | 11 => {
            let (name, body) = RULES[u.choose_index(RULES.len())?];
            let _ = agent.execute(&format!("sp {{{name} {body}}}"));
            format!("source {name}")
        }
        12 => {
            let (name, _) = RULES[u.choose_index(RULES.len())?];
            let _ = agent.execute(&format!("excise {name}"));
            format!("excise {name}")
        }
        13 => register(u, agent)?,
        14 => {
            let name = FUNCTIONS[u.choose_index(FUNCTIONS.len())?];
            agent.unregister_rhs_function(name);
            format!("unregister {name}")
        }
        15 => {
            let mode = if u.ratio(1, 2)? {
                InputUpdate::BlinkIfNoChange
            } else {
                InputUpdate::SkipIfNoChange
            };
            agent.set_input_update(mode);
            format!("input update {mode:?}")
        }
        16 => {
            let mut io = agent.io();
            let commands = io.new_output_commands();
            for c in commands.iter().chain(io.output_commands().iter()) {
                let _ = io.mark_done(c);
            }
            format!("mark {} commands done", commands.len())
        }
        17 => {
            // An environment's hooks: output commands done in the output phase, a counter
            // on the input-link in the input phase.
            let id = if u.ratio(1, 2)? {
                agent.on_output_phase(|io| {
                    for c in io.new_output_commands() {
                        let _ = io.mark_done(&c);
                    }
                })
            } else {
                let mut tick = 0i64;
                let mut handle = None;
                agent.on_input_phase(move |io| {
                    tick += 1;
                    let live = handle.is_some_and(|w| io.update(w, tick).is_ok());
                    if !live {
                        let il = io.input_link();
                        handle = io.add(il, "c", tick).ok();
                    }
                })
            };
            d.listeners.push(id);
            "hook".into()
        }
        18 => {
            if d.listeners.is_empty() {
                "no listener".into()
            } else {
                let id = d.listeners.remove(u.choose_index(d.listeners.len())?);
                agent.remove_listener(id);
                "remove a hook".into()
            }
        }
        19 => {
            let level = u.int_in_range(0..=5)?;
            agent.set_trace_level(level);
            format!("trace level {level}")
        }
        _ => {
            let c = COMMANDS[u.choose_index(COMMANDS.len())?];
            let _ = agent.execute(c);
            c.to_string()
        }
    })
}

/// Makes the calls `u` chooses on `agent`, checking the kernel's invariants after each;
/// a broken invariant is described with the calls that led to it.
pub fn run_api_calls(agent: &mut Agent, u: &mut Unstructured) -> std::result::Result<(), String> {
    let mut d = Driver {
        inputs: Vec::new(),
        objects: Vec::new(),
        listeners: Vec::new(),
        log: Vec::new(),
    };
    let _ = agent.execute("watch 0");
    let Ok(count) = u.int_in_range(1..=MAX_CALLS) else {
        return Ok(());
    };
    for _ in 0..count {
        let Ok(what) = call(u, &mut d, agent) else {
            break;
        };
        d.log.push(what);
        let _ = agent.take_output();
        if let Err(broken) = agent.check_invariants() {
            return Err(format!(
                "the kernel's invariants do not hold after the calls\n{}\n\n{}",
                d.log.join("\n"),
                broken.join("\n")
            ));
        }
    }
    Ok(())
}
