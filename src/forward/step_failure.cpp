// The efforts and loads that grew during a forward run (forward/step_failure.hpp).
#include "forward/step_failure.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"
#include "mo2d/forward.hpp"
#include "run/format.hpp"

namespace mo2d::detail {

LoadGrowth::LoadGrowth(const Model& m, const ForwardData& d, double t0, const VectorXd& q0,
                       const VectorXd& q1)
    : m_(m), d_(d), t0_(t0), q0_start_(q0), q1_start_(q1) {}

std::vector<double> LoadGrowth::values(double t, const VectorXd& q0, const VectorXd& q1) const {
  std::vector<double> v;
  auto add = [&](auto value) {  // a value that cannot be evaluated (not finite): inf
    try {
      v.push_back(value());
    } catch (const Error&) {
      v.push_back(INFINITY);
    }
  };
  for (size_t k = 0; k < d_.effort_laws.size(); ++k)
    add([&] { return law_value(m_, d_.effort_laws[k], q0, q1, t, "effort", m_.inputs[k].label); });
  for (const auto& f : m_.forces) add([&] { return point_force(m_, f, q0, q1, t).norm(); });
  for (const auto& tq : m_.torques) add([&] { return torque_value(m_, tq, q0, q1, t); });
  for (const auto& s : m_.springs) add([&] { return spring_value(m_, s, q0, q1, t).tension; });
  for (const auto& s : m_.torsional_springs)
    add([&] { return torsional_value(m_, s, q0, q1, t).torque; });
  return v;
}

std::string LoadGrowth::describe(double t, const VectorXd& q0, const VectorXd& q1) const {
  std::vector<std::string> labels;
  for (const auto& in : m_.inputs) labels.push_back(in.label);
  for (const auto& f : m_.forces) labels.push_back(f.name);
  for (const auto& tq : m_.torques) labels.push_back(tq.name);
  for (const auto& s : m_.springs) labels.push_back(s.name + ".tension");
  for (const auto& s : m_.torsional_springs) labels.push_back(s.name + ".torque");
  const std::vector<double> start = values(t0_, q0_start_, q1_start_), now = values(t, q0, q1);
  if (start.size() != labels.size() || now.size() != labels.size()) return "";
  // growth |v(t)| / |v(t0)|, with values far below the largest one at t (1e-9 of it) counted as
  // that floor, so that a load that starts at 0 has a finite growth
  double largest = 0;  // of the finite values (a value not finite has grown without bound)
  for (double x : now)
    if (std::isfinite(x)) largest = std::max(largest, std::abs(x));
  const double floor = std::max(1e-9 * largest, 1e-300);
  std::vector<double> growth(now.size());
  for (size_t k = 0; k < now.size(); ++k) {
    growth[k] = std::max(std::abs(now[k]), floor) / std::max(std::abs(start[k]), floor);
    if (std::isnan(growth[k])) growth[k] = 0;  // not finite at the start already: not a growth
  }
  std::vector<size_t> order(now.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return growth[a] > growth[b]; });
  std::string out;
  for (size_t i = 0; i < std::min<size_t>(3, order.size()); ++i) {
    const size_t k = order[i];
    if (!(growth[k] > kGrowth)) break;
    out += (out.empty() ? "; the loads grew (a law that blows up?): '" : ", '") + labels[k] +
           "' = " + fmt(now[k]) + " at t = " + fmt(t) + " s (" + fmt(start[k]) +
           " at t = " + fmt(t0_) + " s)";
  }
  return out;
}

std::string stiffness_cause(const Model& m, const ForwardOptions& o, ForwardData& d, const State& s,
                            double h_min, double regular) {
  try {
    const double pivot = d.pivot_indicator(s.t, s.q0);
    if (!(pivot >= regular)) return "";  // near-singular indeed
    ForwardOptions e = o;
    e.accuracy = kDefaultAccuracy;  // asks choose_method for its estimate of |lambda|max
    const double rho = choose_method(m, s, e).spectral_radius;
    if (!(rho * h_min > kStabilityBound)) return "";
    return "the dynamics are stiff there, not singular (pivot ratio " + fmt(pivot) +
           " at t = " + fmt(s.t) + " s): |lambda|max = " + fmt(rho) + " /s, so " +
           to_string(o.integrator) + " is stable only with steps below " +
           fmt(kStabilityBound / rho) + " s; use cvode_bdf (or an accuracy, which chooses it " +
           "for a stiff mechanism), or soften the stiff law (a gain, a stiffness)";
  } catch (const Error&) {
    return "";
  }
}

}  // namespace mo2d::detail
