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
        mo2d.inverse_dynamics(model, [("link.angle", "t")], duration=1.0, samples=11)
    e = info.value
    assert e.element == "kick" and "kick" in str(e)
    assert e.time == pytest.approx(0.6)


def test_unknown_column_of_a_result(mechanisms):
    r = mo2d.inverse(mo2d.load_scene(mechanisms / "pendulum.yaml"))
    with pytest.raises(mo2d.Error, match="no column 'pivot.torq'") as info:
        r["pivot.torq"]
    assert info.value.element == "pivot.torq" and math.isnan(info.value.time)


def test_unknown_column_is_a_key_error_with_the_closest_label(mechanisms):
    r = mo2d.inverse(mo2d.load_scene(mechanisms / "pendulum.yaml"))
    assert "pivot.torque" in r.columns
    # a mapping's error (dict-like code catches KeyError) that is also a mo2d.Error, with the
    # suggestion the scene loader makes for a mistyped label
    with pytest.raises(KeyError) as info:
        r["pivot.torqe"]
    e = info.value
    assert isinstance(e, mo2d.ColumnError) and isinstance(e, mo2d.Error)
    assert str(e) == ("result: no column 'pivot.torqe' (did you mean 'pivot.torque'?) "
                      "(r.columns lists them)")
    assert e.element == "pivot.torqe"
    # nothing close: no suggestion
    with pytest.raises(mo2d.ColumnError) as info:
        r["something else entirely"]
    assert "did you mean" not in str(info.value)
    # a column that exists, and `in`, are unchanged
    assert len(r["pivot.torque"]) == len(r.t) and "pivot.torqe" not in r


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
        mo2d.inverse_dynamics(model, [("link.angle", "t")], duration=1.0, samples=11)


def test_expression_error_has_its_column():
    with pytest.raises(mo2d.Error) as info:
        mo2d.Law("2 * sinn(t)")
    assert info.value.column == 5


# ---- arguments of the wrong kind name what they are (issue 31, item 5) ------------------------


def test_a_parameter_override_of_the_wrong_type_names_the_parameter(mechanisms):
    with pytest.raises(TypeError, match="set: parameter 'L': a number or a string .* not list"):
        mo2d.load_scene(mechanisms / "pendulum.yaml", set={"L": [1, 2]})
    with pytest.raises(TypeError, match="parameter 'm'.* not bool"):
        mo2d.load_scene(mechanisms / "pendulum.yaml", set={"m": True})


def test_parse_scene_reads_text_or_bytes_and_refuses_other_types(mechanisms):
    text = (mechanisms / "pendulum.yaml").read_text()
    for t in (text, text.encode(), text.encode("utf-16"), bytearray(text.encode())):
        s = mo2d.parse_scene(t)
        assert s.name == "pendulum" and s.parameters["L"] == 1.0 and s.duration == 2
    with pytest.raises(TypeError, match="parse_scene: the text of a scene .*not PosixPath.*"
                                        "load_scene"):
        mo2d.parse_scene(mechanisms / "pendulum.yaml")


def test_add_body_nodes_of_the_wrong_form_name_the_body():
    s = mo2d.System("s")
    with pytest.raises(TypeError, match=r"add_body\('link'\): nodes: a dict .* not str"):
        s.add_body("link", nodes="abc", mass=1.0)
    with pytest.raises(TypeError, match=r"add_body\('link'\): nodes: node 'P': a position \(x, y\)"):
        s.add_body("link", nodes={"O": (0, 0), "P": "far"}, mass=1.0)
    with pytest.raises(TypeError, match=r"item 0: \(name, \(x, y\)\)"):
        s.add_body("link", nodes=[1, 2], mass=1.0)


def test_a_count_beyond_int_names_the_argument():
    s = mo2d.System("pendulum")
    s.add_ground_node("O", (0, 0))
    s.add_body("link", nodes={"O": (0, 0), "P": (1, 0)}, mass=1.0, com="P")
    s.add_revolute("pivot", "ground.O", "link.O", actuated=True)
    s.add_coordinate("link.angle", rate=[("link.w", 1.0)])
    model = mo2d.build_model(s)
    with pytest.raises(mo2d.Error, match="samples = 1000000000000 is out of range: at most "
                                         "2147483647"):
        mo2d.inverse_dynamics(model, [("link.angle", "t")], samples=10**12)
    with pytest.raises(TypeError, match="samples: an integer, not float"):
        mo2d.inverse_dynamics(model, [("link.angle", "t")], samples=11.5)
    with pytest.raises(mo2d.Error, match="max_steps = 1000000000000 is out of range"):
        mo2d.forward_dynamics(model, mo2d.consistent_state(model, velocities=[("link.w", 0.0)]),
                              1.0, max_steps=10**12)
    r = mo2d.inverse_dynamics(model, [("link.angle", "t")], samples=11)
    assert r.t.shape == (11,)
