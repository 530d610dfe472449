// The budgets of linearizations, equilibria and modes (modes_internal.hpp). Their matrices are
// dense (the tangent bases, the Jacobian of the accelerations, G and its eigenvectors), so their
// memory and time grow as the cube of the mechanism's size and are estimated from its sizes
// before anything is allocated or factorized: a mechanism beyond the budgets is refused at once,
// naming the sizes, instead of working for minutes and failing late. During the work, the
// wall-clock budget is checked between the stages (RunBudget, which also polls interrupts).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "mo2d/budget.hpp"
#include "mo2d/error.hpp"
#include "mo2d/run_stop.hpp"
#include "modes/modes_internal.hpp"
#include "run/format.hpp"

namespace mo2d::detail {

namespace {

struct Sizes {
  double n0, n1, m0, m1, nk, p, dof, n;
};

Sizes sizes_of(const Model& m) {
  Sizes s{};
  s.n0 = m.n0;
  s.n1 = m.n1;
  s.m0 = m.m0;
  s.m1 = m.m1;
  s.nk = s.n1 + s.m1;
  s.p = std::max(0.0, s.n0 - s.m0);
  s.dof = std::max(0.0, s.n1 - s.m1);
  s.n = s.p + s.dof;
  return s;
}

// Floating-point operations (multiply-adds counted as 2) of one linearization: the SVDs of the
// dimensionless Psi and A (full V: choose_coordinates), the QRs of [Psi; E0] and [A; E]
// (tangent_bases), the LU of [M A^T; A 0] and its solve for n0 + n1 directions, their right-hand
// sides (dA per direction) and the products of linearize.
double linearize_flops(const Sizes& s) {
  const double svd = kSvdFlops * (std::pow(s.n0, 3) + std::pow(s.n1, 3));
  const double qr = 4.0 / 3 * (std::pow(s.n0, 3) + std::pow(s.n1, 3));
  const double lu = 2.0 / 3 * std::pow(s.nk, 3) + 2 * s.nk * s.nk * (s.n0 + s.n1);
  const double rhs = 3 * s.n0 * s.m1 * s.n1;
  const double products = 2 * s.n1 * (s.n0 + s.n1) * s.n;
  return svd + qr + lu + rhs + products;
}

// Bytes of one linearization: Psi, A and their SVDs' copies and V, the QRs of the selections, the
// dense forward workspace (M, [M A^T; A 0] and its LU), the directions' right-hand sides and
// solutions, the Jacobian, G and the tangent bases.
double linearize_bytes(const Sizes& s) {
  const double values = 3 * (s.n0 * s.n0 + s.n1 * s.n1) + s.m0 * s.n0 + s.m1 * s.n1 +
                        8 * s.n1 * s.n1 + 4 * s.nk * s.nk + 2 * s.nk * (s.n0 + s.n1) +
                        s.n1 * (s.n0 + s.n1) + 2 * s.n * s.n + 3 * (s.n0 + s.n1) * s.n;
  return 8 * values;
}

// Bytes kept per state of a linearization along a reference: its StateSpace (G, the tangent
// bases) and the position basis coordinates_along keeps to choose the coordinates.
double kept_bytes(const Sizes& s) {
  return 8 * (s.n * s.n + (s.n0 + 2 * s.n1) * s.n + 2 * s.n0 * s.p);
}

// The eigenvalues and eigenvectors of G (n x n, real Schur form then complex vectors), and one
// Mode per eigenvalue (its complex eigenvector and dq0).
double modes_flops(const Sizes& s) {
  return 25 * std::pow(s.n, 3);
}
double modes_bytes(const Sizes& s) {
  return 8 * (9 * s.n * s.n + s.n * s.n0);
}

std::string dims(double r, double c) {
  return fmt(r) + " x " + fmt(c);
}

void check_sizes_budget(const std::string& what, const std::string& name, const Sizes& s,
                        double max_seconds, double max_memory, int linearizations, bool modes) {
  const double k = std::max(linearizations, 0);
  const double bytes = (k > 0 ? linearize_bytes(s) : 0.0) + (k > 1 ? k * kept_bytes(s) : 0.0) +
                       (modes ? modes_bytes(s) : 0.0);
  const double seconds =
      (k * linearize_flops(s) + (modes ? modes_flops(s) : 0.0)) / kDenseFlopsPerSecond;
  std::ostringstream work;
  if (k > 0)
    work << (k > 1 ? fmt(k) + " linearizations" : std::string("the linearization"))
         << " (the SVD of the " << dims(s.m0, s.n0) << " position Jacobian, the LU of the "
         << dims(s.nk, s.nk) << " matrix [M A^T; A 0] for " << fmt(s.n0 + s.n1) << " directions)";
  if (modes) work << (k > 0 ? " and " : "") << "the eigenvectors of the " << dims(s.n, s.n) << " G";
  check_memory(what, bytes, max_memory, work.str(), "max_memory");
  if (max_seconds > 0 && std::isfinite(max_seconds) && seconds > max_seconds)
    throw BudgetExhausted(
        what + " needs about " + fmt(seconds) + " s for " + work.str() +
            " (dense: the time grows as the cube of the size; estimated at " +
            fmt(kDenseFlopsPerSecond / 1e9) + " Gflop/s), more than the wall-time budget of " +
            fmt(max_seconds) +
            " s (max_seconds: scene run.max_seconds, mo2d --max-seconds): the mechanism is too "
            "large for mo2d's dense linearization within it",
        name);
}

}  // namespace

void check_modes_budget(const std::string& what, const Model& m, double max_seconds,
                        double max_memory, int linearizations, bool modes) {
  check_sizes_budget(what, m.name, sizes_of(m), max_seconds, max_memory, linearizations, modes);
}

void check_eigen_budget(const std::string& what, const StateSpace& ss, double max_seconds,
                        double max_memory) {
  Sizes s{};
  s.n0 = static_cast<double>(ss.q0.size());
  s.n1 = static_cast<double>(ss.q1.size());
  s.n = ss.n();
  check_sizes_budget(what, what, s, max_seconds, max_memory, 0, true);
}

RunBudget::Settings modes_budget(const std::string& what, const Model& m, double t,
                                 double max_seconds) {
  return {.run = what,
          .name = m.name,
          .t0 = t,
          .t1 = t,
          .max_steps = 0,
          .max_seconds = max_seconds,
          .monitor = {},
          .interval = 1e9,
          .hint = {},
          .unit = "stages"};
}

}  // namespace mo2d::detail
