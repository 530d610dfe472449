// The contacts' points resolved against a Model and their gaps (the kinds: point_line.hpp,
// circle_circle.hpp, profile.hpp): the value, the rate, J' q1 and the gradient J.
#include <cmath>

#include "contact/circle_circle.hpp"
#include "contact/contact_set.hpp"
#include "contact/point_line.hpp"
#include "contact/profile.hpp"
#include "contact/slot_set.hpp"
#include "dynamics/points.hpp"
#include "mo2d/error.hpp"
#include "run/format.hpp"

namespace mo2d::detail {
namespace {

BodyPoint resolve(const Model& m, const ContactDef& c, const std::string& label, const char* role) {
  for (const NamedPoint& p : m.points)
    if (p.name == label) return p.point;
  for (size_t bi = 0; bi < m.bodies.size(); ++bi) {
    const Body& b = m.bodies[bi];
    for (size_t k = 0; k < b.node_names.size(); ++k)
      if (b.node_names[k] == label) {
        BodyPoint p;
        p.body = static_cast<int>(bi);
        p.ci = static_cast<int>(k);
        return p;
      }
  }
  for (size_t g = 0; g < m.ground_names.size(); ++g)
    if (m.ground_names[g] == label) {
      BodyPoint p;
      p.fixed = m.ground_positions[g];
      return p;
    }
  throw Error("contact '" + c.name + "': its " + role + " '" + label +
                  "' is not a body node, a ground node or a named point of '" + m.name + "'",
              c.name);
}

void check_law(const ContactDef& c) {
  const ContactLaw& l = c.law;
  auto bad = [&](const std::string& what) {
    throw Error("contact '" + c.name + "': " + what, c.name);
  };
  if (!(l.restitution >= 0 && l.restitution <= 1))
    bad("the restitution must be in [0, 1] (got " + fmt(l.restitution) + ")");
  if (l.kind == ContactLaw::Kind::compliant) {
    if (!(l.stiffness > 0 && std::isfinite(l.stiffness)))
      bad("a compliant contact needs a stiffness > 0 (got " + fmt(l.stiffness) + ")");
    if (!(l.exponent >= 1 && l.exponent <= 3))
      bad("the exponent must be in [1, 3] (got " + fmt(l.exponent) + ")");
    if (!(l.min_approach_speed > 0 && std::isfinite(l.min_approach_speed)))
      bad("min_approach_speed must be > 0 (got " + fmt(l.min_approach_speed) + ")");
  }
  if (!(l.friction >= 0 && std::isfinite(l.friction)))
    bad("the friction coefficient must be >= 0 (got " + fmt(l.friction) + ")");
  if (!(c.radius >= 0 && std::isfinite(c.radius)))
    bad("the radius must be >= 0 (got " + fmt(c.radius) + ")");
  if (c.target == ContactDef::Target::slot) {
    check_slot(c);
    return;
  }
  if ((c.target == ContactDef::Target::circle || c.target == ContactDef::Target::hole) &&
      !(c.target_radius > 0 && std::isfinite(c.target_radius)))
    bad("a circle or hole needs target_radius > 0 (got " + fmt(c.target_radius) + ")");
  if (c.target == ContactDef::Target::hole && !(c.target_radius > c.radius))
    bad("a hole must be larger than the circle in it (target_radius " + fmt(c.target_radius) +
        " <= radius " + fmt(c.radius) + ")");
}

Jet coordinate_jet(double p, double v) {
  return {p, v, 0.0};
}

// A profile's table (present and fit for the contact's radius), its axis on one body, no friction.
void check_profile(const ContactDef& c, const CompiledContact& out) {
  auto bad = [&](const std::string& what) {
    throw Error("contact '" + c.name + "': " + what, c.name);
  };
  if (!c.profile) bad("a profile target needs its table (ContactDef::profile)");
  const std::string problem = profile_problem(*c.profile, c.radius);
  if (!problem.empty()) bad(problem);
  if (out.a.body != out.b.body)
    bad("its profile's centre '" + c.a + "' and axis point '" + c.b +
        "' must be on one body (the cam's)");
  if (c.law.friction > 0)
    bad("friction on a cam profile is not supported (its tangent is not implemented): give "
        "friction 0");
}

}  // namespace

CompiledContact compile_contact(const Model& m, const ContactDef& c) {
  check_law(c);
  CompiledContact out;
  out.def = c;
  out.p = resolve(m, c, c.point, "point");
  const bool two = c.target == ContactDef::Target::line || c.target == ContactDef::Target::slot ||
                   c.target == ContactDef::Target::profile;
  const char* a_name = c.target == ContactDef::Target::line   ? "line point a"
                       : c.target == ContactDef::Target::slot ? "point a"
                                                              : "centre a";
  const char* b_name = c.target == ContactDef::Target::line   ? "line point b"
                       : c.target == ContactDef::Target::slot ? "point b"
                                                              : "profile axis point b";
  out.a = resolve(m, c, c.a, a_name);
  if (two) out.b = resolve(m, c, c.b, b_name);
  if (c.target == ContactDef::Target::slot) check_slot_points(m, out);
  if (c.target == ContactDef::Target::profile) check_profile(c, out);
  if (out.p.body >= 0 && (out.p.body == out.a.body || (two && out.p.body == out.b.body)))
    throw Error("contact '" + c.name + "': its point and what it touches are on the same body",
                c.name);
  if (c.law.friction > 0 && c.target == ContactDef::Target::line && out.a.body != out.b.body)
    throw Error("contact '" + c.name + "': with friction its line's points '" + c.a + "' and '" +
                    c.b + "' must be on one body (the surface the point slides on)",
                c.name);
  return out;
}

void add_point_gradient(const Model& m, const BodyPoint& p, const Vec2& w, Eigen::VectorXd& J) {
  if (p.body < 0) return;
  const Body& b = m.bodies[p.body];
  auto add = [&J](const NodeRef& n, double x, double y) {
    if (n.var < 0) return;
    J[n.var] += x;
    J[n.var + 1] += y;
  };
  if (p.cj < 0) {
    add(b.nodes[p.ci], w.x(), w.y());
    return;
  }
  const double g = p.gamma, r = p.rho;  // the transpose of Example 2.6 (b)'s J_i, J_j
  add(b.nodes[p.ci], (1 - g) * w.x() - r * w.y(), r * w.x() + (1 - g) * w.y());
  add(b.nodes[p.cj], g * w.x() + r * w.y(), -r * w.x() + g * w.y());
}

void gap_into(const Model& m, const CompiledContact& c, const Eigen::Ref<const Eigen::VectorXd>& q0,
              const Eigen::Ref<const Eigen::VectorXd>& q1, GapValue& out) {
  const PointState P = point_state(m, c.p, q0, q1), A = point_state(m, c.a, q0, q1);
  const Jet px = coordinate_jet(P.p.x(), P.v.x()), py = coordinate_jet(P.p.y(), P.v.y());
  const Jet ax = coordinate_jet(A.p.x(), A.v.x()), ay = coordinate_jet(A.p.y(), A.v.y());
  out.J.setZero();
  if (c.def.target == ContactDef::Target::slot) {
    slot_gap_into(m, c, q0, q1, out);
    return;
  }
  Jet g;
  if (c.def.target == ContactDef::Target::profile) {
    const PointState B = point_state(m, c.b, q0, q1);
    ProfileFoot foot;
    g = profile_gap(*c.def.profile, px, py, ax, ay, coordinate_jet(B.p.x(), B.v.x()),
                    coordinate_jet(B.p.y(), B.v.y()), c.def.radius, c.phi, c.def.name, &foot);
    const ProfileGradient d = profile_gradient(foot, A.p, B.p);
    add_point_gradient(m, c.p, d.dP, out.J);
    add_point_gradient(m, c.a, d.dA, out.J);
    add_point_gradient(m, c.b, d.dB, out.J);
  } else if (c.def.target == ContactDef::Target::line) {
    const PointState B = point_state(m, c.b, q0, q1);
    if (!((B.p - A.p).norm() > 0))
      throw Error("contact '" + c.def.name + "': its line has zero length (a = b)", c.def.name);
    g = point_line_gap(px, py, ax, ay, coordinate_jet(B.p.x(), B.v.x()),
                       coordinate_jet(B.p.y(), B.v.y()), c.def.radius);
    const LineGradient d = point_line_gradient(P.p, A.p, B.p, c.def.radius);
    add_point_gradient(m, c.p, d.dP, out.J);
    add_point_gradient(m, c.a, d.dA, out.J);
    add_point_gradient(m, c.b, d.dB, out.J);
  } else {
    const double sign = c.def.target == ContactDef::Target::circle ? 1.0 : -1.0;
    g = circle_circle_gap(px, py, ax, ay, c.def.target_radius, c.def.radius, sign);
    const double D = (P.p - A.p).norm();
    if (D > 0) {
      const Vec2 u = sign * (P.p - A.p) / D;
      add_point_gradient(m, c.p, u, out.J);
      add_point_gradient(m, c.a, -u, out.J);
    } else if (sign > 0) {
      throw Error("contact '" + c.def.name +
                      "': the circles' centres coincide (a penetration by the sum of the radii)",
                  c.def.name);
    }
  }
  out.g = g.v;
  out.rate = g.d;
  out.curvature = g.dd;
}

double gap_only(const Model& m, const CompiledContact& c,
                const Eigen::Ref<const Eigen::VectorXd>& q0) {
  auto at = [&](const BodyPoint& p) {
    return p.body < 0 ? p.fixed
                      : local_position_of_point(m.bodies[p.body], q0, p.ci, p.cj, p.gamma, p.rho);
  };
  if (c.def.target == ContactDef::Target::slot) return slot_gap_only(m, c, q0);
  const Vec2 P = at(c.p), A = at(c.a);
  if (c.def.target == ContactDef::Target::profile) {
    const Vec2 B = at(c.b);
    return profile_gap(*c.def.profile, Jet(P.x()), Jet(P.y()), Jet(A.x()), Jet(A.y()), Jet(B.x()),
                       Jet(B.y()), c.def.radius, c.phi, c.def.name)
        .v;
  }
  if (c.def.target == ContactDef::Target::line) {
    const Vec2 B = at(c.b);
    return point_line_gap(P.x(), P.y(), A.x(), A.y(), B.x(), B.y(), c.def.radius);
  }
  const double sign = c.def.target == ContactDef::Target::circle ? 1.0 : -1.0;
  return circle_circle_gap(P.x(), P.y(), A.x(), A.y(), c.def.target_radius, c.def.radius, sign);
}

}  // namespace mo2d::detail

namespace mo2d {

GapValue contact_gap(const Model& m, const ContactDef& c, const Eigen::VectorXd& q0,
                     const Eigen::VectorXd& q1) {
  const detail::CompiledContact cc = detail::compile_contact(m, c);
  GapValue out;
  out.J = Eigen::VectorXd::Zero(m.n1);
  detail::gap_into(m, cc, q0, q1, out);
  return out;
}

}  // namespace mo2d
