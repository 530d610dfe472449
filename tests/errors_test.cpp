// Bad input must give a clear mo2d::Error naming the offending element (and the time, for a run):
// never a crash, a NaN or a silent result. One test per bad-input path of the core engine.
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

#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"

using namespace mo2d;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

std::string describe_error(const Error& e) {
  return std::string("\"") + e.what() + "\" (element '" + e.element() + "', time " +
         std::to_string(e.time()) + ")";
}

// Passes if f throws mo2d::Error whose what() contains every string of `parts`; the caught
// Error is copied to *out. Any other outcome (no exception, another exception type) fails.
::testing::AssertionResult ThrowsError(const std::function<void()>& f,
                                       const std::vector<std::string>& parts,
                                       Error* out = nullptr) {
  try {
    f();
  } catch (const Error& e) {
    if (out) *out = e;
    if (std::getenv("MO2D_SHOW_ERRORS"))
      std::cout << "  [mo2d::Error] " << describe_error(e) << "\n";
    const std::string what = e.what();
    for (const auto& p : parts)
      if (what.find(p) == std::string::npos)
        return ::testing::AssertionFailure()
               << "the mo2d::Error message lacks \"" << p << "\": " << describe_error(e);
    return ::testing::AssertionSuccess() << describe_error(e);
  } catch (const std::exception& e) {
    return ::testing::AssertionFailure()
           << "threw " << typeid(e).name() << ", not mo2d::Error: " << e.what();
  } catch (...) {
    return ::testing::AssertionFailure() << "threw something that is not a std::exception";
  }
  return ::testing::AssertionFailure() << "no exception was thrown";
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

// what() names element() (the element a caller would highlight is spelled in the message).
::testing::AssertionResult NamesItsElement(const Error& e) {
  if (e.element().empty())
    return ::testing::AssertionFailure() << "element() is empty: " << describe_error(e);
  if (!contains(e.what(), e.element()))
    return ::testing::AssertionFailure()
           << "what() does not contain element() '" << e.element() << "': " << describe_error(e);
  return ::testing::AssertionSuccess();
}

// what() contains at least one of the names.
::testing::AssertionResult NamesOneOf(const Error& e, const std::vector<std::string>& names) {
  for (const auto& n : names)
    if (contains(e.what(), n)) return ::testing::AssertionSuccess();
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  return ::testing::AssertionFailure()
         << "the message names none of {" << list << "}: " << describe_error(e);
}

std::function<void()> building(const System& s, BuildOptions o = {}) {
  return [s, o] { (void)build_model(s, o); };
}

std::function<void()> running(const System& s, std::vector<Prescribed> motion,
                              InverseOptions run = {}, BuildOptions build = {}) {
  return [s, motion, run, build] {
    const Model m = build_model(s, build);
    (void)inverse_dynamics(m, motion, run);
  };
}

Prescribed constant(std::string label, double value) {
  return {std::move(label), [value](Jet) { return Jet(value); }};
}

// A valid crank O-A hinged to the ground at O: the base most tests break one thing of.
System crank_only() {
  System s("crank_only");
  s.add_ground_node("O", {0, 0});
  s.add_body(
      {.name = "crank", .nodes = {{"O", {0, 0}}, {"A", {0.1, 0}}}, .mass = 1, .inertia = 0.01});
  s.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "crank.O", .actuated = true});
  return s;
}

// Crank-rocker four-bar of mechanisms::fourbar() (ground 0.4, crank 0.1, coupler 0.35, rocker
// 0.3; crank vertical at t = 0), with the angles of crank and rocker as coordinates and a choice
// of actuated pivots.
struct FourBarGeometry {
  Vec2 A0{0, 0}, B0{0.4, 0}, A{0, 0.1}, B{0, 0};
  double rocker_angle = 0;
  FourBarGeometry() {
    const double b = 0.35, c = 0.3;
    const Vec2 AB0 = B0 - A;
    const double l = AB0.norm();
    const double x = (b * b - c * c + l * l) / (2 * l);
    const Vec2 ex = AB0 / l, ey(-ex.y(), ex.x());
    B = A + x * ex + std::sqrt(b * b - x * x) * ey;
    rocker_angle = std::atan2(B.y() - B0.y(), B.x() - B0.x());
  }
};

System fourbar_system(bool crank_actuated, bool rocker_actuated) {
  const FourBarGeometry g;
  System s("fourbar");
  s.add_ground_node("A0", g.A0).add_ground_node("B0", g.B0);
  s.add_body({.name = "crank", .nodes = {{"O", g.A0}, {"A", g.A}}, .mass = 0.2, .inertia = 2e-4});
  s.add_body({.name = "coupler", .nodes = {{"A", g.A}, {"B", g.B}}, .mass = 0.5, .inertia = 5e-3});
  s.add_body({.name = "rocker", .nodes = {{"O", g.B0}, {"B", g.B}}, .mass = 0.4, .inertia = 3e-3});
  s.add_revolute({.name = "crank_pivot",
                  .node_a = "ground.A0",
                  .node_b = "crank.O",
                  .actuated = crank_actuated});
  s.add_revolute({.name = "crank_pin", .node_a = "crank.A", .node_b = "coupler.A"});
  s.add_revolute({.name = "rocker_pin", .node_a = "coupler.B", .node_b = "rocker.B"});
  s.add_revolute({.name = "rocker_pivot",
                  .node_a = "ground.B0",
                  .node_b = "rocker.O",
                  .actuated = rocker_actuated});
  s.add_coordinate({.name = "crank.angle", .rate = {{"crank.w", 1.0}}});
  s.add_coordinate({.name = "rocker.angle", .rate = {{"rocker.w", 1.0}}});
  s.set_gravity({0, -9.81});
  return s;
}

// The slider-crank of mechanisms::slider_crank() with its default parameters.
const mechanisms::SliderCrankParams kSC{};

}  // namespace

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
// Inverse dynamics: prescribed coordinates and actuators
// =================================================================================================

TEST(Errors, PrescribingMoreCoordinatesThanDof) {
  auto ex = mechanisms::slider_crank();
  std::vector<Prescribed> p = ex.motion;
  p.push_back(constant("rail.q", 0.45));
  EXPECT_TRUE(ThrowsError(running(ex.system, p, ex.run),
                          {"1 degree(s) of freedom", "2 coordinate(s)", "crank.angle", "rail.q"}));
}

TEST(Errors, PrescribingFewerCoordinatesThanDof) {
  auto ex = mechanisms::rrr3();  // 3 DOF
  std::vector<Prescribed> p(ex.motion.begin(), ex.motion.begin() + 2);
  EXPECT_TRUE(
      ThrowsError(running(ex.system, p, ex.run),
                  {"3 degree(s) of freedom", "2 coordinate(s)", "platform.C.x", "platform.C.y"}));
}

TEST(Errors, PrescribingNothing) {
  auto ex = mechanisms::slider_crank();
  EXPECT_TRUE(
      ThrowsError(running(ex.system, {}, ex.run), {"1 degree(s) of freedom", "0 coordinate"}));
}

// With nothing prescribed the message names nothing at all: it should name the mechanism (its
// element() is the model name "slider_crank", which the message does not contain).
TEST(Errors, PrescribingNothingNamesTheMechanism) {
  auto ex = mechanisms::slider_crank();
  Error e("");
  EXPECT_TRUE(ThrowsError(running(ex.system, {}, ex.run), {"slider_crank", "0 coordinate"}, &e));
  EXPECT_TRUE(NamesItsElement(e));
}

TEST(Errors, UnknownCoordinateLabelWithSuggestion) {
  auto ex = mechanisms::slider_crank();
  Error e("");
  EXPECT_TRUE(ThrowsError(running(ex.system, {constant("crank.angel", 0.0)}, ex.run),
                          {"crank.angel", "did you mean 'crank.angle'"}, &e));
  EXPECT_EQ(e.element(), "crank.angel");
}

TEST(Errors, SameCoordinatePrescribedTwice) {
  auto ex = mechanisms::rrr3();
  std::vector<Prescribed> p = {ex.motion[0], ex.motion[0], ex.motion[2]};  // x, x, angle
  Error e("");
  EXPECT_TRUE(ThrowsError(running(ex.system, p, ex.run), {"platform.C.x", "twice"}, &e));
  EXPECT_EQ(e.element(), "platform.C.x");
}

// platform.P1 and leg1.distal.P are joined by a revolute: two labels of one coordinate.
TEST(Errors, SameCoordinatePrescribedTwiceThroughAnAlias) {
  auto ex = mechanisms::rrr3();
  std::vector<Prescribed> p = {constant("platform.P1.x", 1.0), constant("leg1.distal.P.x", 1.0),
                               ex.motion[2]};
  EXPECT_TRUE(ThrowsError(running(ex.system, p, ex.run), {"leg1.distal.P.x", "twice"}));
}

TEST(Errors, PrescribedCoordinateWithoutMotion) {
  auto ex = mechanisms::slider_crank();
  EXPECT_TRUE(ThrowsError(running(ex.system, {Prescribed{"crank.angle", {}}}, ex.run),
                          {"crank.angle", "no motion"}));
}

// crank.O is hinged to the ground: its coordinate exists in the definitions but is fixed. The
// message should say so, like build_model does for user constraints ("is fixed (joined to the
// ground)"), instead of "unknown coordinate ... (did you mean 'crank.A.x'?)", which points the
// user to a different node.
TEST(Errors, PrescribingAGroundedCoordinateSaysItIsFixed) {
  auto ex = mechanisms::slider_crank();
  Error e("");
  EXPECT_TRUE(ThrowsError(running(ex.system, {constant("crank.O.x", 0.0)}, ex.run),
                          {"crank.O.x", "fixed"}, &e));
  EXPECT_FALSE(contains(e.what(), "did you mean")) << e.what();
}

// On the slider-crank the rail fixes the slider's y: prescribing it is not an input.
TEST(Errors, SliderCrankPrescribingTheRailFixedCoordinate) {
  auto ex = mechanisms::slider_crank();
  Error e("");
  EXPECT_TRUE(ThrowsError(running(ex.system, {constant("rod.B.y", kSC.e)}, ex.run),
                          {"rod.B.y", "not independent"}, &e));
  EXPECT_EQ(e.element(), "rod.B.y");
  EXPECT_NEAR(e.time(), 0.0, 1e-15);
}

// The same, with a value the rail cannot reach: Newton meets the singular Jacobian first.
TEST(Errors, SliderCrankPrescribingTheRailFixedCoordinateOffTheRail) {
  auto ex = mechanisms::slider_crank();
  EXPECT_TRUE(ThrowsError(running(ex.system, {constant("slider.B.y", 0.2)}, ex.run),
                          {"slider.B.y", "not independent"}));
}

// Four-bar with the crank vertical at t = 0: the crank pin A moves horizontally, so its y (a
// coupler node coordinate, coupler.A.y) is stationary there and cannot be an input at t = 0,
// while coupler.A.x could be.
TEST(Errors, FourBarPrescribingADependentCouplerNodeCoordinate) {
  const System s = fourbar_system(true, false);
  Error e("");
  EXPECT_TRUE(ThrowsError(running(s, {{"coupler.A.y", [](Jet t) { return 0.1 * cos(t); }}},
                                  {.t0 = 0, .t1 = 1, .samples = 11}),
                          {"coupler.A.y", "not independent"}, &e));
  EXPECT_EQ(e.element(), "coupler.A.y");
  EXPECT_NEAR(e.time(), 0.0, 1e-15);
}

// Control for the previous test: coupler.A.x is an independent input at t = 0.
TEST(Errors, FourBarIndependentCouplerNodeCoordinateIsAccepted) {
  const System s = fourbar_system(true, false);
  const Model m = build_model(s);
  std::vector<Prescribed> p = {{"coupler.A.x", [](Jet t) { return 0.01 * sin(t); }}};
  EXPECT_NO_THROW((void)inverse_dynamics(m, p, {.t0 = 0, .t1 = 0.2, .samples = 11}));
}

TEST(Errors, ActuatorsMoreThanDof) {
  const System s = fourbar_system(true, true);
  Error e("");
  EXPECT_TRUE(
      ThrowsError(running(s, {{"crank.angle", [](Jet t) { return std::numbers::pi / 2 + t; }}}),
                  {"actuator", "1 DOF", "2 actuated"}, &e));
}

TEST(Errors, ActuatorsFewerThanDof) {
  const System s = fourbar_system(false, false);
  EXPECT_TRUE(
      ThrowsError(running(s, {{"crank.angle", [](Jet t) { return std::numbers::pi / 2 + t; }}}),
                  {"actuator", "1 DOF", "0 actuated"}));
}

// The actuator-count message should name the actuated inputs (here crank_pivot.torque and
// rocker_pivot.torque) or at least the mechanism (element() is "fourbar", not in the message).
TEST(Errors, ActuatorsMoreThanDofNamesTheInputs) {
  const System s = fourbar_system(true, true);
  Error e("");
  EXPECT_TRUE(
      ThrowsError(running(s, {{"crank.angle", [](Jet t) { return std::numbers::pi / 2 + t; }}}),
                  {"crank_pivot.torque", "rocker_pivot.torque"}, &e));
  EXPECT_TRUE(NamesItsElement(e));
}

TEST(Errors, NonHolonomicModelForInverseDynamics) {
  System s = crank_only();
  s.add_coordinate({.name = "half", .rate = {{"crank.w", 0.5}}});  // not an integer weight
  EXPECT_TRUE(ThrowsError(running(s, {constant("crank.A.x", 0.1)}), {"crank_only", "holonomic"}));
}

TEST(Errors, InvalidRunOptions) {
  auto ex = mechanisms::slider_crank();
  EXPECT_TRUE(
      ThrowsError(running(ex.system, ex.motion, {.t0 = 0, .t1 = 1, .samples = 0}), {"samples"}));
  EXPECT_TRUE(
      ThrowsError(running(ex.system, ex.motion, {.t0 = 1, .t1 = 0, .samples = 10}), {"t0"}));
  EXPECT_TRUE(
      ThrowsError(running(ex.system, ex.motion, {.t0 = 0, .t1 = kNaN, .samples = 10}), {"t0"}));
}

TEST(Errors, RecursiveComplementOnAFlatModelWithSubsystems) {
  auto ex = mechanisms::rrr3();
  InverseOptions run = ex.run;
  run.complement = ComplementMethod::recursive;
  EXPECT_TRUE(ThrowsError(running(ex.system, ex.motion, run), {"Reduction::subsystems"}));
}

// =================================================================================================
// Inverse dynamics: failures during a run carry the time
// =================================================================================================

TEST(Errors, PrescribedMotionReturningNaN) {
  auto ex = mechanisms::slider_crank();
  std::vector<Prescribed> p = {
      {"crank.angle", [](Jet t) { return t.v >= 0.5 ? Jet(kNaN) : 4 * t; }}};
  Error e("");
  EXPECT_TRUE(ThrowsError(running(ex.system, p, {.t0 = 0, .t1 = 1, .samples = 201}),
                          {"crank.angle", "not finite", "t = 0.5"}, &e));
  EXPECT_EQ(e.element(), "crank.angle");
  EXPECT_DOUBLE_EQ(e.time(), 0.5);
}

// A motion whose derivative is infinite (sqrt at t = 0): s_dot must be checked as well.
TEST(Errors, PrescribedMotionWithInfiniteVelocity) {
  auto ex = mechanisms::slider_crank();
  std::vector<Prescribed> p = {{"crank.angle", [](Jet t) { return sqrt(t); }}};
  Error e("");
  EXPECT_TRUE(ThrowsError(running(ex.system, p, {.t0 = 0, .t1 = 1, .samples = 11}),
                          {"crank.angle", "not finite", "t = 0"}, &e));
  EXPECT_EQ(e.time(), 0.0);
}

// Slider-crank driven by the slider position (rail.q) at 10 mm/s towards the outer dead centre,
// |OB| = r + L, which it reaches at t* = (sqrt((r + L)^2 - e^2) - q(0)) / 0.01 ~ 0.0287 s. There
// the crank cannot follow: the run must stop with the time, not return NaN or garbage.
TEST(Errors, SliderCrankDrivenThroughDeadCentre) {
  auto ex = mechanisms::slider_crank();
  const double q0 = kSC.r + std::sqrt(kSC.L * kSC.L - kSC.e * kSC.e);
  const double q_dead = std::sqrt((kSC.r + kSC.L) * (kSC.r + kSC.L) - kSC.e * kSC.e);
  const double rate = 0.01, t_dead = (q_dead - q0) / rate;
  std::vector<Prescribed> p = {{"rail.q", [=](Jet t) { return Jet(q0) + rate * t; }}};
  const InverseOptions run{.t0 = 0, .t1 = 2 * t_dead, .samples = 401};
  const double dt = (run.t1 - run.t0) / (run.samples - 1);
  Error e("");
  EXPECT_TRUE(ThrowsError(running(ex.system, p, run), {"t =", "rail.q"}, &e));
  ASSERT_TRUE(std::isfinite(e.time())) << describe_error(e);
  EXPECT_GE(e.time(), 0.9 * t_dead) << describe_error(e);
  EXPECT_LE(e.time(), t_dead + 1.5 * dt) << describe_error(e);
  EXPECT_FALSE(e.element().empty());
}

// Crank-rocker four-bar driven by the rocker angle (actuator at the rocker pivot) towards its
// extreme position 101.4 deg, where crank and coupler are aligned (toggle).
TEST(Errors, FourBarDrivenThroughToggle) {
  const System s = fourbar_system(false, true);
  const FourBarGeometry g;
  const double a = 0.1, b = 0.35, c = 0.3, d = 0.4;
  const double phi_toggle = std::acos(((a + b) * (a + b) - d * d - c * c) / (2 * d * c));
  const double phi0 = g.rocker_angle, rate = -1.0;  // rad/s, towards the toggle
  ASSERT_GT(phi0, phi_toggle);
  const double t_toggle = (phi_toggle - phi0) / rate;  // ~0.145 s
  std::vector<Prescribed> p = {{"rocker.angle", [=](Jet t) { return Jet(phi0) + rate * t; }}};
  const InverseOptions run{.t0 = 0, .t1 = 2 * t_toggle, .samples = 401};
  const double dt = (run.t1 - run.t0) / (run.samples - 1);
  Error e("");
  EXPECT_TRUE(ThrowsError(running(s, p, run), {"t =", "rocker.angle"}, &e));
  ASSERT_TRUE(std::isfinite(e.time())) << describe_error(e);
  EXPECT_GE(e.time(), 0.9 * t_toggle) << describe_error(e);
  EXPECT_LE(e.time(), t_toggle + 1.5 * dt) << describe_error(e);
}

// The same toggle reached sample by sample through inverse_dynamics_sample.
TEST(Errors, FourBarToggleThroughSampleApi) {
  const Model m = build_model(fourbar_system(false, true));
  const FourBarGeometry g;
  const double phi_toggle = std::acos((0.45 * 0.45 - 0.16 - 0.09) / 0.24);
  const double phi0 = g.rocker_angle;
  std::vector<Prescribed> p = {{"rocker.angle", [=](Jet t) { return Jet(phi0) - t; }}};
  InverseData d(m, p);
  const double t_toggle = phi0 - phi_toggle;
  Error e("");
  EXPECT_TRUE(ThrowsError(
      [&] {
        for (int k = 0; k <= 400; ++k) inverse_dynamics_sample(m, d, 2 * t_toggle * k / 400);
      },
      {"t ="}, &e));
  EXPECT_NEAR(e.time(), t_toggle, 0.1 * t_toggle);
}

TEST(Errors, ResultLookupOfAnUnknownLabel) {
  auto ex = mechanisms::pendulum();
  InverseOptions run = ex.run;
  run.samples = 3;
  const Model m = build_model(ex.system);
  const Trajectory r = inverse_dynamics(m, ex.motion, run);
  EXPECT_TRUE(ThrowsError([&] { (void)r.column("link.Q.x"); }, {"link.Q.x"}));
  EXPECT_TRUE(ThrowsError([&] { (void)r.effort("pivot.force"); }, {"pivot.force"}));
  EXPECT_TRUE(ThrowsError([&] { (void)r.reaction("pivot.Fz"); }, {"pivot.Fz"}));
  EXPECT_TRUE(ThrowsError([&] { (void)m.rate("link.P.vz"); }, {"link.P.vz", "did you mean"}));
}

// =================================================================================================
// Silent NaN paths (expected behaviour; see the report of each)
// =================================================================================================

// A force signal that returns NaN from t = 0.5: the efforts become NaN and the run returns them
// silently. Expected: an Error naming the force and the time.
TEST(Errors, ForceSignalReturningNaNDuringARun) {
  auto ex = mechanisms::slider_crank();
  System s = ex.system;
  s.add_force({.name = "gas", .body = "rod", .point = {0.2, 0.0}, .fx = [](double t) {
                 return t >= 0.5 ? kNaN : -10.0;
               }});
  Error e("");
  EXPECT_TRUE(ThrowsError(running(s, ex.motion, {.t0 = 0, .t1 = 1, .samples = 201}),
                          {"gas", "t = 0.5"}, &e));
  EXPECT_DOUBLE_EQ(e.time(), 0.5);
}

TEST(Errors, TorqueSignalReturningNaNDuringARun) {
  auto ex = mechanisms::slider_crank();
  System s = ex.system;
  s.add_torque({.name = "brake", .body = "crank", .torque = [](double t) {
                  return t >= 0.5 ? kNaN : -1.0;
                }});
  Error e("");
  EXPECT_TRUE(ThrowsError(running(s, ex.motion, {.t0 = 0, .t1 = 1, .samples = 201}),
                          {"brake", "t = 0.5"}, &e));
  EXPECT_DOUBLE_EQ(e.time(), 0.5);
}

// Two sliders on perpendicular rails linked by the user constraint sqrt(qA) + qB = 1. Driving
// qA = 0.5 - t makes the constraint NaN from t = 0.5 on. Expected: an Error naming the constraint
// with the time; the NaN residual must not pass the Newton loop as "converged" (an infinity norm
// skips NaN).
TEST(Errors, UserConstraintTurningNaNDuringARun) {
  System s("sqrt_link");
  s.add_ground_node("O", {0, 0}).add_ground_node("X", {1, 0}).add_ground_node("Y", {0, 1});
  const double qa0 = 0.5, qb0 = 1 - std::sqrt(qa0);
  s.add_body({.name = "a", .nodes = {{"P", {qa0, 0}}}, .mass = 1});
  s.add_body({.name = "b", .nodes = {{"P", {0, qb0}}}, .mass = 1});
  s.add_prismatic({.name = "ra",
                   .axis_from = "ground.O",
                   .axis_to = "ground.X",
                   .slider = "a.P",
                   .actuated = true});
  s.add_prismatic({.name = "rb", .axis_from = "ground.O", .axis_to = "ground.Y", .slider = "b.P"});
  s.add_constraint(PositionConstraintDef{
      .name = "link", .args = {"ra.q", "rb.q"}, .psi = [](std::span<const Jet> x, Jet) {
        return sqrt(x[0]) + x[1] - Jet(1.0);
      }});
  std::vector<Prescribed> p = {{"ra.q", [=](Jet t) { return Jet(qa0) - t; }}};
  Error e("");
  // samples at t = k / 99: the first one past qA = 0 is t = 50 / 99 (qA = -0.005, psi = NaN)
  EXPECT_TRUE(ThrowsError(running(s, p, {.t0 = 0, .t1 = 1, .samples = 100}), {"link", "t ="}, &e));
  EXPECT_NEAR(e.time(), 50.0 / 99.0, 1e-12);
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
