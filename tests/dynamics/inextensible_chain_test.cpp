// The inextensible chain (ChainFidelity::inextensible; src/model/inextensible_chains.cpp, the
// span switching in src/forward/chain_switching.cpp) against independent computations:
//  - two flywheels on fixed centres under a constant torque: the closed form
//    alpha_a = tau / (I_a + rho^2 I_b), T_u = I_b rho alpha_a / r_b (rho = r_a / r_b), the lower
//    span slack, the upper span's length held;
//  - the torque reversing at t_s: the switch to the lower span located at t_s, its tension the
//    closed form after; with a longer lower span (a dead zone delta) the chain goes slack at t_s
//    and the lower span engages at t_s + (6 t_s I_a delta / (r_a tau_0))^(1/3) with the impulse
//    of a perfectly inelastic engagement, rate / (r_a^2 / I_a + r_b^2 / I_b), and the energy
//    balance (the impact's loss counted as dissipated, 1/2 impulse rate);
//  - the stiff bilateral chain tends to it as 1/k (k = 1e4 .. 1e6);
//  - the energy balance with moving centres (the wheel sprocket on a swinging arm);
//  - the sparse engine against the dense one; integrators that do not project and Box2D refuse it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "dynamics/chain.hpp"
#include "forward/chain_log.hpp"
#include "mo2d/crosscheck.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/forward.hpp"
#include "mo2d/mo2d.hpp"

using namespace mo2d;

// named, not anonymous: the debug-asan unity build puts chain_test.cpp's ra, rb, ... beside these
namespace inextensible_chain_test {

constexpr double ra = 0.04, rb = 0.1, Ia = 0.01, Ib = 0.4, tau0 = 2.0, ts = 0.5;
constexpr double rho = ra / rb;

BodyDef disc(const std::string& name, Vec2 c, double inertia) {
  return {.name = name,
          .nodes = {{"C", c}, {"R", c + Vec2(0.05, 0.01)}},
          .mass = 1,
          .inertia = inertia};
}

// Two flywheels on ground axes 0.5 m apart, the drive torque `torque` on a, a chain.
System flywheels(std::function<double(double)> torque, ChainFidelity f, double k = 0,
                 double damping = 0, std::optional<double> rest_lower = {}, double bearing = 0,
                 std::optional<double> rest_upper = {}) {
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
               .rest_upper = rest_upper,
               .rest_lower = rest_lower,
               .fidelity = f});
  return s;
}

State at_rest(const Model& m) {
  return consistent_state(m, {.positions = {}, .velocities = {{"a.w", 0.0}}});
}

ForwardOptions options(double t1, int samples) {
  return {.t1 = t1, .samples = samples, .rtol = 1e-11, .atol = 1e-13, .max_seconds = 30};
}

// The time in the first warning containing `what` (after "t = ").
double time_of(const Trajectory& r, const std::string& what) {
  for (const std::string& w : r.stats.warnings) {
    if (w.find(what) == std::string::npos) continue;
    return std::stod(w.substr(w.find("t = ", w.find(what)) + 4));
  }
  ADD_FAILURE() << "no warning with '" << what << "'";
  return NAN;
}
double number_after(const std::string& w, const std::string& key) {
  const size_t at = w.find(key);
  if (at == std::string::npos) return NAN;
  return std::stod(w.substr(at + key.size()));
}
std::string warning_with(const Trajectory& r, const std::string& what) {
  for (const std::string& w : r.stats.warnings)
    if (w.find(what) != std::string::npos) return w;
  ADD_FAILURE() << "no warning with '" << what << "'";
  return "";
}

double alpha_a(double tau) {
  return tau / (Ia + rho * rho * Ib);
}
double upper_tension(double tau) {  // I_b alpha_b = r_b T_u, alpha_b = rho alpha_a
  return Ib * rho * alpha_a(tau) / rb;
}

TEST(InextensibleChain, FixedCentresAgainstTheClosedForm) {
  const Model m = build_model(flywheels([](double) { return tau0; }, ChainFidelity::inextensible));
  EXPECT_EQ(m.dof, 1);
  const Trajectory r = forward_dynamics(m, at_rest(m), options(1, 11));
  const int Tu = r.reaction("chain.upper.tension"), Tl = r.reaction("chain.lower.tension");
  for (Eigen::Index i = 0; i < r.time.size(); ++i) {
    // the multipliers are least-squares ones of the run's accelerations (accurate to ~1e-8)
    EXPECT_NEAR(r.reactions(i, Tu), upper_tension(tau0), 1e-7 * upper_tension(tau0)) << i;
    EXPECT_EQ(r.reactions(i, Tl), 0);
    EXPECT_NEAR(r.q1(i, r.rate_column("a.w")), alpha_a(tau0) * r.time[i], 1e-7) << i;
    const ChainValue v =
        chain_value(m, m.chains[0], r.q0.row(i).transpose(), r.q1.row(i).transpose(), r.time[i]);
    EXPECT_NEAR(v.upper_length, m.chains[0].rest_upper, 1e-10) << i;
  }
  std::printf("fixed centres: T_u %.9f N (closed form %.9f N)\n", r.reactions(10, Tu),
              upper_tension(tau0));
  EXPECT_LT(energy_balance_error(r), 1e-8);
}

// tau = tau0 (1 - t / ts): the traction reverses at ts. With the default rest lengths (both
// spans at their length on fixed centres) the lower span takes over at ts: one direct handover,
// counted in the run's closing line (src/forward/chain_log.hpp), no slack line.
TEST(InextensibleChain, TractionReversesAndTheLowerSpanTakesOverAtTheClosedFormTime) {
  const Model m = build_model(
      flywheels([](double t) { return tau0 * (1 - t / ts); }, ChainFidelity::inextensible));
  const Trajectory r = forward_dynamics(m, at_rest(m), options(1, 101));
  for (const std::string& w : r.stats.warnings) std::printf("  %s\n", w.c_str());
  const double t_switch = time_of(r, "direct handover");  // the first
  EXPECT_NEAR(t_switch, ts, 1e-7);
  EXPECT_NE(warning_with(r,
                         "chain 'chain': 1 direct handover between the taut spans (1 upper to "
                         "lower, 0 lower to upper")
                .find("the last at t = "),
            std::string::npos);
  for (const std::string& w : r.stats.warnings) EXPECT_EQ(w.find("slack from"), std::string::npos);
  const int Tu = r.reaction("chain.upper.tension"), Tl = r.reaction("chain.lower.tension");
  for (Eigen::Index i = 0; i < r.time.size(); ++i) {
    const double tau = tau0 * (1 - r.time[i] / ts);
    const double T = upper_tension(tau);  // < 0 after ts: the lower span pulls -T
    if (r.time[i] < ts - 1e-9) {
      EXPECT_NEAR(r.reactions(i, Tu), T, 1e-6) << r.time[i];
      EXPECT_EQ(r.reactions(i, Tl), 0) << r.time[i];
    } else if (r.time[i] > ts + 1e-9) {
      EXPECT_NEAR(r.reactions(i, Tl), -T, 1e-6) << r.time[i];
      EXPECT_EQ(r.reactions(i, Tu), 0) << r.time[i];
    }
  }
  EXPECT_LT(energy_balance_error(r), 1e-8);
}

// The step budget is the run's, shared by the legs between span switches: a budget one step
// short of what the whole run takes stops it, though each leg alone would fit in it.
TEST(InextensibleChain, TheStepBudgetIsTheRunsNotEachLegs) {
  const Model m = build_model(
      flywheels([](double t) { return tau0 * (1 - t / ts); }, ChainFidelity::inextensible));
  ForwardOptions o = options(1, 101);
  const Trajectory r = forward_dynamics(m, at_rest(m), o);
  ASSERT_GT(r.stats.steps, 2);
  o.max_steps = static_cast<int>(r.stats.steps) - 1;
  EXPECT_THROW(forward_dynamics(m, at_rest(m), o), Error);
}

// The warnings are not flooded: a torque reversing 30 times with the lower span delta longer
// (each reversal a slack interval and an engagement with an impulse: 4 lines) lists the first
// ChainLog::kListed (50) of its lines, in order, and counts the rest in a closing line.
TEST(InextensibleChain, SwitchLinesBeyondTheFirstFiftyAreCounted) {
  const double D = 0.5, L0 = std::sqrt(D * D - (ra - rb) * (ra - rb)), delta = 1e-3;
  const Model m =
      build_model(flywheels([](double t) { return tau0 * std::sin(6 * std::acos(-1.0) * t); },
                            ChainFidelity::inextensible, 0, 0, L0 + delta));
  ForwardOptions o = options(5, 51);
  o.rtol = 1e-8;
  o.atol = 1e-10;
  const Trajectory r = forward_dynamics(m, at_rest(m), o);
  int engaged = 0, unlisted = 0;
  for (const std::string& w : r.stats.warnings) {
    engaged += w.find("engagement, impulse") != std::string::npos;
    if (w.find("more switch lines not listed") != std::string::npos)
      unlisted = std::stoi(w.substr(w.find("': ") + 3));
  }
  std::printf("30 reversals: %zu warnings, %d engagements listed, %d lines not listed: %s\n",
              r.stats.warnings.size(), engaged, unlisted, r.stats.warnings.back().c_str());
  // the start line first, among the listed
  ASSERT_EQ(r.stats.warnings.size(), detail::ChainLog::kListed + 1u);
  EXPECT_NE(r.stats.warnings.front().find("(start)"), std::string::npos);
  EXPECT_GE(engaged, 10);
  EXPECT_GT(unlisted, 50);
  EXPECT_EQ(r.stats.warnings.back(), "chain 'chain': " + std::to_string(unlisted) +
                                         " more switch lines not listed (the first 50 are)");
}

// The lower span delta longer: slack from ts, the engagement located and its impulse.
TEST(InextensibleChain, SlackIntervalAndInelasticEngagementAgainstTheClosedForm) {
  const double D = 0.5, L0 = std::sqrt(D * D - (ra - rb) * (ra - rb)), delta = 1e-3;
  const Model m = build_model(flywheels([](double t) { return tau0 * (1 - t / ts); },
                                        ChainFidelity::inextensible, 0, 0, L0 + delta));
  const Trajectory r = forward_dynamics(m, at_rest(m), options(1, 101));
  for (const std::string& w : r.stats.warnings) std::printf("  %s\n", w.c_str());
  EXPECT_NEAR(time_of(r, "slack from"), ts, 1e-7);
  const double te = ts + std::cbrt(6 * ts * Ia * delta / (ra * tau0));
  const std::string w = warning_with(r, "reaches its rest length");
  const double t_engage = number_after(w, "t = ");
  EXPECT_NEAR(t_engage, te, 1e-7);
  // the rate of the lower span before the impact, r_a tau0 (t - ts)^2 / (2 ts I_a), and the
  // impulse that stops it
  const double rate = ra * tau0 * (te - ts) * (te - ts) / (2 * ts * Ia);
  const double P = rate / (ra * ra / Ia + rb * rb / Ib);
  EXPECT_NEAR(number_after(w, "impulse "), P, 1e-6 * P);
  EXPECT_NEAR(number_after(w, "kinetic energy lost "), 0.5 * P * rate, 1e-6 * P * rate);
  std::printf("engagement at %.9f s (closed form %.9f), impulse %.6g N s (closed form %.6g)\n",
              t_engage, te, number_after(w, "impulse "), P);
  // slack in between: no tension; taut lower span after, pulling
  const int Tu = r.reaction("chain.upper.tension"), Tl = r.reaction("chain.lower.tension");
  for (Eigen::Index i = 0; i < r.time.size(); ++i) {
    if (r.time[i] > ts + 1e-9 && r.time[i] < te - 1e-9) {
      EXPECT_EQ(r.reactions(i, Tu), 0);
      EXPECT_EQ(r.reactions(i, Tl), 0);
    }
    if (r.time[i] > te + 1e-9) {
      EXPECT_GT(r.reactions(i, Tl), 0);
    }
  }
  // K + W_drive balanced with the impact's loss counted as dissipated
  EXPECT_LT(energy_balance_error(r), 1e-8);
  EXPECT_NEAR(r.dissipated[r.time.size() - 1], 0.5 * P * rate, 1e-6 * P * rate);
}

// A torque step at an output time (ts, the 51st of 101 samples; and the last of a run that ends
// there): the sample there is the mode past the step, whose loads the sample's are: slack with a
// dead zone delta, else the lower span pulling with the closed-form tension. It was the mode
// before: the upper span pushing with -T (the half-bike's -1.56 N at 5 s and -27.8 N at 10 s
// while the warnings said slack from there).
TEST(InextensibleChain, TheSampleAtATorqueStepIsTheModePastTheStep) {
  const double D = 0.5, L0 = std::sqrt(D * D - (ra - rb) * (ra - rb)), T = upper_tension(tau0);
  for (double delta : {1e-3, 0.0}) {
    const Model m = build_model(flywheels([](double t) { return t < ts ? tau0 : -tau0; },
                                          ChainFidelity::inextensible, 0, 0, L0 + delta));
    for (int samples : {101, 51}) {
      if (delta == 0 && samples == 51) continue;  // the run's end at the step: with slack
      SCOPED_TRACE("delta " + std::to_string(delta) + ", samples " + std::to_string(samples));
      const Trajectory r = forward_dynamics(m, at_rest(m), options((samples - 1) * 0.01, samples));
      const int Tu = r.reaction("chain.upper.tension"), Tl = r.reaction("chain.lower.tension");
      ASSERT_EQ(r.time[50], ts);
      EXPECT_NEAR(r.reactions(49, Tu), T, 1e-6 * T);  // before the step: the upper span pulls
      EXPECT_EQ(r.reactions(50, Tu), 0);
      EXPECT_NEAR(r.reactions(50, Tl), delta > 0 ? 0.0 : T, 1e-6 * T);
      std::printf("delta %g, %d samples: at ts T_u %g N, T_l %g N (closed form 0, %g N)\n", delta,
                  samples, r.reactions(50, Tu), r.reactions(50, Tl), delta > 0 ? 0.0 : T);
    }
  }
}

// A chain starts in the mode its span lengths give at the initial positions, where they are: both
// spans with slack, slack; a span at its length (the other with slack), that span taut. The
// build and the consistent state assembled the mechanism onto the upper span's row: the
// sprockets turned to take up its slack (on the half-bike's swinging arm, the arm moved by
// -2.04e-3 rad), and with only the lower span at its length that span was then delta too long
// ("longer than its rest length in the initial state").
TEST(InextensibleChain, StartsWhereItIsInTheModeOfItsSpanLengths) {
  const double D = 0.5, L0 = std::sqrt(D * D - (ra - rb) * (ra - rb)), delta = 1e-3;
  struct Case {
    double upper, lower, torque;
    const char* start;
  };
  for (const Case& c :
       {Case{L0 + delta, L0 + delta, tau0, "slack"}, Case{L0, L0 + delta, tau0, "upper span taut"},
        Case{L0 + delta, L0, -tau0, "lower span taut"}}) {
    SCOPED_TRACE(c.start);
    const double tau = c.torque;
    try {
      const Model m = build_model(flywheels(
          [tau](double) { return tau; }, ChainFidelity::inextensible, 0, 0, c.lower, 0, c.upper));
      const State s = at_rest(m);
      for (const VectorXd& q0 : {m.q0, s.q0}) {
        const ChainValue v = chain_value(m, m.chains[0], q0, s.q1, 0);
        EXPECT_NEAR(v.upper_length, L0, 1e-12);
        EXPECT_NEAR(v.lower_length, L0, 1e-12);
      }
      const Trajectory r = forward_dynamics(m, s, options(0.01, 2));
      EXPECT_EQ(r.stats.warnings.at(0),
                std::string("chain 'chain': ") + c.start + " at t = 0 s (start)");
    } catch (const Error& e) {
      ADD_FAILURE() << e.what();
    }
  }
}

// The torque reversing by a step at ts (+tau0 to -tau0), the lower span delta longer: the upper
// span's tension jumps below 0 at ts, the chain is slack from ts and the lower span engages at
// ts + sqrt(2 I_a delta / (r_a tau0)) (a decelerates at tau0 / I_a, b keeps its rate). A located
// event at a jump of the stop condition must be the state past it, whatever the tolerance: at
// loose tolerances the root finding's last try fell before the jump, where no condition had
// crossed, and the switching took the smallest one, the lower span's slack, for "both spans
// taut" (the half-bike's torque steps at 5 and 10 s with dopri5 at rtol 1e-4 and 1e-6). And with
// CVODE the engagement's located root, an interpolant inside a long step, was off the constraint
// manifolds by 5e-6 of the size (a drift error at rtol 1e-4 and 1e-5).
TEST(InextensibleChain, TorqueStepIsLocatedPastTheStepAtLooseTolerances) {
  const double D = 0.5, L0 = std::sqrt(D * D - (ra - rb) * (ra - rb)), delta = 1e-3;
  const Model m = build_model(flywheels([](double t) { return t < ts ? tau0 : -tau0; },
                                        ChainFidelity::inextensible, 0, 0, L0 + delta));
  const double te = ts + std::sqrt(2 * Ia * delta / (ra * tau0));
  for (Integrator integ : {Integrator::dopri5, Integrator::cvode_bdf})
    for (double rtol : {1e-4, 1e-5, 1e-6, 1e-7, 1e-8}) {
      ForwardOptions o = options(1, 101);
      o.integrator = integ;
      o.rtol = rtol;
      o.atol = 1e-2 * rtol;
      SCOPED_TRACE(std::string(to_string(integ)) + " rtol " + std::to_string(rtol));
      try {
        const Trajectory r = forward_dynamics(m, at_rest(m), o);
        EXPECT_NEAR(time_of(r, "slack from"), ts, 1e-9);
        // the slack interval to 1% at rtol 1e-4 (seen: dopri5 7.9e-6 s at rtol 1e-4 to 3.9e-9 s
        // at 1e-8, the span's length threshold tol_l = atol: (te - ts) atol / (2 delta); CVODE
        // 2e-7 s to 6e-6 s)
        EXPECT_NEAR(time_of(r, "reaches its rest length"), te, 1e-2 * (te - ts));
        // CVODE's located root is its interpolant, projected (else 5e-6 of the size: an error)
        EXPECT_LT(r.stats.max_drift, 1e-9);
        std::printf("%s rtol %.0e: slack from %.12f s, engagement error %.2e s, max drift %.1e\n",
                    to_string(integ), rtol, time_of(r, "slack from"),
                    time_of(r, "reaches its rest length") - te, r.stats.max_drift);
      } catch (const Error& e) {
        ADD_FAILURE() << e.what();
      }
    }
}

// The stiff chain (bilateral, damped, a viscous bearing) tends to the inextensible one as 1/k.
TEST(InextensibleChain, StiffChainTendsToItAsOneOverK) {
  auto ramp = [](double t) {
    const double x = std::min(t / 0.5, 1.0);
    return tau0 * x * x * x * (10 - 15 * x + 6 * x * x);
  };
  ForwardOptions o = options(1, 11);
  o.rtol = 1e-12;
  o.atol = 1e-14;
  const Model rigid =
      build_model(flywheels(ramp, ChainFidelity::inextensible, 0, 0, std::nullopt, 0.05));
  const Trajectory rr = forward_dynamics(rigid, at_rest(rigid), o);
  const double T_inext = rr.reactions(10, rr.reaction("chain.upper.tension"));
  EXPECT_GT(T_inext, 10);
  // unilateral: the upper span carries it all (the lower slack); bilateral: both spans stretch
  // from their rest lengths, the lower one pushing, and the net T_u - T_l carries it
  for (ChainFidelity f : {ChainFidelity::unilateral, ChainFidelity::bilateral}) {
    std::vector<double> err;
    for (double k : {1e4, 1e5, 1e6}) {
      const Model m = build_model(flywheels(ramp, f, k, 200, std::nullopt, 0.05));
      const Trajectory r = forward_dynamics(
          m, consistent_state(m, {.positions = {}, .velocities = {{"a.w", 0.0}, {"b.w", 0.0}}}), o);
      const ChainValue v =
          chain_value(m, m.chains[0], r.q0.row(10).transpose(), r.q1.row(10).transpose(), 1.0);
      err.push_back(v.upper_tension - v.lower_tension - T_inext);
      std::printf("%s, k = %.0e N/m: T_u %.9f N, T_l %.9f N, inextensible %.9f N, error %.3e N\n",
                  f == ChainFidelity::unilateral ? "unilateral" : "bilateral", k, v.upper_tension,
                  v.lower_tension, T_inext, err.back());
    }
    EXPECT_LT(std::abs(err[2]), 1e-6 * T_inext);
    // 1/k: a factor 10 per decade, from the same side. The bilateral net T_u - T_l is the
    // difference of two tensions k e of 22 N each, its 1/k error at 1e6 N/m (~4e-7 N) below what
    // the positions' integration error (~5e-13 m at rtol 1e-12) times 2k leaves: 1e4 -> 1e5 only.
    const size_t decades = f == ChainFidelity::unilateral ? 2 : 1;
    for (size_t i = 1; i <= decades; ++i) {
      EXPECT_GT(err[i - 1] / err[i], 6) << i;
      EXPECT_LT(err[i - 1] / err[i], 16) << i;
    }
  }
}

// Moving centres: the wheel sprocket on an arm swinging under gravity (the wrap term in the row),
// the lower span long enough to stay slack.
TEST(InextensibleChain, EnergyBalanceWithMovingCentres) {
  System s("swing_arm");
  s.add_ground_node("O", {0, 0});
  s.add_ground_node("P", {0.08, -0.03});
  s.add_body(disc("drive", {0, 0}, 2e-3));
  s.add_body({.name = "arm",
              .nodes = {{"P", {0.08, -0.03}}, {"E", {0.55, 0.02}}},
              .mass = 3,
              .inertia = 0.08});
  s.add_body(disc("wheel", {0.55, 0.02}, 0.3));
  s.add_revolute({.name = "p_drive", .node_a = "ground.O", .node_b = "drive.C"});
  s.add_revolute({.name = "pivot", .node_a = "ground.P", .node_b = "arm.P"});
  s.add_revolute({.name = "axle", .node_a = "arm.E", .node_b = "wheel.C"});
  s.add_torsional_spring({.name = "suspension", .joint = "pivot", .stiffness = 400});
  s.add_torque({.name = "drive", .body = "drive", .torque = [](double) { return 3.0; }});
  const Vec2 d(0.55, 0.02);
  const double L0 = std::sqrt(d.squaredNorm() - (ra - rb) * (ra - rb));
  s.add_chain({.name = "chain",
               .body_a = "drive",
               .centre_a = {0, 0},
               .radius_a = ra,
               .body_b = "wheel",
               .centre_b = d,
               .radius_b = rb,
               .rest_lower = L0 + 0.05,
               .fidelity = ChainFidelity::inextensible});
  s.set_gravity({0, -9.81});
  const Model m = build_model(s);
  const State s0 =
      consistent_state(m, {.positions = {}, .velocities = {{"drive.w", 0.0}, {"arm.w", 0.0}}});
  const Trajectory r = forward_dynamics(m, s0, options(1, 101));
  for (const std::string& w : r.stats.warnings) std::printf("  %s\n", w.c_str());
  double lo = 1e9, hi = -1e9, drift = 0;
  for (Eigen::Index i = 0; i < r.time.size(); ++i) {
    const double a = std::atan2(r.q0(i, m.coordinate("arm.E.y")), r.q0(i, m.coordinate("arm.E.x")));
    lo = std::min(lo, a);
    hi = std::max(hi, a);
    const ChainValue v =
        chain_value(m, m.chains[0], r.q0.row(i).transpose(), r.q1.row(i).transpose(), r.time[i]);
    drift = std::max(drift, std::abs(v.upper_length - m.chains[0].rest_upper));
  }
  const double Tmax = r.reactions.col(r.reaction("chain.upper.tension")).maxCoeff();
  std::printf(
      "moving centres: centre line swings %.3f rad, T_u up to %.1f N, drift %.2e m, "
      "energy balance error %.2e J\n",
      hi - lo, Tmax, drift, energy_balance_error(r));
  EXPECT_GT(hi - lo, 0.02);  // the centre line turns
  EXPECT_GT(Tmax, 10);
  EXPECT_LT(drift, 1e-10);
  EXPECT_LT(energy_balance_error(r), 1e-7);
}

TEST(InextensibleChain, SparseEngineAgreesWithDense) {
  const Model m = build_model(
      flywheels([](double t) { return tau0 * (1 - t / ts); }, ChainFidelity::inextensible));
  ForwardOptions o = options(1, 11);
  o.integrator = Integrator::dopri5;
  o.rtol = 1e-10;
  o.atol = 1e-12;
  o.linear_algebra = LinearAlgebra::dense;
  const Trajectory d = forward_dynamics(m, at_rest(m), o);
  o.linear_algebra = LinearAlgebra::sparse;
  const Trajectory s = forward_dynamics(m, at_rest(m), o);
  EXPECT_TRUE(s.stats.sparse);
  EXPECT_FALSE(d.stats.sparse);
  EXPECT_LT((d.q1 - s.q1).lpNorm<Eigen::Infinity>(), 1e-7);
  EXPECT_LT((d.reactions - s.reactions).lpNorm<Eigen::Infinity>(), 1e-5);
  EXPECT_NEAR(time_of(d, "direct handover"), ts, 1e-7);
  EXPECT_NEAR(time_of(s, "direct handover"), ts, 1e-7);
}

TEST(InextensibleChain, IntegratorsThatDoNotProjectAndBox2DRefuseIt) {
  const Model m = build_model(flywheels([](double) { return tau0; }, ChainFidelity::inextensible),
                              {.reduction = Reduction::none});
  for (Integrator i : {Integrator::cvode_adams, Integrator::baumgarte}) {
    ForwardOptions o = options(0.1, 3);
    o.integrator = i;
    try {
      forward_dynamics(m, at_rest(m), o);
      ADD_FAILURE() << to_string(i) << " ran";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("chain 'chain' (inextensible)"), std::string::npos)
          << e.what();
      EXPECT_NE(std::string(e.what()).find(to_string(i)), std::string::npos) << e.what();
    }
  }
  try {
    crosscheck_forward(m, at_rest(m), 0.1);
    ADD_FAILURE() << "an inextensible chain was translated to Box2D";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("chain 'chain' is not translated"), std::string::npos)
        << e.what();
  }
}

}  // namespace inextensible_chain_test
