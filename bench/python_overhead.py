#!/usr/bin/env python3
"""Overhead of the Python binding per call (docs/python.md): the wall time of mo2d.inverse(scene)
against the same sequence in C++ (build/bench/mo2d_scene_bench, BM_SceneInverse), and the cost of
the smallest calls (a property, a column as a NumPy array).

    PYTHONPATH=build/python python3 bench/python_overhead.py [REPEATS]
"""
import pathlib
import statistics
import sys
import time

import mo2d

ROOT = pathlib.Path(__file__).resolve().parents[1]
FORWARD_INITIAL = "\ninitial:\n  velocities: {link.w: 1.0}\n"  # the same in scene_bench.cpp


def per_call(f, repeats, rounds=7):
    """Median over `rounds` of the mean CPU time of `repeats` calls (s): CPU time, like the
    "CPU" column of Google Benchmark, because the machine is shared (wall time depends on the
    load)."""
    times = []
    for _ in range(rounds):
        start = time.process_time()
        for _ in range(repeats):
            f()
        times.append((time.process_time() - start) / repeats)
    return statistics.median(times)


def main(repeats=200):
    for name in ("pendulum", "fourbar"):
        scene = mo2d.load_scene(ROOT / "mechanisms" / f"{name}.yaml")
        mo2d.inverse(scene)  # warm up
        t = per_call(lambda: mo2d.inverse(scene), repeats)
        print(f"mo2d.inverse({name}): {t * 1e6:9.1f} us CPU per call")
    scene_p = mo2d.load_scene(ROOT / "mechanisms" / "pendulum.yaml")
    r = mo2d.inverse(scene_p)
    # forward: the pendulum scene with an initial rate (as BM_SceneForward builds it)
    text = (ROOT / "mechanisms" / "pendulum.yaml").read_text() + FORWARD_INITIAL
    scene_f = mo2d.parse_scene(text, "pendulum_forward.yaml")
    t = per_call(lambda: mo2d.forward(scene_f), repeats)
    print(f"mo2d.forward(pendulum): {t * 1e6:9.1f} us CPU per call")
    t = per_call(lambda: r.cpu_seconds, 100000)
    print(f"r.cpu_seconds (a property):      {t * 1e9:9.0f} ns per call")
    t = per_call(lambda: r["pivot.torque"], 20000)
    print(f"r['pivot.torque'] (201 values):  {t * 1e9:9.0f} ns per call")
    law = mo2d.Law(["x"], lambda x, t: -2.0 * x[0])
    t = per_call(lambda: law([1.0], 0.0), 20000)
    print(f"law([1.0], 0.0) (Python -> C++ -> Python): {t * 1e9:6.0f} ns per call")


if __name__ == "__main__":
    main(*map(int, sys.argv[1:2]))
