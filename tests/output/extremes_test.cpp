// The extremes of a run located between the samples (mo2d/extremes.hpp, issue 30 item 5).
// References: the crank-rocker four-bar's torque peak from an independent evaluation (inverse
// dynamics solved at the 24 Chebyshev nodes of a wider interval around the peak, the root of the
// derivative of that interpolant, and the torque solved again at that root); a forward run's
// extremes against the inverse run's of the same motion.
#include "mo2d/extremes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "mo2d/forward.hpp"
#include "mo2d/inverse.hpp"
#include "mo2d/scene.hpp"

namespace mo2d {
namespace {

struct FourBar {
  Scene scene = load_scene(std::string(MO2D_MECHANISMS_DIR) + "/fourbar.yaml");
  Model model = build_scene_model(scene);
};

// The effort of input k solved by inverse dynamics at t (from the configuration q0 near it).
double torque_at(const FourBar& f, InverseData& d, const Eigen::VectorXd& q0, double t, int k) {
  d.q0 = q0;
  d.has_previous = false;
  inverse_dynamics_sample(f.model, d, t);
  return d.u[k];
}

// The time of the maximum of the effort k in [c - w, c + w]: the Chebyshev interpolant through n
// nodes, the root of its derivative by bisection (independent of extremes.cpp's equally spaced
// local polynomial, its nodes and its interval).
double chebyshev_peak_time(const FourBar& f, InverseData& d, const Eigen::VectorXd& q0, double c,
                           double w, int k, double sign) {
  constexpr int n = 24;
  std::vector<double> fx(n), coef(n, 0.0);
  for (int i = 0; i < n; ++i) {
    const double x = std::cos(std::numbers::pi * (i + 0.5) / n);
    fx[i] = sign * torque_at(f, d, q0, c + w * x, k);
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) coef[j] += fx[i] * std::cos(std::numbers::pi * j * (i + 0.5) / n);
    coef[j] *= 2.0 / n;
  }
  // p'(x) = sum_j c_j j U_{j-1}(x)
  auto dp = [&](double x) {
    double u0 = 1, u1 = 2 * x, s = coef[1] * 1 * u0;
    for (int j = 2; j < n; ++j) {
      s += coef[j] * j * u1;
      const double u2 = 2 * x * u1 - u0;
      u0 = u1, u1 = u2;
    }
    return s;
  };
  double lo = -0.5, hi = 0.5;  // the peak is near the centre
  EXPECT_GT(dp(lo), 0);
  EXPECT_LT(dp(hi), 0);
  for (int it = 0; it < 200 && hi - lo > 1e-16; ++it)
    (dp(0.5 * (lo + hi)) > 0 ? lo : hi) = 0.5 * (lo + hi);
  return c + w * 0.5 * (lo + hi);
}

// The crank torque's maximum and minimum over the scene's 2 s (401 samples) against the
// independent evaluation, to 1e-10 N m and 1e-10 s; the largest sample is ~1e-5 N m below.
TEST(Extremes, CrankRockerTorquePeaksLocatedInInverseRun) {
  const FourBar f;
  const InverseOptions o = inverse_options(f.scene);
  const Trajectory r = inverse_dynamics(f.model, f.scene.motion, o);
  const std::vector<Extreme> ex = locate_extremes(f.model, f.scene.motion, o, r);
  ASSERT_EQ(ex.size(), r.input_labels.size() + r.reaction_labels.size());
  const int k = 0;
  const Extreme& e = ex[k];
  EXPECT_EQ(e.label, r.input_labels[k]);
  EXPECT_TRUE(e.located_max && e.located_min);
  InverseData d(f.model, f.scene.motion, o);
  for (const double sign : {1.0, -1.0}) {
    const double t_found = sign > 0 ? e.t_max : e.t_min;
    const double v_found = sign > 0 ? e.max : e.min;
    const int near = static_cast<int>(std::lround((t_found - o.t0) / (r.time[1] - r.time[0])));
    const Eigen::VectorXd q0 = r.q0.row(near).transpose();
    const double t_ref = chebyshev_peak_time(f, d, q0, t_found, 0.02, k, sign);
    const double v_ref = torque_at(f, d, q0, t_ref, k);
    EXPECT_NEAR(t_found, t_ref, 1e-10) << (sign > 0 ? "max" : "min");
    EXPECT_NEAR(v_found, v_ref, 1e-10 * std::max(1.0, std::abs(v_ref)));
    // the samples alone miss it by far more
    const double sampled = sign > 0 ? e.sampled_max : e.sampled_min;
    EXPECT_GT(std::abs(sampled - v_ref), 1e-7) << "the peak fell on a sample: a weak test";
  }
}

// The pendulum of mechanisms/pendulum.yaml (point mass m = 1 kg at L = 1 m, theta = 0.5 sin 3t +
// t^2): tau = m L^2 theta'' + m g L cos(theta) in closed form, its extremes where tau' = 0 (Newton
// on the closed-form tau', from the located time). 201 samples over 2 s.
TEST(Extremes, PendulumTorquePeaksAreTheClosedForm) {
  const Scene s = load_scene(std::string(MO2D_MECHANISMS_DIR) + "/pendulum.yaml");
  const Model m = build_scene_model(s);
  const InverseOptions o = inverse_options(s);
  const Trajectory r = inverse_dynamics(m, s.motion, o);
  const std::vector<Extreme> ex = locate_extremes(m, s.motion, o, r);
  const double g = 9.81;
  auto theta = [](double t) { return 0.5 * std::sin(3 * t) + t * t; };
  auto d1 = [](double t) { return 1.5 * std::cos(3 * t) + 2 * t; };
  auto d2 = [](double t) { return -4.5 * std::sin(3 * t) + 2; };
  auto d3 = [](double t) { return -13.5 * std::cos(3 * t); };
  auto d4 = [](double t) { return 40.5 * std::sin(3 * t); };
  auto tau = [&](double t) { return d2(t) + g * std::cos(theta(t)); };
  auto dtau = [&](double t) { return d3(t) - g * std::sin(theta(t)) * d1(t); };
  auto ddtau = [&](double t) {
    return d4(t) - g * (std::cos(theta(t)) * d1(t) * d1(t) + std::sin(theta(t)) * d2(t));
  };
  const Extreme& e = ex[0];
  ASSERT_EQ(e.label, "pivot.torque");
  EXPECT_TRUE(e.located_max && e.located_min);
  for (const double t_found : {e.t_max, e.t_min}) {
    const double value = t_found == e.t_max ? e.max : e.min;
    if (t_found == r.time[0] || t_found == r.time[r.time.size() - 1]) {  // an end of the run
      EXPECT_NEAR(value, tau(t_found), 1e-10 * std::abs(value));
      continue;
    }
    double t = t_found;
    for (int it = 0; it < 30; ++it) t -= dtau(t) / ddtau(t);
    EXPECT_NEAR(t_found, t, 1e-10);
    EXPECT_NEAR(value, tau(t), 1e-10 * std::max(1.0, std::abs(tau(t))));
  }
  // every sample is off the peak by more than the tolerance
  EXPECT_GT(std::abs(e.sampled_max - e.max) + std::abs(e.sampled_min - e.min), 1e-7);
}

// A forward run of the same motion (the inverse torque replayed, dopri5 at rtol 1e-12) sampled
// coarsely (51 samples over 1 s): its located extremes of the torque and of every reaction equal
// the inverse run's to the integration error, where the samples miss them by ~1e-3 of the peak.
TEST(Extremes, ForwardRunExtremesEqualTheInverseRuns) {
  const FourBar f;
  InverseOptions io = inverse_options(f.scene);
  io.t1 = 1.0;
  io.samples = 51;
  const Trajectory inv = inverse_dynamics(f.model, f.scene.motion, io);
  const std::vector<Extreme> ei = locate_extremes(f.model, f.scene.motion, io, inv);
  ForwardOptions o{.t0 = 0, .t1 = 1.0, .samples = 51, .integrator = Integrator::dopri5};
  o.rtol = 1e-12;
  o.atol = 1e-14;
  o.efforts = efforts_from_inverse(f.model, f.scene.motion, io);
  const State s{0, inv.q0.row(0).transpose(), inv.q1.row(0).transpose()};
  const Trajectory fw = forward_dynamics(f.model, s, o);
  const std::vector<Extreme> ef = locate_extremes(f.model, o, fw);
  ASSERT_EQ(ef.size(), ei.size());
  double worst = 0, worst_sampled = 0;
  for (std::size_t c = 0; c < ef.size(); ++c) {
    const double scale = std::max({std::abs(ei[c].max), std::abs(ei[c].min), 1e-3});
    worst = std::max(
        {worst, std::abs(ef[c].max - ei[c].max) / scale, std::abs(ef[c].min - ei[c].min) / scale});
    worst_sampled = std::max({worst_sampled, std::abs(ef[c].sampled_max - ei[c].max) / scale,
                              std::abs(ef[c].sampled_min - ei[c].min) / scale});
  }
  EXPECT_LE(worst, 1e-8);
  EXPECT_GT(worst_sampled, 1e-4);
  EXPECT_NEAR(ef[0].t_max, ei[0].t_max, 1e-7);
  EXPECT_NEAR(ef[0].t_min, ei[0].t_min, 1e-7);
  // the torque (a law of time here, so exact whatever the integration) against the independent
  // evaluation
  InverseData d(f.model, f.scene.motion, io);
  const int near = static_cast<int>(std::lround(ef[0].t_max / (inv.time[1] - inv.time[0])));
  const Eigen::VectorXd q0 = inv.q0.row(near).transpose();
  const double t_ref = chebyshev_peak_time(f, d, q0, ef[0].t_max, 0.02, 0, 1.0);
  EXPECT_NEAR(ef[0].t_max, t_ref, 1e-9);
  EXPECT_NEAR(ef[0].max, torque_at(f, d, q0, t_ref, 0), 1e-10);
}

}  // namespace
}  // namespace mo2d
