#!/usr/bin/env python3
"""Episodic memory's database files are shared with the official Soar 9.6.5 kernel (pip
package soar-sml). The same agent, run in each kernel with `database file`, writes the
same rows to every table; each file outlives its process and goes on in a second one
(`append on`); each kernel goes on with the other's file; and `epmem --backup` of a store
kept in memory writes the same file. Exits 1 on a difference.

usage: python3 scripts/epmem_db_compat.py   (after cargo build --release)
"""
import os
import sqlite3
import sys
import tempfile

from command_runs import KERNELS, ROOT

AGENT = os.path.join(ROOT, "tests", "data", "epmem-file-agent.soar")
TABLES = [
    "versions", "epmem_persistent_variables", "epmem_rit_left_nodes", "epmem_rit_right_nodes",
    "epmem_symbols_type", "epmem_symbols_integer", "epmem_symbols_float",
    "epmem_symbols_string", "epmem_nodes", "epmem_episodes", "epmem_wmes_constant_now",
    "epmem_wmes_identifier_now", "epmem_wmes_constant_point", "epmem_wmes_identifier_point",
    "epmem_wmes_constant_range", "epmem_wmes_identifier_range", "epmem_wmes_constant",
    "epmem_wmes_identifier", "epmem_ascii",
]


def first(path):
    return ["epmem --set database file", f"epmem --set path {path}",
            "epmem --set learning on", f"source {{{AGENT}}}", "run 16"]


def second(path):
    return ["epmem --set database file", f"epmem --set path {path}", "epmem --set append on",
            "epmem --set learning on", f"source {{{AGENT}}}", "run 5",
            "epmem --print 3", "epmem --print 7", "epmem --print 18", "epmem --stats time"]


def backup(path):
    return ["epmem --set learning on", f"source {{{AGENT}}}", "run 16",
            f"epmem --backup {path}"]


def dump(path):
    """Every table's rows, sorted (the order of rows is SQLite's, not the kernel's)."""
    db = sqlite3.connect(path)
    try:
        return {t: sorted(map(repr, db.execute(f"SELECT * FROM {t}"))) for t in TABLES}
    finally:
        db.close()


def episodes(text):
    """The printed episodes' lines and the `time` statistic."""
    return [line.strip() for line in text.splitlines()
            if line.startswith(("(<id", "(@")) or line.strip().isdigit()]


def differences(a, b):
    return [t for t in TABLES if a[t] != b[t]]


def check(what, ok, detail=""):
    print(f"{what}: {'same' if ok else 'DIFFERENT ' + detail}")
    return 0 if ok else 1


def main():
    failed = 0
    with tempfile.TemporaryDirectory() as tmp:
        files = {k: os.path.join(tmp, f"{k}.db") for k in KERNELS}
        for kernel, path in files.items():
            KERNELS[kernel](first(path))
        diff = differences(dump(files["official"]), dump(files["rusoar"]))
        failed += check("the first process's file", not diff, ", ".join(diff))

        for writer in KERNELS:
            for reader in KERNELS:
                copy = os.path.join(tmp, f"{writer}-then-{reader}.db")
                with open(files[writer], "rb") as src, open(copy, "wb") as dst:
                    dst.write(src.read())
                printed = episodes(KERNELS[reader](second(copy)))
                if (writer, reader) == ("official", "official"):
                    expected_print, expected_file = printed, dump(copy)
                    if len(printed) < 6:
                        failed += check("the official kernel's second process", False,
                                        "printed no episodes")
                    continue
                failed += check(f"{writer} writes, {reader} goes on: episodes printed",
                                printed == expected_print, f"{printed} != {expected_print}")
                diff = differences(expected_file, dump(copy))
                failed += check(f"{writer} writes, {reader} goes on: the file", not diff,
                                ", ".join(diff))

        for kernel in KERNELS:
            KERNELS[kernel](backup(os.path.join(tmp, f"{kernel}-backup.db")))
        diff = differences(dump(os.path.join(tmp, "official-backup.db")),
                           dump(os.path.join(tmp, "rusoar-backup.db")))
        failed += check("epmem --backup of a store in memory", not diff, ", ".join(diff))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
