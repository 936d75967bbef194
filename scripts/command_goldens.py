#!/usr/bin/env python3
"""Writes the command goldens: what the official Soar 9.6 kernel (pip package soar-sml)
answers to each command of tests/commands/NAME.cmds. tests/command_goldens.rs gives the same
commands to rusoar and compares, command by command. Goldens are never edited by hand.

  Commands  tests/commands/NAME.cmds: one command per line, given in order to one fresh
            agent through ExecuteCommandLine, from the repository's root (so `source
            tests/commands/agents/X.soar` works). Blank lines and lines starting with `#`
            are skipped.
  Golden    tests/golden/commands/NAME.txt: for each command a line `>>> COMMAND`, then
            what it printed: the print callback's text followed by the command's result,
            with a newline added when the text does not end with one. A failing command
            gives one line `!!! MESSAGE`, the first line of its result (rusoar: the
            diagnostic's message). The repository's absolute path, which differs from
            machine to machine (`source -a` prints it), is written `<repo>`.

usage: python3 scripts/command_goldens.py           write the goldens
       python3 scripts/command_goldens.py --check   exit 1 if any golden would change
"""
import difflib
import glob
import os
import re
import subprocess
import sys

import soar_sml as sml

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
COMMANDS = os.path.join(ROOT, "tests", "commands")
GOLDEN = os.path.join(ROOT, "tests", "golden", "commands")


def commands_of(path):
    with open(path) as f:
        lines = [l.rstrip("\n") for l in f]
    return [l for l in lines if l.strip() and not l.lstrip().startswith("#")]


def golden_text(kernel, name, commands):
    agent = kernel.CreateAgent(name)
    printed = []
    agent.RegisterForPrintEvent(sml.smlEVENT_PRINT, lambda *a: printed.append(a[-1]), None)
    out = []
    for c in commands:
        printed.clear()
        result = agent.ExecuteCommandLine(c)
        out.append(f">>> {c}\n")
        if agent.GetLastCommandLineResult():
            text = "".join(printed) + result
            if text and not text.endswith("\n"):
                text += "\n"
            out.append(text)
        else:
            out.append(f"!!! {result.splitlines()[0] if result else ''}\n")
    kernel.DestroyAgent(agent)
    return "".join(out).replace(ROOT + "/", "<repo>/")


def golden_in_own_process(name, path):
    """The golden of one file, from a kernel in a process of its own: 9.6 leaves traces of
    one agent's rules in the process's memory (a rule loaded later can start with a break
    set, as observed with `production break`)."""
    out = subprocess.run([sys.executable, os.path.abspath(__file__), "--one", name, path],
                         capture_output=True, text=True, check=True)
    return out.stdout


def graph_canonical(body):
    """A `visualize` graph's objects, their rows and its edges, each in an order of their
    own (9.6 writes them in the order of its memories' internals, which changes from run to
    run; tests/command_goldens.rs compares them so too). A constant's box, named by its text
    and a running count, is named by its text alone."""
    header, blocks, edges, block = [], [], [], None
    for line in body:
        if block is not None:
            block.append(line)
            if line == "   ];":
                blocks.append(block)
                block = None
        elif line.startswith('   "'):
            block = [line]
        elif line.startswith('"'):
            edges.append(line)
        elif line:
            header.append(line)
    renamed = {}
    for b in blocks:
        if any('shape = "box"' in l for l in b):
            name = b[0].strip()[:-len(" [")]
            label = next((l.strip()[len("label = "):] for l in b if l.strip().startswith("label = ")), "")
            new_name = label.rstrip('"') + '#"'
            b[0] = "   " + new_name + " ["
            renamed[name + ":n"] = new_name + ":n"
        rows = [i for i, l in enumerate(b) if l.lstrip().startswith("<TR> <TD  >")]
        for i, row in zip(rows, sorted(b[i] for i in rows)):
            b[i] = row
    for i, e in enumerate(edges):
        for old, new in renamed.items():
            if old in e:
                edges[i] = e.replace(old, new, 1)
                break
    return header + sorted("\n".join(b) for b in blocks) + sorted(edges)


def stable_form(text):
    """The golden text with what `stats` prints that changes from run to run of the same
    kernel masked (and the time `debug time` prints): times, the date, byte sizes and pool rows (tests/command_goldens.rs masks
    the same figures, and says why). A golden is rewritten only when this form changes, so
    that regenerating does not rewrite goldens whose counts are the same."""
    out, in_stats, in_csv, in_smem = [], False, False, False
    lines, graph, in_visualize = [], None, False
    for line in text.splitlines():
        if line.startswith(">>> "):
            in_visualize = line[4:].split()[:1] == ["visualize"]
        if in_visualize and line == "digraph g {":
            graph = []
            lines.append(line)
        elif graph is not None and line == "}":
            lines.extend(graph_canonical(graph))
            lines.append(line)
            graph = None
        elif graph is not None:
            graph.append(line)
        else:
            lines.append(line)
    for line in lines:
        # `debug time`'s wall-clock time.
        line = re.sub(r"^\([0-9.e+-]+s\) real$", "(#s) real", line)
        if line.startswith(">>> "):
            word = (line[4:].split() or [""])[0]
            in_stats, in_csv = word in ("stats", "st"), False
            in_smem = word == "smem"
            out.append(line)
            continue
        if in_smem and re.match(r" *(SQLite Version|Memory Usage|Memory Highwater)", line):
            line = re.sub(r"[\d.]+", "#", line)
        if in_stats:
            if line == "dc,time,wm_changes,firing_count":
                in_csv = True
            elif in_csv and re.fullmatch(r"\d+,\d+,\d+,\d+", line):
                line = re.sub(r"^(\d+),\d+,", r"\1,#,", line)
            else:
                in_csv = False
                if re.match(r"Soar .* on .* at ", line):
                    line = "Soar # on # at #"
                elif line.strip().startswith("Time (sec)") or line.startswith("Activations:"):
                    line = re.sub(r"[\d.]+", "#", line)
                elif re.fullmatch(r" *\d+ bytes .*", line) or re.fullmatch(r" *\S.{0,14}( +\d+){4}", line):
                    line = re.sub(r" +", " ", re.sub(r"\d+", "#", line))
                line = re.sub(r"\d+\.\d+", "#", line)
        out.append(line)
    return "\n".join(out)


def main():
    os.chdir(ROOT)
    if sys.argv[1:2] == ["--one"]:
        name, path = sys.argv[2], sys.argv[3]
        # The kernel writes some debugging lines straight to the process's standard output
        # (`trace -A`: "in assert_new_preferences:"), not to the agent's print stream: they
        # go to /dev/null, and the golden to the real standard output.
        golden_out = os.fdopen(os.dup(1), "w")
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, 1)
        kernel = sml.Kernel.CreateKernelInCurrentThread(True, 0)
        golden_out.write(golden_text(kernel, name, commands_of(path)))
        golden_out.flush()
        kernel.Shutdown()
        return
    check = "--check" in sys.argv[1:]
    os.makedirs(GOLDEN, exist_ok=True)
    changed = 0
    for path in sorted(glob.glob(os.path.join(COMMANDS, "*.cmds"))):
        name = os.path.basename(path)[:-5]
        text = golden_in_own_process(name, path)
        target = os.path.join(GOLDEN, name + ".txt")
        old = open(target).read() if os.path.exists(target) else None
        if old is not None and stable_form(old) == stable_form(text):
            continue
        changed += 1
        if check:
            sys.stdout.writelines(difflib.unified_diff(
                (old or "").splitlines(True), text.splitlines(True), target + " (stored)",
                target + " (official kernel)"))
        else:
            with open(target, "w") as f:
                f.write(text)
            print("wrote", os.path.relpath(target, ROOT))
    if check and changed:
        print(f"{changed} command golden(s) differ from the official kernel's output")
        sys.exit(1)


if __name__ == "__main__":
    main()
