#!/usr/bin/env python3
"""Decision-cycle speed, side by side: every agent of tests/agents run in the official Soar
9.6 kernel (pip package soar-sml) and in rusoar with the conformance settings (srand 1,
watch 0, run 1000), reporting decisions, firings and decisions per second for each, and
the ratio rusoar / official (above 1: rusoar is faster). One run per agent and kernel, the
median of REPEAT timings; these machines are noisy, so the two kernels take turns: ROUNDS
rounds, each timing every agent in the official kernel and then in rusoar, and each
kernel's figure is the median over the rounds.

Official: `run 1000` timed around ExecuteCommandLine in a fresh agent after `source`.
rusoar:   examples/time_run.rs, in-process: `run 1000` timed in a fresh interpreter after
          the same setup.

usage: python3 scripts/bench_decisions.py [--repeat N] [--rounds R] [AGENT ...]
"""
import argparse
import os
import statistics
import subprocess

from bench_common import ROOT, official
AGENTS = os.path.join(ROOT, "tests", "agents")


def ours_all(paths, repeat):
    out = subprocess.run(
        ["cargo", "run", "--release", "--quiet", "-p", "rusoar-cli", "--example", "time_run", "--", str(repeat)]
        + paths,
        capture_output=True, text=True, cwd=ROOT, check=True).stdout
    res = {}
    for line in out.splitlines():
        name, dec, fir, secs = line.split()
        res[name] = (max(float(secs), 1e-9), int(dec), int(fir))
    return res


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("agents", nargs="*")
    opts = ap.parse_args()
    names = opts.agents or sorted(f[:-5] for f in os.listdir(AGENTS) if f.endswith(".soar"))
    print("| agent | decisions (ours / 9.6) | rusoar dec/s | official dec/s | ratio |")
    print("|---|---|---|---|---|")
    ratios = []
    paths = [os.path.join(AGENTS, n + ".soar") for n in names]
    off_times = {n: [] for n in names}
    our_times = {n: [] for n in names}
    counts = {}
    for _ in range(max(1, opts.rounds)):
        for name, path in zip(names, paths):
            ot, od, _ = official(path, 1000, opts.repeat)
            off_times[name].append(ot)
            counts[name] = od
        mine = ours_all(paths, opts.repeat)
        for name in names:
            our_times[name].append(mine[name][0])
            counts[name] = (mine[name][1], counts[name])
    for name in names:
        rd, od = counts[name]
        rt = statistics.median(our_times[name])
        ot = statistics.median(off_times[name])
        ours_rate, off_rate = rd / rt, od / ot
        ratio = ours_rate / off_rate
        ratios.append(ratio)
        print(f"| {name} | {rd} / {od} | {ours_rate:,.0f} | {off_rate:,.0f} | {ratio:.1f} |")
    print(f"\nmedian ratio {statistics.median(ratios):.1f}, min {min(ratios):.1f}")


if __name__ == "__main__":
    main()
