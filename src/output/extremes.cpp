// The extremes of a run's columns located between its samples (mo2d/extremes.hpp): candidates
// among the samples, a fine grid over the two intervals around each from the run's own solver
// (inverse_dynamics_sample, or the integrator again from the recorded state), the root of the
// derivative of the local interpolating polynomial.
#include "mo2d/extremes.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <functional>
#include <map>
#include <utility>

#include "mo2d/error.hpp"

namespace mo2d {

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// The values of every column at n equally spaced times from sample k0 to sample k1 (rows).
using GridFn = std::function<void(int k0, int k1, int n, MatrixXd& values)>;

// A located extreme's polynomial and the one through its inner kExtremeFit - 2 points agree there
// to this fraction of the column's largest |value| on the grid (else: not smooth enough to locate)
constexpr double kExtremeFitTolerance = 1e-9;

// An extreme of one column inside a fine grid: its value, time and whether it was located.
struct Found {
  double value, t;
  bool located;
};

// The polynomial through (u_i, y_i), i = 0..deg, in Newton form on the nodes u: coefficients of
// the divided differences; eval writes p, p', p'' at x.
struct NewtonPoly {
  std::vector<double> u, c;
  NewtonPoly(std::vector<double> nodes, const std::vector<double>& y) : u(std::move(nodes)), c(y) {
    const int n = static_cast<int>(c.size());
    for (int j = 1; j < n; ++j)
      for (int i = n - 1; i >= j; --i) c[i] = (c[i] - c[i - 1]) / (u[i] - u[i - j]);
  }
  void eval(double x, double& p, double& dp, double& ddp) const {
    const int n = static_cast<int>(c.size());
    p = c[n - 1], dp = 0, ddp = 0;
    for (int k = n - 2; k >= 0; --k) {
      ddp = ddp * (x - u[k]) + 2 * dp;
      dp = dp * (x - u[k]) + p;
      p = p * (x - u[k]) + c[k];
    }
  }
};

// The root of p' in [lo, hi] (p'(lo) > 0 > p'(hi): a maximum of p) by Newton on p', kept inside
// the bracket by bisection.
double derivative_root(const NewtonPoly& poly, double lo, double hi) {
  double x = 0.5 * (lo + hi);
  for (int it = 0; it < 100 && hi - lo > 1e-15 * std::max(1.0, std::abs(x)); ++it) {
    double p, dp, ddp;
    poly.eval(x, p, dp, ddp);
    if (dp == 0) return x;
    (dp > 0 ? lo : hi) = x;
    const double newton = ddp < 0 ? x - dp / ddp : NAN;
    x = newton > lo && newton < hi ? newton : 0.5 * (lo + hi);
  }
  return x;
}

// The maximum of y (sign * column, n points from ta to tb) near its largest point: the root of
// the derivative of the polynomial through the kExtremeFit points around it, in the interval on
// either side of that point. At_start / at_end: ta / tb is the run's first / last sample (an
// extreme there may be the end point itself).
Found grid_maximum(const std::vector<double>& y, double ta, double tb, bool at_start, bool at_end) {
  const int n = static_cast<int>(y.size());
  const int j = static_cast<int>(std::max_element(y.begin(), y.end()) - y.begin());
  const double h = (tb - ta) / (n - 1);
  auto time = [&](int i) { return i == n - 1 ? tb : ta + h * i; };
  const Found fallback{y[j], time(j), false};
  if (n < kExtremeFit) return fallback;
  const int half = kExtremeFit / 2;
  const int w0 = std::clamp(j - half, 0, n - kExtremeFit);
  // nodes u = (t - t_center) / (half h) in [-1, 1], shifted with the window
  std::vector<double> u(kExtremeFit), v(kExtremeFit);
  for (int i = 0; i < kExtremeFit; ++i) {
    u[i] = static_cast<double>(w0 + i - (w0 + half)) / half;
    v[i] = y[w0 + i];
  }
  const NewtonPoly poly(u, v);
  const double uj = static_cast<double>(j - (w0 + half)) / half, du = 1.0 / half;
  const double lo = j > 0 ? uj - du : uj, hi = j < n - 1 ? uj + du : uj;
  double p, dlo, dhi, ddp;
  poly.eval(lo, p, dlo, ddp);
  poly.eval(hi, p, dhi, ddp);
  if (!(dlo > 0 && dhi < 0)) {
    // the largest point is an end of the run with the column leaving the span rising: it is the
    // extreme; else the polynomial has no maximum there (a kink): the point itself, not located
    if ((j == 0 && at_start && dhi <= 0) || (j == n - 1 && at_end && dlo >= 0))
      return {y[j], time(j), true};
    return fallback;
  }
  const double x = derivative_root(poly, lo, hi);
  poly.eval(x, p, dlo, ddp);
  if (!(p >= y[j]) || !std::isfinite(p)) return fallback;
  // the interpolation error: the polynomial through the inner kExtremeFit - 2 points differs from
  // it by ~1e-12 of the column on a smooth stretch; near a kink or a spike (a singular passage)
  // they part, and the largest fine point is reported instead
  const NewtonPoly inner(std::vector<double>(u.begin() + 1, u.end() - 1),
                         std::vector<double>(v.begin() + 1, v.end() - 1));
  double q, dq, ddq;
  inner.eval(x, q, dq, ddq);
  double size = 0;
  for (const double yi : y) size = std::max(size, std::abs(yi));
  if (!(std::abs(p - q) <= kExtremeFitTolerance * size)) return fallback;
  return {p, ta + h * (w0 + half) + x * half * h, true};
}

// The samples that may hold the maximum of sign * column c (at most 3, best first): the local
// maxima of the samples within the largest second difference of the best (the most a smooth
// column rises between samples). Empty for a column without curvature (constant or linear: its
// extremes are samples, `best`).
std::vector<int> candidates(const MatrixXd& values, int c, double sign, int& best) {
  const int N = static_cast<int>(values.rows());
  auto g = [&](int k) { return sign * values(k, c); };
  best = 0;
  double curvature = 0;
  for (int k = 0; k < N; ++k) {
    if (g(k) > g(best)) best = k;
    if (k > 0 && k < N - 1)
      curvature = std::max(curvature, std::abs(g(k + 1) - 2 * g(k) + g(k - 1)));
  }
  std::vector<std::pair<double, int>> found;
  if (curvature > 0)
    for (int k = 0; k < N; ++k)
      if ((k == 0 || g(k) >= g(k - 1)) && (k == N - 1 || g(k) >= g(k + 1)) &&
          g(k) >= g(best) - curvature)
        found.emplace_back(g(k), k);
  std::sort(found.rbegin(), found.rend());
  std::vector<int> out;
  for (std::size_t i = 0; i < found.size() && i < 3; ++i) out.push_back(found[i].second);
  return out;
}

// The two sample intervals around sample k (one at an end of the run).
std::pair<int, int> bracket(int k, int N) {
  return {std::max(k - 1, 0), std::min(k + 1, N - 1)};
}

// The maximum of sign * column c: each candidate located on its fine grid (grids: by bracket,
// absent where the fine evaluation failed).
Found column_maximum(const VectorXd& time, const MatrixXd& values, int c, double sign,
                     const std::vector<int>& cand, int best,
                     const std::map<std::pair<int, int>, MatrixXd>& grids) {
  const int N = static_cast<int>(time.size());
  Found out{sign * values(best, c), time[best], cand.empty()};
  bool first = true;
  for (const int k : cand) {
    const auto [k0, k1] = bracket(k, N);
    const auto it = grids.find({k0, k1});
    if (it == grids.end()) continue;
    const MatrixXd& v = it->second;
    std::vector<double> y(v.rows());
    for (int i = 0; i < v.rows(); ++i) y[i] = sign * v(i, c);
    const Found f = grid_maximum(y, time[k0], time[k1], k0 == 0, k1 == N - 1);
    if (first || f.value > out.value) out = f;
    first = false;
  }
  return out;
}

std::vector<Extreme> locate(const Trajectory& r, const MatrixXd& values,
                            const std::vector<std::string>& labels, const GridFn& fill) {
  std::vector<Extreme> out;
  const int N = static_cast<int>(r.time.size());
  if (N == 0) return out;
  const int C = static_cast<int>(labels.size());
  // the candidates of every column's maximum (sign +1) and minimum (-1), then their grids in
  // the order of time (a solver asked again at times far apart may walk between them:
  // efforts_from_inverse), then the extremes
  std::vector<std::vector<int>> cand(2 * C);
  std::vector<int> best(2 * C);
  std::map<std::pair<int, int>, MatrixXd> grids;
  for (int j = 0; j < 2 * C; ++j) {
    cand[j] = candidates(values, j / 2, j % 2 ? -1.0 : 1.0, best[j]);
    for (const int k : cand[j])
      if (N > 1) grids.emplace(bracket(k, N), MatrixXd());
  }
  for (auto it = grids.begin(); it != grids.end();) {
    const auto [k0, k1] = it->first;
    const int n = k1 - k0 == 2 ? kExtremeGrid : (kExtremeGrid + 1) / 2;
    it->second.resize(n, values.cols());
    bool ok = true;
    try {
      fill(k0, k1, n, it->second);
    } catch (const std::exception&) {  // e.g. a singular configuration there: not located
      ok = false;
    }
    it = ok && it->second.allFinite() ? std::next(it) : grids.erase(it);
  }
  for (int c = 0; c < C; ++c) {
    Extreme e{.label = labels[c]};
    e.sampled_max = values.col(c).maxCoeff();
    e.sampled_min = values.col(c).minCoeff();
    const Found hi = column_maximum(r.time, values, c, 1.0, cand[2 * c], best[2 * c], grids);
    const Found lo =
        column_maximum(r.time, values, c, -1.0, cand[2 * c + 1], best[2 * c + 1], grids);
    e.max = hi.value, e.t_max = hi.t, e.located_max = hi.located;
    e.min = -lo.value, e.t_min = lo.t, e.located_min = lo.located;
    out.push_back(std::move(e));
  }
  return out;
}

// Efforts, reactions and (if asked for and present) the output columns of r, side by side.
int output_count(const Model& m, const Trajectory& r, const OutputRequest& outputs) {
  if (outputs.empty() || r.output_labels.empty()) return 0;
  return output_column_labels(m, outputs) == r.output_labels
             ? static_cast<int>(r.output_labels.size())
             : 0;
}

MatrixXd columns_of(const Trajectory& r, int nout, std::vector<std::string>& labels) {
  const Eigen::Index N = r.time.size(), nu = r.efforts.cols(), nr = r.reactions.cols();
  MatrixXd v(N, nu + nr + nout);
  v.leftCols(nu) = r.efforts;
  v.middleCols(nu, nr) = r.reactions;
  if (nout) v.rightCols(nout) = r.outputs;
  labels = r.input_labels;
  labels.insert(labels.end(), r.reaction_labels.begin(), r.reaction_labels.end());
  if (nout) labels.insert(labels.end(), r.output_labels.begin(), r.output_labels.end());
  return v;
}

// One row of the values: efforts, reactions, outputs at the state (q0, q1, t).
void row_of(const Model& m, const OutputRequest& outputs, int nout, const VectorXd& u,
            const VectorXd& reactions, const VectorXd& q0, const VectorXd& q1, double t,
            VectorXd& out_tmp, MatrixXd& v, int i) {
  v.row(i).head(u.size()) = u.transpose();
  v.row(i).segment(u.size(), reactions.size()) = reactions.transpose();
  if (nout) {
    output_column_values(m, outputs, q0, q1, t, out_tmp);
    v.row(i).tail(nout) = out_tmp.transpose();
  }
}

}  // namespace

std::vector<Extreme> locate_extremes(const Model& m, std::span<const Prescribed> motion,
                                     const InverseOptions& options, const Trajectory& r,
                                     const OutputRequest& outputs) {
  std::vector<std::string> labels;
  const int nout = output_count(m, r, outputs);
  const MatrixXd values = columns_of(r, nout, labels);
  InverseOptions o = options;
  o.monitor = {};
  InverseData d(m, motion, o);
  VectorXd out_tmp(nout);
  return locate(r, values, labels, [&](int k0, int k1, int n, MatrixXd& v) {
    // from the recorded configuration at k0 (the same branch), then from sample to sample
    d.q0 = r.q0.row(k0).transpose();
    d.has_previous = false;
    const double ta = r.time[k0], tb = r.time[k1];
    for (int i = 0; i < n; ++i) {
      const double t = i == n - 1 ? tb : ta + (tb - ta) * i / (n - 1);
      inverse_dynamics_sample(m, d, t);
      row_of(m, outputs, nout, d.u, d.reactions, d.q0, d.q1, t, out_tmp, v, i);
    }
  });
}

std::vector<Extreme> locate_extremes(const Model& m, const ForwardOptions& options,
                                     const Trajectory& r, const OutputRequest& outputs) {
  std::vector<std::string> labels;
  const int nout = output_count(m, r, outputs);
  const MatrixXd values = columns_of(r, nout, labels);
  VectorXd out_tmp(nout);
  // the method the run chose for its accuracy (at its first state), once: each re-integration
  // runs it (without choose_method's stiffness test)
  ForwardOptions method = options;
  if (options.accuracy > 0 && r.time.size() > 0) {
    const State first{r.time[0], r.q0.row(0).transpose(), r.q1.row(0).transpose()};
    method = choose_method(m, first, options).options;
    method.accuracy = 0;
  }
  return locate(r, values, labels, [&](int k0, int k1, int n, MatrixXd& v) {
    // the run's integrator again over the two intervals, from the state recorded at k0
    ForwardOptions o = method;
    o.t0 = r.time[k0];
    o.t1 = r.time[k1];
    o.samples = n;
    o.progress = {};
    o.monitor = {};
    o.stop_when = {};
    // a budget of the run's own size (a re-integration that cannot end, e.g. an end-time step the
    // floating-point grid cannot take, issue 30 item 1, throws: that extreme is not located)
    o.max_steps = static_cast<int>(
        std::min<long>(options.max_steps, std::max<long>(10000, 2 * r.stats.steps)));
    o.max_seconds = 5 + 2 * r.stats.cpu_seconds;
    const State s{o.t0, r.q0.row(k0).transpose(), r.q1.row(k0).transpose()};
    const Trajectory f = forward_dynamics(m, s, o);
    if (f.time.size() != n) throw Error("extremes: the re-integration stopped early");
    for (int i = 0; i < n; ++i)
      row_of(m, outputs, nout, f.efforts.row(i).transpose(), f.reactions.row(i).transpose(),
             f.q0.row(i).transpose(), f.q1.row(i).transpose(), f.time[i], out_tmp, v, i);
  });
}

std::vector<Extreme> sampled_extremes(const Model& m, const Trajectory& r,
                                      const OutputRequest& outputs) {
  std::vector<std::string> labels;
  const int nout = output_count(m, r, outputs);
  const MatrixXd values = columns_of(r, nout, labels);
  return locate(r, values, labels, [](int, int, int, MatrixXd&) {
    throw Error("extremes: the samples only");  // no grid: each extreme its best sample
  });
}

}  // namespace mo2d
