#!/usr/bin/env python3
"""Runs Doxygen on a configured Doxyfile and checks its warnings against a baseline.

  check_docs.py DOXYGEN DOXYFILE BASELINE [--update]

Every warning (an undocumented public symbol, a documentation error) is keyed by its header and
its text, without the line number (edits above it move it). The check fails on any warning not in
BASELINE (docs/api/undocumented.txt: the symbols still waiting for their comment); it also fails
when a baseline entry no longer occurs, so the list only shrinks (--update rewrites it). The aim is
an empty baseline: then the reference builds without any warning.
"""
import re
import subprocess
import sys

LINE = re.compile(r"^(?P<file>[^:]+):(?P<line>\d+): (?:warning|error): (?P<text>.*)$")


def warnings(doxygen, doxyfile):
    run = subprocess.run([doxygen, doxyfile], capture_output=True, text=True)
    found, other = {}, []
    for raw in (run.stdout + run.stderr).splitlines():
        m = LINE.match(raw)
        if not m:
            if raw.strip():
                other.append(raw)
            continue
        name = re.sub(r"^.*/include/", "include/", m.group("file"))
        name = re.sub(r"^.*/tests/docs/", "tests/docs/", name)
        key = f"{name}: {m.group('text')}"
        found.setdefault(key, f"{name}:{m.group('line')}: {m.group('text')}")
    return found, other


def main():
    doxygen, doxyfile, baseline_path = sys.argv[1:4]
    found, other = warnings(doxygen, doxyfile)
    with open(baseline_path, encoding="utf-8") as f:
        baseline = {l.rstrip("\n") for l in f if l.strip() and not l.startswith("#")}
    if "--update" in sys.argv:
        with open(baseline_path, "w", encoding="utf-8") as f:
            f.write("# Public symbols of include/mo2d/ still without documentation (docs/api/check_docs.py).\n")
            f.write("# Document one, then delete its line; the test docs.api fails on anything not listed.\n")
            f.writelines(k + "\n" for k in sorted(found))
        print(f"check_docs: {len(found)} entries written to {baseline_path}")
        return 0
    new = sorted(k for k in found if k not in baseline)
    gone = sorted(baseline - found.keys())
    for line in other:
        print(f"doxygen: {line}")
    for k in new:
        print(f"{found[k]}   <- not documented (or a documentation error): write its comment")
    for k in gone:
        print(f"{baseline_path}: '{k}' no longer occurs: delete that line")
    print(f"check_docs: {len(found)} warnings, {len(baseline)} in the baseline, "
          f"{len(new)} new, {len(gone)} fixed but still listed")
    return 1 if new or gone or other else 0


if __name__ == "__main__":
    sys.exit(main())
