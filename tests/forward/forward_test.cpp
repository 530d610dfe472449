// Forward dynamics against closed forms, conservation laws, inverse dynamics, and the IFToMM
// double four-bar reference; the error of each integrator falls at its expected rate.
#include "mo2d/forward.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"

using namespace mo2d;

namespace {

// Complete elliptic integral of the first kind by the arithmetic-geometric mean.
double elliptic_K(double k) {
  double a = 1, b = std::sqrt(1 - k * k);
  for (int i = 0; i < 40; ++i) {
    const double an = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = an;
  }
  return std::numbers::pi / (2 * a);
}

struct Pendulum {
  Model model;
  State start;
  double quarter_period;
};

// Point mass on a massless link released at rest `amplitude` from the bottom.
Pendulum released_pendulum(double amplitude, double L = 1.0, double g = 9.81) {
  auto ex =
      mechanisms::pendulum({.L = L, .m = 1.0, .g = g, .theta0 = -std::numbers::pi / 2 - amplitude});
  Model m = build_model(ex.system);
  State s = consistent_state(m, {.positions = {}, .velocities = {{"link.w", 0.0}}});
  return {std::move(m), s, std::sqrt(L / g) * elliptic_K(std::sin(amplitude / 2))};
}

// Time of the first passage at the bottom (tip x = 0), by the integrator's root finding.
double bottom_passage(const Pendulum& p, ForwardOptions o) {
  const int ix = p.model.coordinate("link.P.x");
  o.t1 = 2 * p.quarter_period;
  o.samples = 3;
  o.stop_when = [ix](double, const VectorXd& q0, const VectorXd&) { return q0[ix]; };
  const Trajectory r = forward_dynamics(p.model, p.start, o);
  EXPECT_TRUE(r.stats.stopped_by_event);
  return r.stats.t_end;
}

}  // namespace

// The period 4 sqrt(L/g) K(sin(theta0/2)) at large amplitudes, to 1e-9 relative.
TEST(Forward, PendulumPeriodAtLargeAmplitudes) {
  for (double amplitude : {0.5, 2.0, 3.0}) {
    const Pendulum p = released_pendulum(amplitude);
    ForwardOptions bdf{.integrator = Integrator::cvode_bdf, .rtol = 1e-13, .atol = 1e-13};
    ForwardOptions adams{.integrator = Integrator::cvode_adams, .rtol = 1e-13, .atol = 1e-13};
    ForwardOptions rk4{.integrator = Integrator::rk4, .step = 1e-3};
    ForwardOptions dopri5{.integrator = Integrator::dopri5, .rtol = 1e-12, .atol = 1e-12};
    ForwardOptions erk6{.integrator = Integrator::erk6, .rtol = 1e-12, .atol = 1e-12};
    ForwardOptions erk8{.integrator = Integrator::erk8, .rtol = 1e-12, .atol = 1e-12};
    for (const auto& o : {bdf, adams, rk4, dopri5, erk6, erk8}) {
      const double t = bottom_passage(p, o);
      EXPECT_LE(std::abs(t - p.quarter_period) / p.quarter_period, 1e-9)
          << to_string(o.integrator) << " amplitude " << amplitude;
    }
  }
}

// RK4 is fourth order: halving the step divides the error by ~16.
TEST(Forward, Rk4ConvergesAtFourthOrder) {
  const Pendulum p = released_pendulum(2.0);
  auto err = [&](double h) {
    return std::abs(bottom_passage(p, {.integrator = Integrator::rk4, .step = h}) -
                    p.quarter_period);
  };
  const double e1 = err(0.04), e2 = err(0.02), e3 = err(0.01);
  EXPECT_GT(e1 / e2, 11.0);
  EXPECT_LT(e1 / e2, 22.0);
  EXPECT_GT(e2 / e3, 11.0);
  EXPECT_LT(e2 / e3, 22.0);
}

// Dormand-Prince 5(4) with elementary step control: the error of a passage time is proportional to
// the tolerance (local error per unit step ~ tol), so it falls ~10x per decade of tolerance.
TEST(Forward, Dopri5ErrorFollowsTolerance) {
  const Pendulum p = released_pendulum(2.0);
  auto err = [&](double tol) {
    return std::abs(
        bottom_passage(p, {.integrator = Integrator::dopri5, .rtol = tol, .atol = tol}) -
        p.quarter_period);
  };
  const double e6 = err(1e-6), e8 = err(1e-8), e10 = err(1e-10);
  EXPECT_LT(e6, 1e-4);
  EXPECT_GT(e6 / e8, 20.0);
  EXPECT_LT(e6 / e8, 500.0);
  EXPECT_GT(e8 / e10, 20.0);
  EXPECT_LT(e8 / e10, 500.0);
}

// The order of ARKODE's Verner 6(5) and Fehlberg 8(7) tables in mo2d's loop, measured: over four
// decades of tolerance the error and the number of steps N change together as error ~ N^-order
// (the step length ~ 1/N). Pendulum at 2 rad, 21 quarter periods (the tip at the bottom, x = 0),
// errors from ~1e-5 to ~1e-10, above round-off.
TEST(Forward, HighOrderMethodsConvergeAtTheirOrder) {
  const Pendulum p = released_pendulum(2.0);
  const int ix = p.model.coordinate("link.P.x");
  for (auto [integ, order] : {std::pair{Integrator::erk6, 6.0}, std::pair{Integrator::erk8, 8.0}}) {
    auto run = [&](double tol) {
      const Trajectory r = forward_dynamics(p.model, p.start,
                                            {.t0 = 0,
                                             .t1 = 21 * p.quarter_period,
                                             .samples = 2,
                                             .integrator = integ,
                                             .rtol = tol,
                                             .atol = tol});
      return std::pair{std::abs(r.q0(1, ix)), static_cast<double>(r.stats.steps)};
    };
    const auto [e1, n1] = run(1e-6);
    const auto [e2, n2] = run(1e-10);
    const double measured = std::log(e1 / e2) / std::log(n2 / n1);
    std::printf("%s: measured order %.2f (%.2e in %.0f steps, %.2e in %.0f)\n", to_string(integ),
                measured, e1, n1, e2, n2);
    EXPECT_GT(measured, order - 1)
        << to_string(integ) << ": " << e1 << " in " << n1 << " steps, " << e2 << " in " << n2;
    EXPECT_LT(measured, order + 1.5)
        << to_string(integ) << ": " << e1 << " in " << n1 << " steps, " << e2 << " in " << n2;
  }
}

// CVODE's error falls as its tolerance is tightened (BDF and Adams): the tip of the pendulum must
// be at the bottom (x = 0) exactly at the quarter period.
TEST(Forward, CvodeErrorFallsWithTolerance) {
  const Pendulum p = released_pendulum(2.0);
  const int ix = p.model.coordinate("link.P.x");
  for (auto integ : {Integrator::cvode_bdf, Integrator::cvode_adams}) {
    double previous = INFINITY;
    for (double tol : {1e-5, 1e-7, 1e-9, 1e-11}) {
      const Trajectory r = forward_dynamics(p.model, p.start,
                                            {.t0 = 0,
                                             .t1 = p.quarter_period,
                                             .samples = 2,
                                             .integrator = integ,
                                             .rtol = tol,
                                             .atol = tol});
      const double e = std::abs(r.q0(1, ix));
      EXPECT_LT(e, 0.5 * previous) << to_string(integ) << " tol " << tol;
      EXPECT_LT(e, 1000 * tol) << to_string(integ) << " tol " << tol;
      previous = e;
    }
  }
}

// A conservative double pendulum in nodal form (two uniform bars) and the crank-rocker four-bar
// under gravity, passive: energy is conserved and the constraints stay at round-off.
TEST(Forward, EnergyIsConserved) {
  System dp("double_pendulum");
  dp.add_ground_node("O", {0, 0});
  dp.add_body({.name = "upper",
               .nodes = {{"O", {0, 0}}, {"A", {0.3, 0}}},
               .mass = 1,
               .inertia = 0.09 / 12,
               .com = CenterOfMass::between("O", "A", 0.5)});
  dp.add_body({.name = "lower",
               .nodes = {{"A", {0.3, 0}}, {"B", {0.6, 0}}},
               .mass = 1,
               .inertia = 0.09 / 12,
               .com = CenterOfMass::between("A", "B", 0.5)});
  dp.add_revolute({.name = "shoulder", .node_a = "ground.O", .node_b = "upper.O"});
  dp.add_revolute({.name = "elbow", .node_a = "upper.A", .node_b = "lower.A"});
  dp.set_gravity({0, -9.81});
  const Model m = build_model(dp);
  const State s =
      consistent_state(m, {.positions = {}, .velocities = {{"upper.w", 0.0}, {"lower.w", 0.0}}});
  // 100 periods: the double pendulum swings in ~1.1 s (110 s), the four-bar's crank turns in
  // ~0.49 s (50 s). RK4 with projection, h = 2.5e-4 s (measured: 6.8e-10 and 6.4e-10; at
  // h = 5e-4 the drift is 1.8e-8 and 3.7e-8, RK4's h^4 error accumulating over the run).
  const Trajectory r = forward_dynamics(
      m, s, {.t0 = 0, .t1 = 110, .samples = 1101, .integrator = Integrator::rk4, .step = 2.5e-4});
  const VectorXd E = r.kinetic + r.potential;
  EXPECT_LE((E.array() - E[0]).abs().maxCoeff() / r.kinetic.maxCoeff(), 1e-8);
  EXPECT_LE(r.residuals.maxCoeff(), 1e-10);

  const Model fb = build_model(mechanisms::fourbar().system);
  const State s2 = consistent_state(fb, {.positions = {}, .velocities = {{"crank.w", 6.0}}});
  const Trajectory r2 = forward_dynamics(
      fb, s2, {.t0 = 0, .t1 = 50, .samples = 501, .integrator = Integrator::rk4, .step = 2.5e-4});
  const VectorXd E2 = r2.kinetic + r2.potential;
  EXPECT_LE((E2.array() - E2[0]).abs().maxCoeff() / r2.kinetic.maxCoeff(), 1e-8);
  EXPECT_LE(r2.residuals.maxCoeff(), 1e-10);
  const int ia = r2.column("crank.angle");
  EXPECT_GT(std::abs(r2.q0(r2.time.size() - 1, ia) - r2.q0(0, ia)), 100 * 2 * std::numbers::pi);
}

// Round trip: the Whitworth crank torque from inverse dynamics, replayed forward from the same
// initial state, reproduces the prescribed crank angle pi t / 2 over 16 s.
TEST(Forward, WhitworthInverseForwardRoundTrip) {
  auto ex = mechanisms::whitworth();
  const Model m = build_model(ex.system);
  InverseOptions io = ex.run;
  io.samples = 2;
  const Trajectory inv = inverse_dynamics(m, ex.motion, io);
  State s{0, inv.q0.row(0).transpose(), inv.q1.row(0).transpose()};
  ForwardOptions o{.t0 = 0, .t1 = 16, .samples = 161, .integrator = Integrator::rk4, .step = 2e-3};
  o.efforts = efforts_from_inverse(m, ex.motion);
  const Trajectory r = forward_dynamics(m, s, o);
  const int ia = r.column("crank.angle");
  double worst = 0;
  for (int i = 0; i < r.time.size(); ++i)
    worst = std::max(worst, std::abs(r.q0(i, ia) - std::numbers::pi / 2 * r.time[i]));
  EXPECT_LE(worst, 1e-6);
  // forward reactions agree with the inverse-dynamics reactions at the same instants (the
  // trajectories agree to ~1e-9; reactions are O(1) N)
  InverseOptions io2 = ex.run;
  io2.samples = 161;
  const Trajectory inv2 = inverse_dynamics(m, ex.motion, io2);
  EXPECT_EQ(r.reaction_labels, inv2.reaction_labels);
  EXPECT_LE((r.reactions - inv2.reactions).cwiseAbs().maxCoeff(),
            1e-6 * inv2.reactions.cwiseAbs().maxCoeff());
  EXPECT_LE((r.efforts - inv2.efforts).cwiseAbs().maxCoeff(), 1e-9);
  // the work of the input equals the change of kinetic energy (no gravity, no dissipation)
  const int last = static_cast<int>(r.time.size()) - 1;
  EXPECT_NEAR(r.input_work[last], r.kinetic[last] - r.kinetic[0], 1e-6);
}

// efforts_from_inverse asked at a time far from the last (as the re-integrations of
// locate_extremes ask it): the torque of inverse dynamics at that time. Before it walked there,
// Newton from the far prediction landed on the other assembly mode: -0.401 N m instead of -0.635
// at 0.2 s after 1.0 s.
TEST(Forward, EffortsFromInverseAfterAJumpInTime) {
  const Scene scene = load_scene(std::string(MO2D_MECHANISMS_DIR) + "/fourbar.yaml");
  const Model model = build_scene_model(scene);
  const InverseOptions io = inverse_options(scene);
  const auto law = efforts_from_inverse(model, scene.motion, io);
  for (const double t : {1.0, 0.2, 1.7, 0.9}) {
    const double u = law[0](t);
    InverseOptions o = io;  // the reference: a run from 0 to t, sample after sample
    o.t1 = t;
    o.samples = 201;
    const double reference = inverse_dynamics(model, scene.motion, o).efforts(200, 0);
    EXPECT_NEAR(u, reference, 1e-12) << "at t = " << t;
  }
}

// The three formulations give the same motion where the constraint Jacobian is regular.
TEST(Forward, FormulationsAgree) {
  const Model fb = build_model(mechanisms::fourbar().system);
  const State s = consistent_state(fb, {.positions = {}, .velocities = {{"crank.w", 3.0}}});
  ForwardOptions o{.t0 = 0, .t1 = 1, .samples = 11, .integrator = Integrator::rk4, .step = 1e-3};
  o.formulation = Formulation::augmented_lagrangian;
  const Trajectory a = forward_dynamics(fb, s, o);
  o.formulation = Formulation::lagrange;
  const Trajectory b = forward_dynamics(fb, s, o);
  o.formulation = Formulation::null_space;
  const Trajectory c = forward_dynamics(fb, s, o);
  EXPECT_LE((a.q0 - b.q0).cwiseAbs().maxCoeff(), 1e-11);
  EXPECT_LE((a.q0 - c.q0).cwiseAbs().maxCoeff(), 1e-11);
  EXPECT_LE((a.q1 - c.q1).cwiseAbs().maxCoeff(), 1e-10);
}

// Baumgarte (Mo2DPack's mode) lets positions drift; projection keeps them at round-off.
TEST(Forward, BaumgarteDriftsProjectionDoesNot) {
  const Model fb = build_model(mechanisms::fourbar().system);
  const State s = consistent_state(fb, {.positions = {}, .velocities = {{"crank.w", 6.0}}});
  ForwardOptions o{.t0 = 0, .t1 = 5, .samples = 51, .step = 5e-3};
  o.integrator = Integrator::baumgarte;
  const Trajectory b = forward_dynamics(fb, s, o);
  o.integrator = Integrator::rk4;
  const Trajectory p = forward_dynamics(fb, s, o);
  EXPECT_LE(p.residuals.col(0).maxCoeff(), 1e-12);
  EXPECT_GT(b.residuals.col(0).maxCoeff(), 1e3 * p.residuals.col(0).maxCoeff());
}

// The IFToMM double four-bar goes through its singular (all joints collinear) positions ten times
// in 10 s; the run must stay on the physical branch. Reference: the parallelogram reduction
// 3 phi'' = -3.5 g cos(phi), integrated in 40-digit arithmetic (shared/notes/peers.md).
TEST(Forward, DoubleFourBarStaysOnThePhysicalBranch) {
  const Model m = build_model(mechanisms::double_fourbar());
  const State s = consistent_state(m, {.positions = {}, .velocities = {{"crank0.w", -1.0}}});
  const double rx = 0.328458111541, ry = 0.944518538179;
  const int ix = m.coordinate("crank0.B.x"), iy = m.coordinate("crank0.B.y");
  auto final_error = [&](ForwardOptions o) {
    o.t0 = 0;
    o.t1 = 10;
    o.samples = 11;
    const Trajectory r = forward_dynamics(m, s, o);
    const int k = static_cast<int>(r.time.size()) - 1;
    return std::hypot(r.q0(k, ix) - rx, r.q0(k, iy) - ry);
  };
  EXPECT_LE(final_error({.integrator = Integrator::rk4, .step = 1e-3}), 1e-8);
  EXPECT_LE(final_error({.integrator = Integrator::rk4, .step = 1e-4}), 1e-6);
  // the high-order methods down to tol 1e-11: on the branch, the error following the tolerance
  // (error / tol measured: erk6 12 ... 854, erk8 12 ... 390; error per step control adds up
  // over the steps). Without the projected stages of steps next to a singular instant
  // (forward_rk.cpp) erk8 left the branch below 1e-8 (2e-2 away at 1e-10).
  // erk6 at 1e-11 is left out: it falls back on regularized accelerations at some passages and
  // its end point is rounding-sensitive (1.6e-9 with the dense Schur solve, 1.7e-8 with the
  // structured one: docs/performance.md)
  for (Integrator i : {Integrator::erk6, Integrator::erk8})
    for (double tol : {1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11}) {
      if (i == Integrator::erk6 && tol < 1e-10) continue;
      EXPECT_LE(final_error({.integrator = i, .rtol = tol, .atol = tol}), 1000 * tol)
          << to_string(i) << " tol " << tol;
    }
  // a branch flip ends near (1, 0), 0.9 m away; BDF at a loose tolerance must stay close
  EXPECT_LE(final_error({.integrator = Integrator::cvode_bdf, .rtol = 1e-8, .atol = 1e-8}), 1e-3);
}

// Where the stages of a step fall within ~1e-4 s of a singular instant, the regularized
// accelerations are off by O(1); the step is redone with other lengths so that its stages avoid
// the instant. With 41 output times the RK4 grid (h = 0.25 s / 63) puts a stage there: without
// the step-over the final error was 1.1e-3 (it is 3.3e-7 with 11 output times and h = 4e-3).
TEST(Forward, SingularInstantsAreSteppedOver) {
  const Model m = build_model(mechanisms::double_fourbar());
  const State s = consistent_state(m, {.positions = {}, .velocities = {{"crank0.w", -1.0}}});
  const int ix = m.coordinate("crank0.B.x"), iy = m.coordinate("crank0.B.y");
  for (const ForwardOptions& o :
       {ForwardOptions{
            .t0 = 0, .t1 = 10, .samples = 41, .integrator = Integrator::rk4, .step = 4e-3},
        ForwardOptions{.t0 = 0,
        .t1 = 10,
        .samples = 11,
        .integrator = Integrator::dopri5,
        .rtol = 1e-9,
        .atol = 1e-9},
        // with 101 output times one falls 0.7 ms after a singular instant (t = 4.59925 s)
        ForwardOptions{.t0 = 0,
        .t1 = 10,
        .samples = 101,
        .integrator = Integrator::dopri5,
        .rtol = 1e-9,
        .atol = 1e-9},
        ForwardOptions{.t0 = 0,
        .t1 = 10,
        .samples = 11,
        .integrator = Integrator::dopri5,
        .rtol = 3e-9,
        .atol = 3e-9},
        // the high-order methods, with an output time next to a singular instant too
        ForwardOptions{.t0 = 0,
        .t1 = 10,
        .samples = 101,
        .integrator = Integrator::erk6,
        .rtol = 1e-8,
        .atol = 1e-8},
        ForwardOptions{.t0 = 0,
        .t1 = 10,
        .samples = 101,
        .integrator = Integrator::erk8,
        .rtol = 1e-8,
        .atol = 1e-8}}) {
    const Trajectory r = forward_dynamics(m, s, o);
    const int k = static_cast<int>(r.time.size()) - 1;
    // rk4 at 4e-3: 3.3e-7; dopri5: ~370 x tol (3.7e-7 at 1e-9, 1.1e-6 at 3e-9)
    EXPECT_LE(std::hypot(r.q0(k, ix) - 0.328458111541, r.q0(k, iy) - 0.944518538179),
              o.integrator == Integrator::rk4 ? 1e-6 : 1000 * o.rtol)
        << to_string(o.integrator) << " rtol " << o.rtol << " samples " << o.samples;
    if (o.integrator == Integrator::rk4) {
      EXPECT_GT(r.stats.stepped_over, 0);
      const bool said = std::any_of(r.stats.warnings.begin(), r.stats.warnings.end(), [](auto& w) {
        return w.find("stepped over a singular configuration near t = ") != std::string::npos;
      });
      EXPECT_TRUE(said);
    }
  }
}

// The run: `mo2d forward mechanisms/double_fourbar.yaml --integrator erk8 --rtol 5e-9
// --atol 5e-9` (101 output times) stopped at t = 2.7 s with a drift of 8.6e29: the stage states
// of the straddling steps, off the manifolds by O(h^2), got accelerations wrong by that / sigma_min
// (error estimates 1e4 at every length). With projected stages erk6 and erk8 keep the branch at
// tight tolerances, with output times next to singular instants, and end near the 40-digit
// reference (the error follows the tolerance, as above).
TEST(Forward, HighOrderMethodsPassSingularInstantsAtTightTolerances) {
  const Model m = build_model(mechanisms::double_fourbar());
  const State s = consistent_state(m, {.positions = {}, .velocities = {{"crank0.w", -1.0}}});
  const int ix = m.coordinate("crank0.B.x"), iy = m.coordinate("crank0.B.y");
  // (erk6 at 1e-11 with these 101 output times: 1.1e-8, 1100 x tol, on the branch; not here)
  for (Integrator i : {Integrator::erk6, Integrator::erk8})
    for (double tol : {5e-9, 1e-10, 1e-11}) {
      if (i == Integrator::erk6 && tol < 1e-10) continue;
      const Trajectory r = forward_dynamics(
          m, s, {.t0 = 0, .t1 = 10, .samples = 101, .integrator = i, .rtol = tol, .atol = tol});
      const int k = static_cast<int>(r.time.size()) - 1;
      ASSERT_EQ(r.time[k], 10.0) << to_string(i) << " tol " << tol;
      EXPECT_LE(std::hypot(r.q0(k, ix) - 0.328458111541, r.q0(k, iy) - 0.944518538179), 1000 * tol)
          << to_string(i) << " tol " << tol;
      EXPECT_LE(r.residuals.maxCoeff(), 1e-12) << to_string(i) << " tol " << tol;
    }
}

// Output times close to a singular configuration are reported: the first of the ten singular
// instants of the double four-bar is at t = 0.7143 s.
TEST(Forward, NearSingularOutputTimesAreReported) {
  const Model m = build_model(mechanisms::double_fourbar());
  const State s = consistent_state(m, {.positions = {}, .velocities = {{"crank0.w", -1.0}}});
  const Trajectory r = forward_dynamics(
      m, s, {.t0 = 0, .t1 = 1, .samples = 1001, .integrator = Integrator::rk4, .step = 1e-3});
  // (sigma_min / sigma_max)^2 grows as the square of the distance to the instant: 2.3e-6 at the
  // nearest output time (0.32 ms away); any sample within 0.5 ms is below 1e-5
  EXPECT_LT(r.stats.min_pivot_ratio, 1e-5);
  ASSERT_FALSE(r.stats.warnings.empty());
  EXPECT_NE(r.stats.warnings[0].find("near-singular configuration at t = 0.71"), std::string::npos)
      << r.stats.warnings[0];
  // far from it, nothing is reported
  const Trajectory quiet = forward_dynamics(
      m, s, {.t0 = 0, .t1 = 0.5, .samples = 501, .integrator = Integrator::rk4, .step = 1e-3});
  EXPECT_TRUE(quiet.stats.warnings.empty());
  EXPECT_GT(quiet.stats.min_pivot_ratio, 1e-3);
}

TEST(Forward, BadInputIsRefused) {
  const Model fb = build_model(mechanisms::fourbar().system);
  auto msg = [](auto&& f) {
    try {
      f();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(msg([&] {
              consistent_state(fb, {.positions = {}, .velocities = {}});
            }).find("1 independent velocities are needed"),
            std::string::npos);
  EXPECT_NE(
      msg([&] {
        consistent_state(fb, {.positions = {}, .velocities = {{"crank.w", 1}, {"rocker.w", 1}}});
      }).find("2 given"),
      std::string::npos);
  EXPECT_NE(msg([&] {
              consistent_state(fb, {.positions = {}, .velocities = {{"crank.wx", 1}}});
            }).find("crank.w"),
            std::string::npos);
  EXPECT_NE(
      msg([&] {
        consistent_state(fb, {.positions = {{"crank.angle", NAN}}, .velocities = {{"crank.w", 1}}});
      }).find("crank.angle"),
      std::string::npos);
  // the crank tip's y velocity is not independent when the crank is vertical (pure x motion)
  EXPECT_NE(msg([&] {
              consistent_state(fb, {.positions = {}, .velocities = {{"crank.A.vy", 1}}});
            }).find("not independent"),
            std::string::npos);
  const State s = consistent_state(fb, {.positions = {}, .velocities = {{"crank.w", 1}}});
  EXPECT_NE(msg([&] { forward_dynamics(fb, s, {.t0 = 1, .t1 = 0}); }).find("t0 < t1"),
            std::string::npos);
  EXPECT_NE(msg([&] {
              forward_dynamics(fb, s, {.integrator = Integrator::rk4, .step = -1});
            }).find("step"),
            std::string::npos);
  EXPECT_NE(msg([&] { forward_dynamics(fb, s, {.rtol = 0}); }).find("tolerances"),
            std::string::npos);
  ForwardOptions bad{.integrator = Integrator::rk4};
  bad.efforts = {[](double t) { return t > 0.5 ? NAN : 0.0; }};
  const std::string e = msg([&] { forward_dynamics(fb, s, bad); });
  EXPECT_NE(e.find("crank_pivot.torque"), std::string::npos) << e;
  EXPECT_NE(e.find("t = 0.5"), std::string::npos) << e;
  ForwardOptions many{.integrator = Integrator::rk4};
  many.efforts = {[](double) { return 0.0; }, [](double) { return 0.0; }};
  EXPECT_NE(msg([&] { forward_dynamics(fb, s, many); }).find("more efforts"), std::string::npos);
}

TEST(Forward, CsvHasLabelledHeader) {
  const Pendulum p = released_pendulum(0.5);
  const Trajectory r = forward_dynamics(
      p.model, p.start,
      {.t0 = 0, .t1 = 0.1, .samples = 3, .integrator = Integrator::rk4, .step = 1e-3});
  const std::string csv = trajectory_csv(r);
  const std::string header = csv.substr(0, csv.find('\n'));
  EXPECT_EQ(header.find("t,link.P.x,link.P.y,link.angle,link.P.vx"), 0u) << header;
  EXPECT_NE(header.find("energy.kinetic,energy.potential,work.inputs,energy.dissipated"),
            std::string::npos);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 4);
}

// Result lookups by label name the unknown label and suggest the closest one.
TEST(Forward, UnknownLabelsGetASuggestion) {
  const Pendulum p = released_pendulum(0.5);
  const Trajectory r = forward_dynamics(
      p.model, p.start, {.t0 = 0, .t1 = 0.01, .samples = 2, .integrator = Integrator::rk4});
  auto message = [](auto&& f) {
    try {
      f();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message([&] { r.column("link.P.xx"); }),
            "unknown coordinate 'link.P.xx' (did you mean 'link.P.x'?)");
  EXPECT_EQ(message([&] { r.rate_column("link.ww"); }),
            "unknown quasi-velocity 'link.ww' (did you mean 'link.w'?)");
  const auto ex = mechanisms::pendulum();
  const Trajectory inv =
      inverse_dynamics(build_model(ex.system), ex.motion, {.t0 = 0, .t1 = 0.1, .samples = 2});
  EXPECT_EQ(message([&] { inv.effort("pivot.torqe"); }),
            "unknown input 'pivot.torqe' (did you mean 'pivot.torque'?)");
}

namespace mo2d {
namespace {

// An embedded pair's free step that passes output times and then meets the stop condition:
// the output times before the event are recorded (interpolated) before the event's own sample,
// so the trajectory keeps every grid time up to the event (they were dropped, and the chain
// switching of inextensible chains then asked for a leg that ended before it started).
TEST(Forward, OutputTimesBeforeAnEventAreRecorded) {
  const Pendulum p = released_pendulum(0.5);
  const int ix = p.model.coordinate("link.P.x");
  ForwardOptions o{.integrator = Integrator::dopri5, .rtol = 1e-4, .atol = 1e-4};
  o.t1 = 2 * p.quarter_period;
  o.samples = 2000;  // steps of many grid intervals; the event between grid times 999 and 1000
  o.stop_when = [ix](double, const VectorXd& q0, const VectorXd&) { return q0[ix]; };
  const Trajectory r = forward_dynamics(p.model, p.start, o);
  ASSERT_TRUE(r.stats.stopped_by_event);
  const Eigen::Index n = r.time.size();
  ASSERT_GE(n, 2);
  const double h = (o.t1 - o.t0) / (o.samples - 1);
  for (Eigen::Index i = 0; i + 1 < n; ++i) EXPECT_NEAR(r.time[i], o.t0 + i * h, 1e-12) << i;
  EXPECT_NEAR(r.time[n - 1], p.quarter_period, 1e-4);
  EXPECT_EQ(n - 1, static_cast<Eigen::Index>(std::floor(p.quarter_period / h)) + 1);
}

}  // namespace
}  // namespace mo2d
