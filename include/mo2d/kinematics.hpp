#pragma once
// Kinematics over (model, coordinates): constraint residuals and Jacobians at position, velocity
// and acceleration level, assembly from approximate positions, rank and conditioning.
#include <Eigen/Core>
#include <span>

#include "mo2d/model.hpp"

namespace mo2d {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// psi(q0, t) (size m0).
void position_residual(const Model& m, const Eigen::Ref<const VectorXd>& q0, double t,
                       Eigen::Ref<VectorXd> psi);
// psi and d psi / d q0 (m0 x n0).
void position_jacobian(const Model& m, const Eigen::Ref<const VectorXd>& q0, double t,
                       Eigen::Ref<VectorXd> psi, Eigen::Ref<MatrixXd> Psi);
// A(q0, t) q1 = b(q0, t) (A: m1 x n1).
void velocity_jacobian(const Model& m, const Eigen::Ref<const VectorXd>& q0, double t,
                       Eigen::Ref<MatrixXd> A, Eigen::Ref<VectorXd> b);
// A a1 = c(q0, q1, t): the acceleration constraints (the time derivative of A q1 = b).
void acceleration_rhs(const Model& m, const Eigen::Ref<const VectorXd>& q0,
                      const Eigen::Ref<const VectorXd>& q1, double t, Eigen::Ref<VectorXd> c);

// Newton (Gauss-Newton, minimum-norm steps) with a backtracking line search on psi = 0, holding
// the coordinates listed in `fixed` at their values in q0_guess. The minimum-norm step keeps the
// solution on the branch nearest the guess. Throws Error naming the worst constraint on failure.
VectorXd assemble(const Model& m, const VectorXd& q0_guess, double t, std::span<const int> fixed,
                  double tolerance = 1e-12);

// Throws Error naming the redundant constraint rows if the position or velocity Jacobian at q0
// is rank deficient.
void check_constraint_ranks(const Model& m, const VectorXd& q0, double t);

struct Conditioning {
  int rows = 0, cols = 0, rank = 0;
  double sigma_max = 0, sigma_min = 0;  // extreme nonzero-threshold singular values
  double condition = 0;                  // sigma_max / sigma_min (inf if rank deficient)
};
// Singular values of the velocity constraint Jacobian A at q0 (SVD; not for the hot path).
Conditioning velocity_conditioning(const Model& m, const VectorXd& q0, double t = 0);
Conditioning position_conditioning(const Model& m, const VectorXd& q0, double t = 0);

// Degrees of freedom at velocity level n1 - rank(A) and position level n0 - rank(Psi) at q0.
struct DofReport {
  int velocity = 0, position = 0;
};
DofReport degrees_of_freedom(const Model& m, const VectorXd& q0, double t = 0);

}  // namespace mo2d
