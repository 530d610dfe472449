"""mo2d sweep (the C++ tool execs python3 -m mo2d sweep): a CSV on a local cluster of 2 worker
processes, and usage errors with status 2."""
import subprocess
import time

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


def _sweep(mo2d_cli, *args, timeout=60):
    start = time.monotonic()
    p = subprocess.run([mo2d_cli, "sweep", *map(str, args)], capture_output=True, text=True,
                       timeout=timeout)
    return p, time.monotonic() - start


# Issue 31: `-o DIR` failed with IsADirectoryError after all runs, losing every result.
def test_sweep_output_folder_gets_the_csv(mechanisms, mo2d_cli, tmp_path):
    p, _ = _sweep(mo2d_cli, mechanisms / "pendulum.yaml", "--set", "m=1,2", "--jobs", "0",
                  "-o", tmp_path)
    assert p.returncode == 0, p.stderr
    lines = (tmp_path / "pendulum_sweep.csv").read_text().splitlines()
    assert len(lines) == 3 and lines[0].startswith("m,ok,error")
    assert [f.name for f in tmp_path.iterdir()] == ["pendulum_sweep.csv"]  # no .partial left


# An output path that cannot be written and an unreachable scheduler fail before the first run,
# in one line (was: a traceback after every run; after dask's 30 s timeout).
def test_sweep_checks_output_and_scheduler_first(mechanisms, mo2d_cli, tmp_path):
    p, seconds = _sweep(mo2d_cli, mechanisms / "pendulum.yaml", "--set", "m=1:2:1000",
                        "--jobs", "0", "-o", tmp_path / "missing" / "out.csv")
    assert p.returncode == 1 and seconds < 5, (p.returncode, seconds)
    assert "cannot write there" in p.stderr and "Traceback" not in p.stderr, p.stderr
    p, seconds = _sweep(mo2d_cli, mechanisms / "pendulum.yaml", "--set", "m=1,2",
                        "--scheduler", "tcp://127.0.0.1:9", "-o", tmp_path / "s.csv")
    assert p.returncode == 1 and seconds < 8, (p.returncode, seconds, p.stderr)
    assert "cannot reach the Dask scheduler at 127.0.0.1:9" in p.stderr, p.stderr
    assert "Traceback" not in p.stderr and not list(tmp_path.iterdir())


# A grid of 1e9 values ended in a MemoryError after 45 s: refused before anything is made.
def test_sweep_grid_size_guard(mechanisms, mo2d_cli, tmp_path):
    p, seconds = _sweep(mo2d_cli, mechanisms / "pendulum.yaml", "--set", "m=1:2:1000000000",
                        "-o", tmp_path / "s.csv")
    assert p.returncode == 2 and seconds < 5, (p.returncode, seconds)
    assert "1e+09 runs, more than the limit of 1000000" in p.stderr, p.stderr
    p, _ = _sweep(mo2d_cli, mechanisms / "pendulum.yaml", "--set", "m=1:2:1001",
                  "--set", "L=1:2:1000", "-o", tmp_path / "s.csv")
    assert p.returncode == 2 and "the grid 1001 (m) x 1000 (L) has 1.001e+06 runs" in p.stderr
    p, _ = _sweep(mo2d_cli, mechanisms / "pendulum.yaml", "--set", "m=1:2:3", "--max-runs", "2",
                  "-o", tmp_path / "s.csv")
    assert p.returncode == 2 and "more than the limit of 2" in p.stderr, p.stderr
