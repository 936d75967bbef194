#!/usr/bin/env python3
"""Runs the coverage-guided fuzz targets of fuzz/ (cargo fuzz, nightly toolchain).

Each target starts from seeds made from the project's own inputs: the test agents and
command scripts of tests/, the thesis rules of rules/, and a world file. The structure-aware
targets (random_agent, api_calls, smem, epmem), whose bytes are choices rather than text, start
from pseudo-random bytes of a fixed seed; smem also from the knowledge bases of the smem
test agents. The seeds go in
fuzz/corpus/TARGET (kept between runs, not committed); libFuzzer adds what it finds there.
A crash, a panic, a hang (over --timeout seconds per input) or running out of memory stops
the target and leaves the input in fuzz/artifacts/TARGET: each becomes a regression test
in tests/ before it is fixed. The summary gives each target's executions and coverage.

usage: python3 scripts/fuzz.py [--seconds S] [--runs N] [--timeout T] [TARGET ...]
       (every target for S seconds each, 10 by default, or until N executions if sooner)
"""
import argparse
import glob
import os
import random
import re
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FUZZ = os.path.join(ROOT, "fuzz")
TARGETS = ["command_line", "production_parser", "source_files", "world_file",
           "random_agent", "api_calls", "smem", "epmem"]

WORLD_SEED = """name = "seed-room"

[robot]
x = 0.0
y = 0.0
heading = 0.0

[run]
dt = 0.1
noise = "ideal"

[[wall]]
x1 = -4.0
y1 = -3.0
x2 = 4.0
y2 = -3.0

[[wall]]
x1 = 4.0
y1 = -3.0
x2 = 4.0
y2 = 3.0

[[wall]]
x1 = 4.0
y1 = 3.0
x2 = -4.0
y2 = 3.0

[[wall]]
x1 = -4.0
y1 = 3.0
x2 = -4.0
y2 = -3.0
"""


def read(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        return f.read()


def agent_files():
    files = sorted(glob.glob(os.path.join(ROOT, "tests", "agents", "*.soar")))
    files += sorted(glob.glob(os.path.join(ROOT, "rules", "*.soar")))
    files += sorted(glob.glob(os.path.join(ROOT, "benches", "agents", "*.soar")))
    return files


def rule_bodies(text):
    """The bodies of the `sp {...}` commands of a file: up to the brace that closes the
    command's, braces inside |strings| and after a # comment set aside."""
    bodies = []
    for m in re.finditer(r"^sp \{", text, re.M):
        depth, i, quoted = 1, m.end(), False
        while i < len(text) and depth:
            c = text[i]
            if quoted:
                quoted = c != "|"
            elif c == "|":
                quoted = True
            elif c == "#":
                i = text.find("\n", i)
                if i < 0:
                    break
            elif c == "{":
                depth += 1
            elif c == "}":
                depth -= 1
            i += 1
        if depth == 0:
            bodies.append(text[m.end():i - 1])
    return bodies


def seeds(target):
    """The seed inputs of a target, as (name, text)."""
    out = []
    if target == "command_line":
        for f in sorted(glob.glob(os.path.join(ROOT, "tests", "commands", "*.cmds"))):
            # Paths are outside what the target takes: keep the commands, drop the paths.
            text = "\n".join(l for l in read(f).splitlines() if "/" not in l)
            out.append((os.path.basename(f), text))
        out += [(os.path.basename(f), read(f)) for f in agent_files()]
    elif target == "production_parser":
        for f in agent_files():
            for i, body in enumerate(rule_bodies(read(f))):
                out.append(("%s-%d" % (os.path.basename(f), i), body))
    elif target == "source_files":
        files = agent_files()
        for i, f in enumerate(files):
            other = files[(i + 1) % len(files)]
            out.append((os.path.basename(f), read(f) + "\n#file\n" + read(other)))
    elif target == "world_file":
        out.append(("seed-room.toml", WORLD_SEED))
    if target in ("random_agent", "api_calls", "smem", "epmem"):
        rng = random.Random(target)
        for i in range(16):
            data = bytes(rng.randrange(256) for _ in range(rng.choice((64, 512, 1500))))
            out.append(("bytes-%d" % i, data))
    if target == "smem":
        for f in sorted(glob.glob(os.path.join(ROOT, "tests", "agents", "smem*.soar"))):
            for i, kb in enumerate(re.findall(r"^smem --add (\{.*?\})\s*$", read(f), re.S | re.M)):
                out.append(("%s-%d" % (os.path.basename(f), i), kb))
    out = [(n, t if isinstance(t, bytes) else t.encode()) for n, t in out]
    return [(n, t) for n, t in out if len(t) <= 4096]


def prepare(target):
    corpus = os.path.join(FUZZ, "corpus", target)
    os.makedirs(corpus, exist_ok=True)
    for name, text in seeds(target):
        path = os.path.join(corpus, "seed-" + re.sub(r"[^A-Za-z0-9_.-]", "_", name))
        if not os.path.exists(path):
            with open(path, "wb") as f:
                f.write(text)
    return corpus


def run(target, seconds, timeout, runs):
    corpus = prepare(target)
    cmd = ["cargo", "+nightly", "fuzz", "run", "-O", target, corpus, "--",
           "-max_total_time=%d" % seconds, "-timeout=%d" % timeout,
           "-rss_limit_mb=4096", "-max_len=4096", "-print_final_stats=1"]
    if runs:
        cmd.append("-runs=%d" % runs)
    p = subprocess.run(cmd, cwd=FUZZ, capture_output=True, text=True)
    log = p.stdout + p.stderr
    runs = re.findall(r"stat::number_of_executed_units:\s*(\d+)", log)
    cov = re.findall(r"cov: (\d+) ft: (\d+)", log)
    execs = int(runs[-1]) if runs else 0
    edges, features = cov[-1] if cov else ("?", "?")
    ok = p.returncode == 0
    print("%-18s %10d executions  coverage %s edges, %s features  %s"
          % (target, execs, edges, features, "ok" if ok else "FINDING"))
    if not ok:
        print(log[-4000:], file=sys.stderr)
    return ok


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--seconds", type=int, default=10)
    ap.add_argument("--timeout", type=int, default=1)
    ap.add_argument("--runs", type=int, default=0, help="stop a target after this many executions")
    ap.add_argument("targets", nargs="*")
    a = ap.parse_args()
    targets = a.targets or TARGETS
    unknown = [t for t in targets if t not in TARGETS]
    if unknown:
        sys.exit("unknown target(s): %s (targets: %s)" % (", ".join(unknown), ", ".join(TARGETS)))
    if shutil.which("cargo-fuzz") is None:
        sys.exit("cargo-fuzz is not installed: cargo install cargo-fuzz --locked")
    build = subprocess.run(["cargo", "+nightly", "fuzz", "build", "-O"], cwd=FUZZ)
    if build.returncode != 0:
        sys.exit("the fuzz targets do not build")
    failed = [t for t in targets if not run(t, a.seconds, a.timeout, a.runs)]
    if failed:
        sys.exit("findings in: %s (inputs in fuzz/artifacts/)" % ", ".join(failed))


if __name__ == "__main__":
    main()
