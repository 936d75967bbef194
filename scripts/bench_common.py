"""Timing helpers shared by the side-by-side benchmarks (bench_counter.py,
bench_slam_workload.py): `run D` of one agent file in the official 9.6
kernel (pip package soar-sml) and in rusoar (in-process, examples/time_run.rs)."""
import os
import re
import statistics
import subprocess
import time

import soar_sml as sml

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def official(path, decisions, repeat):
    """Median seconds of `run DECISIONS` after `srand 1`, `watch 0`, `source PATH` in the
    official kernel, with the decisions and production firings its `stats` reports."""
    times, dec, fir = [], 0, 0
    for _ in range(repeat):
        k = sml.Kernel.CreateKernelInNewThread()
        a = k.CreateAgent("soar")
        for c in ["srand 1", "watch 0", f"source {path}"]:
            a.ExecuteCommandLine(c)
        t = time.perf_counter()
        a.ExecuteCommandLine(f"run {decisions}")
        times.append(time.perf_counter() - t)
        stats = a.ExecuteCommandLine("stats")
        dec = int(re.search(r"(\d+) decisions", stats).group(1))
        fir = int(re.search(r"(\d+) production firings", stats).group(1))
        k.Shutdown()
    return statistics.median(times), dec, fir


def ours(path, decisions, repeat):
    """The same in rusoar: median seconds, decisions, production firings."""
    out = subprocess.run(
        ["cargo", "run", "--release", "--quiet", "-p", "rusoar-cli", "--example", "time_run", "--", str(repeat),
         "--run", str(decisions), path],
        capture_output=True, text=True, cwd=ROOT, check=True).stdout
    _, dec, fir, secs = out.split()
    return float(secs), int(dec), int(fir)
