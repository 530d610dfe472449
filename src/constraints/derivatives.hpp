#pragma once
// Directional derivatives of the velocity rows A(q0, t) and of the acceleration right-hand side
// c(q0, q1, t) of every constraint kind, along a direction (dq0, dq1) of the state: what the
// Jacobian of the accelerations needs (mo2d/jacobian.hpp). dp below is the derivative of a node
// position along dq0, dv of a node velocity along dq1 (node_velocity of dq0, dq1: a fixed node
// does not move, so both are 0 there).
//
//   revolute, coordinate, gear, prismatic lock:  A constant, c = 0:  dA = 0, dc = 0
//   rigid (rigid.hpp):   A[omega] = -z x (p_k - p0)        dA[omega] = -z x (dp_k - dp0)
//                        c = omega z x (v_k - v0)          dc = domega z x (v_k - v0)
//                                                               + omega z x (dv_k - dv0)
//   slot (prismatic_slot.hpp), sigma = q / l:
//                        A[v_i] = -(1 - sigma) I, A[v_j] = -sigma I, A[qdot] = -(p_j - p_i) / l
//                        dA[v_i] = dsigma I, dA[v_j] = -dsigma I, dA[qdot] = -(dp_j - dp_i) / l
//                        c = (2 qdot / l) (v_j - v_i)      dc = (2 dqdot / l) (v_j - v_i)
//                                                               + (2 qdot / l) (dv_j - dv_i)
//   user position psi(x, t) (user.hpp), from Jets by polarization, D2(u) = d^2/ds^2 psi(x + s u):
//                        dA[k] = psi_xx[dx, e_k] = (D2(dx + e_k) - D2(dx - e_k)) / 4
//                        c = -h(xdot), h(u) = d^2/ds^2 psi(x + s u, t + s)
//                        dc (along dxdot) = -(h(xdot + dxdot) - h(xdot - dxdot)) / 2
//                        dc (along dx) needs third derivatives, which Jets do not carry: a
//                        central difference of h in x (the one entry that is not exact)
//   user velocity g(x, v, t), linear in v, K(u, w) = d^2/ds^2 g(x + s u, v + s w, t + s):
//                        dA[k] = g_xv[dx, e_k] = (D2(dx, e_k) - D2(dx, -e_k)) / 4  (t fixed)
//                        c = -(g_x xdot + g_t) at v = q1
//                        dc (dxdot) = -g_x dxdot          (first order, one Jet)
//                        dc (dv)    = -(K(xdot, dv) - K(xdot, -dv)) / 4
//                        dc (dx)    = -(K(xdot + dx, 0) - K(xdot - dx, 0)) / 4
#include <algorithm>
#include <cmath>
#include <span>

#include "constraints/common.hpp"
#include "constraints/user.hpp"

namespace mo2d::detail {

using VecRef = Eigen::Ref<const VectorXd>;

// dA along dq0 of one constraint into the sink (entries dA.add(row, VarRef, value)).
template <class Sink>
void velocity_rows_derivative(const Model& m, const Constraint& c, const VecRef& q0,
                              const VecRef& dq0, double t, Sink& dA);

// ---- rigid --------------------------------------------------------------------------------------

template <class Rows>
void rigid_velocity_derivative(const Model& m, const Constraint::Rigid& c, int r, const VecRef& dq0,
                               Rows& rows) {
  const Body& b = m.bodies[c.body];
  const Vec2 dp0 = node_velocity(b.nodes[0], dq0);
  const VarRef w = ref_w(m, b.omega);
  for (size_t k = 1; k < b.nodes.size(); ++k) {
    const int row = r + 2 * static_cast<int>(k - 1);
    const Vec2 dzr = perp(node_velocity(b.nodes[k], dq0) - dp0);
    rows.var(row, w, -dzr.x());
    rows.var(row + 1, w, -dzr.y());
  }
}

inline void rigid_acceleration_derivative(const Model& m, const Constraint::Rigid& c, int r,
                                          const VecRef& q1, const VecRef& dq1,
                                          Eigen::Ref<VectorXd> drhs) {
  const Body& b = m.bodies[c.body];
  const double w = omega_value(b.omega, q1), dw = omega_value(b.omega, dq1);
  const Vec2 v0 = node_velocity(b.nodes[0], q1), dv0 = node_velocity(b.nodes[0], dq1);
  for (size_t k = 1; k < b.nodes.size(); ++k) {
    const Vec2 e = dw * perp(node_velocity(b.nodes[k], q1) - v0) +
                   w * perp(node_velocity(b.nodes[k], dq1) - dv0);
    const int row = r + 2 * static_cast<int>(k - 1);
    drhs[row] = e.x();
    drhs[row + 1] = e.y();
  }
}

// ---- slot (and the slider rows of a prismatic joint) --------------------------------------------

template <class Rows>
void slot_velocity_derivative(const Constraint::Slider& c, int r, const VecRef& dq0, Rows& rows) {
  const double ds = dq0[c.q] / c.length;
  point_entries(rows, r, c.i, ds);
  point_entries(rows, r, c.j, -ds);
  const Vec2 dqcol = -(node_velocity(c.j, dq0) - node_velocity(c.i, dq0)) / c.length;
  rows.var(r, VarRef{c.q, -1, -1}, dqcol.x());
  rows.var(r + 1, VarRef{c.q, -1, -1}, dqcol.y());
}

inline void slot_acceleration_derivative(const Constraint::Slider& c, int r, const VecRef& q1,
                                         const VecRef& dq1, Eigen::Ref<VectorXd> drhs) {
  const Vec2 e = (2 * dq1[c.q] / c.length) * (node_velocity(c.j, q1) - node_velocity(c.i, q1)) +
                 (2 * q1[c.q] / c.length) * (node_velocity(c.j, dq1) - node_velocity(c.i, dq1));
  drhs[r] = e.x();
  drhs[r + 1] = e.y();
}

// ---- user constraints ---------------------------------------------------------------------------

// d^2/ds^2 psi(x + s u, t + s tdot) with u_k = dir(k).
template <class Dir>
double user_psi_d2(const Constraint::UserPosition& c, const VecRef& q0, double t, double tdot,
                   Dir dir) {
  UserArgs x;
  const int n = static_cast<int>(c.args.size());
  for (int k = 0; k < n; ++k) x[k] = Jet(q0[c.args[k].var], dir(k), 0);
  return c.psi(std::span<const Jet>(x.data(), n), Jet(t, tdot, 0)).dd;
}

template <class Rows>
void user_psi_velocity_derivative(const Constraint::UserPosition& c, int r, const VecRef& q0,
                                  const VecRef& dq0, double t, Rows& rows) {
  const int n = static_cast<int>(c.args.size());
  for (int j = 0; j < n; ++j) {
    auto plus = [&](int k) { return dq0[c.args[k].var] + (k == j ? 1.0 : 0.0); };
    auto minus = [&](int k) { return dq0[c.args[k].var] - (k == j ? 1.0 : 0.0); };
    rows.var(r, c.args[j], (user_psi_d2(c, q0, t, 0, plus) - user_psi_d2(c, q0, t, 0, minus)) / 4);
  }
}

// d^2/ds^2 g(x + s u, v + s w, t + s tdot), v = q1 rates (v = 0 when at_rest).
template <class DirX, class DirV>
double user_g_d2(const Constraint::UserVelocity& c, const VecRef& q0, const VecRef& q1,
                 bool at_rest, double t, double tdot, DirX ux, DirV wv) {
  UserArgs x, v;
  const int nx = static_cast<int>(c.args.size()), nv = static_cast<int>(c.rates.size());
  for (int k = 0; k < nx; ++k) x[k] = Jet(q0[c.args[k].var], ux(k), 0);
  for (int k = 0; k < nv; ++k)
    v[k] = Jet(at_rest || c.rates[k].var < 0 ? 0.0 : q1[c.rates[k].var], wv(k), 0);
  return c
      .g(std::span<const Jet>(x.data(), nx), std::span<const Jet>(v.data(), nv), Jet(t, tdot, 0))
      .dd;
}

template <class Rows>
void user_g_velocity_derivative(const Constraint::UserVelocity& c, int r, const VecRef& q0,
                                const VecRef& dq0, double t, Rows& rows) {
  const int nv = static_cast<int>(c.rates.size());
  auto dx = [&](int k) { return dq0[c.args[k].var]; };
  for (int j = 0; j < nv; ++j) {
    auto plus = [&](int k) { return k == j ? 1.0 : 0.0; };
    auto minus = [&](int k) { return k == j ? -1.0 : 0.0; };
    // v = 0 (at_rest): the q1 argument is not read
    rows.var(r, c.rates[j],
             (user_g_d2(c, q0, dq0, true, t, 0, dx, plus) -
              user_g_d2(c, q0, dq0, true, t, 0, dx, minus)) /
                 4);
  }
}

template <class Sink>
void velocity_rows_derivative(const Model& m, const Constraint& c, const VecRef& q0,
                              const VecRef& dq0, double t, Sink& dA) {
  VelocityEntries<Sink> rows{dA};
  const int r = c.row1;
  switch (c.kind()) {
    case ConstraintKind::rigid:
      rigid_velocity_derivative(m, std::get<Constraint::Rigid>(c.def), r, dq0, rows);
      break;
    case ConstraintKind::prismatic:  // the lock's rows are constant
      slot_velocity_derivative(std::get<Constraint::Prismatic>(c.def), r, dq0, rows);
      break;
    case ConstraintKind::slot:
      slot_velocity_derivative(std::get<Constraint::Slider>(c.def), r, dq0, rows);
      break;
    case ConstraintKind::user_position:
      user_psi_velocity_derivative(std::get<Constraint::UserPosition>(c.def), r, q0, dq0, t, rows);
      break;
    case ConstraintKind::user_velocity:
      user_g_velocity_derivative(std::get<Constraint::UserVelocity>(c.def), r, q0, dq0, t, rows);
      break;
    case ConstraintKind::revolute:
    case ConstraintKind::coordinate:
    case ConstraintKind::gear:  // constant coefficients (gear.hpp)
      break;
  }
}

// dc of a user position constraint along (dq0, dq1): exact along dq1, a central difference of h
// along dq0 (step: 1e-6 of the larger of |x| and the model's length scale, per argument).
inline double user_psi_acceleration_derivative(const Model& m, const Constraint::UserPosition& c,
                                               const VecRef& q0, const VecRef& q1,
                                               const VecRef& dq0, const VecRef& dq1, double t,
                                               bool& exact) {
  auto xdot = [&](int k) { return q1[c.args[k].var]; };
  auto plus = [&](int k) { return q1[c.args[k].var] + dq1[c.args[k].var]; };
  auto minus = [&](int k) { return q1[c.args[k].var] - dq1[c.args[k].var]; };
  double dc = -(user_psi_d2(c, q0, t, 1, plus) - user_psi_d2(c, q0, t, 1, minus)) / 2;
  const int n = static_cast<int>(c.args.size());
  double step = 0;
  for (int k = 0; k < n; ++k)
    step = std::max(step, 1e-6 * std::max(std::abs(q0[c.args[k].var]), m.scale));
  bool moves = false;
  UserArgs x;
  for (int k = 0; k < n; ++k) moves = moves || dq0[c.args[k].var] != 0;
  if (!moves) return dc;
  exact = false;
  auto h_at = [&](double s) {
    for (int k = 0; k < n; ++k) x[k] = Jet(q0[c.args[k].var] + s * dq0[c.args[k].var], xdot(k), 0);
    return c.psi(std::span<const Jet>(x.data(), n), Jet(t, 1, 0)).dd;
  };
  dc -= (h_at(step) - h_at(-step)) / (2 * step);
  return dc;
}

// dc of a user velocity constraint along (dq0, dq1), exact (see the top of the file).
inline double user_g_acceleration_derivative(const Constraint::UserVelocity& c, const VecRef& q0,
                                             const VecRef& q1, const VecRef& dq0, const VecRef& dq1,
                                             double t) {
  UserArgs x, v;
  const int nx = static_cast<int>(c.args.size()), nv = static_cast<int>(c.rates.size());
  for (int k = 0; k < nx; ++k) x[k] = Jet(q0[c.args[k].var], dq1[c.args[k].var], 0);
  for (int k = 0; k < nv; ++k) v[k] = Jet(c.rates[k].var < 0 ? 0.0 : q1[c.rates[k].var]);
  double dc =
      -c.g(std::span<const Jet>(x.data(), nx), std::span<const Jet>(v.data(), nv), Jet(t)).d;
  auto xdot = [&](int k) { return q1[c.args[k].var]; };
  auto none = [](int) { return 0.0; };
  auto dv = [&](int k) { return c.rates[k].var < 0 ? 0.0 : dq1[c.rates[k].var]; };
  auto mdv = [&](int k) { return -dv(k); };
  dc -=
      (user_g_d2(c, q0, q1, false, t, 1, xdot, dv) - user_g_d2(c, q0, q1, false, t, 1, xdot, mdv)) /
      4;
  auto xp = [&](int k) { return q1[c.args[k].var] + dq0[c.args[k].var]; };
  auto xm = [&](int k) { return q1[c.args[k].var] - dq0[c.args[k].var]; };
  dc -=
      (user_g_d2(c, q0, q1, false, t, 1, xp, none) - user_g_d2(c, q0, q1, false, t, 1, xm, none)) /
      4;
  return dc;
}

// dc along (dq0, dq1) of one constraint into drhs[row]; exact is cleared when an entry was
// differenced (user position constraints along dq0).
inline void acceleration_rows_derivative(const Model& m, const Constraint& c, const VecRef& q0,
                                         const VecRef& q1, const VecRef& dq0, const VecRef& dq1,
                                         double t, Eigen::Ref<VectorXd> drhs, bool& exact) {
  const int r = c.row1;
  switch (c.kind()) {
    case ConstraintKind::rigid:
      rigid_acceleration_derivative(m, std::get<Constraint::Rigid>(c.def), r, q1, dq1, drhs);
      break;
    case ConstraintKind::prismatic:
      slot_acceleration_derivative(std::get<Constraint::Prismatic>(c.def), r, q1, dq1, drhs);
      if (std::get<Constraint::Prismatic>(c.def).lock_velocity) drhs[r + 2] = 0;
      break;
    case ConstraintKind::slot:
      slot_acceleration_derivative(std::get<Constraint::Slider>(c.def), r, q1, dq1, drhs);
      break;
    case ConstraintKind::user_position:
      drhs[r] = user_psi_acceleration_derivative(m, std::get<Constraint::UserPosition>(c.def), q0,
                                                 q1, dq0, dq1, t, exact);
      break;
    case ConstraintKind::user_velocity:
      drhs[r] = user_g_acceleration_derivative(std::get<Constraint::UserVelocity>(c.def), q0, q1,
                                               dq0, dq1, t);
      break;
    case ConstraintKind::revolute:
      drhs[r] = drhs[r + 1] = 0;
      break;
    case ConstraintKind::coordinate:
    case ConstraintKind::gear:  // A a1 = 0 (gear.hpp)
      drhs[r] = 0;
      break;
  }
}

}  // namespace mo2d::detail
