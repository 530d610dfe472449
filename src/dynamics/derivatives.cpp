// Directional derivatives of the applied forces and the laws (dynamics/derivatives.hpp).
//
// Along a direction (dq0, dq1), with e = d / l the unit vector of a spring or distance a -> b:
//   body point      dp = J dq0,  dv = J dq1            (J of Example 2.6 (b): linear)
//   length          l = |d|,  dl = e . dd
//   unit vector     de = (dd - e (e . dd)) / l
//   rate            ldot = e . w (w = v_b - v_a),  dldot = de . w + e . dw
//   body angle      theta = atan2(d),  dtheta = (z x d) . dd / |d|^2  (d = p1 - p0)
//   spring force    T e on a, -T e on b:  d(T e) = dT e + T de,
//                   linear T = k (l - l0) + c ldot: dT = k dl + c dldot (0 where clipped)
//   torsional       tau = -k theta_rel - c omega_rel:  dtau = -k dtheta_rel - c domega_rel
//   laws            f(x, t) on Jets x_k = {x_k, dx_k}: df = sum f_x_k dx_k (one evaluation)
#include "dynamics/derivatives.hpp"

#include <array>
#include <cmath>

#include "constraints/common.hpp"
#include "dynamics/chain.hpp"
#include "dynamics/points.hpp"

namespace mo2d::detail {
namespace {

struct PointJet {
  Vec2 p, v, dp, dv;
};
PointJet point_jet(const Model& m, const BodyPoint& bp, const VecRef& q0, const VecRef& q1,
                   const VecRef& dq0, const VecRef& dq1) {
  const PointState s = point_state(m, bp, q0, q1);
  if (bp.body < 0) return {s.p, s.v, Vec2(0, 0), Vec2(0, 0)};
  const Body& b = m.bodies[bp.body];
  // the velocity helper on dq0 is the derivative of the position: fixed nodes do not move
  return {s.p, s.v, local_velocity_of_point(b, dq0, bp.ci, bp.cj, bp.gamma, bp.rho),
          local_velocity_of_point(b, dq1, bp.ci, bp.cj, bp.gamma, bp.rho)};
}

// Length, rate and unit vector of a -> b with their derivatives (0 where the points meet).
struct DistanceJet {
  double l, dl, ldot, dldot;
  Vec2 e, de;
};
DistanceJet distance_jet(const PointJet& a, const PointJet& b) {
  const Vec2 d = b.p - a.p, dd = b.dp - a.dp, w = b.v - a.v, dw = b.dv - a.dv;
  const double l = d.norm();
  if (!(l > 0)) return {0, 0, 0, 0, Vec2(0, 0), Vec2(0, 0)};
  const Vec2 e = d / l;
  const Vec2 de = (dd - e * e.dot(dd)) / l;
  return {l, e.dot(dd), e.dot(w), de.dot(w) + e.dot(dw), e, de};
}

Jet theta_jet(const Model& m, int body, const VecRef& q0, const VecRef& dq0) {
  if (body < 0) return Jet(0.0);
  const Body& b = m.bodies[body];
  const Vec2 d = node_position(b.nodes[1], q0) - node_position(b.nodes[0], q0);
  const Vec2 dd = node_velocity(b.nodes[1], dq0) - node_velocity(b.nodes[0], dq0);
  return {std::atan2(d.y(), d.x()), perp(d).dot(dd) / d.squaredNorm(), 0};
}

Jet omega_jet(const Model& m, int body, const VecRef& q1, const VecRef& dq1) {
  if (body < 0) return Jet(0.0);
  return {omega_value(m.bodies[body].omega, q1), omega_value(m.bodies[body].omega, dq1), 0};
}

Jet wrapped(Jet a) {
  return {wrap_angle(a.v), a.d, 0};
}

}  // namespace

Jet quantity_jet(const Model& m, const Quantity& q, const VecRef& q0, const VecRef& q1,
                 const VecRef& dq0, const VecRef& dq1) {
  using K = Quantity::Kind;
  switch (q.kind) {
    case K::coordinate:
      return {q0[q.var], dq0[q.var], 0};
    case K::rate:
      return {q1[q.var], dq1[q.var], 0};
    case K::constant:
      return Jet(q.value);
    case K::point_x:
    case K::point_y:
    case K::point_vx:
    case K::point_vy: {
      const PointJet p = point_jet(m, q.a, q0, q1, dq0, dq1);
      if (q.kind == K::point_x) return {p.p.x(), p.dp.x(), 0};
      if (q.kind == K::point_y) return {p.p.y(), p.dp.y(), 0};
      if (q.kind == K::point_vx) return {p.v.x(), p.dv.x(), 0};
      return {p.v.y(), p.dv.y(), 0};
    }
    case K::distance:
    case K::distance_rate: {
      const DistanceJet s =
          distance_jet(point_jet(m, q.a, q0, q1, dq0, dq1), point_jet(m, q.b, q0, q1, dq0, dq1));
      return q.kind == K::distance ? Jet(s.l - q.value, s.dl, 0) : Jet(s.ldot, s.dldot, 0);
    }
    case K::body_angle:
      return wrapped(theta_jet(m, q.body1, q0, dq0) - q.value);
    case K::relative_angle:
      return wrapped(theta_jet(m, q.body2, q0, dq0) - theta_jet(m, q.body1, q0, dq0) - q.value);
    case K::relative_rate:
      return omega_jet(m, q.body2, q1, dq1) - omega_jet(m, q.body1, q1, dq1);
  }
  return Jet(0.0);
}

Jet law_jet(const Model& m, const CompiledLaw& law, const VecRef& q0, const VecRef& q1,
            const VecRef& dq0, const VecRef& dq1, double t, const char* role,
            const std::string& element) {
  if (!law.f) return Jet(0.0);
  std::array<Jet, kMaxLawArgs> x;
  const size_t n = law.args.size();
  for (size_t k = 0; k < n; ++k) x[k] = quantity_jet(m, law.args[k], q0, q1, dq0, dq1);
  const Jet f = call_law(law, std::span<const Jet>(x.data(), n), t, role, element);
  return {f.v, f.d, 0};
}

namespace {

void add_body_point_force(const Model& m, const BodyPoint& p, const Vec2& F, double* local) {
  if (p.body < 0) return;
  const Body& b = m.bodies[p.body];
  add_point_force(b, p.ci, p.cj, p.gamma, p.rho, F, local + b.offset);
}

void add_torque(const Model& m, int body, double tau, Eigen::Ref<Eigen::VectorXd> local) {
  if (body >= 0) local[m.bodies[body].offset + m.bodies[body].slots() - 1] += tau;
}

// dT of a spring (SpringLoad) at its state: the law's derivative, or the linear law's, 0 where
// the spring is clipped (not acting).
double spring_tension_derivative(const Model& m, const SpringLoad& s, const DistanceJet& st,
                                 const VecRef& q0, const VecRef& q1, const VecRef& dq0,
                                 const VecRef& dq1, double t, double& T) {
  Jet tj;
  if (s.tension) {
    tj = law_jet(m, s.tension, q0, q1, dq0, dq1, t, "tension of spring", s.name);
  } else {
    const double dl = st.l - s.rest_length;
    if ((s.acts == SpringActs::tension_only && dl <= 0) ||
        (s.acts == SpringActs::compression_only && dl >= 0)) {
      T = 0;
      return 0;
    }
    tj = Jet(s.stiffness * dl + s.damping * st.ldot, s.stiffness * st.dl + s.damping * st.dldot, 0);
  }
  T = tj.v;
  if ((s.acts == SpringActs::tension_only && tj.v < 0) ||
      (s.acts == SpringActs::compression_only && tj.v > 0)) {
    T = 0;
    return 0;
  }
  return tj.d;
}

}  // namespace

void body_applied_derivative(const Model& m, const VecRef& q0, const VecRef& q1, const VecRef& dq0,
                             const VecRef& dq1, double t, Eigen::Ref<Eigen::VectorXd> dlocal) {
  dlocal.setZero();  // gravity is constant
  for (const auto& f : m.forces) {
    const Jet fx = f.fx ? law_jet(m, f.fx, q0, q1, dq0, dq1, t, "force", f.name) : Jet(0.0);
    const Jet fy = f.fy ? law_jet(m, f.fy, q0, q1, dq0, dq1, t, "force", f.name) : Jet(0.0);
    const Vec2 dF(f.cos * fx.d - f.sin * fy.d, f.sin * fx.d + f.cos * fy.d);
    add_body_point_force(m, BodyPoint{f.body, f.ci, f.cj, f.gamma, f.rho, Vec2(0, 0)}, dF,
                         dlocal.data());
  }
  for (const auto& tq : m.torques)
    if (tq.torque)
      add_torque(m, tq.body, law_jet(m, tq.torque, q0, q1, dq0, dq1, t, "torque", tq.name).d,
                 dlocal);
  for (const auto& s : m.springs) {  // T e on a, -T e on b
    const DistanceJet st =
        distance_jet(point_jet(m, s.a, q0, q1, dq0, dq1), point_jet(m, s.b, q0, q1, dq0, dq1));
    double T = 0;
    const double dT = spring_tension_derivative(m, s, st, q0, q1, dq0, dq1, t, T);
    const Vec2 dTe = dT * st.e + T * st.de;
    add_body_point_force(m, s.a, dTe, dlocal.data());
    add_body_point_force(m, s.b, -dTe, dlocal.data());
  }
  for (const auto& l : m.torsional_springs) {
    double dtau = 0;
    if (l.torque) {
      dtau = law_jet(m, l.torque, q0, q1, dq0, dq1, t, "torque of torsional spring", l.name).d;
    } else {
      const Jet th = theta_jet(m, l.body2, q0, dq0) - theta_jet(m, l.body1, q0, dq0);
      const Jet w = omega_jet(m, l.body2, q1, dq1) - omega_jet(m, l.body1, q1, dq1);
      dtau = -l.stiffness * th.d - l.damping * w.d;
    }
    add_torque(m, l.body2, dtau, dlocal);
    add_torque(m, l.body1, -dtau, dlocal);
  }
  add_chain_forces_derivative(m, q0, q1, dq0, dq1, t, dlocal.data());
}

// load_power = sum F . v (forces) + tau omega (torques) - T ldot (spring laws) + tau w_rel
// (torque laws): each product differentiated by the product rule.
double load_power_derivative(const Model& m, const VecRef& q0, const VecRef& q1, const VecRef& dq0,
                             const VecRef& dq1, double t) {
  double dp = 0;
  for (const auto& f : m.forces) {
    const Jet fx = f.fx ? law_jet(m, f.fx, q0, q1, dq0, dq1, t, "force", f.name) : Jet(0.0);
    const Jet fy = f.fy ? law_jet(m, f.fy, q0, q1, dq0, dq1, t, "force", f.name) : Jet(0.0);
    const Vec2 F(f.cos * fx.v - f.sin * fy.v, f.sin * fx.v + f.cos * fy.v);
    const Vec2 dF(f.cos * fx.d - f.sin * fy.d, f.sin * fx.d + f.cos * fy.d);
    const PointJet p =
        point_jet(m, BodyPoint{f.body, f.ci, f.cj, f.gamma, f.rho, Vec2(0, 0)}, q0, q1, dq0, dq1);
    dp += dF.dot(p.v) + F.dot(p.dv);
  }
  for (const auto& tq : m.torques) {
    if (!tq.torque) continue;
    const Jet tau = law_jet(m, tq.torque, q0, q1, dq0, dq1, t, "torque", tq.name);
    const Jet w = omega_jet(m, tq.body, q1, dq1);
    dp += tau.d * w.v + tau.v * w.d;
  }
  for (const auto& s : m.springs) {
    if (!s.tension) continue;
    const DistanceJet st =
        distance_jet(point_jet(m, s.a, q0, q1, dq0, dq1), point_jet(m, s.b, q0, q1, dq0, dq1));
    double T = 0;
    const double dT = spring_tension_derivative(m, s, st, q0, q1, dq0, dq1, t, T);
    dp -= dT * st.ldot + T * st.dldot;
  }
  for (const auto& l : m.torsional_springs) {
    if (!l.torque) continue;
    const Jet tau = law_jet(m, l.torque, q0, q1, dq0, dq1, t, "torque of torsional spring", l.name);
    const Jet w = omega_jet(m, l.body2, q1, dq1) - omega_jet(m, l.body1, q1, dq1);
    dp += tau.d * w.v + tau.v * w.d;
  }
  return dp;
}

// damping_power = sum c ldot^2 (bilateral linear springs) + (T - k (l - l0)) ldot (unilateral
// linear springs while they act, T clipped) + c w_rel^2 (linear torsional springs).
double damping_power_derivative(const Model& m, const VecRef& q0, const VecRef& q1,
                                const VecRef& dq0, const VecRef& dq1) {
  double dp = 0;
  for (const auto& s : m.springs) {
    if (s.tension) continue;
    const DistanceJet st =
        distance_jet(point_jet(m, s.a, q0, q1, dq0, dq1), point_jet(m, s.b, q0, q1, dq0, dq1));
    if (s.acts == SpringActs::both) {
      dp += 2 * s.damping * st.ldot * st.dldot;
      continue;
    }
    double T = 0;
    const double dT = spring_tension_derivative(m, s, st, q0, q1, dq0, dq1, 0.0, T);
    const double dl = st.l - s.rest_length;
    const bool acting = !((s.acts == SpringActs::tension_only && dl <= 0) ||
                          (s.acts == SpringActs::compression_only && dl >= 0));
    const double elastic = acting ? s.stiffness * dl : 0,
                 delastic = acting ? s.stiffness * st.dl : 0;
    dp += (dT - delastic) * st.ldot + (T - elastic) * st.dldot;
  }
  for (const auto& l : m.torsional_springs) {
    if (l.torque) continue;
    const Jet w = omega_jet(m, l.body2, q1, dq1) - omega_jet(m, l.body1, q1, dq1);
    dp += 2 * l.damping * w.v * w.d;
  }
  return dp + chain_damping_power_derivative(m, q0, q1, dq0, dq1);
}

}  // namespace mo2d::detail
