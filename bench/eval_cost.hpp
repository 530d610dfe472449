#pragma once
// CPU time of one evaluation of the accelerations (forward_accelerations, the integrators'
// right-hand side) at a state: bench/scale_bench.cpp and bench/peers_bench.cpp.
#include <algorithm>
#include <ctime>
#include <vector>

#include "mo2d/forward.hpp"
#include "mo2d/forward_data.hpp"

namespace mo2d::bench {

inline double cpu_now() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// The median over 5 batches of the CPU seconds per evaluation, after a first evaluation (which
// sizes the factorizations); a batch is doubled until it takes 20 ms (one evaluation per batch,
// 3 batches, when one takes over 0.5 s).
inline double eval_cost(const Model& m, const State& s, LinearAlgebra la) {
  ForwardOptions o{.integrator = Integrator::rk4, .step = 2e-3};
  o.linear_algebra = la;
  ForwardData d(m, o);
  const Eigen::VectorXd u = Eigen::VectorXd::Zero(m.n_inputs());
  auto run = [&](int batch) {
    const double c0 = cpu_now();
    for (int k = 0; k < batch; ++k) forward_accelerations(m, d, 0.0, s.q0, s.q1, u);
    return (cpu_now() - c0) / batch;
  };
  const double first = run(1);
  int batch = 1, repeats = first > 0.5 ? 3 : 5;
  while (first < 0.5 && run(batch) * batch < 0.02 && batch < (1 << 20)) batch *= 2;
  std::vector<double> per;
  for (int r = 0; r < repeats; ++r) per.push_back(run(batch));
  std::sort(per.begin(), per.end());
  return per[per.size() / 2];
}

}  // namespace mo2d::bench
