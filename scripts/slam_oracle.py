#!/usr/bin/env python3
"""Replays a Soar-SLAM run of rusoar in the official Soar 9.6 kernel (pip package soar-sml)
and compares the two agents decision by decision (the thesis rules on both kernels).

`rusoar slam --io-log` writes each run's input-link and output-link traffic to
`io-<on|off>-<seed>.log` (format: slam/src/io_log.rs). This script loads the same rules
into the official kernel (robotagent.soar line by line; its Soar 8 `learn -off`, which 9.6
rejects, is given as `chunk never`; with a SLAM-off log the `source slam.soar` line is left
out, as rusoar does), seeds it with `srand SEED`, registers Python versions of the Rust
functions the rules call through `exec` (getlength, checkwallrelation, getwalldistance; the
same arithmetic on the same libm, so the same strings), and then, step by step:

  - in the input phase (smlEVENT_BEFORE_INPUT_PHASE) makes the same input-link changes,
    in the same order, as the log says rusoar's loop made;
  - runs one decision (`RunSelf(1)`, which like rusoar's `run 1` stops before the apply
    phase, so the output phase of decision N-1 comes right before the input phase of N);
  - compares the commands the official kernel put on the output-link, the operators it
    selected (its `watch 1` lines) and its rule firings so far (`stats`) with the log's.

The open-loop replay is exact as long as both kernels agree: rusoar's simulator only reacts
to the commands, which are compared. The first difference is reported and ends the replay.

usage: python3 scripts/slam_oracle.py [--rules DIR] [--steps N] [--every K] LOG [LOG ...]
  LOG       io-<on|off>-<seed>.log (the condition and the seed are read from the name)
  --steps   replay at most N steps
  --every   compare the firing count every K steps (default 1; `stats` costs a little)
Exit status 0 when every compared step agrees, 1 otherwise.
"""
import argparse
import ctypes
import math
import os
import re
import sys
import time

import soar_sml as sml

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LIBM = ctypes.CDLL("libm.so.6")
LIBM.hypot.restype = ctypes.c_double
LIBM.hypot.argtypes = [ctypes.c_double, ctypes.c_double]

# f64::to_degrees multiplies by this constant (Rust's core::f64), not by 180 / pi.
RAD_TO_DEG = 57.2957795130823208767981548141051703

# The Pioneer 2-DX sonar ring: x mm, y mm, heading degrees (slam/src/sonar.rs P2DX_SONARS).
P2DX_SONARS = [
    (69.0, 136.0, 90.0), (114.0, 119.0, 50.0), (148.0, 78.0, 30.0), (166.0, 27.0, 10.0),
    (166.0, -27.0, -10.0), (148.0, -78.0, -30.0), (114.0, -119.0, -50.0),
    (69.0, -136.0, -90.0), (-157.0, -136.0, -90.0), (-203.0, -119.0, -130.0),
    (-237.0, -78.0, -150.0), (-255.0, -27.0, -170.0), (-255.0, 27.0, 170.0),
    (-237.0, 78.0, 150.0), (-203.0, 119.0, 130.0), (-157.0, 136.0, 90.0),
]


def hypot(x, y):
    return LIBM.hypot(x, y)


def rem_euclid(x, m):
    r = math.fmod(x, m)
    return r + abs(m) if r < 0.0 else r


def numbers(args, n):
    """The argument string split on commas, each field a finite float (parse_args)."""
    try:
        vals = [float(f.strip()) for f in args.split(",")]
    except ValueError:
        return None
    if len(vals) != n or any(not math.isfinite(v) for v in vals):
        return None
    return vals


def getlength(args):
    n = numbers(args, 4)
    if n is None:
        return 'Error: getlength expects "x1, y1, x2, y2", got "%s"' % args
    x1, y1, x2, y2 = n
    return "%.3f" % hypot(x2 - x1, y2 - y1)


def checkwallrelation(args):
    n = numbers(args, 7)
    if n is None:
        return "none"
    rx, ry, rth, sx, sy, ex, ey = n
    dx, dy = ex - sx, ey - sy
    len2 = dx * dx + dy * dy
    if len2 == 0.0:
        return "none"
    t = ((rx - sx) * dx + (ry - sy) * dy) / len2
    if not (0.0 <= t <= 1.0):
        return "none"
    fx, fy = sx + t * dx - rx, sy + t * dy - ry
    if hypot(fx, fy) < 1e-9:
        return "none"
    b = rem_euclid(math.atan2(fy, fx) * RAD_TO_DEG - rth + 180.0, 360.0) - 180.0
    if -45.0 <= b <= 45.0:
        return "front"
    if 45.0 < b < 135.0:
        return "left"
    if -135.0 < b < -45.0:
        return "right"
    return "back"


def getwalldistance(args):
    n = numbers(args, 8)
    if n is None:
        return "-1"
    rx, ry, rth, i, sx, sy, ex, ey = n
    if i != math.floor(i) or i < 0.0 or i >= len(P2DX_SONARS):
        return "-1"
    tx, ty, theading = P2DX_SONARS[int(i)]
    r = rth * (math.pi / 180.0)
    sin_r, cos_r = math.sin(r), math.cos(r)
    px = rx + cos_r * tx - sin_r * ty
    py = ry + sin_r * tx + cos_r * ty
    h = (rth + theading) * (math.pi / 180.0)
    dy, dx = math.sin(h), math.cos(h)
    wx_, wy_ = ex - sx, ey - sy
    denom = dx * wy_ - dy * wx_
    length = hypot(wx_, wy_)
    if length == 0.0 or abs(denom) <= 1e-12 * length:
        return "-1"
    wx, wy = sx - px, sy - py
    dist = (wx * wy_ - wy * wx_) / denom
    u = (wx * dy - wy * dx) / denom
    if dist < 0.0 or u < -1e-9 or u > 1.0 + 1e-9:
        return "-1"
    return "%.3f" % dist


WATCH = [1]

FUNCTIONS = {
    "getlength": getlength,
    "checkwallrelation": checkwallrelation,
    "getwalldistance": getwalldistance,
}


# The input lines of a log and their least number of words.
INPUT_WORDS = {"init": 20, "update": 3, "wall": 13, "remove-wall": 2}


def read_log(path):
    """Per step: (commands carried out before its input phase, input changes, decided line)."""
    steps = []
    pending_commands = []
    for number, line in enumerate(open(path), 1):
        words = line.split()
        if not words:
            continue
        if words[0] not in ("step", "command") and not steps:
            raise SystemExit("%s:%d: `%s` before the first step line" % (path, number, words[0]))
        if words[0] == "step":
            steps.append({"n": int(words[1]), "commands": pending_commands, "input": [],
                          "decided": None})
            pending_commands = []
        elif words[0] == "command":
            pending_commands.append(" ".join(words[1:]))
        elif words[0] == "decided":
            steps[-1]["decided"] = (int(words[1]), words[2:])
        elif words[0] in INPUT_WORDS and len(words) >= INPUT_WORDS[words[0]]:
            steps[-1]["input"].append(words)
        else:
            raise SystemExit("%s:%d: not a log line: %s" % (path, number, line.rstrip()))
    return steps


class Replay:
    def __init__(self, kernel, slam, seed, rules_dir):
        self.kernel = kernel
        self.agent = kernel.CreateAgent("soar-slam-oracle")
        self.printed = []
        self.agent.RegisterForPrintEvent(
            sml.smlEVENT_PRINT, lambda _i, _u, _a, msg: self.printed.append(msg), None)
        self.rhs = [kernel.AddRhsFunction(name, self.call, None) for name in FUNCTIONS]
        self.agent.ExecuteCommandLine("cd " + rules_dir)
        for raw in open(os.path.join(rules_dir, "robotagent.soar")):
            line = raw.strip()
            if not line or line.startswith("#"):
                continue
            if line == "learn -off":
                line = "chunk never"
            if line == "source slam.soar" and not slam:
                continue
            self.agent.ExecuteCommandLine(line)
            if not self.agent.GetLastCommandLineResult():
                raise SystemExit("the official kernel rejected `%s`" % line)
        self.agent.ExecuteCommandLine("srand %d" % (seed % (1 << 32)))
        self.agent.ExecuteCommandLine("watch %d" % WATCH[0])
        self.pending = []
        self.agent.RegisterForRunEvent(sml.smlEVENT_BEFORE_INPUT_PHASE, self.input_phase, None)
        self.x = self.y = self.th = None
        self.ranges = []
        self.wall_data = None
        self.walls = {}

    def call(self, _id, _user, _agent, name, argument):
        return FUNCTIONS[name](argument)

    def input_phase(self, *_):
        a = self.agent
        for op in self.pending:
            kind = op[0]
            if kind == "init":
                il = a.GetInputLink()
                data = a.CreateIdWME(il, "currentrobotdata")
                self.x = a.CreateIntWME(data, "X", int(op[1]))
                self.y = a.CreateIntWME(data, "Y", int(op[2]))
                self.th = a.CreateIntWME(data, "Th", int(op[3]))
                for i, r in enumerate(op[4:]):
                    so = a.CreateIdWME(data, "sonar")
                    a.CreateIntWME(so, "index", i)
                    self.ranges.append(a.CreateIntWME(so, "range", int(r)))
                self.wall_data = a.CreateIdWME(il, "wallData")
            elif kind == "update":
                if op[1] == "range":
                    a.Update(self.ranges[int(op[2])], int(op[3]))
                else:
                    a.Update({"X": self.x, "Y": self.y, "Th": self.th}[op[1]], int(op[2]))
            elif kind == "wall":
                k = int(op[1])
                sx, sy, ex, ey, rx, ry, rth = (int(v) for v in op[2:9])
                length, r, th, t = float(op[9]), int(op[10]), int(op[11]), int(op[12])
                w = a.CreateIdWME(self.wall_data, "Wall")
                start = a.CreateIdWME(w, "Start")
                a.CreateIntWME(start, "X", sx)
                a.CreateIntWME(start, "Y", sy)
                end = a.CreateIdWME(w, "End")
                a.CreateIntWME(end, "X", ex)
                a.CreateIntWME(end, "Y", ey)
                ref = a.CreateIdWME(w, "Ref")
                a.CreateIntWME(ref, "X", rx)
                a.CreateIntWME(ref, "Y", ry)
                a.CreateIntWME(ref, "Th", rth)
                a.CreateFloatWME(w, "Length", length)
                a.CreateIntWME(w, "R", r)
                a.CreateIntWME(w, "Th", th)
                a.CreateIntWME(w, "Time", t)
                self.walls[k] = w
            elif kind == "remove-wall":
                a.DestroyWME(self.walls.pop(int(op[1])))
            else:
                raise SystemExit("unknown log line: %s" % " ".join(op))
        self.pending = []
        a.Commit()

    def commands(self):
        """The new output-link commands, as the log words them, each marked complete."""
        a = self.agent
        out = []
        for i in range(a.GetNumberCommands()):
            cmd = a.GetCommand(i)
            if cmd.GetParameterValue("status") is not None:
                continue
            words = [cmd.GetCommandName()]
            for j in range(cmd.GetNumberChildren()):
                c = cmd.GetChild(j)
                value = c.GetValueAsString()
                if c.GetValueType() == "double":
                    # SML prints six significant digits; the kernel's text has six decimals.
                    value = "%.6f" % c.ConvertToFloatElement().GetValue()
                words += [c.GetAttribute(), value]
            out.append(words)
            cmd.AddStatusComplete()
        a.ClearOutputLinkChanges()
        return out

    def firings(self):
        m = re.search(r"(\d+) production firings", self.agent.ExecuteCommandLine("stats"))
        return int(m.group(1)) if m else -1


def operators(text):
    """Operator names selected in one decision's `watch 1` text (any goal level)."""
    return re.findall(r"O: O\d+ \(([^)]*)\)", text)


def same_command(ours, theirs):
    """Same name and parameters; parameters compared as sets (their order is WME order)."""
    a, b = ours.split(), theirs
    if a[0] != b[0]:
        return False
    pa = sorted(zip(a[1::2], a[2::2]))
    pb = sorted(zip(b[1::2], b[2::2]))
    return pa == pb


def replay(path, rules_dir, max_steps, every, show=False):
    name = os.path.basename(path)
    m = re.match(r"io-(on|off)-(\d+)\.log$", name)
    if not m:
        raise SystemExit("%s: expected a file named io-<on|off>-<seed>.log" % path)
    slam, seed = m.group(1) == "on", int(m.group(2))
    steps = read_log(path)
    if max_steps:
        steps = steps[:max_steps]
    kernel = sml.Kernel.CreateKernelInCurrentThread(True, 0)
    started = time.time()
    try:
        r = Replay(kernel, slam, seed, rules_dir)
        for st in steps:
            r.pending = st["input"]
            r.printed.clear()
            r.agent.RunSelf(1)
            text = "".join(r.printed)
            if show:
                print("--- step %d\n%s" % (st["n"], text.rstrip()))
            got_cmds = r.commands()
            want_cmds = st["commands"]
            if len(got_cmds) != len(want_cmds) or not all(
                    same_command(w, g) for w, g in zip(want_cmds, got_cmds)):
                return fail(name, st["n"], "commands", want_cmds,
                            [" ".join(c) for c in got_cmds])
            if st["decided"] is None:
                return fail(name, st["n"], "log", "a decided line", "none")
            want_firings, want_ops = st["decided"]
            got_ops = operators(text)
            if got_ops != want_ops:
                return fail(name, st["n"], "operators", want_ops, got_ops)
            if every and (st["n"] % every == 0 or st is steps[-1]):
                got_firings = r.firings()
                if got_firings != want_firings:
                    return fail(name, st["n"], "firings", want_firings, got_firings)
        n = len(steps)
        firings = steps[-1]["decided"][0] if steps else 0
        print("%s: %d steps agree (operators, commands, %d firings) in %.1f s"
              % (name, n, firings, time.time() - started))
        return True
    finally:
        kernel.Shutdown()


def fail(name, step, what, want, got):
    print("%s: step %d: %s differ\n  rusoar:   %s\n  official: %s" % (name, step, what, want, got))
    return False


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("logs", nargs="+", metavar="LOG")
    ap.add_argument("--rules", default=os.path.join(ROOT, "rules"))
    ap.add_argument("--steps", type=int, default=0)
    ap.add_argument("--every", type=int, default=1)
    ap.add_argument("--show", action="store_true", help="print the official kernel's watch text")
    ap.add_argument("--watch", type=int, default=1, help="the official kernel's watch level")
    args = ap.parse_args()
    WATCH[0] = args.watch
    ok = True
    for path in args.logs:
        ok = replay(path, os.path.abspath(args.rules), args.steps, args.every, args.show) and ok
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
