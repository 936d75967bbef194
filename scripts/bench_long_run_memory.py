#!/usr/bin/env python3
"""Whether a long run's memory stays flat once its working memory is flat, in both kernels:
each agent runs D decisions and then, in a fresh process, ten times as many, and the peak
resident memory of each process is compared. The growth per decision is
(peak at 10·D − peak at D) ÷ 9·D; an agent whose working memory stays the same size should
show none (the official kernel frees what a run stops using: identifiers, numbers and
strings that nothing refers to any more).

rusoar runs as its command-line binary (`target/release/rusoar`, commands on standard
input); the official Soar 9.6 kernel (pip package soar-sml) in a Python process. Each
process does `srand 1`, `watch 0`, `source FILE`, `run D`, and the `stats` WM size is shown so
that a growing working memory can be told apart from a growing kernel.

usage: python3 scripts/bench_long_run_memory.py [--decisions D] [AGENT ...]
  AGENT: a file in benches/agents/ without `.soar` (default: count-deep arithmetic wait)
"""
import argparse
import os
import re
import resource
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RUSOAR = os.path.join(ROOT, "target", "release", "rusoar")
OFFICIAL = """\
import sys, soar_sml
k = soar_sml.Kernel.CreateKernelInCurrentThread(True, 0)
a = k.CreateAgent("soar")
for c in ["srand 1", "watch 0", "source {%s}" % sys.argv[1], "run " + sys.argv[2]]:
    a.ExecuteCommandLine(c)
print(a.ExecuteCommandLine("stats"))
k.Shutdown()
"""
WM_SIZE = re.compile(r"WM size: (\d+) current")


def peak_kb(argv, stdin=None):
    """Runs one process; returns (its peak resident memory in KB, its output)."""
    # ru_maxrss of RUSAGE_CHILDREN is the largest child's so far: each measurement runs
    # in a child of its own, started from a fresh interpreter.
    probe = ("import resource, subprocess, sys\n"
             "r = subprocess.run(sys.argv[1:], input=sys.stdin.read(), capture_output=True,"
             " text=True)\n"
             "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)\n"
             "print(r.stdout)\n")
    out = subprocess.run([sys.executable, "-c", probe] + argv, input=stdin or "",
                         capture_output=True, text=True, check=True).stdout
    first, _, rest = out.partition("\n")
    return int(first), rest


def rusoar(path, decisions):
    cmds = "srand 1\nwatch 0\nsource {%s}\nrun %d\nstats\nexit\n" % (path, decisions)
    return peak_kb([RUSOAR], cmds)


def official(path, decisions):
    return peak_kb([sys.executable, "-c", OFFICIAL, path, str(decisions)])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--decisions", type=int, default=25000)
    ap.add_argument("agents", nargs="*", default=["count-deep", "arithmetic", "wait"])
    args = ap.parse_args()
    if not os.path.exists(RUSOAR):
        raise SystemExit("build rusoar first: cargo build --release")
    d = args.decisions
    print("| agent | kernel | peak at %d decisions | at %d | WM size at the end | growth a decision |"
          % (d, 10 * d))
    print("|---|---|---|---|---|---|")
    for name in args.agents:
        path = os.path.join(ROOT, "benches", "agents", name + ".soar")
        for kernel, run in (("official", official), ("rusoar", rusoar)):
            small, _ = run(path, d)
            large, out = run(path, 10 * d)
            wm = WM_SIZE.search(out)
            growth = (large - small) * 1024 / (9 * d)
            print("| %s | %s | %.1f MB | %.1f MB | %s | %.0f bytes |"
                  % (name, kernel, small / 1024, large / 1024, wm.group(1) if wm else "?",
                     growth))


if __name__ == "__main__":
    main()
