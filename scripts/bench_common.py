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


def time_run_binary():
    """Builds cli/examples/time_run.rs once and returns its path, so that each timing is one
    process start and no cargo invocation."""
    subprocess.run(["cargo", "build", "--release", "--quiet", "-p", "rusoar-cli", "--example",
                    "time_run"], cwd=ROOT, check=True)
    target = os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
    return os.path.join(target, "release", "examples", "time_run")


def official_segments(path, pre, runs):
    """One fresh official agent: `srand 1`, `watch 0`, `source PATH`, `run PRE` off the clock,
    then each `run D` of RUNS under its own clock. Returns the seconds of each timed run and
    the (decisions, firings) its `stats` reports at the end."""
    k = sml.Kernel.CreateKernelInNewThread()
    a = k.CreateAgent("soar")
    for c in ["srand 1", "watch 0", "source {%s}" % path]:
        a.ExecuteCommandLine(c)
    if pre:
        a.ExecuteCommandLine(f"run {pre}")
    times = []
    for d in runs:
        t = time.perf_counter()
        a.ExecuteCommandLine(f"run {d}")
        times.append(time.perf_counter() - t)
    stats = a.ExecuteCommandLine("stats")
    dec = int(re.search(r"(\d+) decisions", stats).group(1))
    fir = int(re.search(r"(\d+) production firings", stats).group(1))
    k.Shutdown()
    return times, (dec, fir)


def ours_segments(binary, path, pre, runs):
    """The same in rusoar, in-process in the time_run binary (`FILE@PRE+D1+D2...`)."""
    spec = "+".join(str(d) for d in ([pre] if pre or len(runs) > 1 else []) + list(runs))
    out = subprocess.run([binary, "1", f"{path}@{spec}"], capture_output=True, text=True,
                         cwd=ROOT, check=True).stdout.split()
    return [float(s) for s in out[3:]], (int(out[1]), int(out[2]))
