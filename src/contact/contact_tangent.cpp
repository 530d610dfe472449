// The contacts' tangents (tangent.hpp): the sliding rate v_t, its Jacobian J_t and the bias
// dv_t/dt - J_t a.
#include "contact/contact_set.hpp"
#include "contact/tangent.hpp"
#include "dynamics/points.hpp"
#include "mo2d/error.hpp"

namespace mo2d::detail {
namespace {

int tangent_omega_var(const Model& m, const BodyPoint& p) {
  return p.body < 0 ? -1 : m.bodies[p.body].omega.var;
}

int tangent_kind(const ContactDef& c) {
  switch (c.target) {
    case ContactDef::Target::line:
      return 0;
    case ContactDef::Target::circle:
      return 1;
    case ContactDef::Target::hole:
      break;
    case ContactDef::Target::slot:  // friction in a slot is refused (check_slot)
      throw Error("contact '" + c.name + "': a slot has no tangent (friction in a slot)", c.name);
    case ContactDef::Target::profile:
      throw Error("contact '" + c.name +
                      "': the tangent of a cam profile is not implemented (no friction on it)",
                  c.name);
  }
  return -1;
}

}  // namespace

void tangent_into(const Model& m, const CompiledContact& c,
                  const Eigen::Ref<const Eigen::VectorXd>& q0,
                  const Eigen::Ref<const Eigen::VectorXd>& q1, TangentValue& out) {
  const int kind = tangent_kind(c.def);
  const PointState P = point_state(m, c.p, q0, q1), A = point_state(m, c.a, q0, q1);
  const PointState B = kind == 0 ? point_state(m, c.b, q0, q1) : A;
  if (kind == 0 ? !((B.p - A.p).norm() > 0) : !((P.p - A.p).norm() > 0))
    throw Error("contact '" + c.def.name + "': its tangent is undefined (" +
                    (kind == 0 ? "a line of zero length" : "the circles' centres coincide") + ")",
                c.def.name);
  const int w1 = tangent_omega_var(m, c.p), w2 = tangent_omega_var(m, c.a);
  const double W1 = w1 < 0 ? 0.0 : q1[w1], W2 = w2 < 0 ? 0.0 : q1[w2];
  // the points moving at their velocities, the velocities held: value v_t, derivative the bias
  auto jet = [](double p, double v) { return Jet(p, v, 0.0); };
  const TangentGeometry<Jet> g = tangent_geometry(
      jet(P.p.x(), P.v.x()), jet(P.p.y(), P.v.y()), jet(A.p.x(), A.v.x()), jet(A.p.y(), A.v.y()),
      jet(B.p.x(), B.v.x()), jet(B.p.y(), B.v.y()), c.def.radius, kind);
  const Vec2 dv = P.v - A.v;
  const Jet vt = g.tx * dv.x() + g.ty * dv.y() + g.arm1 * W1 - g.arm2 * W2;
  out.rate = vt.v;
  out.curvature = vt.d;
  out.J.setZero();
  const Vec2 t(g.tx.v, g.ty.v);
  add_point_gradient(m, c.p, t, out.J);
  add_point_gradient(m, c.a, -t, out.J);
  if (w1 >= 0) out.J[w1] += g.arm1.v;
  if (w2 >= 0) out.J[w2] -= g.arm2.v;
}

}  // namespace mo2d::detail

namespace mo2d {

TangentValue contact_tangent(const Model& m, const ContactDef& c, const Eigen::VectorXd& q0,
                             const Eigen::VectorXd& q1) {
  const detail::CompiledContact cc = detail::compile_contact(m, c);
  if (cc.def.target == ContactDef::Target::line && cc.a.body != cc.b.body)
    throw Error("contact '" + c.name + "': its line's points '" + c.a + "' and '" + c.b +
                    "' are on two bodies: its tangent belongs to no body",
                c.name);
  TangentValue out;
  out.J = Eigen::VectorXd::Zero(m.n1);
  detail::tangent_into(m, cc, q0, q1, out);
  return out;
}

}  // namespace mo2d
