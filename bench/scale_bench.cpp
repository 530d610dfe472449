// Scaling of mo2d in the size of the mechanism (issue 14, docs/performance.md "Scaling"): on the
// IFToMM N-four-bar (bench/n_fourbar.hpp), per N, the CPU time of
//   build      build_model (assembly and rank checks included)
//   state      consistent_state (the initial velocities)
//   describe   describe() and velocity_conditioning() (what `mo2d info` adds to the build)
//   eval       one forward_accelerations (the integrators' right-hand side) on the sparse and the
//              dense path: the median over repeated batches, after a first evaluation
// A plain program printing a Markdown table; --csv FILE writes the same numbers as CSV (the input
// of docs/img/n_scaling.png, apps/render_engine_figures.cpp). Run on one core:
//   taskset -c 1 build/bench/mo2d_scale_bench [--max-n N] [--dense-max-n N] [--csv FILE]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <string>
#include <vector>

#include "eval_cost.hpp"
#include "mo2d/forward.hpp"
#include "mo2d/forward_data.hpp"
#include "mo2d/kinematics.hpp"
#include "mo2d/model.hpp"
#include "n_fourbar.hpp"

namespace {

using namespace mo2d;

template <class F>
double timed(F&& f) {
  const double c0 = bench::cpu_now();
  f();
  return bench::cpu_now() - c0;
}

struct Row {
  int n = 0, n1 = 0, m1 = 0;
  double build = 0, state = 0, describe = 0, sparse = NAN, dense = NAN;
};

Row measure(int n, int dense_max_n) {
  Row r;
  r.n = n;
  Model m;
  r.build = timed([&] { m = build_model(bench::n_fourbar(n)); });
  r.n1 = m.n1;
  r.m1 = m.m1;
  State s;
  r.state = timed([&] {
    s = consistent_state(m, {.positions = {}, .velocities = {{"crank0.w", -1.0}}});
  });
  std::size_t chars = 0;
  r.describe = timed([&] {
    chars = describe(m).size();
    chars += static_cast<std::size_t>(velocity_conditioning(m, m.q0).rank);
  });
  if (chars == 0) std::abort();
  r.sparse = bench::eval_cost(m, s, LinearAlgebra::sparse);
  if (n <= dense_max_n) r.dense = bench::eval_cost(m, s, LinearAlgebra::dense);
  return r;
}

// least-squares slope of log(cost) against log(N) over the rows with lo <= N <= hi
double exponent(const std::vector<Row>& rows, double Row::*cost, int lo, int hi) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int k = 0;
  for (const Row& r : rows)
    if (r.n >= lo && r.n <= hi && std::isfinite(r.*cost)) {
      const double x = std::log(r.n), y = std::log(r.*cost);
      sx += x, sy += y, sxx += x * x, sxy += x * y, ++k;
    }
  return k < 2 ? NAN : (k * sxy - sx * sy) / (k * sxx - sx * sx);
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IONBF, 0);
  int max_n = 1000, dense_max_n = 100;
  std::string csv;
  for (int k = 1; k < argc; ++k) {
    if (std::strcmp(argv[k], "--max-n") == 0 && k + 1 < argc)
      max_n = std::atoi(argv[++k]);
    else if (std::strcmp(argv[k], "--dense-max-n") == 0 && k + 1 < argc)
      dense_max_n = std::atoi(argv[++k]);
    else if (std::strcmp(argv[k], "--csv") == 0 && k + 1 < argc)
      csv = argv[++k];
    else {
      std::fprintf(stderr, "usage: mo2d_scale_bench [--max-n N] [--dense-max-n N] [--csv FILE]\n");
      return 2;
    }
  }
  std::printf(
      "| N | n1 | m1 | build_model | consistent_state | describe + conditioning | eval, sparse | "
      "eval, dense |\n|---|---|---|---|---|---|---|---|\n");
  std::vector<Row> rows;
  for (int n : {2, 5, 10, 20, 40, 100, 400, 1000}) {
    if (n > max_n) break;
    const Row r = measure(n, dense_max_n);
    rows.push_back(r);
    std::printf("| %d | %d | %d | %.3g ms | %.3g ms | %.3g ms | %.3g µs | %.3g µs |\n", r.n, r.n1,
                r.m1, 1e3 * r.build, 1e3 * r.state, 1e3 * r.describe, 1e6 * r.sparse,
                1e6 * r.dense);
  }
  std::printf("\nfitted exponent over N = 10 ... %d: eval sparse %.3f, build %.3f, state %.3f\n",
              max_n, exponent(rows, &Row::sparse, 10, max_n),
              exponent(rows, &Row::build, 10, max_n), exponent(rows, &Row::state, 10, max_n));
  if (!csv.empty()) {
    std::ofstream f(csv);
    f << "N,n1,m1,build_s,state_s,describe_s,eval_sparse_s,eval_dense_s\n";
    for (const Row& r : rows)
      f << r.n << ',' << r.n1 << ',' << r.m1 << ',' << r.build << ',' << r.state << ','
        << r.describe << ',' << r.sparse << ',' << r.dense << '\n';
  }
  return 0;
}
