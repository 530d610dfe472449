"""Run settings from Python (mo2d.forward(scene, duration=..., ...)): the path of the command
line's --duration etc. (the same numbers, the same refusals with the same messages), and the
physics of the runs they select."""
import math
import subprocess

import numpy as np
import pytest

import mo2d

# A point mass M at L on a massless link, released from the horizontal with angular rate W0.
M, L, G, W0 = 1.5, 0.8, 9.81, 1.0
PENDULUM = f"""name: swing
parameters: {{L: {L}, m: {M}, g: {G}}}
ground:
  O: [0, 0]
bodies:
  link: {{nodes: {{O: [0, 0], P: [L, 0]}}, mass: m, com: P}}
joints:
  pivot: {{type: revolute, node_a: ground.O, node_b: link.O, actuated: true}}
coordinates:
  link.angle: {{rate: {{link.w: 1}}}}
loads:
  gravity: [0, -g]
motion:
  link.angle: 0.5 * sin(3 * t)
initial:
  velocities: {{link.w: {W0}}}
run:
  solve: forward
  duration: 2
  samples: 101
"""


@pytest.fixture
def scene_path(tmp_path):
    path = tmp_path / "swing.yaml"
    path.write_text(PENDULUM)
    return path


def cli(mo2d_cli, *args):
    return subprocess.run([mo2d_cli, *map(str, args)], capture_output=True, text=True)


def test_settings_replace_the_scenes(scene_path):
    scene = mo2d.load_scene(scene_path)
    assert (scene.duration, scene.samples, scene.integrator) == (2.0, 101, "cvode_bdf")
    r = mo2d.forward(scene, duration=0.5, samples=11, integrator="rk4", step=1e-3)
    assert len(r) == 11 and r.t[-1] == 0.5
    assert r.stats["steps"] == 500 and r.stats["error_test_failures"] == 0  # rk4, 1 ms steps
    # the scene itself is unchanged; load_scene(run=...) gives the settings to every run
    assert scene.duration == 2.0 and len(mo2d.forward(scene)) == 101
    s2 = mo2d.load_scene(scene_path, run={"duration": 0.25, "integrator": "dopri5"})
    assert (s2.duration, s2.integrator) == (0.25, "dopri5")
    r2 = mo2d.forward(s2, samples=6)  # the scene's overrides stay, the new one is added
    assert len(r2) == 6 and r2.t[-1] == 0.25
    # dopri5 (not CVODE BDF, whose factorizations are its Newton matrices, fewer than its
    # evaluations): one factorization per evaluation
    assert r2.stats["factorizations"] == r2.stats["rhs_evaluations"]
    # (the scene names no method: it runs the default accuracy's choice, so BDF is named here)
    bdf = mo2d.forward(scene, integrator="cvode_bdf").stats
    assert bdf["factorizations"] < bdf["rhs_evaluations"]


@pytest.mark.parametrize("settings,flags", [
    (dict(duration=0.5, samples=11, integrator="rk4", step=1e-3),
     ["--duration", "0.5", "--samples", "11", "--integrator", "rk4", "--step", "0.001"]),
    (dict(duration="L / 2", integrator="cvode_adams", rtol=1e-6, atol=1e-9),
     ["--duration", "L / 2", "--integrator", "cvode_adams", "--rtol", "1e-06", "--atol", "1e-09"]),
    (dict(t0=1, duration=0.3, formulation="lagrange", max_steps=100000),
     ["--t0", "1", "--duration", "0.3", "--formulation", "lagrange", "--max-steps", "100000"]),
    (dict(duration=0.5, samples=11, accuracy=1e-6),
     ["--duration", "0.5", "--samples", "11", "--accuracy", "1e-06"]),
])
def test_forward_with_settings_is_the_command_line(scene_path, mo2d_cli, tmp_path, settings,
                                                   flags):
    out = tmp_path / "out"
    p = cli(mo2d_cli, "forward", scene_path, *flags, "--out", out)
    assert p.returncode == 0, p.stderr
    r = mo2d.forward(mo2d.load_scene(scene_path), **settings)
    assert r.csv() == (out / "swing_forward.csv").read_text()


def test_inverse_with_settings_is_the_command_line(scene_path, mo2d_cli, tmp_path):
    out = tmp_path / "out"
    p = cli(mo2d_cli, "inverse", scene_path, "--duration", "0.7", "--samples", "15",
            "--tolerance", "1e-13", "--out", out)
    assert p.returncode == 0, p.stderr
    r = mo2d.inverse(mo2d.load_scene(scene_path), duration=0.7, samples=15, tolerance=1e-13)
    assert r.csv() == (out / "swing_inverse.csv").read_text()
    # and the closed form tau = M L^2 theta'' + M g L cos(theta) at the 15 samples
    theta, dd = 0.5 * np.sin(3 * r.t), -4.5 * np.sin(3 * r.t)
    np.testing.assert_allclose(r["pivot.torque"], M * L**2 * dd + M * G * L * np.cos(theta),
                               rtol=1e-9, atol=1e-9)
    with pytest.raises(TypeError):
        mo2d.inverse(mo2d.load_scene(scene_path), integrator="rk4")  # not an inverse setting


@pytest.mark.parametrize("settings,flags", [
    (dict(duration=-1), ["--duration", "-1"]),
    (dict(samples=1), ["--samples", "1"]),
    (dict(samples=2.5), ["--samples", "2.5"]),
    (dict(integrator="rk5"), ["--integrator", "rk5"]),
    (dict(rtol=0), ["--rtol", "0"]),
    (dict(step="nope"), ["--step", "nope"]),
    (dict(max_seconds=-2), ["--max-seconds", "-2"]),
    # refused only once the model is known (check_scene_options): 1e9 rk4 steps over a budget
    (dict(integrator="rk4", step=1e-9, max_steps=1000),
     ["--integrator", "rk4", "--step", "1e-09", "--max-steps", "1000"]),
])
def test_bad_settings_are_the_command_lines_errors(scene_path, mo2d_cli, tmp_path, settings,
                                                   flags):
    p = cli(mo2d_cli, "forward", scene_path, *flags, "--out", tmp_path)
    assert p.returncode in (1, 2), p.stderr
    with pytest.raises(mo2d.Error) as info:
        mo2d.forward(mo2d.load_scene(scene_path), **settings)
    message = str(info.value)
    assert message.startswith("--")  # the setting it names, as the command line's flag
    # the CLI prints "mo2d: error: <message>[ (see mo2d --help)]"
    assert p.stderr.startswith(f"mo2d: error: {message}"), (p.stderr, message)


def test_bool_and_unknown_settings_are_refused(scene_path):
    scene = mo2d.load_scene(scene_path)
    with pytest.raises(TypeError, match="bool"):
        mo2d.forward(scene, samples=True)
    with pytest.raises(ValueError, match="'sample' is not a run setting"):
        mo2d.load_scene(scene_path, run={"sample": 3})


def test_the_integrators_selected_agree_on_the_physics(scene_path):
    """rk4 (1e-4 s steps), dopri5 and cvode_bdf (rtol 1e-10) give the same swing: the settings
    reach the integrator (their statistics differ) and each conserves the energy
    E = 1/2 M L^2 w^2 + M g L sin(theta)."""
    scene = mo2d.load_scene(scene_path)
    runs = {
        "rk4": mo2d.forward(scene, integrator="rk4", step=1e-4),
        "dopri5": mo2d.forward(scene, integrator="dopri5", rtol=1e-10, atol=1e-12),
        "cvode_bdf": mo2d.forward(scene, integrator="cvode_bdf", rtol=1e-10, atol=1e-12),
    }
    stats = {name: r.stats for name, r in runs.items()}
    assert stats["rk4"]["steps"] == 20000 and stats["rk4"]["error_test_failures"] == 0
    assert stats["cvode_bdf"]["factorizations"] < stats["cvode_bdf"]["rhs_evaluations"]
    assert stats["dopri5"]["factorizations"] == stats["dopri5"]["rhs_evaluations"]
    assert stats["dopri5"]["steps"] < 20000
    e0 = 0.5 * M * L**2 * W0**2
    for name, r in runs.items():
        theta, w = r["link.angle"], r["link.w"]
        e = 0.5 * M * L**2 * w**2 + M * G * L * np.sin(theta)
        assert np.max(np.abs(e - e0)) < 1e-7 * M * G * L, name
        np.testing.assert_allclose(theta, runs["rk4"]["link.angle"], rtol=0, atol=1e-7,
                                   err_msg=name)
    # a loose tolerance is really used: fewer steps, a larger error
    loose = mo2d.forward(scene, rtol=1e-4, atol=1e-6)
    assert loose.stats["steps"] < runs["cvode_bdf"].stats["steps"] / 3
    assert math.isfinite(loose["link.angle"][-1])


def test_forward_reports_its_estimated_error(scene_path):
    """A run with an accuracy carries its a-posteriori error estimate (issue 30); a run that names
    its integrator only with error_estimate="on"."""
    scene = mo2d.load_scene(str(scene_path))
    f = mo2d.forward(scene, duration=1, accuracy=1e-6)
    assert 0 < f.stats["estimated_error"] <= 1e-6
    assert f.stats["estimated_error_variable"] in f.columns
    assert f.stats["estimate_cpu_seconds"] > 0
    assert "second run" in f.stats["error_estimate"]
    plain = mo2d.forward(scene, duration=1, integrator="dopri5", rtol=1e-8)
    assert plain.stats["estimated_error"] is None
    assert "not estimated" in plain.stats["error_estimate"]
    on = mo2d.forward(scene, duration=1, integrator="dopri5", rtol=1e-8, error_estimate="on")
    assert on.stats["estimated_error"] > 0
    with pytest.raises(mo2d.Error, match="--error-estimate"):
        mo2d.forward(scene, error_estimate="yes")
