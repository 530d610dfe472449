#!/usr/bin/env python3
"""CPU of `mo2d forward` runs with and without the a-posteriori error estimate (issue 30):
medians over N runs of the JSON summary's cpu_seconds (the run) and estimated_error.cpu_seconds
(the second run of the estimate), per shipped scene at its own settings (docs/performance.md,
"Issue 30"). Usage: scripts/measure_error_estimate_cost.py build/mo2d [N]"""
import json
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

MO2D = sys.argv[1]
N = int(sys.argv[2]) if len(sys.argv) > 2 else 5
ROOT = Path(__file__).resolve().parent.parent
SCENES = ["double_fourbar", "gear_train", "sprung_double_pendulum", "rack_pinion", "engine"]


def run(scene, *flags):
    with tempfile.TemporaryDirectory() as out:
        subprocess.run([MO2D, "forward", str(ROOT / "mechanisms" / f"{scene}.yaml"), "--out", out,
                        *flags], check=True, capture_output=True)
        return json.loads((Path(out) / f"{scene}_forward.json").read_text())


print("| scene | method | run CPU ms (estimate off) | run CPU ms | estimate CPU ms | "
      "estimate / run | estimated error |")
print("|---|---|---|---|---|---|---|")
for scene in SCENES:
    off = [run(scene, "--error-estimate", "off")["cpu_seconds"] for _ in range(N)]
    on = [run(scene) for _ in range(N)]
    run_ms = statistics.median(j["cpu_seconds"] for j in on) * 1e3
    est_ms = statistics.median(j["estimated_error"]["cpu_seconds"] for j in on) * 1e3
    e = on[0]["estimated_error"]
    value = "not estimated" if e["value"] is None else f"{e['value']:.1e} ({e['variable']})"
    print(f"| {scene} | {on[0]['run']['integrator']} | {statistics.median(off) * 1e3:.1f} | "
          f"{run_ms:.1f} | {est_ms:.1f} | {est_ms / run_ms:.2f} | {value} |")
