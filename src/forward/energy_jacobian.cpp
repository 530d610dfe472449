// Rows of the energy terms in the Jacobian of a forward run's right-hand side (forward_run.hpp):
// the derivatives of the powers energy_rates integrates, along each state variable, exact like
// the accelerations' (dynamics/derivatives.hpp):
//   input work       P = (B u) . q1                    dP = (B du) . q1 + (B u) . dq1
//   load work        load_power                        load_power_derivative
//   constraint work  P = q1 . (M a - f - B u)          dP = dq1 . (M a - f - B u)
//                                                           + q1 . (M da - df - B du)
//   dissipated       damping_power                     damping_power_derivative
// (joint friction is not differentiated: runs with friction keep CVODE's difference quotients).
#include "dynamics/derivatives.hpp"
#include "forward/forward_run.hpp"
#include "mo2d/dynamics.hpp"

namespace mo2d::detail {

void energy_rate_jacobian(ForwardData& d, double t, const VectorXd& q0, const VectorXd& q1,
                          const AccelerationJacobian& J, const std::vector<int>& terms,
                          MatrixXd& rows) {
  const Model& m = d.m;
  const int n = m.n0 + m.n1;
  rows.setZero(static_cast<Eigen::Index>(terms.size()), n);
  VectorXd dq0 = VectorXd::Zero(m.n0), dq1 = VectorXd::Zero(m.n1), du(m.n_inputs()), Bdu(m.n1),
           dlocal(m.n_slots), df(m.n1), da(m.n1);
  const bool moving_constraints = m.m1 > 0 && d.b.lpNorm<Eigen::Infinity>() > 0;
  const VectorXd Ma_f_Bu = d.M * d.a - d.f - d.Bu;
  for (int k = 0; k < n; ++k) {
    const bool along_q0 = k < m.n0;
    (along_q0 ? dq0[k] : dq1[k - m.n0]) = 1;
    for (int j = 0; j < m.n_inputs(); ++j)
      du[j] =
          law_jet(m, d.effort_laws[j], q0, q1, dq0, dq1, t, "effort of input", m.inputs[j].label).d;
    Bdu.noalias() = d.B * du;
    da = along_q0 ? J.da_dq0.col(k) : J.da_dq1.col(k - m.n0);
    for (size_t r = 0; r < terms.size(); ++r) {
      double v = 0;
      switch (terms[r]) {
        case kInputWork:
          v = Bdu.dot(q1) + d.Bu.dot(dq1);
          break;
        case kLoadWork:
          v = load_power_derivative(m, q0, q1, dq0, dq1, t);
          break;
        case kConstraintWork:
          if (!moving_constraints) break;
          body_applied_derivative(m, q0, q1, dq0, dq1, t, dlocal);
          df.setZero();
          scatter_local(m, dlocal, df);
          v = dq1.dot(Ma_f_Bu) + q1.dot(d.M * da - df - Bdu);
          break;
        case kDissipated:
          v = damping_power_derivative(m, q0, q1, dq0, dq1);
          break;
        default:
          break;
      }
      rows(static_cast<Eigen::Index>(r), k) = v;
    }
    (along_q0 ? dq0[k] : dq1[k - m.n0]) = 0;
  }
}

}  // namespace mo2d::detail
