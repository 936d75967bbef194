//! Embedding the kernel from Rust: load an agent, register a Rust function the rules can call,
//! run it, and read what it printed. Run with `cargo run --release --example water_jug`.

use rusoar::commands::Interpreter;

fn main() {
    let root = env!("CARGO_MANIFEST_DIR");
    let mut interp = Interpreter::new();
    interp.set_cwd(std::path::PathBuf::from(root));
    // A Rust function the rules could call as (exec shout ...) or (shout ...).
    interp
        .agent
        .register_rhs_function("shout", |_agent, args| args.to_uppercase());
    let commands = "srand 1\nwatch 1\nsource tests/agents/water-jug.soar\nrun 1000";
    if let Err(d) = interp.run_text("example", commands) {
        eprintln!("{}", interp.sources.render(&d));
        std::process::exit(1);
    }
    print!("{}", interp.take_output());
    let d = &interp.agent.decider;
    println!("\n{} decisions, {} rule firings", d.decisions, d.firings);
}
