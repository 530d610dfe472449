#pragma once
// Internal to kinematics and the solvers: the row scaling of a dimensionless Jacobian (the public
// column_scaling, dimensionless_jacobian and conditioning tests: mo2d/kinematics.hpp).
#include <Eigen/Core>

namespace mo2d::detail {

// out[i] = 1 / |row i of J diag(d)| (1 for a zero row): diag(out) J diag(d) has unit rows.
void unit_row_scale(const Eigen::MatrixXd& J, const Eigen::VectorXd& d, Eigen::VectorXd& out);

}  // namespace mo2d::detail
