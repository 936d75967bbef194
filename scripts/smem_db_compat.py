#!/usr/bin/env python3
"""Semantic memory's database files are shared with the official Soar 9.6.5 kernel (pip
package soar-sml): a file the official kernel writes opens in rusoar with the same
knowledge, and a file rusoar writes opens in the official kernel; each kernel's file also
outlives its process (the second open is in another process). Exits 1 on a difference.

usage: python3 scripts/smem_db_compat.py   (after cargo build --release)
"""
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RUSOAR = os.path.join(os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target")), "release", "rusoar")
KNOWLEDGE = ("smem --add {(@1 ^name alice ^age 30 ^friend @2) (@2 ^name bob ^friend @1) "
             "(@3 ^name |carol c| ^age 41 ^tags a b)}")


def setup(path):
    return ["smem --set database file", f"smem --set path {path}", "smem --enable"]


def official(commands):
    """Each command's result text in a fresh official kernel (a process of its own)."""
    script = (
        "import soar_sml as sml, sys\n"
        "k = sml.Kernel.CreateKernelInCurrentThread(True, 0)\n"
        "a = k.CreateAgent('soar')\n"
        "for c in sys.argv[1:]:\n"
        "    print(a.ExecuteCommandLine(c))\n"
        "k.DestroyAgent(a)\n"
        "k.Shutdown()\n"
    )
    out = subprocess.run([sys.executable, "-c", script, *commands],
                         capture_output=True, text=True, check=True)
    return out.stdout


def rusoar(commands):
    args = [RUSOAR]
    for c in commands:
        args += ["-c", c]
    out = subprocess.run(args, capture_output=True, text=True)
    return out.stdout + out.stderr


def main():
    failed = 0
    with tempfile.TemporaryDirectory() as tmp:
        for writer, reader in [("official", "rusoar"), ("rusoar", "official")]:
            path = os.path.join(tmp, f"{writer}.db")
            run = {"official": official, "rusoar": rusoar}
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
