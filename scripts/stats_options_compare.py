#!/usr/bin/env python3
"""Compares what `stats --rete`, `stats --cycle-csv` and `stats --max` print in rusoar and in
the official 9.6 kernel (pip package soar-sml), agent by agent (tests/agents/ and
tests/commands/agents/). In each: `srand 1`, `trace 0`, `source AGENT`, `stats --track`,
the run commands given (default `run 40`), then the three reports. Times and the matcher's
activation counts cannot be the same and are left out; every count is compared. One line per
agent, `same` or `DIFF` with the differing lines. Needs target/release/rusoar.

usage: python3 scripts/stats_options_compare.py ['run 7 -p' 'init-soar' 'run 4' ...]
"""
import difflib
import glob
import os
import re
import subprocess
import sys

import soar_sml as sml

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REPORTS = ["stats --rete", "stats --cycle-csv", "stats --max"]


def comparable(text):
    lines = []
    for line in text.strip().splitlines():
        if line.startswith("Activations:"):
            continue
        if re.match(r"^\d+,\d+,\d+,\d+$", line):
            line = re.sub(r"^(\d+),\d+,", r"\1,#,", line)
        if line.strip().startswith("Time (sec)"):
            line = "Time (sec) #"
        lines.append(line)
    return lines


def main():
    os.chdir(ROOT)
    runs = sys.argv[1:] or ["run 40"]
    kernel = sml.Kernel.CreateKernelInCurrentThread(True, 0)
    agents = sorted(glob.glob("tests/agents/*.soar") + glob.glob("tests/commands/agents/*.soar"))
    differ = 0
    for path in agents:
        setup = ["soar stop-phase apply", "srand 1", "trace 0", f"source {path}", "stats --track"]
        agent = kernel.CreateAgent("compare")
        for c in setup + runs:
            agent.ExecuteCommandLine(c)
        official = "".join(agent.ExecuteCommandLine(c) for c in REPORTS)
        kernel.DestroyAgent(agent)
        script = "\n".join(setup + runs + ["echo @@@"] + REPORTS) + "\n"
        out = subprocess.run([ROOT + "/target/release/rusoar"], input=script,
                             capture_output=True, text=True).stdout
        ours = out.split("@@@\n", 1)[-1]
        a, b = comparable(official), comparable(ours)
        if a == b:
            print(f"{path:45} same")
            continue
        differ += 1
        print(f"{path:45} DIFF")
        for line in difflib.unified_diff(a, b, "official", "rusoar", lineterm="", n=0):
            print("   ", line)
    kernel.Shutdown()
    print(f"{differ} of {len(agents)} agents differ")
    sys.exit(1 if differ else 0)


if __name__ == "__main__":
    main()
