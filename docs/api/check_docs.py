#!/usr/bin/env python3
"""Runs Doxygen on a configured Doxyfile and fails on any warning.

  check_docs.py DOXYGEN DOXYFILE

Every warning (a public symbol without documentation, a documentation error) is printed as
`header:line: text` with what to do; the exit status is 1 if there is any, 0 otherwise.
"""
import re
import subprocess
import sys

LINE = re.compile(r"^(?P<file>[^:]+):(?P<line>\d+): (?:warning|error): (?P<text>.*)$")


def main():
    doxygen, doxyfile = sys.argv[1:3]
    run = subprocess.run([doxygen, doxyfile], capture_output=True, text=True)
    count = 0
    for raw in (run.stdout + run.stderr).splitlines():
        if not raw.strip():
            continue
        count += 1
        m = LINE.match(raw)
        if m:
            name = re.sub(r"^.*/(include|tests/docs)/", r"\1/", m.group("file"))
            print(f"{name}:{m.group('line')}: {m.group('text')}")
        else:
            print(f"doxygen: {raw}")
    if count:
        print(f"check_docs: {count} Doxygen warnings: write the missing comments (plain // comments "
              "above the declaration or after it; docs/api/doxygen_filter.py says how they are read)")
        return 1
    if run.returncode != 0:
        print(f"check_docs: doxygen failed (exit status {run.returncode})")
        return 1
    print("check_docs: no Doxygen warning")
    return 0


if __name__ == "__main__":
    sys.exit(main())
