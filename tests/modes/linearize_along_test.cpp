// Linearization along a reference trajectory (linearize_along, mo2d/modes.hpp) against finite
// differences of forward runs (issue 16): the transition matrix Phi(t) of dPhi/dt = G(t) Phi,
// integrated by RK4 with G at the stage times taken from the reference run's samples, against
// (x(t; x0 + eps e_j) - x(t; x0 - eps e_j)) / (2 eps) of two forward runs from the initial state
// displaced along the chart (chart_state), both in the same independent coordinates x = (z, w).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "mo2d/mo2d.hpp"
#include "mo2d/modes.hpp"
#include "mo2d/scene.hpp"

using namespace mo2d;

namespace {

// A crank-rocker four-bar (mechanisms/fourbar.yaml's geometry) released with a crank rate, with
// a torsional spring-damper at the crank pivot and a linear spring-damper from the ground to the
// coupler: a 1-DOF mechanism that swings through a large angle and rings down.
const char* kAlongFourbar = R"(
name: sprung_fourbar
parameters:
  a: 0.1
  b: 0.35
  c: 0.3
  d: 0.4
  l: sqrt(d^2 + a^2)
  x: (b^2 - c^2 + l^2) / (2 * l)
  h: sqrt(b^2 - x^2)
  Bx: x * d / l + h * a / l
  By: a - x * a / l + h * d / l
ground:
  A0: [0, 0]
  B0: [d, 0]
  S: [0.1, 0.5]
bodies:
  crank:
    nodes: {O: [0, 0], A: [0, a]}
    mass: 0.2
    inertia: 0.2 * a^2 / 12
    com: {between: [O, A], gamma: 0.5}
  coupler:
    nodes: {A: [0, a], B: [Bx, By]}
    mass: 0.5
    inertia: 0.5 * b^2 / 12
    com: {between: [A, B], gamma: 0.5}
  rocker:
    nodes: {O: [d, 0], B: [Bx, By]}
    mass: 0.4
    inertia: 0.4 * c^2 / 12
    com: {between: [O, B], gamma: 0.5}
joints:
  crank_pivot:  {type: revolute, node_a: ground.A0, node_b: crank.O}
  crank_pin:    {type: revolute, node_a: crank.A, node_b: coupler.A}
  rocker_pin:   {type: revolute, node_a: coupler.B, node_b: rocker.B}
  rocker_pivot: {type: revolute, node_a: ground.B0, node_b: rocker.O}
coordinates:
  crank.angle: {rate: {crank.w: 1}}
loads:
  gravity: [0, -9.81]
  torsional_springs:
    crank_spring: {joint: crank_pivot, stiffness: 0.3, damping: 0.01, rest: 0}
  springs:
    top: {body_a: ground, point_a: [0.1, 0.5], body_b: coupler, point_b: [Bx, By],
          rest_length: 0.2, stiffness: 20, damping: 0.2}
initial:
  velocities: {crank.w: 3}
run:
  solve: forward
  duration: 1
)";

struct AlongCase {
  Model model;
  State start;
  ForwardOptions run;
};

AlongCase along_case(const Scene& scene, double t1, int samples) {
  AlongCase c{build_scene_model(scene), {}, {}};
  c.start = initial_state(scene, c.model);
  c.run = forward_options(scene, c.model);
  c.run.t1 = c.run.t0 + t1;
  c.run.samples = samples;
  c.run.integrator = Integrator::dopri5;
  c.run.rtol = 1e-12;
  c.run.atol = 1e-14;
  return c;
}

// Phi at the even samples 0, 2, 4, ... of `along` (equally spaced): RK4 steps of two samples,
// G at the step's start, middle (both middle stages) and end.
std::vector<MatrixXd> along_transition(const std::vector<StateSpace>& along) {
  const int n = along.front().n();
  std::vector<MatrixXd> phi{MatrixXd::Identity(n, n)};
  for (size_t k = 0; k + 2 < along.size(); k += 2) {
    const double h = along[k + 2].t - along[k].t;
    const MatrixXd& P = phi.back();
    const MatrixXd k1 = along[k].G * P;
    const MatrixXd k2 = along[k + 1].G * (P + h / 2 * k1);
    const MatrixXd k3 = along[k + 1].G * (P + h / 2 * k2);
    const MatrixXd k4 = along[k + 2].G * (P + h * k3);
    phi.push_back(P + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4));
  }
  return phi;
}

// Central differences of forward runs: column j of dx(t)/dx0 at the run's samples (the even
// samples of the reference), x0 displaced by +- eps_j along the chart of along[0].
std::vector<MatrixXd> along_differences(const AlongCase& c, const StateSpace& ss0, double eps,
                                        int samples) {
  const int n = ss0.n();
  std::vector<MatrixXd> fd(samples, MatrixXd::Zero(n, n));
  ForwardOptions run = c.run;
  run.samples = samples;
  const VectorXd x0 = independent_state(ss0, c.start);
  for (int j = 0; j < n; ++j) {
    const double e = eps * std::max(1.0, std::abs(x0[j]));
    VectorXd dx = VectorXd::Zero(n);
    dx[j] = e;
    const Trajectory plus = forward_dynamics(c.model, chart_state(c.model, ss0, dx), run);
    const Trajectory minus = forward_dynamics(c.model, chart_state(c.model, ss0, -dx), run);
    for (int i = 0; i < samples; ++i) {
      const State sp{plus.time[i], plus.q0.row(i).transpose(), plus.q1.row(i).transpose()};
      const State sm{minus.time[i], minus.q0.row(i).transpose(), minus.q1.row(i).transpose()};
      fd[i].col(j) = (independent_state(ss0, sp) - independent_state(ss0, sm)) / (2 * e);
    }
  }
  return fd;
}

// The largest difference of Phi and fd over the times, per (row block z / w, column), relative to
// the largest |Phi| of that block and column.
double along_worst(const std::vector<MatrixXd>& phi, const std::vector<MatrixXd>& fd, int p) {
  const int n = static_cast<int>(phi.front().rows());
  double worst = 0;
  for (int j = 0; j < n; ++j)
    for (int block = 0; block < 2; ++block) {
      const int r0 = block ? p : 0, rn = block ? n - p : p;
      double diff = 0, size = 0;
      for (size_t i = 0; i < phi.size(); ++i) {
        diff = std::max(diff, (phi[i].col(j) - fd[i].col(j)).segment(r0, rn).cwiseAbs().maxCoeff());
        size = std::max(size, phi[i].col(j).segment(r0, rn).cwiseAbs().maxCoeff());
      }
      worst = std::max(worst, diff / size);
    }
  return worst;
}

double along_max_entry(const std::vector<MatrixXd>& phi) {
  double m = 0;
  for (const auto& P : phi) m = std::max(m, P.cwiseAbs().maxCoeff());
  return m;
}

// The error budget of Phi against the differences, relative (along_worst), as measured on the
// two cases below (sprung double pendulum / four-bar) by varying one setting at a time:
//  - RK4 of Phi, O(h^4): 4.8e-7 / 1.8e-6 at h = 2 ms, 3.0e-8 / 1.1e-7 at h = 1 ms (16 times less);
//    estimated here by Richardson from the same samples (Phi with 2h: every other sample);
//  - central differences, O(eps^2): c eps^2 with c = 18 / 140 (1.8e-7 / 1.4e-6 at eps = 1e-4,
//    whatever h and rtol): 1.4e-8 at most at eps = 1e-5;
//  - the solver's error, divided by eps (dopri5, rtol 1e-12, h = 0.5 ms): 5.4e-8 / 2.5e-8 at
//    eps = 1e-6, 1.3e-6 / 2.5e-7 at eps = 1e-7 (at rtol 1e-10: 8e-7 at eps = 1e-6): at most
//    5.4e-9 at eps = 1e-5, where the first choice, eps = 1e-6, balances worse.
// So worst < 2 e_rk + 3e-8 (the last two terms, summed and rounded up).
double along_bound(const std::vector<StateSpace>& along, const std::vector<MatrixXd>& phi, int p) {
  std::vector<StateSpace> coarse;
  for (size_t k = 0; k < along.size(); k += 2) coarse.push_back(along[k]);
  const std::vector<MatrixXd> phi2 = along_transition(coarse);
  std::vector<MatrixXd> phi_at(phi2.size());
  for (size_t k = 0; k < phi2.size(); ++k) phi_at[k] = phi[2 * k];
  return 2 * along_worst(phi_at, phi2, p) / 15 + 3e-8;
}

constexpr double kAlongEps = 1e-5;  // relative displacement of the initial state (budget above)

}  // namespace

// The sprung double pendulum released from its bent pose (4 states, two lightly damped modes),
// 1 s: Phi from G(t) against central differences of forward runs. Measured: worst 3.0e-8.
TEST(LinearizeAlong, SprungDoublePendulumMatchesForwardDifferences) {
  const Scene scene = load_scene(std::string(MO2D_MECHANISMS_DIR) + "/sprung_double_pendulum.yaml");
  const int steps = 1000;  // RK4 steps of Phi (h = 1 ms), the reference sampled at 2 steps + 1
  AlongCase c = along_case(scene, 1.0, 2 * steps + 1);
  const Trajectory ref = forward_dynamics(c.model, c.start, c.run);
  LinearizeOptions o;
  o.forward = c.run;
  const std::vector<StateSpace> along = linearize_along(c.model, ref, o);
  ASSERT_EQ(along.size(), static_cast<size_t>(2 * steps + 1));
  for (const StateSpace& ss : along) ASSERT_EQ(ss.states, along.front().states);
  const std::vector<MatrixXd> phi = along_transition(along);
  const std::vector<MatrixXd> fd = along_differences(c, along.front(), kAlongEps, steps + 1);
  const double worst = along_worst(phi, fd, along.front().p);
  const double bound = along_bound(along, phi, along.front().p);
  std::printf(
      "  sprung double pendulum: max |Phi| %.3g, worst relative difference %.3g (bound "
      "%.3g)\n",
      along_max_entry(phi), worst, bound);
  EXPECT_LT(worst, bound);
}

// The sprung four-bar swinging through 3.3 rad of crank angle, 1 s, in the crank angle and its
// rate. Measured: worst 1.15e-7, max |Phi| 114.
TEST(LinearizeAlong, SprungFourbarMatchesForwardDifferences) {
  const Scene scene = parse_scene(kAlongFourbar, "sprung_fourbar");
  const int steps = 1000;
  AlongCase c = along_case(scene, 1.0, 2 * steps + 1);
  const Trajectory ref = forward_dynamics(c.model, c.start, c.run);
  LinearizeOptions o;
  o.forward = c.run;
  o.coordinates = {"crank.angle"};
  const std::vector<StateSpace> along = linearize_along(c.model, ref, o);
  ASSERT_EQ(along.front().states, (std::vector<std::string>{"crank.angle", "crank.angle.rate"}));
  double conditioning = 1;
  for (const StateSpace& ss : along) conditioning = std::min(conditioning, ss.conditioning);
  const std::vector<MatrixXd> phi = along_transition(along);
  const std::vector<MatrixXd> fd = along_differences(c, along.front(), kAlongEps, steps + 1);
  const double worst = along_worst(phi, fd, along.front().p);
  const double bound = along_bound(along, phi, along.front().p);
  const int k = c.model.coordinate("crank.angle");
  std::printf(
      "  four-bar: crank angle %.3g -> %.3g rad, conditioning >= %.3g, max |Phi| %.3g, "
      "worst relative difference %.3g (bound %.3g)\n",
      ref.q0.col(k).minCoeff(), ref.q0.col(k).maxCoeff(), conditioning, along_max_entry(phi), worst,
      bound);
  EXPECT_LT(worst, bound);
}

// The pivot's choice at the start of the four-bar's run is crank.A.x, which reaches its extreme at
// t = 0.3 s (the crank horizontal): the chart is singular there. By default linearize_along takes,
// among the pivot's choices at every sample, the one best conditioned over the whole run
// (crank.angle); kept to crank.A.x it stops with an Error naming the time and the coordinate (and
// crank.angle, the pivot's choice there). Forced through it (min_conditioning = 0), Phi in
// crank.A.x reaches 5.8e3 and differs from the forward differences by 100 %: what a silent
// answer would have been.
TEST(LinearizeAlong, CoordinatesThatBecomeSingularAreAnError) {
  const Scene scene = parse_scene(kAlongFourbar, "sprung_fourbar");
  const int steps = 1000;
  AlongCase c = along_case(scene, 1.0, 2 * steps + 1);
  const Trajectory ref = forward_dynamics(c.model, c.start, c.run);
  LinearizeOptions o;
  o.forward = c.run;
  EXPECT_EQ(linearize(c.model, c.start, o).states.front(), "crank.A.x");
  EXPECT_EQ(linearize_along(c.model, ref, o).front().states.front(), "crank.angle");
  o.coordinates = {"crank.A.x"};
  try {
    linearize_along(c.model, ref, o);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("crank.A.x"), std::string::npos) << what;
    EXPECT_NE(what.find("at t = 0.3"), std::string::npos) << what;
    EXPECT_NE(what.find("there: crank.angle"), std::string::npos) << what;
    EXPECT_NEAR(e.time(), 0.3, 0.02);
  }
  o.min_conditioning = 0;
  const std::vector<StateSpace> along = linearize_along(c.model, ref, o);
  ASSERT_EQ(along.front().states.front(), "crank.A.x");
  const std::vector<MatrixXd> phi = along_transition(along);
  const double worst =
      along_worst(phi, along_differences(c, along.front(), kAlongEps, steps + 1), 1);
  std::printf("  forced through: max |Phi| %.3g, worst relative difference %.3g\n",
              along_max_entry(phi), worst);
  EXPECT_GT(worst, 0.1);
}

// chart_state and independent_state are inverse to each other; the JSON/CSV along a run have one
// block per time.
TEST(LinearizeAlong, ChartStateAndExport) {
  const Scene scene = parse_scene(kAlongFourbar, "sprung_fourbar");
  AlongCase c = along_case(scene, 0.1, 3);
  const Trajectory ref = forward_dynamics(c.model, c.start, c.run);
  LinearizeOptions o;
  o.forward = c.run;
  o.coordinates = {"crank.angle"};
  const std::vector<StateSpace> along = linearize_along(c.model, ref, o);
  ASSERT_EQ(along.size(), 3u);
  const VectorXd dx = (VectorXd(2) << 0.01, -0.2).finished();
  const State s = chart_state(c.model, along[1], dx);
  EXPECT_LT((independent_state(along[1], s) -
             independent_state(along[1], {along[1].t, along[1].q0, along[1].q1}) - dx)
                .norm(),
            1e-12);
  const std::string csv = state_space_along_csv(along, 'G');
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "t,G,crank.angle,crank.angle.rate");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 3 * 2);
  const std::string json = state_space_along_json(along);
  EXPECT_NE(json.find("\"samples\""), std::string::npos);
  EXPECT_NE(json.find("\"conditioning\""), std::string::npos);
}
