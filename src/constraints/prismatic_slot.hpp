#pragma once
// Prismatic joint and pin-in-slot (Orsino eq. 5.31, corrected, divided by l), and the prismatic
// joint's rotation lock (eq. 5.30 eliminates it when the joint is reduced).
//
// Axis i -> j on body 1, slider node s on body 2, slider coordinate q (signed distance from i
// towards j), l = |p_j - p_i| (constant), sigma = q / l.
//
// Position (2 rows):
//   psi = p_s - (1 - sigma) p_i - sigma p_j
//   d psi / d q0 = [p_s: I,  p_i: -(1 - sigma) I,  p_j: -sigma I,  q: -(p_j - p_i) / l]
//
// Velocity (2 rows):
//   v_s - (1 - sigma) v_i - sigma v_j - (qdot / l) (p_j - p_i) = 0
//   A = the same entries as d psi / d q0 (column qdot for q),  b = 0
//
// Acceleration:
//   a_s - (1 - sigma) a_i - sigma a_j - (qddot / l) (p_j - p_i) - (2 qdot / l) (v_j - v_i) = 0
//   A a1 = (2 qdot / l) (v_j - v_i)
//
// Rotation lock (prismatic only; one row at each level where lock_position / lock_velocity):
//   psi = wrap(theta_2 - theta_1 - c),  theta of a body from its nodes 0 and 1,
//   d theta / d p1 = z x d / |d|^2,  d theta / d p0 = -z x d / |d|^2,  d = p1 - p0
//   A q1 = omega_2 - omega_1 = 0,  A a1 = 0
// (psi is written in node coordinates, A in the rotation rates: different entries per level.)
#include "constraints/common.hpp"

namespace mo2d::detail {

struct SliderAxis {
  double s;  // sigma = q / l
  Vec2 pi, pj;
};
inline SliderAxis slider_axis(const Constraint::Slider& c, const Eigen::Ref<const VectorXd>& q0) {
  const double q = q0[c.q], l = c.length, s = q / l;
  return {s, node_position(c.i, q0), node_position(c.j, q0)};
}

// The entries of d psi / d q0 = A (without the lock), from row r.
template <class Rows>
void prismatic_entries(const Constraint::Slider& c, const SliderAxis& ax, int r, Rows& rows) {
  const double s = ax.s;
  point_entries(rows, r, c.s, 1);
  point_entries(rows, r, c.i, -(1 - s));
  point_entries(rows, r, c.j, -s);
  const Vec2 dq = -(ax.pj - ax.pi) / c.length;
  rows.var(r, VarRef{c.q, -1, -1}, dq.x());
  rows.var(r + 1, VarRef{c.q, -1, -1}, dq.y());
}

// Pin-in-slot (and the slider part of a prismatic joint): rows r, r + 1.
template <class Rows>
void slot_position(const Constraint::Slider& c, int r, const Eigen::Ref<const VectorXd>& q0,
                   Eigen::Ref<VectorXd> res, Rows& rows) {
  const SliderAxis ax = slider_axis(c, q0);
  const Vec2 e = node_position(c.s, q0) - (1 - ax.s) * ax.pi - ax.s * ax.pj;
  res[r] = e.x();
  res[r + 1] = e.y();
  prismatic_entries(c, ax, r, rows);
}

template <class Rows>
void slot_velocity(const Constraint::Slider& c, int r, const Eigen::Ref<const VectorXd>& q0,
                   Eigen::Ref<VectorXd> rhs, Rows& rows) {
  prismatic_entries(c, slider_axis(c, q0), r, rows);
  rhs[r] = rhs[r + 1] = 0;
}

inline void slot_acceleration(const Constraint::Slider& c, int r,
                              const Eigen::Ref<const VectorXd>& q1, Eigen::Ref<VectorXd> rhs) {
  const Vec2 e = (2 * q1[c.q] / c.length) * (node_velocity(c.j, q1) - node_velocity(c.i, q1));
  rhs[r] = e.x();
  rhs[r + 1] = e.y();
}

// Prismatic joint: the slider rows, then the rotation lock (row r + 2) where it is kept.
template <class Rows>
void prismatic_position(const Model& m, const Constraint::Prismatic& c, int r,
                        const Eigen::Ref<const VectorXd>& q0, Eigen::Ref<VectorXd> res,
                        Rows& rows) {
  slot_position(c, r, q0, res, rows);
  if (c.lock_position) {
    res[r + 2] = wrap_angle(theta(m, c.body2, q0) - theta(m, c.body1, q0) - c.lock_angle);
    theta_entries(rows, m, q0, r + 2, c.body2, 1);
    theta_entries(rows, m, q0, r + 2, c.body1, -1);
  }
}

template <class Rows>
void prismatic_velocity(const Model& m, const Constraint::Prismatic& c, int r,
                        const Eigen::Ref<const VectorXd>& q0, Eigen::Ref<VectorXd> rhs,
                        Rows& rows) {
  slot_velocity(c, r, q0, rhs, rows);
  if (c.lock_velocity) {
    rows.var(r + 2, ref_w(m, c.w2), 1);
    rows.var(r + 2, ref_w(m, c.w1), -1);
    rhs[r + 2] = 0;
  }
}

inline void prismatic_acceleration(const Constraint::Prismatic& c, int r,
                                   const Eigen::Ref<const VectorXd>& q1, Eigen::Ref<VectorXd> rhs) {
  slot_acceleration(c, r, q1, rhs);
  if (c.lock_velocity) rhs[r + 2] = 0;
}

}  // namespace mo2d::detail
