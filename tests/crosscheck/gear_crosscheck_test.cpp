// Gears against Box2D's gear joint (crosscheck/box2d_world.cpp maps a gear pair to b2GearJoint
// on the two shafts' revolute joints, ratio -rho), integrated freely by both. Box2D's error is
// first order in its step (docs/crosscheck.md), so it must fall about 4 times when h does; a
// gear joint of the wrong sign (ratio +rho) is off by radians.
// On a moving carrier Box2D 2.4.1's gear joint loses the carrier's share of its impulse when
// both its joints start on the carrier (crosscheck/box2d_gears.cpp): the translation splits the
// carrier into two welded halves. Checked here on a three-shaft train in a housing, pinned and
// free: the difference falls with Box2D's step (first order), and without the split it is
// 0.17 rad after 1 s whatever the step. mo2d's side is checked against the Lagrangian of the
// pinned housing in tests/constraints/gear_test.cpp.
#include <gtest/gtest.h>

#include "mo2d/crosscheck.hpp"
#include "mo2d/forward.hpp"
#include "mo2d/mo2d.hpp"

namespace mo2d {
namespace {

// Two flywheels on ground axes (the carrier the ground), the driver pulled by gravity through an
// offset centre of mass.
TEST(GearCrosscheck, GroundCarrierFollowsBox2D) {
  System s("pair");
  s.add_ground_node("O1", {0, 0});
  s.add_ground_node("O2", {0.3, 0});
  s.add_body({.name = "w1",
              .nodes = {{"C", {0, 0}}, {"R", {0.1, 0}}},
              .mass = 1,
              .inertia = 0.02,
              .com = CenterOfMass::at_node("R")});
  s.add_body(
      {.name = "w2", .nodes = {{"C", {0.3, 0}}, {"R", {0.4, 0}}}, .mass = 1, .inertia = 0.05});
  s.add_revolute({.name = "p1", .node_a = "ground.O1", .node_b = "w1.C"});
  s.add_revolute({.name = "p2", .node_a = "ground.O2", .node_b = "w2.C"});
  s.add_gear({.name = "mesh", .body = "w2", .driver = "w1", .ratio = -0.6});
  s.set_gravity({0, -9.81});
  const Model m = build_model(s, {.reduction = Reduction::none});
  const State s0 = consistent_state(m, {{}, {{"w1.w", 0.0}}});
  CrosscheckOptions coarse, fine;
  fine.step = coarse.step / 4;
  const ForwardCrosscheck a = crosscheck_forward(m, s0, 0.5, coarse, 11);
  const ForwardCrosscheck b = crosscheck_forward(m, s0, 0.5, fine, 11);
  std::printf("flywheels vs Box2D: %.3g, %.3g rad; %.3g, %.3g rad\n", a.relative_position_error,
              a.max_angle_error, b.relative_position_error, b.max_angle_error);
  EXPECT_LT(b.max_angle_error, a.max_angle_error / 2.5);
}

// A housing (pinned at O, or free in the plane) with three shafts on bearings: input -> idler
// (ratio -0.4) -> output (ratio -2), the shafts' centres of mass on their axes, the housing's
// below its pivot; started swinging with the input spinning, and a torque ramp on the input
// (from outside the housing: on a free housing the gears then push on it).
Model geared_housing(bool pinned) {
  System s("train");
  s.add_ground_node("O", {0, 0});
  s.add_body({.name = "case",
              .nodes = {{"O", {0, 0}},
                        {"A", {-0.07, 0.03}},
                        {"B", {0, 0.03}},
                        {"C", {0.075, 0.03}},
                        {"G", {0, -0.1}}},
              .mass = 4,
              .inertia = 0.05,
              .com = CenterOfMass::at_node("G")});
  const auto shaft = [&](const char* name, Vec2 axis, double inertia) {
    s.add_body({.name = name,
                .nodes = {{"C", axis}, {"R", axis + Vec2(0.02, 0)}},
                .mass = 0.5,
                .inertia = inertia,
                .com = CenterOfMass::at_node("C")});
  };
  shaft("input", {-0.07, 0.03}, 0.002);
  shaft("idler", {0, 0.03}, 0.01);
  shaft("output", {0.075, 0.03}, 0.08);
  if (pinned) s.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "case.O"});
  s.add_revolute({.name = "b_in", .node_a = "case.A", .node_b = "input.C"});
  s.add_revolute({.name = "b_idler", .node_a = "case.B", .node_b = "idler.C"});
  s.add_revolute({.name = "b_out", .node_a = "case.C", .node_b = "output.C"});
  s.add_gear(
      {.name = "first", .body = "idler", .driver = "input", .carrier = "case", .ratio = -0.4});
  s.add_gear(
      {.name = "second", .body = "output", .driver = "idler", .carrier = "case", .ratio = -2});
  s.add_torque({.name = "drive", .body = "input", .torque = [](double t) { return 0.05 * t; }});
  s.set_gravity({0, -9.81});
  return build_model(s, {.reduction = Reduction::none});
}

void expect_first_order_agreement(bool pinned) {
  const Model m = geared_housing(pinned);
  std::vector<std::pair<std::string, double>> v{{"case.w", 3.0}, {"input.w", 4.0}};
  if (!pinned) v.insert(v.end(), {{"case.O.vx", 0.1}, {"case.O.vy", 0.2}});
  const State s0 = consistent_state(m, {{}, v});
  CrosscheckOptions coarse, fine;
  fine.step = coarse.step / 4;
  const ForwardCrosscheck a = crosscheck_forward(m, s0, 1.0, coarse, 11);
  const ForwardCrosscheck b = crosscheck_forward(m, s0, 1.0, fine, 11);
  std::printf("geared housing (%s) vs Box2D: %.3g, %.3g rad at h, h/4\n",
              pinned ? "pinned" : "free", a.max_angle_error, b.max_angle_error);
  EXPECT_LT(a.max_angle_error, 2e-3);
  EXPECT_LT(b.max_angle_error, a.max_angle_error / 2.5);
}

TEST(GearCrosscheck, PinnedHousingFollowsBox2D) {
  expect_first_order_agreement(true);
}

TEST(GearCrosscheck, FreeHousingFollowsBox2D) {
  expect_first_order_agreement(false);
}

}  // namespace
}  // namespace mo2d
