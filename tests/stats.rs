//! `stats` prints 9.6's report. The expected text below was observed on the official kernel
//! (soar_sml 9.6.5, through `ExecuteCommandLine`) for `srand 1`,
//! `source tests/agents/NAME.soar`, `run 1000`, `stats`, and pasted here. The first line
//! (host and date) and the times are not compared: each time (`N.NNN` in the table, the
//! single timers and before `msec/`) is masked as `#.###`; all counts and ratios are
//! compared.

mod common;

use common::mask_decimals;
use rusoar::Agent;
use std::path::PathBuf;

fn stats_after(commands: &[&str]) -> String {
    let mut interp = Agent::default();
    interp.set_working_directory(PathBuf::from(env!("CARGO_MANIFEST_DIR")));
    for c in commands {
        interp
            .source_text("<stats>", c)
            .unwrap_or_else(|d| panic!("`{c}` failed: {}", d.message()));
        interp.take_output();
    }
    interp.source_text("<stats>", "stats").expect("stats runs");
    interp.take_output()
}

fn stats_of(agent: &str) -> String {
    stats_after(&[
        "srand 1",
        &format!("source tests/agents/{agent}.soar"),
        "run 1000",
    ])
}

/// The text from the first count line (`N decisions`) on, times masked.
fn counts(stats: &str) -> String {
    let first = stats
        .lines()
        .position(|l| l.contains(" decisions ("))
        .unwrap_or_else(|| panic!("no count lines in {stats:?}"));
    let at = stats.lines().skip(first).collect::<Vec<_>>().join("\n");
    mask(&at)
}

/// Every `D.DDD` followed by ` msec/` or ` sec.`, and every `D.DDD` on a line of the
/// timing table, becomes `#.###`.
fn mask(text: &str) -> String {
    text.split('\n')
        .map(|line| {
            let table = line.contains('|') || line.contains("CPU Time:");
            mask_decimals(line, |after| table || after.starts_with(" msec/"))
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// Observed on the official kernel (see the module comment), count lines only.
const OFFICIAL_COUNTS: &[(&str, &str)] = &[
    (
        "water-jug",
        "306 decisions (0.042 msec/decision)
1104 elaboration cycles (3.608 ec's per dc, 0.012 msec/ec)
1104 inner elaboration cycles
306 p-elaboration cycles (1.000 pe's per dc, 0.042 msec/pe)
2335 production firings (2.115 pf's per ec, 0.005 msec/pf)
7633 wme changes (3835 additions, 3798 removals)
WM size: 37 current, 33.751 mean, 38 maximum
",
    ),
    (
        "halt",
        "5 decisions (0.017 msec/decision)
11 elaboration cycles (2.200 ec's per dc, 0.008 msec/ec)
11 inner elaboration cycles
5 p-elaboration cycles (1.000 pe's per dc, 0.017 msec/pe)
13 production firings (1.182 pf's per ec, 0.007 msec/pf)
60 wme changes (41 additions, 19 removals)
WM size: 22 current, 17.917 mean, 22 maximum
",
    ),
    (
        "towers-of-hanoi",
        "128 decisions (0.041 msec/decision)
384 elaboration cycles (3.000 ec's per dc, 0.014 msec/ec)
384 inner elaboration cycles
128 p-elaboration cycles (1.000 pe's per dc, 0.041 msec/pe)
1346 production firings (3.505 pf's per ec, 0.004 msec/pf)
3662 wme changes (1865 additions, 1797 removals)
WM size: 68 current, 62.189 mean, 68 maximum
",
    ),
    (
        "impasse-tie",
        "7 decisions (0.027 msec/decision)
16 elaboration cycles (2.286 ec's per dc, 0.012 msec/ec)
16 inner elaboration cycles
4 p-elaboration cycles (0.571 pe's per dc, 0.047 msec/pe)
12 production firings (0.750 pf's per ec, 0.016 msec/pf)
110 wme changes (91 additions, 19 removals)
WM size: 72 current, 51.618 mean, 72 maximum
",
    ),
    (
        "gds",
        "7 decisions (0.023 msec/decision)
13 elaboration cycles (1.857 ec's per dc, 0.012 msec/ec)
13 inner elaboration cycles
5 p-elaboration cycles (0.714 pe's per dc, 0.032 msec/pe)
10 production firings (0.769 pf's per ec, 0.016 msec/pf)
87 wme changes (62 additions, 25 removals)
WM size: 37 current, 26.559 mean, 37 maximum
",
    ),
    (
        // A chunk's match fires at the lower goal in the same elaboration cycle, and 9.6
        // counts each pass of the waterfall over a goal as an inner elaboration cycle.
        "learn-lookahead",
        "6 decisions (0.105 msec/decision)
19 elaboration cycles (3.167 ec's per dc, 0.033 msec/ec)
21 inner elaboration cycles
4 p-elaboration cycles (0.667 pe's per dc, 0.158 msec/pe)
22 production firings (1.158 pf's per ec, 0.029 msec/pf)
188 wme changes (103 additions, 85 removals)
WM size: 18 current, 43.379 mean, 82 maximum
",
    ),
];

#[test]
fn counts_match_the_official_kernel() {
    for (agent, official) in OFFICIAL_COUNTS {
        let ours = counts(&stats_of(agent));
        assert_eq!(
            ours.trim_end(),
            mask(official).trim_end(),
            "stats counts of {agent}"
        );
    }
}

/// The official kernel's whole `stats` for water-jug (first line aside), as observed.
const OFFICIAL_WATER_JUG: &str = "
16 productions (0 default, 16 user, 0 chunks)
   + 0 justifications
                                                        |   Computed
Phases:      Input   Propose   Decide   Apply    Output |     Totals
========================================================|===========
Kernel:      0.000    0.000    0.000    0.006    0.000  |      0.006
========================================================|===========
Input fn:    0.000                                      |      0.000
========================================================|===========
Outpt fn:                                        0.000  |      0.000
========================================================|===========
Callbcks:    0.000    0.000    0.000    0.000    0.000  |      0.000
========================================================|===========
Computed------------------------------------------------+-----------
Totals:      0.000    0.000    0.000    0.006    0.000  |      0.006

Values from single timers:
 Kernel CPU Time:       0.005 sec. 
 Total  CPU Time:       0.006 sec.

306 decisions (0.016 msec/decision)
1104 elaboration cycles (3.608 ec's per dc, 0.005 msec/ec)
1104 inner elaboration cycles
306 p-elaboration cycles (1.000 pe's per dc, 0.016 msec/pe)
2335 production firings (2.115 pf's per ec, 0.002 msec/pf)
7633 wme changes (3835 additions, 3798 removals)
WM size: 37 current, 33.751 mean, 38 maximum

";

#[test]
fn layout_is_the_official_kernels() {
    let ours = stats_of("water-jug");
    let (first, rest) = ours.split_once('\n').expect("more than one line");
    assert!(first.starts_with("Soar 9.6 (rusoar) on "), "{first}");
    assert!(first.contains(" at "), "{first}");
    assert_eq!(mask(rest), mask(OFFICIAL_WATER_JUG));
}

/// After init-soar the counts restart and the new top state's 13 WMEs count as additions;
/// with no phase run yet there is no WM sample (observed on the official kernel).
#[test]
fn init_soar_restarts_the_counts() {
    let ours = stats_after(&[
        "srand 1",
        "source tests/agents/halt.soar",
        "run 1000",
        "init-soar",
    ]);
    let expected = "0 decisions (0.000 msec/decision)
0 elaboration cycles (0.000 ec's per dc, 0.000 msec/ec)
0 inner elaboration cycles
0 p-elaboration cycles (0.000 pe's per dc, 0.000 msec/pe)
0 production firings (0.000 pf's per ec, 0.000 msec/pf)
13 wme changes (13 additions, 0 removals)
WM size: 13 current, 0.000 mean, 0 maximum";
    assert_eq!(counts(&ours).trim_end(), mask(expected));
}
