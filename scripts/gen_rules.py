#!/usr/bin/env python3
"""Generates N Soar rules for the matcher benchmarks, identical input for rusoar
and the official kernel.

kinds:
  nomatch  rules that share the prefix (state <s> ^superstate nil ^task <t>) and then test
           constants no benchmark WME carries: the Rete/UL "flat cost" workload.
  counter  rules whose joins really run: each tests the counter against its own threshold.

usage: gen_rules.py KIND N > file.soar
"""
import sys


def nomatch(n):
    for i in range(n):
        group = i % 100
        yield (
            f"sp {{gen*nomatch*{i}\n"
            f"   (state <s> ^superstate nil ^task <t>)\n"
            f"   (<t> ^name task-{group} ^step <st>)\n"
            f"   (<st> ^kind k{i} ^value <v>)\n"
            f"-->\n"
            f"   (<s> ^result r{i})}}\n"
        )


def counter(n):
    for i in range(n):
        yield (
            f"sp {{gen*counter*{i}\n"
            f"   (state <s> ^superstate nil ^counter <c>)\n"
            f"   (<c> ^value {{ > {i} <v> }})\n"
            f"-->\n"
            f"   (<s> ^passed-{i} <v>)}}\n"
        )


def main():
    if len(sys.argv) != 3 or sys.argv[1] not in ("nomatch", "counter"):
        sys.exit(__doc__)
    gen = {"nomatch": nomatch, "counter": counter}[sys.argv[1]]
    out = sys.stdout
    for rule in gen(int(sys.argv[2])):
        out.write(rule)


if __name__ == "__main__":
    main()
