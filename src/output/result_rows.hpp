#pragma once
// Internal: writing one sample (row k) of a samples x n result matrix.
#include <Eigen/Core>

namespace mo2d::detail {

// x.row(k) = v^T. Eigen's row() of a matrix with no columns (a mechanism without coordinates,
// inputs or reactions) is an offset from its null data pointer, undefined behaviour that
// UBSan reports: such a row is skipped.
template <class Vector>
void set_row(Eigen::MatrixXd& x, Eigen::Index k, const Vector& v) {
  if (x.cols() > 0) x.row(k) = v.transpose();
}

}  // namespace mo2d::detail
