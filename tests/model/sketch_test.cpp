// Geometry given by lengths (issue 12, item 7; BodyDef::shape): a mechanism written with exact
// node positions and the same one given by link lengths plus a rough sketch give the same model
// and the same results (inverse efforts and reactions, a forward run) to 1e-12; the sketch picks
// the branch (two mirrored sketches give the two mirrored assemblies); the moved distances of the
// report against closed forms; lengths that cannot close a loop are refused; points given in a
// shaped body's frame (centre of mass, force, spring) land where they belong. The public forms of
// scene files' `length:` and `shape:` + `at:` (mo2d/sketched_body.hpp) give the exact results and
// the scene loader's model.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "error_support.hpp"
#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"
#include "mo2d/sketched_body.hpp"

using namespace mo2d;
using namespace mo2d::test;

namespace {

// Same numbers up to rounding (the exact scenes compute their positions by other formulas).
constexpr double kSame = 1e-12;

double max_abs_diff(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  EXPECT_EQ(a.rows(), b.rows());
  EXPECT_EQ(a.cols(), b.cols());
  if (a.rows() != b.rows() || a.cols() != b.cols()) return 1e300;
  return a.size() ? (a - b).cwiseAbs().maxCoeff() : 0.0;
}

// Same labels, same initial configuration, same inverse results and the same forward run.
void expect_same_results(const Model& a, const Model& b, const std::vector<Prescribed>& motion,
                         InverseOptions o, const std::string& rate) {
  EXPECT_EQ(a.coordinate_labels, b.coordinate_labels);
  EXPECT_EQ(a.rate_labels, b.rate_labels);
  EXPECT_EQ(a.reaction_labels(), b.reaction_labels());
  EXPECT_LE(max_abs_diff(a.q0, b.q0), kSame);
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (size_t k = 0; k < a.bodies.size(); ++k) {
    EXPECT_NEAR(a.bodies[k].l01, b.bodies[k].l01, kSame);
    EXPECT_NEAR(a.bodies[k].gamma, b.bodies[k].gamma, kSame);
    EXPECT_NEAR(a.bodies[k].rho, b.bodies[k].rho, kSame);
  }
  const Trajectory ta = inverse_dynamics(a, motion, o);
  const Trajectory tb = inverse_dynamics(b, motion, o);
  const double efforts = 1 + tb.efforts.cwiseAbs().maxCoeff();
  const double reactions = 1 + tb.reactions.cwiseAbs().maxCoeff();
  EXPECT_LE(max_abs_diff(ta.q0, tb.q0), kSame);
  EXPECT_LE(max_abs_diff(ta.efforts, tb.efforts), kSame * efforts);
  EXPECT_LE(max_abs_diff(ta.reactions, tb.reactions), kSame * reactions);

  // A fixed step: the run is then a smooth function of the model's numbers, which differ in
  // their last bits (an adaptive integrator may take another step sequence for a difference of
  // 1e-16 and then differ by its tolerance). A quarter second: the Watt six-bar amplifies its
  // initial difference of 2e-16 m to 7e-13 m in q0 and 3e-11 in q1 (6e-13 of max |q1|) in 0.5 s.
  ForwardOptions f;
  f.t1 = 0.25;
  f.samples = 11;
  f.integrator = Integrator::rk4;
  f.step = 1e-3;
  const State sa = consistent_state(a, {.positions = {}, .velocities = {{rate, 3.0}}});
  const State sb = consistent_state(b, {.positions = {}, .velocities = {{rate, 3.0}}});
  EXPECT_LE(max_abs_diff(sa.q0, sb.q0), kSame);
  EXPECT_LE(max_abs_diff(sa.q1, sb.q1), kSame);
  const Trajectory fa = forward_dynamics(a, sa, f);
  const Trajectory fb = forward_dynamics(b, sb, f);
  EXPECT_LE(max_abs_diff(fa.q0, fb.q0), kSame);
  EXPECT_LE(max_abs_diff(fa.q1, fb.q1), kSame * (1 + fb.q1.cwiseAbs().maxCoeff()));
}

// The four-bar of mechanisms/fourbar.cpp with the coupler and the rocker given by their lengths
// and the moving pivot B sketched at `b_sketch` (the crank is exact, at `crank_angle`).
System fourbar_by_lengths(Vec2 b_sketch, double crank_angle = std::numbers::pi / 2,
                          double b = 0.35) {
  const double a = 0.1, c = 0.3, d = 0.4;
  const Vec2 A(a * std::cos(crank_angle), a * std::sin(crank_angle));
  System s("fourbar");
  s.add_ground_node("A0", {0, 0}).add_ground_node("B0", {d, 0});
  s.add_body({.name = "crank",
              .nodes = {{"O", {0, 0}}, {"A", A}},
              .mass = 0.2,
              .inertia = 0.2 * a * a / 12,
              .com = CenterOfMass::between("O", "A", 0.5)});
  s.add_body({.name = "coupler",
              .nodes = {{"A", A + Vec2(0.01, -0.02)}, {"B", b_sketch}},  // a rough sketch
              .shape = {{0, 0}, {b, 0}},
              .mass = 0.5,
              .inertia = 0.5 * 0.35 * 0.35 / 12,
              .com = CenterOfMass::between("A", "B", 0.5)});
  s.add_body({.name = "rocker",
              .nodes = {{"O", {d + 0.02, 0.01}}, {"B", b_sketch + Vec2(-0.01, 0.02)}},
              .shape = {{0, 0}, {c, 0}},
              .mass = 0.4,
              .inertia = 0.4 * c * c / 12,
              .com = CenterOfMass::between("O", "B", 0.5)});
  s.add_revolute(
      {.name = "crank_pivot", .node_a = "ground.A0", .node_b = "crank.O", .actuated = true});
  s.add_revolute({.name = "crank_pin", .node_a = "crank.A", .node_b = "coupler.A"});
  s.add_revolute({.name = "rocker_pin", .node_a = "coupler.B", .node_b = "rocker.B"});
  s.add_revolute({.name = "rocker_pivot", .node_a = "ground.B0", .node_b = "rocker.O"});
  s.add_coordinate({.name = "crank.angle", .rate = {{"crank.w", 1.0}}});
  s.set_gravity({0, -9.81});
  return s;
}

Vec2 node_at(const Model& m, const std::string& label) {
  return {m.q0[m.coordinate(label + ".x")], m.q0[m.coordinate(label + ".y")]};
}

}  // namespace

TEST(Sketch, FourbarByLengthsGivesTheExactResults) {
  const mechanisms::Example exact = mechanisms::fourbar();
  const Model a = build_model(fourbar_by_lengths({0.3, 0.3}));
  const Model b = build_model(exact.system);
  EXPECT_TRUE(b.sketch.nodes.empty());  // exact positions: no sketch, nothing moved
  EXPECT_EQ(a.sketch.nodes.size(), 4u);
  EXPECT_TRUE(a.sketch.nearest);
  EXPECT_TRUE(a.sketch.warnings.empty());
  expect_same_results(a, b, exact.motion, exact.run, "crank.w");
}

TEST(Sketch, SliderCrankByLengthsGivesTheExactResults) {
  const mechanisms::Example exact = mechanisms::slider_crank();
  const mechanisms::SliderCrankParams p;
  System s("slider_crank");
  s.add_ground_node("O", {0, 0}).add_ground_node("R1", {0, p.e}).add_ground_node("R2", {1, p.e});
  s.add_body({.name = "crank",
              .nodes = {{"O", {0, 0}}, {"A", {p.r, 0}}},
              .mass = p.m_crank,
              .inertia = p.m_crank * p.r * p.r / 12,
              .com = CenterOfMass::between("O", "A", 0.5)});
  s.add_body({.name = "rod",  // the rod by its length, the slider anywhere near the rail
              .nodes = {{"A", {p.r, 0.02}}, {"B", {0.4, 0.05}}},
              .shape = {{0, 0}, {p.L, 0}},
              .mass = p.m_rod,
              .inertia = p.m_rod * p.L * p.L / 12,
              .com = CenterOfMass::between("A", "B", 0.5)});
  s.add_body(
      {.name = "slider", .nodes = {{"B", {0.45, 0.0}}}, .shape = {{0, 0}}, .mass = p.m_slider});
  s.add_revolute(
      {.name = "crank_pivot", .node_a = "ground.O", .node_b = "crank.O", .actuated = true});
  s.add_revolute({.name = "crank_pin", .node_a = "crank.A", .node_b = "rod.A"});
  s.add_revolute({.name = "wrist_pin", .node_a = "rod.B", .node_b = "slider.B"});
  s.add_prismatic(
      {.name = "rail", .axis_from = "ground.R1", .axis_to = "ground.R2", .slider = "slider.B"});
  s.add_coordinate({.name = "crank.angle", .rate = {{"crank.w", 1.0}}});
  s.set_gravity({0, -p.gravity});
  const Model a = build_model(s);
  const Model b = build_model(exact.system);
  // the slider lands at xb = r + sqrt(L^2 - e^2), the parameter users computed by hand
  EXPECT_NEAR(node_at(a, "rod.B").x(), p.r + std::sqrt(p.L * p.L - p.e * p.e), 1e-15);
  expect_same_results(a, b, exact.motion, exact.run, "crank.w");
}

// The crank along the line of the ground pivots: the two assemblies are mirror images in it.
TEST(Sketch, MirroredSketchesGiveTheMirroredBranches) {
  const Model up = build_model(fourbar_by_lengths({0.3, 0.25}, 0.0));
  const Model down = build_model(fourbar_by_lengths({0.3, -0.25}, 0.0));
  const Vec2 bu = node_at(up, "coupler.B"), bd = node_at(down, "coupler.B");
  EXPECT_GT(bu.y(), 0.1);
  EXPECT_NEAR(bd.x(), bu.x(), 1e-15);
  EXPECT_NEAR(bd.y(), -bu.y(), 1e-15);
  // both on the circles (A, b) and (B0, c): the upper and lower intersections
  for (const Vec2& B : {bu, bd}) {
    EXPECT_NEAR((B - Vec2(0.1, 0)).norm(), 0.35, 1e-15);
    EXPECT_NEAR((B - Vec2(0.4, 0)).norm(), 0.3, 1e-15);
  }
  // closed form: x from the two circle equations
  const double x = 0.1 + (0.35 * 0.35 - 0.3 * 0.3 + 0.3 * 0.3) / (2 * 0.3);
  EXPECT_NEAR(bu.x(), x, 1e-15);
  EXPECT_NEAR(bu.y(), std::sqrt(0.35 * 0.35 - (x - 0.1) * (x - 0.1)), 1e-15);
}

// A bar pinned to the ground at O, sketched with O off the pivot by (dx, dy) and P at P̂: the
// nearest configuration (least squares over both nodes) keeps O at the pivot and puts P at
// L P̂ / |P̂| whatever O's sketch; the nodes moved by |(dx, dy)| and ||P̂| - L|.
TEST(Sketch, MovedDistancesMatchTheClosedForm) {
  const double L = 0.5;
  const Vec2 o_sketch(0.03, -0.04), p_sketch(0.2, 0.6);
  System s("bar");
  s.add_ground_node("O", {0, 0});
  s.add_body({.name = "bar",
              .nodes = {{"O", o_sketch}, {"P", p_sketch}},
              .shape = {{0, 0}, {L, 0}},
              .mass = 1,
              .inertia = 0.01});
  s.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "bar.O"});
  const Model m = build_model(s);
  ASSERT_EQ(m.sketch.nodes.size(), 2u);
  EXPECT_TRUE(m.sketch.nearest);
  const SketchedNode& o = m.sketch.nodes[0];
  const SketchedNode& p = m.sketch.nodes[1];
  EXPECT_EQ(o.label, "bar.O");
  EXPECT_EQ(p.label, "bar.P");
  EXPECT_LE((o.sketch - o_sketch).norm(), 0.0);
  EXPECT_NEAR(o.moved, o_sketch.norm(), 1e-15);
  const Vec2 expected = L * p_sketch.normalized();
  EXPECT_NEAR((p.assembled - expected).norm(), 0, 1e-14);
  EXPECT_NEAR(p.moved, p_sketch.norm() - L, 1e-14);
  EXPECT_NEAR(m.sketch.max_moved(), p_sketch.norm() - L, 1e-14);
  // 0.132 m of a 0.5 m mechanism: more than 10 % of its size, a warning naming the node
  ASSERT_EQ(m.sketch.warnings.size(), 1u);
  EXPECT_NE(m.sketch.warnings[0].find("'bar.P' moved 0.1325 m"), std::string::npos)
      << m.sketch.warnings[0];
  EXPECT_NE(describe(m).find("bar.P sketched (0.2, 0.6)"), std::string::npos) << describe(m);
}

TEST(Sketch, LengthsThatCannotCloseTheLoopAreRefused) {
  // |A - B0| = sqrt(0.17) = 0.4123 > b + c = 0.05 + 0.3: the loop misses 0.0623 m
  Error e("");
  EXPECT_TRUE(ThrowsError(building(fourbar_by_lengths({0.3, 0.3}, std::numbers::pi / 2, 0.05)),
                          {"cannot be assembled", "stays open", "in the loop",
                           "-> ground -> crank ->", "0.0623", "m in all"},
                          &e));
  EXPECT_TRUE(e.element() == "crank_pin" || e.element() == "rocker_pin" ||
              e.element() == "rocker_pivot")
      << e.element();
}

TEST(Sketch, ShapeErrors) {
  System s("s");
  s.add_ground_node("O", {0, 0});
  s.add_body({.name = "bar",
              .nodes = {{"O", {0, 0}}, {"P", {1, 0}}},
              .shape = {{0, 0}, {1, 0}, {2, 0}},
              .mass = 1});
  EXPECT_TRUE(ThrowsError(building(s), {"body 'bar'", "3 point(s) for 2 node(s)"}));
  System t("t");
  t.add_body({.name = "bar",
              .nodes = {{"O", {0, 0}}, {"P", {1, 0}}},
              .shape = {{0, 0}, {0, 0}},
              .mass = 1});
  EXPECT_TRUE(ThrowsError(building(t), {"body 'bar'", "first two nodes of its shape coincide"}));
}

// Points given on a body with a shape are in its frame: the centre of mass, a force and a
// spring at the middle of a bar stay at its middle, also inside a rotated instance (whose angle
// turns the sketch, not the body frame).
TEST(Sketch, PointsOnAShapedBodyAreInItsFrame) {
  const double L = 0.4;
  System leg("leg");
  leg.add_ground_node("O", {0, 0});
  leg.add_body({.name = "bar",
                .nodes = {{"O", {0.01, 0}}, {"P", {0, 0.38}}},
                .shape = {{0, 0}, {L, 0}},
                .mass = 1,
                .inertia = 0.01,
                .com = CenterOfMass::at_point({L / 2, 0.05})});
  leg.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "bar.O"});
  leg.add_force({.name = "push", .body = "bar", .point = {L / 2, 0}, .fx = {}, .fy = {}});
  leg.add_spring({.name = "tie",
                  .body_a = "ground",
                  .point_a = {0.3, 0},
                  .body_b = "bar",
                  .point_b = {L, 0.1},
                  .rest_length = 0,
                  .stiffness = 1,
                  .damping = 0});
  System root("root");
  root.add_instance("a", leg, {.offset = {1, 2}, .angle = 0.7});
  const Model m = build_model(root);
  const Body& b = m.bodies[0];
  EXPECT_NEAR(b.gamma, 0.5, 1e-14);
  EXPECT_NEAR(b.rho, 0.05 / L, 1e-14);
  ASSERT_EQ(m.forces.size(), 1u);
  EXPECT_NEAR(m.forces[0].gamma, 0.5, 1e-14);
  EXPECT_NEAR(m.forces[0].rho, 0, 1e-14);
  ASSERT_EQ(m.springs.size(), 1u);
  EXPECT_NEAR(m.springs[0].b.gamma, 1, 1e-14);
  EXPECT_NEAR(m.springs[0].b.rho, 0.1 / L, 1e-14);
  // the ground end is a System point: placed by the instance
  EXPECT_NEAR((m.springs[0].a.fixed - Placement{{1, 2}, 0.7}.apply({0.3, 0})).norm(), 0, 1e-15);
  // the bar points where its sketch does (the instance turns the sketch by 0.7 rad):
  const Vec2 p = node_at(m, "a.bar.P") - Vec2(1, 2);
  EXPECT_NEAR(p.norm(), L, 1e-15);
  // nearest: O stays at the pivot, so P points from the pivot to its sketch (0, 0.38)
  EXPECT_NEAR(std::atan2(p.y(), p.x()), 0.7 + std::numbers::pi / 2, 1e-14);
}

// The shipped example against the scene of the same Watt six-bar with hand-computed positions.
TEST(Sketch, WattSixbarByLengthsSceneGivesTheExactResults) {
  const Scene by_lengths =
      load_scene(std::string(MO2D_MECHANISMS_DIR) + "/watt_sixbar_lengths.yaml");
  const Scene exact = load_scene(std::string(MO2D_TEST_DATA_DIR) + "/watt_sixbar.yaml");
  const Model a = build_scene_model(by_lengths);
  const Model b = build_scene_model(exact);
  EXPECT_EQ(a.sketch.nodes.size(), 9u);
  EXPECT_TRUE(a.sketch.warnings.empty());
  InverseOptions o = inverse_options(exact);
  expect_same_results(a, b, exact.motion, o, "crank.w");
}

namespace {

// fourbar_by_lengths written with the public forms of scene files' `length:` (bar_body) and
// `shape:` + `at:` (placed_body), mo2d/sketched_body.hpp.
System fourbar_by_bar_and_placed_body(Vec2 b_sketch, double rocker_angle) {
  const double a = 0.1, b = 0.35, c = 0.3, d = 0.4;
  System s("fourbar");
  s.add_ground_node("A0", {0, 0}).add_ground_node("B0", {d, 0});
  s.add_body({.name = "crank",
              .nodes = {{"O", {0, 0}}, {"A", {0, a}}},
              .mass = 0.2,
              .inertia = 0.2 * a * a / 12,
              .com = CenterOfMass::between("O", "A", 0.5)});
  BodyDef coupler = bar_body("coupler", b, {"A", {0.01, a - 0.02}}, {"B", b_sketch});
  coupler.mass = 0.5;
  coupler.inertia = 0.5 * b * b / 12;
  coupler.com = CenterOfMass::between("A", "B", 0.5);
  s.add_body(coupler);
  BodyDef rocker = placed_body("rocker", {{"O", {0, 0}}, {"B", {c, 0}}}, {{d, 0}, rocker_angle});
  rocker.mass = 0.4;
  rocker.inertia = 0.4 * c * c / 12;
  rocker.com = CenterOfMass::between("O", "B", 0.5);
  s.add_body(rocker);
  s.add_revolute(
      {.name = "crank_pivot", .node_a = "ground.A0", .node_b = "crank.O", .actuated = true});
  s.add_revolute({.name = "crank_pin", .node_a = "crank.A", .node_b = "coupler.A"});
  s.add_revolute({.name = "rocker_pin", .node_a = "coupler.B", .node_b = "rocker.B"});
  s.add_revolute({.name = "rocker_pivot", .node_a = "ground.B0", .node_b = "rocker.O"});
  s.add_coordinate({.name = "crank.angle", .rate = {{"crank.w", 1.0}}});
  s.set_gravity({0, -9.81});
  return s;
}

// The same four-bar as a scene file gives it (docs/scene-format.md, "Bodies given by their
// shape").
constexpr const char* kFourbarScene = R"(name: fourbar
ground: {A0: [0, 0], B0: [0.4, 0]}
bodies:
  crank: {nodes: {O: [0, 0], A: [0, 0.1]}, mass: 0.2, inertia: 0.2 * 0.1^2 / 12,
          com: {between: [O, A]}}
  coupler: {length: 0.35, nodes: {A: [0.01, 0.08], B: [0.3, 0.3]}, mass: 0.5,
            inertia: 0.5 * 0.35^2 / 12, com: {between: [A, B]}}
  rocker: {shape: {O: [0, 0], B: [0.3, 0]}, at: {origin: [0.4, 0], angle: 1.8}, mass: 0.4,
           inertia: 0.4 * 0.3^2 / 12, com: {between: [O, B]}}
joints:
  crank_pivot: {type: revolute, node_a: ground.A0, node_b: crank.O, actuated: true}
  crank_pin: {type: revolute, node_a: crank.A, node_b: coupler.A}
  rocker_pin: {type: revolute, node_a: coupler.B, node_b: rocker.B}
  rocker_pivot: {type: revolute, node_a: ground.B0, node_b: rocker.O}
coordinates: {crank.angle: {rate: {crank.w: 1}}}
loads: {gravity: [0, -9.81]}
motion: {crank.angle: pi / 2 + 2 * pi * t}
)";

}  // namespace

TEST(Sketch, BarAndPlacedBodyGiveTheExactResults) {
  const mechanisms::Example exact = mechanisms::fourbar();
  const Model a = build_model(fourbar_by_bar_and_placed_body({0.3, 0.3}, 1.8));
  const Model b = build_model(exact.system);
  EXPECT_EQ(a.sketch.nodes.size(), 4u);
  EXPECT_TRUE(a.sketch.warnings.empty());
  expect_same_results(a, b, exact.motion, exact.run, "crank.w");
  // the sketch picks the branch: B and the rocker sketched below the line A-B0, elbow down
  const Model down = build_model(fourbar_by_bar_and_placed_body({0.25, -0.2}, -1.8));
  EXPECT_LT(node_at(down, "coupler.B").y(), 0);
  EXPECT_NEAR((node_at(down, "coupler.B") - node_at(down, "crank.A")).norm(), 0.35, kSame);
}

TEST(Sketch, BarAndPlacedBodyAreTheSceneLoaders) {
  const Model from_scene = build_scene_model(parse_scene(kFourbarScene, "fourbar.yaml"));
  const Model from_cpp = build_model(fourbar_by_bar_and_placed_body({0.3, 0.3}, 1.8));
  EXPECT_EQ(from_scene.coordinate_labels, from_cpp.coordinate_labels);
  EXPECT_LE(max_abs_diff(from_scene.q0, from_cpp.q0), kSame);
}

TEST(Sketch, BarAndPlacedBodyErrors) {
  const NodeDef na{"A", {0, 0}}, nb{"B", {1, 0}};
  for (double length : {0.0, -1.0, kNaN, kInf})
    EXPECT_TRUE(ThrowsError([&] { bar_body("bar", length, na, nb); },
                            {"body 'bar': a bar's length must be finite and > 0 m"}));
  EXPECT_TRUE(ThrowsError([] { placed_body("plate", {}, {}); },
                          {"body 'plate': a shape needs at least one node"}));
  const BodyDef p =
      placed_body("plate", {{"O", {0, 0}}, {"P", {1, 0}}}, {{2, 3}, std::numbers::pi / 2});
  EXPECT_NEAR((p.nodes[1].position - Vec2(2, 4)).norm(), 0, 1e-15);  // rotated, then shifted
  EXPECT_EQ(p.shape[1], Vec2(1, 0));
}
