// Assembly refuses what cannot be assembled, redundant and conflicting constraints with a clear
// mo2d::Error naming the constraint or joint (build_model assembles the initial configuration).
//
// Set MO2D_SHOW_ERRORS=1 to print every caught message.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <limits>
#include <numbers>
#include <string>
#include <typeinfo>
#include <vector>

#include "error_support.hpp"
#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"

using namespace mo2d;
using namespace mo2d::test;

// =================================================================================================
// Assembly, redundant and conflicting constraints
// =================================================================================================

// Ground 0.4 m, crank 0.1 m, coupler 0.1 m, rocker 0.1 m: 0.1 + 0.1 + 0.1 < 0.4, the loop cannot
// close whatever the crank angle. Written with the copies of node B 0.3 m apart, which is refused
// by default (Errors.JointNodeCopiesApartAreRefused); with the gap check widened, assembly itself
// must fail with its own message.
constexpr BuildOptions kGapsAllowed{.joint_tolerance = 1.0};
TEST(Errors, FourBarThatCannotClose) {
  System s("short_fourbar");
  s.add_ground_node("A0", {0, 0}).add_ground_node("B0", {0.4, 0});
  s.add_body(
      {.name = "crank", .nodes = {{"O", {0, 0}}, {"A", {0, 0.1}}}, .mass = 1, .inertia = 1e-3});
  s.add_body({.name = "coupler",
              .nodes = {{"A", {0, 0.1}}, {"B", {0.1, 0.1}}},
              .mass = 1,
              .inertia = 1e-3});
  s.add_body({.name = "rocker",
              .nodes = {{"O", {0.4, 0}}, {"B", {0.4, 0.1}}},
              .mass = 1,
              .inertia = 1e-3});
  s.add_revolute(
      {.name = "crank_pivot", .node_a = "ground.A0", .node_b = "crank.O", .actuated = true});
  s.add_revolute({.name = "crank_pin", .node_a = "crank.A", .node_b = "coupler.A"});
  s.add_revolute({.name = "rocker_pin", .node_a = "coupler.B", .node_b = "rocker.B"});
  s.add_revolute({.name = "rocker_pivot", .node_a = "ground.B0", .node_b = "rocker.O"});
  Error e("");
  EXPECT_TRUE(ThrowsError(building(s, kGapsAllowed), {"cannot be assembled"}, &e));
  EXPECT_TRUE(NamesOneOf(e, {"crank", "coupler", "rocker"}));
  EXPECT_FALSE(e.element().empty());
  EXPECT_TRUE(ThrowsError(building(s), {"rocker_pin", "coupler.B", "rocker.B", "0.3 m apart"}));
}

// The same four-bar with the revolute joints kept as constraint rows.
TEST(Errors, FourBarThatCannotCloseUnreduced) {
  System s("short_fourbar");
  s.add_ground_node("A0", {0, 0}).add_ground_node("B0", {0.4, 0});
  s.add_body(
      {.name = "crank", .nodes = {{"O", {0, 0}}, {"A", {0, 0.1}}}, .mass = 1, .inertia = 1e-3});
  s.add_body({.name = "coupler",
              .nodes = {{"A", {0, 0.1}}, {"B", {0.1, 0.1}}},
              .mass = 1,
              .inertia = 1e-3});
  s.add_body({.name = "rocker",
              .nodes = {{"O", {0.4, 0}}, {"B", {0.4, 0.1}}},
              .mass = 1,
              .inertia = 1e-3});
  s.add_revolute(
      {.name = "crank_pivot", .node_a = "ground.A0", .node_b = "crank.O", .actuated = true});
  s.add_revolute({.name = "crank_pin", .node_a = "crank.A", .node_b = "coupler.A"});
  s.add_revolute({.name = "rocker_pin", .node_a = "coupler.B", .node_b = "rocker.B"});
  s.add_revolute({.name = "rocker_pivot", .node_a = "ground.B0", .node_b = "rocker.O"});
  Error e("");
  EXPECT_TRUE(ThrowsError(building(s, {.reduction = Reduction::none, .joint_tolerance = 1.0}),
                          {"cannot be assembled"}, &e));
  EXPECT_TRUE(NamesOneOf(e, {"crank", "coupler", "rocker"}));
}

// The assembly failure of the short four-bar names its worst row ('coupler.rigid(d01)') in the
// message but reports element() = 'crank.rigid(d01)', the first position row, whatever failed.
TEST(Errors, AssemblyFailureElementIsTheRowNamedInTheMessage) {
  System s("short_fourbar");
  s.add_ground_node("A0", {0, 0}).add_ground_node("B0", {0.4, 0});
  s.add_body(
      {.name = "crank", .nodes = {{"O", {0, 0}}, {"A", {0, 0.1}}}, .mass = 1, .inertia = 1e-3});
  s.add_body({.name = "coupler",
              .nodes = {{"A", {0, 0.1}}, {"B", {0.1, 0.1}}},
              .mass = 1,
              .inertia = 1e-3});
  s.add_body({.name = "rocker",
              .nodes = {{"O", {0.4, 0}}, {"B", {0.4, 0.1}}},
              .mass = 1,
              .inertia = 1e-3});
  s.add_revolute(
      {.name = "crank_pivot", .node_a = "ground.A0", .node_b = "crank.O", .actuated = true});
  s.add_revolute({.name = "crank_pin", .node_a = "crank.A", .node_b = "coupler.A"});
  s.add_revolute({.name = "rocker_pin", .node_a = "coupler.B", .node_b = "rocker.B"});
  s.add_revolute({.name = "rocker_pivot", .node_a = "ground.B0", .node_b = "rocker.O"});
  Error e("");
  EXPECT_TRUE(ThrowsError(building(s, kGapsAllowed), {"cannot be assembled"}, &e));
  EXPECT_TRUE(NamesItsElement(e));
}

// Parallelogram four-bar with a fifth bar parallel to crank and rocker: it still moves (1 DOF)
// but one of the constraints is redundant.
TEST(Errors, ParallelogramWithAFifthBarIsRedundant) {
  System s("parallelogram");
  s.add_ground_node("A0", {0, 0}).add_ground_node("M0", {0.5, 0}).add_ground_node("B0", {1, 0});
  s.add_body(
      {.name = "crank", .nodes = {{"O", {0, 0}}, {"A", {0, 0.5}}}, .mass = 1, .inertia = 0.1});
  s.add_body({.name = "coupler",
              .nodes = {{"A", {0, 0.5}}, {"B", {1, 0.5}}, {"M", {0.5, 0.5}}},
              .mass = 1,
              .inertia = 0.1});
  s.add_body(
      {.name = "rocker", .nodes = {{"O", {1, 0}}, {"B", {1, 0.5}}}, .mass = 1, .inertia = 0.1});
  s.add_body(
      {.name = "bar5", .nodes = {{"O", {0.5, 0}}, {"M", {0.5, 0.5}}}, .mass = 1, .inertia = 0.1});
  s.add_revolute(
      {.name = "crank_pivot", .node_a = "ground.A0", .node_b = "crank.O", .actuated = true});
  s.add_revolute({.name = "crank_pin", .node_a = "crank.A", .node_b = "coupler.A"});
  s.add_revolute({.name = "rocker_pin", .node_a = "coupler.B", .node_b = "rocker.B"});
  s.add_revolute({.name = "rocker_pivot", .node_a = "ground.B0", .node_b = "rocker.O"});
  s.add_revolute({.name = "bar5_pivot", .node_a = "ground.M0", .node_b = "bar5.O"});
  s.add_revolute({.name = "bar5_pin", .node_a = "coupler.M", .node_b = "bar5.M"});
  for (Reduction r : {Reduction::flat, Reduction::none}) {
    SCOPED_TRACE(r == Reduction::flat ? "Reduction::flat" : "Reduction::none");
    Error e("");
    EXPECT_TRUE(ThrowsError(building(s, {.reduction = r}), {"redundant"}, &e));
    EXPECT_TRUE(NamesItsElement(e));
    EXPECT_TRUE(NamesOneOf(e, {"crank", "coupler", "rocker", "bar5"}));
  }
}

TEST(Errors, TwoRevolutesOnTheSameNodes) {
  System s = crank_only();
  s.add_body({.name = "rod", .nodes = {{"A", {0.1, 0}}, {"B", {0.4, 0}}}, .mass = 1});
  s.add_revolute({.name = "elbow", .node_a = "crank.A", .node_b = "rod.A"});
  s.add_revolute({.name = "elbow_again", .node_a = "crank.A", .node_b = "rod.A"});
  Error e("");
  EXPECT_TRUE(ThrowsError(building(s), {"elbow_again", "redundant"}, &e));
  EXPECT_EQ(e.element(), "elbow_again");
}

TEST(Errors, TwoRevolutesOnTheSameNodesUnreduced) {
  System s = crank_only();
  s.add_body({.name = "rod", .nodes = {{"A", {0.1, 0}}, {"B", {0.4, 0}}}, .mass = 1});
  s.add_revolute({.name = "elbow", .node_a = "crank.A", .node_b = "rod.A"});
  s.add_revolute({.name = "elbow_again", .node_a = "crank.A", .node_b = "rod.A"});
  Error e("");
  EXPECT_TRUE(ThrowsError(building(s, {.reduction = Reduction::none}), {"redundant"}, &e));
  EXPECT_TRUE(NamesItsElement(e));
  EXPECT_TRUE(NamesOneOf(e, {"elbow"}));
}

TEST(Errors, TwoPrismaticsLockingTheSameRotation) {
  System s("s");
  s.add_ground_node("R1", {0, 0}).add_ground_node("R2", {1, 0});
  s.add_body(
      {.name = "block", .nodes = {{"P", {0.5, 0}}, {"Q", {0.7, 0}}}, .mass = 1, .inertia = 0.1});
  s.add_prismatic(
      {.name = "rail", .axis_from = "ground.R1", .axis_to = "ground.R2", .slider = "block.P"});
  s.add_prismatic({.name = "rail_again",
                   .axis_from = "ground.R1",
                   .axis_to = "ground.R2",
                   .slider = "block.Q"});
  Error e("");
  EXPECT_TRUE(ThrowsError(building(s), {"rail_again", "redundant"}, &e));
}

// On the slider-crank, a user position constraint y_B = e repeats what the rail already imposes.
TEST(Errors, UserPositionConstraintDuplicatingAJoint) {
  System s = mechanisms::slider_crank().system;
  const double e0 = kSC.e;
  s.add_constraint(PositionConstraintDef{
      .name = "level", .args = {"rod.B.y"}, .psi = [e0](std::span<const Jet> x, Jet) {
        return x[0] - Jet(e0);
      }});
  Error e("");
  EXPECT_TRUE(ThrowsError(building(s), {"redundant"}, &e));
  EXPECT_TRUE(NamesItsElement(e));
  EXPECT_TRUE(NamesOneOf(e, {"level", "rail"}));
}

// A user constraint that repeats the length of the pendulum link.
TEST(Errors, UserPositionConstraintDuplicatingARigidBody) {
  System s = mechanisms::pendulum().system;
  s.add_constraint(PositionConstraintDef{
      .name = "length", .args = {"link.P.x", "link.P.y"}, .psi = [](std::span<const Jet> x, Jet) {
        return 0.1 * (x[0] * x[0] + x[1] * x[1] - Jet(1));
      }});
  Error e("");
  EXPECT_TRUE(ThrowsError(building(s), {"redundant"}, &e));
  EXPECT_TRUE(NamesItsElement(e));
  EXPECT_TRUE(NamesOneOf(e, {"length", "link"}));
}

TEST(Errors, RevoluteJoiningTwoGroundNodes) {
  System s = crank_only();
  s.add_ground_node("B0", {1, 0});
  s.add_revolute({.name = "weld", .node_a = "ground.O", .node_b = "ground.B0"});
  EXPECT_TRUE(ThrowsError(building(s), {"weld", "two ground nodes"}));
}

// crank.O hinged to ground.O and to ground.B0: the second joint conflicts with the first.
TEST(Errors, RevoluteJoiningTwoDifferentGroundNodesThroughABody) {
  System s = crank_only();
  s.add_ground_node("B0", {1, 0});
  s.add_revolute({.name = "second_pivot", .node_a = "ground.B0", .node_b = "crank.O"});
  Error e("");
  EXPECT_TRUE(ThrowsError(building(s), {"second_pivot", "conflicting"}, &e));
  EXPECT_EQ(e.element(), "second_pivot");
}

// The same clear diagnosis as with Reduction::flat, whatever the reduction: the topology check does
// not depend on which joints are eliminated.
TEST(Errors, RevoluteJoiningTwoDifferentGroundNodesUnreducedNamesTheJoint) {
  System s = crank_only();
  s.add_ground_node("B0", {1, 0});
  s.add_revolute({.name = "second_pivot", .node_a = "ground.B0", .node_b = "crank.O"});
  Error e("");
  EXPECT_TRUE(
      ThrowsError(building(s, {.reduction = Reduction::none}), {"second_pivot", "ground"}, &e));
  EXPECT_TRUE(NamesItsElement(e));
}

TEST(Errors, UserPositionConstraintThatCannotBeSatisfied) {
  System s = mechanisms::pendulum().system;  // link of length 1 hinged at the origin
  s.add_constraint(PositionConstraintDef{
      .name = "far", .args = {"link.P.x"}, .psi = [](std::span<const Jet> x, Jet) {
        return x[0] - Jet(5.0);  // the tip cannot reach x = 5
      }});
  Error e("");
  EXPECT_TRUE(ThrowsError(building(s), {"cannot be assembled"}, &e));
  EXPECT_TRUE(NamesOneOf(e, {"far", "link"}));
}

// A user constraint that is NaN at the initial configuration: assembly reports it, but with an
// empty element() and a message naming whatever row the NaN comparison happens to pick.
TEST(Errors, UserConstraintNaNAtAssemblyNamesTheConstraint) {
  System s = mechanisms::pendulum().system;  // tip at (1, 0)
  s.add_constraint(PositionConstraintDef{
      .name = "bad", .args = {"link.P.y"}, .psi = [](std::span<const Jet> x, Jet) {
        return sqrt(x[0] - Jet(1.0));
      }});
  Error e("");
  EXPECT_TRUE(ThrowsError(building(s), {"bad"}, &e));
  EXPECT_EQ(e.element(), "bad");
}
