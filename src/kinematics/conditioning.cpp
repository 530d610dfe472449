// Kinematics: rank tests of the constraint Jacobians at the initial configuration, and the
// conditioning of their dimensionless form (column_scaling, mo2d/kinematics.hpp).
#include "kinematics/conditioning.hpp"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "kinematics/sparse_kinematics.hpp"
#include "mo2d/error.hpp"
#include "mo2d/kinematics.hpp"

namespace mo2d {

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

namespace {

// The same checks on the sparse Jacobians (large models: kinematics/sparse_kinematics.hpp).
void check_sparse_ranks(const Model& m, const VectorXd& q0, double t) {
  VectorXd psi(m.m0), b(m.m1);
  detail::SparseRowsK J;
  const VectorXd d = column_scaling(m);
  detail::sparse_position_jacobian(m, q0, t, nullptr, m.n0, psi, J);
  detail::make_dimensionless(J, d.head(m.n0));
  if (auto rows = detail::sparse_dependent_rows(J, 1e-10); !rows.empty())
    throw_redundant(rows, m.position_row_labels, "position", t);
  detail::sparse_velocity_jacobian(m, q0, t, J, b);
  detail::make_dimensionless(J, d);
  if (auto rows = detail::sparse_dependent_rows(J, 1e-10); !rows.empty())
    throw_redundant(rows, m.velocity_row_labels, "velocity", t);
}

}  // namespace

void check_constraint_ranks(const Model& m, const VectorXd& q0, double t) {
  if (detail::sparse_kinematics(m)) return check_sparse_ranks(m, q0, t);
  VectorXd psi(m.m0), b(m.m1);
  MatrixXd Psi(m.m0, m.n0), A(m.m1, m.n1);
  position_jacobian(m, q0, t, psi, Psi);
  velocity_jacobian(m, q0, t, A, b);
  // on the dimensionless Jacobians: the rank test does not depend on units or size
  MatrixXd B;
  const VectorXd d = column_scaling(m);
  dimensionless_jacobian(Psi, d.head(m.n0), B);
  if (auto rows = dependent_rows(B, 1e-10); !rows.empty())
    throw_redundant(rows, m.position_row_labels, "position", t);
  dimensionless_jacobian(A, d, B);
  if (auto rows = dependent_rows(B, 1e-10); !rows.empty())
    throw_redundant(rows, m.velocity_row_labels, "velocity", t);
}

VectorXd column_scaling(const Model& m) {
  VectorXd d = VectorXd::Ones(m.n1);
  std::vector<bool> set(m.n1, false);
  for (const Body& b : m.bodies) {
    if (b.omega.var < 0) continue;
    double l = 0;
    for (const Vec2& p : b.geometry) l = std::max(l, (p - b.geometry[0]).norm());
    if (!(l > 0) && b.mass > 0 && b.inertia > 0) l = std::sqrt(b.inertia / b.mass);
    if (!(l > 0)) l = m.scale;
    // bodies sharing one rotation (welded): the largest of them
    d[b.omega.var] = set[b.omega.var] ? std::min(d[b.omega.var], 1 / l) : 1 / l;
    set[b.omega.var] = true;
  }
  for (const auto& k : m.constraints) {
    const auto* coordinate = std::get_if<Constraint::Coordinate>(&k.def);
    if (!coordinate) continue;
    const Constraint::Coordinate& c = *coordinate;
    double s = 0;
    for (const auto& [ref, w] : c.rate_terms)
      if (ref.var >= 0 && ref.var != c.coord) s = std::max(s, std::abs(w) * d[ref.var]);
    if (s > 0 && std::isfinite(s)) d[c.coord] = s;
  }
  return d;
}

void dimensionless_jacobian(const MatrixXd& J, const VectorXd& d, MatrixXd& out) {
  out.noalias() = J * d.asDiagonal();
  for (Eigen::Index i = 0; i < out.rows(); ++i) {
    const double nr = out.row(i).norm();
    if (nr > 0) out.row(i) /= nr;
  }
}

Conditioning conditioning(const MatrixXd& J, const VectorXd& column_scale) {
  Conditioning c;
  c.rows = static_cast<int>(J.rows());
  c.cols = static_cast<int>(J.cols());
  if (J.size() == 0) return c;
  MatrixXd B;
  dimensionless_jacobian(J, column_scale, B);
  Eigen::JacobiSVD<MatrixXd> svd(B);
  const auto& s = svd.singularValues();
  c.sigma_max = s[0];
  c.sigma_min = s[s.size() - 1];
  const double thr = 1e-10 * c.sigma_max;
  for (int k = 0; k < s.size(); ++k) c.rank += s[k] > thr;
  c.condition = c.sigma_min > 0 ? c.sigma_max / c.sigma_min : INFINITY;
  return c;
}

namespace {

std::string largest_entries(const VectorXd& v, const std::vector<std::string>& labels) {
  std::vector<int> idx(v.size());
  for (int k = 0; k < v.size(); ++k) idx[k] = k;
  std::sort(idx.begin(), idx.end(), [&](int a, int b) { return std::abs(v[a]) > std::abs(v[b]); });
  std::string s;
  const double top = v.size() ? std::abs(v[idx[0]]) : 0.0;
  for (int k = 0; k < std::min<int>(3, static_cast<int>(v.size())); ++k)
    if (std::abs(v[idx[k]]) > 0.1 * top && idx[k] < static_cast<int>(labels.size()))
      s += (s.empty() ? "'" : ", '") + labels[idx[k]] + "'";
  return s;
}

}  // namespace

SingularDirection singular_direction(const MatrixXd& J, const VectorXd& d,
                                     const std::vector<std::string>& row_labels,
                                     const std::vector<std::string>& col_labels) {
  if (J.size() == 0) return {};
  MatrixXd B;
  dimensionless_jacobian(J, d, B);
  Eigen::JacobiSVD<MatrixXd> svd(B, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const int k = static_cast<int>(std::min(B.rows(), B.cols())) - 1;
  return {largest_entries(svd.matrixU().col(k), row_labels),
          largest_entries(svd.matrixV().col(k), col_labels)};
}

namespace {

// conditioning() on a sparse Jacobian (large models: kinematics/sparse_kinematics.hpp)
Conditioning sparse_conditioning(detail::SparseRowsK& J, const VectorXd& d) {
  Conditioning c;
  c.rows = static_cast<int>(J.rows());
  c.cols = static_cast<int>(J.cols());
  if (c.rows == 0 || c.cols == 0) return c;
  detail::make_dimensionless(J, d);
  const detail::SparseSingular s = detail::sparse_extreme_singular_values(J, 1e-10);
  c.sigma_max = s.sigma_max;
  c.sigma_min = s.sigma_min;
  c.rank = s.rank;
  c.condition = c.sigma_min > 0 ? c.sigma_max / c.sigma_min : INFINITY;
  return c;
}

}  // namespace

Conditioning velocity_conditioning(const Model& m, const VectorXd& q0, double t) {
  if (detail::sparse_kinematics(m)) {
    detail::SparseRowsK A;
    VectorXd b(m.m1);
    detail::sparse_velocity_jacobian(m, q0, t, A, b);
    return sparse_conditioning(A, column_scaling(m));
  }
  MatrixXd A(m.m1, m.n1);
  VectorXd b(m.m1);
  velocity_jacobian(m, q0, t, A, b);
  return conditioning(A, column_scaling(m));
}

Conditioning position_conditioning(const Model& m, const VectorXd& q0, double t) {
  if (detail::sparse_kinematics(m)) {
    detail::SparseRowsK Psi;
    VectorXd psi(m.m0);
    detail::sparse_position_jacobian(m, q0, t, nullptr, m.n0, psi, Psi);
    return sparse_conditioning(Psi, column_scaling(m).head(m.n0));
  }
  MatrixXd Psi(m.m0, m.n0);
  VectorXd psi(m.m0);
  position_jacobian(m, q0, t, psi, Psi);
  return conditioning(Psi, column_scaling(m).head(m.n0));
}

DofReport degrees_of_freedom(const Model& m, const VectorXd& q0, double t) {
  return {m.n1 - velocity_conditioning(m, q0, t).rank, m.n0 - position_conditioning(m, q0, t).rank};
}

void detail::unit_row_scale(const MatrixXd& J, const VectorXd& d, VectorXd& out) {
  for (Eigen::Index i = 0; i < J.rows(); ++i) {
    double s = 0;
    for (Eigen::Index j = 0; j < J.cols(); ++j) s += (J(i, j) * d[j]) * (J(i, j) * d[j]);
    out[i] = s > 0 ? 1.0 / std::sqrt(s) : 1.0;
  }
}

}  // namespace mo2d
