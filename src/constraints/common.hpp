#pragma once
// What every constraint kind shares (internal header): angles, z x, references to variables, and
// the two entry adapters through which a kind writes its Jacobian entries ONCE for both levels.
//
//  levels: position rows psi(q0, t) = 0 with their Jacobian d psi / d q0 (from Constraint::row0),
//          velocity rows A(q0, t) q1 = b (from Constraint::row1),
//          acceleration right-hand side A a1 = c, c = exact d/dt of the velocity rows at a1 = 0.
//  A kind's entries go to a `Rows` adapter:
//    rows.node(row, NodeRef n, cx, cy)  coefficient (cx, cy) of the node's (x, y),
//    rows.var(row, VarRef v, value)     coefficient of one variable,
//  and PositionEntries / VelocityEntries turn them into the sink calls of their level, so that a
//  kind whose psi_q0 and A have the same entries (revolute, prismatic, user psi) emits them from
//  one function used at both levels.
#include <array>
#include <cmath>
#include <numbers>

#include "mo2d/model.hpp"

namespace mo2d::detail {

using Eigen::VectorXd;
constexpr int kMaxUserArgs = 32;

inline double wrap_angle(double a) {
  return a - 2 * std::numbers::pi * std::round(a / (2 * std::numbers::pi));
}
inline Vec2 perp(const Vec2& v) {
  return {-v.y(), v.x()};
}  // z x v

inline VarRef ref_x(const NodeRef& n) {
  return {n.var, n.body, 2 * n.local};
}
inline VarRef ref_y(const NodeRef& n) {
  return {n.var < 0 ? -1 : n.var + 1, n.body, 2 * n.local + 1};
}
inline VarRef ref_w(const Model& m, const OmegaRef& w) {
  if (w.body < 0) return {-1, -1, -1};
  return {w.var, w.body, m.bodies[w.body].slots() - 1};
}

// Orientation of a body from its first two nodes; ground is 0.
inline double theta(const Model& m, int body, const Eigen::Ref<const VectorXd>& q0) {
  if (body < 0) return 0.0;
  const Body& b = m.bodies[body];
  const Vec2 d = node_position(b.nodes[1], q0) - node_position(b.nodes[0], q0);
  return std::atan2(d.y(), d.x());
}
// d theta / d p1 (and minus it for p0).
inline Vec2 theta_gradient(const Model& m, int body, const Eigen::Ref<const VectorXd>& q0) {
  const Body& b = m.bodies[body];
  const Vec2 d = node_position(b.nodes[1], q0) - node_position(b.nodes[0], q0);
  return perp(d) / d.squaredNorm();
}

// Position level: d psi / d q0 into jac.add(row, q0 index, value). Fixed nodes and zero node
// coefficients are dropped; variable entries are passed as they are.
template <class Sink>
struct PositionEntries {
  Sink& jac;
  void node(int row, const NodeRef& n, double cx, double cy) {
    if (n.var < 0) return;
    if (cx != 0) jac.add(row, n.var, cx);
    if (cy != 0) jac.add(row, n.var + 1, cy);
  }
  void var(int row, const VarRef& v, double value) { jac.add(row, v.var, value); }
};

// Velocity level: entries of A into A.add(row, VarRef, value). Zeros are kept (the entry pattern
// stays fixed: no reallocation) and so are fixed variables (var -1, still reported with their body
// slot for the reaction bookkeeping); only ground nodes are dropped.
template <class Sink>
struct VelocityEntries {
  Sink& A;
  void node(int row, const NodeRef& n, double cx, double cy) {
    if (n.body < 0 && n.var < 0) return;  // ground node
    A.add(row, ref_x(n), cx);
    A.add(row, ref_y(n), cy);
  }
  void var(int row, const VarRef& v, double value) { A.add(row, v, value); }
};

// k I (2 x 2) on node n: rows (row, row + 1) get k x_n and k y_n.
template <class Rows>
void point_entries(Rows& rows, int row, const NodeRef& n, double k) {
  rows.node(row, n, k, 0);
  rows.node(row + 1, n, 0, k);
}

// w d theta_body / d q0 into one position row (ground: nothing).
template <class Rows>
void theta_entries(Rows& rows, const Model& m, const Eigen::Ref<const VectorXd>& q0, int row,
                   int body, double w) {
  if (body < 0) return;
  const Body& b = m.bodies[body];
  const Vec2 g = theta_gradient(m, body, q0) * w;
  rows.node(row, b.nodes[1], g.x(), g.y());
  rows.node(row, b.nodes[0], -g.x(), -g.y());
}

}  // namespace mo2d::detail
