#!/usr/bin/env python3
"""`print` of every rule of some .soar files, in the official Soar 9.6 kernel (pip package
soar-sml) and in rusoar (target/release/rusoar, build it first), compared rule by rule.
The reorderer and the printer's grouping and wrapping are checked this way.

usage: python3 scripts/print_compare.py FILE.soar ...
"""
import sys, re, os, subprocess, soar_sml as sml

RUSOAR = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "target", "release", "rusoar")
k = sml.Kernel.CreateKernelInCurrentThread(True, 0)
bad = 0
for f in sys.argv[1:]:
    text = open(f, errors='replace').read()
    names = []
    for m in re.finditer(r'sp\s*\{\s*(\S+)', text):
        if m.group(1) not in names: names.append(m.group(1))
    a = k.CreateAgent('x')
    a.ExecuteCommandLine('source ' + f)
    off = []
    for n in names:
        r = a.ExecuteCommandLine('print ' + n)
        if r.startswith('sp {'): off.append(r.rstrip('\n'))
    k.DestroyAgent(a)
    cmds = ' '.join("-c 'print %s'" % n for n in names)
    ours_out = subprocess.run(RUSOAR + " -c 'source %s' -c 'echo MARKER' %s 2>/dev/null </dev/null" % (f, cmds), shell=True, capture_output=True, text=True).stdout
    ours = [b.strip('\n') for b in re.findall(r'(?ms)^sp \{.*?^\}\n', ours_out.split('MARKER',1)[-1])]
    offs = [o.strip('\n') for o in off]
    if ours != offs:
        bad += 1
        print('DIFF', f)
        for o, u in zip(offs, ours):
            if o != u: print('--- official\n' + o + '\n--- ours\n' + u)
        if len(ours) != len(offs): print('counts', len(offs), len(ours))
    else:
        print('same', f, len(offs))
print('files differing:', bad)
