"""Exact sensitivities from Python (mo2d.inverse(..., sensitivity=[...]), docs/design.md,
"Sensitivities"): the derivative columns against central differences of runs with set=, the
shaking force's derivative from the ground reactions', and the refusal of a geometric parameter."""
import numpy as np
import pytest

import mo2d


def test_derivative_columns_against_central_differences(mechanisms):
    path = mechanisms / "slider_crank.yaml"
    r = mo2d.inverse(mo2d.load_scene(path), sensitivity="m_slider, gravity")
    for name, p in (("m_slider", 1.0), ("gravity", 9.81)):
        h = 1e-2 * p  # exact for a dependence of degree <= 2: rounding only (docs/design.md)
        up = mo2d.inverse(mo2d.load_scene(path, set={name: p + h}))
        dn = mo2d.inverse(mo2d.load_scene(path, set={name: p - h}))
        for col in ("crank_pivot.torque", "rail.Fy", "crank_pivot.Fx"):
            fd = (up[col] - dn[col]) / (2 * h)
            # (a column that does not depend on it: its derivative's rounding against |col| / p)
            scale = max(np.abs(fd).max(), np.abs(r[col]).max() / p)
            np.testing.assert_allclose(r[f"d({col})/d({name})"], fd, rtol=0, atol=1e-7 * scale)
    # the frame's shaking force is minus the ground joints' reactions: so is its derivative
    up = mo2d.inverse(mo2d.load_scene(path, set={"m_slider": 1.01}), measures=True)
    dn = mo2d.inverse(mo2d.load_scene(path, set={"m_slider": 0.99}), measures=True)
    for axis in ("x", "y"):
        fd = (up["frame.shaking.F" + axis] - dn["frame.shaking.F" + axis]) / 0.02
        d = -r[f"d(crank_pivot.F{axis})/d(m_slider)"] - r[f"d(rail.F{axis})/d(m_slider)"]
        np.testing.assert_allclose(d, fd, rtol=0, atol=1e-7 * np.abs(fd).max())


def test_geometric_parameter_is_refused(mechanisms):
    with pytest.raises(mo2d.Error, match=r"sensitivity to 'r': it changes the geometry"):
        mo2d.inverse(mo2d.load_scene(mechanisms / "slider_crank.yaml"), sensitivity=["r"])
