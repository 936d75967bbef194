#!/usr/bin/env python3
"""A "joins really run" workload, side by side: a counting agent (an operator adds 1
to ^counter.value each decision) plus N generated rules that each test the counter against
their own threshold (`gen_rules.py counter N`), so that at decision d about d of them match
anew. The same file runs in the official Soar 9.6 kernel (pip package soar-sml) and in
rusoar; `run D` is timed after `source` in both (ours in-process by examples/time_run.rs).
Prints decisions per second and the ratio rusoar / official (above 1: rusoar is faster).
One run per size, the median of REPEAT timings; these machines are noisy.

usage: python3 scripts/bench_counter.py [--repeat R] [--decisions D] [N ...]
       (default N: 1000 10000 100000)
"""
import argparse
import os
import subprocess
import tempfile

from bench_common import ROOT, official, ours

DRIVER = """\
sp {counter*propose*init
   (state <s> ^superstate nil -^counter)
-->
   (<s> ^operator <o> +)
   (<o> ^name init)}

sp {counter*apply*init
   (state <s> ^operator.name init)
-->
   (<s> ^counter <c>)
   (<c> ^value 0)}

sp {counter*propose*increment
   (state <s> ^superstate nil ^counter <c>)
   (<c> ^value <v>)
-->
   (<s> ^operator <o> +)
   (<o> ^name increment ^value <v>)}

sp {counter*apply*increment
   (state <s> ^operator <o> ^counter <c>)
   (<o> ^name increment ^value <v>)
   (<c> ^value <v>)
-->
   (<c> ^value <v> - (+ <v> 1))}
"""


def write_agent(n, path):
    rules = subprocess.run(
        ["python3", os.path.join(ROOT, "scripts", "gen_rules.py"), "counter", str(n)],
        capture_output=True, text=True, check=True).stdout
    with open(path, "w") as f:
        f.write(DRIVER)
        f.write(rules)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--decisions", type=int, default=200)
    ap.add_argument("sizes", nargs="*", type=int)
    opts = ap.parse_args()
    sizes = opts.sizes or [1000, 10000, 100000]
    print("| rules | decisions | rusoar dec/s | official dec/s | ratio |")
    print("|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for n in sizes:
            path = os.path.join(tmp, f"counter-{n}.soar")
            write_agent(n, path)
            rt, rd, _ = ours(path, opts.decisions, opts.repeat)
            ot, _, _ = official(path, opts.decisions, opts.repeat)
            ours_rate, off_rate = rd / rt, opts.decisions / ot
            print(f"| {n:,} | {rd} | {ours_rate:,.0f} | {off_rate:,.0f} | "
                  f"{ours_rate / off_rate:.2f} |", flush=True)


if __name__ == "__main__":
    main()
