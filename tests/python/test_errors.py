"""Errors reach Python as mo2d.Error with the message of the C++ mo2d::Error and its parts."""
import math

import pytest

import mo2d

BAD_LABEL = """name: bad
ground:
  O: [0, 0]
bodies:
  link:
    nodes: {O: [0, 0], P: [1, 0]}
    mass: 1
    com: P
joints:
  pivot: {type: revolute, node_a: ground.O, node_b: link.O, actuated: true}
coordinates:
  link.angle: {rate: {link.w: 1}}
motion:
  link.angel: t
"""


def test_error_is_an_exception_class():
    assert issubclass(mo2d.Error, Exception)


def test_scene_error_names_file_line_column(tmp_path):
    path = tmp_path / "bad.yaml"
    path.write_text(BAD_LABEL)
    with pytest.raises(mo2d.Error) as info:
        mo2d.inverse(mo2d.load_scene(path))
    e = info.value
    assert str(e).startswith(f"{path}:14:3: ")
    assert "link.angel" in str(e) and "link.angle" in str(e)  # the suggestion
    assert (e.file, e.line, e.column) == (str(path), 14, 3)
    assert e.message == str(e)


def test_parse_error_of_an_override(mechanisms):
    with pytest.raises(mo2d.Error, match="nope"):
        mo2d.load_scene(mechanisms / "pendulum.yaml", set={"nope": 1.0})


def test_run_error_carries_element_and_time():
    s = mo2d.System("pendulum")
    s.add_ground_node("O", (0, 0))
    s.add_body("link", nodes={"O": (0, 0), "P": (1, 0)}, mass=1.0, com="P")
    s.add_revolute("pivot", "ground.O", "link.O", actuated=True)
    s.add_coordinate("link.angle", rate=[("link.w", 1.0)])
    # a torque law that is not finite from t = 0.5 s: the run stops there, naming the torque
    s.add_torque("kick", "link", lambda t: math.inf if t > 0.5 else 0.0)
    model = mo2d.build_model(s)
    with pytest.raises(mo2d.Error) as info:
        mo2d.inverse_dynamics(model, [("link.angle", "t")], t1=1.0, samples=11)
    e = info.value
    assert e.element == "kick" and "kick" in str(e)
    assert e.time == pytest.approx(0.6)


def test_unknown_column_of_a_result(mechanisms):
    r = mo2d.inverse(mo2d.load_scene(mechanisms / "pendulum.yaml"))
    with pytest.raises(mo2d.Error, match="no column 'pivot.torq'") as info:
        r["pivot.torq"]
    assert info.value.element == "pivot.torq" and math.isnan(info.value.time)


def test_exception_raised_by_a_python_law_propagates():
    s = mo2d.System("pendulum")
    s.add_ground_node("O", (0, 0))
    s.add_body("link", nodes={"O": (0, 0), "P": (1, 0)}, mass=1.0, com="P")
    s.add_revolute("pivot", "ground.O", "link.O", actuated=True)
    s.add_coordinate("link.angle", rate=[("link.w", 1.0)])

    def law(x, t):
        raise ZeroDivisionError("from the law")

    s.add_torque("bad", "link", mo2d.Law(["link.w"], law))
    model = mo2d.build_model(s)
    with pytest.raises(ZeroDivisionError, match="from the law"):
        mo2d.inverse_dynamics(model, [("link.angle", "t")], t1=1.0, samples=11)


def test_expression_error_has_its_column():
    with pytest.raises(mo2d.Error) as info:
        mo2d.Law("2 * sinn(t)")
    assert info.value.column == 5
