"""Runs a list of commands in a fresh process of each kernel, for the scripts that compare
what the two kernels leave behind (database files): the official Soar 9.6.5 (pip package
soar-sml) and rusoar's release build (CARGO_TARGET_DIR is honoured)."""
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RUSOAR = os.path.join(os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target")),
                      "release", "rusoar")


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
    """What rusoar prints for the commands, given as `-c` arguments to one process."""
    args = [RUSOAR]
    for c in commands:
        args += ["-c", c]
    out = subprocess.run(args, capture_output=True, text=True)
    return out.stdout + out.stderr


KERNELS = {"official": official, "rusoar": rusoar}
