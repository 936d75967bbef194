#!/usr/bin/env python3
"""Semantic and episodic memory side by side: rusoar and the official Soar 9.6 kernel (pip
package soar-sml) run the same generated agents, turn about, and each row's ratio is
official time / rusoar time (above 1: rusoar is faster).

Rows:
  smem N      cue-based retrieval over N long-term identifiers. The knowledge base is
              `smem --add` of N LTIs, (@i ^isa item ^num i ^b i%100 ^c i%1000), in chunks of
              10,000 (loaded off the clock). The agent issues K queries through
              ^smem.command, one every other decision, in turn: ^num (one match), ^isa ^c
              (N/1000 matches, the most active wins), ^b ^c (the same, two selective
              elements) and ^b ^c that nothing has (a failure after the candidates).
  epmem N     cue-based episodic retrieval over N episodes: N decisions off the clock that
              each change ^count and ^data's ^x ^y ^z (epmem learning on, trigger dc), then
              K queries through ^epmem.command, in turn: an old episode (^count and ^data.x
              of one of the first tenth), a partial one (^data ^x ^y ^z where no ^z value was
              ever seen: the best match is 2 of 3 leaves, found after looking at all
              episodes) and a recent perfect one (^data's three values of 50 decisions ago).
  store D     the storage cost of epmem: D decisions of the episodic agent's first phase
              with `epmem --set learning on`, against the same with learning off.

What is timed is only the part in question: the query rows run the same agent for 2K
decisions with the commands put on a ^fake link that no memory reads (the baseline; the
same rules fire and the same cue structures are built), then 2K decisions with the real
commands, each under its own clock, in the same agent; the figure is the difference per
query. The store row is the difference per decision between the two runs.

Each kernel runs every row in a fresh agent; in each round the official kernel and rusoar
alternate row by row. The official kernel is timed around ExecuteCommandLine in this
process, rusoar in-process by cli/examples/time_run.rs (scripts/bench_common.py). The
decisions and firings of both kernels must agree, or the row is marked.

usage: python3 scripts/bench_memories.py [--quick] [--rounds R] [--queries K] [--write-doc]
                                          [--only smem|epmem|store] [--sizes N,...]
                                          [--no-largest]
  --quick      smem 10k, epmem 1k and store 2k only, K=100 (a smoke check, about a minute)
  --queries K  K for every query row (default: 400 smem, 150 epmem)
  --write-doc  replace the table in docs/performance.md (between its bench_memories markers)
"""
import argparse
import datetime
import os
import statistics
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_common import ROOT, official_segments, ours_segments, time_run_binary  # noqa: E402

DOC = os.path.join(ROOT, "docs", "performance.md")
START, END = "<!-- bench_memories:start -->", "<!-- bench_memories:end -->"
CHUNK = 10_000


def smem_kb(tmp, n):
    """The files of an `smem --add` of N LTIs, CHUNK to a file; returns their paths."""
    paths = []
    for start in range(1, n + 1, CHUNK):
        path = os.path.join(tmp, "kb-%d-%d.soar" % (n, start // CHUNK))
        with open(path, "w") as f:
            f.write("smem --add {\n")
            for i in range(start, min(n, start + CHUNK - 1) + 1):
                f.write("(@%d ^isa item ^num %d ^b %d ^c %d)\n" % (i, i, i % 100, i % 1000))
            f.write("}\n")
        paths.append(path)
    return paths


# The query loop shared by both memories: ^q counts the commands given; below K they go on
# the ^fake link (baseline), from K to 2K on the memory's own link. A command stays until
# the next decision, where `clean` removes it. The first decision is `init`'s.
LOOP = """
sp {bench*propose*init
   (state <s> ^superstate nil -^q)
-->
   (<s> ^operator <o> +)
   (<o> ^name init)}

sp {bench*apply*init
   (state <s> ^operator.name init)
-->
   (<s> ^q 0 ^fake <f>)
   (<f> ^command <fc>)}

sp {bench*propose*query
   (state <s> ^q { <q> < %(twok)d } ^%(mem)s.command <cmd> ^fake.command <fc> %(ready)s)
  -(<cmd> ^query)
  -(<fc> ^query)
-->
   (<s> ^operator <o> +)
   (<o> ^name query ^q <q> ^kind (mod <q> %(kinds)d))}

sp {bench*apply*query*count
   (state <s> ^operator <o> ^q <q>)
   (<o> ^name query ^q <q>)
-->
   (<s> ^q <q> - ^q (+ <q> 1))}

sp {bench*propose*clean
   (state <s> ^cue <cue>)
-->
   (<s> ^operator <o> +)
   (<o> ^name clean)}

sp {bench*apply*clean
   (state <s> ^operator.name clean ^cue <cue> ^<< %(mem)s fake >> <m>)
   (<m> ^command <any>)
   (<any> ^query <cue>)
-->
   (<s> ^cue <cue> -)
   (<any> ^query <cue> -)}
"""

# The cues, one per kind of query, as actions on <cue> (<q>: the query's number).
SMEM_CUES = [
    "(<cue> ^num (+ 1 (mod (* <q> 7919) %(n)d)))",
    "(<cue> ^isa item ^c (mod (* <q> 37) 1000))",
    "(<cue> ^b (mod (* <q> 37) 100) ^c (mod (* <q> 37) 1000))",
    "(<cue> ^b 1 ^c 2)",
]


def query_rules(mem, k, cues):
    """The rules that put query Q's cue on ^fake (Q < K) or on the memory's link, one per
    link and kind, so the cue is whole when the memory reads it."""
    rules = []
    for link, test in (("fake", "< %d" % k), (mem, ">= %d" % k)):
        for kind, actions in enumerate(cues):
            rules.append("""
sp {bench*apply*query*%s*%d
   (state <s> ^operator <o> ^q <q> ^%s.command <cmd>)
   (<o> ^name query ^kind %d ^q { <q> %s })
-->
   (<cmd> ^query <cue>)
   (<s> ^cue <cue>)
   %s}
""" % (link, kind, link, kind, test, actions))
    return "".join(rules)


def smem_agent(tmp, n, k, kb):
    path = os.path.join(tmp, "smem-%d.soar" % n)
    with open(path, "w") as f:
        f.write("smem --enable\n")
        for p in kb:
            f.write("source {%s}\n" % p)
        f.write(LOOP % {"mem": "smem", "k": k, "twok": 2 * k, "kinds": 4, "ready": ""})
        f.write(query_rules("smem", k, [c % {"n": n} for c in SMEM_CUES]))
    return path


# The episodic agent: ^count goes up by one each decision of its first phase and ^data's
# ^x ^y ^z follow it (7, 13 and 101 values: 9,191 distinct triples), so each episode differs
# from the one before in four WMEs and the operator.
EPMEM_STEP = """
epmem --set learning on
epmem --set trigger dc
epmem --set exclusions fake
epmem --set exclusions cue

sp {bench*apply*init*data
   (state <s> ^operator.name init)
-->
   (<s> ^count 0 ^data <d>)
   (<d> ^x 0 ^y 0 ^z 0)}

sp {bench*propose*step
   (state <s> ^count { <c> < %(n)d })
-->
   (<s> ^operator <o> +)
   (<o> ^name step ^count <c>)}

sp {bench*apply*step
   (state <s> ^operator <o> ^count <c> ^data <d>)
   (<o> ^name step ^count <c>)
   (<d> ^x <x> ^y <y> ^z <z>)
-->
   (<s> ^count <c> - ^count (+ <c> 1))
   (<d> ^x <x> - ^x (mod (+ <c> 1) 7)
        ^y <y> - ^y (mod (+ <c> 1) 13)
        ^z <z> - ^z (mod (+ <c> 1) 101))}
"""

EPMEM_CUES = [
    "(<cue> ^count (+ 1 (mod (* <q> 7919) %(tenth)d)) ^data <d>)"
    " (<d> ^x (mod (+ 1 (mod (* <q> 7919) %(tenth)d)) 7))",
    "(<cue> ^data <d>) (<d> ^x 3 ^y 5 ^z 999)",
    "(<cue> ^data <d>) (<d> ^x %(x)d ^y %(y)d ^z %(z)d)",
]


def epmem_agent(tmp, n, k, learning=True):
    path = os.path.join(tmp, "epmem-%d%s.soar" % (n, "" if learning else "-off"))
    back = max(0, n - 50)
    with open(path, "w") as f:
        f.write(EPMEM_STEP % {"n": n})
        if not learning:
            f.write("epmem --set learning off\n")
        f.write(LOOP % {"mem": "epmem", "k": k, "twok": 2 * k, "kinds": 3,
                        "ready": "^count %d" % n})
        values = {"tenth": max(1, n // 10), "x": back % 7, "y": back % 13, "z": back % 101}
        f.write(query_rules("epmem", k, [c % values for c in EPMEM_CUES]))
    return path


def rows_of(opts):
    if opts.quick:
        return [("smem", 10_000), ("epmem", 1_000), ("store", 2_000)]
    return ([("smem", n) for n in (10_000, 100_000, 1_000_000)]
            + [("epmem", n) for n in (1_000, 10_000, 100_000)] + [("store", 10_000)])


def measure(binary, tmp, kind, n, k, rounds, log):
    # k: the queries of a query row (the store row makes none).
    """(official seconds per unit, rusoar seconds per unit, counts agree, unit) of one row,
    each the median over the rounds of (measured run - baseline run) / units."""
    if kind == "smem":
        plan = [(smem_agent(tmp, n, k, smem_kb(tmp, n)), 1, [2 * k, 2 * k])]
        unit = k
    elif kind == "epmem":
        plan = [(epmem_agent(tmp, n, k), n + 1, [2 * k, 2 * k])]
        unit = k
    else:
        plan = [(epmem_agent(tmp, n, k, learning=False), 1, [n]),
                (epmem_agent(tmp, n, k, learning=True), 1, [n])]
        unit = n
    off, mine, same = [], [], True
    for r in range(rounds):
        res = {}
        for who, fn in (("official", official_segments),
                        ("rusoar", lambda p, pre, runs: ours_segments(binary, p, pre, runs))):
            times, counts = [], []
            for path, pre, runs in plan:
                t, c = fn(path, pre, runs)
                times += t
                counts.append(c)
            res[who] = (times, counts)
            log("  %s %s %d round %d: %s %s" % (who, kind, n, r + 1,
                                                " ".join("%.4f" % t for t in times), counts))
        same = same and res["official"][1] == res["rusoar"][1]
        off.append((res["official"][0][1] - res["official"][0][0]) / unit)
        mine.append((res["rusoar"][0][1] - res["rusoar"][0][0]) / unit)
    return statistics.median(off), statistics.median(mine), same, off, mine


def fmt_us(s):
    return "%.1f" % (s * 1e6)


def table(rows):
    lines = ["| row | what is timed | official µs | rusoar µs | ratio |", "|---|---|---|---|---|"]
    what = {"smem": "one cue-based retrieval (mean of %d)",
            "epmem": "one cue-based query (mean of %d)",
            "store": "storage, per decision"}
    names = {"smem": "smem, %s LTIs", "epmem": "epmem, %s episodes", "store": "epmem store, %s decisions"}
    for kind, n, off, mine, same, k in rows:
        ratio = off / mine if mine > 0 else float("inf")
        mark = "" if same else " (counts differ)"
        doing = what[kind] % k if "%d" in what[kind] else what[kind]
        lines.append("| %s | %s | %s | %s | %.2f%s |" % (
            names[kind] % format(n, ","), doing, fmt_us(off), fmt_us(mine), ratio, mark))
    return lines


def write_doc(lines, command):
    text = open(DOC).read()
    if START not in text or END not in text:
        raise SystemExit("%s: no %s ... %s markers" % (DOC, START, END))
    body = "\n".join(["Measured on %s with `%s`:" % (datetime.date.today().isoformat(), command),
                      ""] + lines)
    head, rest = text.split(START, 1)
    _, tail = rest.split(END, 1)
    with open(DOC, "w") as f:
        f.write(head + START + "\n" + body + "\n" + END + tail)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--rounds", type=int, default=1)
    ap.add_argument("--queries", type=int, default=0)
    ap.add_argument("--only", choices=["smem", "epmem", "store"])
    ap.add_argument("--sizes", help="comma-separated sizes for the chosen rows")
    ap.add_argument("--no-largest", action="store_true",
                    help="leave out the 1M-LTI and 100k-episode rows")
    ap.add_argument("--write-doc", action="store_true")
    opts = ap.parse_args()
    # Fewer episodic queries than semantic ones: each walks back through the store, which
    # at 100k episodes takes the official kernel milliseconds a query.
    ks = {"smem": 400, "epmem": 150, "store": 0} if not opts.quick else {"smem": 100, "epmem": 100, "store": 0}
    if opts.queries:
        ks = {kind: opts.queries for kind in ks}
    chosen = rows_of(opts)
    if opts.only:
        chosen = [r for r in chosen if r[0] == opts.only]
    if opts.no_largest:
        chosen = [r for r in chosen if r not in (("smem", 1_000_000), ("epmem", 100_000))]
    if opts.sizes:
        sizes = [int(s) for s in opts.sizes.split(",")]
        chosen = [(kind, n) for kind in dict(chosen) for n in sizes]
    binary = time_run_binary()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for kind, n in chosen:
            off, mine, same, _, _ = measure(binary, tmp, kind, n, ks[kind], max(1, opts.rounds),
                                            lambda s: print(s, flush=True))
            rows.append((kind, n, off, mine, same, ks[kind]))
    lines = table(rows)
    print("\n".join(lines))
    if opts.write_doc:
        args = " ".join(a for a in sys.argv[1:] if a != "--write-doc")
        write_doc(lines, ("python3 scripts/bench_memories.py " + args).strip())


if __name__ == "__main__":
    main()
