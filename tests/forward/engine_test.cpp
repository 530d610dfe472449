// The engine example (mechanisms/engine.yaml, issue 12 item 10): a single-cylinder four-stroke
// engine whose gas force is a periodic table against the crank angle, with a flywheel and a
// generator torque -c * omega. Checked against what does not depend on the integrator:
//  - the gas force depends on the crank angle only, so its work is a function of the angle,
//    Phi(theta) = -int_0^theta (p - p_atm) dV (here computed by quadrature of the same table);
//    with the generator's work -c int omega^2 dt it must make up the recorded load work;
//  - the energy balance with every load counted closes;
//  - in the periodic steady state the indicated work per cycle W = Phi(4 pi) is taken by the
//    generator, c int omega dtheta = 4 pi c <omega>_theta: the angle-mean speed over a cycle is
//    W / (4 pi c) exactly (the ripple does not enter; only what is left of the start transient).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"
#include "mo2d/table.hpp"

namespace mo2d {
namespace {

struct Engine {
  Scene scene;
  Model model;
  Trajectory r;
  double r_crank = 0, L = 0, Ap = 0, p_atm = 0, c = 0;
  LookupTable p;

  double parameter(const std::string& name) const {
    for (const auto& [n, v] : scene.parameters)
      if (n == name) return v;
    ADD_FAILURE() << "no parameter " << name;
    return NAN;
  }
  // dV/dtheta = Ap ds/dtheta, s = r + L - r cos(theta) - sqrt(L^2 - r^2 sin^2(theta))
  double dV(double th) const {
    const double s = std::sin(th), root = std::sqrt(L * L - r_crank * r_crank * s * s);
    return Ap * (r_crank * s + r_crank * r_crank * s * std::cos(th) / root);
  }
  // the work of the gas force from angle 0 to theta (J): the force -(p - p_atm) Ap along +y on a
  // piston at y = r + L - s does (p - p_atm) Ap ds = (p - p_atm) dV
  double gas_work(double theta) const {
    const double cycle = 4 * M_PI, whole = std::floor(theta / cycle);
    return whole * gas_work_within(cycle) + gas_work_within(theta - whole * cycle);
  }
  double gas_work_within(double theta) const {  // 0 <= theta <= 4 pi
    const double knot = 2 * M_PI / 180;         // the table's points are 2 deg apart
    const int sub = 16;                         // Simpson on each piece of the spline
    auto f = [&](double th) { return (p(th) - p_atm) * dV(th); };
    double w = 0;
    for (double a = 0; a < theta; a += knot) {
      const double b = std::min(a + knot, theta), h = (b - a) / sub;
      double s = f(a) + f(b);
      for (int k = 1; k < sub; ++k) s += (k % 2 ? 4 : 2) * f(a + k * h);
      w += s * h / 3;
    }
    return w;
  }
};

Engine run_engine(int samples) {
  Engine e{load_scene(std::string(MO2D_MECHANISMS_DIR) + "/engine.yaml"),
           {},
           {},
           0,
           0,
           0,
           0,
           0,
           read_table_csv(std::string(MO2D_MECHANISMS_DIR) + "/engine_pressure.csv", "pressure",
                          {"crank_deg", "p_bar", M_PI / 180, 1e5},
                          {Interpolation::cubic, Extrapolation::periodic})};
  e.model = build_scene_model(e.scene);
  ForwardOptions o = forward_options(e.scene, e.model);
  o.samples = samples;
  e.r = forward_dynamics(e.model, initial_state(e.scene, e.model), o);
  e.r_crank = e.parameter("r");
  e.L = e.parameter("L");
  e.Ap = e.parameter("Ap");
  e.p_atm = e.parameter("p_atm");
  e.c = e.parameter("c_load");
  return e;
}

const Engine& engine() {
  static const Engine e = run_engine(24001);  // 4 kHz: ~170 samples per revolution
  return e;
}

void gas_and_generator_work_make_up_the_load_work(const Engine& e) {
  const Trajectory& r = e.r;
  const int th = e.model.coordinate("crank.angle"), w = e.model.rate("crank.w");
  const Eigen::Index n = r.time.size() - 1;
  // generator: -c int omega^2 dt by Simpson (n even) on the samples
  double s = 0;
  for (Eigen::Index k = 0; k <= n; ++k) {
    const double f = r.q1(k, w) * r.q1(k, w);
    s += (k == 0 || k == n) ? f : (k % 2 ? 4 * f : 2 * f);
  }
  const double h = r.time[1] - r.time[0];
  const double generator = -e.c * s * h / 3;
  const double gas = e.gas_work(r.q0(n, th)) - e.gas_work(r.q0(0, th));
  const double balance = energy_balance_error(r);
  std::printf(
      "engine: gas work %.6f J, generator work %.6f J, recorded load work %.6f J "
      "(difference %.3e J); energy balance error %.3e J\n",
      gas, generator, r.load_work[n], r.load_work[n] - gas - generator, balance);
  // gravity is counted in the potential, not in the load work
  const double scale = std::abs(gas) + std::abs(generator);
  EXPECT_LT(std::abs(r.load_work[n] - gas - generator), 1e-6 * scale);
  // the balance over 6 s at rtol 1e-8: its error relative to the work that went through
  EXPECT_LT(balance, 1e-6 * scale);
}

// t where the crank angle reaches `angle` (linear between samples) and the sample before it.
std::pair<double, Eigen::Index> crossing(const Trajectory& r, int col, double angle) {
  for (Eigen::Index k = 1; k < r.time.size(); ++k)
    if (r.q0(k, col) >= angle) {
      const double a = r.q0(k - 1, col), b = r.q0(k, col);
      return {r.time[k - 1] + (angle - a) / (b - a) * (r.time[k] - r.time[k - 1]), k - 1};
    }
  return {NAN, -1};
}

void steady_mean_speed_is_the_indicated_work_over_the_generators_constant(const Engine& e) {
  const Trajectory& r = e.r;
  const int th = e.model.coordinate("crank.angle"), w = e.model.rate("crank.w");
  const double cycle = 4 * M_PI, W = e.gas_work(cycle);
  const double closed = W / (cycle * e.c);
  // the last complete cycle [4 pi k, 4 pi (k + 1)]
  const double last = std::floor(r.q0(r.time.size() - 1, th) / cycle) - 1;
  const auto [ta, ia] = crossing(r, th, last * cycle);
  const auto [tb, ib] = crossing(r, th, (last + 1) * cycle);
  ASSERT_GT(ia, 0);
  // int omega dtheta = int omega^2 dt by the trapezoid, the two ends by linear pieces
  auto f = [&](Eigen::Index k) { return r.q1(k, w) * r.q1(k, w); };
  auto at = [&](const Eigen::VectorXd& v, double t, Eigen::Index k) {
    return v[k] + (v[k + 1] - v[k]) * (t - r.time[k]) / (r.time[k + 1] - r.time[k]);
  };
  const Eigen::VectorXd f_all = r.q1.col(w).array().square();
  double integral = 0.5 * (at(f_all, ta, ia) + f(ia + 1)) * (r.time[ia + 1] - ta);
  for (Eigen::Index k = ia + 1; k < ib; ++k)
    integral += 0.5 * (f(k) + f(k + 1)) * (r.time[k + 1] - r.time[k]);
  integral += 0.5 * (f(ib) + at(f_all, tb, ib)) * (tb - r.time[ib]);
  const double mean = integral / cycle;
  // what is left of the start transient: the kinetic energy the cycle still gains
  const double dK = at(r.kinetic, tb, ib) - at(r.kinetic, ta, ia);
  const double dV = at(r.potential, tb, ib) - at(r.potential, ta, ia);
  double wmax = -INFINITY, wmin = INFINITY;
  for (Eigen::Index k = ia; k <= ib; ++k) {
    wmax = std::max(wmax, r.q1(k, w));
    wmin = std::min(wmin, r.q1(k, w));
  }
  std::printf(
      "engine: W = %.4f J/cycle, closed-form mean speed %.5f rad/s; run (cycle %.0f, "
      "t = %.3f..%.3f s): angle-mean %.5f rad/s (rel. diff %.2e), dK %.3e J, dV %.1e J; "
      "ripple %.3f..%.3f rad/s (%.2f %% of the mean)\n",
      W, closed, last, ta, tb, mean, mean / closed - 1, dK, dV, wmin, wmax,
      100 * (wmax - wmin) / mean);
  // the exact cycle balance W = 4 pi c <omega> + dK + dV, to the quadrature error
  EXPECT_NEAR(cycle * e.c * mean + dK + dV, W, 1e-4 * W);
  // steady: the transient left (tau = I/c ~ 0.75 s, 8 time constants) is < 1e-3 of the speed
  EXPECT_LT(std::abs(dK), 1e-3 * W);
  EXPECT_NEAR(mean, closed, 1e-3 * closed);
}

// Both checks in one test, so one process runs the 6 s simulation they read (ctest runs every
// test in its own process: two tests ran it twice, 50 s each in the sanitizer build).
TEST(Engine, GasAndGeneratorWorkMakeUpTheLoadWorkAndTheSteadyMeanSpeedIsTheIndicatedWorkOverC) {
  const Engine& e = engine();
  {
    SCOPED_TRACE("gas and generator work make up the load work; the energy balance closes");
    gas_and_generator_work_make_up_the_load_work(e);
  }
  SCOPED_TRACE("the steady mean speed is the indicated work over the generator's constant");
  steady_mean_speed_is_the_indicated_work_over_the_generators_constant(e);
}

}  // namespace
}  // namespace mo2d
