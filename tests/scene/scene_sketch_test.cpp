// Scene files: bodies given by their shape (`shape`, `length`, with a sketch in `nodes` or `at`)
// build the model the exact positions give, and their mistakes are reported at file:line:column.
#include <gtest/gtest.h>

#include <string>

#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"

namespace mo2d {
namespace {

// The four-bar of mechanisms/fourbar.yaml with its coupler given by `length` and its rocker by
// `shape` + `at`. Lines are numbered from 1 ("name: fourbar").
const std::string kBase = R"yaml(name: fourbar
parameters:
  a: 0.1
  b: 0.35
  c: 0.3
  d: 0.4
ground:
  A0: [0, 0]
  B0: [d, 0]
bodies:
  crank:
    nodes: {O: [0, 0], A: [0, a]}
    mass: 0.2
    inertia: 0.2 * a^2 / 12
    com: {between: [O, A], gamma: 0.5}
  coupler:
    length: b
    nodes: {A: [0, a], B: [0.3, 0.3]}
    mass: 0.5
    inertia: 0.5 * b^2 / 12
    com: {between: [A, B], gamma: 0.5}
  rocker:
    shape: {O: [0, 0], B: [c, 0]}
    at: {origin: [d, 0], angle: 1.8}
    mass: 0.4
    inertia: 0.4 * c^2 / 12
    com: {point: [c / 2, 0]}
joints:
  crank_pivot:  {type: revolute, node_a: ground.A0, node_b: crank.O, actuated: true}
  crank_pin:    {type: revolute, node_a: crank.A, node_b: coupler.A}
  rocker_pin:   {type: revolute, node_a: coupler.B, node_b: rocker.B}
  rocker_pivot: {type: revolute, node_a: ground.B0, node_b: rocker.O}
coordinates:
  crank.angle: {rate: {crank.w: 1}}
loads:
  gravity: [0, -9.81]
motion:
  crank.angle: pi/2 + 2*pi*t
run:
  solve: inverse
  duration: 2
  samples: 401
)yaml";

std::string replaced(const std::string& from, const std::string& to) {
  std::string s = kBase;
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

std::string error_of(const std::string& text) {
  try {
    build_scene_model(parse_scene(text, "bad.yaml"));
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

void expect_error(const std::string& text, const std::string& where, const std::string& what) {
  const std::string e = error_of(text);
  EXPECT_EQ(e.rfind(where + ": ", 0), 0u) << "expected at " << where << ", got: " << e;
  EXPECT_NE(e.find(what), std::string::npos) << "expected '" << what << "' in: " << e;
}

TEST(SceneSketch, LengthAndShapeGiveTheExactFourbar) {
  const Model exact =
      build_scene_model(load_scene(std::string(MO2D_MECHANISMS_DIR) + "/fourbar.yaml"));
  const Model sketched = build_scene_model(parse_scene(kBase, "fourbar_sketch.yaml"));
  EXPECT_EQ(sketched.coordinate_labels, exact.coordinate_labels);
  EXPECT_LE((sketched.q0 - exact.q0).cwiseAbs().maxCoeff(), 1e-15);
  // the rocker's centre-of-mass point, given in its frame, is its midpoint
  EXPECT_NEAR(sketched.bodies[2].gamma, 0.5, 1e-15);
  EXPECT_NEAR(sketched.bodies[2].rho, 0, 1e-15);
  // the sketch at the angle 1.8 put B at (d + c cos 1.8, c sin 1.8); the report has it
  ASSERT_EQ(sketched.sketch.nodes.size(), 4u);
  EXPECT_EQ(sketched.sketch.nodes[3].label, "rocker.B");
  EXPECT_NEAR(sketched.sketch.nodes[3].sketch.x(), 0.4 + 0.3 * std::cos(1.8), 1e-15);
  EXPECT_NEAR(sketched.sketch.nodes[3].sketch.y(), 0.3 * std::sin(1.8), 1e-15);
  EXPECT_NEAR(sketched.sketch.nodes[2].moved, 0, 1e-15);  // rocker.O: sketched at the pivot
}

TEST(SceneSketch, Errors) {
  expect_error(replaced("    length: b\n", "    length: b\n    shape: {A: [0, 0], B: [b, 0]}\n"),
               "bad.yaml:17:13", "give either 'shape' or 'length', not both");
  expect_error(replaced("    length: b\n", "    length: -b\n"), "bad.yaml:17:13",
               "a length must be > 0 m");
  expect_error(replaced("nodes: {A: [0, a], B: [0.3, 0.3]}",
                        "nodes: {A: [0, a], B: [0.3, 0.3], "
                        "C: [0, 0]}"),
               "bad.yaml:17:13", "a bar given by its length has exactly two nodes");
  expect_error(replaced("    at: {origin: [d, 0], angle: 1.8}\n",
                        "    nodes: {B: [0.3, 0.3], O: [0.4, 0]}\n"),
               "bad.yaml:24:13", "lists the shape's nodes in the same order (O, B)");
  expect_error(replaced("    at: {origin: [d, 0], angle: 1.8}\n",
                        "    at: {origin: [d, 0]}\n    nodes: {O: [0.4, 0], B: [0.3, 0.3]}\n"),
               "bad.yaml:24:9", "give the sketch either as 'nodes' or as 'at', not both");
  expect_error(replaced("    length: b\n", "    at: {origin: [0, 0]}\n"), "bad.yaml:17:9",
               "places a body given by its 'shape'");
  expect_error(replaced("angle: 1.8}", "angel: 1.8}"), "bad.yaml:24:26", "did you mean 'angle'");
  // lengths that cannot close: at the line of the joint left open
  const std::string e = error_of(replaced("  b: 0.35\n", "  b: 0.05\n"));
  EXPECT_NE(e.find("cannot be assembled"), std::string::npos) << e;
  EXPECT_TRUE(e.rfind("bad.yaml:30:3:", 0) == 0 || e.rfind("bad.yaml:31:3:", 0) == 0 ||
              e.rfind("bad.yaml:32:3:", 0) == 0)
      << e;
}

}  // namespace
}  // namespace mo2d
