//! The kernel's public API as an embedding program uses it: input handles, update modes,
//! events, stop reasons, host functions and errors. Where the official kernel's behaviour is
//! the reference, the expected figures are what soar-sml 9.6.5 gave for the same program.

use rusoar::{Agent, AgentEvent, InputUpdate, Phase, Printed, RunUnit, StopReason, Value};
use std::cell::RefCell;
use std::rc::Rc;

/// An operator proposed for each `^sensor` WME: a new WME for the same value proposes a new
/// operator.
const LOOKER: &str = "sp {propose (state <s> ^io.input-link.sensor <v>)
                        --> (<s> ^operator <o> +) (<o> ^name look ^v <v>)}
                      sp {apply (state <s> ^operator <o>) (<o> ^name look)
                        --> (write |looked| (crlf))}";

/// Runs LOOKER five decisions, setting the sensor to the same value after each.
fn look_five_times(mode: Option<InputUpdate>) -> (Vec<String>, String) {
    let mut agent = Agent::default();
    agent.execute(LOOKER).unwrap();
    if let Some(mode) = mode {
        agent.set_input_update(mode);
    }
    let sensor = {
        let mut io = agent.io();
        let il = io.input_link();
        io.add(il, "sensor", 1).unwrap()
    };
    for _ in 0..5 {
        agent.run(1, RunUnit::Decisions).unwrap();
        agent.io().update(sensor, 1).unwrap();
    }
    let trace = agent.take_output();
    let ops = trace
        .lines()
        .filter_map(|l| l.split_once("O: ").map(|(_, op)| op.to_string()))
        .collect();
    (ops, agent.execute("stats").unwrap())
}

/// soar-sml 9.6.5, `Update(w, 1)` after each of five `RunSelf(1)`: O1 to O5 are selected
/// (each update removes and adds the WME again), with 9 firings, 13 elaboration cycles and
/// 58 WME changes (38 additions, 20 removals).
#[test]
fn updates_blink_by_default_as_the_official_kernel_does() {
    let (ops, stats) = look_five_times(None);
    let names: Vec<&str> = ops.iter().map(|o| &o[..2]).collect();
    assert_eq!(names, ["O1", "O2", "O3", "O4", "O5"], "{ops:?}");
    assert!(stats.contains("9 production firings"), "{stats}");
    assert!(stats.contains("13 elaboration cycles"), "{stats}");
    assert!(
        stats.contains("58 wme changes (38 additions, 20 removals)"),
        "{stats}"
    );
}

#[test]
fn skipping_unchanged_values_keeps_the_operator() {
    let (ops, _) = look_five_times(Some(InputUpdate::SkipIfNoChange));
    assert_eq!(ops.len(), 1, "{ops:?}");
}

#[test]
fn events_report_phases_firings_retractions_and_wme_changes() {
    let mut agent = Agent::default();
    agent.execute(LOOKER).unwrap();
    let log = Rc::new(RefCell::new(Vec::new()));
    let seen = Rc::clone(&log);
    agent.on_event(move |e| {
        let line = match e {
            AgentEvent::BeforePhase(p) => format!("begin {p:?}"),
            AgentEvent::AfterPhase(p) => format!("end {p:?}"),
            AgentEvent::Fired { rule } => format!("fired {rule}"),
            AgentEvent::Retracted { rule } => format!("retracted {rule}"),
            AgentEvent::WmeAdded(_) => "+wme".to_string(),
            AgentEvent::WmeRemoved(_) => "-wme".to_string(),
            AgentEvent::InitSoar => "init".to_string(),
        };
        seen.borrow_mut().push(line);
    });
    let sensor = {
        let mut io = agent.io();
        let il = io.input_link();
        io.add(il, "sensor", 1).unwrap()
    };
    agent.run(1, RunUnit::Decisions).unwrap();
    {
        let log = log.borrow();
        assert_eq!(log[0], "begin Input");
        assert_eq!(log[1], "+wme", "the sensor reaches working memory");
        let phases: Vec<&String> = log.iter().filter(|l| l.starts_with("end")).collect();
        assert_eq!(phases, ["end Input", "end Propose", "end Decide"]);
        assert!(log.contains(&"fired propose".to_string()), "{log:?}");
    }
    agent.io().remove(sensor).unwrap();
    agent.run(1, RunUnit::Decisions).unwrap();
    assert!(log.borrow().contains(&"retracted propose".to_string()));
    assert!(log.borrow().contains(&"-wme".to_string()));
    agent.init_soar().unwrap();
    assert_eq!(log.borrow().last().map(String::as_str), Some("init"));
}

#[test]
fn a_listener_can_be_removed() {
    let mut agent = Agent::default();
    let count = Rc::new(RefCell::new(0));
    let c = Rc::clone(&count);
    let id = agent.on_event(move |e| {
        if matches!(e, AgentEvent::BeforePhase(Phase::Input)) {
            *c.borrow_mut() += 1;
        }
    });
    agent.run(2, RunUnit::Decisions).unwrap();
    assert!(agent.remove_listener(id));
    assert!(!agent.remove_listener(id));
    agent.run(2, RunUnit::Decisions).unwrap();
    assert_eq!(*count.borrow(), 2);
}

#[test]
fn runs_say_why_they_stopped() {
    let mut agent = Agent::default();
    agent.set_trace_level(0);
    let r = agent.run(3, RunUnit::Decisions).unwrap();
    assert_eq!((r.decisions, r.stop), (3, StopReason::LimitReached));

    agent
        .execute("sp {stop (state <s> ^superstate nil) --> (halt)}")
        .unwrap();
    agent.init_soar().unwrap();
    let r = agent.run(10, RunUnit::Decisions).unwrap();
    assert_eq!(r.stop, StopReason::Halted);

    // A hook asks for a stop.
    let mut agent = Agent::default();
    agent.set_trace_level(0);
    agent.on_output_phase(|io| {
        if io.decisions() == 2 {
            io.stop();
        }
    });
    let r = agent.run(10, RunUnit::Decisions).unwrap();
    assert_eq!((r.decisions, r.stop), (2, StopReason::Interrupted));

    // State no-changes all the way down.
    let mut agent = Agent::default();
    agent.execute("watch 0\nsoar max-goal-depth 5").unwrap();
    let r = agent.run(1, RunUnit::Forever).unwrap();
    assert_eq!(r.stop, StopReason::GoalDepthExceeded);

    // Until output: the rule writes the output-link in the first decision.
    let mut agent = Agent::default();
    agent
        .execute("watch 0\nsp {out (state <s> ^io.output-link <ol>) --> (<ol> ^say.text hi)}")
        .unwrap();
    let r = agent.run(1, RunUnit::Output).unwrap();
    assert_eq!((r.decisions, r.stop), (1, StopReason::Output));
    let cmds = agent.io().new_output_commands();
    assert_eq!(cmds[0].str("text"), Some("hi"));
}

#[test]
fn a_panicking_host_function_is_reported_and_the_agent_goes_on() {
    let mut agent = Agent::default();
    agent.register_rhs_function("boom", |_, _| panic!("out of cheese"));
    agent.register_rhs_function("add", |_, args| {
        let sum: f64 = args.iter().filter_map(|a| a.as_f64()).sum();
        Ok(Value::Float(sum))
    });
    agent.register_rhs_function("fails", |_, _| Err("not today".into()));
    agent
        .execute(
            "sp {t (state <s> ^superstate nil) -->
               (<s> ^a (exec boom 1) ^b (exec add 1 2.5) ^c (exec fails))}",
        )
        .unwrap();
    // The panic stops the run after the phase it happened in: the decision is not done.
    let r = agent.run(1, RunUnit::Decisions).unwrap();
    assert_eq!((r.decisions, r.stop), (0, StopReason::Interrupted));
    let trace = agent.take_output();
    assert!(
        trace.contains("rhs function boom panicked: out of cheese"),
        "{trace}"
    );
    assert!(
        trace.contains("rhs function fails failed: not today"),
        "{trace}"
    );
    let s1 = agent.top_state();
    let b = agent
        .children(s1)
        .into_iter()
        .find(|w| agent.text(w.attr) == "b")
        .map(|w| agent.value_of(w.value));
    assert_eq!(b, Some(Value::Float(3.5)));
    // Still usable.
    let r = agent.run(2, RunUnit::Decisions).unwrap();
    assert_eq!(r.stop, StopReason::LimitReached);
    assert_eq!(agent.check_invariants(), Ok(()));
}

#[test]
fn a_panicking_function_in_sml_form_stops_the_run_too() {
    let mut agent = Agent::default();
    agent.register_sml_rhs_function("boom", |_, _| panic!("no more"));
    agent
        .execute("sp {t (state <s> ^superstate nil) --> (<s> ^a (exec boom 1))}")
        .unwrap();
    let r = agent.run(3, RunUnit::Decisions).unwrap();
    assert_eq!((r.decisions, r.stop), (0, StopReason::Interrupted));
    assert!(agent
        .take_output()
        .contains("rhs function boom panicked: no more"));
    let r = agent.run(2, RunUnit::Decisions).unwrap();
    assert_eq!((r.decisions, r.stop), (2, StopReason::LimitReached));
}

#[test]
fn errors_are_standard_errors_that_render_themselves() {
    fn load(agent: &mut Agent) -> Result<(), Box<dyn std::error::Error>> {
        agent.execute("sp {broken (state <s>) --> (<s> ^a)}")?;
        Ok(())
    }
    let mut agent = Agent::default();
    let e = load(&mut agent).unwrap_err();
    let text = e.to_string();
    assert!(text.contains("<command>:1:"), "{text}");
    let e = agent.execute("run -x").unwrap_err();
    assert_eq!(e.location().map(|l| l.line), Some(1));
    assert!(e.render().ends_with('\n'));
}

#[test]
fn misuse_of_the_io_links_is_an_error() {
    let mut agent = Agent::default();
    let mut io = agent.io();
    let il = io.input_link();
    let (obj, o) = io.add_object(il, "obj").unwrap();
    let child = io.add(o, "x", 1).unwrap();
    io.remove(obj).unwrap();
    assert!(
        io.update(child, 2).is_err(),
        "a removed object's WMEs go with it"
    );
    assert!(io.remove(obj).is_err());
    assert!(io.value(child).is_err());
    let five = io.add(il, "five", 5).unwrap();
    let printed: Vec<Printed> = agent.take_printed();
    assert!(printed.is_empty());
    assert_eq!(agent.io().value(five).unwrap(), Value::Int(5));
}

/// soar-sml 9.6.5 keeps an SML client's input WMEs across `init-soar` (the client adds them
/// again) and the client's handles stay valid.
#[test]
fn input_handles_survive_init_soar() {
    let mut agent = Agent::default();
    agent.execute(LOOKER).unwrap();
    let sensor = {
        let mut io = agent.io();
        let il = io.input_link();
        io.add(il, "sensor", 1).unwrap()
    };
    agent.run(2, RunUnit::Decisions).unwrap();
    agent.init_soar().unwrap();
    agent.take_output();
    agent.run(1, RunUnit::Decisions).unwrap();
    assert!(agent.take_output().contains("O: O1 (look)"));
    agent.io().update(sensor, 2).unwrap();
    assert_eq!(agent.io().value(sensor).unwrap(), Value::Int(2));
}

/// An apply phase that never ends (each firing makes the next match, under a huge
/// max-elaborations) stops within an elaboration cycle of the interrupt, and goes on at the
/// next run.
#[test]
fn an_interrupt_stops_an_endless_phase() {
    let mut agent = Agent::default();
    agent
        .source_text(
            "t",
            "soar max-elaborations 30000000\n\
             sp {propose (state <s> ^superstate nil) --> (<s> ^operator <o> +) (<o> ^name count)}\n\
             sp {start (state <s> ^superstate nil) --> (<s> ^n 0)}\n\
             sp {apply (state <s> ^operator.name count ^n <n>) --> (<s> ^n <n> - (+ <n> 1) +)}\n",
        )
        .unwrap();
    let flag = agent.interrupt_flag();
    let setter = std::thread::spawn(move || {
        std::thread::sleep(std::time::Duration::from_millis(300));
        flag.store(true, std::sync::atomic::Ordering::SeqCst);
    });
    let started = std::time::Instant::now();
    let run = agent.run(1, RunUnit::Forever).unwrap();
    setter.join().unwrap();
    assert_eq!(run.stop, StopReason::Interrupted);
    assert!(started.elapsed() < std::time::Duration::from_secs(20));
    let firings = agent.firings();
    assert!(firings > 2, "{firings}");
    // The flag is cleared: the next run goes on in the same phase.
    let flag = agent.interrupt_flag();
    let setter = std::thread::spawn(move || {
        std::thread::sleep(std::time::Duration::from_millis(100));
        flag.store(true, std::sync::atomic::Ordering::SeqCst);
    });
    let again = agent.run(1, RunUnit::Forever).unwrap();
    setter.join().unwrap();
    assert_eq!(again.stop, StopReason::Interrupted);
    assert!(agent.firings() > firings);
}
