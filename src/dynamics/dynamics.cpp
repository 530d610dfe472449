// Constant mass matrix and applied forces of the nodal 2D rigid body element.
#include "mo2d/dynamics.hpp"

#include <string>

#include "constraints/constraints.hpp"
#include "mo2d/error.hpp"

namespace mo2d {
namespace {

// Generalized force of a force F applied at the point (ci, cj, gamma, rho): J^T F.
inline void add_point_force(const Body& b, int ci, int cj, double gamma, double rho, const Vec2& F,
                            double* local) {
  if (cj < 0) {
    local[2 * ci] += F.x();
    local[2 * ci + 1] += F.y();
    return;
  }
  // J_i^T F, J_j^T F
  local[2 * ci] += (1 - gamma) * F.x() - rho * F.y();
  local[2 * ci + 1] += rho * F.x() + (1 - gamma) * F.y();
  local[2 * cj] += gamma * F.x() + rho * F.y();
  local[2 * cj + 1] += -rho * F.x() + gamma * F.y();
  (void)b;
}

// J (x_i, x_j) of Example 2.6 (b): the point (ci, cj, gamma, rho) from its two nodes' values.
inline Vec2 combine_point(const Vec2& xi, const Vec2& xj, double gamma, double rho) {
  return {(1 - gamma) * xi.x() + rho * xi.y() + gamma * xj.x() - rho * xj.y(),
          -rho * xi.x() + (1 - gamma) * xi.y() + rho * xj.x() + gamma * xj.y()};
}

// Velocity (or acceleration, for x = q1 rates) of a body point: a fixed node contributes 0.
inline Vec2 local_velocity_of_point(const Body& b, const Eigen::Ref<const VectorXd>& x, int ci,
                                    int cj, double gamma, double rho) {
  Vec2 vi = node_velocity(b.nodes[ci], x);
  if (cj < 0) return vi;
  return combine_point(vi, node_velocity(b.nodes[cj], x), gamma, rho);
}

// Position of a body point: a fixed node (joined to the ground) sits at its fixed position, which
// is why positions must never go through the velocity helper above.
inline Vec2 local_position_of_point(const Body& b, const Eigen::Ref<const VectorXd>& q0, int ci,
                                    int cj, double gamma, double rho) {
  Vec2 pi = node_position(b.nodes[ci], q0);
  if (cj < 0) return pi;
  return combine_point(pi, node_position(b.nodes[cj], q0), gamma, rho);
}

}  // namespace

void body_inertia(const Model& m, const Eigen::Ref<const VectorXd>& a1,
                  Eigen::Ref<VectorXd> local) {
  local.setZero();
  int off = 0;
  for (const Body& b : m.bodies) {
    double* l = local.data() + off;
    // m J^T (J a): the centre-of-mass acceleration times the mass, distributed by J^T
    const Vec2 acom = local_velocity_of_point(b, a1, b.ci, b.cj, b.gamma, b.rho);
    add_point_force(b, b.ci, b.cj, b.gamma, b.rho, b.mass * acom, l);
    if (b.has_omega) l[b.slots() - 1] = b.inertia * omega_value(b.omega, a1);
    off += b.slots();
  }
}

namespace {

struct PointState {
  Vec2 p, v;
};
PointState point_state(const Model& m, const BodyPoint& bp, const Eigen::Ref<const VectorXd>& q0,
                       const Eigen::Ref<const VectorXd>& q1) {
  if (bp.body < 0) return {bp.fixed, Vec2(0, 0)};
  const Body& b = m.bodies[bp.body];
  return {local_position_of_point(b, q0, bp.ci, bp.cj, bp.gamma, bp.rho),
          local_velocity_of_point(b, q1, bp.ci, bp.cj, bp.gamma, bp.rho)};
}

double relative_angle(const Model& m, const TorsionalLoad& l,
                      const Eigen::Ref<const VectorXd>& q0) {
  auto th = [&](int body) { return body < 0 ? 0.0 : body_angle(m.bodies[body], q0); };
  return detail::wrap_angle(th(l.body2) - th(l.body1) - l.rest);
}

double relative_rate(const Model& m, const TorsionalLoad& l, const Eigen::Ref<const VectorXd>& q1) {
  auto w = [&](int body) { return body < 0 ? 0.0 : omega_value(m.bodies[body].omega, q1); };
  return w(l.body2) - w(l.body1);
}

// Spring: length, its rate and the unit vector from a to b.
struct SpringState {
  double l, ldot;
  Vec2 e;
};
SpringState spring_state(const Model& m, const SpringLoad& s, const Eigen::Ref<const VectorXd>& q0,
                         const Eigen::Ref<const VectorXd>& q1) {
  const PointState a = point_state(m, s.a, q0, q1), b = point_state(m, s.b, q0, q1);
  const Vec2 d = b.p - a.p;
  const double l = d.norm();
  const Vec2 e = l > 0 ? Vec2(d / l) : Vec2(0, 0);
  return {l, e.dot(b.v - a.v), e};
}

}  // namespace

double potential_energy(const Model& m, const Eigen::Ref<const VectorXd>& q0) {
  double v = 0;
  for (const Body& b : m.bodies) v -= b.mass * m.gravity.dot(com_position(b, q0));
  const VectorXd zero = VectorXd::Zero(m.n1);
  for (const auto& s : m.springs) {
    const double dl = spring_state(m, s, q0, zero).l - s.rest_length;
    v += 0.5 * s.stiffness * dl * dl;
  }
  for (const auto& l : m.torsional_springs) {
    const double th = relative_angle(m, l, q0);
    v += 0.5 * l.stiffness * th * th;
  }
  return v;
}

double damping_power(const Model& m, const Eigen::Ref<const VectorXd>& q0,
                     const Eigen::Ref<const VectorXd>& q1) {
  double p = 0;
  for (const auto& s : m.springs) {
    const double ld = spring_state(m, s, q0, q1).ldot;
    p += s.damping * ld * ld;
  }
  for (const auto& l : m.torsional_springs) {
    const double w = relative_rate(m, l, q1);
    p += l.damping * w * w;
  }
  return p;
}

double load_power(const Model& m, const Eigen::Ref<const VectorXd>& q0,
                  const Eigen::Ref<const VectorXd>& q1, double t) {
  double p = 0;
  for (const auto& f : m.forces) {  // F . v of the point it acts on
    const Vec2 F(f.fx ? f.fx(t) : 0.0, f.fy ? f.fy(t) : 0.0);
    const BodyPoint bp{f.body, f.ci, f.cj, f.gamma, f.rho, Vec2(0, 0)};
    p += F.dot(point_state(m, bp, q0, q1).v);
  }
  for (const auto& tq : m.torques)  // tau . omega of its body
    p += (tq.torque ? tq.torque(t) : 0.0) * omega_value(m.bodies[tq.body].omega, q1);
  return p;
}

void body_applied(const Model& m, const Eigen::Ref<const VectorXd>& q0,
                  const Eigen::Ref<const VectorXd>& q1, double t, Eigen::Ref<VectorXd> local) {
  local.setZero();
  for (const Body& b : m.bodies)
    add_point_force(b, b.ci, b.cj, b.gamma, b.rho, b.mass * m.gravity, local.data() + b.offset);
  for (const auto& f : m.forces) {
    const Body& b = m.bodies[f.body];
    const Vec2 F(f.fx ? f.fx(t) : 0.0, f.fy ? f.fy(t) : 0.0);
    if (!F.allFinite())
      throw Error("force '" + f.name + "' is not finite at t = " + std::to_string(t) + " s", f.name,
                  t);
    add_point_force(b, f.ci, f.cj, f.gamma, f.rho, F, local.data() + b.offset);
  }
  for (const auto& tq : m.torques) {
    const Body& b = m.bodies[tq.body];
    const double tau = tq.torque ? tq.torque(t) : 0.0;
    if (!std::isfinite(tau))
      throw Error("torque '" + tq.name + "' is not finite at t = " + std::to_string(t) + " s",
                  tq.name, t);
    local[b.offset + b.slots() - 1] += tau;
  }
  for (const auto& s : m.springs) {  // tension T pulls a towards b and b towards a
    const SpringState st = spring_state(m, s, q0, q1);
    const double T = s.stiffness * (st.l - s.rest_length) + s.damping * st.ldot;
    if (s.a.body >= 0)
      add_point_force(m.bodies[s.a.body], s.a.ci, s.a.cj, s.a.gamma, s.a.rho, T * st.e,
                      local.data() + m.bodies[s.a.body].offset);
    if (s.b.body >= 0)
      add_point_force(m.bodies[s.b.body], s.b.ci, s.b.cj, s.b.gamma, s.b.rho, -T * st.e,
                      local.data() + m.bodies[s.b.body].offset);
  }
  for (const auto& l : m.torsional_springs) {
    const double tau =
        -l.stiffness * relative_angle(m, l, q0) - l.damping * relative_rate(m, l, q1);
    if (l.body2 >= 0) local[m.bodies[l.body2].offset + m.bodies[l.body2].slots() - 1] += tau;
    if (l.body1 >= 0) local[m.bodies[l.body1].offset + m.bodies[l.body1].slots() - 1] -= tau;
  }
}

void scatter_local(const Model& m, const Eigen::Ref<const VectorXd>& local,
                   Eigen::Ref<VectorXd> out) {
  for (const Body& b : m.bodies) {
    const double* l = local.data() + b.offset;
    for (const NodeRef& n : b.nodes) {
      if (n.var < 0) continue;
      out[n.var] += l[2 * n.local];
      out[n.var + 1] += l[2 * n.local + 1];
    }
    if (b.omega.var >= 0) out[b.omega.var] += l[b.slots() - 1];
  }
}

MatrixXd mass_matrix(const Model& m) {
  MatrixXd M = MatrixXd::Zero(m.n1, m.n1);
  VectorXd e = VectorXd::Zero(m.n1), local(m.n_slots), col(m.n1);
  for (int k = 0; k < m.n1; ++k) {
    e.setZero();
    e[k] = 1;
    body_inertia(m, e, local);
    col.setZero();
    scatter_local(m, local, col);
    M.col(k) = col;
  }
  return M;
}

void applied_forces(const Model& m, const Eigen::Ref<const VectorXd>& q0,
                    const Eigen::Ref<const VectorXd>& q1, double t, Eigen::Ref<VectorXd> f) {
  VectorXd local(m.n_slots);
  body_applied(m, q0, q1, t, local);
  f.setZero();
  scatter_local(m, local, f);
}

MatrixXd input_matrix(const Model& m) {
  MatrixXd B = MatrixXd::Zero(m.n1, m.n_inputs());
  for (int k = 0; k < m.n_inputs(); ++k)
    for (const auto& [ref, c] : m.inputs[k].terms)
      if (ref.var >= 0) B(ref.var, k) += c;
  return B;
}

}  // namespace mo2d
