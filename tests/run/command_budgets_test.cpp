// One budget mechanism for every command that computes (issue 31, items 1 and 3): the Box2D
// cross-checks (steps, result memory, wall time), linearizations, equilibria and modes (memory
// and time estimated before the dense work, wall time checked between its stages), and the
// interrupt check every run polls (Ctrl-C in Python: python/src/module.cpp).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <string>

#include "mo2d/crosscheck.hpp"
#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/modes.hpp"
#include "mo2d/run_stop.hpp"
#include "mo2d/scene.hpp"

namespace mo2d {
namespace {

// An n-link chain pivoted end to end (tests/data/generate_chain.cmake), hanging under gravity.
std::string cb_chain_scene(int n) {
  std::string bodies = "bodies:\n", joints = "joints:\n";
  for (int k = 0; k < n; ++k) {
    const std::string l = "l" + std::to_string(k);
    bodies += "  " + l + ": {nodes: {A: [0, " + std::to_string(-k) + "], B: [0, " +
              std::to_string(-k - 1) + "]}, mass: 1, inertia: 0.1}\n";
    joints += "  j" + std::to_string(k) + ": {type: revolute, node_a: " +
              (k == 0 ? std::string("ground.O") : "l" + std::to_string(k - 1) + ".B") +
              ", node_b: " + l + ".A}\n";
  }
  return "name: chain" + std::to_string(n) + "\nground: {O: [0, 0]}\n" + bodies + joints +
         "loads: {gravity: [0, -9.81]}\n";
}

struct CbLoaded {
  Scene scene;
  Model model;
};
CbLoaded cb_load(const std::string& text) {
  Scene s = parse_scene(text, "chain.yaml");
  Model m = build_scene_model(s);
  return {std::move(s), std::move(m)};
}

template <class E, class F>
std::string cb_message(F f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "";
}

double cb_seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool cb_contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

// ---- the Box2D cross-checks -------------------------------------------------------------------

// step 1e-7 s over 1 s: 1e7 Box2D steps passed the CLI's max_steps check (1e7 <= 1e7) and ran
// past 120 s with a 3.3 GB CSV. The library counts them, settling steps included, before the run.
TEST(CommandBudgets, CrosscheckStepsBeyondTheBudgetAreRefused) {
  const mechanisms::Example ex = mechanisms::slider_crank();
  CrosscheckOptions o;
  o.step = 1e-7;
  o.max_motion_per_step = 0;
  const auto start = std::chrono::steady_clock::now();
  const std::string msg =
      cb_message<Error>([&] { crosscheck_inverse(ex.system, ex.motion, ex.run, o); });
  // 1e7 steps over the run and 200 settling steps before it
  EXPECT_TRUE(cb_contains(msg, "needs 1.00002e+07 Box2D steps, more than the step budget of 1e+07"))
      << msg;
  EXPECT_TRUE(cb_contains(msg, "use a longer --step")) << msg;
  EXPECT_LT(cb_seconds_since(start), 1.0);
}

// The results (the report's series and the CSV) are estimated before the run, against max_memory.
TEST(CommandBudgets, CrosscheckResultsBeyondTheMemoryLimitAreRefused) {
  const mechanisms::Example ex = mechanisms::slider_crank();
  CrosscheckOptions o;
  o.max_memory = 1e5;  // 2000 steps x 19 values x 33 bytes = 1.25 MB
  const std::string msg = cb_message<Error>([&] {
    InverseOptions run = ex.run;
    run.t1 = run.t0 + 1;
    crosscheck_inverse(ex.system, ex.motion, run, o);
  });
  EXPECT_TRUE(cb_contains(msg, "its results (")) << msg;
  EXPECT_TRUE(cb_contains(msg, "max_memory")) << msg;
}

// The wall-time budget ends the Box2D loop (inverse and forward cross-checks) with the time
// reached.
TEST(CommandBudgets, CrosscheckWallTimeBudgetEndsTheRun) {
  const mechanisms::Example ex = mechanisms::slider_crank();
  CrosscheckOptions o;
  o.step = 1e-5;  // 1e5 steps over 1 s: seconds of work
  o.max_motion_per_step = 0;
  o.max_seconds = 0.05;
  InverseOptions run = ex.run;
  run.t1 = run.t0 + 1;
  auto start = std::chrono::steady_clock::now();
  std::string msg =
      cb_message<BudgetExhausted>([&] { crosscheck_inverse(ex.system, ex.motion, run, o); });
  EXPECT_TRUE(cb_contains(msg,
                          "Box2D cross-check of 'slider_crank': the wall-time budget of "
                          "0.05 s ran out at t = "))
      << msg;
  EXPECT_LT(cb_seconds_since(start), 1.5);

  const Model model = build_model(mechanisms::double_fourbar(), {.reduction = Reduction::none});
  const State s0 = consistent_state(model, {.positions = {}, .velocities = {{"crank0.w", -1.0}}});
  o.max_seconds = 0.05;
  start = std::chrono::steady_clock::now();
  msg = cb_message<BudgetExhausted>([&] { crosscheck_forward(model, s0, 10.0, o, 11); });
  EXPECT_TRUE(cb_contains(msg, "wall-time budget of 0.05 s ran out")) << msg;
  EXPECT_LT(cb_seconds_since(start), 1.5);
}

// ---- linearization, equilibrium, modes ---------------------------------------------------------

// A mechanism whose dense linearization cannot fit is refused before any work, naming the sizes.
TEST(CommandBudgets, LinearizationBeyondTheMemoryLimitIsRefused) {
  const CbLoaded c = cb_load(cb_chain_scene(30));
  LinearizeOptions o;
  o.forward.max_memory = 1e5;
  const State s0{0, c.model.q0, Eigen::VectorXd::Zero(c.model.n1)};
  const std::string msg = cb_message<Error>([&] { linearize(c.model, s0, o); });
  EXPECT_TRUE(cb_contains(msg, "linearization of 'chain30' needs about")) << msg;
  EXPECT_TRUE(cb_contains(msg, "max_memory")) << msg;
}

// 500 links with --max-seconds 5: 15 s, then a C++ API message. The estimate of the dense work
// (n^3) refuses it at once; the equilibrium and the modes likewise.
TEST(CommandBudgets, LinearizationBeyondTheTimeBudgetIsRefusedAtOnce) {
  const CbLoaded c = cb_load(cb_chain_scene(200));
  const State s0{0, c.model.q0, Eigen::VectorXd::Zero(c.model.n1)};
  LinearizeOptions o;
  o.forward.max_seconds = 1e-3;
  const auto start = std::chrono::steady_clock::now();
  std::string msg = cb_message<BudgetExhausted>([&] { linearize(c.model, s0, o); });
  EXPECT_TRUE(cb_contains(msg, "linearization of 'chain200' needs about")) << msg;
  EXPECT_TRUE(cb_contains(msg, "more than the wall-time budget of 0.001 s")) << msg;
  EquilibriumOptions eo;
  eo.linearize = o;
  msg = cb_message<BudgetExhausted>([&] { static_equilibrium(c.model, c.model.q0, eo); });
  EXPECT_TRUE(cb_contains(msg, "equilibrium of 'chain200' needs about")) << msg;
  EXPECT_LT(cb_seconds_since(start), 0.5);
  StateSpace big;  // the eigenproblem of a 2000 x 2000 G
  big.p = big.dof = 1000;
  big.G = Eigen::MatrixXd::Zero(1, 1);
  msg = cb_message<BudgetExhausted>([&] { vibration_modes(big, {.max_seconds = 0.01}); });
  EXPECT_TRUE(cb_contains(msg, "the eigenvectors of the 2000 x 2000 G")) << msg;
}

// Within a budget the estimate allows, the wall-time budget is checked between the stages: a
// linearization along many states ends with the time reached.
TEST(CommandBudgets, LinearizationAlongARunEndsWithItsWallTimeBudget) {
  const mechanisms::Example ex = mechanisms::pendulum();
  const Model m = build_model(ex.system);
  const State s0 = consistent_state(m, {{{"link.angle", 0.3}}, {{"link.w", 0.0}}}, 0);
  std::vector<State> states(20000, s0);
  LinearizeOptions o;
  o.forward.max_seconds = 0.02;
  const auto start = std::chrono::steady_clock::now();
  const std::string msg = cb_message<BudgetExhausted>([&] { linearize_along(m, states, o); });
  EXPECT_TRUE(cb_contains(msg, "the wall-time budget of 0.02 s ran out")) << msg;
  EXPECT_LT(cb_seconds_since(start), 1.0);
}

// A model whose runs are sparse (a large chain; here asked for) is linearized on a dense
// workspace: was "acceleration_jacobian ... build it with ForwardOptions::linear_algebra = dense".
TEST(CommandBudgets, LinearizationOfASparseRunsModelWorks) {
  const CbLoaded c = cb_load(cb_chain_scene(5));
  const State s0{0, c.model.q0, Eigen::VectorXd::Zero(c.model.n1)};
  LinearizeOptions sparse;
  sparse.forward.integrator = Integrator::rk4;
  sparse.forward.linear_algebra = LinearAlgebra::sparse;
  const StateSpace a = linearize(c.model, s0, sparse);
  const StateSpace b = linearize(c.model, s0, {});
  EXPECT_EQ(a.n(), 10);
  EXPECT_LT((a.G - b.G).norm(), 1e-12 * b.G.norm());
}

// ---- interrupts ------------------------------------------------------------------------------

std::atomic<int> cb_polls{0};
bool cb_interrupt_now() {
  ++cb_polls;
  return true;
}
// The interrupt check of the test, removed at the end of its scope.
struct CbInterrupting {
  CbInterrupting() {
    cb_polls = 0;
    set_interrupt_check(&cb_interrupt_now);
  }
  ~CbInterrupting() { set_interrupt_check(nullptr); }
  CbInterrupting(const CbInterrupting&) = delete;
  CbInterrupting& operator=(const CbInterrupting&) = delete;
};

// Every kind of run polls the interrupt check (every kInterruptPoll = 0.05 s) and ends at once by
// Interrupted, which no Error handler of a run swallows.
TEST(CommandBudgets, EveryRunStopsAtAnInterrupt) {
  const mechanisms::Example ex = mechanisms::slider_crank();
  const Model m = build_model(ex.system);
  const Model fourbars = build_model(mechanisms::double_fourbar());
  const State f0 =
      consistent_state(fourbars, {.positions = {}, .velocities = {{"crank0.w", -1.0}}});
  const CbInterrupting interrupting;
  // 0.5 s (the bound) from the start of the call, its setup included; 10 times that under
  // the sanitizers, whose setup (models, the cross-check's world, 1e5 states) is ~10 times slower
#ifdef MO2D_SANITIZE
  constexpr double kWithin = 5.0;
#else
  constexpr double kWithin = 0.5;
#endif
  auto stops_fast = [&](const char* what, auto run) {
    const auto start = std::chrono::steady_clock::now();
    EXPECT_THROW(run(), Interrupted) << what;
    EXPECT_LT(cb_seconds_since(start), kWithin) << what;
  };
  stops_fast("forward rk4", [&] {
    ForwardOptions o;
    o.t1 = 1e4;
    o.integrator = Integrator::rk4;
    o.step = 1e-4;
    o.max_steps = 1'000'000'000;
    forward_dynamics(fourbars, f0, o);
  });
  stops_fast("forward cvode_bdf", [&] {
    ForwardOptions o;
    // long enough to be interrupted, short enough that the steps of its singular passages do not
    // make the rest of the run exceed 10 x max_steps (the steady step collapse, an Error: seen at
    // t1 = 1e5 s when the machine was fast enough to reach the first passage before the poll)
    o.t1 = 100;
    o.rtol = 1e-12;
    o.atol = 1e-14;
    forward_dynamics(fourbars, f0, o);
  });
  stops_fast("inverse", [&] {
    InverseOptions o = ex.run;
    o.t1 = 1e3;
    o.samples = 100'000;
    o.max_memory = 1e12;
    inverse_dynamics(m, ex.motion, o);
  });
  stops_fast("crosscheck", [&] {
    CrosscheckOptions o;
    o.step = 1e-5;
    o.max_motion_per_step = 0;
    InverseOptions run = ex.run;
    run.t1 = run.t0 + 1;
    crosscheck_inverse(ex.system, ex.motion, run, o);
  });
  stops_fast("linearize_along", [&] {
    const mechanisms::Example pend = mechanisms::pendulum();
    const Model pm = build_model(pend.system);
    const State p0 = consistent_state(pm, {{{"link.angle", 0.3}}, {{"link.w", 0.0}}}, 0);
    linearize_along(pm, std::vector<State>(100000, p0));
  });
  EXPECT_GT(cb_polls.load(), 0);
}

}  // namespace
}  // namespace mo2d
