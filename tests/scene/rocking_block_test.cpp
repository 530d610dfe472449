// The shipped rocking block (mechanisms/rocking_block.yaml; Housner 1963, "The behavior of
// inverted pendulum structures during earthquakes", Bull. Seism. Soc. Am. 53:403): a uniform
// block of width 2 b and height 2 h tilted by theta0 about one corner and released. Between
// impacts it turns about a corner: I_O theta'' = -m g R sin(alpha - theta), so from rest at the
// tilt theta_m it reaches the ground (theta = 0) after
//   T(theta_m) = int_0^theta_m dtheta / sqrt(2 p^2 (cos(alpha - theta_m) - cos(alpha - theta))),
// p^2 = m g R / I_O = 3 g / (4 R), at |omega| = sqrt(2 p^2 (cos(alpha - theta_m) - cos alpha)).
// At the impact it pivots onto the other corner with omega+ = r omega-, r = 1 - (3/2) sin^2 alpha
// (the angular momentum about the new corner conserved), then rises to the tilt theta' with
// cos(alpha - theta') = cos alpha + (r omega)^2 / (2 p^2) and comes back after 2 T(theta').
// T is computed here by Gauss-Legendre quadrature after theta = theta_m (1 - s^2), which removes
// the square-root singularity: independent of the run.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "mo2d/scene.hpp"

namespace mo2d {
namespace {

double rocking_parameter(const Scene& s, const std::string& name) {
  for (const auto& [n, v] : s.parameters)
    if (n == name) return v;
  ADD_FAILURE() << "no parameter " << name;
  return NAN;
}

// 20 panels of 20-point Gauss-Legendre on s in [0, 1] (nodes by Newton on P_20)
double rocking_quarter_time(double theta_m, double alpha, double p2) {
  constexpr int n = 20;
  static std::vector<double> x, w;
  if (x.empty())
    for (int i = 1; i <= n; ++i) {
      double z = std::cos(M_PI * (i - 0.25) / (n + 0.5)), dp = 0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1, p1 = z;
        for (int k = 2; k <= n; ++k) {
          const double pk = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
          p0 = p1;
          p1 = pk;
        }
        dp = n * (z * p1 - p0) / (z * z - 1);
        const double dz = p1 / dp;
        z -= dz;
        if (std::abs(dz) < 1e-16) break;
      }
      x.push_back(z);
      w.push_back(2 / ((1 - z * z) * dp * dp));
    }
  double sum = 0;
  for (int panel = 0; panel < 20; ++panel)
    for (int i = 0; i < n; ++i) {
      const double s = (panel + (x[i] + 1) / 2) / 20;
      const double theta = theta_m * (1 - s * s);
      sum += w[i] / 40 * 2 * theta_m * s /
             std::sqrt(2 * p2 * (std::cos(alpha - theta_m) - std::cos(alpha - theta)));
    }
  return sum;
}

}  // namespace

TEST(RockingBlock, ImpactsFollowHousnersClosedForms) {
  const Scene scene = load_scene(MO2D_MECHANISMS_DIR "/rocking_block.yaml");
  const Model model = build_scene_model(scene);
  const ForwardOptions o = forward_options(scene, model);
  check_scene_options(scene, model, o);
  const SceneRun run = scene_forward(scene, model, initial_state(scene, model), o);
  const double b = rocking_parameter(scene, "b"), h = rocking_parameter(scene, "h");
  const double m = rocking_parameter(scene, "m"), g = rocking_parameter(scene, "g");
  const double theta0 = rocking_parameter(scene, "theta0");
  const double R = std::hypot(b, h), alpha = std::atan(b / h), p2 = 3 * g / (4 * R);
  const double I_O = 4 * m * R * R / 3, r = 1 - 1.5 * std::sin(alpha) * std::sin(alpha);
  std::vector<ContactEvent> hits;
  for (const ContactEvent& e : run.events) {
    EXPECT_NE(e.kind, ContactEvent::Kind::slip) << "t = " << e.t;
    if (e.kind == ContactEvent::Kind::impact) hits.push_back(e);
  }
  ASSERT_EQ(hits.size(), 10U);
  double t = rocking_quarter_time(theta0, alpha, p2), tilt = theta0;
  double w = std::sqrt(2 * p2 * (std::cos(alpha - theta0) - std::cos(alpha)));
  for (size_t k = 0; k < hits.size(); ++k) {
    EXPECT_EQ(hits[k].contact, k % 2 == 0 ? "cornerA" : "cornerB");
    EXPECT_NEAR(hits[k].t, t, 1e-8) << "impact " << k << " (tilt before " << tilt << ")";
    // the landing corner comes down at 2 b omega; the energy lost is I_O omega^2 (1 - r^2) / 2
    EXPECT_NEAR(hits[k].speed, 2 * b * w, 1e-9) << "impact " << k;
    EXPECT_NEAR(hits[k].speed_after, 0, 1e-12) << "impact " << k;
    EXPECT_NEAR(hits[k].energy_lost, I_O * w * w * (1 - r * r) / 2, 1e-9) << "impact " << k;
    if (k > 0) {
      EXPECT_NEAR(hits[k].speed / hits[k - 1].speed, r, 1e-9) << "impact " << k;
    }
    w *= r;
    tilt = alpha - std::acos(std::cos(alpha) + w * w / (2 * p2));
    t += 2 * rocking_quarter_time(tilt, alpha, p2);
  }
  // the pivot never slides: at every sample a corner is on the ground at its place, x = -b or b
  const Trajectory& tr = run.trajectory;
  const auto ax = tr.q0.col(tr.column("block.A.x")), ay = tr.q0.col(tr.column("block.A.y"));
  const auto bx = tr.q0.col(tr.column("block.B.x")), by = tr.q0.col(tr.column("block.B.y"));
  for (Eigen::Index k = 0; k < tr.time.size(); ++k) {
    const bool onA = ay[k] < by[k];
    EXPECT_NEAR(onA ? ay[k] : by[k], 0, 1e-9) << "t = " << tr.time[k];
    EXPECT_NEAR(onA ? ax[k] : bx[k], onA ? -b : b, 1e-9) << "t = " << tr.time[k];
  }
  EXPECT_LT(energy_balance_error(tr), 1e-9 * m * g * h);
}

}  // namespace mo2d
