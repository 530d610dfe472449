// Spring-dampers and torsional springs against closed forms and an energy balance.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mo2d/forward.hpp"
#include "mo2d/mo2d.hpp"

using namespace mo2d;

namespace {
// A 2 kg point mass on a horizontal rail, tied to the ground at the origin by a spring-damper of
// rest length 0.5 m; released at x = 0.8 m.
Model mass_on_rail(double k, double c) {
  System s("oscillator");
  s.add_ground_node("L", {0, 0}).add_ground_node("R", {1, 0});
  s.add_body({.name = "block", .nodes = {{"P", {0.8, 0}}}, .mass = 2.0});
  s.add_prismatic(
      {.name = "rail", .axis_from = "ground.L", .axis_to = "ground.R", .slider = "block.P"});
  s.add_spring({.name = "spring",
                .body_a = "ground",
                .point_a = {0, 0},
                .body_b = "block",
                .point_b = {0.8, 0},
                .rest_length = 0.5,
                .stiffness = k,
                .damping = c});
  return build_model(s);
}
}  // namespace

// x(t) = L0 + (x0 - L0) cos(sqrt(k/m) t)
TEST(Springs, LinearSpringOscillatesAtItsNaturalFrequency) {
  const double k = 50.0, m = 2.0, w = std::sqrt(k / m);
  const Model model = mass_on_rail(k, 0.0);
  const State s = consistent_state(model, {.positions = {}, .velocities = {{"rail.v", 0.0}}});
  const Trajectory r = forward_dynamics(
      model, s, {.t0 = 0, .t1 = 2.5, .samples = 51, .integrator = Integrator::rk4, .step = 1e-3});
  const int ix = r.column("block.P.x");
  for (int i = 0; i < r.time.size(); ++i)
    EXPECT_NEAR(r.q0(i, ix), 0.5 + 0.3 * std::cos(w * r.time[i]), 1e-9) << "t = " << r.time[i];
  const VectorXd E = r.kinetic + r.potential;
  EXPECT_NEAR(E[0], 0.5 * k * 0.3 * 0.3, 1e-12);
  EXPECT_LE((E.array() - E[0]).abs().maxCoeff(), 1e-9);
}

// With damping, kinetic + potential + dissipated energy stays at its initial value.
TEST(Springs, DampedEnergyBalance) {
  const Model model = mass_on_rail(50.0, 1.5);
  const State s = consistent_state(model, {.positions = {}, .velocities = {{"rail.v", 0.4}}});
  for (auto integ : {Integrator::rk4, Integrator::cvode_bdf}) {
    const Trajectory r = forward_dynamics(model, s,
                                          {.t0 = 0,
                                           .t1 = 3,
                                           .samples = 31,
                                           .integrator = integ,
                                           .rtol = 1e-10,
                                           .atol = 1e-10,
                                           .step = 1e-3});
    const VectorXd total = r.kinetic + r.potential + r.dissipated;
    EXPECT_LE((total.array() - total[0]).abs().maxCoeff(), 1e-7 * total[0]) << to_string(integ);
    EXPECT_GT(r.dissipated[r.time.size() - 1], 0.5 * total[0]) << to_string(integ);  // it did damp
  }
}

// A uniform bar pivoted at one end with a torsional spring k at the pivot (rest angle 0), released
// at 0.3 rad: theta(t) = 0.3 cos(sqrt(k / I_pivot) t), I_pivot = m L^2 / 3.
TEST(Springs, TorsionalSpringAtARevoluteJoint) {
  const double m = 1.5, L = 0.8, k = 4.0, I = m * L * L / 12;
  System s("torsion");
  s.add_ground_node("O", {0, 0});
  s.add_body({.name = "bar",
              .nodes = {{"O", {0, 0}}, {"E", {L * std::cos(0.3), L * std::sin(0.3)}}},
              .mass = m,
              .inertia = I,
              .com = CenterOfMass::between("O", "E", 0.5)});
  s.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "bar.O"});
  s.add_coordinate({.name = "bar.angle", .rate = {{"bar.w", 1.0}}});
  s.add_torsional_spring(
      {.name = "coil", .joint = "pivot", .stiffness = k, .damping = 0, .rest = 0.0});
  const Model model = build_model(s);
  const State st = consistent_state(model, {.positions = {}, .velocities = {{"bar.w", 0.0}}});
  const double w = std::sqrt(k / (m * L * L / 3));
  const Trajectory r = forward_dynamics(
      model, st, {.t0 = 0, .t1 = 3, .samples = 31, .integrator = Integrator::rk4, .step = 1e-3});
  const int ia = r.column("bar.angle");
  for (int i = 0; i < r.time.size(); ++i)
    EXPECT_NEAR(r.q0(i, ia), 0.3 * std::cos(w * r.time[i]), 1e-9) << "t = " << r.time[i];
}

TEST(Springs, BadDefinitionsAreRefused) {
  auto building = [](SpringDef sp) {
    System s("bad");
    s.add_ground_node("O", {1, 0});  // at the block's node (a gap is refused before the springs)
    s.add_body({.name = "block", .nodes = {{"P", {1, 0}}}, .mass = 1});
    s.add_revolute({.name = "pin", .node_a = "ground.O", .node_b = "block.P"});
    s.add_spring(std::move(sp));
    try {
      build_model(s, {.assemble = false});
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(
      building(
          {.name = "s", .body_a = "ground", .body_b = "blok", .point_b = {1, 0}, .stiffness = 1})
          .find("did you mean 'block'"),
      std::string::npos);
  EXPECT_NE(
      building(
          {.name = "s", .body_a = "ground", .body_b = "block", .point_b = {1, 0}, .stiffness = -1})
          .find("stiffness"),
      std::string::npos);
  EXPECT_NE(
      building(
          {.name = "s", .body_a = "ground", .body_b = "block", .point_b = {2, 0}, .stiffness = 1})
          .find("one node"),
      std::string::npos);
  EXPECT_NE(building({.name = "s", .body_a = "ground", .body_b = "ground", .stiffness = 1})
                .find("two ground points"),
            std::string::npos);
}

// Trust issue item 1: a spring on a body whose node is pinned to the ground away from the origin.
// A rod pivoted at ground (ax, 0), a spring from its midpoint to the ground point straight above,
// rest length = initial length: zero spring energy and no motion, wherever the pivot is.
TEST(Springs, SpringOnABodyPinnedAwayFromTheOrigin) {
  for (double ax : {0.0, 1.0, -3.5}) {
    System s("offset_pivot");
    s.add_ground_node("A", {ax, 0});
    s.add_body({.name = "rod",
                .nodes = {{"A", {ax, 0}}, {"P", {ax + 1, 0}}},
                .mass = 1,
                .inertia = 1.0 / 12,
                .com = CenterOfMass::between("A", "P", 0.5)});
    s.add_revolute({.name = "pivot", .node_a = "ground.A", .node_b = "rod.A"});
    s.add_spring({.name = "s",
                  .body_a = "ground",
                  .point_a = {ax + 0.5, 1},
                  .body_b = "rod",
                  .point_b = {ax + 0.5, 0},
                  .rest_length = 1,
                  .stiffness = 100});
    const Model model = build_model(s);
    EXPECT_NEAR(potential_energy(model, model.q0), 0.0, 1e-12) << "ax = " << ax;
    const State st = consistent_state(model, {.positions = {}, .velocities = {{"rod.w", 0.0}}});
    const Trajectory r = forward_dynamics(
        model, st, {.t0 = 0, .t1 = 1, .samples = 11, .integrator = Integrator::dopri5});
    const int iy = r.column("rod.P.y");
    for (int i = 0; i < r.time.size(); ++i)
      EXPECT_NEAR(r.q0(i, iy), 0.0, 1e-12) << "ax = " << ax << ", t = " << r.time[i];
  }
}
