// The energy balance of a forward run (mo2d/forward.hpp) and the run's check of it.
#include <algorithm>
#include <cmath>

#include "forward/forward_run.hpp"
#include "mo2d/error.hpp"
#include "mo2d/forward.hpp"

namespace mo2d {

using detail::fmt;

VectorXd energy_balance(const Trajectory& r) {
  if (!r.has_energies())
    throw Error("energy balance: the trajectory has no energies (an inverse-dynamics run)",
                "energies");
  const Eigen::Index n = r.time.size();
  if (n == 0) return VectorXd();
  auto or_zero = [n](const VectorXd& v) { return v.size() == n ? v : VectorXd(VectorXd::Zero(n)); };
  const VectorXd e = r.kinetic + r.potential;
  return e.array() - e[0] - or_zero(r.input_work).array() - or_zero(r.load_work).array() -
         or_zero(r.constraint_work).array() + or_zero(r.dissipated).array();
}

double energy_balance_error(const Trajectory& r) {
  const VectorXd b = energy_balance(r);
  return b.size() ? b.cwiseAbs().maxCoeff() : 0.0;
}

// A forward run whose energy balance (energy_balance: E(t) - E(0) - the work of the inputs, loads
// and constraints + the energy dissipated, each integrated by the run itself) is off by more than
// kBalanceWarn of the run's energy scale (the largest sum of the magnitudes of those terms at a
// sample) is not accurate, whatever its steps' error estimates said: too long a fixed step over a
// singular passage, a reduced element whose held state does work. A warning naming the largest
// error, its time and the first time it passed the bound.
void detail::check_energy_balance(const Model& m, Trajectory& r) {
  constexpr double kBalanceWarn = 1e-2;
  if (!r.has_energies() || r.time.size() < 2) return;
  const VectorXd b = energy_balance(r);
  const Eigen::Index n = b.size();
  auto at = [n](const VectorXd& v, Eigen::Index k) { return v.size() == n ? std::abs(v[k]) : 0.0; };
  double scale = 0, size = 0;  // size: of the energies themselves (rounding of a run at rest)
  for (Eigen::Index k = 0; k < n; ++k) {
    const double dV = r.potential.size() == n ? r.potential[k] - r.potential[0] : 0.0;
    scale =
        std::max(scale, at(r.kinetic, k) + std::abs(dV) + at(r.input_work, k) + at(r.load_work, k) +
                            at(r.constraint_work, k) + at(r.dissipated, k));
    size = std::max(size, at(r.kinetic, k) + at(r.potential, k));
  }
  const double bound = std::max({kBalanceWarn * scale, 1e-9 * size, 1e-12});
  Eigen::Index worst = 0, first = -1;
  for (Eigen::Index k = 0; k < n; ++k) {
    if (first < 0 && !(std::abs(b[k]) <= bound)) first = k;
    if (!(std::abs(b[k]) <= std::abs(b[worst]))) worst = k;
  }
  if (first < 0) return;
  r.stats.warnings.push_back(
      "energy balance of '" + m.name + "' off by " + fmt(b[worst]) +
      " J at t = " + fmt(r.time[worst]) + " s (" + fmt(std::abs(b[worst]) / scale) +
      " of the run's energy scale " + fmt(scale) + " J; above " + fmt(kBalanceWarn) +
      " of it from t = " + fmt(r.time[first]) +
      " s): the result is not accurate; use a tighter tolerance, a shorter step or another method");
}

}  // namespace mo2d
