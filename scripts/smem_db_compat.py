#!/usr/bin/env python3
"""Semantic memory's database files are shared with the official Soar 9.6.5 kernel (pip
package soar-sml): a file the official kernel writes opens in rusoar with the same
knowledge, and a file rusoar writes opens in the official kernel; each kernel's file also
outlives its process (the second open is in another process). Exits 1 on a difference.

usage: python3 scripts/smem_db_compat.py   (after cargo build --release)
"""
import os
import sys
import tempfile

from command_runs import KERNELS

KNOWLEDGE = ("smem --add {(@1 ^name alice ^age 30 ^friend @2) (@2 ^name bob ^friend @1) "
             "(@3 ^name |carol c| ^age 41 ^tags a b)}")


def setup(path):
    return ["smem --set database file", f"smem --set path {path}", "smem --enable"]


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
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
