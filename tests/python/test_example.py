"""The example script of docs/python.md runs (Agg backend) and draws the README's torque: the
same curve as the C++ example of the README figure (mechanisms/whitworth.cpp)."""
import importlib.util

import pytest

from conftest import ROOT


def test_whitworth_example_writes_the_figure(tmp_path):
    pytest.importorskip("matplotlib")
    spec = importlib.util.spec_from_file_location(
        "whitworth_torque", ROOT / "examples" / "python" / "whitworth_torque.py")
    example = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(example)
    out = tmp_path / "torque.png"
    r = example.main(str(out))
    assert out.read_bytes().startswith(b"\x89PNG")
    # the README plot's range: |torque| below 1.25 N m, both signs over a revolution
    tau = r["crank_pivot.torque"]
    assert 0.5 < tau.max() < 1.25 and -1.25 < tau.min() < -0.2
    assert r.t[-1] >= 8
