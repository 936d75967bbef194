#!/usr/bin/env python3
"""Lists import circles between a crate's modules (files), or says there are none.

A file depends on another when it names a path into it: `use crate::a::b`, `crate::a::b::f`,
`super::x` or `self::x` (resolved against the file's own module). A module is a file, so a
circle inside a module's own file is no circle; `#[cfg(test)]` modules, inline (`mod tests
{ ... }`) or in their own file (`mod tests;`), are left out (tests may look anywhere). A file
named `tests.rs` that is not declared under `#[cfg(test)]` (the Rete's join tests) is a module
like any other. Exit status 1 when a circle is found.

    python3 scripts/module_cycles.py src [more crate roots...]
"""
import os
import re
import sys

PATH = re.compile(r"\b(crate|super|self)((?:::[A-Za-z_][A-Za-z0-9_]*)+)")
USE_GROUP = re.compile(r"\buse\s+(crate|super|self)((?:::[A-Za-z_][A-Za-z0-9_]*)*)::\{([^;]*)\}", re.S)


def module_of(root, path):
    rel = os.path.relpath(path, root)[:-3].split(os.sep)
    if rel[-1] in ("mod", "lib", "main"):
        rel = rel[:-1]
    return tuple(rel)


def strip_tests(text):
    # Drops `#[cfg(test)] mod x { ... }` blocks (brace matched) and comments.
    text = re.sub(r"//[^\n]*", "", text)
    out, i = [], 0
    for m in re.finditer(r"#\[cfg\(test\)\]\s*(pub(\([a-z]+\))?\s+)?mod\s+\w+\s*\{", text):
        if m.start() < i:
            continue
        out.append(text[i:m.start()])
        depth, j = 1, m.end()
        while j < len(text) and depth:
            depth += {"{": 1, "}": -1}.get(text[j], 0)
            j += 1
        i = j
    out.append(text[i:])
    return "".join(out)


def resolve(modules, here, head, rest):
    if head == "crate":
        base = ()
    elif head == "super":
        base = here[:-1]
    else:
        base = here
    parts = [p for p in rest.split("::") if p]
    while parts and parts[0] == "super":
        base = base[:-1]
        parts = parts[1:]
    # The longest prefix that is a module.
    for n in range(len(parts), -1, -1):
        cand = base + tuple(parts[:n])
        if cand in modules:
            return cand
    return None


TEST_MOD = re.compile(r"#\[cfg\(test\)\]\s*(?:pub(?:\([a-z]+\))?\s+)?mod\s+(\w+)\s*;")


def graph(root):
    files = {}
    for d, _, names in os.walk(root):
        for n in names:
            if n.endswith(".rs"):
                p = os.path.join(d, n)
                files[module_of(root, p)] = p
    # Modules declared `#[cfg(test)] mod x;` (and everything below them) are tests.
    tests = set()
    for m, p in files.items():
        with open(p, encoding="utf-8") as f:
            text = re.sub(r"//[^\n]*", "", f.read())
        tests.update(m + (name,) for name in TEST_MOD.findall(text))
    files = {m: p for m, p in files.items() if not any(m[: len(t)] == t for t in tests)}
    edges = {m: set() for m in files}
    for m, p in files.items():
        with open(p, encoding="utf-8") as f:
            text = strip_tests(f.read())
        # A file named `x.rs` holding `mod y;` is the module `x`; `super` from it is its parent.
        refs = [(h, r) for h, r in PATH.findall(text)]
        for h, r, group in USE_GROUP.findall(text):
            for item in re.split(r"[,\s{}]+", group):
                item = item.split(" as ")[0].strip()
                if item and item != "self":
                    refs.append((h, r + "::" + item.replace("::", "::")))
        for h, r in refs:
            target = resolve(files, m, h, r)
            if target is not None and target != m:
                edges[m].add(target)
    return edges


def sccs(edges):
    index, low, stack, on, out = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(edges[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in sorted(edges):
        if v not in index:
            visit(v)
    return out


def main():
    roots = sys.argv[1:] or ["src"]
    found = False
    for root in roots:
        for comp in sccs(graph(root)):
            found = True
            names = ["::".join(m) or "(root)" for m in comp]
            print(f"{root}: circle of {len(comp)}: " + ", ".join(names))
    if not found:
        print("no import circles in " + ", ".join(roots))
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
