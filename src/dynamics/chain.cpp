// Chain and belt drives (equations in dynamics/chain.hpp): the spans' lengths and tensions at a
// state, their generalized forces, elastic energy and damping power, and the exact directional
// derivatives of the forces and of the damping power (the same code on Jets).
#include "dynamics/chain.hpp"

#include "dynamics/derivatives.hpp"
#include "dynamics/points.hpp"
#include "mo2d/dynamics.hpp"

namespace mo2d::detail {
namespace {

using Vr = Eigen::Ref<const Eigen::VectorXd>;

ChainInput<double> chain_input(const Model& m, const ChainLoad& c, const Vr& q0, const Vr& q1) {
  const PointState a = point_state(m, c.a, q0, q1), b = point_state(m, c.b, q0, q1);
  auto th = [&](int v) { return v < 0 ? 0.0 : q0[v]; };
  auto w = [&](int body) { return body < 0 ? 0.0 : omega_value(m.bodies[body].omega, q1); };
  return {a.p.x(), a.p.y(), b.p.x(),       b.p.y(),       a.v.x(),     a.v.y(),
          b.v.x(), b.v.y(), th(c.theta_a), th(c.theta_b), w(c.body_a), w(c.body_b)};
}

// The same with each value's derivative along (dq0, dq1) (positions and velocities of body
// points are linear in q0 and q1: the velocity helper on dq0 is the derivative of a position).
ChainInput<Jet> chain_input_jet(const Model& m, const ChainLoad& c, const Vr& q0, const Vr& q1,
                                const Vr& dq0, const Vr& dq1) {
  const ChainInput<double> v = chain_input(m, c, q0, q1);
  auto dpoint = [&](const BodyPoint& p, const Vr& x) {
    if (p.body < 0) return Vec2(0, 0);
    return local_velocity_of_point(m.bodies[p.body], x, p.ci, p.cj, p.gamma, p.rho);
  };
  const Vec2 dpa = dpoint(c.a, dq0), dpb = dpoint(c.b, dq0), dva = dpoint(c.a, dq1),
             dvb = dpoint(c.b, dq1);
  auto dth = [&](int var) { return var < 0 ? 0.0 : dq0[var]; };
  auto dw = [&](int body) { return body < 0 ? 0.0 : omega_value(m.bodies[body].omega, dq1); };
  auto j = [](double x, double dx) { return Jet(x, dx, 0); };
  return {j(v.ax, dpa.x()),
          j(v.ay, dpa.y()),
          j(v.bx, dpb.x()),
          j(v.by, dpb.y()),
          j(v.vax, dva.x()),
          j(v.vay, dva.y()),
          j(v.vbx, dvb.x()),
          j(v.vby, dvb.y()),
          j(v.theta_a, dth(c.theta_a)),
          j(v.theta_b, dth(c.theta_b)),
          j(v.wa, dw(c.body_a)),
          j(v.wb, dw(c.body_b))};
}

// The chain's generalized force: a force (fx, fy) at centre a (its opposite at b) and torques on
// the two bodies, from both spans' tensions.
template <class S>
struct ChainForce {
  S fx, fy, torque_a, torque_b;
};
template <class S>
ChainForce<S> chain_force(const ChainLoad& c, const Spans<S>& sp) {
  const S Tu = span_tension(c, sp.upper, c.rest_upper).T;
  const S Tl = span_tension(c, sp.lower, c.rest_lower).T;
  return {Tu * sp.upper.tx + Tl * sp.lower.tx, Tu * sp.upper.ty + Tl * sp.lower.ty,
          c.radius_a * (Tl - Tu), c.radius_b * (Tu - Tl)};
}

void add_force(const Model& m, const ChainLoad& c, double fx, double fy, double ta, double tb,
               double* local) {
  auto add = [&](const BodyPoint& p, int body, double sign, double tau) {
    if (body < 0) return;
    const Body& bd = m.bodies[body];
    add_point_force(bd, p.ci, p.cj, p.gamma, p.rho, Vec2(sign * fx, sign * fy), local + bd.offset);
    local[bd.offset + bd.slots() - 1] += tau;
  };
  add(c.a, c.body_a, 1, ta);
  add(c.b, c.body_b, -1, tb);
}

// (T - elastic) dl/dt of one span: the damper's power (and, unilateral, the clipped part).
template <class S>
S span_damping_power(const ChainLoad& c, const Span<S>& s, double rest) {
  const SpanTension<S> T = span_tension(c, s, rest);
  if (!T.acting) return S(0.0);
  return (T.T - T.elastic) * s.rate;
}

}  // namespace

std::array<double, 2> chain_span_rates(const Model& m, const ChainLoad& c, const Vr& q0,
                                       const Vr& q1, double t) {
  const Spans<double> sp = chain_spans(c, chain_input(m, c, q0, q1), t);
  return {sp.upper.rate, sp.lower.rate};
}

void add_chain_forces(const Model& m, const Vr& q0, const Vr& q1, double t, double* local) {
  for (const ChainLoad& c : m.chains) {
    const ChainForce<double> f = chain_force(c, chain_spans(c, chain_input(m, c, q0, q1), t));
    if (!std::isfinite(f.fx) || !std::isfinite(f.fy) || !std::isfinite(f.torque_a) ||
        !std::isfinite(f.torque_b))
      throw Error("chain '" + c.name + "': tension not finite at t = " + std::to_string(t) + " s",
                  c.name, t);
    add_force(m, c, f.fx, f.fy, f.torque_a, f.torque_b, local);
  }
}

void add_chain_forces_derivative(const Model& m, const Vr& q0, const Vr& q1, const Vr& dq0,
                                 const Vr& dq1, double t, double* dlocal) {
  for (const ChainLoad& c : m.chains) {
    const ChainForce<Jet> f =
        chain_force(c, chain_spans(c, chain_input_jet(m, c, q0, q1, dq0, dq1), t));
    add_force(m, c, f.fx.d, f.fy.d, f.torque_a.d, f.torque_b.d, dlocal);
  }
}

double chain_potential(const Model& m, const Vr& q0) {
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(m.n1);
  double v = 0;
  for (const ChainLoad& c : m.chains) {
    if (c.fidelity == ChainFidelity::inextensible) continue;  // no elastic energy
    const Spans<double> sp = chain_spans(c, chain_input(m, c, q0, zero), 0.0);
    for (const auto& [s, rest] : {std::pair{sp.upper, c.rest_upper}, {sp.lower, c.rest_lower}}) {
      const double e = s.length - rest;
      if (c.fidelity == ChainFidelity::bilateral || e > 0) v += 0.5 * c.stiffness * e * e;
    }
  }
  return v;
}

double chain_damping_power(const Model& m, const Vr& q0, const Vr& q1) {
  double p = 0;
  for (const ChainLoad& c : m.chains) {
    const Spans<double> sp = chain_spans(c, chain_input(m, c, q0, q1), 0.0);
    p += span_damping_power(c, sp.upper, c.rest_upper) +
         span_damping_power(c, sp.lower, c.rest_lower);
  }
  return p;
}

double chain_damping_power_derivative(const Model& m, const Vr& q0, const Vr& q1, const Vr& dq0,
                                      const Vr& dq1) {
  double dp = 0;
  for (const ChainLoad& c : m.chains) {
    const Spans<Jet> sp = chain_spans(c, chain_input_jet(m, c, q0, q1, dq0, dq1), 0.0);
    dp += (span_damping_power(c, sp.upper, c.rest_upper) +
           span_damping_power(c, sp.lower, c.rest_lower))
              .d;
  }
  return dp;
}

void init_chain(const Model& m, ChainLoad& c) {
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(m.n1);
  c.offset_upper = c.offset_lower = 0;
  ChainInput<double> in = chain_input(m, c, m.q0, zero);
  c.beta0 = std::atan2(in.by - in.ay, in.bx - in.ax);
  const Spans<double> sp = chain_spans(c, in, 0.0);
  c.offset_upper = sp.L - sp.upper.length;
  c.offset_lower = sp.L - sp.lower.length;
  if (std::isnan(c.rest_upper)) c.rest_upper = sp.L;
  if (std::isnan(c.rest_lower)) c.rest_lower = sp.L;
}

}  // namespace mo2d::detail

namespace mo2d {

ChainValue chain_value(const Model& m, const ChainLoad& c, const Eigen::Ref<const VectorXd>& q0,
                       const Eigen::Ref<const VectorXd>& q1, double t) {
  using namespace detail;
  const Spans<double> sp = chain_spans(c, chain_input(m, c, q0, q1), t);
  const double Tu = span_tension(c, sp.upper, c.rest_upper).T;
  const double Tl = span_tension(c, sp.lower, c.rest_lower).T;
  return {sp.upper.length, Tu, sp.lower.length, Tl, -Tu * sp.upper.rate - Tl * sp.lower.rate};
}

}  // namespace mo2d
