// The Jacobian of the accelerations (mo2d/jacobian.hpp) against central differences of the
// evaluation, on every shipped scene whose elements it differentiates exactly (springs linear,
// unilateral and by law, torsional springs, laws of points, lengths and angles, effort laws and
// controllers, prismatic joints, pin-in-slots, user position and velocity constraints), at a
// state reached by a short forward run (velocities and multipliers not zero), and on systems
// built here for the elements no scene has.
#include "mo2d/jacobian.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "metamorphic/generator.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"

namespace mo2d {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// Central differences extrapolated (Richardson: (4 D(h/2) - D(h)) / 3, error O(h^4)) with a step
// h = 1e-4 of the variable's scale (the model's length for positions): an independent reference
// accurate to ~1e-10, whatever the mechanism's size.
void central(ForwardData& d, double t, const VectorXd& q0, const VectorXd& q1, MatrixXd& D0,
             MatrixXd& D1) {
  const Model& m = d.m;
  D0.resize(m.n1, m.n0);
  D1.resize(m.n1, m.n1);
  VectorXd x0 = q0, x1 = q1;
  auto diff = [&](double& x, double h) {
    const double at = x;
    x = at + h;
    d.accelerations(t, x0, x1, false);
    const VectorXd ap = d.a;
    x = at - h;
    d.accelerations(t, x0, x1, false);
    x = at;
    return VectorXd((ap - d.a) / (2 * h));
  };
  for (int k = 0; k < m.n0 + m.n1; ++k) {
    const bool pos = k < m.n0;
    double& x = pos ? x0[k] : x1[k - m.n0];
    const double h = 1e-4 * std::max(std::abs(x), pos ? m.scale : 1.0);
    const VectorXd col = (4 * diff(x, h / 2) - diff(x, h)) / 3;
    (pos ? D0.col(k) : D1.col(k - m.n0)) = col;
  }
}

// max |J - D| / (max |D| + 1) over the columns (each column on its own scale).
double mismatch(const MatrixXd& J, const MatrixXd& D) {
  double e = 0;
  for (Eigen::Index k = 0; k < J.cols(); ++k)
    e = std::max(e, (J.col(k) - D.col(k)).lpNorm<Eigen::Infinity>() /
                        (D.col(k).lpNorm<Eigen::Infinity>() + 1));
  return e;
}

struct Compared {
  double e0, e1;
  std::string approximate;
};
Compared compare_at(const Model& m, ForwardOptions o, const VectorXd& q0, const VectorXd& q1,
                    double t) {
  o.formulation = Formulation::lagrange;  // the same accelerations on both sides, to rounding
  ForwardData d(m, o);
  AccelerationJacobian J;
  acceleration_jacobian(d, t, q0, q1, J);
  MatrixXd D0, D1;
  central(d, t, q0, q1, D0, D1);
  return {mismatch(J.da_dq0, D0), mismatch(J.da_dq1, D1), J.approximate};
}

class SceneJacobian : public ::testing::TestWithParam<const char*> {};

TEST_P(SceneJacobian, EqualsCentralDifferencesAfterAShortRun) {
  const Scene scene = load_scene(std::string(MO2D_MECHANISMS_DIR) + "/" + GetParam() + ".yaml");
  const Model m = build_scene_model(scene);
  ForwardOptions o = forward_options(scene, m);
  Trajectory r;
  if (scene.motion.empty()) {  // a forward scene: a short run from its initial state
    o.t1 = o.t0 + std::min(0.05, o.t1 - o.t0);
    o.samples = 2;
    r = forward_dynamics(m, initial_state(scene, m), o);
  } else {  // an inverse scene: a sample of its prescribed motion (no efforts)
    InverseOptions io = inverse_options(scene);
    io.samples = 8;  // t = 3/7 of the run: not on a table knot (the third derivative jumps there)
    r = inverse_dynamics(m, scene.motion, io);
    o.efforts.clear();
  }
  const Eigen::Index n = r.time.size() / 2;
  const VectorXd q0 = r.q0.row(n).transpose(), q1 = r.q1.row(n).transpose();
  ASSERT_GT(q1.lpNorm<Eigen::Infinity>(), 0) << "the state must move";
  const Compared c = compare_at(m, o, q0, q1, r.time[n]);
  std::printf("%s: n0 %d n1 %d m1 %d, mismatch %.2e (q0) %.2e (q1)%s%s\n", GetParam(), m.n0, m.n1,
              m.m1, c.e0, c.e1, c.approximate.empty() ? "" : ", ", c.approximate.c_str());
  EXPECT_LT(c.e0, 1e-6);
  EXPECT_LT(c.e1, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Shipped, SceneJacobian,
                         ::testing::Values("pendulum", "fourbar", "double_fourbar", "slider_crank",
                                           "whitworth", "rrr3", "door", "crank_press",
                                           "slider_crank_control", "cam_table", "ring_disc",
                                           "rolling_disc", "watt_sixbar_lengths", "engine",
                                           "chain_drive"));

// A disc rolling inside a fixed ring (radius R, centre O), off its rest: the rolling constraint's
// coefficients depend on the position (t = z x C / |C|), so its mixed derivatives g_xv, g_xx
// enter; the constraint depends on time too (a ring turning at a given rate).
TEST(UserConstraintJacobian, DiscRollingInATurningRingEqualsCentralDifferences) {
  constexpr double R = 1.0, r = 0.25;
  System s("disc_in_ring");
  s.add_ground_node("O", Vec2(0, 0));  // (the ring's centre)
  s.add_body({.name = "disc",
              .nodes = {{"C", (R - r) * Vec2(std::sin(0.6), -std::cos(0.6))}},
              .mass = 2,
              .inertia = 0.06});
  s.add_constraint(PositionConstraintDef{
      .name = "on_ring", .args = {"disc.C.x", "disc.C.y"}, .psi = [](std::span<const Jet> x, Jet) {
        return sqrt(x[0] * x[0] + x[1] * x[1]) - (R - r);
      }});
  // contact point velocity zero against the ring's surface turning at 0.3 + 0.2 t rad/s:
  // v . t + r w = R (0.3 + 0.2 t) ... written as g(x, v, t) = v . t + r w - R (0.3 + 0.2 t)
  s.add_constraint(VelocityConstraintDef{
      .name = "rolls",
      .coords = {"disc.C.x", "disc.C.y"},
      .rates = {"disc.C.vx", "disc.C.vy", "disc.w"},
      .g = [](std::span<const Jet> x, std::span<const Jet> v, Jet t) {
        const Jet l = sqrt(x[0] * x[0] + x[1] * x[1]);
        return (-x[1] * v[0] + x[0] * v[1]) / l + r * v[2] - R * (0.3 + 0.2 * t);
      }});
  s.set_gravity({0, -9.81});
  const Model m = build_model(s);
  ForwardOptions o{.t1 = 0.2, .samples = 2};
  const Trajectory tr = forward_dynamics(
      m, consistent_state(m, {.positions = {}, .velocities = {{"disc.w", 3.0}}}), o);
  const VectorXd q0 = tr.q0.row(1).transpose(), q1 = tr.q1.row(1).transpose();
  const Compared c = compare_at(m, o, q0, q1, tr.time[1]);
  std::printf("disc in a turning ring: mismatch %.2e (q0) %.2e (q1)\n", c.e0, c.e1);
  EXPECT_LT(c.e0, 1e-6);
  EXPECT_LT(c.e1, 1e-6);
}

// Random mechanisms (tests/metamorphic/generator.hpp: four-bars, chains, legs in subsystems,
// prismatic joints, pin-in-slots, extra coordinates, linear springs and dampers, torsional
// springs, forces and torques) at the middle sample of their prescribed motion.
TEST(GeneratedJacobian, EqualsCentralDifferencesOnFortyMechanisms) {
  meta::GeneratorStats stats;
  double worst0 = 0, worst1 = 0;
  int springs = 0;
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    const meta::Mechanism mech = meta::generate(seed, stats);
    const Model m = build_model(meta::to_system(mech));
    InverseOptions io;
    io.t1 = mech.t1;
    io.samples = 5;
    const Trajectory r = inverse_dynamics(m, meta::prescribed(mech), io);
    const VectorXd q0 = r.q0.row(2).transpose(), q1 = r.q1.row(2).transpose();
    const Compared c = compare_at(m, ForwardOptions{}, q0, q1, r.time[2]);
    EXPECT_LT(c.e0, 1e-6) << "seed " << seed << " (" << mech.family << ")";
    EXPECT_LT(c.e1, 1e-6) << "seed " << seed << " (" << mech.family << ")";
    EXPECT_TRUE(c.approximate.empty()) << c.approximate;
    worst0 = std::max(worst0, c.e0);
    worst1 = std::max(worst1, c.e1);
    springs += mech.has_springs() ? 1 : 0;
  }
  std::printf("40 generated mechanisms (%d with springs): worst mismatch %.2e (q0) %.2e (q1)\n",
              springs, worst0, worst1);
}

}  // namespace
}  // namespace mo2d
