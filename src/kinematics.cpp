// Kinematics: constraint evaluation over all constraints, assembly, ranks and conditioning.
#include "mo2d/kinematics.hpp"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <cmath>
#include <sstream>

#include "constraints.hpp"
#include "mo2d/error.hpp"

namespace mo2d {

using detail::DenseSink;
using detail::DenseVelSink;
using detail::NullSink;

void position_residual(const Model& m, const Eigen::Ref<const VectorXd>& q0, double t,
                       Eigen::Ref<VectorXd> psi) {
  NullSink sink;
  for (const auto& c : m.constraints)
    if (c.nrow0 > 0) detail::position_rows(m, c, q0, t, psi, sink);
}

void position_jacobian(const Model& m, const Eigen::Ref<const VectorXd>& q0, double t,
                       Eigen::Ref<VectorXd> psi, Eigen::Ref<MatrixXd> Psi) {
  Psi.setZero();
  DenseSink sink{Psi, nullptr};
  for (const auto& c : m.constraints)
    if (c.nrow0 > 0) detail::position_rows(m, c, q0, t, psi, sink);
}

void velocity_jacobian(const Model& m, const Eigen::Ref<const VectorXd>& q0, double t,
                       Eigen::Ref<MatrixXd> A, Eigen::Ref<VectorXd> b) {
  A.setZero();
  DenseVelSink sink{A};
  for (const auto& c : m.constraints) detail::velocity_rows(m, c, q0, t, b, sink);
}

void acceleration_rhs(const Model& m, const Eigen::Ref<const VectorXd>& q0,
                      const Eigen::Ref<const VectorXd>& q1, double t, Eigen::Ref<VectorXd> c) {
  for (const auto& k : m.constraints) detail::acceleration_rows(m, k, q0, q1, t, c);
}

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

}  // namespace

VectorXd assemble(const Model& m, const VectorXd& q0_guess, double t, std::span<const int> fixed,
                  double tolerance) {
  VectorXd q = q0_guess;
  if (m.m0 == 0) return q;
  std::vector<int> colmap(m.n0, 0);
  for (int f : fixed) colmap[f] = -1;
  int nfree = 0;
  for (int& c : colmap) c = c < 0 ? -1 : nfree++;
  VectorXd psi(m.m0), trial_psi(m.m0), q_trial(m.n0);
  MatrixXd J(m.m0, nfree);
  const double tol = tolerance * m.scale;
  for (int it = 0; it < 100; ++it) {
    J.setZero();
    DenseSink sink{J, colmap.data()};
    for (const auto& c : m.constraints)
      if (c.nrow0 > 0) detail::position_rows(m, c, q, t, psi, sink);
    if (!psi.allFinite())
      throw Error("assembly: non-finite constraint residual " + worst_row(m.position_row_labels, psi),
                  m.position_row_labels[worst_index(psi)], t);
    const double norm = psi.norm();
    if (psi.lpNorm<Eigen::Infinity>() <= tol) return q;
    Eigen::CompleteOrthogonalDecomposition<MatrixXd> cod(J);
    cod.setThreshold(1e-12);
    const VectorXd dx = -cod.solve(psi);
    double alpha = 1;
    for (; alpha > 1e-8; alpha *= 0.5) {
      q_trial = q;
      for (int k = 0; k < m.n0; ++k)
        if (colmap[k] >= 0) q_trial[k] += alpha * dx[colmap[k]];
      position_residual(m, q_trial, t, trial_psi);
      if (trial_psi.allFinite() && trial_psi.norm() <= (1 - 1e-4 * alpha) * norm) break;
    }
    if (alpha <= 1e-8) break;
    q = q_trial;
  }
  position_residual(m, q, t, psi);
  throw Error("the mechanism cannot be assembled: Newton stalled with the largest residual in " +
                  worst_row(m.position_row_labels, psi) +
                  " (conflicting constraints or unreachable geometry)",
              m.position_row_labels[worst_index(psi)], t);
}

namespace {

// Rows of J that depend on the others: column-pivoted QR of J^T.
std::vector<int> dependent_rows(const MatrixXd& J, double threshold) {
  std::vector<int> out;
  if (J.rows() == 0) return out;
  Eigen::ColPivHouseholderQR<MatrixXd> qr(J.transpose());
  qr.setThreshold(threshold);
  const int r = static_cast<int>(qr.rank());
  for (int k = r; k < J.rows(); ++k) out.push_back(qr.colsPermutation().indices()[k]);
  return out;
}

void throw_redundant(const std::vector<int>& rows, const std::vector<std::string>& labels,
                     const char* level, double t) {
  std::ostringstream s;
  s << "redundant or conflicting constraints at the initial configuration (" << level
    << " level): ";
  for (size_t k = 0; k < rows.size(); ++k) s << (k ? ", " : "") << "'" << labels[rows[k]] << "'";
  s << (rows.size() == 1 ? " depends" : " depend") << " on the other constraints";
  throw Error(s.str(), labels[rows[0]], t);
}

}  // namespace

void check_constraint_ranks(const Model& m, const VectorXd& q0, double t) {
  VectorXd psi(m.m0), b(m.m1);
  MatrixXd Psi(m.m0, m.n0), A(m.m1, m.n1);
  position_jacobian(m, q0, t, psi, Psi);
  velocity_jacobian(m, q0, t, A, b);
  if (auto rows = dependent_rows(Psi, 1e-10); !rows.empty())
    throw_redundant(rows, m.position_row_labels, "position", t);
  if (auto rows = dependent_rows(A, 1e-10); !rows.empty())
    throw_redundant(rows, m.velocity_row_labels, "velocity", t);
}

namespace {
Conditioning conditioning_of(const MatrixXd& J) {
  Conditioning c;
  c.rows = static_cast<int>(J.rows());
  c.cols = static_cast<int>(J.cols());
  if (J.size() == 0) return c;
  Eigen::JacobiSVD<MatrixXd> svd(J);
  const auto& s = svd.singularValues();
  c.sigma_max = s[0];
  c.sigma_min = s[s.size() - 1];
  const double thr = 1e-10 * std::max(1.0, c.sigma_max);
  for (int k = 0; k < s.size(); ++k) c.rank += s[k] > thr;
  c.condition = c.sigma_min > 0 ? c.sigma_max / c.sigma_min : INFINITY;
  return c;
}
}  // namespace

Conditioning velocity_conditioning(const Model& m, const VectorXd& q0, double t) {
  MatrixXd A(m.m1, m.n1);
  VectorXd b(m.m1);
  velocity_jacobian(m, q0, t, A, b);
  return conditioning_of(A);
}

Conditioning position_conditioning(const Model& m, const VectorXd& q0, double t) {
  MatrixXd Psi(m.m0, m.n0);
  VectorXd psi(m.m0);
  position_jacobian(m, q0, t, psi, Psi);
  return conditioning_of(Psi);
}

DofReport degrees_of_freedom(const Model& m, const VectorXd& q0, double t) {
  return {m.n1 - velocity_conditioning(m, q0, t).rank, m.n0 - position_conditioning(m, q0, t).rank};
}

}  // namespace mo2d
