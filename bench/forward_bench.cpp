// Forward-dynamics benchmarks (Google Benchmark): one second of the IFToMM double four-bar and of
// the four-bar under gravity with each explicit integrator and CVODE BDF. The model and the initial
// state are built outside the timed loop. Counters: "s/step" and "s/eval" (CPU time per accepted
// step and per evaluation of the accelerations, seconds with an SI prefix). See
// docs/performance.md.
#include <benchmark/benchmark.h>

#include "mo2d/forward.hpp"
#include "mo2d/mechanisms.hpp"
#include "mo2d/model.hpp"
#include "n_fourbar.hpp"

namespace {

using namespace mo2d;

benchmark::Counter per_item(double items) {
  return benchmark::Counter(items, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

struct Case {
  Model model;
  State start;
};

Case double_fourbar() {
  Model m = build_model(mechanisms::double_fourbar());
  State s = consistent_state(m, {.positions = {}, .velocities = {{"crank0.w", -1.0}}});
  return {std::move(m), std::move(s)};
}
Case fourbar() {
  Model m = build_model(mechanisms::fourbar().system);
  State s = consistent_state(m, {.positions = {}, .velocities = {{"crank.w", 6.0}}});
  return {std::move(m), std::move(s)};
}

void BM_Forward(benchmark::State& state, Case (*make)(), ForwardOptions o) {
  const Case c = make();
  o.t0 = 0;
  o.t1 = 1;
  o.samples = 11;
  long steps = 0, evals = 0;
  for (auto _ : state) {
    const Trajectory r = forward_dynamics(c.model, c.start, o);
    benchmark::DoNotOptimize(r.q0.data());
    steps += r.stats.steps;
    evals += r.stats.rhs_evaluations;
  }
  state.counters["s/step"] = per_item(static_cast<double>(steps));
  state.counters["s/eval"] = per_item(static_cast<double>(evals));
}

const ForwardOptions kRk4{.integrator = Integrator::rk4, .step = 4e-3};
const ForwardOptions kDopri5{.integrator = Integrator::dopri5, .rtol = 1e-9, .atol = 1e-9};
const ForwardOptions kBdf{.integrator = Integrator::cvode_bdf, .rtol = 1e-8, .atol = 1e-8};
// the same with CVODE's difference quotients for the Newton matrix instead of the exact Jacobian
const ForwardOptions kBdfDq{
    .integrator = Integrator::cvode_bdf, .rtol = 1e-8, .atol = 1e-8, .exact_jacobian = false};

BENCHMARK_CAPTURE(BM_Forward, double_fourbar_rk4_h4e - 3, &double_fourbar, kRk4)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Forward, double_fourbar_dopri5_tol1e - 9, &double_fourbar, kDopri5)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Forward, double_fourbar_bdf_tol1e - 8, &double_fourbar, kBdf)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Forward, double_fourbar_bdf_dq_tol1e - 8, &double_fourbar, kBdfDq)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Forward, fourbar_bdf_tol1e - 8, &fourbar, kBdf)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Forward, fourbar_bdf_dq_tol1e - 8, &fourbar, kBdfDq)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Forward, fourbar_rk4_h4e - 3, &fourbar, kRk4)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Forward, fourbar_dopri5_tol1e - 9, &fourbar, kDopri5)
    ->Unit(benchmark::kMillisecond);

// The N-four-bar (bench/n_fourbar.hpp), rk4 h = 2e-3 over 20 steps, dense against sparse linear
// algebra: the crossover of LinearAlgebra::automatic (kSparseCrossover, docs/performance.md).
void BM_NFourBar(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const Model m = build_model(bench::n_fourbar(n));
  const State s = consistent_state(m, {.positions = {}, .velocities = {{"crank0.w", -1.0}}});
  ForwardOptions o{.integrator = Integrator::rk4, .step = 2e-3};
  o.linear_algebra = state.range(1) ? LinearAlgebra::sparse : LinearAlgebra::dense;
  o.t0 = 0;
  o.t1 = 20 * 2e-3;
  o.samples = 2;
  long steps = 0, evals = 0;
  for (auto _ : state) {
    const Trajectory r = forward_dynamics(m, s, o);
    benchmark::DoNotOptimize(r.q0.data());
    steps += r.stats.steps;
    evals += r.stats.rhs_evaluations;
  }
  state.counters["s/step"] = per_item(static_cast<double>(steps));
  state.counters["s/eval"] = per_item(static_cast<double>(evals));
  state.counters["n1+m1"] = m.n1 + m.m1;
}
BENCHMARK(BM_NFourBar)
    ->ArgsProduct({{2, 5, 10, 20, 40, 100}, {0, 1}})
    ->ArgNames({"N", "sparse"})
    ->Unit(benchmark::kMillisecond);
// the sparse path alone further (a dense step takes about 16 s at N = 400; at N = 1000 the dense
// consistent_state of the set-up takes minutes)
BENCHMARK(BM_NFourBar)->Args({400, 1})->ArgNames({"N", "sparse"})->Unit(benchmark::kMillisecond);

}  // namespace
