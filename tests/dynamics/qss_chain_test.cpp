// The quasi-steady chain (ChainFidelity::quasi_steady: the inextensible chain's span rows and
// switching, the taut span's length held at rest + T / k; mo2d/quasi_steady.hpp) against
// independent computations, on two flywheels on fixed centres (as tests/dynamics/
// inextensible_chain_test.cpp):
//  - a constant torque: the tension is the closed form T_u = I_b rho alpha_a / r_b (a span held at
//    a constant length turns the sprockets as rigidly as the inextensible one), and the upper
//    span's length is rest + T_u / k;
//  - the torque reversing at t_s: the switch to the lower span at t_s, the lower span's length
//    then rest + T_l / k, the held lengths back at rest after the run (and after a run that
//    throws);
//  - the stiff unilateral chain's spring force k e + c de/dt tends to the QSS tension as 1/k;
//  - the torque reversing by a step at t_s, the upper span's tension jumping from T to -T: the
//    span released from rest + T / k to its rest length at t_s, then, with the lower span delta
//    longer, slack and the lower span engaging at the inextensible chain's closed-form time
//    t_s + sqrt(2 I_a delta / (r_a tau0)) (not at the time of delta -+ T / k: the span left at
//    rest + T / k, or at rest - T / k), or, with the default rest lengths, the lower span taking
//    over at t_s; the lower span then held at rest + T / k.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "dynamics/chain.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/forward.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/quasi_steady.hpp"

using namespace mo2d;

namespace qss_chain_test {

constexpr double ra = 0.04, rb = 0.1, Ia = 0.01, Ib = 0.4, tau0 = 2.0, ts = 0.5;
constexpr double rho = ra / rb;

BodyDef disc(const std::string& name, Vec2 c, double inertia) {
  return {.name = name,
          .nodes = {{"C", c}, {"R", c + Vec2(0.05, 0.01)}},
          .mass = 1,
          .inertia = inertia};
}

// Two flywheels on ground axes 0.5 m apart, the drive torque `torque` on a, a chain, a viscous
// bearing on b.
System flywheels(std::function<double(double)> torque, ChainFidelity f, double k,
                 double damping = 0, double bearing = 0, std::optional<double> rest_lower = {}) {
  System s("flywheels");
  s.add_ground_node("A", {0, 0});
  s.add_ground_node("B", {0.5, 0});
  s.add_body(disc("a", {0, 0}, Ia));
  s.add_body(disc("b", {0.5, 0}, Ib));
  s.add_revolute({.name = "pa", .node_a = "ground.A", .node_b = "a.C"});
  s.add_revolute({.name = "pb", .node_a = "ground.B", .node_b = "b.C"});
  if (bearing > 0) s.add_torsional_spring({.name = "bearing", .joint = "pb", .damping = bearing});
  s.add_torque({.name = "drive", .body = "a", .torque = std::move(torque)});
  s.add_chain({.name = "chain",
               .body_a = "a",
               .centre_a = {0, 0},
               .radius_a = ra,
               .body_b = "b",
               .centre_b = {0.5, 0},
               .radius_b = rb,
               .stiffness = k,
               .damping = damping,
               .rest_lower = rest_lower,
               .fidelity = f});
  return s;
}

// At rest: a.w alone with the chain's row (quasi_steady), both rates with spring spans.
State at_rest(const Model& m) {
  if (m.chains[0].held[0])
    return consistent_state(m, {.positions = {}, .velocities = {{"a.w", 0.0}}});
  return consistent_state(m, {.positions = {}, .velocities = {{"a.w", 0.0}, {"b.w", 0.0}}});
}

ForwardOptions options(double t1, int samples) {
  return {.t1 = t1,
          .samples = samples,
          .integrator = Integrator::dopri5,
          .rtol = 1e-11,
          .atol = 1e-13,
          .max_seconds = 60};
}

double upper_tension(double tau) {  // I_b alpha_b = r_b T_u, alpha_b = rho alpha_a
  return Ib * rho * tau / (Ia + rho * rho * Ib) / rb;
}

ChainValue value_at(const Model& m, const Trajectory& r, Eigen::Index i) {
  return chain_value(m, m.chains[0], r.q0.row(i).transpose(), r.q1.row(i).transpose(), r.time[i]);
}

double held(const Model& m, int span) {
  return *m.chains[0].held[span];
}

// The time in the first warning containing `what` (after "t = "), NaN if none.
double time_of(const Trajectory& r, const std::string& what) {
  for (const std::string& w : r.stats.warnings)
    if (w.find(what) != std::string::npos)
      return std::stod(w.substr(w.find("t = ", w.find(what)) + 4));
  return NAN;
}

// +tau0 to -tau0 at ts: the QSS chain with the lower span `delta` longer than the upper's rest.
Trajectory torque_step(double k, double delta, Model& m) {
  const double D = 0.5, L0 = std::sqrt(D * D - (ra - rb) * (ra - rb));
  m = build_model(flywheels([](double t) { return t < ts ? tau0 : -tau0; },
                            ChainFidelity::quasi_steady, k, 0, 0, L0 + delta));
  Trajectory r = forward_dynamics(m, at_rest(m), options(1, 101));
  for (const std::string& w : r.stats.warnings) std::printf("  %s\n", w.c_str());
  return r;
}

// The lower span, from te on, pulls with the closed-form tension at rest + T / k.
void expect_lower_span_holds(const Model& m, const Trajectory& r, double te, double k) {
  const double T = upper_tension(tau0);
  const int Tl = r.reaction("chain.lower.tension");
  double worst_T = 0, worst_l = 0;
  for (Eigen::Index i = 0; i < r.time.size(); ++i) {
    if (r.time[i] < te + 1e-9) continue;
    worst_T = std::max(worst_T, std::abs(r.reactions(i, Tl) - T));
    worst_l = std::max(worst_l,
                       std::abs(value_at(m, r, i).lower_length - (m.chains[0].rest_lower + T / k)));
  }
  std::printf("  after %.9f s: max |T_l - T| %.3g N, max |l_l - (rest + T/k)| %.3g m\n", te,
              worst_T, worst_l);
  EXPECT_LT(worst_T, 1e-5 * T);
  EXPECT_LT(worst_l, 1e-9);
}

// The tension jumps from T to -T at ts; the lower span 1 mm longer (T / k = 0.43 mm): the upper
// span released to its rest length at ts and slack from there; the lower span engaging when a
// (decelerating at tau0 / I_a, b coasting) has taken up delta, as the inextensible chain's.
TEST(QssChain, TorqueStepReleasesTheSpanAndTheLowerEngagesAtTheClosedFormTime) {
  const double k = 1e5, delta = 1e-3, T = upper_tension(tau0);
  Model m;
  const Trajectory r = torque_step(k, delta, m);
  // before ts: the upper span at rest + T / k
  const ChainValue v = value_at(m, r, 49);  // t = 0.49 s
  EXPECT_NEAR(v.upper_length, m.chains[0].rest_upper + T / k, 1e-10);
  EXPECT_NEAR(time_of(r, "upper span released"), ts, 1e-9);
  // past the step the span was settled T / k short of its rest length (T = -tau0 / r_a): said
  int short_lines = 0;
  for (const std::string& w : r.stats.warnings)
    short_lines += w.find("upper span released") != std::string::npos &&
                   w.find("short of its rest length") != std::string::npos;
  EXPECT_EQ(short_lines, 1);
  EXPECT_NEAR(time_of(r, "slack from"), ts, 1e-9);
  const double te = ts + std::sqrt(2 * Ia * delta / (ra * tau0));
  const double t_engage = time_of(r, "lower span reaches its rest length");
  std::printf("engagement at %.9f s, closed form %.9f s (with delta - T/k: %.9f, + T/k: %.9f)\n",
              t_engage, te, ts + std::sqrt(2 * Ia * (delta - T / k) / (ra * tau0)),
              ts + std::sqrt(2 * Ia * (delta + T / k) / (ra * tau0)));
  EXPECT_NEAR(t_engage, te, 1e-7);
  expect_lower_span_holds(m, r, te, k);
}

// The default rest lengths (no dead zone): while the upper span pulls at rest + T / k the lower
// has T / k of slack; released to its rest length at the jump, the lower span is at its length
// and takes over at ts (no slack interval).
TEST(QssChain, TorqueStepHandsOverToTheLowerSpanAtTheStep) {
  const double k = 1e5;
  Model m;
  const Trajectory r = torque_step(k, 0, m);
  EXPECT_NEAR(time_of(r, "upper span released"), ts, 1e-9);
  EXPECT_NEAR(time_of(r, "direct handover"), ts, 1e-9);  // counted: no slack, no impulse
  EXPECT_TRUE(std::isnan(time_of(r, "slack from")));
  expect_lower_span_holds(m, r, ts, k);
}

// The sample at the step (t = ts, an output time) is the mode past it: slack with the dead zone,
// else the lower span pulling T. It was the upper span's, pushing with -T (the QSS half-bike's
// -27.8 N at its brake step while the warnings said slack).
TEST(QssChain, TheSampleAtATorqueStepIsTheModePastTheStep) {
  const double k = 1e5, T = upper_tension(tau0);
  for (double delta : {1e-3, 0.0}) {
    Model m;
    const Trajectory r = torque_step(k, delta, m);
    const int Tu = r.reaction("chain.upper.tension"), Tl = r.reaction("chain.lower.tension");
    ASSERT_EQ(r.time[50], ts);
    EXPECT_NEAR(r.reactions(49, Tu), T, 1e-5 * T);
    EXPECT_EQ(r.reactions(50, Tu), 0) << delta;
    EXPECT_NEAR(r.reactions(50, Tl), delta > 0 ? 0.0 : T, 1e-5 * T) << delta;
  }
}

TEST(QssChain, ConstantTorqueClosedFormTensionAndHeldLength) {
  const double k = 1e4;
  const Model m =
      build_model(flywheels([](double) { return tau0; }, ChainFidelity::quasi_steady, k));
  const Trajectory r = forward_dynamics(m, at_rest(m), options(1, 11));
  const int Tu = r.reaction("chain.upper.tension");
  const double T = upper_tension(tau0);
  double worst_T = 0, worst_l = 0;
  for (Eigen::Index i = 0; i < r.time.size(); ++i) {
    worst_T = std::max(worst_T, std::abs(r.reactions(i, Tu) - T));
    const ChainValue v = value_at(m, r, i);
    if (i > 0)
      worst_l = std::max(worst_l, std::abs(v.upper_length - (m.chains[0].rest_upper + T / k)));
  }
  std::printf(
      "QSS chain, constant torque: max |T_u - closed form| %.3g N (T_u %.6f N), "
      "max |l_u - (rest + T/k)| %.3g m (T/k = %.3g m)\n",
      worst_T, T, worst_l, T / k);
  EXPECT_LT(worst_T, 1e-6 * T);
  EXPECT_LT(worst_l, 1e-10);
  EXPECT_GT(T / k, 1e-3);                         // the stretch the check resolves
  EXPECT_EQ(held(m, 0), m.chains[0].rest_upper);  // reset when the run ends
}

TEST(QssChain, SwitchesAtTheClosedFormTimeAndHoldsTheLowerSpanAtRestPlusTOverK) {
  const double k = 1e4;
  const Model m = build_model(
      flywheels([](double t) { return tau0 * (1 - t / ts); }, ChainFidelity::quasi_steady, k));
  const Trajectory r = forward_dynamics(m, at_rest(m), options(1, 101));
  double t_switch = NAN;
  for (const std::string& w : r.stats.warnings) {
    std::printf("  %s\n", w.c_str());
    if (std::isnan(t_switch) && w.find("1 upper to lower") != std::string::npos)
      t_switch = std::stod(w.substr(w.find("first at t = ") + 13));  // the handover's summary
  }
  EXPECT_NEAR(t_switch, ts, 1e-7);
  const int Tu = r.reaction("chain.upper.tension"), Tl = r.reaction("chain.lower.tension");
  double worst_l = 0, worst_T = 0;
  for (Eigen::Index i = 1; i < r.time.size(); ++i) {
    const double t = r.time[i], T = upper_tension(tau0 * (1 - t / ts));
    const ChainValue v = value_at(m, r, i);
    if (t < ts - 1e-9) {
      worst_T = std::max(worst_T, std::abs(r.reactions(i, Tu) - T));
      worst_l = std::max(worst_l, std::abs(v.upper_length - (m.chains[0].rest_upper + T / k)));
    } else if (t > ts + 1e-9) {
      worst_T = std::max(worst_T, std::abs(r.reactions(i, Tl) + T));
      worst_l = std::max(worst_l, std::abs(v.lower_length - (m.chains[0].rest_lower - T / k)));
    }
  }
  std::printf("QSS chain, switching: max tension error %.3g N, max |l - (rest + T/k)| %.3g m\n",
              worst_T, worst_l);
  // the held length moves with T (linear in t): rest + T/k up to the projection tolerance
  EXPECT_LT(worst_l, 1e-9);
  EXPECT_LT(worst_T, 1e-5);
  EXPECT_EQ(held(m, 0), m.chains[0].rest_upper);
  EXPECT_EQ(held(m, 1), m.chains[0].rest_lower);
  // a run that throws (its step budget) puts the cells back too
  ForwardOptions o = options(1, 101);
  o.max_steps = 30;
  EXPECT_THROW(forward_dynamics(m, at_rest(m), o), Error);
  EXPECT_EQ(held(m, 0), m.chains[0].rest_upper);
  EXPECT_EQ(held(m, 1), m.chains[0].rest_lower);
  EXPECT_NO_THROW(forward_dynamics(m, at_rest(m), options(0.2, 3)));  // the cells released
}

// The stiff unilateral chain (damped, a viscous bearing: its ring-down gone by t = 1 s) against
// the QSS chain of the same stiffness: the spring force k e + c de/dt tends to the QSS tension as
// 1/k (its damping force c dT/dt / k, which the QSS law at zero rate leaves out, and the inertia
// of the stretch).
TEST(QssChain, StiffUnilateralChainForceTendsToTheQssTensionAsOneOverK) {
  auto ramp = [](double t) {
    const double x = std::min(t / 0.5, 1.0);
    return tau0 * x * x * x * (10 - 15 * x + 6 * x * x);
  };
  ForwardOptions o = options(1, 11);
  o.rtol = 1e-12;
  o.atol = 1e-14;
  std::vector<double> err;
  for (double k : {1e4, 1e5, 1e6}) {
    const Model full = build_model(flywheels(ramp, ChainFidelity::unilateral, k, 200, 0.05));
    ForwardOptions of = o;
    of.integrator = Integrator::cvode_bdf;
    const Trajectory rf = forward_dynamics(full, at_rest(full), of);
    const Model qss = build_model(flywheels(ramp, ChainFidelity::quasi_steady, k, 200, 0.05));
    const Trajectory rq = forward_dynamics(qss, at_rest(qss), o);
    const double Tf = value_at(full, rf, 10).upper_tension;
    const double Tq = rq.reactions(10, rq.reaction("chain.upper.tension"));
    err.push_back(Tf - Tq);
    std::printf("k = %.0e N/m: stiff chain T_u %.9f N, QSS %.9f N, difference %.3e N\n", k, Tf, Tq,
                err.back());
  }
  for (size_t i = 1; i < err.size(); ++i) {
    EXPECT_GT(err[i - 1] / err[i], 6) << i;
    EXPECT_LT(err[i - 1] / err[i], 16) << i;
  }
}

// An integrator that does not project is refused by name; the message offers only the explicit
// methods, as quasi-steady elements refuse cvode_bdf (the inextensible chain's offers it too).
TEST(QssChain, IntegratorsThatDoNotProjectAreRefusedWithTheMethodsThatWork) {
  const Model m =
      build_model(flywheels([](double) { return tau0; }, ChainFidelity::quasi_steady, 1e5));
  for (Integrator i : {Integrator::cvode_adams, Integrator::baumgarte}) {
    ForwardOptions o = options(0.1, 3);
    o.integrator = i;
    try {
      forward_dynamics(m, at_rest(m), o);
      ADD_FAILURE() << to_string(i) << " ran";
    } catch (const Error& e) {
      const std::string w = e.what();
      EXPECT_NE(w.find("chain 'chain' (quasi_steady)"), std::string::npos) << w;
      EXPECT_NE(w.find("use dopri5, erk6, erk8 or rk4"), std::string::npos) << w;
      EXPECT_EQ(w.find("cvode_bdf"), std::string::npos) << w;
    }
  }
}

}  // namespace qss_chain_test
