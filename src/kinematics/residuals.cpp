// Kinematics: the constraint residuals and Jacobians over all constraints, at position, velocity
// and acceleration level (each constraint's rows: constraints/constraints.hpp).
#include "kinematics/residuals.hpp"

#include "constraints/constraints.hpp"
#include "mo2d/kinematics.hpp"

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

void detail::position_jacobian(const Model& m, const Eigen::Ref<const VectorXd>& q0, double t,
                               const int* colmap, VectorXd& psi, MatrixXd& J) {
  J.setZero();
  DenseSink sink{J, colmap};
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

}  // namespace mo2d
