// Named summary values of a run (run_values.hpp).
#include "optimize/run_values.hpp"

#include <cmath>

#include "mo2d/error.hpp"

namespace mo2d::optimize_detail {

const std::vector<std::string>& run_value_prefixes() {
  static const std::vector<std::string> p{
      "peak", "max", "min", "mean", "rms", "peak_to_peak", "energy_fluctuation", "flywheel"};
  return p;
}

std::optional<RunValue> parse_run_value(const std::string& name) {
  const auto& p = run_value_prefixes();
  for (std::size_t k = 0; k < p.size(); ++k)
    if (name.size() > p[k].size() + 1 && name.compare(0, p[k].size(), p[k]) == 0 &&
        name[p[k].size()] == '.')
      return RunValue{static_cast<RunValue::Stat>(k), name.substr(p[k].size() + 1)};
  return std::nullopt;
}

namespace {

int find(const std::vector<std::string>& labels, const std::string& label) {
  for (std::size_t k = 0; k < labels.size(); ++k)
    if (labels[k] == label) return static_cast<int>(k);
  return -1;
}

// Time integral of f over the samples (trapezoid rule).
double integral(const Eigen::VectorXd& t, const Eigen::VectorXd& f) {
  double s = 0;
  for (Eigen::Index k = 1; k < t.size(); ++k) s += 0.5 * (f[k] + f[k - 1]) * (t[k] - t[k - 1]);
  return s;
}

}  // namespace

std::optional<Eigen::VectorXd> column_samples(const Trajectory& r, const std::string& label) {
  if (label == "t") return r.time;
  int k = find(r.coordinate_labels, label);
  if (k >= 0) return Eigen::VectorXd(r.q0.col(k));
  if ((k = find(r.rate_labels, label)) >= 0) return Eigen::VectorXd(r.q1.col(k));
  if (label.ends_with(".dot") && (k = find(r.rate_labels, label.substr(0, label.size() - 4))) >= 0)
    return Eigen::VectorXd(r.a1.col(k));
  if ((k = find(r.input_labels, label)) >= 0) return Eigen::VectorXd(r.efforts.col(k));
  if ((k = find(r.reaction_labels, label)) >= 0) return Eigen::VectorXd(r.reactions.col(k));
  if (r.has_energies()) {
    const std::pair<const char*, const Eigen::VectorXd*> energies[] = {
        {"energy.kinetic", &r.kinetic}, {"energy.potential", &r.potential},
        {"work.inputs", &r.input_work}, {"energy.dissipated", &r.dissipated},
        {"work.loads", &r.load_work},   {"work.constraints", &r.constraint_work}};
    for (const auto& [l, v] : energies)
      if (label == l) return *v;
  }
  if ((k = find(r.residual_labels, label)) >= 0) return Eigen::VectorXd(r.residuals.col(k));
  if ((k = find(r.output_labels, label)) >= 0) return Eigen::VectorXd(r.outputs.col(k));
  return std::nullopt;
}

double run_value(const RunValue& v, const Trajectory& r, const DesignSummary* d) {
  using S = RunValue::Stat;
  if (needs_design_summary(v)) {
    if (d)
      for (const EffortMeasures& e : d->efforts)
        if (e.input == v.column)
          return v.stat == S::flywheel ? e.flywheel_inertia : e.energy_fluctuation;
    throw Error("optimize: the run has no input '" + v.column + "'", v.column);
  }
  const std::optional<Eigen::VectorXd> c = column_samples(r, v.column);
  if (!c || c->size() == 0) throw Error("optimize: the run has no column '" + v.column + "'");
  const Eigen::VectorXd& x = *c;
  const Eigen::VectorXd& t = r.time;
  const double T = t.size() > 1 ? t[t.size() - 1] - t[0] : 0;
  switch (v.stat) {
    case S::peak:
      return x.cwiseAbs().maxCoeff();
    case S::max:
      return x.maxCoeff();
    case S::min:
      return x.minCoeff();
    case S::mean:
      return T > 0 ? integral(t, x) / T : x[0];
    case S::rms:
      return T > 0 ? std::sqrt(integral(t, x.cwiseAbs2()) / T) : std::abs(x[0]);
    case S::peak_to_peak:
      return x.maxCoeff() - x.minCoeff();
    default:
      break;
  }
  return 0;
}

}  // namespace mo2d::optimize_detail
