#!/usr/bin/env python3
"""The decision cycle side by side: rusoar and the official Soar 9.6 kernel (pip package
soar-sml) run the same agents with the same commands, turn about, and each agent's ratio is
official time / rusoar time (above 1: rusoar is faster).

Agents and their runs:
  benches/agents/NAME.soar     `run D` from the file's `# bench: run D` line
  tests/agents/long/NAME.soar  the decisions of its end-state golden (scripts/goldens.py)
  tests/agents/NAME.soar       `run 1000`

Each timing is one fresh agent: `srand 1`, `watch 0`, `source FILE`, then `run D` under the
clock. The official kernel is timed around ExecuteCommandLine in this process; rusoar
in-process by cli/examples/time_run.rs. One round times every agent in the official kernel
and then in rusoar, agent by agent; each figure is the median over the rounds. The decisions
and firings of both kernels must agree, or the row is marked.

The minimum is taken over the agents that run 1,000 decisions or more in the official kernel
(the others finish in well under a millisecond, where the clock says little).

usage: python3 scripts/bench_agents.py [--rounds R] [--write-doc] [AGENT ...]
  AGENT: a name such as `wait`, `long/fifteen-puzzle` or `water-jug` (default: all)
  --write-doc  replace the table in docs/performance.md (between its bench_agents markers)
"""
import argparse
import datetime
import glob
import os
import re
import statistics
import subprocess
import time

import soar_sml as sml

from goldens import LONG_RUNS

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BENCH = re.compile(r"^#\s*bench:\s*run\s+(\d+)\s*$", re.M)
DOC = os.path.join(ROOT, "docs", "performance.md")
START, END = "<!-- bench_agents:start -->", "<!-- bench_agents:end -->"
COUNTS = [("decisions", re.compile(r"^(\d+) decisions\b", re.M)),
          ("firings", re.compile(r"^(\d+) production firings\b", re.M))]


def agents():
    """(name, path, decisions) of every agent the benchmark knows."""
    found = []
    for path in sorted(glob.glob(os.path.join(ROOT, "benches", "agents", "*.soar"))):
        m = BENCH.search(open(path).read())
        if not m:
            raise SystemExit("%s: no `# bench: run D` line" % path)
        found.append((os.path.basename(path)[:-5], path, int(m.group(1))))
    for name, decisions in sorted(LONG_RUNS.items()):
        found.append(("long/" + name, os.path.join(ROOT, "tests", "agents", "long", name + ".soar"),
                      decisions))
    for path in sorted(glob.glob(os.path.join(ROOT, "tests", "agents", "*.soar"))):
        found.append((os.path.basename(path)[:-5], path, 1000))
    return found


def counts_of(stats):
    return tuple(int(rx.search(stats).group(1)) for _, rx in COUNTS)


def official(path, decisions):
    """Seconds of `run D` in a fresh official agent, with its (decisions, firings)."""
    kernel = sml.Kernel.CreateKernelInCurrentThread(True, sml.Kernel.kSuppressListener)
    agent = kernel.CreateAgent("bench")
    for c in ["srand 1", "watch 0", "source {%s}" % path]:
        agent.ExecuteCommandLine(c)
    start = time.perf_counter()
    agent.ExecuteCommandLine("run %d" % decisions)
    seconds = time.perf_counter() - start
    counts = counts_of(agent.ExecuteCommandLine("stats"))
    kernel.Shutdown()
    return seconds, counts


def build():
    subprocess.run(["cargo", "build", "--release", "--quiet", "-p", "rusoar-cli", "--example",
                    "time_run"], cwd=ROOT, check=True)
    target = os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
    return os.path.join(target, "release", "examples", "time_run")


def ours(binary, path, decisions):
    """The same in rusoar (cli/examples/time_run.rs)."""
    out = subprocess.run([binary, "1", "%s@%d" % (path, decisions)], capture_output=True,
                         text=True, cwd=ROOT, check=True).stdout
    _, dec, fir, secs = out.split()
    return float(secs), (int(dec), int(fir))


def table(rows):
    lines = ["| agent | decisions | firings | official s | rusoar s | ratio |",
             "|---|---|---|---|---|---|"]
    for name, counts, same, off, mine in rows:
        mark = "" if same else " (counts differ)"
        lines.append("| %s | %s | %s | %.4f | %.4f | %.1f%s |" % (
            name, format(counts[0], ","), format(counts[1], ","), off, mine, off / mine, mark))
    counted = [off / mine for _, counts, _, off, mine in rows if counts[0] >= 1000]
    summary = []
    if counted:
        summary.append("Minimum ratio over the %d agents of 1,000 decisions or more: **%.1f**; "
                       "median %.1f." % (len(counted), min(counted), statistics.median(counted)))
    return lines, summary


def write_doc(lines, summary, command):
    text = open(DOC).read()
    if START not in text or END not in text:
        raise SystemExit("%s: no %s ... %s markers" % (DOC, START, END))
    body = "\n".join(["Measured on %s with `%s`:" % (datetime.date.today().isoformat(), command),
                      ""] + lines + [""] + summary)
    head, rest = text.split(START, 1)
    _, tail = rest.split(END, 1)
    with open(DOC, "w") as f:
        f.write(head + START + "\n" + body + "\n" + END + tail)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--write-doc", action="store_true")
    ap.add_argument("agents", nargs="*")
    opts = ap.parse_args()
    chosen = agents()
    if opts.agents:
        known = {name for name, _, _ in chosen}
        unknown = [a for a in opts.agents if a not in known]
        if unknown:
            raise SystemExit("unknown agents: %s" % ", ".join(unknown))
        chosen = [a for a in chosen if a[0] in opts.agents]
    binary = build()
    times = {name: ([], []) for name, _, _ in chosen}
    counts = {}
    for r in range(max(1, opts.rounds)):
        for name, path, decisions in chosen:
            off, off_counts = official(path, decisions)
            mine, my_counts = ours(binary, path, decisions)
            times[name][0].append(off)
            times[name][1].append(mine)
            counts[name] = (off_counts, my_counts)
        print("round %d of %d done" % (r + 1, opts.rounds), flush=True)
    rows = []
    for name, _, _ in chosen:
        off_counts, my_counts = counts[name]
        rows.append((name, off_counts, off_counts == my_counts,
                     statistics.median(times[name][0]), statistics.median(times[name][1])))
    lines, summary = table(rows)
    print("\n".join(lines + [""] + summary))
    if opts.write_doc:
        command = "python3 scripts/bench_agents.py --rounds %d%s" % (
            opts.rounds, "".join(" " + a for a in opts.agents))
        write_doc(lines, summary, command)


if __name__ == "__main__":
    main()
