#!/usr/bin/env python3
"""Writes tests/golden/rl-mdp.txt: what the official Soar 9.6 kernel (pip package soar-sml)
learns on the random MDP agents of tests/data/rl-mdp/agents.txt (drawn by the proptest
generator of tests/rl_mdp.rs). tests/rl_mdp.rs runs the same agents in rusoar and compares.

  Agents  tests/data/rl-mdp/agents.txt: cases, each a line `### case N` and then one
          command a line, given in order to a fresh agent through ExecuteCommandLine.
  Golden  tests/golden/rl-mdp.txt: for each case its `### case N` line, then for each
          `print --rl` the lines it printed (leading blank lines dropped) and a line `---`.

scripts/goldens.py writes this file with the others (and `--check` compares it).

usage: python3 scripts/rl_mdp_goldens.py           write the golden
       python3 scripts/rl_mdp_goldens.py --check   exit 1 if the golden would change
"""
import os
import sys

import soar_sml as sml

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
AGENTS = os.path.join(ROOT, "tests", "data", "rl-mdp", "agents.txt")
NAME = "rl-mdp.txt"


def cases():
    out = []
    with open(AGENTS) as f:
        for line in f:
            line = line.rstrip("\n")
            if line.startswith("### "):
                out.append((line, []))
            elif out:
                out[-1][1].append(line)
    return out


def golden_text(kernel):
    text = []
    for title, commands in cases():
        agent = kernel.CreateAgent("mdp")
        printed = []
        agent.RegisterForPrintEvent(
            sml.smlEVENT_PRINT, lambda *a: printed.append(a[-1]), None
        )
        text.append(title + "\n")
        for c in commands:
            printed.clear()
            result = agent.ExecuteCommandLine(c)
            if not agent.GetLastCommandLineResult():
                raise SystemExit("%s: `%s` failed: %s" % (title, c, result))
            if c == "print --rl":
                lines = ("".join(printed) + result).lstrip("\n").splitlines()
                text.extend(l + "\n" for l in lines)
                text.append("---\n")
        kernel.DestroyAgent(agent)
    return "".join(text)


def write(kernel, out_dir):
    """Writes the golden into out_dir."""
    with open(os.path.join(out_dir, NAME), "w", newline="\n") as f:
        f.write(golden_text(kernel))


def main():
    kernel = sml.Kernel.CreateKernelInCurrentThread(True, 0)
    try:
        text = golden_text(kernel)
    finally:
        kernel.Shutdown()
    path = os.path.join(ROOT, "tests", "golden", NAME)
    if "--check" in sys.argv[1:]:
        if not os.path.exists(path) or open(path).read() != text:
            print("tests/golden/%s differs from the official kernel" % NAME)
            return 1
        print("rl-mdp golden matches the official kernel")
        return 0
    with open(path, "w", newline="\n") as f:
        f.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
