// Model building refuses bad definitions with a clear mo2d::Error naming the offending element:
// joints naming nodes that do not exist, bodies, joint geometry, coordinates, user constraints,
// loads, gravity, subsystems, names used twice. Never a crash, a NaN or a silent result.
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
// Joints naming nodes that do not exist
// =================================================================================================

TEST(Errors, RevoluteMissingNodeWithSuggestion) {
  System s = crank_only();
  s.add_body({.name = "rod", .nodes = {{"A", {0.1, 0}}, {"B", {0.4, 0}}}, .mass = 1});
  s.add_revolute({.name = "elbow", .node_a = "crank.B", .node_b = "rod.A"});  // crank has O, A
  Error e("");
  EXPECT_TRUE(ThrowsError(building(s), {"elbow", "crank.B", "did you mean"}, &e));
  EXPECT_EQ(e.element(), "elbow");
}

TEST(Errors, RevoluteMissingGroundNodeWithSuggestion) {
  System s("s");
  s.add_ground_node("pivot", {0, 0});
  s.add_body({.name = "crank", .nodes = {{"O", {0, 0}}, {"A", {0.1, 0}}}, .mass = 1});
  s.add_revolute({.name = "hinge", .node_a = "ground.pivto", .node_b = "crank.O"});
  EXPECT_TRUE(ThrowsError(building(s), {"hinge", "ground.pivto", "did you mean 'ground.pivot'"}));
}

TEST(Errors, RevoluteMissingNodeFarFromAnyNameHasNoSuggestion) {
  System s = crank_only();
  s.add_body({.name = "rod", .nodes = {{"A", {0.1, 0}}, {"B", {0.4, 0}}}, .mass = 1});
  s.add_revolute({.name = "elbow", .node_a = "completely_unrelated.name", .node_b = "rod.A"});
  Error e("");
  EXPECT_TRUE(ThrowsError(building(s), {"elbow", "completely_unrelated.name", "not found"}, &e));
  EXPECT_FALSE(contains(e.what(), "did you mean")) << e.what();
}

TEST(Errors, PrismaticMissingSliderNodeWithSuggestion) {
  System s("s");
  s.add_ground_node("R1", {0, 0}).add_ground_node("R2", {1, 0});
  s.add_body({.name = "slider", .nodes = {{"P", {0.5, 0}}}, .mass = 1});
  s.add_prismatic(
      {.name = "rail", .axis_from = "ground.R1", .axis_to = "ground.R2", .slider = "slider.Q"});
  Error e("");
  EXPECT_TRUE(ThrowsError(building(s), {"rail", "slider.Q", "did you mean 'slider.P'"}, &e));
  EXPECT_EQ(e.element(), "rail");
}

TEST(Errors, PrismaticMissingAxisNodeWithSuggestion) {
  System s("s");
  s.add_ground_node("R1", {0, 0}).add_ground_node("R2", {1, 0});
  s.add_body({.name = "slider", .nodes = {{"P", {0.5, 0}}}, .mass = 1});
  s.add_prismatic(
      {.name = "rail", .axis_from = "ground.R1", .axis_to = "ground.R3", .slider = "slider.P"});
  EXPECT_TRUE(ThrowsError(building(s), {"rail", "ground.R3", "did you mean"}));
}

TEST(Errors, PinInSlotMissingPinWithSuggestion) {
  System s("s");
  s.add_ground_node("O", {0, 0}).add_ground_node("C", {0, 0.3});
  s.add_body({.name = "lever", .nodes = {{"O", {0, 0}}, {"B", {0, 1}}}, .mass = 1, .inertia = 0.1});
  s.add_body(
      {.name = "crank", .nodes = {{"O", {0, 0.3}}, {"A", {0, 0.4}}}, .mass = 1, .inertia = 0.1});
  s.add_revolute({.name = "lever_pivot", .node_a = "ground.O", .node_b = "lever.O"});
  s.add_revolute({.name = "crank_pivot", .node_a = "ground.C", .node_b = "crank.O"});
  s.add_pin_in_slot(
      {.name = "slot", .axis_from = "lever.O", .axis_to = "lever.B", .pin = "crank.AA"});
  Error e("");
  EXPECT_TRUE(ThrowsError(building(s), {"slot", "crank.AA", "did you mean 'crank.A'"}, &e));
  EXPECT_EQ(e.element(), "slot");
}

TEST(Errors, PinInSlotMissingAxisNode) {
  System s("s");
  s.add_ground_node("O", {0, 0});
  s.add_body({.name = "lever", .nodes = {{"O", {0, 0}}, {"B", {0, 1}}}, .mass = 1, .inertia = 0.1});
  s.add_body({.name = "pin", .nodes = {{"P", {0, 0.5}}}, .mass = 1});
  s.add_revolute({.name = "lever_pivot", .node_a = "ground.O", .node_b = "lever.O"});
  s.add_pin_in_slot({.name = "slot", .axis_from = "lever.O", .axis_to = "lever.C", .pin = "pin.P"});
  EXPECT_TRUE(ThrowsError(building(s), {"slot", "lever.C", "did you mean 'lever."}));
}

// =================================================================================================
// Bodies
// =================================================================================================

TEST(Errors, NegativeMass) {
  System s("s");
  s.add_body({.name = "link", .nodes = {{"O", {0, 0}}, {"P", {1, 0}}}, .mass = -1});
  Error e("");
  EXPECT_TRUE(ThrowsError(building(s), {"link", "mass"}, &e));
  EXPECT_EQ(e.element(), "link");
}

TEST(Errors, NaNMass) {
  System s("s");
  s.add_body({.name = "link", .nodes = {{"O", {0, 0}}, {"P", {1, 0}}}, .mass = kNaN});
  EXPECT_TRUE(ThrowsError(building(s), {"link", "mass"}));
}

TEST(Errors, InfiniteMass) {
  System s("s");
  s.add_body({.name = "link", .nodes = {{"O", {0, 0}}, {"P", {1, 0}}}, .mass = kInf});
  EXPECT_TRUE(ThrowsError(building(s), {"link", "mass"}));
}

TEST(Errors, NegativeInertia) {
  System s("s");
  s.add_body({.name = "link", .nodes = {{"O", {0, 0}}, {"P", {1, 0}}}, .mass = 1, .inertia = -0.5});
  EXPECT_TRUE(ThrowsError(building(s), {"link", "inertia"}));
}

TEST(Errors, NaNInertia) {
  System s("s");
  s.add_body({.name = "link", .nodes = {{"O", {0, 0}}, {"P", {1, 0}}}, .mass = 1, .inertia = kNaN});
  EXPECT_TRUE(ThrowsError(building(s), {"link", "inertia"}));
}

TEST(Errors, InfiniteInertia) {
  System s("s");
  s.add_body({.name = "link", .nodes = {{"O", {0, 0}}, {"P", {1, 0}}}, .mass = 1, .inertia = kInf});
  EXPECT_TRUE(ThrowsError(building(s), {"link", "inertia"}));
}

TEST(Errors, OneNodeBodyWithZeroMass) {
  System s("s");
  s.add_body({.name = "bead", .nodes = {{"P", {0, 0}}}, .mass = 0});
  Error e("");
  EXPECT_TRUE(ThrowsError(building(s), {"bead", "mass"}, &e));
  EXPECT_EQ(e.element(), "bead");
}

TEST(Errors, FirstTwoNodesCoincide) {
  System s("s");
  s.add_body({.name = "plate", .nodes = {{"A", {1, 1}}, {"B", {1, 1}}, {"C", {2, 1}}}, .mass = 1});
  EXPECT_TRUE(ThrowsError(building(s), {"plate", "coincide"}));
}

TEST(Errors, BodyWithoutNodes) {
  System s("s");
  s.add_body({.name = "ghost", .nodes = {}, .mass = 1});
  EXPECT_TRUE(ThrowsError(building(s), {"ghost", "no nodes"}));
}

TEST(Errors, NonFiniteNodePosition) {
  System s("s");
  s.add_body({.name = "link", .nodes = {{"O", {0, 0}}, {"P", {kNaN, 0}}}, .mass = 1});
  EXPECT_TRUE(ThrowsError(building(s), {"link.P", "non-finite"}));
}

TEST(Errors, BodyDefinedTwice) {
  System s = crank_only();
  s.add_body({.name = "crank", .nodes = {{"X", {0, 0}}, {"Y", {1, 0}}}, .mass = 1});
  EXPECT_TRUE(ThrowsError(building(s), {"crank", "twice"}));
}

TEST(Errors, NodeDefinedTwiceInABody) {
  System s("s");
  s.add_body({.name = "link", .nodes = {{"O", {0, 0}}, {"O", {1, 0}}}, .mass = 1});
  EXPECT_TRUE(ThrowsError(building(s), {"link.O", "twice"}));
}

TEST(Errors, GroundNodeDefinedTwice) {
  System s = crank_only();
  s.add_ground_node("O", {1, 1});
  EXPECT_TRUE(ThrowsError(building(s), {"ground.O", "twice"}));
}

TEST(Errors, BodyNamedGround) {
  System s("s");
  s.add_body({.name = "ground", .nodes = {{"O", {0, 0}}, {"P", {1, 0}}}, .mass = 1});
  EXPECT_TRUE(ThrowsError(building(s), {"ground", "reserved"}));
}

TEST(Errors, NameWithADot) {
  System s("s");
  s.add_body({.name = "my.link", .nodes = {{"O", {0, 0}}, {"P", {1, 0}}}, .mass = 1});
  EXPECT_TRUE(ThrowsError(building(s), {"my.link", "'.'"}));
}

TEST(Errors, JointWithEmptyName) {
  System s = crank_only();
  s.add_body({.name = "rod", .nodes = {{"A", {0.1, 0}}, {"B", {0.4, 0}}}, .mass = 1});
  s.add_revolute({.name = "", .node_a = "crank.A", .node_b = "rod.A"});
  EXPECT_TRUE(ThrowsError(building(s), {"revolute joint", "empty name"}));
}

TEST(Errors, CentreOfMassAtUnknownNodeWithSuggestion) {
  System s("s");
  s.add_body({.name = "link",
              .nodes = {{"O", {0, 0}}, {"tip", {1, 0}}},
              .mass = 1,
              .com = CenterOfMass::between("O", "tpi", 0.5)});
  EXPECT_TRUE(ThrowsError(building(s), {"link", "tpi", "did you mean 'tip'"}));
}

TEST(Errors, CentreOfMassBetweenTheSameNode) {
  System s("s");
  s.add_body({.name = "link",
              .nodes = {{"O", {0, 0}}, {"P", {1, 0}}},
              .mass = 1,
              .com = CenterOfMass::between("O", "O", 0.5)});
  EXPECT_TRUE(ThrowsError(building(s), {"link", "centre of mass"}));
}

TEST(Errors, OneNodeBodyWithCentreOfMassElsewhere) {
  System s("s");
  s.add_body(
      {.name = "bead", .nodes = {{"P", {0, 0}}}, .mass = 1, .com = CenterOfMass::at_point({1, 0})});
  EXPECT_TRUE(ThrowsError(building(s), {"bead", "centre of mass"}));
}

// =================================================================================================
// Joint geometry
// =================================================================================================

TEST(Errors, PrismaticZeroLengthAxis) {
  System s("s");
  s.add_ground_node("R1", {0, 0}).add_ground_node("R2", {0, 0});
  s.add_body({.name = "slider", .nodes = {{"P", {0.5, 0}}}, .mass = 1});
  s.add_prismatic(
      {.name = "rail", .axis_from = "ground.R1", .axis_to = "ground.R2", .slider = "slider.P"});
  Error e("");
  EXPECT_TRUE(ThrowsError(building(s), {"rail", "zero-length axis", "ground.R1", "ground.R2"}, &e));
  EXPECT_EQ(e.element(), "rail");
}

TEST(Errors, PrismaticAxisFromAndToTheSameNode) {
  System s("s");
  s.add_ground_node("R1", {0, 0});
  s.add_body({.name = "slider", .nodes = {{"P", {0.5, 0}}}, .mass = 1});
  s.add_prismatic(
      {.name = "rail", .axis_from = "ground.R1", .axis_to = "ground.R1", .slider = "slider.P"});
  EXPECT_TRUE(ThrowsError(building(s), {"rail", "zero-length axis"}));
}

TEST(Errors, PrismaticAxisNodesOnDifferentBodies) {
  System s = crank_only();
  s.add_ground_node("R", {1, 0});
  s.add_body({.name = "slider", .nodes = {{"P", {0.5, 0}}}, .mass = 1});
  s.add_prismatic(
      {.name = "rail", .axis_from = "crank.A", .axis_to = "ground.R", .slider = "slider.P"});
  EXPECT_TRUE(ThrowsError(building(s), {"rail", "same body"}));
}

TEST(Errors, PrismaticSliderOnTheAxisBody) {
  System s("s");
  s.add_body({.name = "bar", .nodes = {{"A", {0, 0}}, {"B", {1, 0}}, {"C", {0.5, 0}}}, .mass = 1});
  s.add_prismatic({.name = "rail", .axis_from = "bar.A", .axis_to = "bar.B", .slider = "bar.C"});
  EXPECT_TRUE(ThrowsError(building(s), {"rail", "another body"}));
}

TEST(Errors, PrismaticSliderOnGroundWithGroundAxis) {
  System s("s");
  s.add_ground_node("R1", {0, 0}).add_ground_node("R2", {1, 0}).add_ground_node("P", {0.5, 0});
  s.add_prismatic(
      {.name = "rail", .axis_from = "ground.R1", .axis_to = "ground.R2", .slider = "ground.P"});
  EXPECT_TRUE(ThrowsError(building(s), {"rail", "another body"}));
}

TEST(Errors, PinInSlotZeroLengthAxis) {
  System s("s");
  s.add_ground_node("S", {0, 0});
  s.add_body({.name = "pin", .nodes = {{"P", {0.5, 0}}}, .mass = 1});
  s.add_pin_in_slot(
      {.name = "slot", .axis_from = "ground.S", .axis_to = "ground.S", .pin = "pin.P"});
  EXPECT_TRUE(ThrowsError(building(s), {"slot", "zero-length axis"}));
}

TEST(Errors, PinInSlotAxisNodesOnDifferentBodies) {
  System s = crank_only();
  s.add_ground_node("R", {1, 0});
  s.add_body({.name = "pin", .nodes = {{"P", {0.5, 0}}}, .mass = 1});
  s.add_pin_in_slot(
      {.name = "slot", .axis_from = "crank.A", .axis_to = "ground.R", .pin = "pin.P"});
  EXPECT_TRUE(ThrowsError(building(s), {"slot", "same body"}));
}

TEST(Errors, PinInSlotPinOnTheSlotBody) {
  System s("s");
  s.add_body({.name = "bar", .nodes = {{"A", {0, 0}}, {"B", {1, 0}}, {"C", {0.5, 0}}}, .mass = 1});
  s.add_pin_in_slot({.name = "slot", .axis_from = "bar.A", .axis_to = "bar.B", .pin = "bar.C"});
  EXPECT_TRUE(ThrowsError(building(s), {"slot", "another body"}));
}

TEST(Errors, RevoluteJoiningTwoNodesOfTheSameBody) {
  System s = crank_only();
  s.add_revolute({.name = "self", .node_a = "crank.O", .node_b = "crank.A"});
  EXPECT_TRUE(ThrowsError(building(s), {"self", "same body"}));
}

TEST(Errors, RevoluteJoiningANodeToItself) {
  System s = crank_only();
  s.add_revolute({.name = "self", .node_a = "crank.A", .node_b = "crank.A"});
  EXPECT_TRUE(ThrowsError(building(s), {"self"}));
}

TEST(Errors, ActuatedRevoluteOnABodyWithoutRotation) {
  System s = crank_only();
  s.add_body({.name = "bead", .nodes = {{"P", {0.1, 0}}}, .mass = 1});
  s.add_revolute({.name = "pin", .node_a = "crank.A", .node_b = "bead.P", .actuated = true});
  EXPECT_TRUE(ThrowsError(building(s), {"pin", "bead", "no rotation"}));
}

// =================================================================================================
// Other definitions: coordinates, user constraints, loads, gravity
// =================================================================================================

TEST(Errors, CoordinateRateUnknownWithSuggestion) {
  System s = crank_only();
  s.add_coordinate({.name = "crank.angle", .rate = {{"crank.ww", 1.0}}});
  EXPECT_TRUE(ThrowsError(building(s), {"crank.angle", "crank.ww", "did you mean 'crank.w'"}));
}

TEST(Errors, CoordinateWithoutRate) {
  System s = crank_only();
  s.add_coordinate({.name = "crank.angle", .rate = {}});
  EXPECT_TRUE(ThrowsError(building(s), {"crank.angle", "no rate"}));
}

TEST(Errors, CoordinateDefinedByItsOwnRate) {
  System s = crank_only();
  s.add_coordinate({.name = "phi", .rate = {{"phi.rate", 1.0}}});
  EXPECT_TRUE(ThrowsError(building(s), {"phi", "own rate"}));
}

TEST(Errors, CoordinateNonFiniteWeight) {
  System s = crank_only();
  s.add_coordinate({.name = "crank.angle", .rate = {{"crank.w", kNaN}}});
  EXPECT_TRUE(ThrowsError(building(s), {"crank.angle", "crank.w", "non-finite"}));
}

TEST(Errors, CoordinateNonFiniteInitialValue) {
  System s = crank_only();
  s.add_coordinate({.name = "crank.angle", .rate = {{"crank.w", 1.0}}, .initial = kInf});
  EXPECT_TRUE(ThrowsError(building(s), {"crank.angle", "not finite"}));
}

TEST(Errors, CoordinateClashingWithANodeCoordinate) {
  System s = crank_only();
  s.add_coordinate({.name = "crank.A.x", .rate = {{"crank.w", 1.0}}});
  EXPECT_TRUE(ThrowsError(building(s), {"crank.A.x", "clashes"}));
}

TEST(Errors, UserConstraintUnknownCoordinateWithSuggestion) {
  System s = mechanisms::pendulum().system;
  s.add_constraint(PositionConstraintDef{
      .name = "c", .args = {"link.P.z"}, .psi = [](std::span<const Jet> x, Jet) { return x[0]; }});
  EXPECT_TRUE(ThrowsError(building(s), {"'c'", "link.P.z", "did you mean"}));
}

TEST(Errors, UserConstraintOnAGroundedCoordinate) {
  System s = mechanisms::pendulum().system;
  s.add_constraint(PositionConstraintDef{
      .name = "c", .args = {"link.O.x"}, .psi = [](std::span<const Jet> x, Jet) { return x[0]; }});
  EXPECT_TRUE(ThrowsError(building(s), {"'c'", "link.O.x", "fixed"}));
}

TEST(Errors, UserConstraintWithoutFunction) {
  System s = mechanisms::pendulum().system;
  s.add_constraint(PositionConstraintDef{.name = "c", .args = {"link.P.x"}, .psi = {}});
  EXPECT_TRUE(ThrowsError(building(s), {"'c'", "no function"}));
}

TEST(Errors, UserConstraintWithTooManyArguments) {
  System s = mechanisms::pendulum().system;
  std::vector<std::string> args(33, "link.P.x");
  s.add_constraint(PositionConstraintDef{
      .name = "c", .args = args, .psi = [](std::span<const Jet> x, Jet) { return x[0]; }});
  EXPECT_TRUE(ThrowsError(building(s), {"'c'", "32"}));
}

TEST(Errors, VelocityConstraintUnknownRate) {
  System s = mechanisms::pendulum().system;
  s.add_constraint(VelocityConstraintDef{
      .name = "roll",
      .coords = {},
      .rates = {"link.P.vz"},
      .g = [](std::span<const Jet>, std::span<const Jet> v, Jet) { return v[0]; }});
  EXPECT_TRUE(ThrowsError(building(s), {"roll", "link.P.vz", "did you mean"}));
}

TEST(Errors, ForceOnUnknownBodyWithSuggestion) {
  System s = crank_only();
  s.add_force(
      {.name = "push", .body = "crnak", .point = {0.1, 0}, .fx = [](double) { return 1.0; }});
  EXPECT_TRUE(ThrowsError(building(s), {"push", "crnak", "did you mean 'crank'"}));
}

TEST(Errors, ForceOffTheNodeOfAOneNodeBody) {
  System s = crank_only();
  s.add_body({.name = "bead", .nodes = {{"P", {0.1, 0}}}, .mass = 1});
  s.add_revolute({.name = "pin", .node_a = "crank.A", .node_b = "bead.P"});
  s.add_force(
      {.name = "push", .body = "bead", .point = {0.5, 0}, .fx = [](double) { return 1.0; }});
  EXPECT_TRUE(ThrowsError(building(s), {"push", "bead", "one node"}));
}

TEST(Errors, TorqueOnABodyWithoutRotation) {
  System s = crank_only();
  s.add_body({.name = "bead", .nodes = {{"P", {0.1, 0}}}, .mass = 1});
  s.add_revolute({.name = "pin", .node_a = "crank.A", .node_b = "bead.P"});
  s.add_torque({.name = "twist", .body = "bead", .torque = [](double) { return 1.0; }});
  EXPECT_TRUE(ThrowsError(building(s), {"twist", "bead", "no rotation"}));
}

TEST(Errors, NonFiniteGravity) {
  System s = crank_only();
  s.set_gravity({0, kNaN});
  EXPECT_TRUE(ThrowsError(building(s), {"gravity", "not finite"}));
}

// =================================================================================================
// Subsystems
// =================================================================================================

TEST(Errors, DuplicateInstanceNames) {
  System s("rrr3");
  s.add_body(
      {.name = "platform", .nodes = {{"C", {0, 0}}, {"P1", {1, 0}}}, .mass = 1, .inertia = 0.25});
  const System leg = mechanisms::rrr3_leg();
  s.add_instance("leg1", leg);
  s.add_instance("leg1", leg, Placement{{0, 0}, 2.0});
  Error e("");
  EXPECT_TRUE(ThrowsError(building(s), {"leg1", "twice"}, &e));
  EXPECT_EQ(e.element(), "leg1");
}

TEST(Errors, DuplicateInstanceNamesInANestedSubsystem) {
  System inner("pair");
  const System leg = mechanisms::rrr3_leg();
  inner.add_instance("leg", leg);
  inner.add_instance("leg", leg);
  System s("root");
  s.add_instance("pair", inner);
  EXPECT_TRUE(ThrowsError(building(s), {"pair.leg", "twice"}));
}

TEST(Errors, GravityInAChildSubsystem) {
  System leg = mechanisms::rrr3_leg();
  leg.set_gravity({0, -9.81});
  System s("root");
  s.add_instance("leg1", leg);
  EXPECT_TRUE(ThrowsError(building(s), {"leg1", "gravity"}));
}

TEST(Errors, GravityInAGrandchildSubsystem) {
  System leg = mechanisms::rrr3_leg();
  leg.set_gravity({0, -9.81});
  System mid("mid");
  mid.add_instance("leg", leg);
  System s("root");
  s.add_instance("arm", mid);
  EXPECT_TRUE(ThrowsError(building(s), {"arm.leg", "gravity"}));
}

// The element of the gravity error is the instance path without the trailing '.', like every other
// element label (instance errors use "leg1", not "leg1.").
TEST(Errors, GravityInAChildSubsystemElementIsTheInstancePath) {
  System leg = mechanisms::rrr3_leg();
  leg.set_gravity({0, -9.81});
  System s("root");
  s.add_instance("leg1", leg);
  Error e("");
  EXPECT_TRUE(ThrowsError(building(s), {"'leg1'", "gravity"}, &e));
  EXPECT_EQ(e.element(), "leg1");
}

TEST(Errors, ReferenceToANodeOfAMissingInstance) {
  auto ex = mechanisms::rrr3();
  System s = ex.system;
  s.add_revolute({.name = "attach4", .node_a = "platform.C", .node_b = "leg4.distal.P"});
  Error e("");
  EXPECT_TRUE(
      ThrowsError(building(s), {"attach4", "leg4.distal.P", "not found", "did you mean"}, &e));
  EXPECT_EQ(e.element(), "attach4");
}

TEST(Errors, ReferenceToAMissingNodeInsideAnInstance) {
  System leg = mechanisms::rrr3_leg();
  leg.add_revolute({.name = "extra", .node_a = "proximal.E", .node_b = "distal.Q"});
  System s("root");
  s.add_instance("leg1", leg);
  Error e("");
  EXPECT_TRUE(
      ThrowsError(building(s), {"leg1.extra", "leg1.distal.Q", "did you mean 'distal."}, &e));
}

TEST(Errors, InvalidInstanceName) {
  System s("root");
  s.add_instance("leg.1", mechanisms::rrr3_leg());
  EXPECT_TRUE(ThrowsError(building(s), {"leg.1"}));
}

// =================================================================================================
// Names used twice
// =================================================================================================

// Two prismatic joints with the same name: their slider coordinates share the label "rail.q"
// (the second silently shadows the first), and their reactions share "rail.Fx", ... Expected: an
// Error naming the joint, as for bodies and nodes defined twice.
TEST(Errors, JointNameUsedTwice) {
  System s("s");
  s.add_ground_node("R1", {0, 0}).add_ground_node("R2", {1, 0}).add_ground_node("R3", {0, 1});
  s.add_body({.name = "a", .nodes = {{"P", {0.5, 0}}}, .mass = 1});
  s.add_body({.name = "b", .nodes = {{"P", {0, 0.5}}}, .mass = 1});
  s.add_prismatic(
      {.name = "rail", .axis_from = "ground.R1", .axis_to = "ground.R2", .slider = "a.P"});
  s.add_prismatic(
      {.name = "rail", .axis_from = "ground.R1", .axis_to = "ground.R3", .slider = "b.P"});
  EXPECT_TRUE(ThrowsError(building(s), {"rail", "twice"}));
}

TEST(Errors, RevoluteNameUsedTwice) {
  System s = crank_only();
  s.add_body({.name = "rod", .nodes = {{"A", {0.1, 0}}, {"B", {0.4, 0}}}, .mass = 1});
  s.add_revolute(
      {.name = "pivot", .node_a = "crank.A", .node_b = "rod.A"});  // name of crank's pivot
  EXPECT_TRUE(ThrowsError(building(s), {"pivot", "twice"}));
}
