// The Jacobian of the accelerations (mo2d/jacobian.hpp). First version: central differences of the
// evaluation (replaced by the exact directional derivatives).
#include "mo2d/jacobian.hpp"

#include <algorithm>
#include <cmath>

namespace mo2d {

void acceleration_jacobian(ForwardData& d, double t, const Eigen::VectorXd& q0,
                           const Eigen::VectorXd& q1, AccelerationJacobian& J) {
  const Model& m = d.m;
  J.da_dq0.resize(m.n1, m.n0);
  J.da_dq1.resize(m.n1, m.n1);
  Eigen::VectorXd x0 = q0, x1 = q1, ap(m.n1);
  for (int k = 0; k < m.n0 + m.n1; ++k) {
    const bool pos = k < m.n0;
    double& x = pos ? x0[k] : x1[k - m.n0];
    const double x_at = x, h = 1e-6 * std::max(std::abs(x_at), pos ? m.scale : 1.0);
    x = x_at + h;
    d.accelerations(t, x0, x1, false);
    ap = d.a;
    x = x_at - h;
    d.accelerations(t, x0, x1, false);
    x = x_at;
    (pos ? J.da_dq0.col(k) : J.da_dq1.col(k - m.n0)) = (ap - d.a) / (2 * h);
  }
  J.approximate = "central differences";
  d.accelerations(t, q0, q1, false);
}

}  // namespace mo2d
