#!/usr/bin/env python3
"""Run a tutorial of docs/tutorials/ as a test, as a reader runs it: its code blocks, in order,
in a fresh folder, with only the environment the page says to set.

A fenced block is acted on by the braces after its language:
  ```yaml {file=fourbar.yaml}   write the block to that file (any language)
  ```sh {env}                   the page's environment: each `export NAME=...` in it is emulated
                                (PATH: the folder of the mo2d executable, --bin, before the
                                system's; MO2D_SOURCE: the source tree; MO2D_BUILD: the build tree,
                                --prefix; PYTHONPATH: the Python package of the build, --python);
                                any other variable is an error
  ```sh {run}                   run it with bash -euo pipefail in a clean environment (env -i:
                                PATH=/usr/local/bin:/usr/bin:/bin, HOME, and what the {env} blocks
                                before it set); a non-zero exit fails the tutorial
  ```python {run}               save it to a file (block_LINE.py, or the name of {file=NAME run})
                                and run it as a script (`python3 FILE`, the Python that runs this
                                script) in the same clean environment
  ```text {expect}              each non-empty line must appear, as written, in the output of the
                                block run just before (stdout and stderr together)
Blocks without braces are prose. A page with the line <!-- tutorial: python --> needs the Python
package: without --python it is skipped (exit status 77); on another page, without --python, the
Python blocks that import mo2d are skipped (the README's example) and PYTHONPATH is left unset. Variables of the test harness pass
through to the blocks (sanitizer options, MPLBACKEND, CXXFLAGS/LDFLAGS of a sanitized build).
Each block has --timeout seconds (a block that hangs fails, it does not stall the suite).

  run_tutorial.py --bin build --work /tmp/t01 docs/tutorials/01-first-linkage.md
"""
import argparse
import os
import re
import shutil
import signal
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


# what the test harness sets for every block (not the page's business)
PASSED_THROUGH = ("LSAN_OPTIONS", "ASAN_OPTIONS", "UBSAN_OPTIONS", "MPLBACKEND",
                  "PYTHONDONTWRITEBYTECODE", "CXXFLAGS", "LDFLAGS", "TMPDIR")
SYSTEM_PATH = "/usr/local/bin:/usr/bin:/bin"
IMPORTS_MO2D = re.compile(r"^\s*(import|from)\s+mo2d\b", re.M)
EXPORT = re.compile(r"\bexport\s+((?:[A-Za-z_][A-Za-z0-9_]*=(?:\"[^\"]*\"|\S*)\s*)+)")


def clean_env():
    env = {"PATH": SYSTEM_PATH, "HOME": os.environ.get("HOME", "/tmp")}
    env.update({k: os.environ[k] for k in PASSED_THROUGH if k in os.environ})
    return env


def page_env(body, env, values, where):
    """Sets in env each variable an {env} block exports, to its value in this test."""
    names = [item.split("=", 1)[0] for m in EXPORT.finditer(body) for item in
             re.findall(r"[A-Za-z_][A-Za-z0-9_]*=(?:\"[^\"]*\"|\S*)", m.group(1))]
    if not names:
        sys.exit(f"{where}: an env block that exports nothing")
    for name in names:
        if name == "PYTHONPATH" and values[name] is None:
            continue  # no Python package here: the blocks that import it are skipped
        if name not in values or values[name] is None:
            sys.exit(f"{where}: the test cannot emulate `export {name}=...` "
                     f"(known here: {', '.join(k for k, v in values.items() if v is not None)})")
        env[name] = values[name]


def run_block(lang, body, cwd, env, timeout, script):
    if lang in ("sh", "bash"):
        cmd = ["bash", "-euo", "pipefail", "-c", body]
    else:  # saved to a file and run as a script, as a reader does (python3 sweep.py)
        with open(os.path.join(cwd, script), "w", encoding="utf-8") as f:
            f.write(body)
        cmd = [sys.executable, script]
    # its own session: on a timeout the whole group goes (a Dask cluster's workers too)
    p = subprocess.Popen(cmd, cwd=cwd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                         text=True, start_new_session=True)
    try:
        out, _ = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        out, _ = p.communicate()
        return None, out
    return p.returncode, out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("tutorial")
    ap.add_argument("--bin", required=True, help="folder of the mo2d executable")
    ap.add_argument("--work", required=True, help="folder to run in (emptied first)")
    ap.add_argument("--python", default="", help="folder of the mo2d Python package")
    ap.add_argument("--prefix", default="", help="build tree for find_package(mo2d)")
    ap.add_argument("--timeout", type=float, default=120, help="seconds per block")
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
    source = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    values = {  # what an `export NAME=...` of the page means in this test
        "PATH": os.path.abspath(a.bin) + os.pathsep + SYSTEM_PATH,
        "MO2D_SOURCE": source,
        "MO2D_BUILD": os.path.abspath(a.prefix) if a.prefix else None,
        "PYTHONPATH": os.path.abspath(a.python) if a.python else None,
    }
    env = clean_env()

    last = None  # output of the last block run
    skipping = False  # the last block to run was skipped (and so is its expect block)
    for lang, attrs, body, line in todo:
        where = f"{a.tutorial}:{line}"
        if "env" in attrs:
            page_env(body, env, values, where)
            continue
        if "file" in attrs and not ("run" in attrs and lang == "python"):
            path = os.path.join(a.work, attrs["file"])
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "w", encoding="utf-8") as f:
                f.write(body)
        if "run" in attrs and lang == "python" and not a.python and IMPORTS_MO2D.search(body):
            print(f"== {where}: skipped, needs mo2d's Python package (MO2D_PYTHON=OFF here)")
            last = ""
            skipping = True
            continue
        if "run" in attrs:
            skipping = False
            script = attrs.get("file") or f"block_{line}.py"
            print(f"== {where}: {body.strip().splitlines()[0]}", flush=True)
            code, last = run_block(lang, body, a.work, env, a.timeout, script)
            print(last, end="", flush=True)
            if code is None:
                sys.exit(f"{where}: the block did not end within {a.timeout:g} s")
            if code != 0:
                sys.exit(f"{where}: the block exited with status {code}")
        elif "expect" in attrs and not skipping:
            if last is None:
                sys.exit(f"{where}: an expect block with no block run before it")
            for want in filter(None, (s.strip() for s in body.splitlines())):
                if want not in last:
                    sys.exit(f"{where}: expected output line not found: {want!r}")
    print(f"{name}: every block ran as written")


if __name__ == "__main__":
    main()
