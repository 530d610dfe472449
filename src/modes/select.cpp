// The independent coordinates of a linearization (mo2d/modes.hpp) and the continuously varying
// tangent bases of their chart.
//
// Positions: the tangent space of psi(q0) = 0 at q0* is null(Psi). In dimensionless columns
// (Psi diag(d0), column_scaling) an orthonormal basis N (n0 x p) is taken from the SVD only to
// *choose*: column-pivoted QR of N^T ranks the coordinates by how well they parametrize the
// tangent space; the first p are E0. The basis itself is dq0/dz = K0^-1 [0; I], K0 = [Psi; E0]:
// smooth in q0 and unique (the SVD's N is neither), as Proposition 4.4 needs.
// Velocities: the rates of the p coordinates, then dof - p more chosen the same way in the part
// of null(A diag(d)) where those rates vanish; dq1/dw = K^-1 [0; I], K = [A; E] (Theorem 2.8's
// C = K^-1 [0; I] of the null-space formulation).
#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

#include "mo2d/error.hpp"
#include "mo2d/kinematics.hpp"
#include "modes/modes_internal.hpp"

namespace mo2d::detail {

namespace {

// Orthonormal basis of the null space of J (rows x cols), rank by a relative threshold.
MatrixXd null_basis(const MatrixXd& J, int cols) {
  if (J.rows() == 0) return MatrixXd::Identity(cols, cols);
  Eigen::JacobiSVD<MatrixXd> svd(J, Eigen::ComputeFullV);
  const auto& s = svd.singularValues();
  const double tol = 1e-9 * std::max(1.0, s.size() ? s[0] : 0.0);
  int rank = 0;
  for (int i = 0; i < s.size(); ++i) rank += s[i] > tol;
  return svd.matrixV().rightCols(cols - rank);
}

// The k rows of N (n x k) that best parametrize its span: column-pivoted QR of N^T.
std::vector<int> pivot_rows(const MatrixXd& N, int k) {
  std::vector<int> rows;
  if (k == 0) return rows;
  Eigen::ColPivHouseholderQR<MatrixXd> qr(N.transpose());
  for (int i = 0; i < k; ++i) rows.push_back(qr.colsPermutation().indices()[i]);
  return rows;
}

// Smallest singular value of the rows `sel` of the orthonormal basis N: 1 for a perfect choice,
// 0 when the selected variables cannot parametrize the span.
double selection_quality(const MatrixXd& N, const std::vector<int>& sel) {
  if (sel.empty()) return 1;
  MatrixXd R(sel.size(), N.cols());
  for (size_t i = 0; i < sel.size(); ++i) R.row(static_cast<Eigen::Index>(i)) = N.row(sel[i]);
  Eigen::JacobiSVD<MatrixXd> svd(R);
  return svd.singularValues().size() ? svd.singularValues().tail(1)[0] : 0.0;
}

std::string join(const std::vector<std::string>& labels, const std::vector<int>& idx) {
  std::string s;
  for (int i : idx) s += (s.empty() ? "" : ", ") + labels[i];
  return s;
}

}  // namespace

void choose_coordinates(const Model& m, const State& ref, const LinearizeOptions& o,
                        StateSpace& ss) {
  const VectorXd d = column_scaling(m);
  VectorXd psi(m.m0), b(m.m1);
  MatrixXd Psi(m.m0, m.n0), A(m.m1, m.n1);
  position_jacobian(m, ref.q0, ref.t, psi, Psi);
  velocity_jacobian(m, ref.q0, ref.t, A, b);
  const MatrixXd N0 = null_basis(Psi * d.head(m.n0).asDiagonal(), m.n0);
  const MatrixXd N1 = null_basis(A * d.asDiagonal(), m.n1);
  ss.p = static_cast<int>(N0.cols());
  ss.dof = static_cast<int>(N1.cols());
  if (ss.p > ss.dof)
    throw Error("linearization of '" + m.name + "': " + std::to_string(ss.p) +
                    " position coordinates but only " + std::to_string(ss.dof) +
                    " independent velocities (the velocity constraints are not the derivatives "
                    "of the position constraints here)",
                m.name, ref.t);
  // positions
  if (o.coordinates.empty()) {
    ss.coordinate_vars = pivot_rows(N0, ss.p);
  } else {
    for (const auto& l : o.coordinates) ss.coordinate_vars.push_back(m.coordinate(l));
  }
  const std::string given = join(m.coordinate_labels, ss.coordinate_vars);
  if (static_cast<int>(ss.coordinate_vars.size()) != ss.p)
    throw Error("linearization of '" + m.name + "': " + std::to_string(ss.p) +
                    " independent coordinates are needed, " +
                    std::to_string(ss.coordinate_vars.size()) + " given (" + given + ")",
                m.name, ref.t);
  const double position_quality = selection_quality(N0, ss.coordinate_vars);
  if (position_quality < 1e-6)
    throw Error("linearization of '" + m.name + "': the coordinates " + given +
                    " do not parametrize the configurations near this one (the constraints tie "
                    "them); give instead e.g. " +
                    join(m.coordinate_labels, pivot_rows(N0, ss.p)),
                m.name, ref.t);
  // velocities: the coordinates' rates, then the rest in the part of null(A) where they vanish
  ss.velocity_vars = ss.coordinate_vars;
  const int extra = ss.dof - ss.p;
  if (o.velocities.empty()) {
    MatrixXd R(ss.p, ss.dof);
    for (int i = 0; i < ss.p; ++i) R.row(i) = N1.row(ss.coordinate_vars[i]);
    const MatrixXd N2 = N1 * null_basis(R, ss.dof);
    for (int k : pivot_rows(N2, extra)) ss.velocity_vars.push_back(k);
  } else {
    for (const auto& l : o.velocities) ss.velocity_vars.push_back(m.rate(l));
  }
  const std::string rates = join(m.rate_labels, ss.velocity_vars);
  const bool sized = static_cast<int>(ss.velocity_vars.size()) == ss.dof;
  const double velocity_quality = sized ? selection_quality(N1, ss.velocity_vars) : 0.0;
  ss.conditioning = std::min(position_quality, velocity_quality);
  if (velocity_quality < 1e-6)
    throw Error("linearization of '" + m.name + "': the quasi-velocities " + rates + " are not " +
                    std::to_string(ss.dof) + " independent ones at this configuration",
                m.name, ref.t);
  for (int k : ss.coordinate_vars) ss.states.push_back(m.coordinate_labels[k]);
  for (int k : ss.velocity_vars) ss.states.push_back(m.rate_labels[k]);
}

namespace {

// Candidate coordinates for bases (n0 x p each) along a reference, without repeats: the pivot's
// choice on all of them side by side (the coordinates that take part most over the whole
// reference), each single coordinate when p = 1, the pivot's choice at each state.
std::vector<std::vector<int>> candidates_along(const std::vector<MatrixXd>& bases, int n0, int p) {
  MatrixXd all(n0, static_cast<Eigen::Index>(bases.size()) * p);
  for (size_t i = 0; i < bases.size(); ++i)
    all.middleCols(static_cast<Eigen::Index>(i) * p, p) = bases[i];
  std::vector<std::vector<int>> tries = {pivot_rows(all, p)};
  for (int k = 0; p == 1 && k < n0; ++k) tries.push_back({k});
  for (const MatrixXd& N : bases) tries.push_back(pivot_rows(N, p));
  std::vector<std::vector<int>> out, seen;
  for (const auto& c : tries) {
    std::vector<int> sorted = c;
    std::sort(sorted.begin(), sorted.end());
    if (std::find(seen.begin(), seen.end(), sorted) != seen.end()) continue;
    seen.push_back(sorted);
    out.push_back(c);
  }
  return out;
}

}  // namespace

std::vector<int> coordinates_along(const Model& m, const std::vector<State>& states,
                                   RunBudget* budget) {
  const VectorXd d = column_scaling(m);
  VectorXd psi(m.m0);
  MatrixXd Psi(m.m0, m.n0);
  std::vector<MatrixXd> bases;
  for (const State& s : states) {
    if (budget != nullptr) budget->check(s.t, static_cast<long>(bases.size()), 0);
    position_jacobian(m, s.q0, s.t, psi, Psi);
    bases.push_back(null_basis(Psi * d.head(m.n0).asDiagonal(), m.n0));
    // a change of the DOF: the bases up to it (linearize_along reports the change)
    if (bases.back().cols() != bases.front().cols()) {
      bases.pop_back();
      break;
    }
  }
  const int p = static_cast<int>(bases.front().cols());
  std::vector<int> best;
  double best_worst = -1;
  for (const auto& c : candidates_along(bases, m.n0, p)) {
    double worst = 1;
    for (const MatrixXd& N : bases) worst = std::min(worst, selection_quality(N, c));
    if (worst > best_worst) {
      best_worst = worst;
      best = c;
    }
  }
  return best;
}

// X = K^-1 [0; I] for K = [J; rows sel of I] (least squares if J has redundant rows: consistent).
MatrixXd selection_basis(const MatrixXd& J, const std::vector<int>& sel, int cols,
                         const std::string& what, double t) {
  const auto rows = J.rows(), k = static_cast<Eigen::Index>(sel.size());
  MatrixXd K = MatrixXd::Zero(rows + k, cols), rhs = MatrixXd::Zero(rows + k, k);
  K.topRows(rows) = J;
  for (Eigen::Index i = 0; i < k; ++i) {
    K(rows + i, sel[i]) = 1.0;
    rhs(rows + i, i) = 1.0;
  }
  Eigen::ColPivHouseholderQR<MatrixXd> qr(K);
  if (qr.rank() < cols)
    throw Error("linearization: the " + what + " basis is singular at this configuration", what, t);
  return qr.solve(rhs);
}

void tangent_bases(const Model& m, const State& ref, StateSpace& ss) {
  VectorXd psi(m.m0), b(m.m1);
  MatrixXd Psi(m.m0, m.n0), A(m.m1, m.n1);
  position_jacobian(m, ref.q0, ref.t, psi, Psi);
  velocity_jacobian(m, ref.q0, ref.t, A, b);
  ss.dq0_dz = selection_basis(Psi, ss.coordinate_vars, m.n0, "position", ref.t);
  ss.dq1_dw = selection_basis(A, ss.velocity_vars, m.n1, "velocity", ref.t);
  // dq1/dz at fixed w: [A; E] dq1 = [d(b - A q1*) ; 0] along each tangent direction (central
  // differences of the velocity residual, smooth in q0)
  ss.dq1_dz = MatrixXd::Zero(m.n1, ss.p);
  const VectorXd d = column_scaling(m);
  VectorXd bp(m.m1), bm(m.m1);
  MatrixXd Ap(m.m1, m.n1), Am(m.m1, m.n1), rhs = MatrixXd::Zero(m.m1 + ss.dof, 1);
  MatrixXd K = MatrixXd::Zero(m.m1 + ss.dof, m.n1);
  K.topRows(m.m1) = A;
  for (int i = 0; i < ss.dof; ++i) K(m.m1 + i, ss.velocity_vars[i]) = 1.0;
  Eigen::ColPivHouseholderQR<MatrixXd> qr(K);
  bool any = false;
  for (int j = 0; j < ss.p; ++j) {
    const double h = 1e-5 * m.scale * d[ss.coordinate_vars[j]];
    const VectorXd v = ss.dq0_dz.col(j);
    velocity_jacobian(m, ref.q0 + h * v, ref.t, Ap, bp);
    velocity_jacobian(m, ref.q0 - h * v, ref.t, Am, bm);
    const VectorXd dr = ((bp - Ap * ref.q1) - (bm - Am * ref.q1)) / (2 * h);
    if (dr.lpNorm<Eigen::Infinity>() == 0) continue;
    any = true;
    rhs.col(0).head(m.m1) = dr;
    ss.dq1_dz.col(j) = qr.solve(rhs);
  }
  if (any) ss.approximate += "; dq1/dz by central differences of A q1 - b";
}

LinearizeOptions same_coordinates(const Model& m, const StateSpace& ss, LinearizeOptions o) {
  o.coordinates.clear();
  o.velocities.clear();
  for (int k : ss.coordinate_vars) o.coordinates.push_back(m.coordinate_labels[k]);
  for (int i = ss.p; i < ss.dof; ++i) o.velocities.push_back(m.rate_labels[ss.velocity_vars[i]]);
  return o;
}

}  // namespace mo2d::detail
