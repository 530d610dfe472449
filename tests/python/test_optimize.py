"""mo2d.optimize (docs/design.md, "Optimization"): Berkof and Lowen's counterweights of a four-bar
against their closed form, a constraint active at the optimum, progress, and bad input."""
import pytest

import mo2d

pytestmark = pytest.mark.skipif(not hasattr(mo2d, "optimize"),
                                reason="mo2d built without NLopt (libnlopt-dev)")


def test_four_bar_counterweights_are_berkof_lowens(mechanisms):
    seen = []
    r = mo2d.optimize(str(mechanisms / "fourbar_balance.yaml"), minimize="rms.frame.shaking.F^2",
                      vary={"m1": (0, 2), "m3": (0, 3)}, set={"a": 0.12}, xtol=1e-10,
                      progress=seen.append)
    a, c = 0.12, 0.3
    assert r["x"]["m1"] == pytest.approx((0.2 + 0.5) * a / 2 / 0.05, abs=1e-7)
    assert r["x"]["m3"] == pytest.approx((0.4 + 0.5) * c / 2 / 0.1, abs=1e-7)
    assert r["stop"] == "converged" and r["method"] == "BOBYQA" and r["warnings"] == []
    assert len(seen) == r["evaluations"] and seen[-1]["best"] == r["value"]
    scene = mo2d.parse_scene(r["scene_text"])
    assert scene.parameters["m1"] == r["x"]["m1"]
    assert scene.parameters["a"] == 0.12


def test_active_constraint(mechanisms):
    # the lightest crank counterweight that keeps the shaking force's RMS within 1 N
    r = mo2d.optimize(str(mechanisms / "fourbar_balance.yaml"), minimize="m1 + m3",
                      vary={"m1": (0, 2), "m3": (0, 3)},
                      subject_to=["rms.frame.shaking.F <= 1"])
    assert r["method"] == "COBYLA" and r["feasible"]
    assert r["constraints"][0] == pytest.approx(0, abs=1e-7)


def test_bad_input(mechanisms):
    path = str(mechanisms / "fourbar_balance.yaml")
    with pytest.raises(mo2d.Error, match="did you mean 'm1'"):
        mo2d.optimize(path, minimize="m1", vary={"m11": (0, 1)})
    with pytest.raises(mo2d.Error, match="LO < HI"):
        mo2d.optimize(path, minimize="m1", vary={"m1": (1, 0)})
    with pytest.raises(mo2d.Error, match="column 6"):
        mo2d.optimize(path, minimize="m1 + rms.crank_pivot.torqe", vary={"m1": (0, 1)})
