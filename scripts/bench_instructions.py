#!/usr/bin/env python3
"""The decision cycle side by side in instructions, not seconds: each kernel runs the same
agent under `valgrind --tool=cachegrind --cache-sim=no`, which counts the instructions it
executes. Counts do not drift with the machine's load as timings do, so two builds (or the two
kernels) compare in one run, and a change's effect shows as a difference of a few tenths of a
percent.

For each agent, both kernels do `srand 1`, `watch 0`, `source FILE`, then `run D`; the same
commands with `run 0` give the cost of starting up and loading, which is subtracted. The
official Soar 9.6 kernel (pip package soar-sml) runs in a Python process; rusoar in
cli/examples/time_run.rs. Prints instructions per decision in each kernel and their ratio
(official / rusoar, above 1: rusoar executes fewer). Both kernels' decision and firing counts
must agree, or the row is marked.

usage: python3 scripts/bench_instructions.py [--max-decisions N] [--rusoar-only] [AGENT ...]
  AGENT: a name as scripts/bench_agents.py takes it (`arithmetic`, `long/factorization`,
         `water-jug`) or a path to a .soar file; default: the agents of benches/agents/
  --max-decisions N  run at most N decisions of each agent (valgrind runs 30-50x slower)
  --rusoar-only      skip the official kernel (to compare two builds of rusoar)
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

from bench_agents import agents
from bench_common import ROOT, time_run_binary

OFFICIAL = """\
import re, sys, soar_sml
k = soar_sml.Kernel.CreateKernelInCurrentThread(True, 0)
a = k.CreateAgent("soar")
for c in ["srand 1", "watch 0", "source {%s}" % sys.argv[1], "run " + sys.argv[2]]:
    a.ExecuteCommandLine(c)
stats = a.ExecuteCommandLine("stats")
print(re.search(r"(\\d+) decisions", stats).group(1),
      re.search(r"(\\d+) production firings", stats).group(1))
k.Shutdown()
"""


def instructions(argv):
    """(instructions, stdout) of one command under cachegrind."""
    with tempfile.NamedTemporaryFile(suffix=".cg") as out:
        r = subprocess.run(["valgrind", "--tool=cachegrind", "--cache-sim=no",
                            "--cachegrind-out-file=" + out.name] + argv,
                           capture_output=True, text=True, cwd=ROOT)
    m = re.search(r"I\s+refs:\s+([\d,]+)", r.stderr)
    if r.returncode != 0 or not m:
        raise SystemExit("%s failed:\n%s" % (" ".join(argv), r.stderr[-2000:]))
    return int(m.group(1).replace(",", "")), r.stdout


def ours(binary, path, decisions):
    """Instructions of rusoar's `run DECISIONS` (start-up and loading subtracted), with the
    decision and firing counts."""
    total, out = instructions([binary, "1", "%s@%d" % (path, decisions)])
    base, _ = instructions([binary, "1", "%s@0" % path])
    _, dec, fir, _ = out.split()
    return total - base, (int(dec), int(fir))


def official(script, path, decisions):
    """The same in the official kernel."""
    # The interpreter itself, not a launcher script (pyenv's shims are shell scripts).
    python = sys.executable
    total, out = instructions([python, script, path, str(decisions)])
    base, _ = instructions([python, script, path, "0"])
    dec, fir = out.split()
    return total - base, (int(dec), int(fir))


def pick(names):
    """(name, path, decisions) of the agents asked for."""
    known = agents()
    if not names:
        return [a for a in known if os.sep + "benches" + os.sep in a[1]]
    chosen = []
    for n in names:
        if n.endswith(".soar"):
            chosen.append((os.path.basename(n)[:-5], os.path.abspath(n), 1000))
            continue
        found = [a for a in known if a[0] == n]
        if not found:
            raise SystemExit("unknown agent %r" % n)
        chosen.extend(found)
    return chosen


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--max-decisions", type=int, default=0)
    ap.add_argument("--rusoar-only", action="store_true")
    ap.add_argument("agent", nargs="*")
    opts = ap.parse_args()
    binary = time_run_binary()
    with tempfile.NamedTemporaryFile("w", suffix=".py", delete=False) as f:
        f.write(OFFICIAL)
        script = f.name
    try:
        print("| agent | decisions | rusoar instr/decision | official instr/decision | ratio |")
        print("|---|---|---|---|---|")
        for name, path, decisions in pick(opts.agent):
            if opts.max_decisions:
                decisions = min(decisions, opts.max_decisions)
            ours_n, ours_counts = ours(binary, path, decisions)
            row = "| %s | %d | %s |" % (name, decisions, "{:,.0f}".format(ours_n / decisions))
            if opts.rusoar_only:
                print(row + " | |", flush=True)
                continue
            off_n, off_counts = official(script, path, decisions)
            mark = "" if ours_counts == off_counts else " (counts differ: %s against %s)" % (
                ours_counts, off_counts)
            print(row + " %s | %.2f%s |" % ("{:,.0f}".format(off_n / decisions),
                                            off_n / ours_n, mark), flush=True)
    finally:
        os.unlink(script)


if __name__ == "__main__":
    main()
