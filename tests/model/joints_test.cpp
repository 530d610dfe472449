// Joint definitions that contradict the bodies' shapes (the copies of a joint node apart, a slider
// off its axis) are refused with the joint, both nodes and the gap; the check is dimensionless.
// Prescribed body angles other than the crank's (inverse dynamics), initial velocities that the
// constraints fix (forward dynamics): what runs, and what is refused says why.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "mo2d/error.hpp"
#include "mo2d/forward.hpp"
#include "mo2d/inverse.hpp"
#include "mo2d/mechanisms.hpp"
#include "mo2d/model.hpp"
#include "mo2d/scene.hpp"
#include "test_support.hpp"

namespace mo2d {
namespace {

// The crank-rocker four-bar of mechanisms::fourbar() scaled by `s` (lengths in m), with the
// coupler's copy of the crank pin moved by `gap` (the crank's copy stays exact).
System fourbar(double s, Vec2 gap = {0, 0}, Vec2 pivot_gap = {0, 0}) {
  const double a = 0.1 * s, b = 0.35 * s, c = 0.3 * s, d = 0.4 * s;
  const Vec2 A(0, a), B0(d, 0);
  const Vec2 AB0 = B0 - A;
  const double l = AB0.norm(), x = (b * b - c * c + l * l) / (2 * l);
  const Vec2 ex = AB0 / l, ey(-ex.y(), ex.x());
  const Vec2 B = A + x * ex + std::sqrt(b * b - x * x) * ey;
  System sys("fourbar");
  sys.add_ground_node("A0", {0, 0}).add_ground_node("B0", B0);
  sys.add_body({.name = "crank", .nodes = {{"O", pivot_gap}, {"A", A}}, .mass = 1, .inertia = 1});
  sys.add_body({.name = "coupler", .nodes = {{"A", A + gap}, {"B", B}}, .mass = 1, .inertia = 1});
  sys.add_body({.name = "rocker", .nodes = {{"O", B0}, {"B", B}}, .mass = 1, .inertia = 1});
  sys.add_revolute({.name = "pivot", .node_a = "ground.A0", .node_b = "crank.O", .actuated = true});
  sys.add_revolute({.name = "crank_pin", .node_a = "crank.A", .node_b = "coupler.A"});
  sys.add_revolute({.name = "rocker_pin", .node_a = "coupler.B", .node_b = "rocker.B"});
  sys.add_revolute({.name = "rocker_pivot", .node_a = "ground.B0", .node_b = "rocker.O"});
  return sys;
}

std::string build_error(const System& s, BuildOptions o = {}) {
  try {
    build_model(s, o);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

void expect_contains(const std::string& text, std::initializer_list<const char*> parts) {
  for (const char* p : parts) EXPECT_NE(text.find(p), std::string::npos) << p << " in: " << text;
}

// The issue's case: the coupler's copy of the crank pin 4.2 cm from the crank's (a user who took
// positions for approximate). It used to build: the coupler's length silently became 0.35 m +-
// the gap, and the joint reported "consistent".
TEST(Joints, JointNodeCopiesApartAreRefused) {
  const System s = fourbar(1.0, {-0.03, 0.03});
  const std::string e = build_error(s);
  expect_contains(e, {"revolute joint 'crank_pin'", "'crank.A'", "'coupler.A'", "0.04243 m apart",
                      "of the mechanism's size", "tolerance 1e-06"});
  try {
    build_model(s);
  } catch (const Error& err) {
    EXPECT_EQ(err.element(), "crank_pin");
  }
  // with the reductions that keep the joint as constraint rows too
  expect_contains(build_error(s, {.reduction = Reduction::none}), {"'crank_pin'", "0.04243"});
  // and the copy is what defines the coupler's length: allowed explicitly, the length changes
  const Model m = build_model(s, {.joint_tolerance = 1.0});
  const Vec2 A(m.q0[m.coordinate("crank.A.x")], m.q0[m.coordinate("crank.A.y")]);
  const Vec2 B(m.q0[m.coordinate("coupler.B.x")], m.q0[m.coordinate("coupler.B.y")]);
  EXPECT_GT(std::abs((B - A).norm() - 0.35), 0.01);
}

// A body's copy of a ground node (here the crank's pivot) is a copy of a joint node too.
TEST(Joints, GroundPivotCopyApartIsRefused) {
  expect_contains(build_error(fourbar(1.0, {0, 0}, {0.001, 0})),
                  {"revolute joint 'pivot'", "'ground.A0'", "'crank.O'", "0.001 m apart"});
}

// The tolerance is relative to the mechanism's size: the same relative gap is refused (1e-5) or
// accepted (1e-8, and the round-off of the computed positions) at every scale from 1 cm to 10 km.
TEST(Joints, GapToleranceIsDimensionless) {
  for (double s : {0.1, 1.0, 1e3, 1e5}) {
    const double size = build_model(fourbar(s)).scale;  // box diagonal (> 1 mm here)
    EXPECT_NE(build_error(fourbar(s, {1e-5 * size, 0})), "") << "scale " << s;
    EXPECT_EQ(build_error(fourbar(s, {1e-8 * size, 0})), "") << "scale " << s;
    EXPECT_EQ(build_error(fourbar(s)), "") << "scale " << s;
  }
  // a mechanism 0.1 mm in size (below the 1 mm floor of Model::scale): still relative to its size
  EXPECT_NE(build_error(fourbar(1e-3, {1e-5 * 5.1e-4, 0})), "");
  EXPECT_EQ(build_error(fourbar(1e-3, {1e-8 * 5.1e-4, 0})), "");
}

// A slider must lie on the line of its axis (anywhere along it, also beyond the axis nodes): the
// slider node is part of its body's shape, exactly like the copy of a revolute node.
TEST(Joints, SliderOffItsAxisIsRefused) {
  auto slider = [](double y, bool slot) {
    System s("slide");
    s.add_ground_node("R1", {0, 0}).add_ground_node("R2", {1, 0}).add_ground_node("O", {0, 0.5});
    s.add_body(
        {.name = "rod", .nodes = {{"O", {0, 0.5}}, {"B", {2.0, y}}}, .mass = 1, .inertia = 1});
    s.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "rod.O"});
    if (slot)
      s.add_pin_in_slot(
          {.name = "rail", .axis_from = "ground.R1", .axis_to = "ground.R2", .pin = "rod.B"});
    else {
      s.add_body({.name = "block", .nodes = {{"B", {2.0, y}}}, .mass = 1});
      s.add_revolute({.name = "wrist", .node_a = "rod.B", .node_b = "block.B"});
      s.add_prismatic(
          {.name = "rail", .axis_from = "ground.R1", .axis_to = "ground.R2", .slider = "block.B"});
    }
    return build_error(s);
  };
  for (bool slot : {false, true}) {
    expect_contains(slider(0.01, slot),
                    {"joint 'rail'", slot ? "pin 'rod.B'" : "slider 'block.B'", "'ground.R1'",
                     "'ground.R2'", "0.01 m apart", "a slider must lie on the line of its axis"});
    EXPECT_EQ(slider(0.0, slot), "") << "slot " << slot;
  }
}

// Every shipped mechanism builds (their positions are exact, to round-off, including the 3RRR's
// legs placed at 120 degrees and the Whitworth's pin in its slot).
TEST(Joints, ShippedMechanismsPassTheGapCheck) {
  for (const System& s : {mechanisms::whitworth().system, mechanisms::rrr3().system,
                          mechanisms::fourbar().system, mechanisms::slider_crank().system,
                          mechanisms::pendulum().system, mechanisms::double_fourbar()}) {
    EXPECT_EQ(build_error(s), "") << s.name();
    EXPECT_EQ(build_error(s, {.reduction = Reduction::none}), "") << s.name();
  }
}

// From a scene file the error is at the joint's line and column.
TEST(Joints, GapInASceneIsReportedAtTheJoint) {
  const std::string text = R"yaml(name: p
ground:
  O: [0, 0]
bodies:
  upper:
    nodes: {O: [0, 0], E: [0.3, 0]}
    mass: 1
    inertia: 0.01
  lower:
    nodes: {E: [0.3, 0.02], P: [0.6, 0]}
    mass: 1
    inertia: 0.01
joints:
  pivot: {type: revolute, node_a: ground.O, node_b: upper.O}
  elbow: {type: revolute, node_a: upper.E, node_b: lower.E}
)yaml";
  try {
    build_scene_model(parse_scene(text, "gap.yaml"));
    ADD_FAILURE() << "expected a SceneError";
  } catch (const SceneError& e) {
    const std::string w = e.what();
    EXPECT_EQ(w.rfind("gap.yaml:15:3: ", 0), 0u) << w;
    expect_contains(w, {"revolute joint 'elbow'", "'upper.E'", "'lower.E'", "0.02 m apart"});
  }
}

// ---- prescribed body angles -----------------------------------------------------------------

System fourbar_with_angles() {
  System s = fourbar(1.0);
  s.add_coordinate({.name = "crank.angle", .rate = {{"crank.w", 1.0}}});
  s.add_coordinate({.name = "coupler.angle", .rate = {{"coupler.w", 1.0}}});
  s.add_coordinate({.name = "rocker.angle", .rate = {{"rocker.w", 1.0}}});
  s.set_gravity({0, -9.81});
  return s;
}

// The coupler's angle over a full crank turn, from circle intersections (independent of mo2d).
std::pair<double, double> coupler_range() {
  const double a = 0.1, b = 0.35, c = 0.3, d = 0.4;
  double lo = 10, hi = -10;
  for (int i = 0; i < 200000; ++i) {
    const double phi = 2 * M_PI * i / 200000;
    const Vec2 A(a * std::cos(phi), a * std::sin(phi)), AB0 = Vec2(d, 0) - A;
    const double l = AB0.norm(), x = (b * b - c * c + l * l) / (2 * l);
    const Vec2 ex = AB0 / l, ey(-ex.y(), ex.x());
    const Vec2 B = A + x * ex + std::sqrt(b * b - x * x) * ey;
    const double psi = std::atan2(B.y() - A.y(), B.x() - A.x());
    lo = std::min(lo, psi);
    hi = std::max(hi, psi);
  }
  return {lo, hi};
}

// Prescribing the coupler's angle from its initial value runs, and gives the crank torque that
// prescribing the crank's angle gives for the same motion (a second choice of independent
// coordinates: another null-space basis C).
TEST(Joints, PrescribedCouplerAngleGivesTheCrankDrivenTorque) {
  const Model m = build_model(fourbar_with_angles());
  const double c0 = m.q0[m.coordinate("coupler.angle")];
  EXPECT_NEAR(c0, body_angle(m.bodies[1], m.q0), 1e-15);
  const std::vector<Prescribed> coupler{
      {"coupler.angle", [c0](Jet t) { return Jet(c0) + 0.03 * sin(2.0 * t); }}};
  const Trajectory r = inverse_dynamics(m, coupler, {.t0 = 0, .t1 = 1, .samples = 11});
  const int ic = r.column("crank.angle"), u = r.effort("pivot.torque");
  for (int i = 0; i < r.time.size(); ++i) {
    const double ti = r.time[i], phi = r.q0(i, ic), w = r.q1(i, ic), al = r.a1(i, ic);
    const std::vector<Prescribed> crank{{"crank.angle", [=](Jet t) {
                                           const Jet h = t - ti;
                                           return Jet(phi) + w * h + 0.5 * al * h * h;
                                         }}};
    const Trajectory rc = inverse_dynamics(m, crank, {.t0 = ti, .t1 = ti, .samples = 1});
    EXPECT_NEAR(rc.efforts(0, 0), r.efforts(i, u), 1e-9 * (1 + std::abs(r.efforts(i, u))))
        << "t = " << ti;
    EXPECT_NEAR(rc.q0(0, r.column("coupler.angle")), r.q0(i, r.column("coupler.angle")), 1e-12);
  }
}

// The issue's probe prescribed coupler.angle = 0.01 t: at t = 0 the coupler would lie horizontal,
// outside its range [0.5235, 1.1180] rad (the closure needs cos(crank angle) = -7.75). The
// refusal said "Newton did not converge, residual 2.2e-07 (leaves the workspace?)"; it now names
// the initial value and the limit where the positions stop, which is the range's end.
TEST(Joints, CouplerAngleOutsideItsRangeNamesTheLimit) {
  const Model m = build_model(fourbar_with_angles());
  const auto [lo, hi] = coupler_range();
  EXPECT_NEAR(lo, 0.52351, 1e-4);
  EXPECT_NEAR(hi, 1.11798, 1e-4);
  const std::vector<Prescribed> coupler{{"coupler.angle", [](Jet t) { return 0.01 * t; }}};
  try {
    inverse_dynamics(m, coupler, {.t0 = 0, .t1 = 1, .samples = 3});
    ADD_FAILURE() << "expected an Error";
  } catch (const Error& e) {
    const std::string w = e.what();
    expect_contains(w, {"coupler.angle = 0 cannot be reached from the initial configuration",
                        "near-singular", "a limit of the workspace"});
    const std::string key = "only to coupler.angle = ";
    ASSERT_NE(w.find(key), std::string::npos) << w;
    EXPECT_NEAR(std::stod(w.substr(w.find(key) + key.size())), lo, 1e-4) << w;
    EXPECT_EQ(e.element(), "coupler.angle");
    EXPECT_EQ(e.time(), 0.0);
  }
}

// ---- initial velocities ----------------------------------------------------------------------

// A point-mass pendulum: massless rod O-P pivoted at the ground, one-node bob at P, at angle th.
System bob_pendulum(double th, double L = 1.0) {
  const Vec2 P(L * std::cos(th), L * std::sin(th));
  System s("bob");
  s.add_ground_node("O", {0, 0});
  s.add_body({.name = "rod", .nodes = {{"O", {0, 0}}, {"P", P}}, .mass = 0});
  s.add_body({.name = "bob", .nodes = {{"B", P}}, .mass = 1});
  s.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "rod.O"});
  s.add_revolute({.name = "hang", .node_a = "rod.P", .node_b = "bob.B"});
  s.set_gravity({0, -9.81});
  return s;
}

std::string state_error(const Model& m, const InitialConditions& ic) {
  try {
    consistent_state(m, ic);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// Either velocity of the bob can be given wherever it is free (v = w z x r, r = L (cos, sin)).
TEST(Joints, BobVelocityGivenAsVxOrVy) {
  const double L = 0.7;
  for (double th : {-1.2, -0.3, 0.4, 2.5}) {
    const Model m = build_model(bob_pendulum(th, L));
    const State sx = consistent_state(m, {.positions = {}, .velocities = {{"bob.B.vx", 0.5}}});
    EXPECT_NEAR(sx.q1[m.rate("rod.w")], 0.5 / (-L * std::sin(th)), 1e-12) << th;
    const State sy = consistent_state(m, {.positions = {}, .velocities = {{"bob.B.vy", 0.5}}});
    EXPECT_NEAR(sy.q1[m.rate("rod.w")], 0.5 / (L * std::cos(th)), 1e-12) << th;
    EXPECT_NEAR(sy.q1[m.rate("bob.B.vx")], -L * std::sin(th) * sy.q1[m.rate("rod.w")], 1e-12);
  }
}

// Lying horizontal, the bob moves vertically: its vx is 0 whatever the motion, so it cannot be
// the independent initial velocity. That is not a singular configuration (the refusal said
// "singular start"): the error says which velocity the constraints fix, to what, and what to
// give instead; hanging, the same for vy.
TEST(Joints, VelocityFixedByTheConstraintsIsNamed) {
  for (auto [th, fixed] : {std::pair{0.0, "bob.B.vx"}, std::pair{M_PI, "bob.B.vx"},
                           std::pair{-M_PI / 2, "bob.B.vy"}}) {
    const Model m = build_model(bob_pendulum(th));
    const std::string e = state_error(m, {.positions = {}, .velocities = {{fixed, 1.0}}});
    expect_contains(
        e, {"the constraints fix", fixed, "(= ", "configuration is regular", "give instead e.g."});
    EXPECT_EQ(e.find("singular start"), std::string::npos) << e;
    // the label suggested instead works
    const std::string key = "give instead e.g. ";
    const std::string instead = e.substr(e.find(key) + key.size());
    EXPECT_EQ(state_error(m, {.positions = {}, .velocities = {{instead, 1.0}}}), "") << instead;
  }
  // a double pendulum given the same variable under two names: tied, not singular
  System s = bob_pendulum(-1.0);
  s.add_body({.name = "rod2",
              .nodes = {{"P", {std::cos(-1.0), std::sin(-1.0)}}, {"Q", {1.5, 0}}},
              .mass = 1,
              .inertia = 0.1});
  s.add_revolute({.name = "knee", .node_a = "bob.B", .node_b = "rod2.P"});
  const Model m2 = build_model(s);
  expect_contains(
      state_error(m2, {.positions = {}, .velocities = {{"bob.B.vx", 1}, {"rod2.P.vx", 1}}}),
      {"bob.B.vx, rod2.P.vx", "tied to each other", "give instead e.g."});
}

// A configuration where the constraints themselves lose rank is called singular.
TEST(Joints, SingularConfigurationIsCalledSingular) {
  const Model m = build_model(test::flat_parallelogram(), {.assemble = false});
  expect_contains(state_error(m, {.positions = {}, .velocities = {{"crank.w", 1}}}),
                  {"configuration is singular", "lose rank"});
}

}  // namespace
}  // namespace mo2d
