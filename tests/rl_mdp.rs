//! Reinforcement learning on random small MDP agents, against the official kernel's
//! learned values. A proptest generator makes layered decision processes (states in layers,
//! two or three actions each, a next state per action, an integer reward on entering a
//! state, the last layer ending the episode with a halt) and the agent that walks one:
//! one RL rule per state and action, with the learning policy, rates, eligibility-trace
//! decay, learning-rate decay mode, exploration policy and numeric-indifferent mode drawn
//! too. Each agent runs several episodes (`init-soar`
//! between them) and prints `print --rl` after each.
//!
//! The agents are drawn from a fixed seed and kept in `tests/data/rl-mdp/agents.txt`; the
//! official kernel's answers, from `python3 scripts/rl_mdp_goldens.py` (which
//! `scripts/goldens.py` runs too), are in `tests/golden/rl-mdp.txt`. This test checks that
//! the generator still draws the kept agents, then runs each in rusoar and compares every
//! `print --rl`. `RUSOAR_WRITE_RL_MDP=1 cargo test --test rl_mdp` writes the agents file
//! anew (the goldens must then be regenerated).

use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use rusoar::Agent;
use std::fmt::Write;

const CASES: usize = 1000;
const EPISODES: usize = 5;
const AGENTS: &str = "tests/data/rl-mdp/agents.txt";
const GOLDEN: &str = "tests/golden/rl-mdp.txt";

/// One drawn process and its learning settings, as raw numbers the agent is made from.
#[derive(Debug, Clone)]
struct Mdp {
    depth: usize,
    width: usize,
    actions: usize,
    nexts: Vec<usize>,
    rewards: Vec<i32>,
    values: Vec<i32>,
    policy: usize,
    rates: (usize, usize, usize),
    exploration: usize,
    /// `decay-mode`, and whether numeric preferences average (`numeric-indifferent-mode`).
    decay: usize,
    average: bool,
    seed: u32,
}

fn mdp() -> impl Strategy<Value = Mdp> {
    (
        (2usize..=4, 1usize..=3, 2usize..=3),
        prop::collection::vec(0usize..100, 36),
        prop::collection::vec(-3i32..=5, 12),
        prop::collection::vec(-2i32..=2, 36),
        0usize..4,
        (0usize..3, 0usize..3, 0usize..3),
        (0usize..3, 0usize..4, any::<bool>()),
        1u32..100_000,
    )
        .prop_map(
            |(
                (depth, width, actions),
                nexts,
                rewards,
                values,
                policy,
                rates,
                (exploration, decay, average),
                seed,
            )| Mdp {
                depth,
                width,
                actions,
                nexts,
                rewards,
                values,
                policy,
                rates,
                exploration,
                decay,
                average,
                seed,
            },
        )
}

impl Mdp {
    /// The states of each layer: one to start, `width` in each middle layer, at most two
    /// at the end.
    fn layers(&self) -> Vec<Vec<usize>> {
        let mut layers = Vec::new();
        let mut n = 0;
        for l in 0..self.depth {
            let w = if l == 0 {
                1
            } else if l + 1 == self.depth {
                self.width.min(2)
            } else {
                self.width
            };
            layers.push((n..n + w).collect());
            n += w;
        }
        layers
    }

    /// The commands that load the agent and set learning up, one a line.
    fn commands(&self) -> String {
        let mut c = String::new();
        let layers = self.layers();
        let _ = writeln!(c, "srand {}", self.seed);
        c.push_str(
            "sp {mdp*propose*init (state <s> ^superstate nil -^at) --> (<s> ^operator <o> + =) (<o> ^name init)}\n",
        );
        c.push_str("sp {mdp*apply*init (state <s> ^operator.name init) --> (<s> ^at 0)}\n");
        let mut k = 0;
        for (l, layer) in layers.iter().enumerate() {
            for &s in layer {
                if s > 0 && self.rewards[s] != 0 {
                    let _ = writeln!(
                        c,
                        "sp {{mdp*reward*s{s} (state <s> ^at {s} ^reward-link <r>) --> (<r> ^reward.value {})}}",
                        self.rewards[s]
                    );
                }
                let Some(next) = layers.get(l + 1) else {
                    let _ = writeln!(c, "sp {{mdp*halt*s{s} (state <s> ^at {s}) --> (halt)}}");
                    continue;
                };
                let ops: Vec<String> = (0..self.actions).map(|a| format!("<a{a}> +")).collect();
                let acts: Vec<String> = (0..self.actions)
                    .map(|a| format!("(<a{a}> ^action {a})"))
                    .collect();
                let _ = writeln!(
                    c,
                    "sp {{mdp*propose*s{s} (state <s> ^at {s}) --> (<s> ^operator {}) {}}}",
                    ops.join(", "),
                    acts.join(" ")
                );
                for a in 0..self.actions {
                    let to = next[self.nexts[k] % next.len()];
                    let v = self.values[k];
                    k += 1;
                    let _ = writeln!(
                        c,
                        "sp {{mdp*rl*s{s}*a{a} (state <s> ^at {s} ^operator <o> +) (<o> ^action {a}) --> (<s> ^operator <o> = {v})}}"
                    );
                    let _ = writeln!(
                        c,
                        "sp {{mdp*apply*s{s}*a{a} (state <s> ^at {s} ^operator <o>) (<o> ^action {a}) --> (<s> ^at {s} - ^at {to})}}"
                    );
                }
            }
        }
        let policy = [
            "sarsa",
            "q-learning",
            "on-policy-gq-lambda",
            "off-policy-gq-lambda",
        ][self.policy];
        let alpha = ["0.3", "0.1", "0.5"][self.rates.0];
        let gamma = ["0.9", "1", "0.5"][self.rates.1];
        let lambda = ["0", "0.5", "0.9"][self.rates.2];
        let exploration = ["epsilon-greedy", "boltzmann", "softmax"][self.exploration];
        let _ = writeln!(c, "rl --set learning on");
        let _ = writeln!(c, "rl --set learning-policy {policy}");
        let _ = writeln!(c, "rl --set learning-rate {alpha}");
        let _ = writeln!(c, "rl --set discount-rate {gamma}");
        let _ = writeln!(c, "rl --set eligibility-trace-decay-rate {lambda}");
        let decay = ["normal", "exp", "log", "delta-bar-delta"][self.decay];
        let mode = if self.average { "avg" } else { "sum" };
        let _ = writeln!(c, "rl --set decay-mode {decay}");
        let _ = writeln!(c, "indifferent-selection --{exploration}");
        let _ = writeln!(c, "numeric-indifferent-mode --{mode}");
        for _ in 0..EPISODES {
            c.push_str("run 50\nprint --rl\ninit-soar\n");
        }
        c
    }
}

/// The agents the generator draws from its fixed seed, in the agents file's form.
fn drawn_agents() -> String {
    let config = Config {
        cases: CASES as u32,
        ..Config::default()
    };
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &[29; 32]);
    let mut runner = TestRunner::new_with_rng(config, rng);
    let strategy = mdp();
    let mut out = String::new();
    for i in 0..CASES {
        let case = strategy
            .new_tree(&mut runner)
            .expect("the strategy draws a value")
            .current();
        let _ = writeln!(out, "### case {i}");
        out.push_str(&case.commands());
    }
    out
}

/// The file's cases: each case's lines after its `### case N` line.
fn cases(text: &str) -> Vec<Vec<String>> {
    let mut out: Vec<Vec<String>> = Vec::new();
    for line in text.lines() {
        if line.starts_with("### ") {
            out.push(Vec::new());
        } else if let Some(case) = out.last_mut() {
            case.push(line.to_string());
        }
    }
    out
}

#[test]
fn learned_values_are_the_official_kernels() {
    let drawn = drawn_agents();
    if std::env::var_os("RUSOAR_WRITE_RL_MDP").is_some() {
        std::fs::create_dir_all("tests/data/rl-mdp").expect("the folder can be made");
        std::fs::write(AGENTS, &drawn).expect("the agents file can be written");
    }
    let kept = std::fs::read_to_string(AGENTS).expect("the agents file is readable");
    assert!(
        kept == drawn,
        "the generator no longer draws {AGENTS}: write it anew (RUSOAR_WRITE_RL_MDP=1) and regenerate the goldens"
    );
    let golden = std::fs::read_to_string(GOLDEN).expect("the golden file is readable");
    let expected = cases(&golden);
    let agents = cases(&kept);
    assert_eq!(expected.len(), agents.len(), "one golden per agent");
    for (i, (commands, want)) in agents.iter().zip(&expected).enumerate() {
        let mut agent = Agent::default();
        let mut got = Vec::new();
        for c in commands {
            let result = agent.source_text("mdp", c);
            let text = agent.take_output();
            if let Err(e) = result {
                panic!("case {i}: `{c}`: {}", e.message());
            }
            if c == "print --rl" {
                got.extend(text.trim_start_matches('\n').lines().map(str::to_string));
                got.push("---".to_string());
            }
        }
        assert!(
            &got == want,
            "case {i}: learned values differ from the official kernel's\nagent:\n{}\n--- official\n{}\n--- rusoar\n{}",
            commands.join("\n"),
            want.join("\n"),
            got.join("\n")
        );
    }
}
