// The Model's loads in the Box2D world; see box2d_world.hpp.
//
// What both engines share: the code that turns a state into a load value (point_force,
// torque_value, spring_value, torsional_value, friction_forces and friction_normal, law_value:
// src/dynamics/, src/model/). What stays independent: the state those functions read. Here it is
// Box2D's own, read back from its bodies every step (read_box2d_state), never mo2d's trajectory,
// so a law evaluated in the wrong frame or at the wrong point, or a spring on the wrong node,
// gives Box2D a different motion (or motor effort) from mo2d's.
//
// Translation of the loads:
//   linear bilateral spring-damper with k > 0  -> b2DistanceJoint {length = rest length,
//                                                 stiffness = k N/m, damping = c N s/m}: Box2D
//                                                 integrates it (its soft constraint)
//   spring with a law, unilateral, or k = 0    -> the tension T of spring_value on Box2D's state,
//     (a damper)                                  a force pair +-T e at its two points
//   torsional spring (linear or law)           -> torsional_value: +tau on body 2, -tau on body 1
//   force / torque (of time or of the state)   -> ApplyForce at the body point / ApplyTorque
//   input effort (forward: efforts, PD controllers)
//                                              -> law_value, applied along the input's column
//   joint friction in a free revolute or prismatic joint
//                                              -> the joint's motor: speed 0, max torque (force)
//                                                 = viscous |v| + mu N, N from Box2D's reaction
//                                                 of the last step (Box2D's friction idiom)
//   joint friction elsewhere (a driven joint, a pin-in-slot)
//                                              -> friction_forces on Box2D's state and reactions,
//                                                 applied along the friction's column
#include <cmath>
#include <numbers>

#include "box2d_world.hpp"
#include "dynamics/friction.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"

namespace mo2d::crosscheck_detail {

namespace {

Vec2 from_b2(const b2Vec2& v) {
  return Vec2(v.x, v.y);
}

// World position of a BodyPoint on Box2D's bodies.
Vec2 world_point(const Model& m, const Box2DWorld& w, const BodyPoint& p) {
  if (p.body < 0) return p.fixed;
  return from_b2(body_of(w, p.body)->GetWorldPoint(local_point(m, w, p)));
}

void force_at(const Box2DWorld& w, int body, const Vec2& F, const Vec2& at) {
  if (body < 0) return;
  w.bodies[body].body->ApplyForce(to_b2(F), to_b2(at), false);
}

void torque_on(const Box2DWorld& w, int body, double tau) {
  if (body < 0) return;
  w.bodies[body].body->ApplyTorque(static_cast<float>(tau), false);
}

// The slide whose coordinate is q0[var] (-1: none).
int slider_of(const Model& m, int var) {
  for (size_t c = 0; c < m.constraints.size(); ++c)
    if (const Constraint::Slider* s = m.constraints[c].slider(); s && s->q == var)
      return static_cast<int>(c);
  return -1;
}

// A generalized force F along one term of a column (an input's, a friction's): a body slot (a
// node's x or y: a force at the node; the rotation: a torque) or a slide coordinate (an axial
// force pair at the slider node).
void apply_generalized(const Model& m, const Box2DWorld& w, const VarRef& ref, double F,
                       const std::string& element) {
  if (ref.body >= 0) {
    const Body& b = m.bodies[ref.body];
    const int n = static_cast<int>(b.geometry.size());
    if (ref.slot == 2 * n) {
      torque_on(w, ref.body, F);
      return;
    }
    const int k = ref.slot / 2;
    const Vec2 at = node_position(b.nodes[k], w.q0);
    force_at(w, ref.body, ref.slot % 2 == 0 ? Vec2(F, 0) : Vec2(0, F), at);
    return;
  }
  if (ref.var < 0) return;
  const int c = slider_of(m, ref.var);
  if (c < 0)
    throw Error("Box2D cross-check: '" + element + "' acts on variable '" + m.rate_labels[ref.var] +
                    "', which has no Box2D counterpart",
                element);
  const Constraint::Slider& s = *m.constraints[c].slider();
  const Vec2 d = node_position(s.j, w.q0) - node_position(s.i, w.q0);
  const Vec2 e = d / d.norm();
  const Vec2 at = node_position(s.s, w.q0);
  force_at(w, s.body2, F * e, at);
  force_at(w, s.body1, -F * e, at);
}

double unwrap_near(double a, double previous) {
  const double two_pi = 2 * std::numbers::pi;
  return a + two_pi * std::round((previous - a) / two_pi);
}

}  // namespace

b2Vec2 local_point(const Model& m, const Box2DWorld& w, const BodyPoint& p) {
  if (p.body < 0) return to_b2(p.fixed);
  const Body& b = m.bodies[p.body];
  return to_b2(geometry_point(b, p.ci, p.cj, p.gamma, p.rho) - w.bodies[p.body].com_geometry);
}

void read_box2d_state(const Model& m, Box2DWorld& w, double h) {
  for (size_t k = 0; k < m.bodies.size(); ++k) {
    const Body& b = m.bodies[k];
    const b2Body* body = w.bodies[k].body;
    for (size_t n = 0; n < b.nodes.size(); ++n) {
      const NodeRef& node = b.nodes[n];
      if (node.var < 0) continue;
      const b2Vec2 local = to_b2(b.geometry[n] - w.bodies[k].com_geometry);
      const b2Vec2 p = body->GetWorldPoint(local);
      const b2Vec2 v = body->GetLinearVelocityFromLocalPoint(local);
      w.q0[node.var] = p.x;
      w.q0[node.var + 1] = p.y;
      w.q1[node.var] = v.x;
      w.q1[node.var + 1] = v.y;
    }
    if (b.omega.var >= 0) w.q1[b.omega.var] = body->GetAngularVelocity();
  }
  for (const Constraint& c : m.constraints) {
    if (const Constraint::Slider* s = c.slider()) {
      const Vec2 pi = node_position(s->i, w.q0), pj = node_position(s->j, w.q0);
      const Vec2 d = pj - pi, r = node_position(s->s, w.q0) - pi;
      const Vec2 vd = node_velocity(s->j, w.q1) - node_velocity(s->i, w.q1);
      const Vec2 vr = node_velocity(s->s, w.q1) - node_velocity(s->i, w.q1);
      w.q0[s->q] = r.dot(d) / s->length;
      w.q1[s->q] = (vr.dot(d) + r.dot(vd)) / s->length;
    } else if (const auto* cd = std::get_if<Constraint::Coordinate>(&c.def)) {
      double rate = 0;
      for (const auto& [ref, weight] : cd->rate_terms)
        if (ref.var >= 0) rate += weight * w.q1[ref.var];
      w.q1[cd->coord] = rate;
      if (!cd->holonomic) {  // only its rate is defined: integrate it over the last step
        w.q0[cd->coord] += h * rate;
        continue;
      }
      double value = cd->offset;
      for (const auto& [var, weight] : cd->coord_terms) value += weight * w.q0[var];
      for (const auto& [body, weight] : cd->angle_terms)
        if (body >= 0) value += weight * body_angle(m.bodies[body], w.q0);
      w.q0[cd->coord] = cd->angle_terms.empty() ? value : unwrap_near(value, w.q0[cd->coord]);
    }
  }
  for (const JointMap& j : w.joints) {
    if (j.reaction < 0) continue;
    const b2Vec2 F = j.joint->GetReactionForce(static_cast<float>(w.last_inv_dt));
    w.reactions[j.reaction] = F.x;
    w.reactions[j.reaction + 1] = F.y;
  }
}

void add_spring_joints(const Model& m, Box2DWorld& w) {
  w.spring_joints.assign(m.springs.size(), nullptr);
  for (size_t k = 0; k < m.springs.size(); ++k) {
    const SpringLoad& s = m.springs[k];
    // b2DistanceJoint clamps its lengths to b2_linearSlop and is a spring only for k > 0 (with
    // k = 0 its damping is not applied); a law or a unilateral spring has no joint form
    if (s.tension || s.acts != SpringActs::both || !(s.stiffness > 0) ||
        !(s.rest_length > 10 * b2_linearSlop) || s.a.body == s.b.body)
      continue;
    b2DistanceJointDef def;
    def.bodyA = body_of(w, s.a.body);
    def.bodyB = body_of(w, s.b.body);
    def.localAnchorA = local_point(m, w, s.a);
    def.localAnchorB = local_point(m, w, s.b);
    def.length = static_cast<float>(s.rest_length);
    def.minLength = 0;  // no stops: the spring alone
    def.maxLength = FLT_MAX;
    def.stiffness = static_cast<float>(s.stiffness);
    def.damping = static_cast<float>(s.damping);
    def.collideConnected = false;
    w.spring_joints[k] = static_cast<b2DistanceJoint*>(w.world->CreateJoint(&def));
  }
}

void assign_friction_motors(const Model& m, Box2DWorld& w) {
  for (size_t k = 0; k < m.frictions.size(); ++k)
    for (JointMap& j : w.joints) {
      if (j.name != m.frictions[k].joint || j.motor || j.friction >= 0) continue;
      if (j.kind == JointKind::revolute) {
        auto* r = static_cast<b2RevoluteJoint*>(j.joint);
        r->EnableMotor(true);
        r->SetMotorSpeed(0);
        r->SetMaxMotorTorque(0);
        j.friction = static_cast<int>(k);
      } else if (j.kind == JointKind::prismatic && m.frictions[k].slider >= 0) {
        auto* p = static_cast<b2PrismaticJoint*>(j.joint);
        p->EnableMotor(true);
        p->SetMotorSpeed(0);
        p->SetMaxMotorForce(0);
        j.friction = static_cast<int>(k);
      }
    }
}

void apply_loads(const Model& m, Box2DWorld& w, double t, double h) {
  read_box2d_state(m, w, h);
  const Eigen::VectorXd& q0 = w.q0;
  const Eigen::VectorXd& q1 = w.q1;
  for (const PointLoad& f : m.forces) {
    if (f.body < 0) continue;
    const BodyPoint p{.body = f.body, .ci = f.ci, .cj = f.cj, .gamma = f.gamma, .rho = f.rho};
    force_at(w, f.body, point_force(m, f, q0, q1, t), world_point(m, w, p));
  }
  for (const TorqueLoad& tl : m.torques)
    if (tl.body >= 0 && tl.torque) torque_on(w, tl.body, torque_value(m, tl, q0, q1, t));
  for (size_t k = 0; k < m.springs.size(); ++k) {
    if (w.spring_joints[k]) continue;  // Box2D's distance joint
    const SpringLoad& s = m.springs[k];
    const SpringValue v = spring_value(m, s, q0, q1, t);
    const Vec2 pa = world_point(m, w, s.a), pb = world_point(m, w, s.b);
    const double l = (pb - pa).norm();
    if (!(l > 0)) continue;  // no direction: mo2d's spring_value has none either
    const Vec2 e = (pb - pa) / l;
    force_at(w, s.a.body, v.tension * e, pa);
    force_at(w, s.b.body, -v.tension * e, pb);
  }
  for (const TorsionalLoad& s : m.torsional_springs) {
    const double tau = torsional_value(m, s, q0, q1, t).torque;
    torque_on(w, s.body2, tau);
    torque_on(w, s.body1, -tau);
  }
  for (size_t k = 0; k < w.efforts.size() && k < m.inputs.size(); ++k) {
    if (!w.efforts[k]) continue;
    const Input& in = m.inputs[k];
    const double u = law_value(m, w.efforts[k], q0, q1, t, "effort", in.label);
    for (const auto& [ref, coef] : in.terms) apply_generalized(m, w, ref, coef * u, in.label);
  }
  if (m.frictions.empty()) return;
  friction_forces(m, q0, q1, w.reactions, w.regularized_friction, w.friction_values);
  std::vector<char> on_motor(m.frictions.size(), 0);
  for (const JointMap& j : w.joints) {
    if (j.friction < 0) continue;
    const FrictionLoad& f = m.frictions[j.friction];
    const double v = detail::friction_rate(f, q1);
    const double N = f.mu != 0 ? detail::friction_normal(m, f, q0, w.reactions) : 0.0;
    const auto limit = static_cast<float>(f.viscous * std::fabs(v) + f.mu * N);
    if (j.kind == JointKind::revolute)
      static_cast<b2RevoluteJoint*>(j.joint)->SetMaxMotorTorque(limit);
    else
      static_cast<b2PrismaticJoint*>(j.joint)->SetMaxMotorForce(limit);
    on_motor[j.friction] = 1;
  }
  for (size_t k = 0; k < m.frictions.size(); ++k) {
    if (on_motor[k]) continue;
    const double F = w.friction_values[static_cast<int>(k)];
    for (const auto& [ref, coef] : m.frictions[k].terms)
      apply_generalized(m, w, ref, coef * F, m.frictions[k].name);
  }
  w.last_inv_dt = 1.0 / h;
}

}  // namespace mo2d::crosscheck_detail
