#pragma once
// Extra coordinate (AddCoordinate): a variable q_e of q0 with d/dt q_e = sum c v, where each v of
// the sum is a rate of q0 (node or coordinate) or a body's rotation rate omega_b.
//
// Position (1 row, only when holonomic: every omega_b term has an integer weight on a body with
// at least two nodes; c.coord_terms are the q0 terms, c.angle_terms the omega_b terms):
//   psi = q_e - sum c_k q_k - sum c_b theta_b - offset,  wrapped to [-pi, pi] if there are angles
//   d psi / d q0 = [q_e: 1,  q_k: -c_k,  nodes 1 and 0 of body b: -c_b (+-) z x d_b / |d_b|^2]
//
// Velocity (1 row; c.rate_terms, all the terms in the order of the definition):
//   qdot_e - sum c v = 0
//   A = [qdot_e: 1,  v: -c],  b = 0
//
// Acceleration:
//   A a1 = 0
//
// psi is written in q0 (theta through its gradient), A in q1 (omega directly), from two term lists
// of Constraint::Coordinate: the entries are written once at each level.
#include "constraints/common.hpp"

namespace mo2d::detail {

template <class Rows>
void coordinate_position(const Model& m, const Constraint::Coordinate& c, int r,
                         const Eigen::Ref<const VectorXd>& q0, Eigen::Ref<VectorXd> res,
                         Rows& rows) {
  if (!c.holonomic) return;
  double v = q0[c.coord] - c.offset;
  rows.var(r, VarRef{c.coord, -1, -1}, 1);
  for (auto [k, w] : c.coord_terms) {
    v -= w * q0[k];
    rows.var(r, VarRef{k, -1, -1}, -w);
  }
  for (auto [body, w] : c.angle_terms) {
    v -= w * theta(m, body, q0);
    theta_entries(rows, m, q0, r, body, -w);
  }
  res[r] = c.angle_terms.empty() ? v : wrap_angle(v);
}

template <class Rows>
void coordinate_velocity(const Constraint::Coordinate& c, int r, Eigen::Ref<VectorXd> rhs,
                         Rows& rows) {
  rows.var(r, VarRef{c.coord, -1, -1}, 1);
  for (const auto& [ref, w] : c.rate_terms) rows.var(r, ref, -w);
  rhs[r] = 0;
}

inline void coordinate_acceleration(int r, Eigen::Ref<VectorXd> rhs) {
  rhs[r] = 0;
}

}  // namespace mo2d::detail
