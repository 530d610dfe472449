"""An exception raised by Python code inside a run (a law, an effort, a stop condition) comes out
of the run as itself - its type, its message - with the load and the time it was raised at, for
every integrator (CVODE's callbacks are C: the exception must not unwind through them), and the
run stops there (no retry calls the failing code again)."""
import pytest

import mo2d

INTEGRATORS = ["rk4", "dopri5", "cvode_bdf", "cvode_adams", "baumgarte"]
T_FAIL = 0.3


def pendulum():
    s = mo2d.System("pendulum")
    s.add_ground_node("O", (0, 0))
    s.add_body("link", nodes={"O": (0, 0), "P": (1, 0)}, mass=1.0, com="P")
    s.add_revolute("pivot", "ground.O", "link.O", actuated=True)
    s.add_coordinate("link.angle", rate=[("link.w", 1.0)])
    s.set_gravity((0, -9.81))
    return s


class Failing:
    """A law f(x, t) = -0.1 x[0] that raises `error` from t > T_FAIL on, and records the calls."""

    def __init__(self, error):
        self.error, self.raised_at, self.calls_after = error, None, 0

    def __call__(self, x, t):
        if self.raised_at is not None:
            self.calls_after += 1
        if t > T_FAIL:
            self.raised_at = t
            raise self.error
        return -0.1 * x[0]


def run(system, integrator, **kwargs):
    model = mo2d.build_model(system)
    x0 = mo2d.consistent_state(model, positions=[("link.angle", 0.0)],
                               velocities=[("link.w", 0.5)])
    return mo2d.forward_dynamics(model, x0, duration=1.0, samples=11, integrator=integrator,
                                 **kwargs)


def check(info, law, element, role):
    e = info.value
    assert law.raised_at is not None and law.raised_at > T_FAIL
    assert law.calls_after == 0  # not called again once it raised: the run stopped there
    assert e.mo2d_element == element and e.mo2d_time == law.raised_at
    note = f"{role} '{element}' failed at t = "
    assert any(n.startswith(note) for n in getattr(e, "__notes__", [])), e.__notes__
    assert note in e.mo2d_message


@pytest.mark.parametrize("integrator", INTEGRATORS)
def test_a_law_raising_in_a_forward_run(integrator):
    s = pendulum()
    law = Failing(ValueError("the law refuses"))
    s.add_torque("brake", "link", mo2d.Law(["link.w"], law))
    with pytest.raises(ValueError, match="^the law refuses$") as info:
        run(s, integrator)
    check(info, law, "brake", "torque")


@pytest.mark.parametrize("integrator", INTEGRATORS)
def test_an_effort_raising_in_a_forward_run(integrator):
    law = Failing(ZeroDivisionError("effort"))
    with pytest.raises(ZeroDivisionError) as info:
        run(pendulum(), integrator, efforts=[("pivot.torque", mo2d.Law(["link.w"], law))])
    check(info, law, "pivot.torque", "effort of input")


@pytest.mark.parametrize("integrator", ["rk4", "cvode_bdf"])
def test_a_time_law_and_a_spring_tension_raising(integrator):
    # a law of t only (its own wrapper) on a force, and a spring's tension law
    calls = []

    def fx(t):
        calls.append(t)
        if t > T_FAIL:
            raise KeyError("fx")
        return 0.0

    s = pendulum()
    s.add_force("push", "link", (1, 0), fx=fx)
    with pytest.raises(KeyError) as info:
        run(s, integrator)
    assert info.value.mo2d_element == "push" and info.value.mo2d_time == calls[-1] > T_FAIL
    s = pendulum()
    law = Failing(ArithmeticError("tension"))
    s.add_spring("cord", "ground", (0, 0), "link", (1, 0), tension=mo2d.Law(["length"], law))
    with pytest.raises(ArithmeticError) as info:
        run(s, integrator)
    check(info, law, "cord", "tension of spring")


@pytest.mark.parametrize("integrator", ["rk4", "dopri5", "cvode_bdf", "cvode_adams"])
def test_a_stop_condition_raising(integrator):
    def stop(t, q0, q1):
        if t > T_FAIL:
            raise RuntimeError(f"stop at {t}")
        return 1.0

    with pytest.raises(RuntimeError, match="stop at"):
        run(pendulum(), integrator, stop_when=stop)


def test_a_law_in_inverse_dynamics_names_the_load():
    s = pendulum()
    law = Failing(ValueError("inverse"))
    s.add_torque("brake", "link", mo2d.Law(["link.w"], law))
    model = mo2d.build_model(s)
    with pytest.raises(ValueError, match="inverse") as info:
        mo2d.inverse_dynamics(model, [("link.angle", "t")], duration=1.0, samples=11)
    check(info, law, "brake", "torque")
    assert info.value.mo2d_time == pytest.approx(0.4)  # the first sample past T_FAIL


def test_a_law_returning_a_non_number_names_the_load():
    s = pendulum()
    s.add_torque("brake", "link", mo2d.Law(["link.w"], lambda x, t: "soft"))
    with pytest.raises(mo2d.Error, match="torque 'brake' failed at t = 0 s: .*not a number") as i:
        run(s, "rk4")
    assert i.value.element == "brake" and i.value.time == 0.0


def test_a_motion_raising_in_inverse_dynamics_names_the_coordinate():
    times = []

    def motion(t):
        times.append(t)
        if t > T_FAIL:
            raise IndexError("no such motion")
        return (t, 1.0, 0.0)

    model = mo2d.build_model(pendulum())
    with pytest.raises(IndexError, match="no such motion") as info:
        mo2d.inverse_dynamics(model, [("link.angle", motion)], duration=1.0, samples=11)
    e = info.value
    assert e.mo2d_element == "link.angle" and e.mo2d_time == times[-1] == pytest.approx(0.4)
    assert "prescribed motion of 'link.angle' failed at t = 0.4 s" in e.mo2d_message
