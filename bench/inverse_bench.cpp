// Inverse-dynamics benchmarks (Google Benchmark): per-sample cost of the Whitworth and 3RRR
// reference runs, whole 501-sample runs, and model construction. See docs/performance.md.
//
// Per-sample benchmarks (BM_Sample/*) build the Model and the InverseData once, then call
// inverse_dynamics_sample() with t stepping through the reference run exactly as
// inverse_dynamics() does (t_k = t0 + (t1 - t0) k / (N - 1)), wrapping around after the last
// sample. A sample uses the previous one as its Newton predictor, so consecutive times are those
// of the real run; on wrap-around the predictor is dropped (has_previous = false) and the
// coordinates are reset to the model's assembled configuration, like a fresh run.
// The reported Time is the time per sample; the counter "s/sample" repeats it (CPU time, seconds
// with an SI prefix). BM_Run reports the time of a whole run and "s/sample" = run time / N.
#include <benchmark/benchmark.h>

#include "linalg/pattern_lu.hpp"
#include "mo2d/inverse.hpp"
#include "mo2d/mechanisms.hpp"
#include "mo2d/model.hpp"

namespace {

using mo2d::mechanisms::Example;
using Factory = Example (*)();

// CPU seconds per item (a rate counter, inverted); printed with an SI prefix, e.g. "3.9u" = 3.9 us.
benchmark::Counter per_item(double items) {
  return benchmark::Counter(items, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_Sample(benchmark::State& state, Factory make) {
  const Example ex = make();
  const mo2d::Model model = mo2d::build_model(ex.system);
  mo2d::InverseData data(model, ex.motion, ex.run);
  const int N = ex.run.samples;
  const double t0 = ex.run.t0, t1 = ex.run.t1;
  int k = 0;
  for (auto _ : state) {
    const double t = N == 1 ? t0 : t0 + (t1 - t0) * k / (N - 1);
    mo2d::inverse_dynamics_sample(model, data, t);
    benchmark::DoNotOptimize(data.u.data());
    benchmark::ClobberMemory();
    if (++k == N) {  // wrap around: start a fresh run
      k = 0;
      data.has_previous = false;
      data.q0 = model.q0;
    }
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["s/sample"] = per_item(static_cast<double>(state.iterations()));
  state.counters["newton_it"] = data.newton_iterations;
  // factorizations of K and of the Newton Jacobian on the fixed pattern, and analyses of it
  const auto& lk = *data.lu_K;
  const auto& lp = *data.lu_pos;
  state.counters["sparse_K"] = static_cast<double>(lk.refactorizations);
  state.counters["analyses_K"] = static_cast<double>(lk.analyses);
  state.counters["sparse_J"] = static_cast<double>(lp.refactorizations);
  state.counters["analyses_J"] = static_cast<double>(lp.analyses);
}

void BM_Run(benchmark::State& state, Factory make) {
  const Example ex = make();
  const mo2d::Model model = mo2d::build_model(ex.system);
  for (auto _ : state) {
    mo2d::Trajectory r = mo2d::inverse_dynamics(model, ex.motion, ex.run);
    benchmark::DoNotOptimize(r.efforts.data());
    benchmark::ClobberMemory();
  }
  const double items = static_cast<double>(state.iterations()) * ex.run.samples;
  state.SetItemsProcessed(static_cast<int64_t>(items));
  state.counters["samples"] = ex.run.samples;
  state.counters["s/sample"] = per_item(items);
}

void BM_BuildModel(benchmark::State& state, Factory make) {
  const Example ex = make();
  for (auto _ : state) {
    mo2d::Model model = mo2d::build_model(ex.system);
    benchmark::DoNotOptimize(&model);
    benchmark::ClobberMemory();
  }
}

}  // namespace

BENCHMARK_CAPTURE(BM_Sample, whitworth, &mo2d::mechanisms::whitworth)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Sample, rrr3, &mo2d::mechanisms::rrr3)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Run, whitworth, &mo2d::mechanisms::whitworth)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Run, rrr3, &mo2d::mechanisms::rrr3)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BuildModel, whitworth, &mo2d::mechanisms::whitworth)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_BuildModel, rrr3, &mo2d::mechanisms::rrr3)->Unit(benchmark::kMicrosecond);
