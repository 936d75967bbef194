//! Times `run 1000` on agents in-process, for scripts/bench_decisions.py: for each agent
//! file given, `repeat` fresh interpreters each run `srand 1`, `watch 0`, `source FILE`,
//! then `run 1000` under the clock; prints `NAME decisions firings median_seconds`.
//!
//! usage: cargo run --release --example time_run -- REPEAT FILE...

use rusoar::cli::Interpreter;
use std::time::Instant;

// The allocator the rusoar binary uses, so the figures are the binary's.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn count(stats: &str, what: &str) -> u64 {
    stats
        .lines()
        .find_map(|l| l.strip_suffix(what)?.trim().parse().ok())
        .unwrap_or(0)
}

fn main() {
    let mut args = std::env::args().skip(1);
    let repeat: usize = args.next().and_then(|r| r.parse().ok()).unwrap_or(5).max(1);
    for file in args {
        let mut times = Vec::with_capacity(repeat);
        let mut stats = String::new();
        for _ in 0..repeat {
            let mut interp = Interpreter::new();
            let setup = format!("srand 1\nwatch 0\nsource {{{file}}}");
            if let Err(d) = interp.run_text("<time_run>", &setup) {
                eprintln!("{file}: {}", d.message);
                std::process::exit(1);
            }
            let start = Instant::now();
            let _ = interp.run_text("<time_run>", "run 1000");
            times.push(start.elapsed().as_secs_f64());
            let _ = interp.take_output();
            let _ = interp.run_text("<time_run>", "stats");
            stats = interp.take_output();
        }
        times.sort_by(f64::total_cmp);
        let name = std::path::Path::new(&file)
            .file_stem()
            .map_or(file.clone(), |s| s.to_string_lossy().into_owned());
        println!(
            "{name} {} {} {:.9}",
            count(&stats, " decisions"),
            count(&stats, " production firings"),
            times[times.len() / 2]
        );
    }
}
