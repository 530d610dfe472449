// Velocity-level constraints from scene files (`constraints: NAME: {g: ...}`), on the shipped
// examples mechanisms/ring_disc.yaml (Orsino Examples 4.2 and 4.7) and mechanisms/rolling_disc.yaml
// (a disc rolling down an incline), against their closed forms, against the same mechanism
// written in C++ with VelocityConstraintDef's coords/rates form, and the energy balance (rolling
// constraints do no work).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "mo2d/forward.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"

namespace mo2d {
namespace {

std::string scene_path(const std::string& name) {
  return std::string(MO2D_MECHANISMS_DIR) + "/" + name + ".yaml";
}

// The thesis's data (Example 4.7): m2/m1 = 8/67, xi = asin(4/5), theta_bar = asin(3/5).
constexpr double g = 9.8, r1 = 1.0, r2 = 0.3, m1 = 0.670;
const double xi = std::asin(0.8);
const double theta_bar = std::asin(0.6);

struct SceneRun {
  Model model;
  Trajectory r;
};

SceneRun run_scene(const std::string& name, const std::vector<ParameterOverride>& overrides = {},
                   void (*adjust)(ForwardOptions&) = nullptr) {
  const Scene scene = load_scene(scene_path(name), overrides);
  Model m = build_scene_model(scene);
  ForwardOptions o = forward_options(scene, m);
  if (adjust) adjust(o);
  check_scene_options(scene, m, o);
  Trajectory r = forward_dynamics(m, initial_state(scene, m), o);
  return {std::move(m), std::move(r)};
}

// theta from the centres: disc.C - ring.C = (r1 - r2) (sin(xi - theta), -cos(xi - theta))
double theta_of(const Model& m, const Trajectory& r, int i) {
  const double dx = r.q0(i, m.coordinate("disc.C.x")) - r.q0(i, m.coordinate("ring.C.x"));
  const double dy = r.q0(i, m.coordinate("disc.C.y")) - r.q0(i, m.coordinate("ring.C.y"));
  return xi - std::atan2(dx, -dy);
}

// G_{theta_dot, theta} of Example 4.7 (e); omega_bar = sqrt(-G).
double omega_bar() {
  const double th = theta_bar;
  const double G = 2 * g * (std::cos(th) + 2 * std::cos(xi)) * std::sin(xi) /
                   ((2 * std::cos(th - xi) + 1) *
                    (2 * std::sin(th) + 3 * std::sin(2 * th - xi) - 2 * std::sin(xi) +
                     2 * std::sin(th - 2 * xi) + std::sin(2 * th - 3 * xi)) *
                    (r1 - r2));
  return std::sqrt(-G);
}

TEST(RollingScene, RingDiscModelFromTheScene) {
  const Scene scene = load_scene(scene_path("ring_disc"));
  const Model m = build_scene_model(scene);
  EXPECT_EQ(m.dof, 2);
  EXPECT_FALSE(m.holonomic);
  EXPECT_EQ(m.n0, 4);  // ring.C, disc.C
  EXPECT_EQ(m.n1, 6);  // their rates and ring.w, disc.w
  EXPECT_EQ(m.m0, 2);  // on_plane, inside
  EXPECT_EQ(m.m1, 4);  // their rates, ring_rolls, disc_rolls
  int rolling = 0;
  for (const auto& c : m.constraints) rolling += c.kind() == ConstraintKind::user_velocity;
  EXPECT_EQ(rolling, 2);
  // the mass ratio of the scene's parameters gives the thesis's steady angle, Example 4.2 (h)
  const double ratio = std::sin(theta_bar) / (2 * std::sin(xi) * std::cos(theta_bar - xi) -
                                              3 * std::sin(theta_bar) + std::sin(xi)) -
                       1;
  EXPECT_NEAR(ratio, 8.0 / 67.0, 1e-12);
}

// Example 4.2 (h): released at theta_bar the pair keeps theta = theta_bar, with
// du1 = du2 = 2 g sin(theta_bar) / (2 cos(theta_bar - xi) + 1), dv1 = dv2 = 0,
// dw1 = -du1 / r1, dw2 = -du2 / r2, at every sample of the scene's forward run.
TEST(RollingScene, RingDiscSteadySolutionOfExample42h) {
  const SceneRun run = run_scene("ring_disc");
  const Model& m = run.model;
  const Trajectory& r = run.r;
  const double a = 2 * g * std::sin(theta_bar) / (2 * std::cos(theta_bar - xi) + 1);
  const int u1 = r.rate_column("ring.C.vx"), v1 = r.rate_column("ring.C.vy"),
            w1 = r.rate_column("ring.w"), u2 = r.rate_column("disc.C.vx"),
            v2 = r.rate_column("disc.C.vy"), w2 = r.rate_column("disc.w");
  double worst = 0;
  for (int i = 0; i < r.time.size(); ++i) {
    const double errs[] = {r.a1(i, u1) - a,
                           r.a1(i, u2) - a,
                           r.a1(i, v1),
                           r.a1(i, v2),
                           r.a1(i, w1) + a / r1,
                           r.a1(i, w2) + a / r2,
                           theta_of(m, r, i) - theta_bar};
    for (const double e : errs) worst = std::max(worst, std::abs(e));
  }
  std::printf("ring_disc steady: max |error| against Example 4.2 (h) %.3g (a = %.12f m/s^2)\n",
              worst, a);
  EXPECT_LE(worst, 1e-9);
  EXPECT_NEAR(r.time[r.time.size() - 1], 2.0, 1e-15);
  // rolling constraints do no work: E(t) - E(0) = 0 to integration accuracy (rk4, h = 1e-3)
  const double kinetic = r.kinetic.maxCoeff();
  std::printf("ring_disc steady: energy balance error %.3g J (kinetic energy up to %.3g J)\n",
              energy_balance_error(r), kinetic);
  EXPECT_LE(energy_balance_error(r), 1e-9 * kinetic);
}

// Example 4.7: started theta_bar + delta from the steady angle, theta oscillates with the period
// 2 pi / omega_bar of the linearized model, omega_bar = 2.632965 rad/s (issue 16). The period is
// measured between two downward crossings of theta_bar (linear interpolation between samples,
// 1.1e-3 s apart: near a crossing theta - theta_bar is nearly linear, the interpolation error is
// O((omega dt)^3) ~ 3e-8 of a period at most). The nonlinear period differs from the linearized
// one by O(delta^2) = 1e-6 relative, the rk4 phase error by O((omega h)^4) ~ 1e-12: tolerance 1e-6.
TEST(RollingScene, RingDiscSmallOscillationPeriodOfExample47) {
  const double w = omega_bar();
  EXPECT_NEAR(w, 2.632965, 5e-7);
  const double period = 2 * std::numbers::pi / w;
  const double delta = 1e-3;
  const SceneRun run =
      run_scene("ring_disc", {{"theta0", "theta_bar + 0.001"}}, [](ForwardOptions& o) {
        o.t1 = o.t0 + 2.2 * 2 * std::numbers::pi / 2.632965;
        o.samples = 2001;
        o.step = 5e-4;
      });
  const Model& m = run.model;
  const Trajectory& r = run.r;
  ASSERT_NEAR(theta_of(m, r, 0) - theta_bar, delta, 1e-12);
  std::vector<double> crossings;
  double peak = 0;
  for (int i = 1; i < r.time.size(); ++i) {
    const double a = theta_of(m, r, i - 1) - theta_bar, b = theta_of(m, r, i) - theta_bar;
    peak = std::max(peak, std::abs(b));
    if (a > 0 && b <= 0)
      crossings.push_back(r.time[i - 1] + (r.time[i] - r.time[i - 1]) * a / (a - b));
  }
  ASSERT_GE(crossings.size(), 2u);
  const double measured = crossings[1] - crossings[0];
  std::printf(
      "ring_disc oscillation: period %.9f s measured, 2 pi / omega_bar = %.9f s, "
      "relative difference %.3g, amplitude %.3g rad\n",
      measured, period, measured / period - 1, peak);
  EXPECT_NEAR(measured / period, 1.0, 1e-6);
  // an oscillation about the steady angle: the amplitude stays delta (energy is conserved)
  EXPECT_NEAR(peak, delta, 1e-5);
  EXPECT_LE(energy_balance_error(r), 1e-9 * r.kinetic.maxCoeff());
}

// The same mechanism written in C++ with the coords/rates form of VelocityConstraintDef (as in
// tests/forward/ring_disc_test.cpp) gives the scene's run to round-off: the labels form of the
// scene (sorted by build_model) compiles to the same constraint.
TEST(RollingScene, RingDiscSceneMatchesCoordsRatesFormInCpp) {
  const double theta0 = theta_bar + 0.2, m2 = m1 * 8.0 / 67.0;
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
                                         .args = {"disc.C.x", "ring.C.x", "disc.C.y", "ring.C.y"},
                                         .psi = [](std::span<const Jet> x, Jet) {
                                           const Jet dx = x[0] - x[1], dy = x[2] - x[3];
                                           return sqrt(dx * dx + dy * dy) - (r1 - r2);
                                         }});
  s.add_constraint(VelocityConstraintDef{
      .name = "ring_rolls",
      .coords = {},
      .rates = {"ring.C.vx", "ring.w"},
      .g = [](std::span<const Jet>, std::span<const Jet> v, Jet) { return v[0] + r1 * v[1]; }});
  s.add_constraint(VelocityConstraintDef{
      .name = "disc_rolls",
      .coords = {"ring.C.x", "ring.C.y", "disc.C.x", "disc.C.y"},
      .rates = {"ring.C.vx", "ring.C.vy", "disc.C.vx", "disc.C.vy", "ring.w", "disc.w"},
      .g = [](std::span<const Jet> x, std::span<const Jet> v, Jet) {
        const Jet dx = x[2] - x[0], dy = x[3] - x[1];
        const Jet l = sqrt(dx * dx + dy * dy);
        return (v[0] - v[2]) * (-dy / l) + (v[1] - v[3]) * (dx / l) + r1 * v[4] - r2 * v[5];
      }});
  s.set_gravity({g * std::sin(xi), -g * std::cos(xi)});
  const Model cpp = build_model(s);
  const State start =
      consistent_state(cpp, {.positions = {}, .velocities = {{"ring.C.vx", 0.0}, {"disc.w", 0.0}}});
  ForwardOptions o{.t0 = 0, .t1 = 1, .samples = 11, .integrator = Integrator::rk4, .step = 1e-3};
  const Trajectory b = forward_dynamics(cpp, start, o);

  const SceneRun run =
      run_scene("ring_disc", {{"theta0", "theta_bar + 0.2"}}, [](ForwardOptions& f) {
        f.t1 = 1;
        f.samples = 11;
        // the C++ run's method (the scene asks for an accuracy: the method chosen may differ)
        f.accuracy = 0;
        f.integrator = Integrator::rk4;
        f.step = 1e-3;
      });
  const Trajectory& a = run.r;
  ASSERT_EQ(run.model.coordinate_labels, cpp.coordinate_labels);
  ASSERT_EQ(run.model.rate_labels, cpp.rate_labels);
  EXPECT_LE((a.q0 - b.q0).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LE((a.q1 - b.q1).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LE((a.a1 - b.a1).cwiseAbs().maxCoeff(), 1e-11);
  // and theta moves (this is not the steady solution)
  EXPECT_GT(std::abs(theta_of(run.model, a, 10) - theta_of(run.model, a, 0)), 1e-2);
}

// mechanisms/rolling_disc.yaml: thrown uphill at v0 = -r w0 along e = (cos a, -sin a), the centre
// moves by s(t) = v0 t + A t^2 / 2 along e, A = g sin(alpha) / (1 + I / (m r^2)) = 2/3 g
// sin(alpha), stays at distance r from the surface, and rolls: e . v + r w = 0.
TEST(RollingScene, RollingDiscMatchesItsClosedForm) {
  const SceneRun run = run_scene("rolling_disc");
  const Model& m = run.model;
  const Trajectory& r = run.r;
  EXPECT_EQ(m.dof, 1);
  EXPECT_FALSE(m.holonomic);
  const double gr = 9.81, alpha = std::numbers::pi / 6, rad = 0.2, w0 = 5;
  const double A = gr * std::sin(alpha) / (1 + 0.5), v0 = -rad * w0;
  const Vec2 e(std::cos(alpha), -std::sin(alpha)), n(std::sin(alpha), std::cos(alpha));
  const int x = m.coordinate("disc.C.x"), y = m.coordinate("disc.C.y");
  const int vx = r.rate_column("disc.C.vx"), vy = r.rate_column("disc.C.vy"),
            w = r.rate_column("disc.w");
  const Vec2 c0(r.q0(0, x), r.q0(0, y));
  double pos = 0, vel = 0, acc = 0, roll = 0;
  for (int i = 0; i < r.time.size(); ++i) {
    const double t = r.time[i];
    const Vec2 c(r.q0(i, x), r.q0(i, y)), v(r.q1(i, vx), r.q1(i, vy)), a(r.a1(i, vx), r.a1(i, vy));
    pos = std::max(
        {pos, std::abs(e.dot(c - c0) - (v0 * t + A * t * t / 2)), std::abs(n.dot(c) - rad)});
    vel = std::max(vel, std::abs(e.dot(v) - (v0 + A * t)));
    acc = std::max({acc, std::abs(e.dot(a) - A), std::abs(n.dot(a))});
    roll = std::max(roll, std::abs(e.dot(v) + rad * r.q1(i, w)));
  }
  std::printf(
      "rolling_disc: max error position %.3g m, velocity %.3g m/s, acceleration %.3g "
      "m/s^2, rolling %.3g m/s; energy balance %.3g J\n",
      pos, vel, acc, roll, energy_balance_error(r));
  EXPECT_LE(acc, 1e-12);   // the accelerations at each state: exact, whatever the integration
  EXPECT_LE(roll, 1e-12);  // the velocity constraint holds (projected)
  EXPECT_LE(vel, 1e-8);    // cvode_bdf, rtol 1e-10, atol 1e-12: integration error
  EXPECT_LE(pos, 1e-8);
  // it went uphill and came back: the velocity along e changed sign
  EXPECT_LT(r.q1(0, vx), 0);
  EXPECT_GT(r.q1(r.time.size() - 1, vx), 0);
  EXPECT_LE(energy_balance_error(r), 1e-7);
}

// tests/data/rolling_axle.yaml: inverse dynamics of a model with a velocity-level constraint whose
// positions the prescribed coordinate fixes: the axle force against its closed form
// F = (m_axle + m + I / r^2) q'' - (m_axle + m) g sin(alpha), and the rolling rate w = -q' / r.
TEST(RollingScene, RollingAxleInverseMatchesItsClosedForm) {
  const Scene scene = load_scene(std::string(MO2D_TEST_DATA_DIR) + "/rolling_axle.yaml");
  const Model m = build_scene_model(scene);
  EXPECT_EQ(m.dof, 1);
  EXPECT_FALSE(m.holonomic);
  const InverseOptions o = inverse_options(scene);
  check_scene_options(scene, m, o);
  const Trajectory r = inverse_dynamics(m, scene.motion, o);
  const double gr = 9.81, alpha = std::numbers::pi / 6, rad = 0.2, md = 2.0, ma = 0.5;
  const double inertia = md * rad * rad / 2;
  double force = 0, rate = 0;
  for (int i = 0; i < r.time.size(); ++i) {
    const double t = r.time[i], q1 = 0.6 * std::cos(2 * t), q2 = -1.2 * std::sin(2 * t);
    const double f = (ma + md + inertia / (rad * rad)) * q2 - (ma + md) * gr * std::sin(alpha);
    force = std::max(force, std::abs(r.efforts(i, 0) - f));
    rate = std::max(rate, std::abs(r.q1(i, r.rate_column("disc.w")) + q1 / rad));
  }
  std::printf("rolling_axle inverse: max |F - closed form| %.3g N, |w + q'/r| %.3g rad/s\n", force,
              rate);
  EXPECT_LE(force, 1e-12 * 20);
  EXPECT_LE(rate, 1e-12);
}

}  // namespace
}  // namespace mo2d
