#!/usr/bin/env python3
"""Compares the rules rusoar learns with those the official Soar 9.6 kernel (pip package
soar-sml) learns, agent by agent, whatever the agent's own learning settings.

For each agent both kernels get, in a fresh agent:

    srand 1
    chunk always         (or the --learn setting given)
    source AGENT
    watch 0
    run RUN              (default: run 200)

then `print NAME` for every chunk the official kernel lists (`print --chunks`). The texts
of the rules are compared whole, so variable names, condition order and tests all count.
An agent either kernel does not finish in --timeout seconds (one whose working memory grows
without end, say) is reported and skipped.

usage: python3 scripts/chunk_compare.py [--learn 'chunk always'] [--run 'run 200']
                                        [--timeout 60] [AGENT ...]
  AGENT   names in tests/agents/ or tests/commands/agents/, or paths to .soar files
          (default: every agent of both folders)
The exit status is 1 if an agent's rules differ.
"""
import argparse
import difflib
import glob
import json
import os
import subprocess
import sys

import soar_sml as sml

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FOLDERS = [os.path.join(ROOT, "tests", "agents"), os.path.join(ROOT, "tests", "commands", "agents")]
BINARY = os.path.join(ROOT, "target", "release", "rusoar")


def official_here(path, learn, run):
    """The official kernel's chunk names and the text of each, printed (in this process)."""
    kernel = sml.Kernel.CreateKernelInCurrentThread(True, 0)
    agent = kernel.CreateAgent("soar1")
    for command in ["srand 1", learn, "source {%s}" % path, "watch 0", run]:
        agent.ExecuteCommandLine(command)
    names = [n.strip() for n in agent.ExecuteCommandLine("print --chunks").splitlines() if n.strip()]
    text = "".join(agent.ExecuteCommandLine("print " + n) for n in names)
    kernel.Shutdown()
    return names, text


def official(path, learn, run, timeout):
    """`official_here` in a child process, so that an agent that never finishes is given up."""
    args = [sys.executable, os.path.abspath(__file__), "--official-child", path, "--learn", learn,
            "--run", run]
    out = subprocess.run(args, capture_output=True, text=True, timeout=timeout).stdout
    found = json.loads(out)
    return found["names"], found["text"]


def ours(path, learn, run, names, timeout):
    """rusoar's text of the same chunks, printed after the same commands."""
    commands = ["srand 1", learn, "source {%s}" % path, "watch 0", run] + ["print " + n for n in names]
    out = subprocess.run([BINARY], input="\n".join(commands) + "\n", capture_output=True,
                         text=True, timeout=timeout).stdout
    start = out.find("sp {")
    return out[start:] if start >= 0 else ""


def rules(text):
    """The rules of a text, blank lines dropped."""
    return [line for line in text.splitlines() if line.strip()]


def agent_paths(names):
    if not names:
        return sorted(p for folder in FOLDERS for p in glob.glob(os.path.join(folder, "*.soar")))
    paths = []
    for n in names:
        if os.path.exists(n):
            paths.append(n)
            continue
        found = [os.path.join(f, n + ".soar") for f in FOLDERS if os.path.exists(os.path.join(f, n + ".soar"))]
        if not found:
            sys.exit("no agent named " + n)
        paths.append(found[0])
    return paths


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--learn", default="chunk always")
    parser.add_argument("--run", default="run 200")
    parser.add_argument("--timeout", type=float, default=60)
    parser.add_argument("--official-child", help=argparse.SUPPRESS)
    parser.add_argument("agents", nargs="*")
    args = parser.parse_args()
    if args.official_child:
        names, text = official_here(args.official_child, args.learn, args.run)
        print(json.dumps({"names": names, "text": text}))
        return
    differ = 0
    for path in agent_paths(args.agents):
        name = os.path.splitext(os.path.basename(path))[0]
        try:
            names, theirs = official(path, args.learn, args.run, args.timeout)
            if not names:
                continue
            mine = ours(path, args.learn, args.run, names, args.timeout)
        except subprocess.TimeoutExpired:
            print("%-28s skipped: not finished in %g s" % (name, args.timeout))
            continue
        same = rules(theirs) == rules(mine)
        differ += not same
        print("%-28s %2d rules: %s" % (name, len(names), "same" if same else "DIFFER"))
        if not same:
            for line in difflib.unified_diff(rules(theirs), rules(mine), "official", "rusoar",
                                             lineterm="", n=1):
                print("   " + line)
    sys.exit(1 if differ else 0)


if __name__ == "__main__":
    main()
