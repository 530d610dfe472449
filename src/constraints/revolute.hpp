#pragma once
// Revolute joint kept as constraint rows (Orsino eq. 5.27 eliminates it when the joint is reduced:
// node b's variables merge into node a's).
//
// Node a on body 1, node b on body 2 (either may be a fixed or ground node).
//
// Position (2 rows):
//   psi = p_b - p_a
//   d psi / d q0 = [p_b: I,  p_a: -I]
//
// Velocity (2 rows):
//   v_b - v_a = 0
//   A = [v_b: I,  v_a: -I]  (the same entries as d psi / d q0),  b = 0
//
// Acceleration:
//   A a1 = 0
#include "constraints/common.hpp"

namespace mo2d::detail {

// The entries of d psi / d q0 = A, from row r.
template <class Rows>
void revolute_entries(const Constraint::Revolute& c, int r, Rows& rows) {
  point_entries(rows, r, c.b, 1);
  point_entries(rows, r, c.a, -1);
}

template <class Rows>
void revolute_position(const Constraint::Revolute& c, int r, const Eigen::Ref<const VectorXd>& q0,
                       Eigen::Ref<VectorXd> res, Rows& rows) {
  const Vec2 e = node_position(c.b, q0) - node_position(c.a, q0);
  res[r] = e.x();
  res[r + 1] = e.y();
  revolute_entries(c, r, rows);
}

template <class Rows>
void revolute_velocity(const Constraint::Revolute& c, int r, Eigen::Ref<VectorXd> rhs, Rows& rows) {
  revolute_entries(c, r, rows);
  rhs[r] = rhs[r + 1] = 0;
}

inline void revolute_acceleration(int r, Eigen::Ref<VectorXd> rhs) {
  rhs[r] = rhs[r + 1] = 0;
}

}  // namespace mo2d::detail
