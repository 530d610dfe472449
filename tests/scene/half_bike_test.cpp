// The half-bike of Gamba 2009 (mechanisms/half_bike.yaml, issue 13 item 4): the scene loads and
// runs its scenarios; each check is against something the chain element does not compute:
// - the steady speeds of a constant engine torque in closed form (the rigid-chain balance
//   T1 = (gamma_ds + gamma_rw rho^2) w_ds, w_rw = rho w_ds, rho = r_ds / r_ws) and the steady
//   lower-span tension from the wheel's balance r_ws T = gamma_rw w_rw;
// - which span pulls, from the sign of the torque the shaft's own equation of motion needs from
//   the chain, J_ds a_ds + gamma_ds w_ds - tau_eng (finite differences of the recorded speed):
//   the lower span (wheel behind the shaft) gives the shaft a clockwise torque, the upper span a
//   counter-clockwise one;
// - the energy balance of the forward run (an independent energy function);
// - the chain's extension at the same tension falls as 1/k.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "mo2d/forward.hpp"
#include "mo2d/output_columns.hpp"
#include "mo2d/render.hpp"
#include "mo2d/scene.hpp"

namespace mo2d {
namespace {

struct BikeRun {
  Scene scene;
  Model model;
  Trajectory r;
};

BikeRun run_bike(std::vector<ParameterOverride> set, std::vector<RunOverride> run = {}) {
  BikeRun b{load_scene(std::string(MO2D_MECHANISMS_DIR) + "/half_bike.yaml", set, run), {}, {}};
  b.model = build_scene_model(b.scene);
  b.r =
      forward_dynamics(b.model, initial_state(b.scene, b.model), forward_options(b.scene, b.model));
  add_output_columns(b.model, b.r, b.scene.outputs);
  return b;
}

double bike_parameter(const Scene& s, const std::string& name) {
  for (const auto& [n, v] : s.parameters)
    if (n == name) return v;
  ADD_FAILURE() << "no parameter " << name;
  return 0;
}

Eigen::Index bike_sample_at(const Trajectory& r, double t) {
  Eigen::Index k = 0;
  while (k + 1 < r.time.size() && r.time[k] < t) ++k;
  return k;
}

double bike_output(const Trajectory& r, const std::string& label, Eigen::Index k) {
  return r.outputs(k, r.output(label));
}

// Scenario 3 (constant engine torque) settles at the rigid-chain balance.
TEST(HalfBike, SteadySpeedFollowsTheDriveRatio) {
  // Frictions 20 times the scene's (a time constant J_eff / gamma_eq of 0.68 s instead of 15 s).
  const BikeRun b = run_bike({{"scenario", "3"}, {"gamma_ds", "0.01"}, {"gamma_rw", "0.1"}},
                             {{"duration", "12"}, {"samples", "121"}});
  const Scene& s = b.scene;
  EXPECT_EQ(b.model.dof, 3);
  const double rho = bike_parameter(s, "r_ds") / bike_parameter(s, "r_ws");
  const double g_ds = bike_parameter(s, "gamma_ds"), g_rw = bike_parameter(s, "gamma_rw");
  const double w_ds = bike_parameter(s, "T1") / (g_ds + g_rw * rho * rho);
  const Eigen::Index last = b.r.time.size() - 1;
  const double shaft = b.r.q1(last, b.r.rate_column("shaft.w"));
  const double wheel = b.r.q1(last, b.r.rate_column("wheel.w"));
  const double arm = b.r.q1(last, b.r.rate_column("arm.w"));
  const double Tl = bike_output(b.r, "chain.lower.tension", last);
  std::printf(
      "steady: shaft %.4f rad/s (closed form %.4f), wheel/shaft %.6f (rho %.6f), lower %.3f N\n",
      shaft, w_ds, (wheel - arm) / shaft, rho, Tl);
  EXPECT_NEAR(shaft, w_ds, 1e-4 * w_ds);  // 12 s = 17 time constants J_eff / gamma_eq
  // a ratio of rates: to the integrator's rtol (1e-7 in the scene) times a few
  EXPECT_NEAR((wheel - arm) / shaft, rho, 1e-6);
  EXPECT_NEAR(Tl, g_rw * rho * w_ds / bike_parameter(s, "r_ws"), 1e-3 * Tl);
  EXPECT_EQ(bike_output(b.r, "chain.upper.tension", last), 0);
  // the balance error grows with the energy that flows through (the engine's work T1 theta_ds,
  // about 1.8 kJ, 30 times the kinetic energy at the steady state)
  const double work = bike_parameter(s, "T1") * b.r.q0(last, b.model.coordinate("chain.theta_b"));
  std::printf("energy balance error %.3e J, engine work %.1f J\n", energy_balance_error(b.r), work);
  EXPECT_LT(energy_balance_error(b.r), 1e-6 * work);
}

// The torque the shaft needs from the chain at sample k (its own equation of motion).
double bike_shaft_needs(const BikeRun& b, Eigen::Index k) {
  const Trajectory& r = b.r;
  const int w = r.rate_column("shaft.w");
  const double a = (r.q1(k + 1, w) - r.q1(k - 1, w)) / (r.time[k + 1] - r.time[k - 1]);
  return bike_parameter(b.scene, "J_ds") * a + bike_parameter(b.scene, "gamma_ds") * r.q1(k, w) -
         bike_output(r, "engine.torque", k);
}

// Scenario 1: the lower span pulls during traction and braking, the upper one while coasting;
// each time the tension times r_ds is the torque the shaft's own balance needs.
TEST(HalfBike, Scenario1SpansAndEnergy) {
  const BikeRun b = run_bike({}, {{"duration", "11.5"}, {"samples", "1151"}});
  const double r_ds = bike_parameter(b.scene, "r_ds");
  struct Phase {
    double t;
    bool lower;
  };
  for (const Phase& p : {Phase{4.5, true}, Phase{9.0, false}, Phase{11.0, true}}) {
    const Eigen::Index k = bike_sample_at(b.r, p.t);
    const double Tu = bike_output(b.r, "chain.upper.tension", k);
    const double Tl = bike_output(b.r, "chain.lower.tension", k);
    const double need = bike_shaft_needs(b, k);
    std::printf("t = %.2f s: upper %.3f N, lower %.3f N, the shaft needs %.4f N m\n", b.r.time[k],
                Tu, Tl, need);
    EXPECT_EQ(p.lower ? Tu : Tl, 0) << "t = " << p.t;
    const double pulls = p.lower ? Tl : Tu;
    EXPECT_GT(pulls, 0) << "t = " << p.t;
    // lower: the span's torque on the shaft is -r_ds Tl; upper: +r_ds Tu
    EXPECT_NEAR(p.lower ? -r_ds * Tl : r_ds * Tu, need, 2e-3 * std::abs(need) + 1e-4)
        << "t = " << p.t;
  }
  // the kinetic energy of the spinning shaft and wheel at the end of the engine's ramp
  const Eigen::Index k5 = bike_sample_at(b.r, 5.0);
  const double w_ds = b.r.q1(k5, b.r.rate_column("shaft.w"));
  const double w_rw = b.r.q1(k5, b.r.rate_column("wheel.w"));
  const double E = 0.5 * (bike_parameter(b.scene, "J_ds") * w_ds * w_ds +
                          bike_parameter(b.scene, "J_rw") * w_rw * w_rw);
  std::printf("energy balance error %.3e J (kinetic energy at 5 s %.1f J)\n",
              energy_balance_error(b.r), E);
  EXPECT_LT(energy_balance_error(b.r), 1e-6 * E);
}

// The inextensible chain (fidelity inextensible, the wheel's velocity left to the chain's row)
// starts where the full model starts: its spans both have 0.5 mm of slack, so it starts slack
// with the arm level, every coordinate the full model's. It was assembled onto the upper span's
// row, which moved the swing arm by -2.04e-3 rad against the suspension (the arm rang until
// ~1 s). Then 0.3 s of both agree (the arm within 2e-5 rad: measured 1.1e-5, printed).
TEST(HalfBike, InextensibleChainStartsWhereTheFullModelStarts) {
  const std::string path = std::string(MO2D_MECHANISMS_DIR) + "/half_bike.yaml";
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const auto& [from, to] :
       {std::pair<std::string, std::string>{"fidelity: unilateral", "fidelity: inextensible"},
        {"{shaft.w: 0, arm.w: 0, wheel.w: 0}", "{shaft.w: 0, arm.w: 0}"}}) {
    const size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  }
  const std::vector<RunOverride> run = {{"duration", "0.3"}, {"samples", "4"}};
  const Scene si = parse_scene(text, path, {}, run), sf = load_scene(path, {}, run);
  const Model mi = build_scene_model(si), mf = build_scene_model(sf);
  const State i = initial_state(si, mi), f = initial_state(sf, mf);
  for (int j = 0; j < mf.n0; ++j) {
    const std::string& label = mf.coordinate_labels[j];
    EXPECT_NEAR(i.q0[mi.coordinate(label)], f.q0[j], 1e-12) << label;
    EXPECT_NEAR(mi.q0[mi.coordinate(label)], mf.q0[j], 1e-12) << label;
  }
  const Trajectory ri = forward_dynamics(mi, i, forward_options(si, mi));
  const Trajectory rf = forward_dynamics(mf, f, forward_options(sf, mf));
  EXPECT_EQ(ri.stats.warnings.at(0), "chain 'chain': slack at t = 0 s (start)");
  double worst = 0;
  for (Eigen::Index k = 0; k < rf.time.size(); ++k) {
    auto angle = [](const Trajectory& r, Eigen::Index k) {
      return std::atan2(-r.q0(k, r.column("arm.W.y")), -r.q0(k, r.column("arm.W.x")));
    };
    worst = std::max(worst, std::abs(angle(ri, k) - angle(rf, k)));
  }
  std::printf("swing arm, inextensible against full chain over 0.3 s: %.2e rad\n", worst);
  EXPECT_LT(worst, 2e-5);
}

// Scenario 2, first second (the engine's triangle rising to 10 N m): at t = 1 s the lower
// span's tension is set by the dynamics (nearly the same at k = 1e4 and 1e5 N/m), so its
// extension falls as 1/k.
TEST(HalfBike, Scenario2ExtensionFallsAsOneOverK) {
  std::vector<double> ext, tension;
  for (const char* k : {"1e4", "1e5"}) {
    const BikeRun b =
        run_bike({{"scenario", "2"}, {"k_chain", k}}, {{"duration", "1"}, {"samples", "101"}});
    const Eigen::Index at = bike_sample_at(b.r, 1.0);
    const double rest = bike_parameter(b.scene, "L0") + bike_parameter(b.scene, "slack") / 2;
    ext.push_back(bike_output(b.r, "chain.lower.length", at) - rest);
    tension.push_back(bike_output(b.r, "chain.lower.tension", at));
    std::printf("k = %s N/m: lower extension %.4e m, tension %.2f N, energy error %.2e J\n", k,
                ext.back(), tension.back(), energy_balance_error(b.r));
  }
  EXPECT_NEAR(tension[0], tension[1], 0.02 * tension[1]);
  EXPECT_NEAR(ext[0] / ext[1], 10, 0.2);
}

// The frame draws the chain (render/chains.cpp): at the end of the engine's ramp the pulling
// lower span is red and the slack upper span grey (dashed), at the spans' midpoints computed
// here from the open-belt tangents of the initial geometry (the arm has moved < 1e-4 rad).
bool bike_near(const Image& im, const Vec2& px, bool (*test)(unsigned)) {
  for (int dy = -3; dy <= 3; ++dy)
    for (int dx = -3; dx <= 3; ++dx)
      if (test(rgb_of(im.at(static_cast<int>(px.x()) + dx, static_cast<int>(px.y()) + dy))))
        return true;
  return false;
}
bool bike_red(unsigned c) {
  return ((c >> 16) & 0xFF) > ((c >> 8) & 0xFF) + 40;
}
bool bike_grey(unsigned c) {
  const int r = (c >> 16) & 0xFF, g = (c >> 8) & 0xFF, b = c & 0xFF;
  return r < 200 && std::abs(r - g) < 12 && std::abs(g - b) < 12;
}

TEST(HalfBike, FrameDrawsTheSpansByTension) {
  const BikeRun b = run_bike({}, {{"duration", "5"}, {"samples", "51"}});
  const Motion m = motion_of(b.r);
  const FrameOptions o;
  const Image im = render_frame(b.model, m, 50, o);
  const View v = fit_view(b.model, m, o);
  const double l = bike_parameter(b.scene, "l_sa"), h = bike_parameter(b.scene, "h_x");
  const double ra = bike_parameter(b.scene, "r_ws"), rb = bike_parameter(b.scene, "r_ds");
  const double alpha = std::acos((ra - rb) / (l + h));
  auto mid = [&](double phi) {
    const Vec2 u(std::cos(phi), std::sin(phi));
    return to_pixel(v, 0.5 * (Vec2(-l, 0) + ra * u + Vec2(h, 0) + rb * u));
  };
  EXPECT_GT(bike_output(b.r, "chain.lower.tension", 50), 0);
  EXPECT_TRUE(bike_near(im, mid(-alpha), bike_red));
  EXPECT_FALSE(bike_near(im, mid(alpha), bike_red));
  EXPECT_TRUE(bike_near(im, mid(alpha), bike_grey));
}

}  // namespace
}  // namespace mo2d
