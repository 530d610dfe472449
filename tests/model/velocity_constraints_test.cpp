// VelocityConstraintDef from C++: the labels form (sorted into coordinates and quasi-velocities
// by build_model, the form scene files use) against the coords/rates form, and the refusals:
// a g that is not linear in the rates (Orsino eq. 2.11), an unknown or fixed label, both forms.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "error_support.hpp"
#include "mo2d/forward.hpp"
#include "mo2d/mo2d.hpp"

namespace mo2d {
namespace {

using test::ThrowsError;

constexpr double r = 0.2, m = 1.0, I = 0.02;

// A disc on the line y = r, pushed along by gravity (1, -9.81), rolling without slipping.
System disc(VelocityConstraintDef rolls) {
  System s("disc");
  s.add_body({.name = "disc", .nodes = {{"C", Vec2(0, r)}}, .mass = m, .inertia = I});
  s.add_constraint(PositionConstraintDef{
      .name = "on_line", .args = {"disc.C.y"}, .psi = [](std::span<const Jet> x, Jet) {
        return x[0] - r;
      }});
  s.add_constraint(std::move(rolls));
  s.set_gravity({1, -9.81});
  return s;
}

VelocityConstraintDef by_labels(std::vector<std::string> labels,
                                std::function<Jet(std::span<const Jet>, Jet)> g) {
  VelocityConstraintDef d;
  d.name = "rolls";
  d.labels = std::move(labels);
  d.g_labels = std::move(g);
  return d;
}

TEST(VelocityConstraints, LabelsFormEqualsCoordsRatesForm) {
  // (1 + x^2) vx + r w = 0 with x a coordinate: the labels in mixed order
  const Model a = build_model(
      disc(by_labels({"disc.w", "disc.C.x", "disc.C.vx"}, [](std::span<const Jet> v, Jet) {
        return (1 + v[1] * v[1]) * v[2] + r * v[0];
      })));
  const Model b = build_model(
      disc(VelocityConstraintDef{.name = "rolls",
                                 .coords = {"disc.C.x"},
                                 .rates = {"disc.C.vx", "disc.w"},
                                 .g = [](std::span<const Jet> x, std::span<const Jet> v, Jet) {
                                   return (1 + x[0] * x[0]) * v[0] + r * v[1];
                                 }}));
  EXPECT_EQ(a.dof, 1);
  EXPECT_FALSE(a.holonomic);
  const State sa = consistent_state(a, {.positions = {}, .velocities = {{"disc.w", -3.0}}});
  const State sb = consistent_state(b, {.positions = {}, .velocities = {{"disc.w", -3.0}}});
  const ForwardOptions o{.t0 = 0, .t1 = 1, .samples = 11, .integrator = Integrator::rk4};
  const Trajectory ta = forward_dynamics(a, sa, o), tb = forward_dynamics(b, sb, o);
  EXPECT_EQ((ta.q0 - tb.q0).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ((ta.q1 - tb.q1).cwiseAbs().maxCoeff(), 0.0);
  // rolling: vx = -r w / (1 + x^2) at every sample
  for (int i = 0; i < ta.time.size(); ++i) {
    const double x = ta.q0(i, a.coordinate("disc.C.x"));
    EXPECT_NEAR((1 + x * x) * ta.q1(i, ta.rate_column("disc.C.vx")) +
                    r * ta.q1(i, ta.rate_column("disc.w")),
                0, 1e-12);
  }
}

// The closed form on a straight line: a = g_x / (1 + I / (m r^2)), from the labels form.
TEST(VelocityConstraints, RollingDiscAcceleration) {
  const Model md = build_model(disc(by_labels(
      {"disc.C.vx", "disc.w"}, [](std::span<const Jet> v, Jet) { return v[0] + r * v[1]; })));
  const State s = consistent_state(md, {.positions = {}, .velocities = {{"disc.w", 2.0}}});
  const Trajectory t = forward_dynamics(
      md, s, {.t0 = 0, .t1 = 0.5, .samples = 6, .integrator = Integrator::rk4, .step = 1e-3});
  const double a = 1.0 / (1 + I / (m * r * r));
  for (int i = 0; i < t.time.size(); ++i) {
    EXPECT_NEAR(t.a1(i, t.rate_column("disc.C.vx")), a, 1e-12);
    EXPECT_NEAR(t.q1(i, t.rate_column("disc.C.vx")), -r * 2.0 + a * t.time[i], 1e-12);
  }
  EXPECT_LE(energy_balance_error(t), 1e-12);
}

TEST(VelocityConstraints, NotLinearInTheRatesIsRefused) {
  // coords/rates form too
  EXPECT_TRUE(ThrowsError(
      [] {
        build_model(disc(VelocityConstraintDef{.name = "rolls",
                                               .coords = {},
                                               .rates = {"disc.C.vx", "disc.w"},
                                               .g = [](std::span<const Jet>, std::span<const Jet> v,
                                                       Jet) { return v[0] + r * v[1] * v[1]; }}));
      },
      {"constraint 'rolls'", "not linear in 'disc.w'", "eq. 2.11"}));
  EXPECT_TRUE(ThrowsError(
      [] {
        build_model(disc(by_labels({"disc.C.vx", "disc.w"},
                                   [](std::span<const Jet> v, Jet) { return v[0] * v[1]; })));
      },
      {"constraint 'rolls'", "not linear in the quasi-velocities"}));
}

TEST(VelocityConstraints, LabelErrors) {
  Error e("");
  EXPECT_TRUE(ThrowsError(
      [] {
        build_model(disc(by_labels({"disc.C.vx", "disc.W"},
                                   [](std::span<const Jet> v, Jet) { return v[0] + v[1]; })));
      },
      {"constraint 'rolls': unknown coordinate or quasi-velocity 'disc.W'",
       "did you mean 'disc.w'"},
      &e));
  EXPECT_EQ(e.element(), "disc.W");
  EXPECT_TRUE(ThrowsError(
      [] {
        build_model(
            disc(by_labels({"disc.C.x"}, [](std::span<const Jet> v, Jet) { return v[0]; })));
      },
      {"constraint 'rolls': uses no quasi-velocity"}));
  EXPECT_TRUE(ThrowsError(
      [] {
        VelocityConstraintDef d =
            by_labels({"disc.w"}, [](std::span<const Jet> v, Jet) { return v[0]; });
        d.rates = {"disc.w"};
        build_model(disc(d));
      },
      {"give either coords, rates and g, or labels and g_labels"}));
  // a node joined to the ground: its coordinates are fixed, its rates zero
  EXPECT_TRUE(ThrowsError(
      [] {
        System s = disc(by_labels({"disc.C.vx", "disc.w"},
                                  [](std::span<const Jet> v, Jet) { return v[0] + r * v[1]; }));
        s.add_ground_node("O", Vec2(1, 0));
        s.add_body({.name = "arm", .nodes = {{"O", Vec2(1, 0)}, {"P", Vec2(2, 0)}}, .mass = 1});
        s.add_revolute({.name = "pin", .node_a = "ground.O", .node_b = "arm.O"});
        VelocityConstraintDef d = by_labels(
            {"arm.O.vx", "disc.w"}, [](std::span<const Jet> v, Jet) { return v[0] + v[1]; });
        d.name = "arm_rolls";
        s.add_constraint(std::move(d));
        build_model(s);
      },
      {"quasi-velocity 'arm.O.vx' is zero (its node is joined to the ground)"}));
}

}  // namespace
}  // namespace mo2d
