//! The kernel's consistency checks hold after every decision of every test agent and
//! benchmark agent, and after `init-soar` (the checks: `Agent::check_invariants`).

use rusoar::Agent;

fn agents() -> Vec<std::path::PathBuf> {
    let mut files: Vec<_> = ["tests/agents", "tests/agents/long", "benches/agents"]
        .iter()
        .flat_map(|d| std::fs::read_dir(d).expect("the folder is readable"))
        .map(|e| e.expect("a folder entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "soar"))
        .collect();
    files.sort();
    files
}

#[test]
fn invariants_hold_after_every_decision() {
    for file in agents() {
        let mut agent = Agent::default();
        agent.execute("srand 1\nwatch 0").expect("settings");
        agent.source_file(&file).expect("the agent loads");
        for d in 0..150 {
            agent.execute("run 1").expect("a decision runs");
            if let Err(v) = agent.check_invariants() {
                panic!(
                    "{}: after decision {}:\n{}",
                    file.display(),
                    d + 1,
                    v.join("\n")
                );
            }
            if agent.is_halted() {
                break;
            }
        }
        agent.init_soar().expect("init-soar");
        if let Err(v) = agent.check_invariants() {
            panic!("{}: after init-soar:\n{}", file.display(), v.join("\n"));
        }
    }
}
