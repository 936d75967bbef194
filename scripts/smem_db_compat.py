#!/usr/bin/env python3
"""Semantic memory's database files are shared with the official Soar 9.6.5 kernel (pip
package soar-sml): a file the official kernel writes opens in rusoar with the same
knowledge, and a file rusoar writes opens in the official kernel; each kernel's file also
outlives its process (the second open is in another process). Spreading activation's rows
agree too: the agent of the command golden smem-spreading-agent, run by each kernel on a
file up to its second run (while a source is in working memory), leaves the same rows in
the spreading tables, the same edge weights and the same activations. Exits 1 on a difference.

usage: python3 scripts/smem_db_compat.py   (after cargo build --release)
"""
import os
import sqlite3
import sys
import tempfile

from command_runs import KERNELS

KNOWLEDGE = ("smem --add {(@1 ^name alice ^age 30 ^friend @2) (@2 ^name bob ^friend @1) "
             "(@3 ^name |carol c| ^age 41 ^tags a b)}")


def setup(path):
    return ["smem --set database file", f"smem --set path {path}", "smem --enable"]


ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# The spreading tables and the columns that spreading writes elsewhere, as (name, query);
# rows are compared as sorted lists, reals to nine decimals.
SPREAD_ROWS = [
    ("edge weights", "SELECT lti_id, value_lti_id, edge_weight FROM smem_augmentations "
                     "WHERE value_lti_id != 0"),
    ("LTI activations", "SELECT lti_id, activation_base_level, activation_spread, "
                        "activation_value FROM smem_lti"),
    ("trajectories", "SELECT * FROM smem_likelihood_trajectories"),
    ("likelihoods", "SELECT * FROM smem_likelihoods"),
    ("trajectory sums", "SELECT * FROM smem_trajectory_num"),
    ("current spread", "SELECT * FROM smem_current_spread"),
    ("spread activations", "SELECT * FROM smem_current_spread_activations"),
]


def spread_commands(path):
    """The commands of the spreading golden up to its second run, on a database file."""
    with open(os.path.join(ROOT, "tests", "commands", "smem-spreading-agent.cmds")) as f:
        lines = [l.strip() for l in f if l.strip() and not l.startswith("#")]
    out = []
    for line in lines:
        if line == "run 2":
            break
        if line == "smem --enable":
            out += ["smem --set database file", f"smem --set path {path}"]
        out.append(line.replace("source tests/", f"source {ROOT}/tests/"))
    return out


def rows_of(path):
    db = sqlite3.connect(path)
    out = {}
    for name, query in SPREAD_ROWS:
        rows = [tuple(round(v, 9) if isinstance(v, float) else v for v in r)
                for r in db.execute(query)]
        out[name] = sorted(rows, key=repr)
    db.close()
    return out


def compare_spreading(tmp):
    """Whether both kernels leave the same spreading rows; prints each table's verdict."""
    got = {}
    for kernel, run in KERNELS.items():
        path = os.path.join(tmp, f"spread-{kernel}.db")
        run(spread_commands(path))
        got[kernel] = rows_of(path)
    same = True
    for name, _ in SPREAD_ROWS:
        ok = got["official"][name] == got["rusoar"][name]
        same &= ok
        print(f"spreading, {name}: {'same' if ok else 'DIFFERENT'}")
        if not ok:
            print("  official:", got["official"][name])
            print("  rusoar:  ", got["rusoar"][name])
    return same


def main():
    failed = 0
    with tempfile.TemporaryDirectory() as tmp:
        for writer, reader in [("official", "rusoar"), ("rusoar", "official")]:
            path = os.path.join(tmp, f"{writer}.db")
            run = KERNELS
            run[writer](setup(path) + [KNOWLEDGE])
            expected = run[writer](setup(path) + ["print @"])
            got = run[reader](setup(path) + ["print @"])
            ok = "(@3 ^age 41 ^name |carol c| ^tags a b [+0.000])" in got and \
                all(line in got for line in expected.splitlines() if line.startswith("(@"))
            print(f"{writer} writes, {reader} reads: {'same' if ok else 'DIFFERENT'}")
            if not ok:
                print("--- written and read back by", writer, "\n" + expected)
                print("--- read by", reader, "\n" + got)
                failed += 1
        if not compare_spreading(tmp):
            failed += 1
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
