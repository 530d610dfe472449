#!/usr/bin/env python3
"""Run a tutorial of docs/tutorials/ as a test: its code blocks, in order, in a fresh folder.

A fenced block is acted on by the braces after its language:
  ```yaml {file=fourbar.yaml}   write the block to that file (any language)
  ```sh {run}                   run it with bash -euo pipefail; a non-zero exit fails the tutorial
  ```python {run}               run it with the Python that runs this script
  ```text {expect}              each non-empty line must appear, as written, in the output of the
                                block run just before (stdout and stderr together)
Blocks without braces are prose. A page with the line <!-- tutorial: python --> needs the Python
package: without --python it is skipped (exit status 77). The folder's PATH starts with the folder of the mo2d executable
(--bin), PYTHONPATH with the Python package of the build (--python), and MO2D_BUILD names the
build tree to install from (--prefix), MO2D_SOURCE the source tree (mechanisms/ etc.).

  run_tutorial.py --bin build --work /tmp/t01 docs/tutorials/01-first-linkage.md
"""
import argparse
import os
import re
import shutil
import subprocess
import sys

FENCE = re.compile(r"^```(\w*)\s*(\{[^}]*\})?\s*$")


def blocks(text):
    """(language, attributes, body, line) of each fenced block."""
    out, lines, i = [], text.splitlines(), 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m or not m.group(1) and not m.group(2):
            i += 1
            continue
        start, body = i + 1, []
        i += 1
        while i < len(lines) and lines[i].rstrip() != "```":
            body.append(lines[i])
            i += 1
        attrs = {}
        for item in (m.group(2) or "{}")[1:-1].split():
            key, _, value = item.partition("=")
            attrs[key] = value
        out.append((m.group(1), attrs, "\n".join(body) + "\n", start))
        i += 1
    return out


def run_block(lang, body, cwd, env, timeout):
    cmd = ["bash", "-euo", "pipefail", "-c", body] if lang in ("sh", "bash") else [sys.executable, "-c", body]
    p = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout)
    return p.returncode, p.stdout + p.stderr


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("tutorial")
    ap.add_argument("--bin", required=True, help="folder of the mo2d executable")
    ap.add_argument("--work", required=True, help="folder to run in (emptied first)")
    ap.add_argument("--python", default="", help="folder of the mo2d Python package")
    ap.add_argument("--prefix", default="", help="build tree for find_package(mo2d)")
    ap.add_argument("--timeout", type=float, default=600, help="seconds per block")
    a = ap.parse_args()

    name = os.path.basename(a.tutorial)
    with open(a.tutorial, encoding="utf-8") as f:
        text = f.read()
    todo = blocks(text)
    if "<!-- tutorial: python -->" in text and not a.python:
        print(f"{name}: needs mo2d's Python package, not built here (MO2D_PYTHON=OFF): skipped")
        sys.exit(77)
    if not any("run" in attrs for _, attrs, _, _ in todo):
        sys.exit(f"{name}: no block to run (a tutorial the tests cannot fail)")
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    env = dict(os.environ)
    env["PATH"] = os.path.abspath(a.bin) + os.pathsep + env.get("PATH", "")
    if a.python:
        env["PYTHONPATH"] = os.path.abspath(a.python) + os.pathsep + env.get("PYTHONPATH", "")
    if a.prefix:
        env["MO2D_BUILD"] = os.path.abspath(a.prefix)
    env["MO2D_SOURCE"] = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

    last = None  # output of the last block run
    for lang, attrs, body, line in todo:
        where = f"{a.tutorial}:{line}"
        if "file" in attrs:
            path = os.path.join(a.work, attrs["file"])
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "w", encoding="utf-8") as f:
                f.write(body)
        elif "run" in attrs:
            print(f"== {where}: {body.strip().splitlines()[0]}", flush=True)
            code, last = run_block(lang, body, a.work, env, a.timeout)
            print(last, end="", flush=True)
            if code != 0:
                sys.exit(f"{where}: the block exited with status {code}")
        elif "expect" in attrs:
            if last is None:
                sys.exit(f"{where}: an expect block with no block run before it")
            for want in filter(None, (s.strip() for s in body.splitlines())):
                if want not in last:
                    sys.exit(f"{where}: expected output line not found: {want!r}")
    print(f"{name}: every block ran as written")


if __name__ == "__main__":
    main()
