// Orsino Examples 4.2 and 4.7 (Holics 2011): a thin ring rolls without slipping down an incline
// (angle xi) and a disc rolls without slipping inside it. Velocity-level rolling constraints on
// one-node bodies with rotation. Closed forms from the thesis:
//   steady angle theta_bar (line ring-centre/disc-centre against the vertical) with
//     m2/m1 = sin(th)/(2 sin(xi) cos(th - xi) - 3 sin(th) + sin(xi)) - 1,
//   the common acceleration down the incline 2 g sin(th) / (2 cos(th - xi) + 1),
//   the small-oscillation frequency w = sqrt(-G), G = G_{theta_dot, theta} of Example 4.7 (e).
// Frame of the thesis: x along the incline, y normal to it, gravity g (sin xi, -cos xi).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mo2d/forward.hpp"
#include "mo2d/mo2d.hpp"

using namespace mo2d;

namespace {

constexpr double g = 9.8, r1 = 1.0, r2 = 0.3, m1 = 0.670;
const double xi = std::asin(0.8);
const double theta_bar = std::asin(0.6);  // steady angle for m2/m1 = 8/67

struct RingDisc {
  Model model;
  State start;
};

RingDisc ring_and_disc(double theta0) {
  const double m2 = m1 * 8.0 / 67.0;
  System s("ring_disc");
  const Vec2 p1(0, r1);
  const Vec2 p2 = p1 + (r1 - r2) * Vec2(std::sin(xi - theta0), -std::cos(xi - theta0));
  s.add_body({.name = "ring", .nodes = {{"C", p1}}, .mass = m1, .inertia = m1 * r1 * r1});
  s.add_body({.name = "disc", .nodes = {{"C", p2}}, .mass = m2, .inertia = m2 * r2 * r2 / 2});
  s.add_constraint(PositionConstraintDef{
      .name = "on_plane", .args = {"ring.C.y"}, .psi = [](std::span<const Jet> x, Jet) {
        return x[0] - r1;
      }});
  s.add_constraint(PositionConstraintDef{.name = "inside",
                                         .args = {"ring.C.x", "ring.C.y", "disc.C.x", "disc.C.y"},
                                         .psi = [](std::span<const Jet> x, Jet) {
                                           const Jet dx = x[2] - x[0], dy = x[3] - x[1];
                                           return sqrt(dx * dx + dy * dy) - (r1 - r2);
                                         }});
  // ring on the plane: contact point at (0, -r1) from the centre: u1 + r1 w1 = 0
  s.add_constraint(VelocityConstraintDef{
      .name = "ring_rolls",
      .coords = {},
      .rates = {"ring.C.vx", "ring.w"},
      .g = [](std::span<const Jet>, std::span<const Jet> v, Jet) { return v[0] + r1 * v[1]; }});
  // disc in the ring: tangential velocities of both bodies equal at the contact point
  // (v1 - v2).t + r1 w1 - r2 w2 = 0, n = (p2 - p1)/|p2 - p1|, t = z x n
  s.add_constraint(VelocityConstraintDef{
      .name = "disc_rolls",
      .coords = {"ring.C.x", "ring.C.y", "disc.C.x", "disc.C.y"},
      .rates = {"ring.C.vx", "ring.C.vy", "disc.C.vx", "disc.C.vy", "ring.w", "disc.w"},
      .g = [](std::span<const Jet> x, std::span<const Jet> v, Jet) {
        const Jet dx = x[2] - x[0], dy = x[3] - x[1];
        const Jet l = sqrt(dx * dx + dy * dy);
        const Jet tx = -dy / l, ty = dx / l;
        return (v[0] - v[2]) * tx + (v[1] - v[3]) * ty + r1 * v[4] - r2 * v[5];
      }});
  s.set_gravity({g * std::sin(xi), -g * std::cos(xi)});
  Model m = build_model(s);
  State st =
      consistent_state(m, {.positions = {}, .velocities = {{"ring.C.vx", 0.0}, {"disc.w", 0.0}}});
  return {std::move(m), st};
}

// theta from the centres: p2 - p1 = (r1 - r2) (sin(xi - theta), -cos(xi - theta))
double theta_of(const Model& m, const Trajectory& r, int i) {
  const double dx = r.q0(i, m.coordinate("disc.C.x")) - r.q0(i, m.coordinate("ring.C.x"));
  const double dy = r.q0(i, m.coordinate("disc.C.y")) - r.q0(i, m.coordinate("ring.C.y"));
  return xi - std::atan2(dx, -dy);
}

}  // namespace

TEST(RingDisc, ModelHasTwoDegreesOfFreedom) {
  const RingDisc rd = ring_and_disc(theta_bar);
  EXPECT_EQ(rd.model.dof, 2);
  EXPECT_FALSE(rd.model.holonomic);
  // the thesis's mass ratio for this steady angle
  const double ratio = std::sin(theta_bar) / (2 * std::sin(xi) * std::cos(theta_bar - xi) -
                                              3 * std::sin(theta_bar) + std::sin(xi)) -
                       1;
  EXPECT_NEAR(ratio, 8.0 / 67.0, 1e-12);
}

// Released at the steady angle, the pair keeps theta = theta_bar and accelerates down the incline
// at 2 g sin(theta_bar) / (2 cos(theta_bar - xi) + 1).
TEST(RingDisc, SteadyRelativeAngle) {
  const RingDisc rd = ring_and_disc(theta_bar);
  const Trajectory r = forward_dynamics(
      rd.model, rd.start,
      {.t0 = 0, .t1 = 2, .samples = 21, .integrator = Integrator::rk4, .step = 1e-3});
  const double accel = 2 * g * std::sin(theta_bar) / (2 * std::cos(theta_bar - xi) + 1);
  const int iu1 = r.rate_column("ring.C.vx"), iu2 = r.rate_column("disc.C.vx");
  for (int i = 0; i < r.time.size(); ++i) {
    EXPECT_NEAR(theta_of(rd.model, r, i), theta_bar, 1e-10) << "t = " << r.time[i];
    EXPECT_NEAR(r.a1(i, iu1), accel, 1e-9) << "t = " << r.time[i];
    EXPECT_NEAR(r.a1(i, iu2), accel, 1e-9) << "t = " << r.time[i];
  }
}

// A small departure from theta_bar oscillates at the frequency of the linearized model
// (Example 4.7): w^2 = -G, G given in closed form in (e).
TEST(RingDisc, SmallOscillationFrequencyOfTheLinearizedModel) {
  const double th = theta_bar;
  const double G = 2 * g * (std::cos(th) + 2 * std::cos(xi)) * std::sin(xi) /
                   ((2 * std::cos(th - xi) + 1) *
                    (2 * std::sin(th) + 3 * std::sin(2 * th - xi) - 2 * std::sin(xi) +
                     2 * std::sin(th - 2 * xi) + std::sin(2 * th - 3 * xi)) *
                    (r1 - r2));
  ASSERT_LT(G, 0);
  const double period = 2 * std::numbers::pi / std::sqrt(-G);
  const double delta = 1e-3;
  const RingDisc rd = ring_and_disc(theta_bar + delta);
  const int n = 2001;
  const Trajectory r = forward_dynamics(
      rd.model, rd.start,
      {.t0 = 0, .t1 = 2.2 * period, .samples = n, .integrator = Integrator::rk4, .step = 5e-4});
  // period from the two downward crossings of theta - theta_bar (linear interpolation)
  std::vector<double> crossings;
  for (int i = 1; i < r.time.size(); ++i) {
    const double a = theta_of(rd.model, r, i - 1) - theta_bar,
                 b = theta_of(rd.model, r, i) - theta_bar;
    if (a > 0 && b <= 0)
      crossings.push_back(r.time[i - 1] + (r.time[i] - r.time[i - 1]) * a / (a - b));
  }
  ASSERT_GE(crossings.size(), 2u);
  const double measured = crossings[1] - crossings[0];
  // the nonlinear period differs from the linearized one by O(delta^2) ~ 1e-6 (measured: 8.3e-8)
  EXPECT_NEAR(measured / period, 1.0, 1e-6)
      << "measured " << measured << " s, linearized " << period << " s";
}
