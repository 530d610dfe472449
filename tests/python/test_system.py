"""Mechanisms built in Python: closed forms, and state-dependent loads written as Python callables
and expressions checked against the built-in linear laws (a second formulation)."""
import math

import numpy as np
import pytest

import mo2d

M, L, G, C = 2.0, 0.5, 9.81, 0.3


def pendulum(damper=None, damping=0.0):
    """Point mass M at L on a massless link about ground O; optionally a torsional damper at the
    pivot, linear (damping) or given as a law (damper)."""
    s = mo2d.System("pendulum")
    s.add_ground_node("O", (0, 0))
    s.add_body("link", nodes={"O": (0, 0), "P": (L, 0)}, mass=M, com="P")
    s.add_revolute("pivot", "ground.O", "link.O", actuated=True)
    s.add_coordinate("link.angle", rate=[("link.w", 1.0)])
    s.set_gravity((0, -G))
    if damper is not None or damping:
        s.add_torsional_spring("damper", "pivot", damping=damping, torque=damper)
    return s


MOTION = [("link.angle", "0.5 * sin(3 * t) + t^2")]


def closed_form(t, c=0.0):
    theta = 0.5 * np.sin(3 * t) + t**2
    w = 1.5 * np.cos(3 * t) + 2 * t
    dd = -4.5 * np.sin(3 * t) + 2
    return M * L**2 * dd + M * G * L * np.cos(theta) + c * w


def test_inverse_dynamics_of_a_python_system_is_the_closed_form():
    model = mo2d.build_model(pendulum())
    assert model.dof == 1 and model.input_labels == ["pivot.torque"]
    r = mo2d.inverse_dynamics(model, MOTION, duration=2.0, samples=201)
    np.testing.assert_allclose(r["pivot.torque"], closed_form(r.t), rtol=1e-9, atol=1e-9)


def test_motion_as_a_callable_with_its_derivatives():
    model = mo2d.build_model(pendulum())
    motion = [("link.angle", lambda t: (0.5 * math.sin(3 * t) + t * t,
                                        1.5 * math.cos(3 * t) + 2 * t,
                                        -4.5 * math.sin(3 * t) + 2))]
    r = mo2d.inverse_dynamics(model, motion, duration=2.0, samples=51)
    np.testing.assert_allclose(r["pivot.torque"], closed_form(r.t), rtol=1e-9, atol=1e-9)


@pytest.mark.parametrize("damper", [
    mo2d.Law(["rate"], lambda x, t: -C * x[0]),  # a Python callable of the damper's rate
    "-c * rate",                                  # an expression (params below)
    mo2d.Law(["link.w"], lambda x, t: -C * x[0]),  # a state label (pivot on the ground)
])
def test_state_dependent_load_from_python_in_inverse_dynamics(damper):
    model = mo2d.build_model(pendulum(damper=damper) if not isinstance(damper, str) else
                             _expression_pendulum(damper))
    r = mo2d.inverse_dynamics(model, MOTION, duration=2.0, samples=101)
    np.testing.assert_allclose(r["pivot.torque"], closed_form(r.t, C), rtol=1e-9, atol=1e-9)


def _expression_pendulum(text):
    s = pendulum()
    s.add_torsional_spring("damper", "pivot", torque=text, params={"c": C})
    return s


def test_python_damper_in_forward_dynamics_matches_the_linear_damper():
    def run(system):
        model = mo2d.build_model(system)
        x0 = mo2d.consistent_state(model, positions=[("link.angle", 0.2)],
                                   velocities=[("link.w", 1.0)])
        # a fixed step: both runs take the same steps, so only the damper's torque can differ
        return mo2d.forward_dynamics(model, x0, duration=1.0, samples=21, integrator="rk4",
                                     step=1e-3)

    calls = []

    def damper(x, t):
        calls.append(t)
        return -C * x[0]

    a = run(pendulum(damper=mo2d.Law(["rate"], damper)))
    b = run(pendulum(damping=C))
    assert len(calls) > 20  # the Python function was evaluated by the integrator
    np.testing.assert_allclose(a["link.angle"], b["link.angle"], rtol=0, atol=1e-12)
    assert a["energy.dissipated"][-1] == pytest.approx(0, abs=1e-12)  # a law's work is load work
    np.testing.assert_allclose(-a["work.loads"][-1], b["energy.dissipated"][-1], rtol=1e-9)


def test_forward_efforts_from_python():
    model = mo2d.build_model(pendulum())
    x0 = mo2d.consistent_state(model, positions=[("link.angle", 0.0)],
                               velocities=[("link.w", 0.0)])
    # the torque that holds the mass still at the horizontal: M g L
    r = mo2d.forward_dynamics(model, x0, duration=0.5, samples=11,
                              efforts=[("pivot.torque", M * G * L)])
    assert np.max(np.abs(r["link.angle"])) < 1e-8
    r = mo2d.forward_dynamics(model, x0, duration=0.5, samples=11,
                              efforts=[("pivot.torque", lambda t: M * G * L)])
    assert np.max(np.abs(r["link.angle"])) < 1e-8


def test_law_value_and_labels():
    law = mo2d.Law("-k * crank.w + t", params={"k": 2.0})
    assert law.labels == ["crank.w"] and law.depends_on_state
    assert law([3.0], 1.0) == -5.0


def test_four_bar_built_in_python_agrees_with_box2d():
    s = mo2d.System("fourbar")
    a, b, c, d = 0.1, 0.35, 0.3, 0.4
    l = math.hypot(d, a)
    x = (b * b - c * c + l * l) / (2 * l)
    h = math.sqrt(b * b - x * x)
    B = (x * d / l + h * a / l, a - x * a / l + h * d / l)
    s.add_ground_node("A0", (0, 0))
    s.add_ground_node("B0", (d, 0))
    s.add_body("crank", nodes={"O": (0, 0), "A": (0, a)}, mass=0.2, inertia=0.2 * a * a / 12,
               com=("O", "A", 0.5))
    s.add_body("coupler", nodes={"A": (0, a), "B": B}, mass=0.5, inertia=0.5 * b * b / 12,
               com=("A", "B", 0.5))
    s.add_body("rocker", nodes={"O": (d, 0), "B": B}, mass=0.4, inertia=0.4 * c * c / 12,
               com=("O", "B", 0.5))
    s.add_revolute("crank_pivot", "ground.A0", "crank.O", actuated=True)
    s.add_revolute("crank_pin", "crank.A", "coupler.A")
    s.add_revolute("rocker_pin", "coupler.B", "rocker.B")
    s.add_revolute("rocker_pivot", "ground.B0", "rocker.O")
    s.add_coordinate("crank.angle", rate=[("crank.w", 1.0)])
    s.set_gravity((0, -9.81))
    report = mo2d.crosscheck_inverse(s, [("crank.angle", "pi/2 + 2*pi*t")], duration=1.0)
    assert report["agree"], report["failures"]
    # and the same numbers as the scene file of the same mechanism
    model = mo2d.build_model(s)
    r = mo2d.inverse_dynamics(model, [("crank.angle", "pi/2 + 2*pi*t")], duration=2.0, samples=401)
    from conftest import MECHANISMS
    q = mo2d.inverse(mo2d.load_scene(MECHANISMS / "fourbar.yaml"))
    np.testing.assert_allclose(r["crank_pivot.torque"], q["crank_pivot.torque"], rtol=1e-9,
                               atol=1e-12)


def test_python_law_derivatives_reach_the_bdf_newton_matrix():
    """A stiff, heavily damped torsional spring written as a Python callable: the fast mode
    (-c/I = -2000 1/s) is far shorter than the steps BDF takes on the slow one (-k/c = -10 1/s),
    so cvode_bdf's Newton iteration converges only with the law's derivatives in its matrix, which
    mo2d takes by central differences of the callable (laws.cpp, along_curve). Without them (zero
    derivatives) the run needs several times the evaluations. The motion must equal the
    expression law's."""
    k, c = 1e4, 1e3

    def run(torque):
        s = pendulum()
        s.add_torsional_spring("stiff", "pivot", torque=torque, params={"k": k, "c": c})
        model = mo2d.build_model(s)
        x0 = mo2d.consistent_state(model, positions=[("link.angle", 0.05)],
                                   velocities=[("link.w", 0.0)])
        return mo2d.forward_dynamics(model, x0, duration=0.5, samples=11, integrator="cvode_bdf",
                                     rtol=1e-7, atol=1e-9)

    a = run(mo2d.Law(["angle", "rate"], lambda x, t: -k * x[0] - c * x[1]))
    b = run("-k * angle - c * rate")
    np.testing.assert_allclose(a["link.angle"], b["link.angle"], rtol=0, atol=1e-6)
    print("evaluations: callable", a.stats["rhs_evaluations"], "expression",
          b.stats["rhs_evaluations"])
    assert a.stats["rhs_evaluations"] <= 1.3 * b.stats["rhs_evaluations"]
