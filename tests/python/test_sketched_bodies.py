"""Bodies given by their lengths and a sketch in Python (System.add_body(length=...),
add_body(shape={...}, at=...); C++: mo2d/sketched_body.hpp), as scene files give them: the same
model as the scene loader's for the four-bar of docs/scene-format.md, and the closed-form circle
intersection a user would otherwise compute by hand."""
import math

import pytest

import mo2d

A, B, C, D = 0.1, 0.35, 0.3, 0.4  # crank, coupler, rocker, ground (m)

SCENE = f"""name: fourbar_lengths
parameters: {{a: {A}, b: {B}, c: {C}, d: {D}}}
ground:
  A0: [0, 0]
  B0: [d, 0]
bodies:
  crank:
    nodes: {{O: [0, 0], A: [0, a]}}
    mass: 0.2
  coupler:
    length: b
    nodes: {{A: [0, 0.1], B: [0.3, 0.3]}}
    mass: 0.5
  rocker:
    shape: {{O: [0, 0], B: [c, 0]}}
    at: {{origin: [d, 0], angle: 1.8}}
    mass: 0.4
    com: {{point: [c / 2, 0]}}
joints:
  crank_pivot:  {{type: revolute, node_a: ground.A0, node_b: crank.O, actuated: true}}
  crank_pin:    {{type: revolute, node_a: crank.A, node_b: coupler.A}}
  rocker_pin:   {{type: revolute, node_a: coupler.B, node_b: rocker.B}}
  rocker_pivot: {{type: revolute, node_a: ground.B0, node_b: rocker.O}}
coordinates:
  crank.angle: {{rate: {{crank.w: 1}}}}
loads:
  gravity: [0, -9.81]
motion:
  crank.angle: pi / 2 + t
"""


def python_fourbar(coupler_sketch_b=(0.3, 0.3), rocker_angle=1.8):
    s = mo2d.System("fourbar_lengths")
    s.add_ground_node("A0", (0, 0))
    s.add_ground_node("B0", (D, 0))
    s.add_body("crank", nodes={"O": (0, 0), "A": (0, A)}, mass=0.2)
    s.add_body("coupler", length=B, nodes={"A": (0, 0.1), "B": coupler_sketch_b}, mass=0.5)
    s.add_body("rocker", shape={"O": (0, 0), "B": (C, 0)}, at=((D, 0), rocker_angle), mass=0.4,
               com_point=(C / 2, 0))
    s.add_revolute("crank_pivot", "ground.A0", "crank.O", actuated=True)
    s.add_revolute("crank_pin", "crank.A", "coupler.A")
    s.add_revolute("rocker_pin", "coupler.B", "rocker.B")
    s.add_revolute("rocker_pivot", "ground.B0", "rocker.O")
    s.add_coordinate("crank.angle", rate=[("crank.w", 1.0)])
    s.set_gravity((0, -9.81))
    return mo2d.build_model(s)


def coupler_b(model):
    q = dict(zip(model.coordinate_labels, model.q0))
    return q["coupler.B.x"], q["coupler.B.y"]


def test_lengths_and_a_sketch_give_the_scene_loaders_model():
    scene = mo2d.parse_scene(SCENE, "fourbar_lengths.yaml").build_model()
    model = python_fourbar()
    assert model.coordinate_labels == scene.coordinate_labels
    assert list(model.q0) == pytest.approx(list(scene.q0), abs=1e-12)
    assert model.dof == scene.dof == 1


def test_the_assembly_is_the_circle_intersection():
    # B: |B - A| = b from the crank pin A = (0, a), |B - B0| = c from the pivot B0 = (d, 0)
    ax, ay, bx, by = 0.0, A, D, 0.0
    dist = math.hypot(bx - ax, by - ay)
    along = (B**2 - C**2 + dist**2) / (2 * dist)
    h = math.sqrt(B**2 - along**2)
    ex, ey = (bx - ax) / dist, (by - ay) / dist
    up = (ax + along * ex - h * ey, ay + along * ey + h * ex)     # elbow up (sketched)
    down = (ax + along * ex + h * ey, ay + along * ey - h * ex)   # the mirror branch
    assert up[1] > down[1]
    assert coupler_b(python_fourbar()) == pytest.approx(up, abs=1e-10)
    # the sketch picks the branch: B sketched below the line A-B0 (on the coupler and by the
    # rocker's placement) assembles elbow down
    assert coupler_b(python_fourbar((0.25, -0.2), -1.8)) == pytest.approx(down, abs=1e-10)


def test_bad_lengths_and_sketches_are_refused():
    s = mo2d.System("bad")
    with pytest.raises(mo2d.Error, match="bar's length must be finite and > 0"):
        s.add_body("bar", length=0.0, nodes={"A": (0, 0), "B": (1, 0)})
    with pytest.raises(TypeError, match="exactly two nodes"):
        s.add_body("bar", length=1.0, nodes={"A": (0, 0), "B": (1, 0), "C": (2, 0)})
    with pytest.raises(TypeError, match="either shape= or length="):
        s.add_body("bar", length=1.0, nodes={"A": (0, 0), "B": (1, 0)}, shape=[(0, 0), (1, 0)])
    with pytest.raises(TypeError, match="at= places a shape"):
        s.add_body("bar", nodes={"A": (0, 0)}, at=((0, 0), 0.0))
    with pytest.raises(TypeError, match=r"at: \(\(x, y\), angle\)"):
        s.add_body("bar", shape={"A": (0, 0)}, at=(1, 2, 3))
    with pytest.raises(TypeError, match="nodes= missing"):
        s.add_body("bar", mass=1.0)
