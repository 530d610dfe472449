// Static equilibrium (mo2d/modes.hpp). At rest (q1 = 0, scleronomic constraints: b = 0, c = 0)
// the accelerations are a = dq1/dw x with x = E a the independent ones, and
//   Mr x = Q(z),   Mr = dq1/dw^T M dq1/dw,   Q = dq1/dw^T (f + B u)   (C^T f = 0, eq. 4.1)
// so the equilibria are the zeros of r(z) = E a1(q0(z), 0), the rows w of the linearization's
// drift. Newton: G21 dz = -r, G21 = d r / d z the lower-left block of G (Gauss-Newton when
// dof > p); a backtracking line search on |r| and a bounded step keep it on the branch of the
// start; each iterate chooses its coordinates again, convergence is tested on |a| (lengths,
// independent of that choice). At r = 0,
// dQ/dz = Mr G21 (Mr^-1's derivative multiplies Q = 0): the reduced stiffness is Kr = -Mr G21, the
// Hessian of the potential for conservative loads.
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <cmath>
#include <sstream>

#include "mo2d/budget.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"
#include "mo2d/kinematics.hpp"
#include "mo2d/modes.hpp"
#include "mo2d/run_stop.hpp"
#include "modes/modes_internal.hpp"

namespace mo2d {

namespace {

State at_rest(const Model& m, const VectorXd& q0, double t) {
  State s;
  s.t = t;
  s.q0 = q0;
  s.q1 = VectorXd::Zero(m.n1);
  MatrixXd A(m.m1, m.n1);
  VectorXd b(m.m1);
  velocity_jacobian(m, q0, t, A, b);
  if (b.size() && b.lpNorm<Eigen::Infinity>() > 1e-12 * m.scale)
    throw Error("equilibrium of '" + m.name +
                    "': the constraints move with time (A q1 = b with b != 0), the mechanism "
                    "cannot be at rest",
                m.name, t);
  return s;
}

// |a| at rest in lengths (rotations times their body's size): the accelerations are a = dq1/dw x,
// x = E a, so this does not depend on which coordinates the linearization chose.
double merit(const Model& m, const StateSpace& ss) {
  const VectorXd a = ss.dq1_dw * ss.drift.tail(ss.dof);
  return a.cwiseQuotient(column_scaling(m)).norm();
}

// Largest |dz_i| in lengths (angles times their body's size) over Model::scale.
double scaled_size(const Model& m, const StateSpace& ss, const VectorXd& dz) {
  const VectorXd d = column_scaling(m);
  double s = 0;
  for (int i = 0; i < ss.p; ++i) s = std::max(s, std::abs(dz[i]) / d[ss.coordinate_vars[i]]);
  return s / m.scale;
}

void stiffness_of(const Model& m, Equilibrium& e) {
  const StateSpace& ss = e.linear;
  e.reduced_mass = ss.dq1_dw.transpose() * mass_matrix(m) * ss.dq1_dw;
  if (ss.p != ss.dof) {  // rates without coordinates: no square stiffness; stability from G
    e.stability = "see the eigenvalues of G (velocities without coordinates)";
    return;
  }
  e.stiffness = -e.reduced_mass * ss.G.bottomLeftCorner(ss.dof, ss.p);
  const MatrixXd sym = 0.5 * (e.stiffness + e.stiffness.transpose());
  const double norm = e.stiffness.norm();
  e.asymmetry = norm > 0 ? (e.stiffness - e.stiffness.transpose()).norm() / norm : 0.0;
  Eigen::SelfAdjointEigenSolver<MatrixXd> eig(sym);
  e.stiffness_eigenvalues = eig.eigenvalues();
  const double tol = 1e-8 * std::max(1e-300, e.stiffness_eigenvalues.cwiseAbs().maxCoeff());
  e.stability = "stable";
  for (int i = 0; i < e.stiffness_eigenvalues.size(); ++i) {
    if (e.stiffness_eigenvalues[i] < -tol) {
      e.stability = "unstable";
      return;
    }
    if (e.stiffness_eigenvalues[i] <= tol) e.stability = "neutral";
  }
}

[[noreturn]] void not_converged(const Model& m, const EquilibriumOptions& o, int it, double r,
                                const std::string& why) {
  std::ostringstream s;
  s << "equilibrium of '" << m.name << "': " << why << " after " << it
    << " Newton iterations, |a| = " << r
    << " m/s^2 at rest (rotations times their body's size); the mechanism may have no equilibrium "
       "near the "
       "start (it accelerates under its loads), or start nearer to one";
  throw Error(s.str(), m.name, o.t);
}

}  // namespace

Equilibrium static_equilibrium(const Model& m, const VectorXd& q0_guess,
                               const EquilibriumOptions& o) {
  Equilibrium e;
  const std::string what = "equilibrium of '" + m.name + "'";
  const ForwardOptions& fo = o.linearize.forward;
  detail::check_modes_budget(what, m, fo.max_seconds, fo.max_memory, 1, false);
  detail::RunBudget budget(detail::modes_budget(what, m, o.t, fo.max_seconds));
  auto linearize = [&](const State& s, const LinearizeOptions& lo) {
    return detail::linearize_within(m, s, lo, budget);
  };
  const VectorXd start = assemble(m, q0_guess, o.t, {}, 1e-13);
  e.state = at_rest(m, start, o.t);
  // The line search compares |E a| in the coordinates of the iterate (a descent direction
  // there); the next iterate chooses its coordinates again (unless given): those of the start may
  // not parametrize the configurations near the equilibrium (a crank turned by 90 degrees).
  // Convergence is tested on |a|, which does not depend on the choice.
  LinearizeOptions lo = o.linearize;
  lo.outputs.clear();
  e.linear = linearize(e.state, lo);
  double r = merit(m, e.linear);
  const double ref = std::max(m.gravity.norm(), r);
  for (;; ++e.iterations) {
    if (r <= o.tolerance * ref || r == 0) break;
    if (e.iterations >= o.max_iterations) not_converged(m, o, e.iterations, r, "no convergence");
    const int p = e.linear.p, dof = e.linear.dof;
    const VectorXd rE = e.linear.drift.tail(dof);
    VectorXd dz = -e.linear.G.bottomLeftCorner(dof, p).colPivHouseholderQr().solve(rE);
    const double size = scaled_size(m, e.linear, dz);
    if (size > o.max_step) dz *= o.max_step / size;
    const LinearizeOptions fixed = detail::same_coordinates(m, e.linear, lo);
    bool accepted = false;
    for (double alpha = 1; alpha > 1e-4 && !accepted; alpha /= 2) {
      try {
        const State s = at_rest(m, chart_positions(m, e.linear, alpha * dz), o.t);
        const StateSpace next = linearize(s, fixed);
        if (next.drift.tail(dof).norm() <= (1 - 1e-4 * alpha) * rE.norm()) {
          e.state = s;
          e.linear = o.linearize.coordinates.empty() ? linearize(s, lo) : next;
          r = merit(m, e.linear);
          accepted = true;
        }
      } catch (const BudgetExhausted&) {
        throw;
      } catch (const Error&) {  // no configuration there, or a singular one: shorter step
      }
    }
    if (!accepted) not_converged(m, o, e.iterations, r, "the line search stalled");
  }
  e.residual = r;
  e.moved = (e.state.q0 - start).lpNorm<Eigen::Infinity>();
  if (!o.linearize.outputs.empty()) e.linear = linearize(e.state, o.linearize);
  stiffness_of(m, e);
  return e;
}

VectorXd holding_efforts(const Model& m, const VectorXd& q0, double t, double* residual) {
  const State s = at_rest(m, q0, t);
  MatrixXd A(m.m1, m.n1);
  VectorXd b(m.m1), f(m.n1);
  velocity_jacobian(m, q0, t, A, b);
  Eigen::JacobiSVD<MatrixXd> svd(A * column_scaling(m).asDiagonal(), Eigen::ComputeFullV);
  const double tol = 1e-9 * (svd.singularValues().size() ? svd.singularValues()[0] : 1.0);
  int rank = 0;
  for (int i = 0; i < svd.singularValues().size(); ++i) rank += svd.singularValues()[i] > tol;
  const MatrixXd C = column_scaling(m).asDiagonal() * svd.matrixV().rightCols(m.n1 - rank);
  applied_forces(m, q0, s.q1, t, f);
  const VectorXd Qf = C.transpose() * f;
  const MatrixXd CB = C.transpose() * input_matrix(m);
  VectorXd u = VectorXd::Zero(m.n_inputs());
  if (m.n_inputs() > 0) u = -CB.colPivHouseholderQr().solve(Qf);
  const double left = (Qf + CB * u).norm();
  if (residual) *residual = left;
  if (left > 1e-9 * std::max(Qf.norm(), 1e-300) && left > 0) {
    std::ostringstream msg;
    msg << "holding efforts of '" << m.name << "': the inputs cannot hold this pose at rest ("
        << m.n_inputs() << " inputs for " << C.cols()
        << " degrees of freedom; reduced force left |C^T (f + B u)| = " << left << " of "
        << Qf.norm() << ")";
    throw Error(msg.str(), m.name, t);
  }
  return u;
}

}  // namespace mo2d
