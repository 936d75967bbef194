#!/usr/bin/env python3
"""Writes tests/agents/smem/kb-facts.soar, the knowledge base of the agent
tests/agents/smem-kb.soar: one `smem --add` of 300 LTIs, @N for the number N, with its
parity, its square and a link to the next number.

usage: python3 scripts/smem_kb.py
"""
import os

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
N = 300


def main():
    lines = ["# Written by scripts/smem_kb.py: 300 numbers, each an LTI with its parity, its",
             "# square and a link to the next one.",
             "smem --add {"]
    for n in range(1, N + 1):
        parity = "even" if n % 2 == 0 else "odd"
        nxt = f" ^next @{n + 1}" if n < N else ""
        lines.append(f"(@{n} ^isa number ^value {n} ^parity {parity} ^square {n * n}{nxt})")
    lines.append("}")
    path = os.path.join(ROOT, "tests", "agents", "smem", "kb-facts.soar")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
