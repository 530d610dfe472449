// Contacts (issue 35, item 4) and constant-speed drives in the Box2D world; see box2d_world.hpp.
//
// Translation of a contact (mo2d/contact.hpp) into two fixtures, one on each body (density 0: the
// bodies keep the mass data set by build_box2d_world), friction 0 (a contact with Coulomb
// friction, ContactLaw::friction > 0, is refused: not compared with Box2D's yet), restitution e on
// both (Box2D mixes restitutions by max), restitution threshold
// CrosscheckOptions::restitution_threshold on both (mixed by min; 2.4.1 has no global
// b2_velocityThreshold: the threshold is b2FixtureDef::restitutionThreshold, default 1 m/s):
//   circle of radius r around P (r = 0: a point) -> b2CircleShape {P, r}
//   line a -> b (free side on the left)          -> one-sided b2EdgeShape from b to a (Box2D's
//       edge normal points to the right of v1 -> v2), extended by 10 Model::scale beyond a and b
//       (mo2d's line is unbounded), and moved by b2_polygonRadius (1 cm: the skin Box2D puts
//       around every edge) into the obstacle, so that Box2D's shapes touch where mo2d's gap is 0
//   circle of radius R around a, from outside    -> b2CircleShape {a, R} (circles have no skin)
//   hole, compliant law, friction > 0            -> refused (docs/contact.md, "Box2D")
// Each contact's two fixtures collide with each other only (filter category and mask bit k), so
// the shapes of different contacts never meet. Box2D does not collide two bodies that a joint
// connects (b2JointDef::collideConnected false): such a contact is refused.
//
// A constant-speed drive: a user position constraint psi(x, t) = a x + b t + c on one extra
// coordinate x whose rate is one body's rotation rate (weight w), the body pivoted on the ground
// by a revolute joint (the cam follower's and the clearance slider-crank's `cam.angle - omega *
// t`): the joint's motor at the speed -b / (a w) with the limit max_motor_torque.
#include <cmath>

#include "box2d_world.hpp"
#include "contact/contact_set.hpp"
#include "mo2d/error.hpp"
#include "run/format.hpp"

namespace mo2d::crosscheck_detail {

namespace {

[[noreturn]] void refuse_contact(const ContactDef& c, const std::string& why) {
  throw Error("Box2D cross-check: contact '" + c.name + "': " + why, c.name);
}

bool joined(const Model& m, int b1, int b2) {
  for (const Constraint& c : m.constraints) {
    int x = -2, y = -2;
    if (const auto* r = std::get_if<Constraint::Revolute>(&c.def)) {
      x = r->body1;
      y = r->body2;
    } else if (const Constraint::Slider* s = c.slider()) {
      x = s->body1;
      y = s->body2;
    }
    if ((x == b1 && y == b2) || (x == b2 && y == b1)) return true;
  }
  return false;
}

b2FixtureDef fixture_def(const ContactDef& c, const b2Shape& shape, int bit,
                         const CrosscheckOptions& options) {
  b2FixtureDef f;
  f.shape = &shape;
  f.density = 0;  // keeps the mass data
  f.friction = 0;
  f.restitution = static_cast<float>(c.law.restitution);
  f.restitutionThreshold = static_cast<float>(options.restitution_threshold);
  f.filter.categoryBits = static_cast<uint16>(1u << bit);
  f.filter.maskBits = static_cast<uint16>(1u << bit);
  return f;
}

Vec2 vec_of(const b2Vec2& v) {
  return Vec2(v.x, v.y);
}

}  // namespace

void add_contact_shapes(const Model& m, Box2DWorld& w, const std::vector<ContactDef>& contacts,
                        const CrosscheckOptions& options) {
  if (contacts.size() > 16)
    refuse_contact(contacts[16], "more than 16 contacts (Box2D has 16 collision filter bits)");
  for (size_t k = 0; k < contacts.size(); ++k) {
    const ContactDef& c = contacts[k];
    const detail::CompiledContact cc = detail::compile_contact(m, c);
    if (c.law.kind != ContactLaw::Kind::rigid)
      refuse_contact(c,
                     "a compliant (Lankarani-Nikravesh) law has no Box2D equivalent (its contacts "
                     "are rigid, with restitution)");
    if (c.law.friction > 0)
      refuse_contact(c, "Coulomb friction (friction " + detail::fmt(c.law.friction, 3) +
                            "): the cross-check compares frictionless contacts only (Box2D's "
                            "friction is not compared with mo2d's yet)");
    if (c.target == ContactDef::Target::hole)
      refuse_contact(c,
                     "a pin in a hole: Box2D 2.4.1 has no hole shape, and its contacts rest up to "
                     "b2_linearSlop = 5 mm inside each other (clearance " +
                         detail::fmt(c.target_radius - c.radius, 3) +
                         " m): the ring of edges that would stand for the hole is not built "
                         "(docs/contact.md, \"Box2D\")");
    if (c.target == ContactDef::Target::slot)
      refuse_contact(c,
                     "a pin in a slot: its walls, closed end and lips (docs/contact.md, \"A pin "
                     "in a slot\") are not built as Box2D edges");
    if (c.target == ContactDef::Target::profile)
      refuse_contact(c, "a cam profile (table '" + c.profile->name() +
                            "'): it is not built as a Box2D shape (a b2ChainShape loop of its "
                            "spline would be a polygon, whose corners a knife-edge catches; "
                            "docs/contact.md, \"Cam profiles\")");
    const int other = cc.a.body;
    if (cc.p.body == other) refuse_contact(c, "its point and its target are on the same body");
    if (joined(m, cc.p.body, other))
      refuse_contact(c,
                     "its two bodies are connected by a joint, and Box2D does not collide "
                     "the bodies a joint connects");
    if (c.target == ContactDef::Target::line && cc.b.body != other)
      refuse_contact(c, "the line's two points are on different bodies");
    b2CircleShape circle;
    circle.m_p = local_point(m, w, cc.p);
    circle.m_radius = static_cast<float>(c.radius);
    b2Body* body_p = body_of(w, cc.p.body);
    b2Body* body_t = body_of(w, other);
    const int bit = static_cast<int>(k);
    const b2FixtureDef fp = fixture_def(c, circle, bit, options);
    body_p->CreateFixture(&fp);
    if (c.target == ContactDef::Target::circle) {
      b2CircleShape target;
      target.m_p = local_point(m, w, cc.a);
      target.m_radius = static_cast<float>(c.target_radius);
      const b2FixtureDef ft = fixture_def(c, target, bit, options);
      body_t->CreateFixture(&ft);
      continue;
    }
    // the line, in the target body's frame: from b to a (Box2D's normal on the right of v1 -> v2
    // is mo2d's on the left of a -> b), extended, and moved into the obstacle by the edge's skin
    const Vec2 a = vec_of(local_point(m, w, cc.a)), b = vec_of(local_point(m, w, cc.b));
    const Vec2 d = (b - a).normalized();
    const Vec2 n = perp(d);  // the free side's normal
    const double extend = 10 * m.scale;
    const Vec2 shift = -static_cast<double>(b2_polygonRadius) * n;
    const Vec2 v1 = b + extend * d + shift, v2 = a - extend * d + shift;
    b2EdgeShape edge;
    edge.SetOneSided(to_b2(v1 + (v1 - v2)), to_b2(v1), to_b2(v2), to_b2(v2 + (v2 - v1)));
    const b2FixtureDef fe = fixture_def(c, edge, bit, options);
    body_t->CreateFixture(&fe);
  }
}

int constant_speed_drive(const Model& m, const Constraint& c, double& speed) {
  const auto* u = std::get_if<Constraint::UserPosition>(&c.def);
  if (u == nullptr || u->args.size() != 1) return -1;
  const int x = u->args[0].var;
  // x must be an extra coordinate whose rate is one body's rotation rate
  int body = -1;
  double weight = 0;
  for (const Constraint& k : m.constraints) {
    const auto* co = std::get_if<Constraint::Coordinate>(&k.def);
    if (co == nullptr || co->coord != x || co->rate_terms.size() != 1) continue;
    for (size_t b = 0; b < m.bodies.size(); ++b)
      if (m.bodies[b].has_omega && m.bodies[b].omega.var == co->rate_terms[0].first.var) {
        body = static_cast<int>(b);
        weight = co->rate_terms[0].second;
      }
  }
  if (body < 0 || weight == 0) return -1;
  // psi linear in x and t with constant coefficients: its gradient and second derivatives at a
  // few points
  auto psi = [&](double xv, double tv, bool along_x) {
    const Jet arg = along_x ? Jet::variable(xv) : Jet(xv);
    const Jet t = along_x ? Jet(tv) : Jet::variable(tv);
    return u->psi(std::span<const Jet>(&arg, 1), t);
  };
  const Jet x0 = psi(0, 0, true), t0 = psi(0, 0, false);
  const double a = x0.d, b = t0.d;
  if (!(std::fabs(a) > 0)) return -1;
  for (const auto& [xv, tv] : {std::pair{1.0, 0.0}, {0.0, 1.0}, {-2.5, 3.7}}) {
    const Jet px = psi(xv, tv, true), pt = psi(xv, tv, false);
    const double linear = x0.v + a * xv + b * tv;
    const double tol = 1e-12 * (std::fabs(x0.v) + std::fabs(a * xv) + std::fabs(b * tv) + 1);
    if (std::fabs(px.v - linear) > tol || std::fabs(px.d - a) > tol * std::fabs(a) + 1e-300 ||
        std::fabs(pt.d - b) > tol || px.dd != 0 || pt.dd != 0)
      return -1;
  }
  // the body's revolute joint to the ground
  for (const Constraint& k : m.constraints) {
    const auto* r = std::get_if<Constraint::Revolute>(&k.def);
    if (r == nullptr) continue;
    if ((r->body1 < 0 && r->body2 == body) || (r->body2 < 0 && r->body1 == body)) {
      speed = -b / (a * weight);
      return body;
    }
  }
  return -1;
}

void drive_at_constant_speed(const Model& m, Box2DWorld& w, int body, double speed,
                             const CrosscheckOptions& options) {
  for (const JointMap& j : w.joints) {
    if (j.kind != JointKind::revolute) continue;
    const bool forward = j.body1 < 0 && j.body2 == body, reverse = j.body2 < 0 && j.body1 == body;
    if (!forward && !reverse) continue;
    auto* joint = static_cast<b2RevoluteJoint*>(j.joint);
    joint->EnableMotor(true);
    joint->SetMaxMotorTorque(static_cast<float>(options.max_motor_torque));
    joint->SetMotorSpeed(static_cast<float>(forward ? speed : -speed));
    return;
  }
  throw Error("Box2D cross-check: no revolute joint of body '" + m.bodies[body].name +
                  "' to the ground carries its drive",
              m.bodies[body].name);
}

}  // namespace mo2d::crosscheck_detail
