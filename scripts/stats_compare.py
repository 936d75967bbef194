#!/usr/bin/env python3
"""Compares `stats` counts of rusoar with the official 9.6 kernel (pip package soar-sml) for
agents in tests/agents/ (all by default): `srand 1`, `source AGENT`, `run 1000`, `stats` in
each, then one line per agent, `OK` or `key:official/rusoar` for each count that differs.
Needs target/release/rusoar (cargo build --release). FULL=1 prints both texts.

usage: python3 scripts/stats_compare.py [AGENT ...]
"""
import os
import re
import subprocess
import sys

import soar_sml as sml

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RUN=os.environ.get("RUN","run 1000")
KEYS=[("dec",r"^(\d+) decisions"),("ec",r"^(\d+) elaboration cycles"),("inner",r"^(\d+) inner"),
("pe",r"^(\d+) p-elaboration"),("pf",r"^(\d+) production firings"),("wmc",r"^(\d+) wme changes"),
("add",r"\((\d+) additions"),("rem",r"(\d+) removals"),("cur",r"^WM size: (\d+) current"),
("mean",r"([\d.]+) mean"),("max",r"(\d+) maximum")]
def parse(s):
    d={}
    for k,rx in KEYS:
        m=re.search(rx,s,re.M); d[k]=m.group(1) if m else "-"
    return d
k = sml.Kernel.CreateKernelInNewThread()
names = sys.argv[1:] or sorted(f[:-5] for f in os.listdir(ROOT+"/tests/agents") if f.endswith(".soar"))
full = os.environ.get("FULL")
for n in names:
    a = k.CreateAgent("stats")
    path="%s/tests/agents/%s.soar" % (ROOT, n)
    for c in ["srand 1", "watch 0", "source "+path, RUN]:
        a.ExecuteCommandLine(c)
    s = a.ExecuteCommandLine("stats")
    k.DestroyAgent(a)
    o = subprocess.run([ROOT+"/target/release/rusoar","-c","srand 1","-c","watch 0","--source",path,"-c",RUN,"-c","stats"],capture_output=True,text=True,stdin=subprocess.DEVNULL,cwd=ROOT).stdout
    po,pr=parse(s),parse(o)
    diffs=[f"{key}:{po[key]}/{pr[key]}" for key,_ in KEYS if po[key]!=pr[key]]
    print(f"{n:30} {'OK' if not diffs else ' '.join(diffs)}")
    if full:
        print(s); print("--- ours"); print(o)
k.Shutdown()
