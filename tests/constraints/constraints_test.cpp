// User constraints (position and velocity level), one-node bodies with rotation and pin-in-slot
// actuation, each against a closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"

using namespace mo2d;

// A disc (one node, the centre, with inertia) rolls without slip on the line y = r: its centre
// slides in a horizontal slot pushed by an actuated force, and the rolling condition
// vx + r w = 0 is a velocity-level user constraint. Closed form: F = (m + I / r^2) x'', and the
// friction force on the disc f = -I x'' / r^2 = -lambda.
TEST(Constraints, RollingDiscVelocityLevelConstraint) {
  const double m = 2.0, I = 0.03, r = 0.15;
  System s("rolling_disc");
  s.add_ground_node("L", {-1, r}).add_ground_node("R", {1, r});
  s.add_body({.name = "disc", .nodes = {{"C", {0, r}}}, .mass = m, .inertia = I});
  s.add_pin_in_slot({.name = "rail",
                     .axis_from = "ground.L",
                     .axis_to = "ground.R",
                     .pin = "disc.C",
                     .actuated_slide = true});
  s.add_constraint(VelocityConstraintDef{
      .name = "roll",
      .coords = {},
      .rates = {"disc.C.vx", "disc.w"},
      .g = [r](std::span<const Jet>, std::span<const Jet> v, Jet) { return v[0] + r * v[1]; }});
  const Model model = build_model(s);
  EXPECT_EQ(model.dof, 1);
  EXPECT_FALSE(model.holonomic);
  auto x = [](Jet t) { return 0.3 * sin(2.0 * t) + 0.1 * t * t; };
  const Trajectory res = inverse_dynamics(model, std::vector<Prescribed>{{"disc.C.x", x}},
                                          {.t0 = 0, .t1 = 3, .samples = 61});
  for (int i = 0; i < res.time.size(); ++i) {
    const Jet xi = x(Jet(res.time[i], 1, 0));
    EXPECT_NEAR(res.efforts(i, 0), (m + I / (r * r)) * xi.dd, 1e-12);
    EXPECT_NEAR(res.reactions(i, res.reaction("roll.lambda")), I * xi.dd / (r * r), 1e-12);
    EXPECT_NEAR(res.q1(i, model.rate("disc.w")), -xi.d / r, 1e-12);
    EXPECT_NEAR(res.reactions(i, res.reaction("rail.Fy")), 0.0, 1e-12);  // no gravity
  }
}

// Two discs on fixed pivots geared by the position-level user constraint th1 + 2 th2 = 0
// (angles as extra coordinates). Driving th1 with a torque on disc 1:
// tau = (I1 + I2 / 4) th1''; the gear multiplier carries I2 th2'' / 2 ... checked via power.
TEST(Constraints, GearPairPositionLevelConstraint) {
  const double I1 = 0.02, I2 = 0.05;
  System s("gears");
  s.add_ground_node("O1", {0, 0}).add_ground_node("O2", {0.3, 0});
  s.add_body({.name = "g1", .nodes = {{"O", {0, 0}}, {"A", {0.1, 0}}}, .mass = 1, .inertia = I1});
  s.add_body({.name = "g2", .nodes = {{"O", {0.3, 0}}, {"A", {0.5, 0}}}, .mass = 1, .inertia = I2});
  s.add_revolute({.name = "p1", .node_a = "ground.O1", .node_b = "g1.O", .actuated = true});
  s.add_revolute({.name = "p2", .node_a = "ground.O2", .node_b = "g2.O"});
  s.add_coordinate({.name = "th1", .rate = {{"g1.w", 1}}});
  s.add_coordinate({.name = "th2", .rate = {{"g2.w", 1}}});
  s.add_constraint(PositionConstraintDef{
      .name = "mesh", .args = {"th1", "th2"}, .psi = [](std::span<const Jet> q, Jet) {
        return q[0] + 2.0 * q[1];
      }});
  const Model model = build_model(s);
  EXPECT_EQ(model.dof, 1);
  auto th = [](Jet t) { return 1.2 * sin(1.5 * t); };
  const Trajectory res = inverse_dynamics(model, std::vector<Prescribed>{{"th1", th}},
                                          {.t0 = 0, .t1 = 4, .samples = 41});
  for (int i = 0; i < res.time.size(); ++i) {
    const Jet a = th(Jet(res.time[i], 1, 0));
    EXPECT_NEAR(res.efforts(i, 0), (I1 + I2 / 4) * a.dd, 1e-12);
    EXPECT_NEAR(res.q0(i, res.column("th2")), -a.v / 2, 1e-12);
    // the mesh force acts on g2 only through the constraint: I2 th2'' = -2 lambda
    EXPECT_NEAR(res.reactions(i, res.reaction("mesh.lambda")), I2 * a.dd / 4, 1e-12);
  }
}

// A rheonomic user constraint drives the motion: a point-mass pendulum without actuator whose
// angle follows psi = angle - theta(t) = 0. With no DOF left nothing is prescribed, and the
// constraint's multiplier is minus the torque the pendulum needs:
// lambda = -(m L^2 theta'' + m g L cos(theta)).
TEST(Constraints, RheonomicUserConstraintDrivesThePendulum) {
  const double L = 0.8, mass = 1.3, g = 9.81;
  System s("clock_pendulum");
  s.add_ground_node("O", {0, 0});
  s.add_body({.name = "link",
              .nodes = {{"O", {0, 0}}, {"P", {L * std::cos(0.3), L * std::sin(0.3)}}},
              .mass = mass,
              .inertia = 0.0,
              .com = CenterOfMass::at_node("P")});
  s.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "link.O"});
  s.add_coordinate({.name = "angle", .rate = {{"link.w", 1.0}}});
  auto theta = [](Jet t) { return 0.3 + 0.5 * sin(3.0 * t) + t * t; };
  s.add_constraint(PositionConstraintDef{
      .name = "clock", .args = {"angle"}, .psi = [theta](std::span<const Jet> q, Jet t) {
        return q[0] - theta(t);
      }});
  s.set_gravity({0, -g});
  const Model model = build_model(s);
  EXPECT_EQ(model.dof, 0);
  const Trajectory res =
      inverse_dynamics(model, std::vector<Prescribed>{}, {.t0 = 0, .t1 = 2, .samples = 41});
  for (int i = 0; i < res.time.size(); ++i) {
    const Jet th = theta(Jet(res.time[i], 1, 0));
    const double tau = mass * L * L * th.dd + mass * g * L * std::cos(th.v);
    EXPECT_NEAR(res.reactions(i, res.reaction("clock.lambda")), -tau, 1e-10);
    EXPECT_NEAR(res.q0(i, res.column("angle")), th.v, 1e-12);
  }
}

// Constraint::def holds one struct per kind: kind() follows it, slider() gives the axis of a
// pin-in-slot, and as<T>() on another kind is an Error naming the constraint and both kinds.
TEST(Constraints, OneStructPerKind) {
  System s("rolling_disc");
  s.add_ground_node("L", {-1, 0.15}).add_ground_node("R", {1, 0.15});
  s.add_body({.name = "disc", .nodes = {{"C", {0, 0.15}}}, .mass = 2, .inertia = 0.03});
  s.add_pin_in_slot(
      {.name = "rail", .axis_from = "ground.L", .axis_to = "ground.R", .pin = "disc.C"});
  s.add_constraint(VelocityConstraintDef{
      .name = "roll",
      .coords = {},
      .rates = {"disc.C.vx", "disc.w"},
      .g = [](std::span<const Jet>, std::span<const Jet> v, Jet) { return v[0] + 0.15 * v[1]; }});
  const Model model = build_model(s);
  ASSERT_EQ(model.constraints.size(), 2u);
  const Constraint& rail = model.constraints[0];
  const Constraint& roll = model.constraints[1];
  EXPECT_EQ(rail.kind(), ConstraintKind::slot);
  EXPECT_EQ(roll.kind(), ConstraintKind::user_velocity);
  ASSERT_NE(rail.slider(), nullptr);
  EXPECT_DOUBLE_EQ(rail.slider()->length, 2.0);
  EXPECT_EQ(roll.slider(), nullptr);
  EXPECT_EQ(roll.as<Constraint::UserVelocity>().rates.size(), 2u);
  try {
    (void)rail.as<Constraint::Prismatic>();
    FAIL() << "as<Prismatic> on a pin-in-slot did not throw";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "constraint 'rail' is a pin-in-slot constraint, not a prismatic one");
    EXPECT_EQ(e.element(), "rail");
  }
}
