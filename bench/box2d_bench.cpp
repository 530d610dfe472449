// Box2D 2.4.1 step cost for the cross-check worlds (Google Benchmark), to set beside mo2d's cost
// per inverse-dynamics sample (inverse_bench.cpp, BM_Sample). See docs/performance.md.
//
// Setup (not timed): the Model built with Reduction::none is translated into a Box2D world at the
// first instant of the reference run, and the motor speed targets of one crosscheck run (mean
// rates over each step, as crosscheck_inverse sets them) are precomputed from mo2d's exact motion.
// Timed: set the motor speeds, apply the loads, b2World::Step. After the last precomputed step the
// world is rebuilt outside the timing. Arguments: velocity and position iterations; h = 1/2000 s.
#include <benchmark/benchmark.h>

#include <vector>

#include "box2d_world.hpp"
#include "mo2d/inverse.hpp"
#include "mo2d/mechanisms.hpp"

namespace {

using namespace mo2d;
using Factory = mechanisms::Example (*)();
constexpr double kStep = 1.0 / 2000;

void BM_Box2DStep(benchmark::State& state, Factory make, double seconds) {
  using namespace crosscheck_detail;
  const mechanisms::Example ex = make();
  const Model m = build_model(ex.system, {.reduction = Reduction::none});
  const int steps = static_cast<int>(seconds / kStep);
  CrosscheckOptions o;
  o.velocity_iterations = static_cast<int>(state.range(0));
  o.position_iterations = static_cast<int>(state.range(1));
  InverseData d(m, ex.motion, ex.run);
  inverse_dynamics_sample(m, d, ex.run.t0);
  const Eigen::VectorXd q0 = d.q0, q1 = d.q1;
  auto build = [&] { return build_box2d_world(m, q0, q1, o, true); };
  Box2DWorld w = build();
  std::vector<const JointMap*> motors;
  for (const JointMap& j : w.joints)
    if (j.motor) motors.push_back(&j);
  std::vector<double> speed;  // steps x motors
  std::vector<double> s(motors.size());
  for (size_t k = 0; k < motors.size(); ++k) s[k] = joint_coordinate(m, w, *motors[k], d.q0);
  for (int n = 0; n < steps; ++n) {
    inverse_dynamics_sample(m, d, ex.run.t0 + (n + 1) * kStep);
    for (size_t k = 0; k < motors.size(); ++k) {
      const double next = joint_coordinate(m, w, *motors[k], d.q0);
      speed.push_back((motors[k]->linear_motor ? next - s[k] : wrap_angle(next - s[k])) / kStep);
      s[k] = next;
    }
  }
  int n = 0;
  for (auto _ : state) {
    for (size_t k = 0; k < motors.size(); ++k)
      set_motor_speed(*motors[k], speed[n * motors.size() + k]);
    apply_loads(m, w, ex.run.t0 + n * kStep, kStep);
    w.world->Step(static_cast<float>(kStep), o.velocity_iterations, o.position_iterations);
    if (++n == steps) {
      state.PauseTiming();
      w = build();
      motors.clear();
      for (const JointMap& j : w.joints)
        if (j.motor) motors.push_back(&j);
      n = 0;
      state.ResumeTiming();
    }
  }
}

}  // namespace

BENCHMARK_CAPTURE(BM_Box2DStep, whitworth, &mechanisms::whitworth, 4.0)
    ->Args({50, 20})
    ->Args({8, 3})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Box2DStep, rrr3, &mechanisms::rrr3, 4.0)
    ->Args({50, 20})
    ->Args({8, 3})
    ->Unit(benchmark::kMicrosecond);
