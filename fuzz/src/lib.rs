//! What the fuzz targets share: an agent that cannot run for ever, in a folder of its own,
//! and the filter that keeps fuzzed commands from reaching files outside that folder.

pub mod api_calls;
pub mod epmem_agent;
pub mod random_agent;
pub mod smem_agent;
pub mod steps;

use rusoar::{Agent, AgentEvent, Limits};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// Events (phases, firings, WME changes) an agent may make before its run is stopped: a
/// fuzzed agent may loop for ever by design (`run` with no count, a rule that elaborates
/// without end under a raised `max-elaborations`), which is no finding.
pub const EVENT_BUDGET: u64 = 10_000;

/// Inputs longer than this are passed over: long inputs slow the search and find nothing
/// short ones do not.
pub const MAX_INPUT: usize = 4096;

/// The ceilings every fuzzed agent runs under: the event budget is looked at between
/// elaboration cycles, and an agent whose matches double with each cycle makes each run's
/// first cycle twice the last; a ceiling stops a run before it starts. They are low enough
/// that a runaway agent stops within the fuzzer's second per input under its
/// instrumentation (a rule matching every `^io` WME of every state took 2.3 s at 50,000
/// partial matches).
pub const CEILINGS: Limits = Limits {
    wmes: 5_000,
    tokens: 10_000,
    preferences: 10_000,
    chunks: 0,
};

/// A fresh agent whose runs stop once [`EVENT_BUDGET`] events have happened, under
/// [`CEILINGS`], working in a folder of its own.
pub fn bounded_agent() -> Agent {
    let mut agent = Agent::new("fuzz");
    agent.set_limits(CEILINGS);
    agent.set_working_directory(scratch_dir());
    let flag: Arc<AtomicBool> = agent.interrupt_flag();
    let mut events = 0u64;
    agent.on_event(move |_: &AgentEvent| {
        events += 1;
        if events > EVENT_BUDGET {
            flag.store(true, Ordering::Relaxed);
        }
    });
    agent
}

/// Panics (a finding) when one of the kernel's consistency checks fails.
pub fn assert_invariants(agent: &Agent) {
    if let Err(broken) = agent.check_invariants() {
        panic!(
            "the kernel's invariants do not hold:\n{}",
            broken.join("\n")
        );
    }
}

/// The folder fuzzed commands may write in (`save`, `output log`, `command-to-file`).
pub fn scratch_dir() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rusoar-fuzz-{}", std::process::id()));
    let _ = std::fs::create_dir_all(&dir);
    dir
}

/// Whether fuzzed text may be given to the command language: it names no path outside
/// the scratch folder (no `/`, `\`, `..` or `~`), it does not lift the harness's ceilings
/// (no word that names the `limits` command), and it is not too long.
pub fn confined(text: &str) -> bool {
    text.len() <= MAX_INPUT
        && !text.contains('/')
        && !text.contains('\\')
        && !text.contains("..")
        && !text.contains('~')
        && !text
            .split(|c: char| c.is_whitespace() || "{}()\"|;".contains(c))
            .any(|w| w.len() >= 2 && "limits".starts_with(w))
}
