// Validation of inverse dynamics against things independent of the solver: a power balance
// with its own energy function, a second formulation (Lagrange multipliers on the unreduced
// model), closed forms, and flattened vs recursive subsystem assembly.
#include <gtest/gtest.h>

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
double worst_power_balance(const System& s, const Model& m, const InverseResult& r,
                           const std::vector<Drive>& drives) {
  const auto par = mo2d::test::params_of(s);
  double peak = 0, worst = 0;
  std::vector<double> pin(r.time.size()), de(r.time.size());
  for (int i = 0; i < r.time.size(); ++i) {
    double p = 0;
    for (const auto& d : drives)
      p += r.efforts(i, r.input(d.input)) * body_motion(m, r, i, body_index(m, d.body)).w;
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
  const InverseResult r = inverse_dynamics(m, ex.motion, ex.run);
  const double err = worst_power_balance(ex.system, m, r, {{"crank_pivot.torque", "crank"}});
  RecordProperty("worst_relative_power_error", std::to_string(err));
  EXPECT_LE(err, 1e-6);
}

TEST(Validation, Rrr3PowerBalance) {
  auto ex = mechanisms::rrr3();
  const Model m = build_model(ex.system);
  const InverseResult r = inverse_dynamics(m, ex.motion, ex.run);
  const double err = worst_power_balance(ex.system, m, r,
                                         {{"leg1.pivot.torque", "leg1.proximal"},
                                          {"leg2.pivot.torque", "leg2.proximal"},
                                          {"leg3.pivot.torque", "leg3.proximal"}});
  EXPECT_LE(err, 1e-6);
}

TEST(Validation, FourbarUnderGravityPowerBalance) {
  auto ex = mechanisms::fourbar();
  const Model m = build_model(ex.system);
  const InverseResult r = inverse_dynamics(m, ex.motion, ex.run);
  EXPECT_LE(worst_power_balance(ex.system, m, r, {{"crank_pivot.torque", "crank"}}), 1e-6);
}

TEST(Validation, SliderCrankPowerBalance) {
  auto ex = mechanisms::slider_crank();
  const Model m = build_model(ex.system);
  const InverseResult r = inverse_dynamics(m, ex.motion, ex.run);
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
    const InverseResult r = inverse_dynamics(m, ex.motion, ex.run);
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
  EXPECT_GT(run([&](System& s) { with_body(s, "lever", [](BodyDef& b) { b.inertia *= 1.05; }); }), 1e-4);
  EXPECT_GT(run([&](System& s) { with_body(s, "rod", [](BodyDef& b) { b.mass *= 1.05; }); }), 1e-4);
  EXPECT_GT(run([&](System& s) {
              with_body(s, "lever", [](BodyDef& b) { b.com = CenterOfMass::between("O", "B", 0.6); });
            }),
            1e-4);
}

namespace {
void expect_lagrange_agrees(mechanisms::Example ex, double tol) {
  const Model flat = build_model(ex.system);
  const Model none = build_model(ex.system, {.reduction = Reduction::none});
  ASSERT_EQ(none.dof, flat.dof);
  const InverseResult a = inverse_dynamics(flat, ex.motion, ex.run);
  const InverseResult b = inverse_dynamics_lagrange(none, ex.motion, ex.run);
  ASSERT_EQ(a.reaction_labels, b.reaction_labels);
  ASSERT_EQ(a.input_labels, b.input_labels);
  EXPECT_LE(max_relative_difference(a.efforts, b.efforts), tol);
  EXPECT_LE(max_relative_difference(a.reactions, b.reactions), tol);
}
}  // namespace

TEST(Validation, WhitworthLagrangeAgrees) { expect_lagrange_agrees(mechanisms::whitworth(), 1e-9); }
TEST(Validation, Rrr3LagrangeAgrees) { expect_lagrange_agrees(mechanisms::rrr3(), 1e-9); }
TEST(Validation, FourbarLagrangeAgrees) { expect_lagrange_agrees(mechanisms::fourbar(), 1e-9); }
TEST(Validation, SliderCrankLagrangeAgrees) { expect_lagrange_agrees(mechanisms::slider_crank(), 1e-9); }
TEST(Validation, PendulumLagrangeAgrees) { expect_lagrange_agrees(mechanisms::pendulum(), 1e-9); }

TEST(Validation, PendulumClosedForm) {
  for (double theta0 : {0.0, 0.7, -2.0}) {
    mechanisms::PendulumParams p;
    p.L = 0.8;
    p.m = 1.3;
    p.theta0 = theta0;
    auto ex = mechanisms::pendulum(p);
    const Model m = build_model(ex.system);
    const InverseResult r = inverse_dynamics(m, ex.motion, ex.run);
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
  const InverseResult r = inverse_dynamics(m, ex.motion, ex.run);
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
  const InverseResult a = inverse_dynamics(flat, ex.motion, o);
  o.complement = ComplementMethod::recursive;
  const InverseResult b = inverse_dynamics(tree, ex.motion, o);
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
