//! Matcher benchmarks, on the rules of `scripts/gen_rules.py nomatch N` (generated here,
//! byte for byte the same text): N rules in 100 groups that share the prefix
//! `(state <s> ^superstate nil ^task <t>) (<t> ^name task-G ^step <st>)` and then test
//! `(<st> ^kind kI ^value <v>)` (`kI` reads as the string `K<I>`): no WME carries `^kind`
//! and `^value` together, so no rule can match.
//!
//! Working memory, the same for every size and for the official kernel
//! (`scripts/bench_official.py` sends the same commands):
//!
//! ```text
//! wm add S1 task *        # (S1 ^task I4)
//! wm add I4 name task-0   # I4 passes group 0's ^name test
//! wm add S1 other *       # (S1 ^other I5): an object that is not the task
//! wm add I4 step *        # (I4 ^step I6): group 0's partial matches reach ^kind
//! ```
//!
//! Changes timed, one WME added then removed, with 1,000 / 10,000 / 100,000 rules loaded:
//!
//! - `noise`, `(S1 ^noise x)`: no rule tests `^noise`; the WME enters no alpha memory.
//! - `step-fail`, `(I5 ^step x)`: enters the alpha memory `(* ^step *)` that every rule
//!   uses; group 0's `^step` join (its parent holds the I4 token) runs and fails (`I5` is not
//!   the task); the 99 other groups' joins have empty parents (right-unlinked).
//! - `step-partial`, `(I4 ^step x)`: passes group 0's `^step` join, so a partial match
//!   reaches group 0's beta memory, whose N/100 children test `^kind kI` against empty alpha
//!   memories (left-unlinked).
//! - `value-fail`, `(I5 ^value x)`: enters `(* ^value *)`, the alpha memory of every
//!   rule's last condition: N joins, all with empty parents (right-unlinked in Rete/UL).
//! - `kind-partial`, `(I6 ^kind |K0|)`: passes rule 0's `^kind` join, so one token enters
//!   rule 0's last beta memory (its `^value` join, on that N-join alpha memory, comes back
//!   from right-unlinking) and leaves again on removal.
//!
//! Each change is timed two ways: through the API (`Agent::add_wme` / `remove_wme`, the
//! matcher's own cost) and through the command layer (`Interpreter::run_text("wm add ...")`
//! then `wm remove <timetag>`, the output taken each time), which is what
//! `bench_official.py` measures in the official kernel with `ExecuteCommandLine`. The three
//! sizes are timed in interleaved rounds (one batch each in turn, median per size), so that
//! load from elsewhere on a shared machine falls on all sizes alike. The first add+remove of
//! each change right after the load is also timed on its own: one-time work, such as joins
//! unlinking themselves lazily on their first right activation, shows there.
//!
//! Also: the time to load the rules through the `sp` path (`run_text` of the whole text),
//! and memory per production and per WME from `VmRSS` growth in `/proc/self/status`, each
//! measured in a fresh child process (this program again) with mimalloc's purge delay at 0,
//! so that freed memory leaves the resident set at once. The package forbids `unsafe`, so a
//! counting global allocator is not possible here; the allocator is mimalloc, as in the
//! `rusoar` binary.
//!
//! Run with `cargo bench --bench rete`. `main` prints the figures first, then divan's
//! statistics follow. `RETE_BENCH_JSON=FILE` also writes the figures as JSON (read by
//! `scripts/bench_official.py --ours FILE`); `RETE_BENCH_DUMP=DIR` writes the generated rule
//! files to DIR. Under `cargo test --benches` every size is divided by 100.

use rusoar::commands::Interpreter;
use rusoar::symbols::Sym;
use std::cell::{Cell, RefCell};
use std::collections::BTreeMap;
use std::rc::Rc;
use std::time::Instant;

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

const SIZES: [usize; 3] = [1_000, 10_000, 100_000];
/// Loads timed (median) for the 1,000 and 10,000 sizes.
const LOADS_SMALL: usize = 5;
/// Interleaved rounds for the per-change tables (see `interleaved_ns`).
const API_ROUNDS: usize = 25;
const CMD_ROUNDS: usize = 25;

thread_local! {
    /// Sizes are divided by this (100 under `cargo test --benches`, 1 under `cargo bench`).
    static SCALE: Cell<usize> = const { Cell::new(100) };
    /// One loaded agent per size, built once and shared by `main`'s table and divan.
    static LOADED: RefCell<BTreeMap<usize, Rc<RefCell<Setup>>>> =
        const { RefCell::new(BTreeMap::new()) };
}

fn scaled(n: usize) -> usize {
    (n / SCALE.with(Cell::get)).max(1)
}

/// `scripts/gen_rules.py nomatch n`, the same text.
fn nomatch(n: usize) -> String {
    use std::fmt::Write;
    let mut s = String::with_capacity(n * 170);
    for i in 0..n {
        let group = i % 100;
        let _ = write!(
            s,
            "sp {{gen*nomatch*{i}\n   (state <s> ^superstate nil ^task <t>)\n   \
             (<t> ^name task-{group} ^step <st>)\n   (<st> ^kind k{i} ^value <v>)\n\
             -->\n   (<s> ^result r{i})}}\n"
        );
    }
    s
}

/// The working-memory setup, as commands (the official kernel gets the same text).
const SETUP: &str =
    "wm add S1 task *\nwm add I4 name task-0\nwm add S1 other *\nwm add I4 step *\n";

#[derive(Clone, Copy)]
enum Change {
    Noise,
    StepFail,
    StepPartial,
    ValueFail,
    KindPartial,
}

const CHANGES: [Change; 5] = [
    Change::Noise,
    Change::StepFail,
    Change::StepPartial,
    Change::ValueFail,
    Change::KindPartial,
];

impl Change {
    fn name(self) -> &'static str {
        match self {
            Change::Noise => "noise",
            Change::StepFail => "step-fail",
            Change::StepPartial => "step-partial",
            Change::ValueFail => "value-fail",
            Change::KindPartial => "kind-partial",
        }
    }
    fn wme(self) -> &'static str {
        match self {
            Change::Noise => "(S1 ^noise x)",
            Change::StepFail => "(I5 ^step x)",
            Change::StepPartial => "(I4 ^step x)",
            Change::ValueFail => "(I5 ^value x)",
            Change::KindPartial => "(I6 ^kind |K0|)",
        }
    }
    fn command(self) -> &'static str {
        match self {
            Change::Noise => "wm add S1 noise x",
            Change::StepFail => "wm add I5 step x",
            Change::StepPartial => "wm add I4 step x",
            Change::ValueFail => "wm add I5 value x",
            Change::KindPartial => "wm add I6 kind |K0|",
        }
    }
}

struct Setup {
    it: Interpreter,
    rules: usize,
    load_secs: f64,
    /// VmRSS growth over the load, and the text's size (which the source map keeps).
    load_rss: u64,
    text_bytes: usize,
    /// The first add+remove of each change after the load, through the command layer, in
    /// `CHANGES` order: one-time work (lazy unlinking) shows here.
    first_secs: Vec<f64>,
    triples: [(Sym, Sym, Sym); 5],
}

impl Setup {
    fn build(n: usize) -> Setup {
        let rules = scaled(n);
        let text = nomatch(rules);
        // Small loads are timed as the median of LOADS_SMALL fresh loads (the last one is
        // kept); 100,000 rules once (divan's `load_100k` times it again).
        let loads = if n <= 10_000 { LOADS_SMALL } else { 1 };
        let mut times = Vec::with_capacity(loads);
        let (mut it, mut load_rss) = (Interpreter::new(), 0);
        for _ in 0..loads {
            it = Interpreter::new();
            let rss0 = rss_bytes();
            let t = Instant::now();
            if let Err(d) = it.run_text(&format!("nomatch-{rules}.soar"), &text) {
                panic!(
                    "the generated rules failed to load: {}",
                    it.sources.render(&d)
                );
            }
            times.push(t.elapsed().as_secs_f64());
            load_rss = rss_bytes().saturating_sub(rss0);
        }
        times.sort_by(f64::total_cmp);
        let load_secs = times[times.len() / 2];
        assert_eq!(it.agent.production_count(), rules, "every rule loads");
        if let Err(d) = it.run_text("setup", SETUP) {
            panic!("setup failed: {}", it.sources.render(&d));
        }
        it.take_output();
        let agent = &mut it.agent;
        let id = |name: &str| {
            agent
                .symbols
                .find_id(name)
                .unwrap_or_else(|| panic!("`wm add ... *` made no {name}"))
        };
        let (s1, i4, i5, i6) = (id("S1"), id("I4"), id("I5"), id("I6"));
        let [noise, step, value, kind, x, k0] =
            ["noise", "step", "value", "kind", "x", "K0"].map(|w| agent.symbols.str(w));
        let mut s = Setup {
            it,
            rules,
            load_secs,
            load_rss,
            text_bytes: text.len(),
            first_secs: Vec::new(),
            triples: [
                (s1, noise, x),
                (i5, step, x),
                (i4, step, x),
                (i5, value, x),
                (i6, kind, k0),
            ],
        };
        for c in CHANGES {
            let t = Instant::now();
            s.cmd_pair(c);
            s.first_secs.push(t.elapsed().as_secs_f64());
        }
        s
    }

    /// One change through the API: add the WME, then remove it.
    fn api_pair(&mut self, c: Change) {
        let (i, a, v) = self.triples[c as usize];
        let w = self.it.agent.add_wme(i, a, v, false);
        self.it.agent.remove_wme(w);
    }

    /// One change through the command layer, as the official kernel's `ExecuteCommandLine`.
    fn cmd_pair(&mut self, c: Change) {
        self.it.run_text("bench", c.command()).expect("wm add runs");
        let out = self.it.take_output();
        let tt = out
            .trim()
            .strip_prefix("Timetag: ")
            .unwrap_or_else(|| panic!("unexpected wm add output {out:?}"));
        self.it
            .run_text("bench", &format!("wm remove {tt}"))
            .expect("wm remove runs");
        divan::black_box(self.it.take_output());
    }

    fn echo(&mut self) {
        self.it.run_text("bench", "echo x").expect("echo runs");
        divan::black_box(self.it.take_output());
    }
}

fn setup(n: usize) -> Rc<RefCell<Setup>> {
    if let Some(s) = LOADED.with(|l| l.borrow().get(&n).cloned()) {
        return s;
    }
    let s = Rc::new(RefCell::new(Setup::build(n)));
    LOADED.with(|l| l.borrow_mut().insert(n, s.clone()));
    s
}

/// Resident set size now, from `/proc/self/status` (0 where there is none).
fn rss_bytes() -> u64 {
    status_kb("VmRSS:") * 1024
}

/// Minor page faults of this process so far (field 10 of `/proc/self/stat`).
fn minor_faults() -> u64 {
    std::fs::read_to_string("/proc/self/stat")
        .ok()
        .and_then(|s| {
            let after = s.rsplit_once(')')?.1;
            after.split_whitespace().nth(7)?.parse().ok()
        })
        .unwrap_or(0)
}

fn status_kb(field: &str) -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with(field))
                .and_then(|l| l.split_whitespace().nth(1))
                .and_then(|v| v.parse().ok())
        })
        .unwrap_or(0)
}

/// Median time per call over `batches` batches of `per_batch` calls, after a warm-up.
fn median_ns(batches: usize, per_batch: usize, mut f: impl FnMut()) -> f64 {
    for _ in 0..per_batch / 10 {
        f();
    }
    let mut v: Vec<f64> = (0..batches)
        .map(|_| {
            let t = Instant::now();
            for _ in 0..per_batch {
                f();
            }
            t.elapsed().as_nanos() as f64 / per_batch as f64
        })
        .collect();
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Median time per call at each of `SIZES`: `rounds` rounds, each timing one batch of
/// `per_batch` calls on every size in turn, so that a burst of load elsewhere on the machine
/// hits all sizes alike. A warm-up of a tenth of a batch per size comes first.
fn interleaved_ns(rounds: usize, per_batch: usize, mut f: impl FnMut(&mut Setup)) -> Vec<f64> {
    let setups: Vec<_> = SIZES.iter().map(|&n| setup(n)).collect();
    for s in &setups {
        let mut s = s.borrow_mut();
        for _ in 0..per_batch / 10 {
            f(&mut s);
        }
    }
    let mut times = vec![Vec::with_capacity(rounds); setups.len()];
    for _ in 0..rounds {
        for (i, s) in setups.iter().enumerate() {
            let mut s = s.borrow_mut();
            let t = Instant::now();
            for _ in 0..per_batch {
                f(&mut s);
            }
            times[i].push(t.elapsed().as_nanos() as f64 / per_batch as f64);
        }
    }
    times
        .into_iter()
        .map(|mut v| {
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        })
        .collect()
}

// ------------------------------------------------------------------------- divan

#[divan::bench(args = SIZES)]
fn api_noise(bencher: divan::Bencher, n: usize) {
    let s = setup(n);
    let mut s = s.borrow_mut();
    bencher.bench_local(|| s.api_pair(Change::Noise));
}

#[divan::bench(args = SIZES)]
fn api_step_fail(bencher: divan::Bencher, n: usize) {
    let s = setup(n);
    let mut s = s.borrow_mut();
    bencher.bench_local(|| s.api_pair(Change::StepFail));
}

#[divan::bench(args = SIZES)]
fn api_step_partial(bencher: divan::Bencher, n: usize) {
    let s = setup(n);
    let mut s = s.borrow_mut();
    bencher.bench_local(|| s.api_pair(Change::StepPartial));
}

#[divan::bench(args = SIZES)]
fn api_value_fail(bencher: divan::Bencher, n: usize) {
    let s = setup(n);
    let mut s = s.borrow_mut();
    bencher.bench_local(|| s.api_pair(Change::ValueFail));
}

#[divan::bench(args = SIZES)]
fn api_kind_partial(bencher: divan::Bencher, n: usize) {
    let s = setup(n);
    let mut s = s.borrow_mut();
    bencher.bench_local(|| s.api_pair(Change::KindPartial));
}

#[divan::bench(args = SIZES, sample_count = 30)]
fn cmd_noise(bencher: divan::Bencher, n: usize) {
    let s = setup(n);
    let mut s = s.borrow_mut();
    bencher.bench_local(|| s.cmd_pair(Change::Noise));
}

/// Adding 100,000 generated productions through the `sp` path (the interpreter is dropped
/// outside the timing).
#[divan::bench(sample_count = 3, sample_size = 1)]
fn load_100k(bencher: divan::Bencher) {
    let n = scaled(100_000);
    let text = nomatch(n);
    bencher
        .counter(divan::counter::ItemsCount::new(n))
        .bench_local(|| {
            let mut it = Interpreter::new();
            it.run_text("nomatch.soar", &text).expect("rules load");
            it
        });
}

// ------------------------------------------------------------------------- the table

/// Set in a child process (this program again) that measures memory in a fresh process:
/// `rules`, `noise` or `step` (see `memory_child`).
const CHILD: &str = "RETE_BENCH_MEMORY";

fn main() {
    // `cargo bench` passes `--bench`; under `cargo test --benches` the sizes shrink and
    // divan runs each benchmark once.
    let full = std::env::args().any(|a| a == "--bench");
    if full {
        SCALE.with(|s| s.set(1));
    }
    if let Ok(key) = std::env::var(CHILD) {
        println!("{}", memory_child(&key));
        return;
    }
    if full {
        table();
    }
    divan::main();
}

/// In a fresh process: VmRSS growth per production over loading 100,000 rules (`rules`), or
/// per WME over 1,000,000 WMEs `(S1 ^noise <int>)` (`noise`) or `(I5 ^step <int>)` (`step`)
/// added to an agent with 1,000 rules, the values interned first.
fn memory_child(key: &str) -> f64 {
    if key == "rules" {
        let n = scaled(100_000);
        let text = nomatch(n);
        let mut it = Interpreter::new();
        let rss0 = rss_bytes();
        it.run_text("nomatch.soar", &text).expect("rules load");
        return rss_bytes().saturating_sub(rss0) as f64 / n as f64;
    }
    let mut it = Interpreter::new();
    it.run_text("nomatch-1000.soar", &nomatch(scaled(1_000)))
        .expect("rules load");
    it.run_text("setup", SETUP).expect("setup runs");
    let a = &mut it.agent;
    let count = scaled(1_000_000);
    let id = a
        .symbols
        .find_id(if key == "noise" { "S1" } else { "I5" })
        .expect("S1 and I5 exist");
    let attr = a.symbols.str(key);
    // The values are interned first: the figures are for WMEs, not symbols.
    let values: Vec<Sym> = (0..count as i64).map(|i| a.symbols.int(i)).collect();
    let rss0 = rss_bytes();
    for &v in &values {
        a.add_wme(id, attr, v, false);
    }
    rss_bytes().saturating_sub(rss0) as f64 / count as f64
}

/// Runs `memory_child(key)` in a child process with mimalloc's purge delay at 0, so that
/// freed memory (old buffers of grown vectors and tables, parser temporaries) leaves the
/// resident set at once and the growth counts live bytes only.
fn memory_in_child(key: &str) -> f64 {
    let exe = std::env::current_exe().expect("the bench's own path");
    let out = std::process::Command::new(exe)
        .args(std::env::args().skip(1))
        .env(CHILD, key)
        .env("MIMALLOC_PURGE_DELAY", "0")
        .output()
        .expect("the child process runs");
    String::from_utf8_lossy(&out.stdout)
        .trim()
        .parse()
        .unwrap_or(f64::NAN)
}

fn table() {
    let mut json: Vec<(String, f64)> = Vec::new();
    if let Ok(dir) = std::env::var("RETE_BENCH_DUMP") {
        for n in SIZES {
            let path = std::path::Path::new(&dir).join(format!("nomatch-{n}.soar"));
            std::fs::write(&path, nomatch(n)).expect("RETE_BENCH_DUMP is writable");
        }
    }
    println!("rete bench: {} cores, one run", cores());
    println!("\n== loading `nomatch` rules through the sp path (run_text of the whole text) ==");
    println!(
        "(1k and 10k: median of {LOADS_SMALL} loads; 100k: one load, the first of this process)"
    );
    println!(
        "{:>8} {:>9} {:>12} {:>11} {:>8} {:>10} {:>13}",
        "rules", "load s", "rules/s", "beta nodes", "amems", "RSS MB", "RSS B/rule*"
    );
    // Largest first, so that its RSS delta starts from a near-empty process.
    for n in SIZES.iter().rev() {
        let s = setup(*n);
        let s = s.borrow();
        let (beta, amems) = s.it.agent.rete.node_count();
        println!(
            "{:>8} {:>9.3} {:>12.0} {:>11} {:>8} {:>10.1} {:>13.0}",
            s.rules,
            s.load_secs,
            s.rules as f64 / s.load_secs,
            beta,
            amems,
            s.load_rss as f64 / 1e6,
            s.load_rss as f64 / s.rules as f64,
        );
        json.push((format!("load_s.{n}"), s.load_secs));
        json.push((format!("load_rss_bytes.{n}"), s.load_rss as f64));
    }
    {
        let s = setup(100_000);
        let s = s.borrow();
        let per = s.load_rss as f64 / s.rules as f64;
        let text = s.text_bytes as f64 / s.rules as f64;
        let live = memory_in_child("rules");
        println!(
            "* VmRSS growth over the (last) load; below 100,000 rules it is within the \
             allocator's noise.\n  At 100,000 rules: {per:.0} B per production here; \
             {live:.0} B in a fresh process with freed memory purged at once (live bytes), \
             of which\n  {text:.0} B is the rule's source text (kept by the source map)",
        );
        json.push(("mem_live_bytes_per_production".into(), live));
        json.push(("mem_bytes_per_production".into(), per));
        json.push(("mem_text_bytes_per_production".into(), text));
    }

    println!(
        "\n== the first add+remove of each change after the load (command layer, once, in \
         this order) =="
    );
    println!(
        "{:<13} {:<20} {:>10} {:>10} {:>10}",
        "change", "command", "1k us", "10k us", "100k us"
    );
    for (i, c) in CHANGES.iter().enumerate() {
        let row: Vec<f64> = SIZES
            .iter()
            .map(|&n| setup(n).borrow().first_secs[i] * 1e6)
            .collect();
        for (n, us) in SIZES.iter().zip(&row) {
            json.push((format!("first_us.{}.{n}", c.name()), *us));
        }
        println!(
            "{:<13} {:<20} {:>10.1} {:>10.1} {:>10.1}",
            c.name(),
            c.command(),
            row[0],
            row[1],
            row[2]
        );
    }

    println!("\n== one WME added then removed: API (Agent::add_wme + remove_wme) ==");
    println!(
        "{:<13} {:<16} {:>10} {:>10} {:>10} {:>9} {:>12}",
        "change", "WME", "1k ns", "10k ns", "100k ns", "100k/1k", "R/L acts"
    );
    for c in CHANGES {
        let row = interleaved_ns(API_ROUNDS, 20_000, |s| s.api_pair(c));
        let s = setup(100_000);
        let mut s = s.borrow_mut();
        let r = &s.it.agent.rete;
        let (r0, l0) = (r.right_activations, r.left_activations);
        s.api_pair(c);
        let r = &s.it.agent.rete;
        let acts = (r.right_activations - r0, r.left_activations - l0);
        drop(s);
        for n in SIZES {
            assert!(
                setup(n).borrow().it.agent.matches.assertions.is_empty(),
                "no rule may match {}",
                c.wme()
            );
        }
        for (n, ns) in SIZES.iter().zip(&row) {
            json.push((format!("api_ns.{}.{n}", c.name()), *ns));
        }
        println!(
            "{:<13} {:<16} {:>10.0} {:>10.0} {:>10.0} {:>8.2}x {:>12}",
            c.name(),
            c.wme(),
            row[0],
            row[1],
            row[2],
            row[2] / row[0],
            format!("{}/{}", acts.0, acts.1),
        );
        json.push((format!("api_ratio_100k_1k.{}", c.name()), row[2] / row[0]));
    }
    println!("(R/L acts: right and left activations counted for one pair at 100,000 rules)");

    println!(
        "\n== the same through the command layer: run_text(\"wm add ...\") + \"wm remove <tt>\" =="
    );
    println!(
        "{:<13} {:<20} {:>8} {:>8} {:>8} {:>8} {:>17}",
        "change", "command", "1k us", "10k us", "100k us", "100k/1k", "kept B/pair"
    );
    for c in CHANGES {
        let (rss0, flt0) = (rss_bytes(), minor_faults());
        let row: Vec<f64> = interleaved_ns(CMD_ROUNDS, 2_000, |s| s.cmd_pair(c))
            .into_iter()
            .map(|ns| ns / 1e3)
            .collect();
        let calls = (SIZES.len() * (CMD_ROUNDS * 2_000 + 2_000 / 10)) as f64;
        let kept = rss_bytes().saturating_sub(rss0) as f64 / calls;
        let faults = (minor_faults() - flt0) as f64 / calls;
        for (n, us) in SIZES.iter().zip(&row) {
            json.push((format!("cmd_us.{}.{n}", c.name()), *us));
        }
        println!(
            "{:<13} {:<20} {:>8.2} {:>8.2} {:>8.2} {:>7.2}x {:>17}",
            c.name(),
            c.command(),
            row[0],
            row[1],
            row[2],
            row[2] / row[0],
            format!("{kept:.0} ({faults:.3} flt)"),
        );
    }
    println!(
        "(kept B/pair: VmRSS growth per pair and minor page faults per pair, all sizes \
         together;\n run_text registers each text in the source map for good)"
    );
    let echo = {
        let s = setup(1_000);
        let mut s = s.borrow_mut();
        median_ns(7, 10_000, || s.echo()) / 1e3
    };
    json.push(("cmd_us.echo".into(), echo));
    println!("(baseline: run_text(\"echo x\") + take_output: {echo:.2} us per call)");

    println!(
        "\n== memory per WME (VmRSS growth over 1,000,000 WMEs, 1,000 rules loaded, in a fresh \
         process, freed memory purged at once) =="
    );
    for (key, label) in [
        ("noise", "(S1 ^noise <int>): no alpha memory"),
        ("step", "(I5 ^step <int>): in (* ^step *)"),
    ] {
        let per = memory_in_child(key);
        println!("{label:<40} {per:>6.0} B per WME");
        json.push((format!("mem_bytes_per_wme.{key}"), per));
    }
    println!(
        "peak RSS of this process so far: {} MB",
        status_kb("VmHWM:") / 1024
    );
    println!("\n(divan's statistics follow; ns figures are per add+remove pair)\n");

    if let Ok(path) = std::env::var("RETE_BENCH_JSON") {
        let body: Vec<String> = json
            .iter()
            .map(|(k, v)| format!("  \"{k}\": {v}"))
            .collect();
        std::fs::write(&path, format!("{{\n{}\n}}\n", body.join(",\n")))
            .expect("RETE_BENCH_JSON is writable");
    }
}

fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}
