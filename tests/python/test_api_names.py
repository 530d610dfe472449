"""The package's names: mo2d.__version__ is the project's version, and one name per concept
across the command line, scene files and Python: a run's length is `duration` (run.duration of
scene files, `--duration`, mo2d.forward / inverse), for the runs of a System too; their old end
time t1= still works for one release, with a DeprecationWarning."""
import os
import pathlib
import re
import subprocess
import warnings

import pytest

import mo2d

ROOT = pathlib.Path(__file__).resolve().parents[2]


def pendulum_model():
    s = mo2d.System("pendulum")
    s.add_ground_node("O", (0, 0))
    s.add_body("link", nodes={"O": (0, 0), "P": (0.5, 0)}, mass=2.0, com="P")
    s.add_revolute("pivot", "ground.O", "link.O", actuated=True)
    s.add_coordinate("link.angle", rate=[("link.w", 1.0)])
    s.set_gravity((0, -9.81))
    return mo2d.build_model(s)


def test_version_is_the_projects():
    version = re.search(r"project\(mo2d VERSION ([0-9.]+)",
                        (ROOT / "CMakeLists.txt").read_text()).group(1)
    assert mo2d.__version__ == version
    cli = os.environ.get("MO2D_CLI")
    if cli:  # the command line prints the same one
        out = subprocess.run([cli, "--version"], capture_output=True, text=True, check=True)
        assert out.stdout.strip() == f"mo2d {mo2d.__version__}"


# The runs of a System and the keyword of their length (the end time t1 before).
RUNS = ["inverse_dynamics", "forward_dynamics", "inverse_dynamics_lagrange",
        "crosscheck_inverse", "crosscheck_forward"]


@pytest.mark.parametrize("name", RUNS)
def test_runs_take_duration_as_the_scene_runs_do(name):
    signature = getattr(mo2d, name).__doc__.splitlines()[0]
    assert "duration" in signature, signature
    for run in (mo2d.forward, mo2d.inverse):  # the scene runs (the command line's --duration)
        assert "duration" in run.__code__.co_varnames


def test_forward_dynamics_duration_is_counted_from_the_initial_time():
    model = pendulum_model()
    x0 = mo2d.consistent_state(model, velocities=[("link.w", 1.0)], t0=0.5)
    r = mo2d.forward_dynamics(model, x0, duration=1.0, samples=11, integrator="rk4", step=1e-2)
    assert r.t[0] == 0.5 and r.t[-1] == pytest.approx(1.5, abs=1e-12)
    # the deprecated end time: the same run, and a DeprecationWarning naming the new keyword
    with pytest.warns(DeprecationWarning, match=r"forward_dynamics\(t1=...\) is deprecated: give "
                      r"duration="):
        old = mo2d.forward_dynamics(model, x0, t1=1.5, samples=11, integrator="rk4", step=1e-2)
    assert old.csv() == r.csv()


def test_inverse_dynamics_duration_is_counted_from_t0():
    model = pendulum_model()
    motion = [("link.angle", "sin(t)")]
    r = mo2d.inverse_dynamics(model, motion, t0=1.0, duration=2.0, samples=5)
    assert list(r.t) == pytest.approx([1.0, 1.5, 2.0, 2.5, 3.0], abs=1e-12)
    with pytest.warns(DeprecationWarning, match="inverse_dynamics"):
        old = mo2d.inverse_dynamics(model, motion, t0=1.0, t1=3.0, samples=5)
    assert old.csv() == r.csv()
    # the default length is 1 s, as before (t1 = 1 from t0 = 0)
    assert mo2d.inverse_dynamics(model, motion, samples=3).t[-1] == 1.0
    lagrange = mo2d.build_model(pendulum_system_none(), reduction="none")
    r = mo2d.inverse_dynamics_lagrange(lagrange, motion, t0=1.0, duration=2.0, samples=5)
    assert r.t[-1] == pytest.approx(3.0, abs=1e-12)


def pendulum_system_none():
    s = mo2d.System("pendulum")
    s.add_ground_node("O", (0, 0))
    s.add_body("link", nodes={"O": (0, 0), "P": (0.5, 0)}, mass=2.0, com="P")
    s.add_revolute("pivot", "ground.O", "link.O", actuated=True)
    s.add_coordinate("link.angle", rate=[("link.w", 1.0)])
    return s


def test_both_names_or_none_are_refused():
    model = pendulum_model()
    x0 = mo2d.consistent_state(model, velocities=[("link.w", 1.0)])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        with pytest.raises(TypeError, match="duration= or t1= .deprecated., not both"):
            mo2d.forward_dynamics(model, x0, duration=1.0, t1=1.0)
        with pytest.raises(TypeError, match="not both"):
            mo2d.crosscheck_inverse(pendulum_system_none(), [("link.angle", "t")], duration=1,
                                    t1=1)
    with pytest.raises(TypeError, match="forward_dynamics: missing the argument duration"):
        mo2d.forward_dynamics(model, x0)
    with pytest.raises(TypeError, match="duration: a number of seconds, not str"):
        mo2d.forward_dynamics(model, x0, duration="1")


def test_deprecated_t1_is_an_error_where_warnings_are():
    model = pendulum_model()
    with warnings.catch_warnings():
        warnings.simplefilter("error", DeprecationWarning)
        with pytest.raises(DeprecationWarning):
            mo2d.inverse_dynamics(model, [("link.angle", "t")], t1=1.0, samples=3)
