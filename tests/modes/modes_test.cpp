// Equilibria, linearization and vibration modes (mo2d/modes.hpp) against closed forms: the
// pendulum and the double pendulum (small-oscillation frequencies), the ring and disc of Orsino's
// Example 4.7 (omega = sqrt(-G_{theta_dot, theta}), and its table against the mass ratio from the
// closed forms of Example 4.2 (h)), a damped spring pendulum against the decay and frequency
// fitted to a small-amplitude forward run, and G against finite differences of the accelerations
// through the chart at a moving state.
#include "mo2d/modes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "mo2d/forward_data.hpp"
#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"

using namespace mo2d;

namespace {

constexpr double pi = std::numbers::pi;

// The oscillatory modes' omega_n, ascending.
std::vector<double> frequencies(const std::vector<Mode>& modes) {
  std::vector<double> w;
  for (const Mode& md : modes)
    if (md.oscillatory) w.push_back(md.omega_n);
  return w;
}

// Two point masses on massless links hanging from O: link1 O-P (m1 at P), link2 P-Q (m2 at Q).
Model double_pendulum(double l1, double l2, double m1, double m2, double g, double th1,
                      double th2) {
  System s("double_pendulum");
  s.add_ground_node("O", {0, 0});
  const Vec2 p(l1 * std::sin(th1), -l1 * std::cos(th1));
  const Vec2 q = p + Vec2(l2 * std::sin(th2), -l2 * std::cos(th2));
  s.add_body({.name = "upper",
              .nodes = {{"O", {0, 0}}, {"P", p}},
              .mass = m1,
              .com = CenterOfMass::at_node("P")});
  s.add_body({.name = "lower",
              .nodes = {{"P", p}, {"Q", q}},
              .mass = m2,
              .com = CenterOfMass::at_node("Q")});
  s.add_revolute({.name = "shoulder", .node_a = "ground.O", .node_b = "upper.O"});
  s.add_revolute({.name = "elbow", .node_a = "upper.P", .node_b = "lower.P"});
  s.set_gravity({0, -g});
  return build_model(s);
}

// Pendulum (point mass m at L) with a torsional spring-damper at its pivot (rest at the
// horizontal, so that the equilibrium is not straight down) and a horizontal linear spring.
Model spring_pendulum(double k, double c, double th0) {
  System s("spring_pendulum");
  s.add_ground_node("O", {0, 0});
  s.add_body({.name = "link",
              .nodes = {{"O", {0, 0}}, {"P", {std::cos(th0), std::sin(th0)}}},
              .mass = 1.0,
              .com = CenterOfMass::at_node("P")});
  s.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "link.O"});
  s.add_torsional_spring(
      {.name = "hinge", .joint = "pivot", .stiffness = k, .damping = c, .rest = -th0});
  s.add_spring({.name = "side",
                .body_a = "ground",
                .point_a = {-1.5, -1},
                .body_b = "link",
                .point_b = {std::cos(th0), std::sin(th0)},
                .rest_length = 1.0,
                .stiffness = 4.0,
                .damping = 0.3});
  s.set_gravity({0, -9.81});
  return build_model(s);
}

std::string scene_path(const std::string& name) {
  return std::string(MO2D_MECHANISMS_DIR) + "/" + name + ".yaml";
}

}  // namespace

// omega = sqrt(g / L) about the lower equilibrium, found from 0.4 rad away; the stiffness in the
// angle is m g L, the reduced mass m L^2; H = 1 / (m L^2) for the pivot torque.
TEST(Modes, PendulumFrequencyStiffnessAndInput) {
  const double L = 0.8, m = 1.5, g = 9.81;
  const mechanisms::Example e =
      mechanisms::pendulum({.L = L, .m = m, .g = g, .theta0 = -pi / 2 + 0.4});
  const Model model = build_model(e.system);
  EquilibriumOptions o;
  o.linearize.coordinates = {"link.angle"};
  o.linearize.outputs = {"link.P.x", "link.w"};
  const Equilibrium eq = static_equilibrium(model, model.q0, o);
  EXPECT_NEAR(eq.state.q0[model.coordinate("link.angle")], -pi / 2, 1e-10);
  EXPECT_EQ(eq.stability, "stable");
  ASSERT_EQ(eq.stiffness.rows(), 1);
  EXPECT_NEAR(eq.stiffness(0, 0), m * g * L, 1e-6 * m * g * L);
  EXPECT_NEAR(eq.reduced_mass(0, 0), m * L * L, 1e-12);
  const auto w = frequencies(vibration_modes(eq.linear));
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NEAR(w[0], std::sqrt(g / L), 1e-7 * std::sqrt(g / L));
  ASSERT_EQ(eq.linear.H.cols(), 1);
  EXPECT_NEAR(eq.linear.H(1, 0), 1 / (m * L * L), 1e-9);
  // outputs: dx_P / d theta = -L sin(theta) = L at theta = -pi/2; link.w = the rate itself
  EXPECT_NEAR(eq.linear.C(0, 0), L, 1e-7);
  EXPECT_NEAR(eq.linear.C(1, 1), 1.0, 1e-12);
}

// Started near the top, Newton goes to the nearest branch: the inverted, unstable equilibrium,
// with the real pair +- sqrt(g / L).
TEST(Modes, InvertedPendulumIsUnstable) {
  const mechanisms::Example e = mechanisms::pendulum({.theta0 = pi / 2 + 0.3});
  const Model model = build_model(e.system);
  const Equilibrium eq = static_equilibrium(model, model.q0);
  EXPECT_NEAR(eq.state.q0[model.coordinate("link.angle")], pi / 2, 1e-9);
  EXPECT_EQ(eq.stability, "unstable");
  const auto modes = vibration_modes(eq.linear);
  ASSERT_EQ(modes.size(), 2u);
  const double s = std::sqrt(9.81);
  EXPECT_NEAR(std::abs(modes[0].eigenvalue.real()), s, 1e-6);
  EXPECT_NEAR(std::abs(modes[1].eigenvalue.real()), s, 1e-6);
  EXPECT_FALSE(modes[0].oscillatory);
}

// The double pendulum's two frequencies in closed form:
// w^2 = g / (2 m1 l1 l2) [(m1 + m2)(l1 + l2) -+ sqrt((m1 + m2)((m1 + m2)(l1 + l2)^2 - 4 m1 l1 l2))]
TEST(Modes, DoublePendulumFrequencies) {
  const double l1 = 1.0, l2 = 0.6, m1 = 2.0, m2 = 0.7, g = 9.81;
  const Model model = double_pendulum(l1, l2, m1, m2, g, 0.3, -0.2);
  const Equilibrium eq = static_equilibrium(model, model.q0);
  EXPECT_EQ(eq.stability, "stable");
  EXPECT_LT(eq.residual, 1e-9);
  const double M = m1 + m2, S = l1 + l2;
  const double root = std::sqrt(M * (M * S * S - 4 * m1 * l1 * l2));
  const double w1 = std::sqrt(g / (2 * m1 * l1 * l2) * (M * S - root));
  const double w2 = std::sqrt(g / (2 * m1 * l1 * l2) * (M * S + root));
  const auto w = frequencies(vibration_modes(eq.linear));
  ASSERT_EQ(w.size(), 2u);
  EXPECT_NEAR(w[0], w1, 1e-7 * w1);
  EXPECT_NEAR(w[1], w2, 1e-7 * w2);
  // the mode shapes reach every node: the lower mass moves most in the first mode, in phase
  const auto modes = vibration_modes(eq.linear);
  const auto shape = mode_node_shapes(model, modes[0], 0.1);
  double q = 0, p = 0;
  for (const NodeShape& n : shape) {
    if (n.label == "lower.Q") q = n.dx;
    if (n.label == "upper.P") p = n.dx;
  }
  EXPECT_NEAR(std::abs(q), 0.1, 1e-12);
  EXPECT_GT(q * p, 0);
}

// G against central differences of E a1 through the chart at a moving, non-equilibrium state
// (exercises dq1/dz, the velocity-dependent terms and the drift).
TEST(Modes, LinearizationMatchesFiniteDifferencesAtAMovingState) {
  const Model model = double_pendulum(1.0, 0.6, 2.0, 0.7, 9.81, 0.7, -0.4);
  const State s = consistent_state(
      model, {.positions = {}, .velocities = {{"upper.w", 1.3}, {"lower.w", -0.8}}});
  const StateSpace ss = linearize(model, s);
  ForwardData d(model);
  const VectorXd none(0);
  auto velocities = [&](const VectorXd& q0, const VectorXd& w) {
    MatrixXd K = MatrixXd::Zero(model.n1, model.n1);
    VectorXd b(model.m1), rhs(model.n1);
    velocity_jacobian(model, q0, 0, K.topRows(model.m1), b);
    rhs.head(model.m1) = b;
    for (int i = 0; i < ss.dof; ++i) {
      K(model.m1 + i, ss.velocity_vars[i]) = 1;
      rhs[model.m1 + i] = w[i];
    }
    return VectorXd(K.lu().solve(rhs));
  };
  auto wdot = [&](const VectorXd& q0, const VectorXd& q1) {
    const VectorXd& a = forward_accelerations(model, d, 0, q0, q1, none);
    VectorXd out(ss.dof);
    for (int i = 0; i < ss.dof; ++i) out[i] = a[ss.velocity_vars[i]];
    return out;
  };
  VectorXd w(ss.dof);
  for (int i = 0; i < ss.dof; ++i) w[i] = s.q1[ss.velocity_vars[i]];
  EXPECT_LT((velocities(s.q0, w) - s.q1).norm(), 1e-12);
  const double h = 1e-5;
  for (int j = 0; j < ss.n(); ++j) {
    VectorXd plus, minus;
    if (j < ss.p) {
      VectorXd dz = VectorXd::Zero(ss.p);
      dz[j] = h;
      const VectorXd qp = chart_positions(model, ss, dz), qm = chart_positions(model, ss, -dz);
      plus = wdot(qp, velocities(qp, w));
      minus = wdot(qm, velocities(qm, w));
    } else {
      VectorXd wp = w, wm = w;
      wp[j - ss.p] += h;
      wm[j - ss.p] -= h;
      plus = wdot(s.q0, velocities(s.q0, wp));
      minus = wdot(s.q0, velocities(s.q0, wm));
    }
    const VectorXd fd = (plus - minus) / (2 * h);
    for (int i = 0; i < ss.dof; ++i)
      EXPECT_NEAR(ss.G(ss.p + i, j), fd[i], 1e-5 * (1 + std::abs(fd[i])))
          << ss.states[ss.p + i] << " / " << ss.states[j];
  }
  EXPECT_GT(ss.drift.norm(), 1.0);  // not an equilibrium
}

// Example 4.7: the ring and disc released at rest at theta_bar (asin 3/5 for m2/m1 = 8/67, xi =
// asin 4/5) is not an equilibrium (it rolls down, accelerating), but the linearization at that
// state has the eigenvalues 0 (twice) and +- i omega, omega = sqrt(-G_{theta_dot, theta}) =
// 2.632965 rad/s; the drift is the common acceleration 2 g sin(th) / (2 cos(th - xi) + 1).
TEST(Modes, RingAndDiscFrequencyExample47) {
  const Scene scene = load_scene(scene_path("ring_disc"));
  const Model model = build_scene_model(scene);
  LinearizeOptions o;
  o.coordinates = {"ring.C.x", "disc.C.x"};
  const StateSpace ss = linearize(model, initial_state(scene, model), o);
  EXPECT_EQ(ss.p, 2);
  EXPECT_EQ(ss.dof, 2);
  const auto modes = vibration_modes(ss);
  const auto w = frequencies(modes);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NEAR(w[0], 2.632965, 5e-7);  // the thesis's figure
  const double th = std::asin(0.6), xi = std::asin(0.8);
  const double G = 2 * 9.8 * (std::cos(th) + 2 * std::cos(xi)) * std::sin(xi) /
                   ((2 * std::cos(th - xi) + 1) *
                    (2 * std::sin(th) + 3 * std::sin(2 * th - xi) - 2 * std::sin(xi) +
                     2 * std::sin(th - 2 * xi) + std::sin(2 * th - 3 * xi)) *
                    (1.0 - 0.3));
  EXPECT_NEAR(w[0], std::sqrt(-G), 1e-8 * w[0]);  // its closed form (measured 2e-10)
  EXPECT_NEAR(modes[0].damping_ratio, 0, 1e-7);
  int rigid = 0;
  for (const Mode& md : modes) rigid += md.rigid;
  EXPECT_EQ(rigid, 2);
  const double accel = 2 * 9.8 * std::sin(th) / (2 * std::cos(th - xi) + 1);
  EXPECT_NEAR(ss.drift[2], accel, 1e-9);
  // no equilibrium: Newton says so instead of returning a wrong answer
  EXPECT_THROW(static_equilibrium(model, model.q0), Error);
}

// Figures 4.15 and 4.16 (xi = asin 4/5): theta_bar from the mass ratio by Example 4.7 (c), and
// omega against sqrt(-G_{theta_dot, theta}) at that angle.
TEST(Modes, RingAndDiscTableAgainstMassRatio) {
  const double xi = std::asin(0.8), g = 9.8, r1 = 1.0, r2 = 0.3;
  auto ratio = [&](double th) {
    return std::sin(th) / (2 * std::sin(xi) * std::cos(th - xi) - 3 * std::sin(th) + std::sin(xi)) -
           1;
  };
  auto G = [&](double th) {
    return 2 * g * (std::cos(th) + 2 * std::cos(xi)) * std::sin(xi) /
           ((2 * std::cos(th - xi) + 1) *
            (2 * std::sin(th) + 3 * std::sin(2 * th - xi) - 2 * std::sin(xi) +
             2 * std::sin(th - 2 * xi) + std::sin(2 * th - 3 * xi)) *
            (r1 - r2));
  };
  // ratio(theta) increases through each value on (0.5, 1.0): bisection
  const std::vector<std::pair<double, double>> table = {
      {8.0 / 67, 2.632965}, {0.5, 2.906604}, {1.0, 3.237230}, {5.0, 5.207239}};
  for (const auto& [R, omega] : table) {
    double lo = 0.5, hi = 1.0;
    for (int i = 0; i < 200; ++i) ((ratio(0.5 * (lo + hi)) < R) ? lo : hi) = 0.5 * (lo + hi);
    const double th = 0.5 * (lo + hi);
    EXPECT_NEAR(std::sqrt(-G(th)), omega, 1e-6);  // the closed forms, as tabulated in the docs
    char m2[64], tb[64];
    std::snprintf(m2, sizeof m2, "m2=%.17g", 0.670 * R);
    std::snprintf(tb, sizeof tb, "theta_bar=%.17g", th);
    const std::vector<ParameterOverride> set = {parse_override(m2), parse_override(tb)};
    const Scene scene = load_scene(scene_path("ring_disc"), set);
    const Model model = build_scene_model(scene);
    const auto w = frequencies(vibration_modes(linearize(model, initial_state(scene, model))));
    ASSERT_EQ(w.size(), 1u) << "m2/m1 = " << R;
    EXPECT_NEAR(w[0], std::sqrt(-G(th)), 1e-8 * omega) << "m2/m1 = " << R;  // measured 5e-11
  }
}

// Spring-damper pendulum: the eigenvalue sigma +- i omega_d of the linearization against the
// decay rate and the frequency fitted to a free vibration of amplitude 1e-4 rad (forward run).
TEST(Modes, DampedEigenvalueMatchesForwardRun) {
  const Model model = spring_pendulum(30.0, 0.4, 0.2);
  const Equilibrium eq = static_equilibrium(model, model.q0);
  EXPECT_EQ(eq.stability, "stable");
  const auto modes = vibration_modes(eq.linear);
  ASSERT_EQ(modes.size(), 1u);
  ASSERT_TRUE(modes[0].oscillatory);
  const double sigma = modes[0].eigenvalue.real(), wd = modes[0].eigenvalue.imag();
  EXPECT_GT(modes[0].damping_ratio, 0.005);
  // free vibration from the equilibrium displaced along the mode
  State s;
  s.q0 = chart_positions(model, eq.linear, 1e-4 * modes[0].dz);
  s.q1 = VectorXd::Zero(model.n1);
  const double period = 2 * pi / wd;
  const int n = 4001;
  ForwardOptions fo;
  fo.t1 = 6 * period;
  fo.samples = n;
  fo.rtol = 1e-11;
  fo.atol = 1e-14;
  const Trajectory r = forward_dynamics(model, s, fo);
  const int k = eq.linear.coordinate_vars[0];
  const double z0 = eq.state.q0[k];
  // upward zero crossings of z - z0 (linear interpolation) and the peaks between them
  std::vector<double> cross, peak;
  double best = 0;
  for (int i = 1; i < n; ++i) {
    const double a = r.q0(i - 1, k) - z0, b = r.q0(i, k) - z0;
    best = std::max(best, std::abs(b));
    if (a < 0 && b >= 0) {
      cross.push_back(r.time[i - 1] + (r.time[i] - r.time[i - 1]) * (-a) / (b - a));
      peak.push_back(best);
      best = 0;
    }
  }
  ASSERT_GE(cross.size(), 5u);
  const double fitted_period = (cross[4] - cross[0]) / 4;
  EXPECT_NEAR(2 * pi / fitted_period, wd, 2e-5 * wd);  // measured 3.8e-7
  const double fitted_sigma = std::log(peak[4] / peak[1]) / (cross[4] - cross[1]);
  EXPECT_NEAR(fitted_sigma, sigma, 3e-4 * std::abs(sigma));  // measured 2.4e-5
}

// The efforts that hold a pose at rest (Theorem 4.3 at zero velocity and acceleration): the pivot
// torque of the pendulum at theta is m g L cos(theta) (theta from +x); a passive mechanism
// cannot be held.
TEST(Modes, HoldingEfforts) {
  const double L = 0.8, m = 1.5, g = 9.81, th = 0.3;
  const mechanisms::Example e = mechanisms::pendulum({.L = L, .m = m, .g = g, .theta0 = th});
  const Model model = build_model(e.system);
  double left = 1;
  const VectorXd u = holding_efforts(model, model.q0, 0, &left);
  ASSERT_EQ(u.size(), 1);
  EXPECT_NEAR(u[0], m * g * L * std::cos(th), 1e-12);
  EXPECT_LT(left, 1e-12);
  const Model passive = double_pendulum(1.0, 0.6, 2.0, 0.7, 9.81, 0.3, -0.2);
  EXPECT_THROW(holding_efforts(passive, passive.q0), Error);
}

// Export: labelled CSV and JSON; every label appears.
TEST(Modes, ExportHasLabels) {
  const mechanisms::Example e = mechanisms::pendulum({.theta0 = -pi / 2 + 0.1});
  const Model model = build_model(e.system);
  LinearizeOptions o;
  o.outputs = {"link.P.y"};
  const StateSpace ss = linearize(model, {0, model.q0, VectorXd::Zero(model.n1)}, o);
  const std::string g = state_space_csv(ss, 'G');
  EXPECT_EQ(g.substr(0, g.find('\n')), "G," + ss.states[0] + "," + ss.states[1]);
  EXPECT_NE(state_space_csv(ss, 'H').find("pivot.torque"), std::string::npos);
  EXPECT_NE(state_space_csv(ss, 'C').find("link.P.y,"), std::string::npos);
  const std::string j = state_space_json(ss, vibration_modes(ss));
  EXPECT_NE(j.find("\"modes\""), std::string::npos);
  EXPECT_NE(j.find("\"damping_ratio\""), std::string::npos);
  EXPECT_THROW(linearize(model, {0, model.q0, VectorXd::Zero(model.n1)}, {.outputs = {"no.such"}}),
               Error);
}
