#!/usr/bin/env python3
"""Writes the conformance goldens: what the official Soar 9.6 kernel (pip package soar-sml)
prints for each agent in tests/agents/. tests/conformance.rs runs the same agents in rusoar
and compares, line for line. Goldens are never edited by hand: change an agent, then run
this script.

Conventions (tests/conformance.rs follows the same ones):

  Agents    tests/agents/NAME.soar, plain Soar source written for this project, starting
            with a comment that says what it checks. An agent may set kernel options
            itself (`soar max-goal-depth 6`, `soar wait-snc on`) but never runs itself: the
            harness does. It must load without any warning in the official kernel (this
            script stops otherwise), should halt by itself within 1000 decisions where
            it can, and for now uses only the RHS functions write, crlf, halt, +, - and *.
  Commands  for each agent, in a fresh agent of the official kernel, through
            ExecuteCommandLine, one at a time:
                srand 1
                watch 1
                source /abs/path/tests/agents/NAME.soar
                run 1000
                stats
            The print callback's text during `run 1000` is the trace; `run`'s result text
            gives the run summary; `stats`'s result text gives the statistics.
  Decisions The trace's lines that match `^\\s+\\d+: ` (every decision line starts
            with a newline, then the cycle number right-aligned in 6 columns, then ": "),
            kept whole: a `write` without a leading `(crlf)` lands on the decision line
            before it, so such writes are compared too. Other trace text (`System halted.`,
            the max-goal-depth message, writes on their own lines) is not compared.
  Counts    after the line `--- counts ---`, one `key: value` per line:
              run decisions     N of `--> N decision cycle(s) executed.` (run's result)
              run firings       M of `M rule(s) fired.`, 0 for `No rules fired.`
              halted            yes if the trace contains the line `System halted.`
              decisions         `N decisions` of `stats`
              elaboration cycles`N elaboration cycles` of `stats`
              production firings`N production firings` of `stats`
              wm size           `WM size: N current` of `stats`
            All of these are exact integers in 9.6 (stats' timings, means and ratios are
            not used; `wme changes` is not used either).
  Golden    tests/golden/NAME.txt: the decision lines, then `--- counts ---` and the counts.
  Learning  agents named learn-*.soar add `chunks learned: N` (from run's
            `N new rule(s) learned.`, 0 without it) to their counts, then
            `--- after init-soar ---` and the same text for a second `init-soar` +
            `run 1000` + `stats` in the same agent (chunks are kept). Their learned rules go
            to tests/golden/NAME.rules.txt: `print --chunks` after the first run, then
            `print NAME` of each chunk listed.
  RL MDP    tests/golden/rl-mdp.txt: what 9.6 learns on the random MDP agents of
            tests/data/rl-mdp/agents.txt, written by scripts/rl_mdp_goldens.py.
  RL        agents named rl-*.soar (which turn reinforcement learning on themselves) add
            `--- print --rl ---` and the result text of `print --rl` after the first run,
            then for episodes 2 to RL_EPISODES: `--- episode N ---`, the same text for an
            `init-soar` + `run 1000` + `stats` in the same agent, and `print --rl` again.
  rusoar    tests/conformance.rs gives rusoar::commands::Interpreter (cwd: the repository)
            "srand 1\nwatch 1\nsource PATH\nrun 1000" with run_text, takes the output
            (trace and run summary together), then runs `stats`, and builds the same text.

  Traces    for every agent in tests/agents/ and the long-run agents in LONG_TRACE_AGENTS,
            and each trace level in TRACE_LEVELS, in a fresh agent of the official kernel
            in a process of its own (9.6 orders some structures by memory address, so an
            agent run after others in one process may list them in another order):
                srand 1
                source /abs/path/tests/agents/NAME.soar
                trace LEVEL
                run 50
            The print callback's text during `run 50`, then run's result text, go to
            tests/golden/traces/NAME.LEVEL.txt, whole (a newline added if the text does not
            end with one). tests/trace_goldens.rs runs the same commands in rusoar and
            compares the text line for line. The long-run agents (`long/NAME`,
            tests/agents/long/NAME.soar) have their traces in tests/golden/traces/long/.

  Long runs for the agents in tests/agents/long/ (each with its number of decisions in
            LONG_RUNS), in a fresh agent of the official kernel:
                srand 1
                watch 0
                source /abs/path/tests/agents/long/NAME.soar
                run N
                stats
                print --depth 2 s1
                print --justifications
            tests/golden/long/NAME.txt holds `run: N`, then `--- counts ---` with the counts
            above (run decisions, run firings, decisions, elaboration cycles, production
            firings, wm size; halted is yes if run's result says `An agent halted during
            the run.`) and
              wm mean           `M mean` of `stats`' WM size line (three decimals)
              wm maximum        `X maximum` of the same line
              justifications    `+ J justifications` of `stats`, 0 without that line
            then `--- print --depth 2 s1 ---` and `--- print --justifications ---`, each
            followed by that command's result text, whole (a newline added if it does not
            end with one). The prints come straight after `stats`: 9.6 wraps a printed
            object's lines by the column the previous output left it at.
            tests/conformance.rs runs the same commands in rusoar and compares the text.

usage: python3 scripts/goldens.py [--out DIR]   write goldens to DIR (default tests/golden)
       python3 scripts/goldens.py --check       regenerate into a temporary folder and exit
                                                1 if any file differs from tests/golden
       python3 scripts/goldens.py --trace NAME  print everything the official kernel printed
                                                for one agent (for writing agents)
"""
import argparse
import difflib
import os
import re
import subprocess
import sys
import tempfile

import soar_sml as sml

import rl_mdp_goldens  # the random MDP agents of tests/rl_mdp.rs (beside this script)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
AGENTS = os.path.join(ROOT, "tests", "agents")
GOLDEN = os.path.join(ROOT, "tests", "golden")
RUN = "run 1000"

# Long-run agents whose whole trace at levels 2 to 5 (of `run 50`) is kept as a golden too
# (tests/trace_goldens.rs); every agent of tests/agents/ has its traces kept.
LONG_TRACE_AGENTS = [
    "long/factorization",
    "long/fifteen-puzzle",
]
TRACE_LEVELS = [2, 3, 4, 5]
TRACE_RUN = "run 50"

# Agents in tests/agents/long/ and the number of decisions each runs for its end-state
# golden (tests/golden/long/NAME.txt). The factorization stops where two justifications
# are alive in 9.6.
LONG = os.path.join(AGENTS, "long")
LONG_RUNS = {
    "factorization": 99300,
    "fifteen-puzzle": 5000,
}
WM_SIZE = re.compile(r"^WM size: (\d+) current, ([\d.]+) mean, (\d+) maximum", re.M)
JUSTIFICATIONS = re.compile(r"^\s*\+ (\d+) justifications?\b", re.M)

# Episodes of each rl-* agent (one `run 1000` each, `init-soar` between them).
RL_EPISODES = 5

DECISION = re.compile(r"^\s+\d+: ")
RUN_RESULT = re.compile(
    r"--> (\d+) decision cycles? executed\. (?:No rules fired|(\d+) rules? fired)\."
)
STATS = [
    ("decisions", re.compile(r"^(\d+) decisions\b", re.M)),
    ("elaboration cycles", re.compile(r"^(\d+) elaboration cycles\b", re.M)),
    ("production firings", re.compile(r"^(\d+) production firings\b", re.M)),
    ("wm size", re.compile(r"^WM size: (\d+) current\b", re.M)),
]


class AgentError(Exception):
    pass


def learned_count(run_result):
    m = re.search(r"(\d+) new rules? learned\.", run_result)
    return m.group(1) if m else "0"


def golden_text(trace, run_result, stats):
    """The golden file for one run: decision lines, then the counts (see the module doc)."""
    lines = [l for l in trace.split("\n") if DECISION.match(l)]
    m = RUN_RESULT.search(run_result)
    if not m:
        raise AgentError("no run summary in %r" % run_result)
    counts = [
        ("run decisions", m.group(1)),
        ("run firings", m.group(2) or "0"),
        ("halted", "yes" if "System halted." in trace.split("\n") else "no"),
    ]
    for key, rx in STATS:
        s = rx.search(stats)
        if not s:
            raise AgentError("no %r in stats output %r" % (key, stats))
        counts.append((key, s.group(1)))
    out = lines + ["--- counts ---"] + ["%s: %s" % kv for kv in counts]
    return "\n".join(out) + "\n"


def run_agent(kernel, path, raw=False):
    """Runs one agent in a fresh agent of the official kernel; returns its golden text (with
    raw, the whole printed trace and the run and stats results instead)."""
    agent = kernel.CreateAgent("conformance")
    printed = []
    cb = agent.RegisterForPrintEvent(
        sml.smlEVENT_PRINT, lambda _id, _ud, _agent, msg: printed.append(msg), None
    )
    try:

        def cmd(c):
            printed.clear()
            r = agent.ExecuteCommandLine(c)
            if not agent.GetLastCommandLineResult():
                raise AgentError("%s: `%s` failed:\n%s" % (path, c, r))
            return r

        cmd("srand 1")
        cmd("watch 1")
        loaded = cmd("source %s" % path)
        if "warning" in loaded.lower():
            raise AgentError("%s: warnings while loading:\n%s" % (path, loaded))
        run_result = cmd(RUN)
        trace = "".join(printed)
        stats = cmd("stats")
        if raw:
            return trace + "\n" + run_result + "\n" + stats
        text = golden_text(trace, run_result, stats)
        if os.path.basename(path).startswith("rl-"):
            text += "--- print --rl ---\n" + ends_with_newline(cmd("print --rl"))
            for episode in range(2, RL_EPISODES + 1):
                cmd("init-soar")
                run_n = cmd(RUN)
                trace_n = "".join(printed)
                stats_n = cmd("stats")
                text += "--- episode %d ---\n" % episode
                text += golden_text(trace_n, run_n, stats_n)
                text += "--- print --rl ---\n" + ends_with_newline(cmd("print --rl"))
            return text, None
        if not os.path.basename(path).startswith("learn-"):
            return text, None
        text += "chunks learned: %s\n" % learned_count(run_result)
        listing = cmd("print --chunks")
        rules = listing + "".join(
            cmd("print %s" % n.strip()) for n in listing.splitlines() if n.strip()
        )
        cmd("init-soar")
        run2 = cmd(RUN)
        trace2 = "".join(printed)
        stats2 = cmd("stats")
        text += "--- after init-soar ---\n" + golden_text(trace2, run2, stats2)
        text += "chunks learned: %s\n" % learned_count(run2)
        return text, rules
    finally:
        agent.UnregisterForPrintEvent(cb)
        kernel.DestroyAgent(agent)


def trace_agent(path, level):
    """The whole text the official kernel prints for `trace LEVEL` and `run 50`, from a
    process of its own."""
    args = [sys.executable, os.path.abspath(__file__), "--trace-one", path, str(level)]
    done = subprocess.run(args, capture_output=True, text=True, cwd=ROOT)
    if done.returncode != 0:
        raise AgentError("%s: trace %d failed:\n%s" % (path, level, done.stderr))
    return done.stdout


def trace_agent_here(path, level):
    """trace_agent's text, in this process's own kernel."""
    kernel = sml.Kernel.CreateKernelInCurrentThread(True, 0)
    try:
        return trace_agent_in(kernel, path, level)
    finally:
        kernel.Shutdown()


def trace_agent_in(kernel, path, level):
    agent = kernel.CreateAgent("traces")
    printed = []
    cb = agent.RegisterForPrintEvent(
        sml.smlEVENT_PRINT, lambda _id, _ud, _agent, msg: printed.append(msg), None
    )
    try:
        for c in ["srand 1", "source %s" % path, "trace %d" % level]:
            agent.ExecuteCommandLine(c)
            if not agent.GetLastCommandLineResult():
                raise AgentError("%s: `%s` failed" % (path, c))
        printed.clear()
        result = agent.ExecuteCommandLine(TRACE_RUN)
        text = "".join(printed) + result
        return text if text.endswith("\n") else text + "\n"
    finally:
        agent.UnregisterForPrintEvent(cb)
        kernel.DestroyAgent(agent)


def ends_with_newline(text):
    return text if text.endswith("\n") else text + "\n"


def long_run(kernel, name):
    """The end-state golden of one long run (see the module doc)."""
    path = os.path.join(LONG, name + ".soar")
    if name not in LONG_RUNS:
        raise AgentError("%s: no number of decisions in LONG_RUNS" % path)
    agent = kernel.CreateAgent("long")
    try:

        def cmd(c):
            r = agent.ExecuteCommandLine(c)
            if not agent.GetLastCommandLineResult():
                raise AgentError("%s: `%s` failed:\n%s" % (path, c, r))
            return r

        cmd("srand 1")
        cmd("watch 0")
        loaded = cmd("source %s" % path)
        if "warning" in loaded.lower():
            raise AgentError("%s: warnings while loading:\n%s" % (path, loaded))
        # No print callback: with watch 0 the trace holds nothing the golden uses, and a
        # halt shows in run's result (`An agent halted during the run.`).
        run_result = cmd("run %d" % LONG_RUNS[name])
        stats = cmd("stats")
        printed = cmd("print --depth 2 s1")
        justifications = cmd("print --justifications")
        m = RUN_RESULT.search(run_result)
        wm = WM_SIZE.search(stats)
        if not m or not wm:
            raise AgentError("%s: no run summary or WM size in %r" % (path, stats))
        counts = [
            ("run decisions", m.group(1)),
            ("run firings", m.group(2) or "0"),
            ("halted", "yes" if "An agent halted during the run." in run_result else "no"),
        ]
        for key, rx in STATS:
            counts.append((key, rx.search(stats).group(1)))
        j = JUSTIFICATIONS.search(stats)
        counts += [
            ("wm mean", wm.group(2)),
            ("wm maximum", wm.group(3)),
            ("justifications", j.group(1) if j else "0"),
        ]
        return (
            "run: %d\n--- counts ---\n" % LONG_RUNS[name]
            + "".join("%s: %s\n" % kv for kv in counts)
            + "--- print --depth 2 s1 ---\n"
            + ends_with_newline(printed)
            + "--- print --justifications ---\n"
            + ends_with_newline(justifications)
        )
    finally:
        kernel.DestroyAgent(agent)


def long_names():
    if not os.path.isdir(LONG):
        return []
    return sorted(f[: -len(".soar")] for f in os.listdir(LONG) if f.endswith(".soar"))


def agent_names():
    return sorted(f[: -len(".soar")] for f in os.listdir(AGENTS) if f.endswith(".soar"))


def generate(out_dir):
    """Writes NAME.txt for every agent into out_dir, and removes goldens of agents that are
    gone."""
    os.makedirs(out_dir, exist_ok=True)
    names = agent_names()
    for f in os.listdir(out_dir):
        base = f[: -len(".txt")]
        if base.endswith(".rules"):
            base = base[: -len(".rules")]
        if f.endswith(".txt") and base not in names and f != rl_mdp_goldens.NAME:
            os.remove(os.path.join(out_dir, f))
    kernel = sml.Kernel.CreateKernelInCurrentThread(True, 0)
    try:
        rl_mdp_goldens.write(kernel, out_dir)
        for name in names:
            text, rules = run_agent(kernel, os.path.join(AGENTS, name + ".soar"))
            with open(os.path.join(out_dir, name + ".txt"), "w", newline="\n") as f:
                f.write(text)
            if rules is not None:
                with open(
                    os.path.join(out_dir, name + ".rules.txt"), "w", newline="\n"
                ) as f:
                    f.write(rules)
        traces = os.path.join(out_dir, "traces")
        os.makedirs(os.path.join(traces, "long"), exist_ok=True)
        wanted = set()
        for name in agent_names() + LONG_TRACE_AGENTS:
            for level in TRACE_LEVELS:
                f = "%s.%d.txt" % (name, level)
                wanted.add(f)
                text = trace_agent(os.path.join(AGENTS, name + ".soar"), level)
                with open(os.path.join(traces, f), "w", newline="\n") as out:
                    out.write(text)
        for sub in ["", "long/"]:
            for f in os.listdir(os.path.join(traces, sub)):
                if f.endswith(".txt") and sub + f not in wanted:
                    os.remove(os.path.join(traces, sub + f))
        long_dir = os.path.join(out_dir, "long")
        os.makedirs(long_dir, exist_ok=True)
        names = long_names()
        for name in names:
            with open(os.path.join(long_dir, name + ".txt"), "w", newline="\n") as out:
                out.write(long_run(kernel, name))
        for f in os.listdir(long_dir):
            if f.endswith(".txt") and f[: -len(".txt")] not in names:
                os.remove(os.path.join(long_dir, f))
    finally:
        kernel.Shutdown()


def golden_files(folder):
    """The golden files under folder: NAME.txt, NAME.rules.txt, traces/NAME.L.txt,
    traces/long/NAME.L.txt and long/NAME.txt."""
    found = set(f for f in os.listdir(folder) if f.endswith(".txt"))
    for sub in ["traces", "traces/long", "long"]:
        d = os.path.join(folder, sub)
        if os.path.isdir(d):
            found |= set(sub + "/" + f for f in os.listdir(d) if f.endswith(".txt"))
    return found


def check():
    """Regenerates into a temporary folder; 1 if anything differs from tests/golden."""
    with tempfile.TemporaryDirectory() as tmp:
        generate(tmp)
        fresh = golden_files(tmp)
        committed = golden_files(GOLDEN) if os.path.isdir(GOLDEN) else set()
        bad = 0
        for f in sorted(fresh | committed):
            if f not in committed:
                print("missing golden: tests/golden/%s" % f)
                bad += 1
                continue
            if f not in fresh:
                print("golden without an agent: tests/golden/%s" % f)
                bad += 1
                continue
            a = open(os.path.join(GOLDEN, f)).read().splitlines(True)
            b = open(os.path.join(tmp, f)).read().splitlines(True)
            if a != b:
                bad += 1
                sys.stdout.writelines(
                    difflib.unified_diff(
                        a, b, "tests/golden/" + f, "official kernel: " + f, n=2
                    )
                )
        if bad:
            print(
                "%d golden file(s) differ from the official kernel; "
                "run `python3 scripts/goldens.py` to regenerate" % bad
            )
            return 1
        print("goldens: %d files match the official kernel" % len(fresh))
        return 0


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--out", default=GOLDEN, help="output folder (default tests/golden)")
    p.add_argument(
        "--check",
        action="store_true",
        help="regenerate into a temporary folder and fail if tests/golden differs",
    )
    p.add_argument("--trace", metavar="NAME", help="print one agent's whole trace")
    if sys.argv[1:2] == ["--trace-one"]:
        sys.stdout.write(trace_agent_here(sys.argv[2], int(sys.argv[3])))
        return 0
    args = p.parse_args()
    try:
        if args.trace:
            kernel = sml.Kernel.CreateKernelInCurrentThread(True, 0)
            path = os.path.join(AGENTS, args.trace + ".soar")
            sys.stdout.write(run_agent(kernel, path, raw=True))
            kernel.Shutdown()
            return 0
        if args.check:
            return check()
        generate(args.out)
    except AgentError as e:
        print("error: %s" % e, file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
