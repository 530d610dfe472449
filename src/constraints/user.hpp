#pragma once
// User constraints (Orsino 2.4; simple nonholonomic constraints, Def. 2.1), one row each, with
// exact derivatives on Jet (value, d/ds, d^2/ds^2 along one direction s), never finite differences.
//
// Position constraint psi(x, t) = 0, x = the q0 variables c.args:
//   position:      psi;  d psi / d q0 = psi_x  (Jet with x_k' = 1, one argument at a time)
//   velocity:      psi_x xdot = -psi_t
//                  A = psi_x (the same entries, in the columns of the rates of x),
//                  b = -psi_t (Jet with t' = 1)
//   acceleration:  psi_x xddot + (d^2/dt^2 psi at xddot = 0) = 0
//                  A a1 = -(d^2/dt^2 psi)(x' = xdot, x'' = 0, t' = 1)
//
// Velocity constraint g(x, v, t) = 0, linear in v (the q1 rates c.rates):
//   velocity:      g_v v = -g(x, 0, t):  A = g_v (Jet with v_k' = 1 at v = 0),  b = -g(x, 0, t)
//   acceleration:  g_v a + (d/dt g at a = 0) = 0
//                  A a1 = -(d/dt g)(x' = xdot, v = q1 with v' = 0, t' = 1)
#include <span>

#include "constraints/common.hpp"

namespace mo2d::detail {

using UserArgs = std::array<Jet, kMaxUserArgs>;

// x_k = q0[args[k]] as constants (no direction yet).
inline void user_args_at(const std::vector<VarRef>& args, const Eigen::Ref<const VectorXd>& q0,
                         UserArgs& x) {
  const int n = static_cast<int>(args.size());
  for (int k = 0; k < n; ++k) x[k] = Jet(q0[args[k].var]);
}

// The entries of psi_x = d psi / d q0 = A, into row r (x is left as it came).
template <class Rows>
void user_psi_entries(const Constraint::UserPosition& c, UserArgs& x, double t, int r, Rows& rows) {
  const int n = static_cast<int>(c.args.size());
  const std::span<const Jet> xs(x.data(), n);
  for (int k = 0; k < n; ++k) {
    x[k].d = 1;
    rows.var(r, c.args[k], c.psi(xs, Jet(t)).d);
    x[k].d = 0;
  }
}

template <class Rows>
void user_psi_position(const Constraint::UserPosition& c, int r,
                       const Eigen::Ref<const VectorXd>& q0, double t, Eigen::Ref<VectorXd> res,
                       Rows& rows) {
  UserArgs x;
  user_args_at(c.args, q0, x);
  res[r] = c.psi(std::span<const Jet>(x.data(), c.args.size()), Jet(t)).v;
  user_psi_entries(c, x, t, r, rows);
}

template <class Rows>
void user_psi_velocity(const Constraint::UserPosition& c, int r,
                       const Eigen::Ref<const VectorXd>& q0, double t, Eigen::Ref<VectorXd> rhs,
                       Rows& rows) {
  UserArgs x;
  user_args_at(c.args, q0, x);
  user_psi_entries(c, x, t, r, rows);
  rhs[r] = -c.psi(std::span<const Jet>(x.data(), c.args.size()), Jet(t, 1, 0)).d;
}

inline void user_psi_acceleration(const Constraint::UserPosition& c, int r,
                                  const Eigen::Ref<const VectorXd>& q0,
                                  const Eigen::Ref<const VectorXd>& q1, double t,
                                  Eigen::Ref<VectorXd> rhs) {
  UserArgs x;
  const int n = static_cast<int>(c.args.size());
  for (int k = 0; k < n; ++k) x[k] = Jet(q0[c.args[k].var], q1[c.args[k].var], 0);
  rhs[r] = -c.psi(std::span<const Jet>(x.data(), n), Jet(t, 1, 0)).dd;
}

template <class Rows>
void user_g_velocity(const Constraint::UserVelocity& c, int r, const Eigen::Ref<const VectorXd>& q0,
                     double t, Eigen::Ref<VectorXd> rhs, Rows& rows) {
  UserArgs x, v;
  const int nx = static_cast<int>(c.args.size()), nv = static_cast<int>(c.rates.size());
  user_args_at(c.args, q0, x);
  for (int k = 0; k < nv; ++k) v[k] = Jet(0.0);
  const std::span<const Jet> xs(x.data(), nx), vs(v.data(), nv);
  rhs[r] = -c.g(xs, vs, Jet(t)).v;
  for (int k = 0; k < nv; ++k) {
    v[k].d = 1;
    rows.var(r, c.rates[k], c.g(xs, vs, Jet(t)).d);
    v[k].d = 0;
  }
}

inline void user_g_acceleration(const Constraint::UserVelocity& c, int r,
                                const Eigen::Ref<const VectorXd>& q0,
                                const Eigen::Ref<const VectorXd>& q1, double t,
                                Eigen::Ref<VectorXd> rhs) {
  UserArgs x, v;
  const int nx = static_cast<int>(c.args.size()), nv = static_cast<int>(c.rates.size());
  for (int k = 0; k < nx; ++k) x[k] = Jet(q0[c.args[k].var], q1[c.args[k].var], 0);
  for (int k = 0; k < nv; ++k) v[k] = Jet(c.rates[k].var < 0 ? 0.0 : q1[c.rates[k].var]);
  rhs[r] =
      -c.g(std::span<const Jet>(x.data(), nx), std::span<const Jet>(v.data(), nv), Jet(t, 1, 0)).d;
}

}  // namespace mo2d::detail
