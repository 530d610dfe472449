// The recursive orthogonal complement of the constraint Jacobian along the tree of subsystems
// (Orsino, Theorem 2.10): InverseOptions::complement = ComplementMethod::recursive.
#include <Eigen/QR>
#include <Eigen/SVD>

#include "mo2d/error.hpp"
#include "mo2d/inverse.hpp"
#include "mo2d/model.hpp"

namespace mo2d {

// ---- recursive orthogonal complement (Theorem 2.10) ---------------------------------------------
namespace {

MatrixXd null_space(const MatrixXd& Bm) {
  const int n = static_cast<int>(Bm.cols());
  if (Bm.rows() == 0) return MatrixXd::Identity(n, n);
  Eigen::ColPivHouseholderQR<MatrixXd> qr(Bm.transpose());
  qr.setThreshold(1e-10);
  const int r = static_cast<int>(qr.rank());
  const MatrixXd Q = qr.householderQ();
  return Q.rightCols(n - r);
}

MatrixXd complement_of(const Model& m, const Eigen::Ref<const MatrixXd>& A, int node,
                       std::vector<int>& vars) {
  const TreeNode& tn = m.tree[node];
  vars = tn.vars;
  std::vector<MatrixXd> S_children;
  std::vector<std::vector<int>> child_vars;
  for (int ch : tn.children) {
    std::vector<int> cv;
    S_children.push_back(complement_of(m, A, ch, cv));
    child_vars.push_back(std::move(cv));
  }
  int cols = static_cast<int>(tn.vars.size());
  for (const auto& S : S_children) cols += static_cast<int>(S.cols());
  for (const auto& cv : child_vars) vars.insert(vars.end(), cv.begin(), cv.end());
  const int n = static_cast<int>(vars.size());
  MatrixXd R = MatrixXd::Zero(n, cols);  // R = blockdiag(I, S_children)  (2.34)
  const int own = static_cast<int>(tn.vars.size());
  R.topLeftCorner(own, own).setIdentity();
  int r0 = own, c0 = own;
  for (const auto& S : S_children) {
    R.block(r0, c0, S.rows(), S.cols()) = S;
    r0 += static_cast<int>(S.rows());
    c0 += static_cast<int>(S.cols());
  }
  MatrixXd Aown(tn.rows.size(), n);  // external constraints of this node
  for (size_t i = 0; i < tn.rows.size(); ++i)
    for (int j = 0; j < n; ++j) Aown(i, j) = A(tn.rows[i], vars[j]);
  const MatrixXd C = null_space(Aown * R);  // B = A_ext R, C = null(B)
  return R * C;                             // S = R C  (2.35)
}

}  // namespace

MatrixXd recursive_complement(const Model& m, const Eigen::Ref<const MatrixXd>& A) {
  if (m.reduction == Reduction::flat && m.tree.size() > 1)
    throw Error("the recursive complement needs a model built with Reduction::subsystems or none",
                m.name);
  std::vector<int> vars;
  const MatrixXd S = complement_of(m, A, 0, vars);
  if (static_cast<int>(vars.size()) != m.n1)
    throw Error("internal: subsystem tree does not cover all variables", m.name);
  MatrixXd out(m.n1, S.cols());
  for (int k = 0; k < m.n1; ++k) out.row(vars[k]) = S.row(k);
  return out;
}

}  // namespace mo2d
