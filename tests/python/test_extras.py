"""The rest of the public API from Python, against closed forms: lookup tables (read from CSV),
PD control, efforts replayed from inverse dynamics, gears and racks, user constraints, a stop
condition, the lumped transmission."""
import math

import numpy as np
import pytest

import mo2d

G = 9.81


def cubic(x):
    return 0.3 - 1.2 * x + 0.7 * x**2 + 0.25 * x**3, -1.2 + 1.4 * x + 0.75 * x**2, 1.4 + 1.5 * x


def test_a_cubic_table_reproduces_a_cubic():
    """Not-a-knot cubic splines are exact for cubics: value, slope and curvature."""
    xs = np.array([0.0, 0.4, 1.1, 1.5, 2.3, 3.0])
    table = mo2d.Table("p", xs, cubic(xs)[0])
    assert table.name == "p" and table.x == list(xs)
    for x in [0.05, 0.77, 1.5, 2.9]:
        np.testing.assert_allclose(table.derivatives(x), cubic(x), rtol=1e-12, atol=1e-12)
    grid = np.linspace(0, 3, 7)
    np.testing.assert_allclose(table(grid), cubic(grid)[0], rtol=1e-12, atol=1e-12)
    with pytest.raises(mo2d.Error, match="'p'"):
        table(3.5)  # beyond the range
    assert mo2d.Table("p", xs, cubic(xs)[0], extrapolation="clamp")(3.5) == pytest.approx(
        cubic(3.0)[0])
    lin = mo2d.Table("l", [0, 1, 3], [0, 2, 3], interpolation="linear")
    assert lin.derivatives(2.0) == pytest.approx((2.5, 0.5, 0.0))


def test_read_table_csv(tmp_path):
    path = tmp_path / "cam.csv"
    xs = [0.0, 0.4, 1.1, 1.5, 2.3, 3.0]
    rows = "\n".join(f"{1000 * x!r}, {cubic(x)[0]!r}, 7" for x in xs)
    path.write_text(f"# a cam\nangle_mrad, lift, other\n{rows}\n")
    table = mo2d.read_table_csv(path, "cam", x="angle_mrad", y="lift", scale_x=1e-3)
    np.testing.assert_allclose(table.derivatives(1.3), cubic(1.3), rtol=1e-12)
    bad = tmp_path / "bad.csv"
    bad.write_text("x, y\n0, 1\n1, oops\n")
    with pytest.raises(mo2d.Error, match=f"{bad}:3"):
        mo2d.read_table_csv(bad, "bad")
    with pytest.raises(mo2d.Error, match="lift"):
        mo2d.read_table_csv(path, "cam", y="lifts")  # did you mean


def rotor(inertia=0.4, gravity=False, mass=0.0, length=1.0):
    """A bar about a ground pivot: mass at its end (length) and inertia about its centre of
    mass."""
    s = mo2d.System("rotor")
    s.add_ground_node("O", (0, 0))
    s.add_body("bar", nodes={"O": (0, 0), "P": (length, 0)}, mass=mass, inertia=inertia,
               com="P" if mass else "O")
    s.add_revolute("pivot", "ground.O", "bar.O", actuated=True)
    s.add_coordinate("bar.angle", rate=[("bar.w", 1.0)])
    if gravity:
        s.set_gravity((0, -G))
    return s


def test_a_table_drives_a_motion():
    """inverse dynamics of the rotor (inertia J) along the table's cubic: tau = J theta''."""
    xs = np.linspace(0, 2, 9)
    table = mo2d.Table("path", xs, cubic(xs)[0])
    model = mo2d.build_model(rotor(inertia=0.4))
    r = mo2d.inverse_dynamics(model, [("bar.angle", lambda t: tuple(table.derivatives(t)))],
                              duration=2.0, samples=21)
    np.testing.assert_allclose(r["pivot.torque"], 0.4 * cubic(r.t)[2], rtol=1e-10, atol=1e-12)


def test_pd_control_follows_the_closed_loop_equation():
    """No gravity, inertia m* = J: e'' + (kd / J) e' + (kp / J) e = 0, e = theta - r, with
    e(0) = -r, e'(0) = 0 (underdamped)."""
    J, kp, kd, ref = 0.4, 10.0, 0.8, 0.5
    model = mo2d.build_model(rotor(inertia=J))
    law = mo2d.pd_control("bar.angle", kp=kp, kd=kd, reference=ref)
    assert law.labels == ["bar.angle", mo2d.rate_label("bar.angle")]
    x0 = mo2d.consistent_state(model, positions=[("bar.angle", 0.0)], velocities=[("bar.w", 0)])
    r = mo2d.forward_dynamics(model, x0, duration=3.0, samples=61, rtol=1e-11, atol=1e-12,
                              efforts=[("pivot.torque", law)])
    zeta_w = kd / (2 * J)
    wd = math.sqrt(kp / J - zeta_w**2)
    e = -ref * np.exp(-zeta_w * r.t) * (np.cos(wd * r.t) + zeta_w / wd * np.sin(wd * r.t))
    np.testing.assert_allclose(r["bar.angle"] - ref, e, rtol=0, atol=1e-7)
    np.testing.assert_allclose(r["pivot.torque"], kp * (ref - r["bar.angle"]) - kd * r["bar.w"],
                               rtol=1e-12, atol=1e-12)


def test_pd_control_with_the_exact_feed_forward_tracks_exactly():
    """With u_ff the inverse-dynamics effort of the reference (efforts_from_inverse), the
    reference is a solution of the closed loop: the error stays at integration accuracy."""
    model = mo2d.build_model(rotor(inertia=0.05, gravity=True, mass=1.0, length=0.5))
    reference = "0.4 * sin(2 * t)"
    (ff,) = mo2d.efforts_from_inverse(model, [("bar.angle", reference)])
    t = 0.3
    assert ff([], t) == pytest.approx(
        (0.05 + 0.25) * -1.6 * math.sin(0.6) + 0.5 * G * math.cos(0.4 * math.sin(0.6)))
    law = mo2d.pd_control("bar.angle", kp=5.0, kd=1.0, reference=reference, feed_forward=ff)
    x0 = mo2d.consistent_state(model, positions=[("bar.angle", 0.0)],
                               velocities=[("bar.w", 0.8)])
    r = mo2d.forward_dynamics(model, x0, duration=2.0, samples=41, rtol=1e-11, atol=1e-12,
                              efforts=[("pivot.torque", law)])
    assert np.max(np.abs(r["bar.angle"] - 0.4 * np.sin(2 * r.t))) < 1e-7
    with pytest.raises(mo2d.Error, match="kp"):
        mo2d.pd_control("bar.angle", kp=-1.0, kd=0.0)


def two_rotors(ratio, j_driver, j_driven):
    s = mo2d.System("gears")
    s.add_ground_node("A", (0, 0))
    s.add_ground_node("B", (1, 0))
    s.add_body("k", nodes={"O": (0, 0), "P": (0.1, 0)}, mass=0.0, inertia=j_driver)
    s.add_body("j", nodes={"O": (1, 0), "P": (1.2, 0)}, mass=0.0, inertia=j_driven)
    s.add_revolute("pk", "ground.A", "k.O", actuated=True)
    s.add_revolute("pj", "ground.B", "j.O")
    s.add_coordinate("k.angle", rate=[("k.w", 1.0)])
    s.add_gear("mesh", body="j", driver="k", ratio=ratio)
    return s


def test_a_gear_pair_reflects_the_driven_inertia():
    """u = (J_k + ratio^2 J_j) theta_k''; the mesh torque on j is J_j ratio theta_k''."""
    ratio, jk, jj = -2.5, 0.02, 0.3
    model = mo2d.build_model(two_rotors(ratio, jk, jj))
    assert model.dof == 1 and "mesh.phi" in model.coordinate_labels
    r = mo2d.inverse_dynamics(model, [("k.angle", "sin(4 * t)")], duration=1.0, samples=11)
    dd = -16 * np.sin(4 * r.t)
    np.testing.assert_allclose(r["pk.torque"], (jk + ratio**2 * jj) * dd, rtol=1e-10,
                               atol=1e-12)
    np.testing.assert_allclose(r["mesh.torque"], jj * ratio * dd, rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(r["j.w"], ratio * 4 * np.cos(4 * r.t), rtol=1e-12, atol=1e-12)


def test_a_rack_and_pinion():
    """q' = radius w: u = (J + m radius^2) theta'' on the pinion."""
    J, m, radius = 0.01, 3.0, 0.05
    s = mo2d.System("rack")
    s.add_ground_node("O", (0, 0))
    s.add_ground_node("A", (0, -1))
    s.add_ground_node("B", (1, -1))
    s.add_body("pinion", nodes={"O": (0, 0), "P": (0.05, 0)}, mass=0.0, inertia=J)
    s.add_body("rack", nodes={"S": (0, -1), "T": (0.5, -1)}, mass=m, com="S")
    s.add_revolute("pivot", "ground.O", "pinion.O", actuated=True)
    s.add_prismatic("slide", "ground.A", "ground.B", "rack.S")
    s.add_coordinate("pinion.angle", rate=[("pinion.w", 1.0)])
    s.add_rack("mesh", slide="slide", pinion="pinion", radius=radius)
    model = mo2d.build_model(s)
    r = mo2d.inverse_dynamics(model, [("pinion.angle", "t^3")], duration=1.0, samples=11)
    np.testing.assert_allclose(r["pivot.torque"], (J + m * radius**2) * 6 * r.t, rtol=1e-10,
                               atol=1e-12)
    np.testing.assert_allclose(r["slide.q"], radius * r.t**3, rtol=1e-10, atol=1e-12)


def test_a_position_constraint_makes_a_pendulum():
    """A free point mass held at |OP| = L by a user constraint swings like the revolute
    pendulum."""
    Lp, mass = 0.7, 1.3

    def system(by_constraint):
        s = mo2d.System("p")
        s.add_ground_node("O", (0, 0))
        s.set_gravity((0, -G))
        if by_constraint:
            s.add_body("m", nodes={"P": (Lp, 0)}, mass=mass)
            s.add_constraint("rod", "m.P.x^2 + m.P.y^2 - L^2", params={"L": Lp})
        else:
            s.add_body("m", nodes={"O": (0, 0), "P": (Lp, 0)}, mass=mass, com="P")
            s.add_revolute("pivot", "ground.O", "m.O")
        return mo2d.build_model(s)

    a, b = system(True), system(False)
    assert a.dof == 1
    ra = mo2d.forward_dynamics(a, mo2d.consistent_state(a, velocities=[("m.P.vy", 0.5)]),
                               duration=1.5, samples=16, rtol=1e-11, atol=1e-12)
    rb = mo2d.forward_dynamics(b, mo2d.consistent_state(b, velocities=[("m.P.vy", 0.5)]),
                               duration=1.5, samples=16, rtol=1e-11, atol=1e-12)
    np.testing.assert_allclose(ra["m.P.x"], rb["m.P.x"], rtol=0, atol=1e-7)
    np.testing.assert_allclose(ra["m.P.y"], rb["m.P.y"], rtol=0, atol=1e-7)
    assert np.max(np.abs(np.hypot(ra["m.P.x"], ra["m.P.y"]) - Lp)) < 1e-9
    with pytest.raises(TypeError):
        mo2d.System("x").add_constraint("c", lambda x, t: 0.0)  # expressions only


def test_a_velocity_constraint():
    """A free point mass with vx = vy slides along the diagonal: ax = ay = -g / 2."""
    s = mo2d.System("slide")
    s.add_body("m", nodes={"P": (0, 0)}, mass=2.0)
    s.set_gravity((0, -G))
    s.add_velocity_constraint("diagonal", "m.P.vx - m.P.vy")
    model = mo2d.build_model(s)
    ws = mo2d.ForwardWorkspace(model)
    x = mo2d.consistent_state(model, velocities=[("m.P.vx", 0.3)])
    a = ws.accelerations(0.0, x.q0, x.q1)
    vx, vy = model.rate_labels.index("m.P.vx"), model.rate_labels.index("m.P.vy")
    assert x.q1[vy] == pytest.approx(0.3)
    assert (a[vx], a[vy]) == pytest.approx((-G / 2, -G / 2), rel=1e-10)


def agm(a, b):
    while abs(a - b) > 1e-15 * a:
        a, b = (a + b) / 2, math.sqrt(a * b)
    return a


@pytest.mark.parametrize("integrator", ["cvode_bdf", "dopri5", "rk4"])
def test_stop_when_finds_the_quarter_period(integrator):
    """Released at rest from the horizontal, the mass reaches the bottom after a quarter of the
    period, sqrt(L/g) K(sin 45 deg), K(k) = pi / (2 agm(1, sqrt(1 - k^2)))."""
    Lp = 0.9
    s = mo2d.System("pendulum")
    s.add_ground_node("O", (0, 0))
    s.add_body("m", nodes={"O": (0, 0), "P": (Lp, 0)}, mass=1.0, com="P")
    s.add_revolute("pivot", "ground.O", "m.O")
    s.add_coordinate("m.angle", rate=[("m.w", 1.0)])
    s.set_gravity((0, -G))
    model = mo2d.build_model(s)
    angle = model.coordinate_labels.index("m.angle")
    x0 = mo2d.consistent_state(model, velocities=[("m.w", 0.0)])
    r = mo2d.forward_dynamics(model, x0, duration=2.0, samples=201, integrator=integrator,
                              rtol=1e-11, atol=1e-12, step=1e-4,
                              stop_when=lambda t, q0, q1: q0[angle] + math.pi / 2)
    k = math.sin(math.pi / 4)
    quarter = math.sqrt(Lp / G) * math.pi / (2 * agm(1.0, math.sqrt(1 - k * k)))
    assert r.stats["stopped_by_event"]
    assert r.stats["t_end"] == pytest.approx(quarter, abs=1e-6)
    assert r.t[-1] == pytest.approx(quarter, abs=1e-6)


def test_lump_transmission_has_the_invariants():
    shafts = [dict(mass=1.0, inertia=0.02, axis=(0.1, 0.0), ratio=1.0),
              dict(mass=3.0, inertia=0.05, axis=(0.3, 0.2), ratio=-0.4)]
    h = mo2d.lump_transmission(housing_mass=5.0, housing_com=(0.2, 0.1), housing_inertia=0.7,
                               shafts=shafts)
    sigma = 0.02 + 0.05
    s_ = 0.02 - 0.4 * 0.05
    p = 0.02 + 0.16 * 0.05
    rho = math.sqrt(p / sigma)
    axis = np.array([(1.0 * 0.1 + 3.0 * 0.3) / 4, (3.0 * 0.2) / 4])
    spread = 1.0 * np.sum((np.array([0.1, 0.0]) - axis) ** 2) + 3.0 * np.sum(
        (np.array([0.3, 0.2]) - axis) ** 2)
    assert (h["sigma"], h["s"], h["p"]) == pytest.approx((sigma, s_, p), rel=1e-14)
    assert h["ratio"] == pytest.approx(rho, rel=1e-14)
    assert h["inertia_a"] == pytest.approx((sigma + s_ / rho) / 2, rel=1e-12)
    assert h["inertia_b"] == pytest.approx((sigma - s_ / rho) / 2, rel=1e-12)
    assert h["shaft_mass"] == pytest.approx(2.0) and h["axis"] == pytest.approx(list(axis))
    assert h["housing_inertia"] == pytest.approx(0.7 + spread, rel=1e-12)
    with pytest.raises(mo2d.Error, match="gearbox"):
        mo2d.lump_transmission(1.0, (0, 0), 0.1, [dict(mass=-1.0, inertia=0.1)], name="gearbox")


def pendulum_system(mass=2.0, length=0.5):
    s = mo2d.System("pendulum")
    s.add_ground_node("O", (0, 0))
    s.add_body("link", nodes={"O": (0, 0), "P": (length, 0)}, mass=mass, com="P")
    s.add_revolute("pivot", "ground.O", "link.O", actuated=True)
    s.add_coordinate("link.angle", rate=[("link.w", 1.0)])
    s.set_gravity((0, -G))
    return s


def pendulum_torque(t, mass=2.0, length=0.5):
    theta = 0.5 * np.sin(3 * t) + t**2
    dd = -4.5 * np.sin(3 * t) + 2
    return mass * length**2 * dd + mass * G * length * np.cos(theta)


MOTION = [("link.angle", "0.5 * sin(3 * t) + t^2")]


def test_inverse_dynamics_by_lagrange_multipliers():
    model = mo2d.build_model(pendulum_system(), reduction="none")
    r = mo2d.inverse_dynamics_lagrange(model, MOTION, duration=1.0, samples=21)
    np.testing.assert_allclose(r["pivot.torque"], pendulum_torque(r.t), rtol=1e-9, atol=1e-9)
    flat = mo2d.inverse_dynamics(mo2d.build_model(pendulum_system()), MOTION, duration=1.0,
                                 samples=21)
    np.testing.assert_allclose(r["pivot.torque"], flat["pivot.torque"], rtol=1e-10, atol=1e-10)


def test_efforts_from_samples_interpolate_the_run():
    """Cubic Hermite between samples, slopes from centred differences: at the midpoints of the
    interior intervals the error against the closed form falls as h^4 (the slope errors cancel
    there), in the two end intervals (one-sided slopes) as h^2."""
    model = mo2d.build_model(pendulum_system())

    def midpoint_errors(samples):
        r = mo2d.inverse_dynamics(model, MOTION, duration=1.0, samples=samples)
        (law,) = mo2d.efforts_from_samples(r)
        assert law([], r.t[3]) == pytest.approx(r["pivot.torque"][3], rel=1e-14)
        mid = (r.t[1:] + r.t[:-1]) / 2
        err = np.array([abs(law([], t) - pendulum_torque(t)) for t in mid])
        return np.max(err[1:-1]), max(err[0], err[-1])

    (inner_c, end_c), (inner_f, end_f) = midpoint_errors(51), midpoint_errors(101)
    assert inner_f < 1e-6 and 12 < inner_c / inner_f < 20  # 2^4
    assert 3 < end_c / end_f < 5  # 2^2


def test_units_of_the_columns():
    model = mo2d.build_model(pendulum_system())
    r = mo2d.inverse_dynamics(model, MOTION, duration=1.0, samples=3)
    units = dict(zip(r.columns, r.units))
    assert len(r.units) == len(r.columns)
    assert (units["t"], units["link.P.x"], units["link.w"], units["pivot.torque"],
            units["pivot.Fx"]) == ("s", "m", "rad/s", "N·m", "N")
