// User constraints at velocity level (VelocityConstraintDef, e.g. rolling without slipping): the
// `labels` form sorted into coordinates and quasi-velocities, and the check that g is linear in
// the rates. A simple non-holonomic invariant is affine in q1 (Orsino eq. 2.11):
//   g(x, v, t) = A(x, t) v + b(x, t) = 0,
// which is what the velocity rows (constraints/user.hpp: A = dg/dv at v = 0, b = g(x, 0, t)) and
// the acceleration bias assume; a g with a term in v^2, |v| or v_i v_j would be silently linearized
// at v = 0, so it is refused here.
#include <algorithm>
#include <array>
#include <cmath>

#include "constraints/common.hpp"
#include "mo2d/error.hpp"
#include "model/build_stages.hpp"
#include "model/suggest.hpp"
#include "run/format.hpp"

namespace mo2d::build {

namespace {

std::vector<std::string> sorted_keys(const std::unordered_map<std::string, int>& index) {
  std::vector<std::string> out;
  out.reserve(index.size());
  for (const auto& [k, v] : index) out.push_back(k);
  std::sort(out.begin(), out.end());
  return out;
}

// The label's coordinate when it names the rate of a node joined to the ground ("A.vx" of a
// fixed "A.x"), else "".
std::string fixed_rate_coordinate(const Model& m, const std::string& label) {
  for (const char* s : {".vx", ".vy"}) {
    const std::string suffix = s;
    if (label.size() > suffix.size() && label.ends_with(suffix)) {
      std::string c = label.substr(0, label.size() - suffix.size()) + "." + suffix.substr(2);
      if (m.fixed_coordinates.count(c)) return c;
    }
  }
  return "";
}

[[noreturn]] void unknown_label(const Model& m, const std::string& label, const std::string& what) {
  if (m.fixed_coordinates.count(label))
    throw Error(what + ": coordinate '" + label + "' is fixed (joined to the ground)", label);
  if (const std::string c = fixed_rate_coordinate(m, label); !c.empty())
    throw Error(
        what + ": quasi-velocity '" + label + "' is zero (its node is joined to the ground)",
        label);
  std::vector<std::string> names = sorted_keys(m.coordinate_index);
  const std::vector<std::string> rates = sorted_keys(m.rate_index);
  names.insert(names.end(), rates.begin(), rates.end());
  throw Error(
      what + ": unknown coordinate or quasi-velocity '" + label + "'" + did_you_mean(label, names),
      label);
}

}  // namespace

VelocityConstraintDef sort_velocity_labels(const Model& m, const std::string& prefix,
                                           const VelocityConstraintDef& def,
                                           const std::string& what) {
  const std::string name = prefix + def.name;
  if (def.g || !def.coords.empty() || !def.rates.empty())
    throw Error(what + ": give either coords, rates and g, or labels and g_labels, not both", name);
  if (def.labels.size() > static_cast<size_t>(detail::kMaxUserArgs))
    throw Error(what + " has more than 32 arguments", name);
  struct Slot {
    bool rate = false;
    int index = 0;
  };
  std::vector<Slot> slots;
  VelocityConstraintDef out;
  out.name = def.name;
  for (const auto& label : def.labels) {
    const std::string full = prefix + label;
    const bool coordinate = m.coordinate_index.count(full) > 0, rate = m.rate_index.count(full) > 0;
    if (coordinate && rate)
      throw Error(what + ": '" + full + "' is both a coordinate and a quasi-velocity label", full);
    if (!coordinate && !rate) unknown_label(m, full, what);
    std::vector<std::string>& list = rate ? out.rates : out.coords;
    slots.push_back({rate, static_cast<int>(list.size())});
    list.push_back(label);
  }
  if (out.rates.empty())
    throw Error(what + ": uses no quasi-velocity (labels such as 'disc.w', 'disc.C.vx'); a " +
                    "constraint on coordinates only belongs at position level (psi)",
                name);
  out.g = [f = def.g_labels, slots](std::span<const Jet> x, std::span<const Jet> v, Jet t) {
    std::array<Jet, detail::kMaxUserArgs> a;
    const size_t n = slots.size();
    for (size_t k = 0; k < n; ++k) a[k] = slots[k].rate ? v[slots[k].index] : x[slots[k].index];
    return f(std::span<const Jet>(a.data(), n), t);
  };
  return out;
}

void check_linear_in_rates(const Constraint::UserVelocity& c, const VelocityConstraintDef& def,
                           const Eigen::VectorXd& q0, const std::string& what,
                           const std::string& name) {
  const int nx = static_cast<int>(c.args.size()), nv = static_cast<int>(c.rates.size());
  std::array<Jet, detail::kMaxUserArgs> x, v;
  for (int k = 0; k < nx; ++k) x[k] = Jet(q0[c.args[k].var]);
  const std::span<const Jet> xs(x.data(), nx), vs(v.data(), nv);
  // g at the rates w (t = 0), and the slopes A_k = dg/dv_k at v = 0
  auto g_at = [&](const std::array<double, detail::kMaxUserArgs>& w) {
    for (int k = 0; k < nv; ++k) v[k] = Jet(w[k]);
    return c.g(xs, vs, Jet(0.0)).v;
  };
  std::array<double, detail::kMaxUserArgs> w{}, slope{};
  const double g0 = g_at(w);
  for (int k = 0; k < nv; ++k) {
    for (int j = 0; j < nv; ++j) v[j] = Jet(0.0, j == k ? 1.0 : 0.0, 0.0);
    slope[k] = c.g(xs, vs, Jet(0.0)).d;
  }
  // |g(w) - g(0) - A w| against the size of its terms (round-off only if g is affine in v)
  auto affine_error = [&](const std::array<double, detail::kMaxUserArgs>& rates, double& gw) {
    gw = g_at(rates);
    double linear = 0, size = std::abs(g0) + std::abs(gw);
    for (int k = 0; k < nv; ++k)
      linear += slope[k] * rates[k], size += std::abs(slope[k] * rates[k]);
    const double err = gw - g0 - linear;
    return std::isfinite(err) && std::abs(err) > 1e-9 * size ? err : 0.0;
  };
  const std::string rule =
      "; a velocity constraint must be linear in the quasi-velocities (g = A(x, t) v + b(x, t), "
      "Orsino eq. 2.11)";
  for (int k = 0; k < nv; ++k)
    for (const double s : {1.0, -2.0}) {
      w.fill(0.0);
      w[k] = s;
      double gw = 0;
      if (const double err = affine_error(w, gw); err != 0)
        throw Error(what + ": g is not linear in '" + def.rates[k] + "': at the initial " +
                        "configuration g = " + detail::fmt(gw) + " at " + def.rates[k] + " = " +
                        detail::fmt(s) + " (the other rates 0), but g(0) + (dg/dv) v = " +
                        detail::fmt(gw - err) + rule,
                    name);
    }
  for (int k = 0; k < nv; ++k) w[k] = (k % 2 == 0 ? 1.0 : -1.0) * (1.0 + 0.5 * k);
  double gw = 0;
  if (const double err = affine_error(w, gw); err != 0)
    throw Error(what + ": g is not linear in the quasi-velocities (a product of rates?): at the " +
                    "initial configuration g(v) - g(0) - (dg/dv) v = " + detail::fmt(err) + rule,
                name);
}

}  // namespace mo2d::build
