#!/usr/bin/env python3
"""Inclusive instructions and calls of the functions whose name starts with PREFIX, from a
callgrind output file (summed over the call sites outside the function itself, so that recursion
counts once). Prints "IR CALLS". Used by scripts/instructions.sh and scripts/startup_instructions.sh.

    scripts/callgrind_inclusive.py CALLGRIND_FILE PREFIX
"""
import re, sys
path, prefix = sys.argv[1], sys.argv[2]
names, fn, cfn, calls, ir, n = {}, None, None, None, 0, 0
def name(spec):
    m = re.match(r"\((\d+)\)(?:\s+(.*))?", spec)
    if not m:
        return spec
    if m.group(2):
        names[m.group(1)] = m.group(2)
    return names.get(m.group(1), "")
for line in open(path):
    line = line.rstrip("\n")
    if line.startswith("fn="):
        fn = name(line[3:])
    elif line.startswith("cfn="):
        cfn = name(line[4:])
    elif line.startswith("calls="):
        calls = int(line[6:].split()[0])
    elif calls is not None:
        cost = line.split()
        if cfn.startswith(prefix) and not fn.startswith(prefix):
            n += calls
            ir += int(cost[1]) if len(cost) > 1 else 0
        calls = None
print(ir, n)
