"""Scene files from Python: the same numbers as the mo2d command line, overrides, NumPy columns."""
import csv
import io
import math
import subprocess

import numpy as np
import pytest

import mo2d


def test_inverse_of_a_scene_has_the_columns_of_the_csv(mechanisms):
    scene = mo2d.load_scene(mechanisms / "fourbar.yaml")
    assert scene.name == "fourbar" and scene.solve == "inverse"
    r = mo2d.inverse(scene)
    assert r.kind == "inverse"
    assert r.columns[0] == "t"
    assert len(r.t) == 401 and r.t[0] == 0.0 and r.t[-1] == pytest.approx(2.0)
    torque = r["crank_pivot.torque"]
    assert isinstance(torque, np.ndarray) and torque.shape == (401,)
    assert r.effort_labels == ["crank_pivot.torque"]
    np.testing.assert_array_equal(r.efforts[:, 0], torque)
    assert r.reactions.shape == (401, len(r.reaction_labels))
    # the header of the CSV the CLI writes is r.columns, its rows the columns
    rows = list(csv.reader(io.StringIO(r.csv())))
    assert rows[0] == r.columns
    for k, label in enumerate(r.columns):
        assert float(rows[5][k]) == r[label][4], label
    assert r.stats["cpu_seconds"] > 0 and r.cpu_seconds == r.stats["cpu_seconds"]


def test_pendulum_torque_is_the_closed_form(mechanisms):
    # point mass m at L on a massless link: tau = m L^2 theta'' + m g L cos(theta)
    r = mo2d.inverse(mo2d.load_scene(mechanisms / "pendulum.yaml", set={"m": 2.0, "L": 0.5}))
    t = r.t
    theta = 0.5 * np.sin(3 * t) + t**2
    dd = -4.5 * np.sin(3 * t) + 2
    m, L, g = 2.0, 0.5, 9.81
    np.testing.assert_allclose(r["pivot.torque"], m * L**2 * dd + m * g * L * np.cos(theta),
                               rtol=1e-9, atol=1e-9)


def test_extremes_are_located_between_the_samples(mechanisms):
    # the pendulum's torque tau = m L^2 theta'' + m g L cos(theta): its peaks where tau' = 0
    r = mo2d.inverse(mo2d.load_scene(mechanisms / "pendulum.yaml", set={"m": 2.0, "L": 0.5}))
    m, L, g = 2.0, 0.5, 9.81
    th = lambda t: 0.5 * np.sin(3 * t) + t**2
    d1 = lambda t: 1.5 * np.cos(3 * t) + 2 * t
    d2 = lambda t: -4.5 * np.sin(3 * t) + 2
    tau = lambda t: m * L**2 * d2(t) + m * g * L * np.cos(th(t))
    dtau = lambda t: m * L**2 * (-13.5 * np.cos(3 * t)) - m * g * L * np.sin(th(t)) * d1(t)
    e = r.extremes["pivot.torque"]
    assert e["located"] and set(r.extremes) == set(r.effort_labels + r.reaction_labels)
    for key in ("max", "min"):
        t = e["t_" + key]
        if t in (r.t[0], r.t[-1]):
            continue
        h = 1e-6  # Newton on tau' with a difference quotient for tau''
        tr = t
        for _ in range(8):
            tr -= dtau(tr) * 2 * h / (dtau(tr + h) - dtau(tr - h))
        assert abs(t - tr) < 1e-10 and abs(e[key] - tau(tr)) < 1e-10
        assert abs(e["sampled_" + key] - e[key]) > 1e-7


def test_overrides_are_expressions_or_numbers(mechanisms):
    a = mo2d.load_scene(mechanisms / "pendulum.yaml", set={"m": "2*L", "L": 0.75})
    assert a.parameters["m"] == 1.5 and a.parameters["L"] == 0.75


def test_same_numbers_as_the_command_line(mechanisms, mo2d_cli, tmp_path):
    subprocess.run([mo2d_cli, "inverse", str(mechanisms / "pendulum.yaml"), "--set", "m=3",
                    "--out", str(tmp_path)], check=True, capture_output=True)
    text = (tmp_path / "pendulum_inverse.csv").read_text()
    r = mo2d.inverse(mo2d.load_scene(mechanisms / "pendulum.yaml", set={"m": 3}))
    assert r.csv() == text


def test_forward_of_a_scene(mechanisms):
    r = mo2d.forward(mo2d.load_scene(mechanisms / "double_fourbar.yaml"))
    assert r.kind == "forward"
    assert "energy.kinetic" in r.columns
    assert r.stats["steps"] > 0
    # energy balance of the forward run: kinetic + potential - work of inputs and loads
    # + dissipated is constant
    e = (r["energy.kinetic"] + r["energy.potential"] - r["work.inputs"] - r["work.loads"]
         - r["work.constraints"] + r["energy.dissipated"])
    assert np.max(np.abs(e - e[0])) < 1e-5 * max(1.0, np.max(np.abs(r["energy.kinetic"])))


def test_to_pandas(mechanisms):
    pandas = pytest.importorskip("pandas")
    r = mo2d.inverse(mo2d.load_scene(mechanisms / "pendulum.yaml"))
    df = r.to_pandas()
    assert isinstance(df, pandas.DataFrame)
    assert list(df.columns) == r.columns
    np.testing.assert_array_equal(df["pivot.torque"].to_numpy(), r["pivot.torque"])


def test_crosscheck_of_a_scene(mechanisms):
    c = mo2d.crosscheck(mo2d.load_scene(mechanisms / "fourbar.yaml"))
    assert c["agree"], c["failures"]
    assert c["effort_labels"] == ["crank_pivot.torque"]
    assert 0 < c["effort_rms"] < 0.01 and math.isfinite(c["reaction_max"])


# A scene that solves forward is cross-checked forward (was: refused, "the model has 1 DOF and
# 'motion' prescribes 0"), judged by the command line's tolerances, which a caller can tighten.
def test_crosscheck_of_a_forward_scene(mechanisms):
    scene = mo2d.load_scene(mechanisms / "slider_crank_control.yaml")
    c = mo2d.crosscheck(scene)
    assert c["agree"] and c["box2d_cause"] == "", c
    assert (c["position_tolerance"], c["angle_tolerance"]) == (1e-2, 2e-2)
    assert 0 < c["relative_position_error"] < 1e-2 and len(c["time"]) == 201
    strict = mo2d.crosscheck(scene, position_tolerance=1e-12)
    assert not strict["agree"]
    with pytest.raises(mo2d.Error, match="prescribes 0"):
        mo2d.crosscheck(scene, forward=False)
