#!/usr/bin/env python3
"""Times the official Soar 9.6 kernel (pip package soar-sml) on the matcher benchmarks,
with the same generated rules and the same working-memory changes as
benches/rete.rs, so the README can show both side by side.

For each size (1,000 / 10,000 / 100,000 `nomatch` rules from scripts/gen_rules.py, written
to a temporary directory in files of at most 10,000 rules so that progress can be printed):

  load     `source` of the files into a fresh agent, timed around ExecuteCommandLine, and
           the VmRSS growth of this process over it (1,000 and 10,000: median of 5 loads);
  changes  the working-memory setup of benches/rete.rs
               wm add S1 task *        -> I4
               wm add I4 name task-0
               wm add S1 other *       -> I5
               wm add I4 step *        -> I6
           then, for each change, `wm add ...` and `wm remove <timetag>` through
           ExecuteCommandLine, in rounds that time one batch on each size in turn (the
           agents of all sizes stay loaded), the median per size; and the first
           add+remove of each change after the load, timed once (one-time work):
               noise         wm add S1 noise x   no rule tests ^noise
               step-fail     wm add I5 step x    enters (* ^step *); group 0's join fails
               step-partial  wm add I4 step x    a partial match that stops at group 0's
                                                 ^kind joins (left-unlinked in Rete/UL)
               value-fail    wm add I5 value x   enters (* ^value *), whose N joins (one
                                                 per rule) all have empty parents
               kind-partial  wm add I6 kind |K0| a token in rule 0's last beta memory,
                                                 whose ^value join is on (* ^value *)
  echo     `echo x` through ExecuteCommandLine: the command layer's own cost.

With --ours FILE (the JSON that `RETE_BENCH_JSON=FILE cargo bench --features internals --bench rete` writes) it
also prints the side-by-side table. Ratios there are official time / rusoar time: above 1
means rusoar is faster by that factor.

usage: bench_official.py [--sizes 1000,10000,100000] [--limit SECONDS] [--ours FILE]
                         [--json FILE]
"""
import argparse
import json
import os
import statistics
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gen_rules  # noqa: E402

import soar_sml as sml  # noqa: E402

SETUP = ["wm add S1 task *", "wm add I4 name task-0", "wm add S1 other *", "wm add I4 step *"]
CHANGES = [
    ("noise", "wm add S1 noise x"),
    ("step-fail", "wm add I5 step x"),
    ("step-partial", "wm add I4 step x"),
    ("value-fail", "wm add I5 value x"),
    ("kind-partial", "wm add I6 kind |K0|"),
]
CHUNK = 10_000
LOADS_SMALL = 5
ROUNDS = 15
BATCH = 1_000


def rss_bytes():
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return 0


def write_files(tmp, n):
    """The rules of `gen_rules.py nomatch n`, split into files of CHUNK rules, in order."""
    rules = list(gen_rules.nomatch(n))
    paths = []
    for k in range(0, n, CHUNK):
        path = os.path.join(tmp, f"nomatch-{n}-{k // CHUNK:02d}.soar")
        with open(path, "w") as f:
            f.writelines(rules[k:k + CHUNK])
        paths.append(path)
    return paths


def run(agent, cmd):
    r = agent.ExecuteCommandLine(cmd)
    if not agent.GetLastCommandLineResult():
        raise RuntimeError(f"{cmd!r} failed: {r}")
    return r


def median_us(batches, per_batch, f):
    for _ in range(per_batch // 10):
        f()
    times = []
    for _ in range(batches):
        t = time.perf_counter()
        for _ in range(per_batch):
            f()
        times.append((time.perf_counter() - t) / per_batch * 1e6)
    return statistics.median(times)


def change_pair(agent, cmd):
    r = agent.ExecuteCommandLine(cmd)
    tt = r.strip().split()[-1]
    agent.ExecuteCommandLine("wm remove " + tt)


def load(kernel, paths, n, limit):
    """Sources the files into a new agent: (agent, seconds, RSS growth, rules, complete)."""
    agent = kernel.CreateAgent(f"bench{n}")
    rss0 = rss_bytes()
    loaded = 0
    r = ""
    t0 = time.perf_counter()
    for path in paths:
        r = run(agent, f"source {{{path}}}")
        loaded += min(CHUNK, n - loaded)
        elapsed = time.perf_counter() - t0
        if len(paths) > 1:
            print(f"  official: {loaded:>7} of {n} rules sourced, {elapsed:8.1f} s", flush=True)
        if elapsed > limit and loaded < n:
            return agent, elapsed, rss_bytes() - rss0, loaded, False
    load_s = time.perf_counter() - t0
    if f"Total: {CHUNK if n > CHUNK else n} productions sourced." not in r:
        print(f"  (unexpected source output: {r[-200:]!r})")
    return agent, load_s, rss_bytes() - rss0, loaded, True


def load_size(kernel, tmp, n, limit, figures):
    """Loads n rules; returns the agent with the working-memory setup, or None."""
    paths = write_files(tmp, n)
    # Small sizes: the median of LOADS_SMALL loads, each into a new agent (the last is kept).
    times = []
    for _ in range(LOADS_SMALL if n <= 10_000 else 1):
        if times:
            kernel.DestroyAgent(agent)
        agent, load_s, rss, loaded, complete = load(kernel, paths, n, limit)
        times.append(load_s)
    load_s = statistics.median(times)
    key = str(n)
    if not complete:
        print(f"  official: stopped after {load_s:.0f} s with {loaded} of {n} rules: the load "
              f"time is a lower bound and the change costs are not measured at this size")
        figures["load_s_lower_bound." + key] = load_s
        figures["load_rules_loaded." + key] = loaded
        kernel.DestroyAgent(agent)
        return None
    figures["load_s." + key] = load_s
    figures["load_rss_bytes." + key] = rss
    print(f"  loaded in {load_s:.3f} s", flush=True)
    for cmd in SETUP:
        run(agent, cmd)
    # The first add+remove of each change, timed once: one-time work shows here.
    for name, cmd in CHANGES:
        t = time.perf_counter()
        out = run(agent, cmd)
        run(agent, "wm remove " + out.split()[-1])
        figures[f"first_us.{name}.{key}"] = (time.perf_counter() - t) * 1e6
        assert out.startswith("Timetag: "), out
    return agent


def measure_changes(agents, figures):
    """Per change: ROUNDS rounds, each timing one batch on every size in turn (so that load
    from elsewhere on the machine falls on all sizes alike); the median per size."""
    for name, cmd in CHANGES:
        for agent in agents.values():
            for _ in range(BATCH // 10):
                change_pair(agent, cmd)
        times = {n: [] for n in agents}
        for _ in range(ROUNDS):
            for n, agent in agents.items():
                t = time.perf_counter()
                for _ in range(BATCH):
                    change_pair(agent, cmd)
                times[n].append((time.perf_counter() - t) / BATCH * 1e6)
        for n in agents:
            figures[f"cmd_us.{name}.{n}"] = statistics.median(times[n])
        print(f"  {name}: " + ", ".join(f"{n} rules {figures[f'cmd_us.{name}.{n}']:.2f} us"
                                        for n in agents), flush=True)
    agent = next(iter(agents.values()))
    figures["cmd_us.echo"] = median_us(7, 5_000, lambda: agent.ExecuteCommandLine("echo x"))


def fmt(v, spec):
    return format(v, spec) if isinstance(v, (int, float)) else "-"


def withunit(v, unit):
    return "-" if v is None else format(v, ".3f") + unit


def print_official(sizes, f):
    print("\n== official Soar 9.6 kernel (soar_sml), one run ==")
    print(f"{'rules':>8} {'source s':>10} {'rules/s':>10} {'RSS MB':>8} {'B/rule':>8}")
    for n in sizes:
        k = str(n)
        if "load_s." + k in f:
            s = f["load_s." + k]
            print(f"{n:>8} {s:>10.3f} {n / s:>10.0f} {f['load_rss_bytes.' + k] / 1e6:>8.1f} "
                  f"{f['load_rss_bytes.' + k] / n:>8.0f}")
        else:
            s = f.get("load_s_lower_bound." + k)
            print(f"{n:>8} {'>' + fmt(s, '.1f'):>10}   ({f.get('load_rules_loaded.' + k)} loaded)")
    print("(RSS: this process's growth over the last load; freed agents' memory is reused, so "
          "only the\n largest size's figure means much)")
    print("\nper change, wm add + wm remove through ExecuteCommandLine (us per pair)")
    print(f"{'change':<13} {'command':<20}" + "".join(f" {n:>9}" for n in sizes) + "  last/first")
    for name, cmd in CHANGES:
        row = [f.get(f"cmd_us.{name}.{n}") for n in sizes]
        ratio = row[-1] / row[0] if None not in (row[0], row[-1]) else None
        print(f"{name:<13} {cmd:<20}" + "".join(f" {fmt(v, '9.2f'):>9}" for v in row)
              + f"  {fmt(ratio, '.2f')}x")
    print(f"(baseline: echo x through ExecuteCommandLine: {fmt(f.get('cmd_us.echo'), '.2f')} us)")
    print("\nthe first add+remove of each change after the load (us, once, in this order)")
    for name, cmd in CHANGES:
        row = [f.get(f"first_us.{name}.{n}") for n in sizes]
        print(f"{name:<13} {cmd:<20}" + "".join(f" {fmt(v, '9.1f'):>9}" for v in row))


def print_side_by_side(sizes, off, ours):
    print("\n== side by side: rusoar vs the official kernel, same machine, same run ==")
    print("ratio = official time / rusoar time (above 1: rusoar is faster by that factor)\n")
    print(f"{'figure':<56} {'rusoar':>12} {'official':>12} {'ratio':>8}")

    def row(label, a, b, unit):
        r = b / a if a and b else None
        print(f"{label:<56} {withunit(a, unit):>12} {withunit(b, unit):>12} "
              f"{fmt(r, '.1f'):>8}")

    for n in sizes:
        k = str(n)
        b = off.get("load_s." + k)
        if b is None and ("load_s_lower_bound." + k) in off:
            a = ours.get("load_s." + k)
            lb = off["load_s_lower_bound." + k]
            print(f"{'load ' + format(n, ',') + ' rules (s)':<56} {withunit(a, ' s'):>12} "
                  f"{'>' + format(lb, '.1f') + ' s':>12} {'>' + fmt(lb / a if a else None, '.0f'):>8}")
            continue
        row(f"load {n:,} rules (s)", ours.get("load_s." + k), b, " s")
    for name, cmd in CHANGES:
        for n in sizes:
            row(f"{cmd} +remove, {n:,} rules (us)", ours.get(f"cmd_us.{name}.{n}"),
                off.get(f"cmd_us.{name}.{n}"), " us")
    row("echo x (us)", ours.get("cmd_us.echo"), off.get("cmd_us.echo"), " us")
    for name, cmd in CHANGES:
        for n in sizes:
            row(f"first {cmd} +remove, {n:,} rules (us)", ours.get(f"first_us.{name}.{n}"),
                off.get(f"first_us.{name}.{n}"), " us")
    n = sizes[-1]
    a = ours.get(f"load_rss_bytes.{n}")
    b = off.get(f"load_rss_bytes.{n}")
    if a and b:
        print(f"{'RSS growth per rule at ' + format(n, ',') + ' (bytes)':<56} {a / n:>12.0f} "
              f"{b / n:>12.0f} {b / a:>8.1f}")
    print("\nflatness, cost at the largest size / cost at the smallest (target: at most 1.5)")
    for name, cmd in CHANGES:
        lo, hi = sizes[0], sizes[-1]
        o = [ours.get(f"cmd_us.{name}.{lo}"), ours.get(f"cmd_us.{name}.{hi}")]
        f = [off.get(f"cmd_us.{name}.{lo}"), off.get(f"cmd_us.{name}.{hi}")]
        api = ours.get(f"api_ratio_100k_1k.{name}")
        print(f"  {name:<13} rusoar commands {fmt(o[1] / o[0] if all(o) else None, '.2f')}x, "
              f"rusoar API {fmt(api, '.2f')}x, official commands "
              f"{fmt(f[1] / f[0] if all(f) else None, '.2f')}x")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--sizes", default="1000,10000,100000")
    ap.add_argument("--limit", type=float, default=300.0,
                    help="stop loading a size after this many seconds (then a lower bound)")
    ap.add_argument("--ours", help="rusoar's figures: the JSON of RETE_BENCH_JSON")
    ap.add_argument("--json", help="write the official figures here")
    args = ap.parse_args()
    sizes = [int(s) for s in args.sizes.split(",")]
    print(f"official kernel: soar_sml {getattr(sml, '__version__', '')} "
          f"on {os.cpu_count()} cores", flush=True)
    kernel = sml.Kernel.CreateKernelInCurrentThread(True, 0)
    figures = {}
    agents = {}
    with tempfile.TemporaryDirectory() as tmp:
        for n in sizes:
            print(f"official: {n:,} rules ...", flush=True)
            agent = load_size(kernel, tmp, n, args.limit, figures)
            if agent is not None:
                agents[n] = agent
    print(f"official: per-change costs, {ROUNDS} interleaved rounds of {BATCH} pairs",
          flush=True)
    measure_changes(agents, figures)
    for agent in agents.values():
        kernel.DestroyAgent(agent)
    kernel.Shutdown()
    print_official(sizes, figures)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(figures, f, indent=2)
    if args.ours:
        with open(args.ours) as f:
            ours = json.load(f)
        print_side_by_side(sizes, figures, ours)


if __name__ == "__main__":
    main()
