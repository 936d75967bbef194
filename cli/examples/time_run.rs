//! Times `run 1000` on agents in-process, for scripts/bench_agents.py: for each agent
//! file given, `repeat` fresh agents each run `srand 1`, `watch 0`, `source FILE`,
//! then `run 1000` under the clock; prints `NAME decisions firings median_seconds`.
//!
//! usage: cargo run --release -p rusoar-cli --example time_run -- REPEAT [--run N] FILE[@D]...
//! (`--run N`: time `run N` instead of `run 1000`; `FILE@D`: time `run D` for that file;
//! `FILE@P+D1+D2...`: `run P` off the clock first, so that a memory is filled before the
//! part measured, then each `run Di` under its own clock, one median per segment printed)

use rusoar::Agent;
use std::time::Instant;

// The allocator the rusoar binary uses, so the figures are the binary's.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// The count of a `stats` line such as `512 decisions (0.020 msec/decision)`.
fn count(stats: &str, what: &str) -> u64 {
    stats
        .lines()
        .find_map(|l| {
            let (n, rest) = l.split_once(' ')?;
            rest.starts_with(what.trim()).then(|| n.parse().ok())?
        })
        .unwrap_or(0)
}

fn main() {
    let mut args = std::env::args().skip(1).peekable();
    let repeat: usize = args.next().and_then(|r| r.parse().ok()).unwrap_or(5).max(1);
    let mut decisions = 1000u64;
    if args.peek().map(String::as_str) == Some("--run") {
        args.next();
        decisions = args.next().and_then(|n| n.parse().ok()).unwrap_or(1000);
    }
    for arg in args {
        let segments = arg.rsplit_once('@').and_then(|(file, d)| {
            let runs: Option<Vec<u64>> = d.split('+').map(|n| n.parse().ok()).collect();
            Some((file.to_string(), runs?))
        });
        let (file, pre, runs) = match segments {
            Some((file, runs)) if runs.len() == 1 => (file, 0, runs),
            Some((file, runs)) => (file, runs[0], runs[1..].to_vec()),
            None => (arg.clone(), 0, vec![decisions]),
        };
        let mut times: Vec<Vec<f64>> = vec![Vec::with_capacity(repeat); runs.len()];
        let mut stats = String::new();
        for _ in 0..repeat {
            let mut agent = Agent::default();
            let setup = format!("srand 1\nwatch 0\nsource {{{file}}}");
            if let Err(e) = agent.source_text("<time_run>", &setup) {
                eprintln!("{file}: {}", e.message());
                std::process::exit(1);
            }
            if pre > 0 {
                let _ = agent.source_text("<time_run>", &format!("run {pre}"));
                let _ = agent.take_output();
            }
            for (i, d) in runs.iter().enumerate() {
                let start = Instant::now();
                let _ = agent.source_text("<time_run>", &format!("run {d}"));
                times[i].push(start.elapsed().as_secs_f64());
                let _ = agent.take_output();
            }
            let _ = agent.source_text("<time_run>", "stats");
            stats = agent.take_output();
        }
        let medians: Vec<String> = times
            .iter_mut()
            .map(|t| {
                t.sort_by(f64::total_cmp);
                format!("{:.9}", t[t.len() / 2])
            })
            .collect();
        let name = std::path::Path::new(&file)
            .file_stem()
            .map_or(file.clone(), |s| s.to_string_lossy().into_owned());
        println!(
            "{name} {} {} {}",
            count(&stats, " decisions"),
            count(&stats, " production firings"),
            medians.join(" ")
        );
    }
}
