#!/usr/bin/env python3
"""CLI overhead of mo2d: process CPU (user + system, from the child's rusage) per run, minus the
solver's own CPU time (`cpu_seconds` of the JSON summary, when the command writes one).

    scripts/cli_overhead.py [--runs 30] [--mo2d build/mo2d] [-- COMMAND ARGS...]

Without a command it measures the three of docs/performance.md ("CLI start-up"):
`mo2d --version`, `mo2d info mechanisms/double_fourbar.yaml` and
`mo2d forward mechanisms/double_fourbar.yaml --integrator dopri5 --rtol 3e-6`.
Prints the median and the quartiles over the runs, in ms, plus the page faults.
"""
import argparse
import glob
import json
import os
import statistics
import subprocess
import sys
import tempfile

DEFAULTS = [
    ["--version"],
    ["info", "mechanisms/double_fourbar.yaml"],
    ["forward", "mechanisms/double_fourbar.yaml", "--integrator", "dopri5", "--rtol", "3e-6"],
]


def solver_seconds(out_dir):
    """The summed cpu_seconds of the JSON summaries written under out_dir (0 if none)."""
    total = 0.0
    for path in glob.glob(os.path.join(out_dir, "*.json")):
        with open(path, encoding="utf-8") as f:
            total += float(json.load(f).get("cpu_seconds", 0.0))
    return total


def one_run(cmd, out_dir):
    for path in glob.glob(os.path.join(out_dir, "*")):
        os.remove(path)
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, status, usage = os.wait4(proc.pid, 0)
    if status != 0:
        sys.exit(f"{' '.join(cmd)}: exit status {status}")
    cpu = usage.ru_utime + usage.ru_stime
    return cpu, solver_seconds(out_dir), usage.ru_minflt


def measure(mo2d, args, runs):
    with tempfile.TemporaryDirectory() as out_dir:
        cmd = [mo2d] + args
        if args and args[0] in ("forward", "inverse"):
            cmd += ["--out", out_dir]
        one_run(cmd, out_dir)  # warm the page cache
        rows = [one_run(cmd, out_dir) for _ in range(runs)]
    over = sorted(1e3 * (cpu - solve) for cpu, solve, _ in rows)
    solve = statistics.median(1e3 * s for _, s, _ in rows)
    faults = statistics.median(f for _, _, f in rows)
    q = statistics.quantiles(over, n=4)
    print(f"{' '.join(['mo2d'] + args)}: overhead median {statistics.median(over):.2f} ms "
          f"(quartiles {q[0]:.2f}-{q[2]:.2f}), solver {solve:.2f} ms, "
          f"{faults:.0f} minor page faults, {runs} runs")


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--runs", type=int, default=30)
    p.add_argument("--mo2d", default="build/mo2d")
    p.add_argument("command", nargs="*")
    a = p.parse_args()
    for args in [a.command] if a.command else DEFAULTS:
        measure(a.mo2d, args, a.runs)


if __name__ == "__main__":
    main()
