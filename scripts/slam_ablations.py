#!/usr/bin/env python3
"""Controls, ablations and a sweep of the constants of the Soar-SLAM thesis rules.

Runs `rusoar slam` once per configuration (SLAM on only, and dead reckoning once per drift
model), pairs the runs by seed, and writes a Markdown report that attributes the harm of the
thesis rules, in metres, to named causes:

- the zero-drift control (`--drift none`): with perfect odometry every error is the rules';
- each ablation (`--variant NAME`, rules/README.md section 6) against the thesis rules, same
  seeds: the paired difference of the position-error RMSE and of the error at the end;
- the correction logs (`corrections-on-<seed>.csv`): per rule, how many corrections moved the
  belief closer and their net effect; ChangeRobotPosition2 against a hidden wall; incidence;
- the sweep (`--what sweep`): the three constants the thesis does not give
  (r-tolerance 500 mm, th-tolerance 15 deg, overlap 50 %), one at a time.

Not run in CI (20 seeds x 600 s per configuration take minutes). Usage:

    cargo build --release
    python3 scripts/slam_ablations.py --what all --out /tmp/ablations \
        --report docs/slam/ablations.md

Each configuration goes to OUT/<drift>-<name>/; `--reuse` skips configurations whose
runs.csv is there already. The p-values are the exact two-sided Wilcoxon signed-rank test of
`rusoar slam` (zeros dropped, tied ranks averaged).
"""

import argparse
import csv
import os
import shlex
import subprocess
import sys

ABLATIONS = [
    ("thesis", []),
    ("h2-only", ["--variant", "h2-only"]),
    ("crp2-only", ["--variant", "crp2-only"]),
    ("nearest-wall", ["--variant", "nearest-wall"]),
    ("cone", ["--variant", "cone"]),
    ("wrap", ["--variant", "wrap"]),
    ("tenths", ["--variant", "tenths"]),
    ("all-fixes", ["--variant", "nearest-wall,cone,wrap,tenths"]),
]

CAUSES = {
    "h2-only": "ChangeRobotPosition2 as a whole (removed)",
    "crp2-only": "hypothesis 2's correction as a whole (removed)",
    "nearest-wall": "ChangeRobotPosition2 against walls hidden behind nearer ones",
    "cone": "getwalldistance's central ray against the sonar's cone",
    "wrap": "wall angles not wrapped at 0/360 deg",
    "tenths": "heading in whole degrees (rounded on every correction)",
    "all-fixes": "the four reconstruction faults together (nearest-wall, cone, wrap, tenths)",
}

SKIPPED = []

SWEEP = [
    ("r-tolerance", [125, 250, 1000]),
    ("th-tolerance", [5, 10, 30]),
    ("overlap", [25, 75, 90]),
]


def wilcoxon(diffs):
    """Exact two-sided Wilcoxon signed-rank p, as slam/src/stats.rs computes it."""
    d = [x for x in diffs if x == x and x != 0.0]
    n = len(d)
    if n == 0:
        return None
    order = sorted(range(n), key=lambda k: abs(d[k]))
    rank2 = [0] * n
    i = 0
    while i < n:
        j = i
        while j + 1 < n and abs(d[order[j + 1]]) == abs(d[order[i]]):
            j += 1
        for k in order[i:j + 1]:
            rank2[k] = i + j + 2
        i = j + 1
    w2 = sum(rank2[k] for k in range(n) if d[k] > 0)
    total = sum(rank2)
    dist = [0.0] * (total + 1)
    dist[0] = 1.0
    reach = 0
    for r in rank2:
        for s in range(reach, -1, -1):
            p = dist[s] * 0.5
            dist[s] = p
            dist[s + r] += p
        reach += r
    low = sum(dist[:w2 + 1])
    high = sum(dist[w2:])
    return min(1.0, 2.0 * min(low, high))


def fmt_p(p):
    if p is None:
        return "–"
    if p < 0.001:
        return "< 0.001"
    return f"{p:.3f}"


def p_is(p):
    t = fmt_p(p)
    return f"p {t}" if t.startswith("<") else f"p = {t}"


def median(v):
    v = sorted(v)
    if not v:
        return float("nan")
    m = len(v) // 2
    return v[m] if len(v) % 2 else (v[m - 1] + v[m]) / 2


def quantile(v, q):
    v = sorted(v)
    if not v:
        return float("nan")
    pos = q * (len(v) - 1)
    lo, hi = int(pos), min(int(pos) + 1, len(v) - 1)
    return v[lo] + (v[hi] - v[lo]) * (pos - lo)


def run(args, name, drift, extra, slam="on", seeds=None):
    seeds = seeds or args.seeds
    out = os.path.join(args.out, f"{drift}-{name}")
    cmd = [args.rusoar, "slam", "--seeds", str(seeds), "--first-seed",
           str(args.first_seed), "--duration", str(args.duration), "--slam", slam,
           "--drift", drift, "--out", out] + extra
    if args.jobs:
        cmd += ["--jobs", str(args.jobs)]
    shown = "rusoar " + " ".join(shlex.quote(c) for c in cmd[1:])
    done = os.path.isfile(os.path.join(out, "runs.csv"))
    if args.report_only and not done:
        print(f"not run, left out: {shown}", file=sys.stderr)
        SKIPPED.append(shown)
        return None
    if not ((args.reuse or args.report_only) and done):
        print(f"running: {shown}", file=sys.stderr)
        r = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        if r.returncode != 0:
            sys.exit(f"failed ({r.returncode}): {shown}\n{r.stderr[-2000:]}")
    return load(out, slam, shown, args.duration)


def load(out, slam, shown, duration):
    """Per seed: RMSE, error at 60 s, at 300 s and at the end (mm), and the corrections."""
    runs = {}
    with open(os.path.join(out, "runs.csv")) as f:
        for row in csv.DictReader(f):
            if row["slam"] != slam:
                continue
            if row["outcome"] != "completed":
                sys.exit(f"{out}: seed {row['seed']} did not complete")
            seed = int(row["seed"])
            at = errors_at(os.path.join(out, f"steps-{slam}-{seed}.csv"), [60.0, 300.0])
            corr = []
            cpath = os.path.join(out, f"corrections-on-{seed}.csv")
            if slam == "on" and os.path.isfile(cpath):
                with open(cpath) as cf:
                    corr = list(csv.DictReader(cf))
            runs[seed] = {
                "rmse": float(row["rmse_mm"]),
                "final": float(row["final_mm"]),
                "e60": at.get(60.0, float("nan")),
                "e300": at.get(300.0, float("nan")),
                "corr": corr,
            }
    return {"runs": runs, "cmd": shown, "duration": duration}


def errors_at(path, times):
    want = {round(t * 10): t for t in times}
    found = {}
    with open(path) as f:
        f.readline()
        for line in f:
            step = int(line.split(",", 1)[0])
            if step in want:
                found[want[step]] = float(line.split(",")[8])
    return found


def paired(a, b, key):
    """(median of b - a in metres, seeds where b is lower, n, p) over the common seeds."""
    seeds = sorted(set(a["runs"]) & set(b["runs"]))
    d = [(b["runs"][s][key] - a["runs"][s][key]) / 1000.0 for s in seeds]
    lower = sum(1 for x in d if x < 0)
    return median(d), lower, len(d), wilcoxon(d)


def m(v):
    return f"{v:+.2f}" if v == v else "–"


def band_m(cfg, key):
    v = [r[key] / 1000.0 for r in cfg["runs"].values()]
    return f"{median(v):.2f} [{quantile(v, 0.1):.2f}–{quantile(v, 0.9):.2f}]"


def correction_rows(cfg):
    """Per rule: count, share that moved the belief closer, net change of the error (m)."""
    rows = {}
    for r in cfg["runs"].values():
        for c in r["corr"]:
            key = c["rule"]
            if key == "crp2":
                key = "crp2, nearest wall" if c["nearest"] == "true" else "crp2, hidden wall"
            e = rows.setdefault(key, [0, 0, 0.0])
            delta = float(c["err_after_mm"]) - float(c["err_before_mm"])
            e[0] += 1
            e[1] += delta < 0
            e[2] += delta / 1000.0
    return rows


def incidence_rows(cfg):
    bins = [(0, 10), (10, 20), (20, 30), (30, 90.01)]
    rows = []
    for lo, hi in bins:
        n = helped = 0
        net = 0.0
        for r in cfg["runs"].values():
            for c in r["corr"]:
                if c["rule"] != "crp2" or not c["incidence_deg"]:
                    continue
                inc = float(c["incidence_deg"])
                if lo <= inc < hi:
                    delta = float(c["err_after_mm"]) - float(c["err_before_mm"])
                    n += 1
                    helped += delta < 0
                    net += delta / 1000.0
        rows.append((lo, min(hi, 90), n, helped, net))
    return rows


def report(args, res, sweep):
    L = []
    w = L.append
    w("# Soar-SLAM: why the thesis rules hurt\n")
    w("Generated by `scripts/slam_ablations.py` (do not edit by hand): "
      f"{args.seeds} seeds from {args.first_seed}, {args.duration} s each, world `empty-room`, "
      "`ideal` sonar. Every configuration runs the same seeds, so each row compares the same "
      "true paths, odometry biases and sonar readings; differences are paired by seed (median "
      "of the per-seed difference, in metres; negative = less error). p: exact two-sided "
      "Wilcoxon signed-rank test. The variants are described in "
      "[rules/README.md](../../rules/README.md#6-controls-and-ablations).\n")
    for drift in ["stage", "none"]:
        if ("thesis", drift) not in res:
            continue
        th = res[("thesis", drift)]
        dr = res[("off", drift)]
        title = ("Stage 2 drift (the thesis's setup)" if drift == "stage"
                 else "No drift (the control: perfect odometry)")
        w(f"## {title}\n")
        w("| rules | RMSE, m | at 60 s, m | at 300 s, m | at the end, m |")
        w("|---|---|---|---|---|")
        for name, cfg in [("dead reckoning (SLAM off)", dr), ("thesis rules", th)]:
            w(f"| {name} | {band_m(cfg, 'rmse')} | {band_m(cfg, 'e60')} | "
              f"{band_m(cfg, 'e300')} | {band_m(cfg, 'final')} |")
        w("")
        md, low, n, p = paired(dr, th, "rmse")
        mf, lowf, _, pf = paired(dr, th, "final")
        w(f"**Harm of the thesis rules** (thesis − dead reckoning, paired): RMSE {m(md)} m "
          f"(lower with the rules in {low} of {n} seeds, {p_is(p)}); error at the end "
          f"{m(mf)} m ({lowf} of {n} lower, {p_is(pf)}).\n")
        w("**Causes**: each row is one variant against the thesis rules, same seeds. A "
          "negative difference is harm the cause accounts for.\n")
        w("| cause | variant | RMSE, m | Δ RMSE, m | seeds better | p | Δ at the end, m | p | "
          "corrections |")
        w("|---|---|---|---|---|---|---|---|---|")
        for name, _ in ABLATIONS[1:]:
            cfg = res.get((name, drift))
            if cfg is None:
                continue
            md, low, n, p = paired(th, cfg, "rmse")
            mf, _, _, pf = paired(th, cfg, "final")
            nc = median([len(r["corr"]) for r in cfg["runs"].values()])
            w(f"| {CAUSES[name]} | `{name}` | {band_m(cfg, 'rmse')} | {m(md)} | {low} of {n} | "
              f"{fmt_p(p)} | {m(mf)} | {fmt_p(pf)} | {nc:.0f} |")
        w("")
        w("**The corrections of the thesis rules**, from the correction logs (all seeds): "
          "net = the sum over corrections of the position error just after minus just "
          "before, in metres.\n")
        w("| rule | corrections | moved the belief closer | net, m |")
        w("|---|---|---|---|")
        for key, (n, helped, net) in sorted(correction_rows(th).items()):
            w(f"| {key} | {n} | {100.0 * helped / max(n, 1):.0f} % | {net:+.1f} |")
        w("")
        w("ChangeRobotPosition2 by the angle between the sonar's axis and the wall's normal:\n")
        w("| incidence | corrections | moved the belief closer | net, m |")
        w("|---|---|---|---|")
        for lo, hi, n, helped, net in incidence_rows(th):
            w(f"| {lo}–{hi}° | {n} | {100.0 * helped / max(n, 1):.0f} % | {net:+.1f} |")
        w("")
    if sweep:
        th = res[("thesis", "stage")]
        w("## The constants the thesis does not give\n")
        n = args.sweep_seeds or args.seeds
        w("One constant at a time, the others at their `Elaborate.soar` values (r-tolerance "
          "500 mm, th-tolerance 15°, overlap 50 %), Stage drift, "
          f"seeds {args.first_seed}–{args.first_seed + n - 1}; against the thesis values on "
          "the same seeds, paired by seed.\n")
        w("| constant | value | RMSE, m | Δ RMSE, m | seeds better | p | Δ at the end, m | p |")
        w("|---|---|---|---|---|---|---|---|")
        for (const, value), cfg in sweep:
            md, low, n, p = paired(th, cfg, "rmse")
            mf, _, _, pf = paired(th, cfg, "final")
            w(f"| {const} | {value} | {band_m(cfg, 'rmse')} | {m(md)} | {low} of {n} | "
              f"{fmt_p(p)} | {m(mf)} | {fmt_p(pf)} |")
        w("")
    if SKIPPED:
        w("Not run for this report (left out above):\n")
        w("```sh")
        for c in SKIPPED:
            w(c.replace(args.out, "OUT"))
        w("```\n")
    w("## Commands\n")
    w(f"This report: `python3 scripts/slam_ablations.py {' '.join(sys.argv[1:])}`"
      .replace(args.out, "OUT") + ", after the runs below.\n")
    w("Each figure above comes from these runs (`rusoar` is `target/release/rusoar`):\n")
    w("```sh")
    for cfg in list(res.values()) + [c for _, c in sweep]:
        w(cfg["cmd"].replace(args.out, "OUT"))
    w("```")
    return "\n".join(L) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--rusoar", default="target/release/rusoar")
    ap.add_argument("--what", choices=["ablations", "sweep", "all"], default="all")
    ap.add_argument("--seeds", type=int, default=20)
    ap.add_argument("--first-seed", type=int, default=1)
    ap.add_argument("--duration", type=float, default=600)
    ap.add_argument("--drift", choices=["stage", "none", "both"], default="both")
    ap.add_argument("--jobs", type=int, default=0)
    ap.add_argument("--sweep-seeds", type=int, default=0,
                    help="seeds per sweep configuration (default: --seeds), the first of them")
    ap.add_argument("--out", default="slam-ablations")
    ap.add_argument("--report", help="write the Markdown report here (default: stdout)")
    ap.add_argument("--reuse", action="store_true", help="keep configurations already run")
    ap.add_argument("--report-only", action="store_true",
                    help="run nothing: report on the configurations already in --out")
    args = ap.parse_args()
    if args.seeds < 1 or args.duration <= 0:
        sys.exit("--seeds must be at least 1 and --duration positive")
    if not os.path.isfile(args.rusoar):
        sys.exit(f"{args.rusoar} not found: build it with `cargo build --release`")
    args.duration = int(args.duration) if args.duration == int(args.duration) else args.duration
    drifts = ["stage", "none"] if args.drift == "both" else [args.drift]
    res = {}
    for drift in drifts:
        off = run(args, "off", drift, [], slam="off")
        thesis = run(args, "thesis", drift, [])
        if off is None or thesis is None:
            continue
        res[("off", drift)] = off
        res[("thesis", drift)] = thesis
        if args.what in ("ablations", "all"):
            for name, extra in ABLATIONS[1:]:
                cfg = run(args, name, drift, extra)
                if cfg is not None:
                    res[(name, drift)] = cfg
    sweep = []
    if args.what in ("sweep", "all"):
        if ("thesis", "stage") not in res:
            res[("off", "stage")] = run(args, "off", "stage", [], slam="off")
            res[("thesis", "stage")] = run(args, "thesis", "stage", [])
        for const, values in SWEEP:
            for v in values:
                n = args.sweep_seeds or args.seeds
                tag = f"{const}-{v}" if n == args.seeds else f"{const}-{v}-{n}seeds"
                cfg = run(args, tag, "stage", [f"--{const}", str(v)], seeds=n)
                if cfg is not None:
                    sweep.append(((const, v), cfg))
    text = report(args, res, sweep)
    if args.report:
        with open(args.report, "w") as f:
            f.write(text)
    else:
        sys.stdout.write(text)


if __name__ == "__main__":
    main()
