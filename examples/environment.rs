//! An environment loop on the kernel's public API alone: a robot on a line of cells walks to
//! its goal. Every input phase writes its position on the input-link; every output phase
//! carries out the `move` commands the rules put on the output-link and marks them done; a
//! Rust function the rules call reports the distance left; a print listener shows the trace.
//!
//! Run with `cargo run --release --example environment`.

use rusoar::{Agent, InputUpdate, InputWme, Printed, RunUnit, StopReason, Value};
use std::cell::RefCell;
use std::rc::Rc;

/// The robot's rules: step toward the goal, say how far it is, halt there.
const RULES: &str = r#"
sp {propose*step-right
   (state <s> ^io.input-link <il>)
   (<il> ^position <x> ^goal > <x>)
-->
   (<s> ^operator <o> +)
   (<o> ^name step ^direction right ^from <x>)}

sp {propose*step-left
   (state <s> ^io.input-link <il>)
   (<il> ^position <x> ^goal < <x>)
-->
   (<s> ^operator <o> +)
   (<o> ^name step ^direction left ^from <x>)}

sp {apply*step
   (state <s> ^operator <o> ^io.output-link <out>)
   (<o> ^name step ^direction <d>)
-->
   (<out> ^move.direction <d>)}

sp {report*distance
   (state <s> ^io.input-link <il>)
   (<il> ^position <x> ^goal <g>)
-->
   (write |distance to go: | (exec distance <x> <g>) (crlf))}

sp {arrived
   (state <s> ^io.input-link <il>)
   (<il> ^position <x> ^goal <x>)
-->
   (write |arrived at | <x> (crlf))
   (halt)}
"#;

/// The world: a robot at a cell.
struct World {
    position: i64,
    /// The input WME that holds the position, once made.
    position_wme: Option<InputWme>,
    moves: u32,
}

fn main() -> Result<(), rusoar::Error> {
    let mut agent = Agent::new("walker");
    // The trace, `write` output and warnings, as the agent prints them.
    agent.on_print(|p| match p {
        Printed::Text(text) => print!("{text}"),
        Printed::Diagnostic(e) => eprint!("{}", e.render()),
    });
    // A host function: typed arguments in, a value (or an error) out.
    agent.register_rhs_function("distance", |_call, args| {
        let number = |i: usize| args.get(i).and_then(|a| a.as_i64());
        match (number(0), number(1)) {
            (Some(x), Some(g)) => Ok(Value::Int((g - x).abs())),
            _ => Err("distance takes two integers".to_string()),
        }
    });
    agent.execute(RULES)?;
    agent.execute("watch 1")?;
    // Only a changed position is a new WME (SML's default would re-add it every time).
    agent.set_input_update(InputUpdate::SkipIfNoChange);

    let world = Rc::new(RefCell::new(World {
        position: 0,
        position_wme: None,
        moves: 0,
    }));
    {
        // Every input phase: the goal once, the position each time.
        let world = Rc::clone(&world);
        agent.on_input_phase(move |io| {
            let mut w = world.borrow_mut();
            let result = match w.position_wme {
                Some(h) => io.update(h, w.position).map(|_| ()),
                None => {
                    let il = io.input_link();
                    io.add(il, "goal", 4)
                        .and_then(|_| io.add(il, "position", w.position))
                        .map(|h| w.position_wme = Some(h))
                }
            };
            if let Err(e) = result {
                eprintln!("input phase: {e}");
                io.stop();
            }
        });
    }
    {
        // Every output phase: carry out each new command once, then mark it done.
        let world = Rc::clone(&world);
        agent.on_output_phase(move |io| {
            for cmd in io.new_output_commands() {
                let mut w = world.borrow_mut();
                match (cmd.name.as_str(), cmd.str("direction")) {
                    ("move", Some("right")) => w.position += 1,
                    ("move", Some("left")) => w.position -= 1,
                    _ => eprintln!("unknown command {}", cmd.name),
                }
                w.moves += 1;
                if let Err(e) = io.mark_done(&cmd) {
                    eprintln!("output phase: {e}");
                }
            }
        });
    }

    let run = agent.run(50, RunUnit::Decisions)?;
    let w = world.borrow();
    println!(
        "\n{} decisions, {} firings, {} moves; the robot is at {}",
        run.decisions, run.firings, w.moves, w.position
    );
    assert_eq!(run.stop, StopReason::Halted, "the robot reaches its goal");
    assert_eq!(w.position, 4);
    Ok(())
}
