#pragma once
// Constraint rows of every kind, at position, velocity and acceleration level (internal header).
//
//  rigid body (Example 2.6): nodes 0..n-1, d = p1 - p0, z x (x, y) = (-y, x)
//    psi:   (|d|^2 - l01^2) / (2 l01);   p_k - p_0 - (a_k d + b_k z x d),  k >= 2
//    A q1:  v_k - v_0 - w z x (p_k - p_0) = 0,  k >= 1
//    accel: A a1 = w z x (v_k - v_0)
//  revolute (not eliminated):  psi = p_b - p_a;  A q1 = v_b - v_a;  accel rhs 0
//  prismatic / pin-in-slot (eq. 5.31 corrected, divided by l):
//    psi = p_s - (1 - q/l) p_i - (q/l) p_j
//    A q1 = v_s - (1 - q/l) v_i - (q/l) v_j - (qdot/l)(p_j - p_i)
//    accel rhs = (2 qdot / l)(v_j - v_i)
//    rotation lock (prismatic): psi = wrap(theta_2 - theta_1 - c);  A q1 = w_2 - w_1
//  extra coordinate: psi = wrap(q_e - sum c q - sum c theta - offset); A q1 = qdot_e - sum c v
//  user constraints: psi(x, t) and g(x, v, t), differentiated exactly with Jet.
#include <array>
#include <cmath>
#include <numbers>

#include "dynamics/reactions.hpp"
#include "mo2d/error.hpp"
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

// Position rows: residual into res[row], Jacobian entries jac.add(row, q0 index, value).
template <class Sink>
void position_rows(const Model& m, const Constraint& c, const Eigen::Ref<const VectorXd>& q0,
                   double t, Eigen::Ref<VectorXd> res, Sink& jac) {
  const int r = c.row0;
  auto add_node = [&](int row, const NodeRef& n, double cx, double cy) {
    if (n.var < 0) return;
    if (cx != 0) jac.add(row, n.var, cx);
    if (cy != 0) jac.add(row, n.var + 1, cy);
  };
  auto add_theta = [&](int row, int body, double w) {
    if (body < 0) return;
    const Body& b = m.bodies[body];
    const Vec2 g = theta_gradient(m, body, q0) * w;
    add_node(row, b.nodes[1], g.x(), g.y());
    add_node(row, b.nodes[0], -g.x(), -g.y());
  };
  switch (c.kind) {
    case ConstraintKind::rigid: {
      const Body& b = m.bodies[c.body];
      const Vec2 p0 = node_position(b.nodes[0], q0);
      const Vec2 d = node_position(b.nodes[1], q0) - p0;
      res[r] = (d.squaredNorm() - b.l01 * b.l01) / (2 * b.l01);
      add_node(r, b.nodes[1], d.x() / b.l01, d.y() / b.l01);
      add_node(r, b.nodes[0], -d.x() / b.l01, -d.y() / b.l01);
      for (size_t k = 2; k < b.nodes.size(); ++k) {
        const double ak = b.frame[k].x(), bk = b.frame[k].y();
        const Vec2 e = node_position(b.nodes[k], q0) - p0 - ak * d - bk * perp(d);
        const int row = r + 1 + 2 * static_cast<int>(k - 2);
        res[row] = e.x();
        res[row + 1] = e.y();
        // d e / d p_k = I; d e / d p_1 = -G; d e / d p_0 = -I + G, G = a I + b Z, Z = [0 -1; 1 0]
        add_node(row, b.nodes[k], 1, 0);
        add_node(row + 1, b.nodes[k], 0, 1);
        add_node(row, b.nodes[1], -ak, bk);
        add_node(row + 1, b.nodes[1], -bk, -ak);
        add_node(row, b.nodes[0], -1 + ak, -bk);
        add_node(row + 1, b.nodes[0], bk, -1 + ak);
      }
      break;
    }
    case ConstraintKind::revolute: {
      const Vec2 e = node_position(c.b, q0) - node_position(c.a, q0);
      res[r] = e.x();
      res[r + 1] = e.y();
      add_node(r, c.b, 1, 0);
      add_node(r + 1, c.b, 0, 1);
      add_node(r, c.a, -1, 0);
      add_node(r + 1, c.a, 0, -1);
      break;
    }
    case ConstraintKind::prismatic:
    case ConstraintKind::slot: {
      const double q = q0[c.q], l = c.length, s = q / l;
      const Vec2 pi = node_position(c.i, q0), pj = node_position(c.j, q0);
      const Vec2 e = node_position(c.s, q0) - (1 - s) * pi - s * pj;
      res[r] = e.x();
      res[r + 1] = e.y();
      add_node(r, c.s, 1, 0);
      add_node(r + 1, c.s, 0, 1);
      add_node(r, c.i, -(1 - s), 0);
      add_node(r + 1, c.i, 0, -(1 - s));
      add_node(r, c.j, -s, 0);
      add_node(r + 1, c.j, 0, -s);
      const Vec2 dq = -(pj - pi) / l;
      jac.add(r, c.q, dq.x());
      jac.add(r + 1, c.q, dq.y());
      if (c.lock_position) {
        res[r + 2] = wrap_angle(theta(m, c.body2, q0) - theta(m, c.body1, q0) - c.lock_angle);
        add_theta(r + 2, c.body2, 1);
        add_theta(r + 2, c.body1, -1);
      }
      break;
    }
    case ConstraintKind::coordinate: {
      if (!c.holonomic) break;
      double v = q0[c.coord] - c.offset;
      jac.add(r, c.coord, 1);
      for (auto [k, w] : c.coord_terms) {
        v -= w * q0[k];
        jac.add(r, k, -w);
      }
      for (auto [body, w] : c.angle_terms) {
        v -= w * theta(m, body, q0);
        add_theta(r, body, -w);
      }
      res[r] = c.angle_terms.empty() ? v : wrap_angle(v);
      break;
    }
    case ConstraintKind::user_position: {
      std::array<Jet, kMaxUserArgs> x;
      const int n = static_cast<int>(c.args.size());
      for (int k = 0; k < n; ++k) x[k] = Jet(q0[c.args[k].var]);
      const std::span<const Jet> xs(x.data(), n);
      res[r] = c.psi(xs, Jet(t)).v;
      for (int k = 0; k < n; ++k) {
        x[k].d = 1;
        jac.add(r, c.args[k].var, c.psi(xs, Jet(t)).d);
        x[k].d = 0;
      }
      break;
    }
    case ConstraintKind::user_velocity:
      break;
  }
}

// Velocity rows A(q0, t) q1 = b: entries A.add(row, VarRef, value) (VarRef.var may be -1: a fixed
// variable, still reported with its body slot for the reaction bookkeeping), b into rhs[row].
template <class Sink>
void velocity_rows(const Model& m, const Constraint& c, const Eigen::Ref<const VectorXd>& q0,
                   double t, Eigen::Ref<VectorXd> rhs, Sink& A) {
  const int r = c.row1;
  auto add_node = [&](int row, const NodeRef& n, double cx, double cy) {
    if (n.body < 0 && n.var < 0) return;  // ground node
    A.add(row, ref_x(n), cx);  // zeros too: the entry pattern stays fixed (no reallocation)
    A.add(row, ref_y(n), cy);
  };
  switch (c.kind) {
    case ConstraintKind::rigid: {
      const Body& b = m.bodies[c.body];
      const Vec2 p0 = node_position(b.nodes[0], q0);
      const VarRef w = ref_w(m, b.omega);
      for (size_t k = 1; k < b.nodes.size(); ++k) {
        const int row = r + 2 * static_cast<int>(k - 1);
        const Vec2 zr = perp(node_position(b.nodes[k], q0) - p0);
        add_node(row, b.nodes[k], 1, 0);
        add_node(row + 1, b.nodes[k], 0, 1);
        add_node(row, b.nodes[0], -1, 0);
        add_node(row + 1, b.nodes[0], 0, -1);
        A.add(row, w, -zr.x());
        A.add(row + 1, w, -zr.y());
        rhs[row] = rhs[row + 1] = 0;
      }
      break;
    }
    case ConstraintKind::revolute:
      add_node(r, c.b, 1, 0);
      add_node(r + 1, c.b, 0, 1);
      add_node(r, c.a, -1, 0);
      add_node(r + 1, c.a, 0, -1);
      rhs[r] = rhs[r + 1] = 0;
      break;
    case ConstraintKind::prismatic:
    case ConstraintKind::slot: {
      const double q = q0[c.q], l = c.length, s = q / l;
      const Vec2 pi = node_position(c.i, q0), pj = node_position(c.j, q0);
      add_node(r, c.s, 1, 0);
      add_node(r + 1, c.s, 0, 1);
      add_node(r, c.i, -(1 - s), 0);
      add_node(r + 1, c.i, 0, -(1 - s));
      add_node(r, c.j, -s, 0);
      add_node(r + 1, c.j, 0, -s);
      const Vec2 dq = -(pj - pi) / l;
      A.add(r, VarRef{c.q, -1, -1}, dq.x());
      A.add(r + 1, VarRef{c.q, -1, -1}, dq.y());
      rhs[r] = rhs[r + 1] = 0;
      if (c.lock_velocity) {
        A.add(r + 2, ref_w(m, c.w2), 1);
        A.add(r + 2, ref_w(m, c.w1), -1);
        rhs[r + 2] = 0;
      }
      break;
    }
    case ConstraintKind::coordinate:
      A.add(r, VarRef{c.coord, -1, -1}, 1);
      for (const auto& [ref, w] : c.rate_terms) A.add(r, ref, -w);
      rhs[r] = 0;
      break;
    case ConstraintKind::user_position: {
      std::array<Jet, kMaxUserArgs> x;
      const int n = static_cast<int>(c.args.size());
      for (int k = 0; k < n; ++k) x[k] = Jet(q0[c.args[k].var]);
      const std::span<const Jet> xs(x.data(), n);
      for (int k = 0; k < n; ++k) {
        x[k].d = 1;
        A.add(r, c.args[k], c.psi(xs, Jet(t)).d);
        x[k].d = 0;
      }
      rhs[r] = -c.psi(xs, Jet(t, 1, 0)).d;
      break;
    }
    case ConstraintKind::user_velocity: {
      std::array<Jet, kMaxUserArgs> x, v;
      const int nx = static_cast<int>(c.args.size()), nv = static_cast<int>(c.rates.size());
      for (int k = 0; k < nx; ++k) x[k] = Jet(q0[c.args[k].var]);
      for (int k = 0; k < nv; ++k) v[k] = Jet(0.0);
      const std::span<const Jet> xs(x.data(), nx), vs(v.data(), nv);
      rhs[r] = -c.g(xs, vs, Jet(t)).v;
      for (int k = 0; k < nv; ++k) {
        v[k].d = 1;
        A.add(r, c.rates[k], c.g(xs, vs, Jet(t)).d);
        v[k].d = 0;
      }
      break;
    }
  }
}

// Acceleration right-hand side: A a1 = rhs - (terms of d/dt A q1 with a1 = 0) (exact).
inline void acceleration_rows(const Model& m, const Constraint& c,
                              const Eigen::Ref<const VectorXd>& q0,
                              const Eigen::Ref<const VectorXd>& q1, double t,
                              Eigen::Ref<VectorXd> rhs) {
  const int r = c.row1;
  switch (c.kind) {
    case ConstraintKind::rigid: {
      const Body& b = m.bodies[c.body];
      const double w = omega_value(b.omega, q1);
      const Vec2 v0 = node_velocity(b.nodes[0], q1);
      for (size_t k = 1; k < b.nodes.size(); ++k) {
        const Vec2 e = w * perp(node_velocity(b.nodes[k], q1) - v0);
        const int row = r + 2 * static_cast<int>(k - 1);
        rhs[row] = e.x();
        rhs[row + 1] = e.y();
      }
      break;
    }
    case ConstraintKind::revolute:
      rhs[r] = rhs[r + 1] = 0;
      break;
    case ConstraintKind::prismatic:
    case ConstraintKind::slot: {
      const Vec2 e = (2 * q1[c.q] / c.length) * (node_velocity(c.j, q1) - node_velocity(c.i, q1));
      rhs[r] = e.x();
      rhs[r + 1] = e.y();
      if (c.lock_velocity) rhs[r + 2] = 0;
      break;
    }
    case ConstraintKind::coordinate:
      rhs[r] = 0;
      break;
    case ConstraintKind::user_position: {
      std::array<Jet, kMaxUserArgs> x;
      const int n = static_cast<int>(c.args.size());
      for (int k = 0; k < n; ++k) x[k] = Jet(q0[c.args[k].var], q1[c.args[k].var], 0);
      rhs[r] = -c.psi(std::span<const Jet>(x.data(), n), Jet(t, 1, 0)).dd;
      break;
    }
    case ConstraintKind::user_velocity: {
      std::array<Jet, kMaxUserArgs> x, v;
      const int nx = static_cast<int>(c.args.size()), nv = static_cast<int>(c.rates.size());
      for (int k = 0; k < nx; ++k) x[k] = Jet(q0[c.args[k].var], q1[c.args[k].var], 0);
      for (int k = 0; k < nv; ++k) v[k] = Jet(c.rates[k].var < 0 ? 0.0 : q1[c.rates[k].var]);
      rhs[r] =
          -c.g(std::span<const Jet>(x.data(), nx), std::span<const Jet>(v.data(), nv), Jet(t, 1, 0))
               .d;
      break;
    }
  }
}

// Sinks.
struct DenseSink {  // position Jacobian (columns = q0 indices through colmap, -1 dropped)
  Eigen::Ref<Eigen::MatrixXd> J;
  const int* colmap = nullptr;
  void add(int row, int var, double v) {
    const int c = colmap ? colmap[var] : var;
    if (c >= 0) J(row, c) += v;
  }
};
struct DenseVelSink {  // velocity Jacobian A (columns = q1 indices)
  Eigen::Ref<Eigen::MatrixXd> A;
  void add(int row, const VarRef& ref, double v) {
    if (ref.var >= 0) A(row, ref.var) += v;
  }
};
struct SlotRecordSink {  // writes A and records the entries owned by body slots (reactions)
  Eigen::Ref<Eigen::MatrixXd> A;
  const Model& m;
  std::vector<SlotEntry>& entries;
  void add(int row, const VarRef& ref, double v) {
    if (ref.var >= 0) A(row, ref.var) += v;
    if (ref.body >= 0 && ref.slot >= 0)
      entries.push_back({row, m.bodies[ref.body].offset + ref.slot, v});
  }
};
struct NullSink {
  void add(int, int, double) {}
  void add(int, const VarRef&, double) {}
};

}  // namespace mo2d::detail
