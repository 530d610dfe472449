#!/usr/bin/env python3
"""CPU time and error of the shipped forward scenes: the method they used before issue 14 item 4
(the flags of SCENES) against `--accuracy 1e-6` (the default accuracy: the stiffness test and
the method it chooses). Medians of REPEATS runs of the run's own CPU time (the
JSON summary's cpu_seconds: the solve, including the stiffness test, without start-up); error:
the largest difference of a position coordinate (m or rad) from a reference run, over all samples.

Usage: scripts/measure_defaults.py [MO2D_BINARY] [REPEATS]   (docs/performance.md, "item 4")
"""
import csv
import json
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MO2D = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build", "mo2d")
REPEATS = int(sys.argv[2]) if len(sys.argv) > 2 else 5

BDF = ["--integrator", "cvode_bdf"]
# scene: (the run settings it shipped with before, the reference run's settings)
SCENES = {
    "chain_drive": (BDF + ["--rtol", "1e-8", "--atol", "1e-10"], BDF + ["--rtol", "1e-12", "--atol", "1e-14"]),
    "door": (BDF + ["--rtol", "1e-9", "--atol", "1e-11"], BDF + ["--rtol", "1e-12", "--atol", "1e-14"]),
    "double_fourbar": (["--integrator", "rk4", "--step", "2e-3"], ["--integrator", "rk4", "--step", "5e-4"]),
    "engine": (BDF, BDF + ["--rtol", "1e-12", "--atol", "1e-14"]),
    "gear_train": (BDF + ["--rtol", "1e-10", "--atol", "1e-12"], BDF + ["--rtol", "1e-12", "--atol", "1e-14"]),
    "half_bike": (BDF + ["--rtol", "1e-7", "--atol", "1e-9"], BDF + ["--rtol", "1e-11", "--atol", "1e-13"]),
    "mass_spring_mass": (BDF + ["--rtol", "1e-10", "--atol", "1e-12"], BDF + ["--rtol", "1e-12", "--atol", "1e-14"]),
    "rack_pinion": (BDF, BDF + ["--rtol", "1e-12", "--atol", "1e-14"]),
    "ring_disc": (["--integrator", "rk4", "--step", "1e-3"], ["--integrator", "rk4", "--step", "2.5e-4"]),
    "rolling_disc": (BDF + ["--rtol", "1e-10", "--atol", "1e-12"], BDF + ["--rtol", "1e-12", "--atol", "1e-14"]),
    "slider_crank_control": (BDF, BDF + ["--rtol", "1e-12", "--atol", "1e-14"]),
    "sprung_double_pendulum": (BDF, BDF + ["--rtol", "1e-12", "--atol", "1e-14"]),
}


def run(scene, flags, out):
    subprocess.run([MO2D, "forward", os.path.join(ROOT, "mechanisms", scene + ".yaml"), "--out", out]
                   + flags, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(os.path.join(out, scene + "_forward.json")) as f:
        summary = json.load(f)
    with open(os.path.join(out, scene + "_forward.csv")) as f:
        rows = list(csv.reader(f))
    units = {c["name"]: c["unit"] for c in summary["columns"]} if isinstance(
        summary["columns"], list) else summary["columns"]
    return summary, rows, units


def positions(rows, units):
    header = rows[0]
    cols = [i for i, h in enumerate(header)
            if units.get(h) in ("m", "rad") and not h.startswith(("residual", "energy", "work"))]
    return header, cols, [[float(r[i]) for i in cols] for r in rows[1:]]


def measure(scene, flags):
    times, summary, rows, units = [], None, None, None
    for _ in range(REPEATS):
        with tempfile.TemporaryDirectory() as out:
            summary, rows, units = run(scene, flags, out)
        times.append(summary["cpu_seconds"])
    return statistics.median(times), summary, rows, units


def main():
    print("| scene | before: method | CPU ms | error | accuracy 1e-6: method | CPU ms | error | ratio |")
    print("|---|---|---|---|---|---|---|---|")
    for scene, (old, ref) in SCENES.items():
        with tempfile.TemporaryDirectory() as out:
            _, ref_rows, units = run(scene, ref, out)
        _, cols, ref_q = positions(ref_rows, units)
        cells = []
        for flags in (old, ["--accuracy", "1e-6"]):
            t, summary, rows, _ = measure(scene, flags)
            _, _, q = positions(rows, units)
            err = max(abs(a - b) for ra, rb in zip(q, ref_q) for a, b in zip(ra, rb))
            r = summary["run"]
            how = r.get("method") or " ".join(flags[1::2]) or r["integrator"]
            if r.get("method"):
                how = r["integrator"] + " (" + how.split(" (")[0] + ")"
            cells.append((how, t, err))
        (ho, to, eo), (hn, tn, en) = cells
        print(f"| {scene} | {ho} | {1e3 * to:.2f} | {eo:.1e} | {hn} | {1e3 * tn:.2f} | {en:.1e} | "
              f"{to / tn:.1f}x |")


if __name__ == "__main__":
    main()
