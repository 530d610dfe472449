"""The designer's measures from Python (docs/design.md): mo2d.four_bar's closed forms, the
columns of a scene with a design: block, measures=True, and r.design."""
import math

import numpy as np
import pytest

import mo2d


def test_four_bar_closed_forms():
    d = mo2d.four_bar(ground=0.4, input=0.1, coupler=0.35, output=0.3)
    assert d["grashof"] == "crank-rocker" and d["input_rotates"] and d["input_range"] is None
    # the cosine law at theta = 0 and pi: |A - B0| = d - a and d + a
    b, c = 0.35, 0.3
    assert d["min_transmission"] == pytest.approx(math.acos((b * b + c * c - 0.3**2) / (2 * b * c)))
    assert d["max_transmission"] == pytest.approx(math.acos((b * b + c * c - 0.5**2) / (2 * b * c)))
    assert mo2d.transmission_angle(0.4, 0.1, 0.35, 0.3, 0.0) == pytest.approx(d["min_transmission"])
    assert mo2d.four_bar(0.4, 0.3, 0.35, 0.32)["grashof"] == "triple-rocker"
    with pytest.raises(mo2d.Error, match="cannot close"):
        mo2d.four_bar(1.0, 0.1, 0.2, 0.3)


def test_scene_design_block_and_measures(mechanisms):
    r = mo2d.inverse(mo2d.load_scene(mechanisms / "fourbar_design.yaml"))
    s = r.design
    assert s["four_bars"]["loop"]["grashof"] == "crank-rocker"
    e = s["efforts"]["crank_pivot.torque"]
    tau = r["crank_pivot.torque"]
    assert e["peak_to_peak"] == pytest.approx(tau.max() - tau.min())
    assert e["flywheel_inertia"] == pytest.approx(
        e["energy_fluctuation"] / (0.02 * e["mean_speed"] ** 2))
    # the shaking force: minus the ground joints' reactions (the force of the ground on the links)
    for axis in ("x", "y"):
        np.testing.assert_allclose(
            r["frame.shaking.F" + axis],
            -r["crank_pivot.F" + axis] - r["rocker_pivot.F" + axis], rtol=0, atol=1e-12)
    assert r["loop.transmission_angle"].min() == pytest.approx(
        s["four_bars"]["loop"]["run_min_transmission"])
    # a scene without a design block: no summary unless measures=True
    plain = mo2d.load_scene(mechanisms / "slider_crank.yaml")
    assert mo2d.inverse(plain).design is None
    m = mo2d.inverse(plain, measures=True)
    assert "frame.shaking.M" in m.columns and "rail.load" in m.columns
    assert set(m.design["efforts"]) == {"crank_pivot.torque"}
