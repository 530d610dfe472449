// Issue 31, item 2: the singular passage of a four-bar chain on every integrator (cvode_bdf's is
// open: below), and a collapse of the step size ended with its cause
// (RunBudget::check_collapse, run/budget.cpp; collapse_cause.cpp) instead of a run that grinds
// until its wall-time budget.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <string>

#include "forward/forward_run.hpp"
#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"
#include "run/run_budget.hpp"

namespace collapse_test {

using namespace mo2d;

template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

// A chain of n parallelogram four-bars (tests/data/chain40_bdf.yaml with n loops): n + 1 cranks
// of 1 m pivoted at x = 0..n, n couplers; released upright with the crank tips at 1 m/s, it
// reaches its flat (singular) position at t = 0.72 s, all n loops at once.
std::string chain_scene(int n, double duration) {
  std::string s = "name: chain\nground:\n";
  for (int k = 0; k <= n; ++k)
    s += "  O" + std::to_string(k) + ": [" + std::to_string(k) + ", 0]\n";
  s += "bodies:\n";
  const std::string mass = ", mass: 1, inertia: 1/12, com: {between: [";
  for (int k = 0; k <= n; ++k) {
    const std::string x = std::to_string(k);
    s += "  crank" + x + ": {nodes: {O: [" + x + ", 0], B: [" + x + ", 1]}" + mass + "O, B]}}\n";
  }
  for (int k = 1; k <= n; ++k) {
    const std::string x = std::to_string(k), xm = std::to_string(k - 1);
    s += "  coupler" + x + ": {nodes: {A: [" + xm + ", 1], B: [" + x + ", 1]}" + mass + "A, B]}}\n";
  }
  s += "joints:\n";
  for (int k = 0; k <= n; ++k) {
    const std::string x = std::to_string(k);
    s += "  p" + x + ": {type: revolute, node_a: ground.O" + x + ", node_b: crank" + x + ".O}\n";
  }
  for (int k = 1; k <= n; ++k) {
    const std::string x = std::to_string(k), xm = std::to_string(k - 1);
    s += "  l" + x + ": {type: revolute, node_a: crank" + xm + ".B, node_b: coupler" + x + ".A}\n";
    s += "  r" + x + ": {type: revolute, node_a: crank" + x + ".B, node_b: coupler" + x + ".B}\n";
  }
  s += "loads: {gravity: [0, -9.81]}\ninitial: {velocities: {crank0.w: -1}}\n";
  s += "run: {solve: forward, duration: " + std::to_string(duration) + ", samples: 101}\n";
  return s;
}

// The 20-loop chain (1 s, 101 samples: the issue's setting) over its flat position at t = 0.72 s,
// within a bounded number of steps, on integrator i; "" or the run's error.
std::string chain_passage(Integrator i) {
  const Scene scene = parse_scene(chain_scene(20, 1.0), "chain20.yaml");
  const Model m = build_scene_model(scene);
  const State s0 = initial_state(scene, m);
  const int iy = m.coordinate("crank0.B.y");
  ForwardOptions o = forward_options(scene, m);
  o.accuracy = 0;  // the integrator named, not the scene's default accuracy
  o.integrator = i;
  o.rtol = 1e-8, o.atol = 1e-10, o.step = 2e-3;
  o.max_steps = 1000;
  o.max_seconds = 30;
  Trajectory r;
  const std::string msg = error_of([&] { r = forward_dynamics(m, s0, o); });
  if (!msg.empty()) return msg;
  // the crank tips went below the pivots' line: the flat position is passed
  EXPECT_LT(r.q0(r.time.size() - 1, iy), -0.05) << to_string(i);
  EXPECT_LT(r.stats.max_drift, 1e-9) << to_string(i);
  return "";
}

// The explicit integrators step over the flat position (rk4 501 steps at h = 2e-3 s, dopri5 63,
// erk6 34, erk8 16); the ones that do not project stop there with the reason.
TEST(ChainPassage, TwentyLoopChainPassesItsFlatPositionOnExplicitIntegrators) {
  for (const Integrator i :
       {Integrator::rk4, Integrator::dopri5, Integrator::erk6, Integrator::erk8})
    EXPECT_EQ(chain_passage(i), "") << to_string(i);
  EXPECT_NE(chain_passage(Integrator::cvode_adams).find("does not project"), std::string::npos);
}

// OPEN (issue 31, item 2): cvode_bdf does not pass the 20-loop chain's flat position (nor the
// 40-loop one of the issue): since ed2d141 its Newton matrix there is the difference quotients
// of the regularized accelerations, and the step collapses to 1e-8 ... 1e-14 s at t = 0.726 s.
// The exact Jacobian also where the evaluation is regularized passes this chain (408 steps) and
// the 40-loop one (777 steps over 1 s, 2833 over 10 s), but collapses the double four-bar at rtol
// 1e-10 (the cross-check's reference run: a step of 5e-27 s at t = 0.714 s), so it was reverted;
// neither scheme is robust (CVODE's own quotients, the scheme before ed2d141, collapse on the 11-
// and 17-loop chains). Enable when a Newton matrix passes both.
// Tried on 2026-12-07 (branch i31-bdf, not merged), over n = 11, 17, 20, 30, 40 loops x rtol 1e-6,
// 1e-8, 1e-10 (atol rtol/100, 1 s): main fails 7 of the 15. (1) The dense velocity projection is
// not idempotent next to the flat position: its penalty iteration crawls (residual 2e-10 shrinking
// by 4e-5 per iteration, q1 moved 8e-9 each), so every retry of a step moved the accepted state
// again and CVODE's error test failed down to 1e-35 s steps; a truncated minimum-norm correction in
// the crawling directions removes that failure mode, yet 8 of 15 still fail (error test at 1e-12 s
// steps: the regularized accelerations vary by ~1e3 m/s^2 over Newton-sized state changes). (2)
// With (1), the accelerations at the projected state f(P(y)), with the augmented Lagrangian started
// from lambda = 0 (a function of the state): 4 of 15 fail (all at rtol 1e-10). (3) With (1),
// handing the collapsed passage to erk6 from the last output time: 7 of 15 fail (erk6 itself cannot
// step over the instant from 0.5 ms before it at some tolerances). (4) A damped least-squares Schur
// solve where the direct solve is refused: 11 to 13 of 15 fail.
TEST(ChainPassage, DISABLED_TwentyLoopChainPassesItsFlatPositionOnCvodeBdf) {
  EXPECT_EQ(chain_passage(Integrator::cvode_bdf), "");
}

// RunBudget: a step that collapses suddenly (1e-3 s, then 1e-14 s) ends the run after
// kSustain checks, with the cause the driver names; a passage through 1e-8 s steps does not.
TEST(StepCollapse, SuddenCollapseEndsTheRunWithItsCause) {
  int asked = 0;
  detail::RunBudget b({.run = "run",
                       .name = "m",
                       .t0 = 0,
                       .t1 = 1,
                       .max_steps = 10'000'000,
                       .hint = "",
                       .collapse_cause = [&](double, const double*) {
                         ++asked;
                         return std::string("the cause");
                       }});
  double t = 0;
  long steps = 0;
  for (int k = 0; k < 300; ++k) b.check(t += 1e-3, ++steps, 1e-3);
  for (int k = 0; k < 60; ++k) b.check(t += 1e-8, ++steps, 1e-8);  // a singular passage
  for (int k = 0; k < 300; ++k) b.check(t += 1e-3, ++steps, 1e-3);
  std::string msg;
  int checks = 0;
  try {  // steps of 1e-14 s, a few tries (right-hand sides) each
    for (; checks < 1000; ++checks)
      b.check(t += 1e-14 * (checks % 4 == 0), steps += checks % 4 == 0, 1e-14);
  } catch (const Error& e) {
    msg = e.what();
  }
  EXPECT_NE(msg.find("the step size collapsed to 1e-14 s at t = 0.6"), std::string::npos) << msg;
  EXPECT_NE(msg.find("1e-11 of the steps just before, 0.001 s"), std::string::npos) << msg;
  EXPECT_NE(msg.find(": the cause"), std::string::npos) << msg;
  EXPECT_EQ(asked, 1);
  EXPECT_LT(checks, 200);
  // 100 checks in a row over a single accepted step (a Newton matrix by difference quotients)
  detail::RunBudget c(
      {.run = "run", .name = "m", .t0 = 0, .t1 = 1, .max_steps = 10'000'000, .hint = ""});
  t = 0, steps = 0;
  for (int k = 0; k < 300; ++k) c.check(t += 1e-3, ++steps, 1e-3);
  EXPECT_EQ(error_of([&] {
              for (int k = 0; k < 500; ++k) c.check(t, steps, 1e-14);
            }),
            "");
}

// A step size that shrinks steadily, 0.1 % per step, from 1e-3 s: judged by the step budget (the
// rest of the run at that size needs more than 10 x max_steps steps).
TEST(StepCollapse, SteadilyShrinkingStepEndsOnTheStepBudget) {
  detail::RunBudget b(
      {.run = "run", .name = "m", .t0 = 0, .t1 = 10, .max_steps = 1'000'000, .hint = ""});
  double t = 0, h = 1e-3;
  long steps = 0;
  const std::string msg = error_of([&] {
    for (; steps < 100'000;) {
      h *= 0.999;
      b.check(t += h, ++steps, h);
    }
  });
  EXPECT_NE(msg.find("more than 10 x the step budget of 1000000"), std::string::npos) << msg;
  EXPECT_LT(steps, 20'000);
  // a passage: 200 steps of 1e-8 s among 1e-3 s ones, no error
  detail::RunBudget c(
      {.run = "run", .name = "m", .t0 = 0, .t1 = 10, .max_steps = 10'000'000, .hint = ""});
  t = 0, steps = 0;
  EXPECT_EQ(error_of([&] {
              for (int k = 0; k < 300; ++k) c.check(t += 1e-3, ++steps, 1e-3);
              for (int k = 0; k < 200; ++k) c.check(t += 1e-8, ++steps, 1e-8);
              for (int k = 0; k < 300; ++k) c.check(t += 1e-3, ++steps, 1e-3);
            }),
            "");
}

// A torque exp(1000 t) on a pendulum: its rate grows without bound and the steps shrink with it.
// Before: 3.5 M steps in 60 s on dopri5 and cvode_bdf, ended by the wall-time budget; now a
// blow-up, named, within a few seconds (CPU, release: 0.1 s).
TEST(StepCollapse, BlowUpLawEndsQuicklyNamed) {
  const Scene scene = parse_scene(R"yaml(
name: blowup
ground: {O: [0, 0]}
bodies:
  rod: {nodes: {A: [0, 0], B: [1, 0]}, mass: 1, inertia: 0.1}
joints:
  pivot: {type: revolute, node_a: ground.O, node_b: rod.A}
loads:
  gravity: [0, -9.81]
  torques: {surge: {body: rod, torque: "exp(1000 * t)"}}
initial: {velocities: {rod.w: 0}}
run: {solve: forward, duration: 10, samples: 11}
)yaml",
                                  "blowup.yaml");
  const Model m = build_scene_model(scene);
  const State s0 = initial_state(scene, m);
  for (const Integrator i : {Integrator::dopri5, Integrator::cvode_bdf, Integrator::erk8}) {
    ForwardOptions o = forward_options(scene, m);
    o.accuracy = 0;
    o.integrator = i;
    o.max_seconds = 60;
    const auto start = std::chrono::steady_clock::now();
    const std::string msg = error_of([&] { forward_dynamics(m, s0, o); });
    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_NE(msg.find("the step size collapsed"), std::string::npos) << to_string(i) << msg;
    EXPECT_NE(msg.find("a blow-up: the kinetic energy has grown to"), std::string::npos)
        << to_string(i) << msg;
    EXPECT_NE(msg.find("'rod."), std::string::npos) << to_string(i) << msg;
    EXPECT_LT(secs, 10) << to_string(i);
  }
}

// collapse_cause at the double four-bar's flat position names the singular position and the
// dependent constraints; at an ordinary state, no blow-up and no singular position.
TEST(StepCollapse, CauseAtASingularPositionNamesIt) {
  const Model m = build_model(mechanisms::double_fourbar());
  ForwardOptions o;
  o.integrator = Integrator::cvode_bdf;
  ForwardData d(m, o);
  // the flat position: crank tips on the pivots' line
  VectorXd q0 = m.q0, q1 = VectorXd::Zero(m.n1);
  for (int k = 0; k < 3; ++k) {
    q0[m.coordinate("crank" + std::to_string(k) + ".B.x")] = k + 1.0;
    q0[m.coordinate("crank" + std::to_string(k) + ".B.y")] = 0.0;
  }
  VectorXd y(m.n0 + m.n1);
  y << q0, q1;
  const std::string flat = detail::collapse_cause(d, 0.0, y.data(), {});
  EXPECT_NE(flat.find("a singular position"), std::string::npos) << flat;
  EXPECT_NE(flat.find("rk4, dopri5, erk6 and erk8 step over"), std::string::npos) << flat;
  y << m.q0, q1;
  const std::string upright = detail::collapse_cause(d, 0.0, y.data(), {});
  EXPECT_NE(upright.find("neither a singular position nor a blow-up"), std::string::npos)
      << upright;
}

}  // namespace collapse_test
