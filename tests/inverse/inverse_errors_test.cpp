// Inverse dynamics refuses bad prescribed coordinates and actuators, and a failure during a run
// (a NaN motion, signal or constraint; a dead centre or a toggle) is a mo2d::Error naming the
// element and the time: never a crash, a NaN or a silent result.
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
