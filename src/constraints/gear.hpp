#pragma once
// Gear pair and rack and pinion (GearDef, RackDef in mo2d/system.hpp): a transmission between a
// driving body k and a driven body j (gear) or a slide coordinate q (rack), both turning in a
// carrier (housing) body c, on carrier-relative rates (Gamba 2009, the epicyclic form of a gear
// pair; the carrier may be the ground):
//   gear:  omega_j - omega_c = rho (omega_k - omega_c)
//   rack:  q'                = r   (omega_k - omega_c)      (q: the slide of the rack in c)
// A non-integer rho cannot be written on the wrapped body angles, so build_model gives each gear
// an extra coordinate phi (Constraint::Coordinate "name.phi", d/dt phi = omega_k - omega_c, whose
// position row phi - (theta_k - theta_c) - offset_k is holonomic) and the gear's rows read phi:
//
// Position (1 row):
//   gear: psi = wrap(theta_j - theta_c - rho phi - offset)       (wrap to [-pi, pi])
//         d psi / d q0 = [nodes of j: +d theta_j / d q0,  nodes of c: -d theta_c / d q0,
//                         phi: -rho]
//   rack: psi = q - r phi - offset,   d psi / d q0 = [q: 1,  phi: -r]
//   offset: the value at the initial configuration (the teeth mesh where the user put them).
//
// Velocity (1 row, linear in q1 with constant coefficients):
//   gear: omega_j - omega_c - rho phi' = 0,   A = [omega_j: 1,  omega_c: -1,  phi': -rho], b = 0
//   rack: q' - r phi' = 0,                    A = [q': 1,  phi': -r],                     b = 0
//   (exactly d psi / dt: d theta_b / dt = omega_b on the rigid rows.)
//
// Acceleration:  A a1 = c = 0.
//
// Derivatives for exact Jacobians (the lead's jacobian work): the coefficients of A are constants,
// so d A / d q0 = 0; c = 0, so d c / d q0 = 0 and d c / d q1 = 0.
//
// Multiplier and reactions (the constraint force is -A^T lambda, as for every row): the mesh
// torque on j is tau = -lambda ("name.torque"; a rack: the force on the slide, "name.force");
// phi carries no inertia, so the multiplier of its coordinate row is rho lambda and the driving
// body k receives -rho tau, the carrier -(1 - rho) tau ("name.carrier_torque"; a rack: r F on k
// and -r F on c). The three sum to zero and their power tau (omega_j - omega_c - rho (omega_k -
// omega_c)) vanishes.
#include "constraints/common.hpp"

namespace mo2d::detail {

template <class Rows>
void gear_position(const Model& m, const Constraint::Gear& g, int r,
                   const Eigen::Ref<const VectorXd>& q0, Eigen::Ref<VectorXd> res, Rows& rows) {
  double v = -g.ratio * q0[g.phi] - g.offset;
  rows.var(r, VarRef{g.phi, -1, -1}, -g.ratio);
  if (g.coord >= 0) {  // rack
    v += q0[g.coord];
    rows.var(r, VarRef{g.coord, -1, -1}, 1);
    res[r] = v;
    return;
  }
  v += theta(m, g.body, q0) - theta(m, g.carrier, q0);
  theta_entries(rows, m, q0, r, g.body, 1);
  theta_entries(rows, m, q0, r, g.carrier, -1);
  res[r] = wrap_angle(v);
}

template <class Rows>
void gear_velocity(const Constraint::Gear& g, int r, Eigen::Ref<VectorXd> rhs, Rows& rows) {
  rows.var(r, g.driven, 1);
  if (g.carrier_w.body >= 0) rows.var(r, g.carrier_w, -1);
  rows.var(r, g.phi_rate, -g.ratio);
  rhs[r] = 0;
}

inline void gear_acceleration(int r, Eigen::Ref<VectorXd> rhs) {
  rhs[r] = 0;
}

}  // namespace mo2d::detail
