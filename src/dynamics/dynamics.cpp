// Constant mass matrix and applied forces of the nodal 2D rigid body element.
#include "mo2d/dynamics.hpp"

#include <algorithm>
#include <string>

#include "constraints/constraints.hpp"
#include "dynamics/chain.hpp"
#include "dynamics/points.hpp"
#include "mo2d/error.hpp"

namespace mo2d {
using detail::add_point_force;
using detail::local_velocity_of_point;
using detail::point_state;
using detail::PointState;

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

namespace {

// A spring's tension at its state, and the elastic part of it that has a potential (linear
// springs: k (l - l0) while the spring acts; laws: none, their work is load work).
struct SpringForce {
  double T = 0, elastic = 0;
};
SpringForce spring_force(const Model& m, const SpringLoad& s, const SpringState& st,
                         const Eigen::Ref<const VectorXd>& q0, const Eigen::Ref<const VectorXd>& q1,
                         double t) {
  if (s.tension) {
    const double T = law_value(m, s.tension, q0, q1, t, "tension of spring", s.name);
    if (s.acts == SpringActs::tension_only) return {std::max(T, 0.0), 0};
    if (s.acts == SpringActs::compression_only) return {std::min(T, 0.0), 0};
    return {T, 0};
  }
  const double dl = st.l - s.rest_length;
  if ((s.acts == SpringActs::tension_only && dl <= 0) ||
      (s.acts == SpringActs::compression_only && dl >= 0))
    return {0, 0};
  const double T = s.stiffness * dl + s.damping * st.ldot;
  if (s.acts == SpringActs::tension_only) return {std::max(T, 0.0), s.stiffness * dl};
  if (s.acts == SpringActs::compression_only) return {std::min(T, 0.0), s.stiffness * dl};
  return {T, s.stiffness * dl};
}

// A torsional spring's torque on body 2 (a law; the linear law is written out where it is used).
double torsional_law(const Model& m, const TorsionalLoad& l, const Eigen::Ref<const VectorXd>& q0,
                     const Eigen::Ref<const VectorXd>& q1, double t) {
  return law_value(m, l.torque, q0, q1, t, "torque of torsional spring", l.name);
}

}  // namespace

double potential_energy(const Model& m, const Eigen::Ref<const VectorXd>& q0) {
  double v = 0;
  for (const Body& b : m.bodies) v -= b.mass * m.gravity.dot(com_position(b, q0));
  const VectorXd zero = VectorXd::Zero(m.n1);
  for (const auto& s : m.springs) {
    if (s.tension) continue;  // a law: load work
    const double dl = spring_state(m, s, q0, zero).l - s.rest_length;
    if ((s.acts == SpringActs::tension_only && dl <= 0) ||
        (s.acts == SpringActs::compression_only && dl >= 0))
      continue;
    v += 0.5 * s.stiffness * dl * dl;
  }
  for (const auto& l : m.torsional_springs) {
    if (l.torque) continue;
    const double th = relative_angle(m, l, q0);
    v += 0.5 * l.stiffness * th * th;
  }
  return v + detail::chain_potential(m, q0);
}

double damping_power(const Model& m, const Eigen::Ref<const VectorXd>& q0,
                     const Eigen::Ref<const VectorXd>& q1) {
  double p = 0;
  for (const auto& s : m.springs) {
    if (s.tension) continue;
    const SpringState st = spring_state(m, s, q0, q1);
    if (s.acts == SpringActs::both) {
      p += s.damping * st.ldot * st.ldot;
      continue;
    }
    // a unilateral spring: what its tension takes beyond the elastic part (the damping, and the
    // clipped part when it would push or pull), t unused by linear springs
    const SpringForce F = spring_force(m, s, st, q0, q1, 0.0);
    p += (F.T - F.elastic) * st.ldot;
  }
  for (const auto& l : m.torsional_springs) {
    if (l.torque) continue;
    const double w = relative_rate(m, l, q1);
    p += l.damping * w * w;
  }
  return p + detail::chain_damping_power(m, q0, q1);
}

Vec2 point_force(const Model& m, const PointLoad& f, const Eigen::Ref<const VectorXd>& q0,
                 const Eigen::Ref<const VectorXd>& q1, double t) {
  const double fx = f.fx ? law_value(m, f.fx, q0, q1, t, "force", f.name) : 0.0;
  const double fy = f.fy ? law_value(m, f.fy, q0, q1, t, "force", f.name) : 0.0;
  return {f.cos * fx - f.sin * fy, f.sin * fx + f.cos * fy};
}

double torque_value(const Model& m, const TorqueLoad& tq, const Eigen::Ref<const VectorXd>& q0,
                    const Eigen::Ref<const VectorXd>& q1, double t) {
  return tq.torque ? law_value(m, tq.torque, q0, q1, t, "torque", tq.name) : 0.0;
}

double load_power(const Model& m, const Eigen::Ref<const VectorXd>& q0,
                  const Eigen::Ref<const VectorXd>& q1, double t) {
  double p = 0;
  for (const auto& f : m.forces) {  // F . v of the point it acts on
    const BodyPoint bp{f.body, f.ci, f.cj, f.gamma, f.rho, Vec2(0, 0)};
    p += point_force(m, f, q0, q1, t).dot(point_state(m, bp, q0, q1).v);
  }
  for (const auto& tq : m.torques)  // tau . omega of its body
    p += torque_value(m, tq, q0, q1, t) * omega_value(m.bodies[tq.body].omega, q1);
  for (const auto& s : m.springs) {  // a spring law: -T dl/dt
    if (!s.tension) continue;
    const SpringState st = spring_state(m, s, q0, q1);
    p -= spring_force(m, s, st, q0, q1, t).T * st.ldot;
  }
  for (const auto& l : m.torsional_springs)  // a torque law: tau (w2 - w1)
    if (l.torque) p += torsional_law(m, l, q0, q1, t) * relative_rate(m, l, q1);
  return p;
}

void body_applied(const Model& m, const Eigen::Ref<const VectorXd>& q0,
                  const Eigen::Ref<const VectorXd>& q1, double t, Eigen::Ref<VectorXd> local) {
  local.setZero();
  for (const Body& b : m.bodies)
    add_point_force(b, b.ci, b.cj, b.gamma, b.rho, b.mass * m.gravity, local.data() + b.offset);
  for (const auto& f : m.forces) {
    const Body& b = m.bodies[f.body];
    const Vec2 F = point_force(m, f, q0, q1, t);
    if (!F.allFinite())
      throw Error("force '" + f.name + "' is not finite at t = " + std::to_string(t) + " s", f.name,
                  t);
    add_point_force(b, f.ci, f.cj, f.gamma, f.rho, F, local.data() + b.offset);
  }
  for (const auto& tq : m.torques) {
    const Body& b = m.bodies[tq.body];
    const double tau = torque_value(m, tq, q0, q1, t);
    if (!std::isfinite(tau))
      throw Error("torque '" + tq.name + "' is not finite at t = " + std::to_string(t) + " s",
                  tq.name, t);
    local[b.offset + b.slots() - 1] += tau;
  }
  for (const auto& s : m.springs) {  // tension T pulls a towards b and b towards a
    const SpringState st = spring_state(m, s, q0, q1);
    const double T = spring_force(m, s, st, q0, q1, t).T;
    if (s.a.body >= 0)
      add_point_force(m.bodies[s.a.body], s.a.ci, s.a.cj, s.a.gamma, s.a.rho, T * st.e,
                      local.data() + m.bodies[s.a.body].offset);
    if (s.b.body >= 0)
      add_point_force(m.bodies[s.b.body], s.b.ci, s.b.cj, s.b.gamma, s.b.rho, -T * st.e,
                      local.data() + m.bodies[s.b.body].offset);
  }
  for (const auto& l : m.torsional_springs) {
    const double tau =
        l.torque ? torsional_law(m, l, q0, q1, t)
                 : -l.stiffness * relative_angle(m, l, q0) - l.damping * relative_rate(m, l, q1);
    if (l.body2 >= 0) local[m.bodies[l.body2].offset + m.bodies[l.body2].slots() - 1] += tau;
    if (l.body1 >= 0) local[m.bodies[l.body1].offset + m.bodies[l.body1].slots() - 1] -= tau;
  }
  detail::add_chain_forces(m, q0, q1, t, local.data());
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

SpringValue spring_value(const Model& m, const SpringLoad& s, const Eigen::Ref<const VectorXd>& q0,
                         const Eigen::Ref<const VectorXd>& q1, double t) {
  const SpringState st = spring_state(m, s, q0, q1);
  return {st.l, st.ldot, spring_force(m, s, st, q0, q1, t).T};
}

TorsionalValue torsional_value(const Model& m, const TorsionalLoad& l,
                               const Eigen::Ref<const VectorXd>& q0,
                               const Eigen::Ref<const VectorXd>& q1, double t) {
  const double w = relative_rate(m, l, q1);
  const double tau = l.torque ? torsional_law(m, l, q0, q1, t)
                              : -l.stiffness * relative_angle(m, l, q0) - l.damping * w;
  return {tau, w};
}

MatrixXd input_matrix(const Model& m) {
  MatrixXd B = MatrixXd::Zero(m.n1, m.n_inputs());
  for (int k = 0; k < m.n_inputs(); ++k)
    for (const auto& [ref, c] : m.inputs[k].terms)
      if (ref.var >= 0) B(ref.var, k) += c;
  return B;
}

}  // namespace mo2d
