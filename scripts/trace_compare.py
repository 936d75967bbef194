#!/usr/bin/env python3
"""Compares the trace text of rusoar with the official Soar 9.6 kernel (pip package
soar-sml), agent by agent and trace level by trace level.

For each agent and level, both kernels get, in a fresh agent:

    srand 1
    source AGENT
    BEFORE               (with --before, e.g. 'wm activation --set activation on')
    trace LEVEL          (or the --trace options given)
    run RUN              (default: run 50)

The official kernel's text of the run is what its print callback received during `run`
followed by run's result, in a process of its own for each agent and level; rusoar's is what the binary (target/release/rusoar) printed for
that command. They are compared line for line; the first difference is shown.

usage: python3 scripts/trace_compare.py [--levels 2,3,4,5] [--run 'run 50']
                                        [--trace '-p -w'] [--before CMD] [--show] [AGENT ...]
  AGENT     names in tests/agents/ (default: all) or paths to .soar files
  --show    print both texts in full for one agent (with --levels N)
The exit status is 1 if any compared text differs.
"""
import argparse
import difflib
import os
import subprocess
import sys

import soar_sml as sml

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
AGENTS = os.path.join(ROOT, "tests", "agents")
BINARY = os.path.join(ROOT, "target", "release", "rusoar")
MARK = "@@trace-compare@@"


def official(path, trace_cmd, run_cmd, before):
    """The official kernel's text, from a process of its own: 9.6 orders some structures
    by memory address, so an agent run after others in one process can list them in
    another order than it does alone."""
    args = [sys.executable, os.path.abspath(__file__), "--official-one", path, trace_cmd, run_cmd]
    args.append(before)
    return subprocess.run(args, capture_output=True, text=True, cwd=ROOT).stdout


def official_here(kernel, path, trace_cmd, run_cmd, before):
    agent = kernel.CreateAgent("compare")
    printed = []
    cb = agent.RegisterForPrintEvent(
        sml.smlEVENT_PRINT, lambda _id, _ud, _agent, msg: printed.append(msg), None
    )
    try:
        for c in ["srand 1", "source %s" % path, before, trace_cmd]:
            if c:
                agent.ExecuteCommandLine(c)
        printed.clear()
        result = agent.ExecuteCommandLine(run_cmd)
        text = "".join(printed) + result
        return text if text.endswith("\n") else text + "\n"
    finally:
        agent.UnregisterForPrintEvent(cb)
        kernel.DestroyAgent(agent)


def ours(path, trace_cmd, run_cmd, before):
    args = [BINARY, "-c", "srand 1", "--source", path]
    args += ["-c", before] if before else []
    args += ["-c", trace_cmd]
    args += ["-c", "echo " + MARK, "-c", run_cmd, "-c", "echo " + MARK]
    out = subprocess.run(args, capture_output=True, text=True, cwd=ROOT).stdout
    parts = out.split(MARK + "\n")
    return parts[1] if len(parts) >= 3 else "(no output: %r)" % out[-400:]


def agent_path(name):
    if name.endswith(".soar"):
        return os.path.abspath(name)
    return os.path.join(AGENTS, name + ".soar")


def official_one(path, trace_cmd, run_cmd, before):
    kernel = sml.Kernel.CreateKernelInCurrentThread(True, 0)
    try:
        sys.stdout.write(official_here(kernel, path, trace_cmd, run_cmd, before))
    finally:
        kernel.Shutdown()


def main():
    if sys.argv[1:2] == ["--official-one"]:
        official_one(*sys.argv[2:6])
        return 0
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("agents", nargs="*")
    p.add_argument("--levels", default="2,3,4,5")
    p.add_argument("--run", default="run 50")
    p.add_argument("--trace", help="trace options instead of levels, e.g. '-p -w'")
    p.add_argument("--before", default="", help="a command after the source, before the trace")
    p.add_argument("--show", action="store_true")
    p.add_argument("--context", type=int, default=3)
    args = p.parse_args()
    names = args.agents or sorted(
        f[: -len(".soar")] for f in os.listdir(AGENTS) if f.endswith(".soar")
    )
    traces = (
        ["trace " + args.trace]
        if args.trace
        else ["trace %s" % l for l in args.levels.split(",")]
    )
    bad = 0
    for name in names:
        path = agent_path(name)
        row = []
        for t in traces:
            a = official(path, t, args.run, args.before)
            b = ours(path, t, args.run, args.before)
            if args.show:
                print("=== official: %s, %s" % (name, t))
                sys.stdout.write(a)
                print("=== rusoar: %s, %s" % (name, t))
                sys.stdout.write(b)
            if a == b:
                row.append("%s: same" % t)
                continue
            bad += 1
            la, lb = a.splitlines(True), b.splitlines(True)
            first = next(
                (i for i, (x, y) in enumerate(zip(la, lb)) if x != y),
                min(len(la), len(lb)),
            )
            row.append("%s: differs at line %d" % (t, first + 1))
            if not args.show:
                lo = max(0, first - args.context)
                diff = difflib.unified_diff(
                    la[lo : first + 8],
                    lb[lo : first + 8],
                    "official",
                    "rusoar",
                    n=args.context,
                )
                sys.stdout.write("--- %s, %s\n" % (name, t))
                sys.stdout.writelines(diff)
        print("%-28s %s" % (name, "; ".join(row)))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
