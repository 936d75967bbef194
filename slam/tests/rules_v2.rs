//! Rules v2 (`rules/v2/`) and its oracle in the closed loop: they load, build a map of the
//! room's walls, correct the pose, beat dead reckoning, and repeat themselves byte for byte.

use soar_slam::experiment::{parse_options, v2_rules_dir};
use soar_slam::method::Method;
use soar_slam::soar_loop::{self, default_rules_dir, true_map, LoopConfig, Outcome};
use soar_slam::variant::{Ablation, Constants, Drift, Variant};
use soar_slam::World;

fn v2_config(seed: u64, duration_s: f64, oracle: bool) -> LoopConfig {
    let mut cfg = LoopConfig::new(World::empty_room(), seed, true, duration_s);
    cfg.rules_dir = v2_rules_dir(&default_rules_dir());
    cfg.ablation = Ablation::new(Drift::Stage, &[Variant::Tenths], Constants::default()).unwrap();
    cfg.oracle = oracle;
    cfg
}

#[test]
fn rules_v2_map_the_room_and_correct_the_pose() {
    let cfg = v2_config(101, 120.0, false);
    let a = soar_loop::run(&cfg);
    assert_eq!(a.outcome, Outcome::Completed, "{:?}", a.stats.messages);
    assert!(a.stats.messages.is_empty(), "{:?}", a.stats.messages);
    assert!(
        a.stats.bad_commands.is_empty(),
        "{:?}",
        a.stats.bad_commands
    );
    assert!(!a.stats.corrections.is_empty());
    let walls = a.memory_walls.len();
    assert!((2..=6).contains(&walls), "{walls} walls");
    // Every map wall lies at a right angle of the map's axes.
    let axis = a.memory_walls[0].th.rem_euclid(90.0);
    for w in &a.memory_walls {
        let d = (w.th - axis).rem_euclid(90.0);
        assert!(d.min(90.0 - d) < 1e-6, "{w:?}");
    }
    let mut off = cfg.clone();
    off.slam = false;
    off.expire_after = Some(8);
    let dr = soar_loop::run(&off);
    let last = |r: &soar_loop::RunResult| r.steps.last().map_or(f64::NAN, |s| s.pos_err_mm);
    assert!(
        last(&a) < last(&dr),
        "v2 {} mm, dead reckoning {} mm",
        last(&a),
        last(&dr)
    );
    let b = soar_loop::run(&cfg);
    assert_eq!(a.csv(), b.csv());
}

#[test]
fn the_oracle_loads_the_true_walls_and_never_adds_one() {
    let truth = true_map(&World::empty_room());
    let mut rs: Vec<(i64, i64)> = truth
        .iter()
        .map(|w| (w.r.round() as i64, w.th.round() as i64))
        .collect();
    rs.sort();
    assert_eq!(rs, [(3000, 90), (3000, 270), (4000, 0), (4000, 180)]);
    let r = soar_loop::run(&v2_config(102, 60.0, true));
    assert_eq!(r.outcome, Outcome::Completed, "{:?}", r.stats.messages);
    assert_eq!(r.memory_walls.len(), 4);
    assert!(!r.stats.corrections.is_empty());
}

#[test]
fn method_accepts_the_new_methods_and_rejects_unknown_ones() {
    let args = |a: &[&str]| -> Vec<String> { a.iter().map(|s| s.to_string()).collect() };
    let o = parse_options(&args(&["--method", "dr,v2", "--method", "oracle"])).unwrap();
    assert_eq!(o.methods, [Method::Dr, Method::V2, Method::Oracle]);
    assert!(parse_options(&args(&["--method", "v3"])).is_err());
    // `--rules rules/v2` runs rules v2 with and without SLAM, angles in tenths.
    let dir = v2_rules_dir(&default_rules_dir()).display().to_string();
    let o = parse_options(&args(&["--rules", &dir])).unwrap();
    assert_eq!(o.methods, [Method::Thesis]);
    assert!(o.ablation.has(Variant::Tenths));
}

#[test]
fn the_default_comparison_repeats_byte_for_byte() {
    let base = std::env::temp_dir().join(format!("rusoar-compare-{}", std::process::id()));
    let run = |name: &str| {
        let dir = base.join(name);
        let args: Vec<String> = ["--seeds", "2", "--duration", "30", "--jobs", "2", "--out"]
            .iter()
            .map(|s| s.to_string())
            .chain([dir.display().to_string()])
            .collect();
        let opts = parse_options(&args).unwrap();
        soar_slam::experiment::run_comparison(&opts, false).unwrap();
        dir
    };
    let (a, b) = (run("a"), run("b"));
    for f in [
        "comparison.md",
        "comparison.csv",
        "fig-compare.svg",
        "fig-compare-diff.svg",
        "fig-compare-heading.png",
        "thesis/steps-on-1.csv",
        "thesis/ekf.md",
        "v2/steps-on-2.csv",
        "v2/map-on-1.csv",
        "oracle/believed-on-1.tum",
    ] {
        let (x, y) = (std::fs::read(a.join(f)), std::fs::read(b.join(f)));
        assert!(x.is_ok(), "{f} missing");
        assert!(x.ok() == y.ok(), "{f} differs between two runs");
    }
    assert!(
        !a.join("thesis/summary.md").exists(),
        "no wall-clock times in a comparison"
    );
    let md = std::fs::read_to_string(a.join("comparison.md")).unwrap();
    for label in [
        "dead reckoning",
        "thesis rules",
        "rules v2",
        "EKF",
        "oracle",
    ] {
        assert!(md.contains(label), "{label} missing from comparison.md");
    }
    let _ = std::fs::remove_dir_all(&base);
}
