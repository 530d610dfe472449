// design_summary (mo2d/design.hpp): each input effort's mean, RMS, peak-to-peak, energy
// fluctuation and flywheel inertia (trapezoid rule over the samples), and the four-bar loops'
// closed forms with their transmission angles' extremes in the run.
#include <algorithm>
#include <cmath>
#include <limits>

#include "mo2d/design.hpp"
#include "mo2d/error.hpp"

namespace mo2d {

namespace {

EffortMeasures effort_measures(const Model& m, const Trajectory& r, int input, double cs) {
  const Input& in = m.inputs[input];
  const Eigen::Index N = r.time.size();
  const Eigen::VectorXd u = r.efforts.col(input);
  Eigen::VectorXd v = Eigen::VectorXd::Zero(N);  // the input's rate B^T q1
  for (const auto& [ref, coef] : in.terms)
    if (ref.var >= 0) v += coef * r.q1.col(ref.var);
  const Eigen::VectorXd P = u.cwiseProduct(v);
  const double T = r.time[N - 1] - r.time[0];
  auto integral = [&](const Eigen::VectorXd& f) {
    double s = 0;
    for (Eigen::Index k = 1; k < N; ++k) s += 0.5 * (f[k] + f[k - 1]) * (r.time[k] - r.time[k - 1]);
    return s;
  };
  EffortMeasures e;
  e.input = in.label;
  e.mean = integral(u) / T;
  e.rms = std::sqrt(integral(u.cwiseAbs2()) / T);
  e.peak_to_peak = u.maxCoeff() - u.minCoeff();
  e.travel = integral(v);
  e.mean_speed = e.travel / T;
  const double P_mean = integral(P) / T;
  double E = 0, lo = 0, hi = 0;
  for (Eigen::Index k = 1; k < N; ++k) {
    E += 0.5 * (P[k] + P[k - 1] - 2 * P_mean) * (r.time[k] - r.time[k - 1]);
    lo = std::min(lo, E);
    hi = std::max(hi, E);
  }
  e.energy_fluctuation = hi - lo;
  e.flywheel_inertia = cs > 0 && e.mean_speed != 0
                           ? e.energy_fluctuation / (cs * e.mean_speed * e.mean_speed)
                           : std::numeric_limits<double>::quiet_NaN();
  return e;
}

}  // namespace

DesignSummary design_summary(const Model& m, const Trajectory& r, const DesignRequest& q) {
  if (r.time.size() < 2 || !(r.time[r.time.size() - 1] > r.time[0]))
    throw Error("design: the summary needs at least two samples over a time > 0", "design");
  if (r.efforts.cols() != m.n_inputs() || r.q1.cols() != m.n1)
    throw Error("design: the trajectory does not match the model '" + m.name + "'", "design");
  DesignSummary s;
  s.speed_fluctuation = q.speed_fluctuation;
  for (int k = 0; k < m.n_inputs(); ++k)
    s.efforts.push_back(effort_measures(m, r, k, q.speed_fluctuation));
  for (const FourBarDef& f : q.four_bars) {
    FourBarSummary b;
    b.name = f.name;
    b.lengths = four_bar_lengths(m, f);
    b.grashof = grashof_class(b.lengths);
    b.positions = four_bar_positions(b.lengths);
    b.run_min_transmission = b.run_max_transmission = std::numeric_limits<double>::quiet_NaN();
    for (size_t c = 0; c < r.output_labels.size(); ++c)
      if (r.output_labels[c] == f.name + ".transmission_angle") {
        b.run_min_transmission = r.outputs.col(static_cast<Eigen::Index>(c)).minCoeff();
        b.run_max_transmission = r.outputs.col(static_cast<Eigen::Index>(c)).maxCoeff();
      }
    s.four_bars.push_back(b);
  }
  return s;
}

}  // namespace mo2d
