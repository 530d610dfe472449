// Kinematics: assembly of a configuration from approximate positions (build_model, and
// consistent_state for the initial state of a forward run), by solve_positions.
#include <cmath>
#include <sstream>

#include "kinematics/solve_positions.hpp"
#include "kinematics/sparse_kinematics.hpp"
#include "mo2d/error.hpp"
#include "mo2d/kinematics.hpp"

namespace mo2d {

namespace {

// Row with the largest |residual|, or the first non-finite one.
int worst_index(const VectorXd& r) {
  for (int k = 0; k < r.size(); ++k)
    if (!std::isfinite(r[k])) return k;
  Eigen::Index k = 0;
  if (r.size()) r.cwiseAbs().maxCoeff(&k);
  return static_cast<int>(k);
}

std::string worst_row(const std::vector<std::string>& labels, const VectorXd& r) {
  if (r.size() == 0) return "";
  const int k = worst_index(r);
  std::ostringstream s;
  s << "'" << labels[k] << "' (residual " << r[k] << ")";
  return s.str();
}

// Gauss-Newton from a guess that may be far from the constraints, with J rectangular or rank
// deficient when coordinates are fixed (solve_positions.hpp): 100 iterations, the last not tested.
detail::NewtonOptions assembly_newton(double tolerance) {
  return {.tolerance = tolerance,
          .max_iterations = 100,
          .test_last = false,
          .step = detail::NewtonStep::minimum_norm,
          .rank_threshold = 1e-12,
          .line_search = detail::LineSearch::armijo,
          .min_alpha = 1e-8,
          .non_finite = detail::NonFinite::reject};
}

using Status = detail::NewtonStatus;

Status dense_newton(const Model& m, double tolerance, double t, const std::vector<int>& colmap,
                    int nfree, VectorXd& q, VectorXd& psi) {
  VectorXd dx(nfree), q_trial(m.n0);
  MatrixXd J(m.m0, nfree);
  detail::NewtonBuffers w{.psi = psi, .J = J, .dx = dx, .q_trial = &q_trial};
  return detail::solve_positions(m, assembly_newton(tolerance), w, t, colmap, q).status;
}

// the same Newton on the sparse Jacobian (large models: kinematics/sparse_kinematics.hpp)
Status sparse_newton(const Model& m, double tolerance, double t, const std::vector<int>& colmap,
                     int nfree, VectorXd& q, VectorXd& psi) {
  using S = detail::SparseNewton;
  switch (detail::sparse_assembly_newton(m, tolerance, t, colmap, nfree, q, psi)) {
    case S::converged:
      return Status::converged;
    case S::non_finite:
      return Status::non_finite;
    case S::stalled:
      return Status::stalled;
    case S::max_iterations:
      break;
  }
  return Status::max_iterations;
}

}  // namespace

VectorXd assemble(const Model& m, const VectorXd& q0_guess, double t, std::span<const int> fixed,
                  double tolerance) {
  VectorXd q = q0_guess;
  if (m.m0 == 0) return q;
  std::vector<int> colmap(m.n0, 0);
  for (int f : fixed) colmap[f] = -1;
  int nfree = 0;
  for (int& c : colmap) c = c < 0 ? -1 : nfree++;
  VectorXd psi(m.m0);
  const Status status = detail::sparse_kinematics(m)
                            ? sparse_newton(m, tolerance * m.scale, t, colmap, nfree, q, psi)
                            : dense_newton(m, tolerance * m.scale, t, colmap, nfree, q, psi);
  if (status == Status::converged) return q;
  if (status == Status::non_finite)
    throw Error("assembly: non-finite constraint residual " + worst_row(m.position_row_labels, psi),
                m.position_row_labels[worst_index(psi)], t);
  // stalled (no acceptable step) or max_iterations: psi is evaluated at q
  throw Error("the mechanism cannot be assembled: Newton stalled with the largest residual in " +
                  worst_row(m.position_row_labels, psi) +
                  " (conflicting constraints or unreachable geometry)",
              m.position_row_labels[worst_index(psi)], t);
}

}  // namespace mo2d
