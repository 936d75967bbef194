//! Embedding the kernel from Rust: load an agent, register a Rust function the rules can
//! call, run it, and read what it printed. Run with
//! `cargo run --release --example water_jug`.

use rusoar::{Agent, RunUnit};

fn main() -> Result<(), rusoar::Error> {
    let mut agent = Agent::new("soar");
    agent.set_working_directory(env!("CARGO_MANIFEST_DIR"));
    // A Rust function the rules could call as (exec shout ...), in SML's form: the
    // arguments' texts joined, a string back.
    agent.register_sml_rhs_function("shout", |_agent, args| args.to_uppercase());
    agent.source_text(
        "example",
        "srand 1\nwatch 1\nsource tests/agents/water-jug.soar",
    )?;
    let run = agent.run(1000, RunUnit::Decisions)?;
    print!("{}", agent.take_output());
    println!(
        "\n{} decisions, {} rule firings ({:?})",
        agent.decisions(),
        agent.firings(),
        run.stop
    );
    Ok(())
}
