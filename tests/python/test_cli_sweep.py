"""mo2d sweep (the C++ tool execs python3 -m mo2d sweep): a CSV on a local cluster of 2 worker
processes, and usage errors with status 2."""
import subprocess

import numpy as np
import pytest


def test_sweep_command_line(mechanisms, mo2d_cli, tmp_path):
    pytest.importorskip("distributed")
    out = tmp_path / "sweep.csv"
    p = subprocess.run([mo2d_cli, "sweep", str(mechanisms / "pendulum.yaml"), "--set", "m=1:2:3",
                        "--set", "L=0.5,1", "--jobs", "2", "-o", str(out)],
                       capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    assert "6 runs, 0 failed" in p.stdout
    lines = out.read_text().splitlines()
    header = lines[0].split(",")
    assert header[:4] == ["m", "L", "ok", "error"] and len(lines) == 7
    rows = [dict(zip(header, line.split(","))) for line in lines[1:]]
    assert [(float(r["m"]), float(r["L"])) for r in rows] == [
        (m, L) for m in (1.0, 1.5, 2.0) for L in (0.5, 1.0)]
    peaks = np.array([float(r["peak.pivot.torque"]) for r in rows])
    assert peaks[4] == pytest.approx(2 * peaks[0])  # m = 2 against m = 1 at L = 0.5


def test_sweep_command_line_usage_error(mechanisms, mo2d_cli):
    p = subprocess.run([mo2d_cli, "sweep", str(mechanisms / "pendulum.yaml"), "--set", "m"],
                       capture_output=True, text=True, timeout=60)
    assert p.returncode == 2 and "NAME=VALUES" in p.stderr
    p = subprocess.run([mo2d_cli, "sweep", str(mechanisms / "pendulum.yaml"), "--set", "mass=1,2"],
                       capture_output=True, text=True, timeout=60)
    assert p.returncode == 2 and "--set mass: not a parameter" in p.stderr, p.stderr
    p = subprocess.run([mo2d_cli, "sweep", "--help"], capture_output=True, text=True, timeout=60)
    assert p.returncode == 0 and "--scheduler" in p.stdout
