// Scene files: each mechanisms/*.yaml builds the same model as its C++ twin (labels, sizes, q0)
// and gives the same inverse (or forward) results; parameters, overrides and subsystems.
#include "mo2d/scene.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <span>
#include <string>

#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"

namespace mo2d {
namespace {

// Same operations on the same numbers up to the association of a few constants: rounding only.
constexpr double kSame = 1e-12;

std::string scene_path(const std::string& name) {
  return std::string(MO2D_MECHANISMS_DIR) + "/" + name + ".yaml";
}

double max_abs_diff(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  EXPECT_EQ(a.rows(), b.rows());
  EXPECT_EQ(a.cols(), b.cols());
  if (a.rows() != b.rows() || a.cols() != b.cols() || a.size() == 0)
    return a.size() == b.size() ? 0 : 1e300;
  return (a - b).cwiseAbs().maxCoeff();
}

void expect_same_model(const Model& a, const Model& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.n0, b.n0);
  EXPECT_EQ(a.n1, b.n1);
  EXPECT_EQ(a.m0, b.m0);
  EXPECT_EQ(a.m1, b.m1);
  EXPECT_EQ(a.dof, b.dof);
  EXPECT_EQ(a.coordinate_labels, b.coordinate_labels);
  EXPECT_EQ(a.rate_labels, b.rate_labels);
  EXPECT_EQ(a.input_labels(), b.input_labels());
  EXPECT_EQ(a.reaction_labels(), b.reaction_labels());
  EXPECT_EQ(a.bodies.size(), b.bodies.size());
  for (size_t k = 0; k < std::min(a.bodies.size(), b.bodies.size()); ++k) {
    EXPECT_EQ(a.bodies[k].name, b.bodies[k].name);
    EXPECT_NEAR(a.bodies[k].mass, b.bodies[k].mass, kSame);
    EXPECT_NEAR(a.bodies[k].inertia, b.bodies[k].inertia, kSame);
  }
  EXPECT_LE(max_abs_diff(a.gravity, b.gravity), kSame);
  EXPECT_LE(max_abs_diff(a.q0, b.q0), kSame);
}

void expect_same_inverse(const std::string& name, const mechanisms::Example& ex) {
  SCOPED_TRACE(name);
  const Scene scene = load_scene(scene_path(name));
  const Model from_scene = build_scene_model(scene);
  const Model from_cpp = build_model(ex.system);
  expect_same_model(from_scene, from_cpp);

  ASSERT_EQ(scene.run.solve, Solve::inverse);
  const InverseOptions o = inverse_options(scene);
  EXPECT_EQ(o.t0, ex.run.t0);
  EXPECT_NEAR(o.t1, ex.run.t1, kSame);
  EXPECT_EQ(o.samples, ex.run.samples);
  ASSERT_EQ(scene.motion.size(), ex.motion.size());
  for (size_t k = 0; k < ex.motion.size(); ++k)
    EXPECT_EQ(scene.motion[k].coordinate, ex.motion[k].coordinate);

  const Trajectory a = inverse_dynamics(from_scene, scene.motion, o);
  const Trajectory b = inverse_dynamics(from_cpp, ex.motion, o);
  const double effort_scale = 1 + b.efforts.cwiseAbs().maxCoeff();
  const double reaction_scale = 1 + b.reactions.cwiseAbs().maxCoeff();
  EXPECT_LE(max_abs_diff(a.q0, b.q0), kSame);
  EXPECT_LE(max_abs_diff(a.q1, b.q1), kSame * 10);
  EXPECT_LE(max_abs_diff(a.efforts, b.efforts), kSame * effort_scale);
  EXPECT_LE(max_abs_diff(a.reactions, b.reactions), kSame * reaction_scale);
}

TEST(Scene, WhitworthMatchesCpp) {
  expect_same_inverse("whitworth", mechanisms::whitworth());
}
TEST(Scene, PendulumMatchesCpp) {
  expect_same_inverse("pendulum", mechanisms::pendulum());
}
TEST(Scene, SliderCrankMatchesCpp) {
  expect_same_inverse("slider_crank", mechanisms::slider_crank());
}
TEST(Scene, FourbarMatchesCpp) {
  expect_same_inverse("fourbar", mechanisms::fourbar());
}
TEST(Scene, Rrr3WithLegSubsystemMatchesCpp) {
  expect_same_inverse("rrr3", mechanisms::rrr3());
}

TEST(Scene, DoubleFourbarForwardMatchesCpp) {
  const Scene scene = load_scene(scene_path("double_fourbar"));
  ASSERT_EQ(scene.run.solve, Solve::forward);
  const Model from_scene = build_scene_model(scene);
  const Model from_cpp = build_model(mechanisms::double_fourbar());
  expect_same_model(from_scene, from_cpp);
  ForwardOptions o = forward_options(scene, from_scene);
  o.t1 = o.t0 + 2;  // 2 s are enough to compare (the full 10 s run is the CLI's)
  o.samples = 21;
  const State s_scene = initial_state(scene, from_scene);
  const State s_cpp =
      consistent_state(from_cpp, {.positions = {}, .velocities = {{"crank0.w", -1.0}}});
  EXPECT_LE(max_abs_diff(s_scene.q0, s_cpp.q0), kSame);
  EXPECT_LE(max_abs_diff(s_scene.q1, s_cpp.q1), kSame);
  const Trajectory a = forward_dynamics(from_scene, s_scene, o);
  const Trajectory b = forward_dynamics(from_cpp, s_cpp, o);
  EXPECT_LE(max_abs_diff(a.q0, b.q0), kSame);
  EXPECT_LE(max_abs_diff(a.q1, b.q1), kSame);
}

TEST(Scene, ParametersInDependencyOrderAndOverrides) {
  const std::string text = R"yaml(
name: p
parameters:
  b: 2 * a      # uses a parameter defined below
  a: 3
ground: {O: [0, 0]}
bodies:
  link: {nodes: {O: [0, 0], P: [b, 0]}, mass: a, com: P}
joints:
  pivot: {type: revolute, node_a: ground.O, node_b: link.O, actuated: true}
)yaml";
  const Scene s = parse_scene(text, "p.yaml");
  ASSERT_EQ(s.parameters.size(), 2u);
  EXPECT_EQ(s.parameters[0].first, "a");
  EXPECT_EQ(s.parameters[1].second, 6.0);
  EXPECT_EQ(s.system.bodies()[0].nodes[1].position.x(), 6.0);
  const ParameterOverride o[] = {parse_override("a=0.5 * 3")};
  const Scene s2 = parse_scene(text, "p.yaml", o);
  EXPECT_EQ(s2.system.bodies()[0].mass, 1.5);
  EXPECT_EQ(s2.system.bodies()[0].nodes[1].position.x(), 3.0);
}

TEST(Scene, UserConstraintAndLoadsBuild) {
  // A slider on a free point held on the circle x^2 + y^2 = R^2 by a user constraint, with a
  // force, a torque-free spring to the ground and gravity: builds with DOF 1.
  const std::string text = R"yaml(
name: bead
parameters: {R: 0.5}
bodies:
  bead: {nodes: {P: [R, 0]}, mass: 1}
coordinates: {}
constraints:
  circle: {psi: "bead.P.x^2 + bead.P.y^2 - R^2"}
loads:
  gravity: [0, -9.81]
  forces:
    push: {body: bead, point: [R, 0], fx: "0.1*sin(t)", fy: 0}
  springs:
    tether: {body_a: ground, point_a: [0, 0], body_b: bead, point_b: [R, 0], rest_length: R,
             stiffness: 10, damping: 0.1}
initial:
  velocities: {bead.P.vy: 1}
run: {solve: forward, duration: 0.1, samples: 3}
)yaml";
  const Scene s = parse_scene(text, "bead.yaml");
  const Model m = build_scene_model(s);
  EXPECT_EQ(m.dof, 1);
  const Trajectory r = forward_dynamics(m, initial_state(s, m), forward_options(s, m));
  EXPECT_LE(r.residuals.col(0).maxCoeff(), 1e-8);
}

// A user constraint (expression of a coordinate label and t) and every kind of load, written once
// in YAML and once in C++: same model, same inverse dynamics.
TEST(Scene, UserConstraintAndLoadsMatchCpp) {
  const std::string text = R"yaml(
name: loaded
parameters: {h: 0.02}
ground: {O: [0, 0]}
bodies:
  crank: {nodes: {O: [0, 0], A: [0.1, 0]}, mass: 0.5, inertia: 0.001, com: {between: [O, A]}}
  rod: {nodes: {A: [0.1, 0], B: [0.45, 0]}, mass: 0.3, inertia: 0.003, com: {between: [A, B]}}
joints:
  pivot: {type: revolute, node_a: ground.O, node_b: crank.O, actuated: true}
  pin: {type: revolute, node_a: crank.A, node_b: rod.A}
coordinates:
  crank.angle: {rate: {crank.w: 1}}
constraints:
  on_line: {psi: "rod.B.y - h * sin(t)"}
loads:
  gravity: [0, -9.81]
  forces: {push: {body: rod, point: [0.45, 0], fx: -2 * cos(t), fy: 0.5}}
  torques: {drag: {body: rod, torque: -0.1 * t}}
  springs:
    s: {body_a: ground, point_a: [0.6, 0.1], body_b: rod, point_b: [0.3, 0], rest_length: 0.1,
        stiffness: 50, damping: 0.2}
  torsional_springs: {ts: {joint: pin, stiffness: 0.5, damping: 0.01}}
motion:
  crank.angle: 2 * t
run: {duration: 1, samples: 51}
)yaml";
  const Scene scene = parse_scene(text, "loaded.yaml");

  System s("loaded");
  s.add_ground_node("O", {0, 0});
  s.add_body({.name = "crank",
              .nodes = {{"O", {0, 0}}, {"A", {0.1, 0}}},
              .mass = 0.5,
              .inertia = 0.001,
              .com = CenterOfMass::between("O", "A", 0.5)});
  s.add_body({.name = "rod",
              .nodes = {{"A", {0.1, 0}}, {"B", {0.45, 0}}},
              .mass = 0.3,
              .inertia = 0.003,
              .com = CenterOfMass::between("A", "B", 0.5)});
  s.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "crank.O", .actuated = true});
  s.add_revolute({.name = "pin", .node_a = "crank.A", .node_b = "rod.A"});
  s.add_coordinate({.name = "crank.angle", .rate = {{"crank.w", 1.0}}});
  s.add_constraint(PositionConstraintDef{
      .name = "on_line", .args = {"rod.B.y"}, .psi = [](std::span<const Jet> x, Jet t) {
        return x[0] - 0.02 * sin(t);
      }});
  s.set_gravity({0, -9.81});
  s.add_force({.name = "push",
               .body = "rod",
               .point = {0.45, 0},
               .fx = [](double t) { return -2 * std::cos(t); },
               .fy = [](double) { return 0.5; }});
  s.add_torque({.name = "drag", .body = "rod", .torque = [](double t) { return -0.1 * t; }});
  s.add_spring({.name = "s",
                .body_a = "ground",
                .point_a = {0.6, 0.1},
                .body_b = "rod",
                .point_b = {0.3, 0},
                .rest_length = 0.1,
                .stiffness = 50,
                .damping = 0.2});
  s.add_torsional_spring({.name = "ts", .joint = "pin", .stiffness = 0.5, .damping = 0.01});
  const std::vector<Prescribed> motion = {{"crank.angle", [](Jet t) { return 2.0 * t; }}};

  const Model a = build_scene_model(scene), b = build_model(s);
  expect_same_model(a, b);
  EXPECT_EQ(a.dof, 1);
  const InverseOptions o = inverse_options(scene);
  const Trajectory ra = inverse_dynamics(a, scene.motion, o);
  const Trajectory rb = inverse_dynamics(b, motion, o);
  EXPECT_LE(max_abs_diff(ra.q0, rb.q0), kSame);
  EXPECT_LE(max_abs_diff(ra.efforts, rb.efforts), kSame * (1 + rb.efforts.cwiseAbs().maxCoeff()));
  EXPECT_LE(max_abs_diff(ra.reactions, rb.reactions),
            kSame * (1 + rb.reactions.cwiseAbs().maxCoeff()));
}

}  // namespace
}  // namespace mo2d
