#pragma once
// Internal to kinematics: the position constraints over a subset of the coordinates.
#include <Eigen/Core>

#include "mo2d/model.hpp"

namespace mo2d::detail {

// psi(q0, t) (m0) and its Jacobian over the columns colmap[k] >= 0 of coordinate k (colmap null:
// all n0 coordinates), J zeroed first. On a plain MatrixXd (zeroed as one block) for the solvers'
// hot path; the public position_jacobian takes any Eigen::Ref.
void position_jacobian(const Model& m, const Eigen::Ref<const Eigen::VectorXd>& q0, double t,
                       const int* colmap, Eigen::VectorXd& psi, Eigen::MatrixXd& J);

}  // namespace mo2d::detail
