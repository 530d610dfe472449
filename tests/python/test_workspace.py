"""Step by step from Python: the forward workspace (accelerations, multipliers, reactions and the
projection at a state) and the inverse workspace (one sample), against the closed forms of a
pendulum and against the whole runs; the energies of a state and the energy balance of a run."""
import math

import numpy as np
import pytest

import mo2d

M, L, G = 2.0, 0.5, 9.81


def pendulum(damping=0.0):
    s = mo2d.System("pendulum")
    s.add_ground_node("O", (0, 0))
    s.add_body("link", nodes={"O": (0, 0), "P": (L, 0)}, mass=M, com="P")
    s.add_revolute("pivot", "ground.O", "link.O", actuated=True)
    s.add_coordinate("link.angle", rate=[("link.w", 1.0)])
    s.set_gravity((0, -G))
    if damping:
        s.add_torsional_spring("damper", "pivot", damping=damping)
    return s


@pytest.fixture
def model():
    return mo2d.build_model(pendulum())


def state(model, theta, w):
    return mo2d.consistent_state(model, positions=[("link.angle", theta)],
                                 velocities=[("link.w", w)])


def index(labels, label):
    return labels.index(label)


@pytest.mark.parametrize("formulation", ["augmented_lagrangian", "lagrange", "null_space"])
def test_accelerations_are_the_closed_form(model, formulation):
    """theta'' = (u - M g L cos theta) / (M L^2) for the point mass M at L."""
    ws = mo2d.ForwardWorkspace(model, formulation=formulation)
    iw = index(model.rate_labels, "link.w")
    for theta, w, u in [(0.3, 1.2, 0.0), (-2.0, -0.4, 1.7), (1.0, 0.0, -3.0)]:
        x = state(model, theta, w)
        a = ws.accelerations(x.t, x.q0, x.q1, efforts=[u])
        assert isinstance(a, np.ndarray) and a.shape == (len(model.rate_labels),)
        expected = (u - M * G * L * math.cos(theta)) / (M * L**2)
        assert a[iw] == pytest.approx(expected, rel=1e-10, abs=1e-10)
        np.testing.assert_array_equal(ws.a, a)
        assert ws.efforts[0] == u


def test_multipliers_solve_the_equations_of_motion(model):
    """M a = f + B u - A^T lambda and A a = c at the state (the workspace's own fields)."""
    ws = mo2d.ForwardWorkspace(model)
    x = state(model, 0.7, 2.0)
    a = ws.accelerations(x.t, x.q0, x.q1, efforts=[0.4])
    lam = ws.multipliers
    scale = np.max(np.abs(ws.M @ a)) + np.max(np.abs(ws.f))
    np.testing.assert_allclose(ws.M @ a, ws.f + ws.Bu - ws.A.T @ lam, rtol=0, atol=1e-8 * scale)
    np.testing.assert_allclose(ws.A @ a, ws.c, rtol=0, atol=1e-9)
    np.testing.assert_allclose(ws.Bu, ws.B @ [0.4], rtol=0, atol=0)


def test_reactions_are_the_closed_form(model):
    """The force of the ground on the link at the pivot: F = M (a_P - g), with
    a_P = L theta'' (-sin, cos) - L w^2 (cos, sin); efforts from the workspace's laws."""
    theta, w, u = 0.9, -1.5, 2.5
    ws = mo2d.ForwardWorkspace(model, efforts=[("pivot.torque", u)])
    x = state(model, theta, w)
    r = ws.reactions(x.t, x.q0, x.q1)
    dd = (u - M * G * L * math.cos(theta)) / (M * L**2)
    ax = -L * dd * math.sin(theta) - L * w * w * math.cos(theta)
    ay = L * dd * math.cos(theta) - L * w * w * math.sin(theta)
    labels = model.reaction_labels
    assert r[index(labels, "pivot.Fx")] == pytest.approx(M * ax, rel=1e-9, abs=1e-9)
    assert r[index(labels, "pivot.Fy")] == pytest.approx(M * (ay + G), rel=1e-9, abs=1e-9)


def test_accelerations_and_reactions_are_those_of_the_forward_run(model):
    """At every recorded state of mo2d.forward_dynamics the workspace gives the run's a1 and its
    reactions (the same evaluation)."""
    x0 = state(model, 0.2, 1.0)
    r = mo2d.forward_dynamics(model, x0, duration=1.0, samples=11,
                              efforts=[("pivot.torque", "0.3*t")])
    ws = mo2d.ForwardWorkspace(model, efforts=[("pivot.torque", "0.3*t")])
    for k in range(len(r)):
        a = ws.accelerations(r.t[k], r.q0[k], r.q1[k])
        np.testing.assert_allclose(a, r.a1[k], rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(ws.reactions(r.t[k], r.q0[k], r.q1[k]), r.reactions[k],
                                   rtol=1e-10, atol=1e-10)


def test_projection_returns_to_the_constraints(model):
    ws = mo2d.ForwardWorkspace(model)
    x = state(model, 0.4, 0.8)
    q0 = x.q0 + 1e-4
    q1 = x.q1 + 1e-3
    p0, p1 = ws.project(x.t, q0, q1)
    ix, iy = (index(model.coordinate_labels, c) for c in ("link.P.x", "link.P.y"))
    assert math.hypot(p0[ix], p0[iy]) == pytest.approx(L, abs=1e-12)  # |OP| = L again
    assert math.hypot(q0[ix], q0[iy]) != pytest.approx(L, abs=1e-6)  # it was off
    vx, vy = (index(model.rate_labels, c) for c in ("link.P.vx", "link.P.vy"))
    assert p0[ix] * p1[vx] + p0[iy] * p1[vy] == pytest.approx(0, abs=1e-12)  # v normal to OP


def test_a_state_of_the_wrong_size_is_an_error(model):
    ws = mo2d.ForwardWorkspace(model)
    with pytest.raises(mo2d.Error, match="coordinates"):
        ws.accelerations(0.0, np.zeros(1), np.zeros(1))
    with pytest.raises(mo2d.Error, match="1 values expected"):
        x = state(model, 0, 0)
        ws.accelerations(0.0, x.q0, x.q1, efforts=[1.0, 2.0])


def test_inverse_workspace_is_one_sample_of_the_run(model):
    motion = [("link.angle", "0.5 * sin(3 * t) + t^2")]
    r = mo2d.inverse_dynamics(model, motion, duration=1.0, samples=11)
    iw = mo2d.InverseWorkspace(model, motion)
    for k in [3, 7, 10]:  # any order of samples
        iw.solve(r.t[k])
        assert iw.t == r.t[k]
        np.testing.assert_allclose(iw.efforts, r.efforts[k], rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(iw.reactions, r.reactions[k], rtol=1e-12, atol=1e-12)
        # solved from another starting point than the run's (its previous sample): the same
        # positions to the solver's tolerance, |psi| <= 1e-12 of the model's size
        np.testing.assert_allclose(iw.q0, r.q0[k], rtol=0, atol=1e-12)
        t = r.t[k]
        theta = 0.5 * math.sin(3 * t) + t * t
        dd = -4.5 * math.sin(3 * t) + 2
        assert iw.efforts[0] == pytest.approx(M * L**2 * dd + M * G * L * math.cos(theta),
                                              rel=1e-10)
        assert iw.residuals["position"] < 1e-12
    assert iw.warnings == []


def test_energies_of_a_state(model):
    x = state(model, 0.6, -1.3)
    assert mo2d.kinetic_energy(model, x.q1) == pytest.approx(0.5 * M * L**2 * 1.3**2, rel=1e-12)
    v = mo2d.potential_energy(model, x.q0)
    v0 = mo2d.potential_energy(model, state(model, 0.0, 0.0).q0)
    assert v - v0 == pytest.approx(M * G * L * math.sin(0.6), rel=1e-12)


def test_energy_balance_of_a_run():
    """The balance is the integration error: with rk4 it falls as step^4."""
    model = mo2d.build_model(pendulum(damping=0.2))
    x0 = state(model, 0.3, 2.0)

    def run(step):
        return mo2d.forward_dynamics(model, x0, duration=2.0, samples=41, integrator="rk4",
                                     step=step, efforts=[("pivot.torque", "0.5 * sin(2 * t)")])

    r = run(1e-3)
    e = mo2d.energy_balance(r)
    # the definition, from the columns of the run
    total = r["energy.kinetic"] + r["energy.potential"]
    by_hand = (total - total[0] - r["work.inputs"] - r["work.loads"] - r["work.constraints"]
               + r["energy.dissipated"])
    np.testing.assert_allclose(e, by_hand, rtol=0, atol=1e-12)
    assert mo2d.energy_balance_error(r) == np.max(np.abs(e))
    assert r["energy.dissipated"][-1] > 0.1 and abs(r["work.inputs"][-1]) > 1e-3  # not trivial
    assert mo2d.energy_balance_error(r) < 1e-9
    ratio = mo2d.energy_balance_error(run(2e-3)) / mo2d.energy_balance_error(r)
    assert 10 < ratio < 24  # 2^4 = 16
    with pytest.raises(mo2d.Error, match="no energies"):
        mo2d.energy_balance(mo2d.inverse_dynamics(model, [("link.angle", "t")], samples=3))
