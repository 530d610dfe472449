#pragma once
// Kinematics over (model, coordinates): constraint residuals and Jacobians at position, velocity
// and acceleration level, assembly from approximate positions, rank and conditioning.
#include <Eigen/Core>
#include <span>
#include <string>
#include <vector>

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

// Dimensionless constraint Jacobians. The columns of a Jacobian carry the units of the variables
// (m/s for node velocities and slider rates, rad/s for rotation rates), its rows those of the
// constraints, so its singular values depend on the units and on the size of the mechanism (the
// rotation columns of a rigid body's rows scale with its length). column_scaling(m) returns d
// (n1; its first n0 entries scale the coordinates) with d = 1 for lengths and 1 / l for a
// rotation, l the size of its body (largest node distance from node 0; for a one-node body its
// radius of gyration; Model::scale if it has neither); an extra coordinate takes the largest
// |weight| d of its rate terms. J diag(d) with unit rows is then the Jacobian in lengths only
// (a rotation measured by the arc l theta): every singularity test in mo2d is made on it, so it
// does not depend on units or on the size of the mechanism.
VectorXd column_scaling(const Model& m);
// J diag(d) with every nonzero row divided by its norm, into out.
void dimensionless_jacobian(const MatrixXd& J, const VectorXd& d, MatrixXd& out);

// Rank and singular values of a dimensionless constraint Jacobian (see column_scaling).
struct Conditioning {
  // its size and numerical rank
  int rows = 0, cols = 0, rank = 0;
  // extreme singular values of the dimensionless Jacobian (column_scaling of the model, unit
  // rows): independent of units and of the mechanism's size
  double sigma_max = 0, sigma_min = 0;
  double condition = 0;  // sigma_max / sigma_min (inf if rank deficient)
};
// Singular values of the dimensionless velocity constraint Jacobian A at q0 (SVD; not for the
// hot path); rank: singular values above 1e-10 sigma_max.
Conditioning velocity_conditioning(const Model& m, const VectorXd& q0, double t = 0);
Conditioning position_conditioning(const Model& m, const VectorXd& q0, double t = 0);
// The same with a given column scaling (e.g. the one of the initial configuration).
Conditioning conditioning(const MatrixXd& J, const VectorXd& column_scale);

// Where the dimensionless J diag(d) (unit rows) is closest to losing rank: the rows that become
// dependent (left singular vector of its smallest singular value, sigma number min(rows, cols))
// and the variables of the motion they no longer determine (right singular vector), each as the
// labels of its largest entries (at most three, above 10 % of the largest): "'a', 'b'".
struct SingularDirection {
  // labels of the rows that become dependent, and of the variables they leave undetermined
  std::string rows, variables;
};
// The SingularDirection of J with column scaling d; row_labels and col_labels name J's rows and
// columns.
SingularDirection singular_direction(const MatrixXd& J, const VectorXd& d,
                                     const std::vector<std::string>& row_labels,
                                     const std::vector<std::string>& col_labels);

// Degrees of freedom at velocity level n1 - rank(A) and position level n0 - rank(Psi) at q0.
struct DofReport {
  // velocity-level and position-level degrees of freedom
  int velocity = 0, position = 0;
};
// The DofReport of model m at positions q0 and time t (s) (Orsino 2016 Def. 2.5).
DofReport degrees_of_freedom(const Model& m, const VectorXd& q0, double t = 0);

}  // namespace mo2d
