// Validation of inverse dynamics against things independent of the solver: a power balance
// with its own energy function, a second formulation (Lagrange multipliers on the unreduced
// model), closed forms, and flattened vs recursive subsystem assembly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"
#include "test_support.hpp"

using namespace mo2d;
using mo2d::test::body_index;
using mo2d::test::body_motion;
using mo2d::test::energy_rate;
using mo2d::test::max_relative_difference;

namespace {

// Input power of the three RRR pivots or the Whitworth crank, from body rotation rates that the
// test computes itself from node velocities.
struct Drive {
  std::string input, body;  // torque input and the body it turns relative to the ground
};

// Input power against the rate of kinetic + potential energy, with the inertial parameters and
// gravity of the definitions `s` (independent of how build_model compiled them).
double worst_power_balance(const System& s, const Model& m, const Trajectory& r,
                           const std::vector<Drive>& drives) {
  const auto par = mo2d::test::params_of(s);
  double peak = 0, worst = 0;
  std::vector<double> pin(r.time.size()), de(r.time.size());
  for (int i = 0; i < r.time.size(); ++i) {
    double p = 0;
    for (const auto& d : drives)
      p += r.efforts(i, r.effort(d.input)) * body_motion(m, r, i, body_index(m, d.body)).w;
    pin[i] = p;
    de[i] = energy_rate(m, r, i, par, s.gravity());
    peak = std::max(peak, std::abs(p));
  }
  for (size_t i = 0; i < pin.size(); ++i) worst = std::max(worst, std::abs(pin[i] - de[i]) / peak);
  return worst;
}

}  // namespace

TEST(Validation, WhitworthPowerBalance) {
  auto ex = mechanisms::whitworth();
  const Model m = build_model(ex.system);
  const Trajectory r = inverse_dynamics(m, ex.motion, ex.run);
  const double err = worst_power_balance(ex.system, m, r, {{"crank_pivot.torque", "crank"}});
  RecordProperty("worst_relative_power_error", std::to_string(err));
  EXPECT_LE(err, 1e-6);
}

TEST(Validation, Rrr3PowerBalance) {
  auto ex = mechanisms::rrr3();
  const Model m = build_model(ex.system);
  const Trajectory r = inverse_dynamics(m, ex.motion, ex.run);
  const double err = worst_power_balance(ex.system, m, r,
                                         {{"leg1.pivot.torque", "leg1.proximal"},
                                          {"leg2.pivot.torque", "leg2.proximal"},
                                          {"leg3.pivot.torque", "leg3.proximal"}});
  EXPECT_LE(err, 1e-6);
}

TEST(Validation, FourbarUnderGravityPowerBalance) {
  auto ex = mechanisms::fourbar();
  const Model m = build_model(ex.system);
  const Trajectory r = inverse_dynamics(m, ex.motion, ex.run);
  EXPECT_LE(worst_power_balance(ex.system, m, r, {{"crank_pivot.torque", "crank"}}), 1e-6);
}

TEST(Validation, SliderCrankPowerBalance) {
  auto ex = mechanisms::slider_crank();
  const Model m = build_model(ex.system);
  const Trajectory r = inverse_dynamics(m, ex.motion, ex.run);
  EXPECT_LE(worst_power_balance(ex.system, m, r, {{"crank_pivot.torque", "crank"}}), 1e-6);
}

// The power balance has teeth: the same check with the solver's model perturbed must fail.
TEST(Validation, PowerBalanceDetectsWrongModel) {
  auto base = mechanisms::whitworth();
  const Model truth = build_model(base.system);
  auto run = [&](auto&& mutate) {
    auto ex = mechanisms::whitworth();
    mutate(ex.system);
    const Model m = build_model(ex.system);
    const Trajectory r = inverse_dynamics(m, ex.motion, ex.run);
    // energy from the true parameters, efforts from the mutated model
    return worst_power_balance(base.system, truth, r, {{"crank_pivot.torque", "crank"}});
  };
  // (reach into the definition: rebuild with a changed lever inertia / mass / centre of mass)
  auto with_body = [](System& s, const std::string& name, auto&& change) {
    System out(s.name());
    for (const auto& g : s.ground()) out.add_ground_node(g.name, g.position);
    for (auto b : s.bodies()) {
      if (b.name == name) change(b);
      out.add_body(b);
    }
    for (const auto& j : s.revolutes()) out.add_revolute(j);
    for (const auto& j : s.prismatics()) out.add_prismatic(j);
    for (const auto& j : s.slots()) out.add_pin_in_slot(j);
    for (const auto& c : s.coordinates()) out.add_coordinate(c);
    s = out;
  };
  EXPECT_GT(run([&](System& s) { with_body(s, "lever", [](BodyDef& b) { b.inertia *= 1.05; }); }),
            1e-4);
  EXPECT_GT(run([&](System& s) { with_body(s, "rod", [](BodyDef& b) { b.mass *= 1.05; }); }), 1e-4);
  EXPECT_GT(run([&](System& s) {
              with_body(s, "lever",
                        [](BodyDef& b) { b.com = CenterOfMass::between("O", "B", 0.6); });
            }),
            1e-4);
}

namespace {
void expect_lagrange_agrees(mechanisms::Example ex, double tol) {
  const Model flat = build_model(ex.system);
  const Model none = build_model(ex.system, {.reduction = Reduction::none});
  ASSERT_EQ(none.dof, flat.dof);
  const Trajectory a = inverse_dynamics(flat, ex.motion, ex.run);
  const Trajectory b = inverse_dynamics_lagrange(none, ex.motion, ex.run);
  ASSERT_EQ(a.reaction_labels, b.reaction_labels);
  ASSERT_EQ(a.input_labels, b.input_labels);
  EXPECT_LE(max_relative_difference(a.efforts, b.efforts), tol);
  // a reaction that vanishes identically (slide.Fx of a frictionless horizontal slider) is
  // compared on the scale of the mechanism's reactions, not on 1e-12 N: both formulations give it
  // at rounding level (~1e-16 of the largest reaction, 3e-16 N), which tol x 1e-12 N (1e-21 N)
  // cannot resolve; with the floor 1e-6 x the largest, such a column must agree to 1e-15 of it
  const double floor = std::max(1e-300, 1e-6 * b.reactions.cwiseAbs().maxCoeff());
  EXPECT_LE(max_relative_difference(a.reactions, b.reactions, floor), tol);
}
}  // namespace

TEST(Validation, WhitworthLagrangeAgrees) {
  expect_lagrange_agrees(mechanisms::whitworth(), 1e-9);
}
TEST(Validation, Rrr3LagrangeAgrees) {
  expect_lagrange_agrees(mechanisms::rrr3(), 1e-9);
}
TEST(Validation, FourbarLagrangeAgrees) {
  expect_lagrange_agrees(mechanisms::fourbar(), 1e-9);
}
TEST(Validation, SliderCrankLagrangeAgrees) {
  expect_lagrange_agrees(mechanisms::slider_crank(), 1e-9);
}
TEST(Validation, PendulumLagrangeAgrees) {
  expect_lagrange_agrees(mechanisms::pendulum(), 1e-9);
}

TEST(Validation, PendulumClosedForm) {
  for (double theta0 : {0.0, 0.7, -2.0}) {
    mechanisms::PendulumParams p;
    p.L = 0.8;
    p.m = 1.3;
    p.theta0 = theta0;
    auto ex = mechanisms::pendulum(p);
    const Model m = build_model(ex.system);
    const Trajectory r = inverse_dynamics(m, ex.motion, ex.run);
    double worst_tau = 0, worst_f = 0;
    for (int i = 0; i < r.time.size(); ++i) {
      const Jet th = ex.motion[0].motion(Jet(r.time[i], 1, 0));
      const double s = std::sin(th.v), c = std::cos(th.v);
      // tau = m L^2 theta'' + m g L cos(theta); F = m a_P - m g (force of the ground on the link)
      const double tau = p.m * p.L * p.L * th.dd + p.m * p.g * p.L * c;
      const double ax = p.L * (-th.dd * s - th.d * th.d * c);
      const double ay = p.L * (th.dd * c - th.d * th.d * s);
      const double fx = p.m * ax, fy = p.m * ay + p.m * p.g;
      worst_tau = std::max(worst_tau, std::abs(r.efforts(i, 0) - tau));
      worst_f = std::max(worst_f, std::abs(r.reactions(i, r.reaction("pivot.Fx")) - fx));
      worst_f = std::max(worst_f, std::abs(r.reactions(i, r.reaction("pivot.Fy")) - fy));
    }
    EXPECT_LE(worst_tau, 1e-9) << "theta0 = " << theta0;
    EXPECT_LE(worst_f, 1e-9) << "theta0 = " << theta0;
  }
}

TEST(Validation, SliderCrankMasslessRodClosedForm) {
  mechanisms::SliderCrankParams p;
  p.m_crank = 0;
  p.m_rod = 0;
  p.m_slider = 2.5;
  p.gravity = 9.81;
  auto ex = mechanisms::slider_crank(p);
  const Model m = build_model(ex.system);
  const Trajectory r = inverse_dynamics(m, ex.motion, ex.run);
  double worst_tau = 0, worst_n = 0, peak = 0;
  for (int i = 0; i < r.time.size(); ++i) {
    const Jet th = ex.motion[0].motion(Jet(r.time[i], 1, 0));
    // x_B(theta) = r cos(theta) + sqrt(L^2 - (r sin(theta) - e)^2), differentiated by Jet
    const Jet h = p.r * sin(th) - p.e;
    const Jet xb = p.r * cos(th) + sqrt(p.L * p.L - h * h);
    // virtual work: tau dtheta = m x_B'' dx_B; rod is a two-force member along (A - B)
    const double tau = p.m_slider * xb.dd * (xb.d / th.d);
    const Eigen::Vector2d A(p.r * std::cos(th.v), p.r * std::sin(th.v)), B(xb.v, p.e);
    const Eigen::Vector2d u = (A - B) / p.L;
    const double T = p.m_slider * xb.dd / u.x();
    const double N = p.m_slider * p.gravity - T * u.y();
    worst_tau = std::max(worst_tau, std::abs(r.efforts(i, 0) - tau));
    worst_n = std::max(worst_n, std::abs(r.reactions(i, r.reaction("rail.Fy")) - N));
    peak = std::max(peak, std::abs(tau));
  }
  EXPECT_LE(worst_tau / peak, 1e-9);
  EXPECT_LE(worst_n, 1e-8);
}

TEST(Validation, Rrr3FlattenedAndRecursiveAgree) {
  auto ex = mechanisms::rrr3();
  const Model flat = build_model(ex.system, {.reduction = Reduction::flat});
  const Model tree = build_model(ex.system, {.reduction = Reduction::subsystems});
  EXPECT_EQ(flat.dof, 3);
  EXPECT_EQ(tree.dof, 3);
  EXPECT_LT(flat.n1, tree.n1);  // the attach joints are rows in the tree model
  InverseOptions o = ex.run;
  const Trajectory a = inverse_dynamics(flat, ex.motion, o);
  o.complement = ComplementMethod::recursive;
  const Trajectory b = inverse_dynamics(tree, ex.motion, o);
  ASSERT_EQ(a.reaction_labels, b.reaction_labels);
  EXPECT_LE(max_relative_difference(a.efforts, b.efforts), 1e-11);
  EXPECT_LE(max_relative_difference(a.reactions, b.reactions), 1e-11);
  // same platform motion
  EXPECT_LE((a.q0.col(a.column("platform.P1.x")) - b.q0.col(b.column("platform.P1.x")))
                .cwiseAbs()
                .maxCoeff(),
            1e-12);
}

TEST(Validation, RecursiveComplementSpansNullSpace) {
  auto ex = mechanisms::rrr3();
  const Model tree = build_model(ex.system, {.reduction = Reduction::subsystems});
  MatrixXd A(tree.m1, tree.n1);
  VectorXd b(tree.m1);
  velocity_jacobian(tree, tree.q0, 0, A, b);
  const MatrixXd S = recursive_complement(tree, A);
  EXPECT_EQ(S.cols(), 3);
  EXPECT_LE((A * S).cwiseAbs().maxCoeff(), 1e-12);
  Eigen::FullPivLU<MatrixXd> lu(S);
  EXPECT_EQ(lu.rank(), 3);
}

// Velocities and accelerations against 5-point central differences of the positions solved at
// neighbouring instants, and the input power against the difference of the energy. The power
// balance above uses the solver's own accelerations, so it cannot see a wrong acceleration term;
// these can. Stencil h = 1e-3 s: for motions of angular frequency w and amplitude a the truncation
// is about (w h)^4 w a / 30 for the first derivative (< 1e-9 at w = 4 pi rad/s, a = 0.1 m), and a
// position error d (Newton, ~1e-14 m) enters the second derivative as 64 d / (12 h^2) (~1e-7).
namespace {
struct Stencil {
  Trajectory r;
  double h;
  double d1(const Eigen::VectorXd& f) const {
    return (-f[4] + 8 * f[3] - 8 * f[1] + f[0]) / (12 * h);
  }
  double d2(const Eigen::VectorXd& f) const {
    return (-f[4] + 16 * f[3] - 30 * f[2] + 16 * f[1] - f[0]) / (12 * h * h);
  }
};

void expect_kinematics_match_differences(const mechanisms::Example& ex,
                                         const std::vector<Drive>& drives, int instants = 7) {
  const Model m = build_model(ex.system);
  const auto par = mo2d::test::params_of(ex.system);
  const double h = 1e-3;
  double worst_v = 0, worst_a = 0, worst_w = 0, worst_p = 0, vscale = 0, ascale = 0, pscale = 0;
  for (int k = 1; k <= instants; ++k) {
    const double t = ex.run.t0 + 2 * h + (ex.run.t1 - ex.run.t0 - 4 * h) * (k - 0.37) / instants;
    InverseOptions o = ex.run;
    o.t0 = t - 2 * h;
    o.t1 = t + 2 * h;
    o.samples = 5;
    const Stencil s{inverse_dynamics(m, ex.motion, o), h};
    for (int j = 0; j < m.n0; ++j) {
      const Eigen::VectorXd q = s.r.q0.col(j);
      worst_v = std::max(worst_v, std::abs(s.d1(q) - s.r.q1(2, j)));
      worst_a = std::max(worst_a, std::abs(s.d2(q) - s.r.a1(2, j)));
      vscale = std::max(vscale, std::abs(s.r.q1(2, j)));
      ascale = std::max(ascale, std::abs(s.r.a1(2, j)));
    }
    for (size_t b = 0; b < m.bodies.size(); ++b) {  // rotation rate vs the angle of nodes 0-1
      const Body& body = m.bodies[b];
      if (body.nodes.size() < 2 || body.omega.var < 0) continue;
      Eigen::VectorXd th(5);
      for (int i = 0; i < 5; ++i) {
        const auto n0 = mo2d::test::node_state(m, s.r, i, static_cast<int>(b), 0);
        const auto n1 = mo2d::test::node_state(m, s.r, i, static_cast<int>(b), 1);
        th[i] = std::atan2(n1.p.y() - n0.p.y(), n1.p.x() - n0.p.x());
        if (i > 0) th[i] = th[i - 1] + std::remainder(th[i] - th[i - 1], 2 * std::numbers::pi);
      }
      worst_w = std::max(worst_w, std::abs(s.d1(th) - s.r.q1(2, body.omega.var)));
      worst_w = std::max(worst_w, std::abs(s.d2(th) - s.r.a1(2, body.omega.var)) / 10);
    }
    Eigen::VectorXd e(5);
    for (int i = 0; i < 5; ++i) e[i] = mo2d::test::energy(m, s.r, i);
    double pin = 0;
    for (const auto& d : drives)
      pin += s.r.efforts(2, s.r.effort(d.input)) * body_motion(m, s.r, 2, body_index(m, d.body)).w;
    worst_p = std::max(worst_p, std::abs(s.d1(e) - pin));
    pscale = std::max(pscale, std::abs(pin));
    (void)par;
  }
  EXPECT_LE(worst_v, 1e-6 * std::max(1.0, vscale));
  EXPECT_LE(worst_a, 1e-5 * std::max(1.0, ascale));
  EXPECT_LE(worst_w, 1e-5);
  EXPECT_LE(worst_p, 1e-5 * std::max(1.0, pscale));
}
}  // namespace

TEST(Validation, WhitworthKinematicsMatchDifferences) {
  expect_kinematics_match_differences(mechanisms::whitworth(), {{"crank_pivot.torque", "crank"}});
}
TEST(Validation, Rrr3KinematicsMatchDifferences) {
  expect_kinematics_match_differences(mechanisms::rrr3(), {{"leg1.pivot.torque", "leg1.proximal"},
                                                           {"leg2.pivot.torque", "leg2.proximal"},
                                                           {"leg3.pivot.torque", "leg3.proximal"}});
}
TEST(Validation, SliderCrankKinematicsMatchDifferences) {
  expect_kinematics_match_differences(mechanisms::slider_crank(),
                                      {{"crank_pivot.torque", "crank"}});
}
TEST(Validation, FourbarKinematicsMatchDifferences) {
  expect_kinematics_match_differences(mechanisms::fourbar(), {{"crank_pivot.torque", "crank"}});
}
