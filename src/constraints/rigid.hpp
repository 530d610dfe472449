#pragma once
// Rigid body (Orsino Example 2.6 (c), (d), with the erratum on the omega column).
//
// Nodes 0..n-1 of one body, d = p1 - p0, l = l01 = |d| in the geometry, z x (x, y) = (-y, x);
// node k >= 2 has body-frame coefficients (a_k, b_k): p_k = p0 + a_k d + b_k z x d.
//
// Position (1 + 2 (n - 2) rows):
//   psi_0 = (|d|^2 - l^2) / (2 l)
//   psi_k = p_k - p0 - (a_k d + b_k z x d),  k >= 2
//   d psi_0 / d p1 = d^T / l,  d psi_0 / d p0 = -d^T / l
//   d psi_k / d p_k = I,  d psi_k / d p1 = -G,  d psi_k / d p0 = -I + G,
//   G = a_k I + b_k Z,  Z = [0 -1; 1 0]
//
// Velocity (2 (n - 1) rows; q1 holds the node velocities and the body's omega):
//   v_k - v0 - omega z x (p_k - p0) = 0,  k >= 1
//   A = [v_k: I,  v0: -I,  omega: -z x (p_k - p0)],  b = 0
//
// Acceleration (d/dt of the velocity rows):
//   a_k - a0 - omega_dot z x (p_k - p0) - omega z x (v_k - v0) = 0
//   A a1 = omega z x (v_k - v0)
//
// psi is written in q0 (node coordinates, no omega) and A in q1 (rigid velocity field with omega):
// the two levels have different rows and entries, each written once at its level.
#include "constraints/common.hpp"

namespace mo2d::detail {

template <class Rows>
void rigid_position(const Model& m, const Constraint::Rigid& c, int r,
                    const Eigen::Ref<const VectorXd>& q0, Eigen::Ref<VectorXd> res, Rows& rows) {
  const Body& b = m.bodies[c.body];
  const Vec2 p0 = node_position(b.nodes[0], q0);
  const Vec2 d = node_position(b.nodes[1], q0) - p0;
  res[r] = (d.squaredNorm() - b.l01 * b.l01) / (2 * b.l01);
  rows.node(r, b.nodes[1], d.x() / b.l01, d.y() / b.l01);
  rows.node(r, b.nodes[0], -d.x() / b.l01, -d.y() / b.l01);
  for (size_t k = 2; k < b.nodes.size(); ++k) {
    const double ak = b.frame[k].x(), bk = b.frame[k].y();
    const Vec2 e = node_position(b.nodes[k], q0) - p0 - ak * d - bk * perp(d);
    const int row = r + 1 + 2 * static_cast<int>(k - 2);
    res[row] = e.x();
    res[row + 1] = e.y();
    point_entries(rows, row, b.nodes[k], 1);  // I
    rows.node(row, b.nodes[1], -ak, bk);      // -G
    rows.node(row + 1, b.nodes[1], -bk, -ak);
    rows.node(row, b.nodes[0], -1 + ak, -bk);  // -I + G
    rows.node(row + 1, b.nodes[0], bk, -1 + ak);
  }
}

template <class Rows>
void rigid_velocity(const Model& m, const Constraint::Rigid& c, int r,
                    const Eigen::Ref<const VectorXd>& q0, Eigen::Ref<VectorXd> rhs, Rows& rows) {
  const Body& b = m.bodies[c.body];
  const Vec2 p0 = node_position(b.nodes[0], q0);
  const VarRef w = ref_w(m, b.omega);
  for (size_t k = 1; k < b.nodes.size(); ++k) {
    const int row = r + 2 * static_cast<int>(k - 1);
    const Vec2 zr = perp(node_position(b.nodes[k], q0) - p0);
    point_entries(rows, row, b.nodes[k], 1);
    point_entries(rows, row, b.nodes[0], -1);
    rows.var(row, w, -zr.x());
    rows.var(row + 1, w, -zr.y());
    rhs[row] = rhs[row + 1] = 0;
  }
}

inline void rigid_acceleration(const Model& m, const Constraint::Rigid& c, int r,
                               const Eigen::Ref<const VectorXd>& q1, Eigen::Ref<VectorXd> rhs) {
  const Body& b = m.bodies[c.body];
  const double w = omega_value(b.omega, q1);
  const Vec2 v0 = node_velocity(b.nodes[0], q1);
  for (size_t k = 1; k < b.nodes.size(); ++k) {
    const Vec2 e = w * perp(node_velocity(b.nodes[k], q1) - v0);
    const int row = r + 2 * static_cast<int>(k - 1);
    rhs[row] = e.x();
    rhs[row + 1] = e.y();
  }
}

}  // namespace mo2d::detail
