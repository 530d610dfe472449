// Translation of a mo2d Model (Reduction::none) into a Box2D 2.4.1 world; see box2d_world.hpp.
#include "box2d_world.hpp"

#include <cmath>
#include <numbers>

#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"

namespace mo2d::crosscheck_detail {

b2Vec2 to_b2(const Vec2& v) {
  return b2Vec2(static_cast<float>(v.x()), static_cast<float>(v.y()));
}

Vec2 perp(const Vec2& d) {
  return Vec2(-d.y(), d.x());
}

// A point given by local nodes i, j and (gamma, rho) (Example 2.6 (b)) on the geometry.
Vec2 geometry_point(const Body& b, int ci, int cj, double gamma, double rho) {
  Vec2 pi = b.geometry[ci];
  if (cj < 0) return pi;
  const Vec2 d = b.geometry[cj] - pi;
  return pi + gamma * d + rho * perp(d);
}

b2Body* body_of(const Box2DWorld& w, int body) {
  return body < 0 ? w.ground : w.bodies[body].body;
}

namespace {

Vec2 com_velocity(const Body& b, const Eigen::VectorXd& q1) {
  Vec2 vi = node_velocity(b.nodes[b.ci], q1);
  if (b.cj < 0) return vi;
  const Vec2 d = node_velocity(b.nodes[b.cj], q1) - vi;
  return vi + b.gamma * d + b.rho * perp(d);
}

// Local anchor (Box2D body frame) of a node; ground nodes are at their fixed world position.
b2Vec2 local_anchor(const Model& m, const Box2DWorld& w, const NodeRef& n) {
  if (n.body < 0) return to_b2(n.fixed);
  return to_b2(m.bodies[n.body].geometry[n.local] - w.bodies[n.body].com_geometry);
}

bool rotates(const Box2DWorld& w, int body) {
  return body >= 0 && w.bodies[body].rotates;
}

// Axis i -> j of body 1 in its Box2D frame (world axes of the geometry; ground: world).
b2Vec2 local_axis(const Model& m, const Constraint::Slider& c) {
  const Vec2 pi = c.i.body < 0 ? c.i.fixed : m.bodies[c.i.body].geometry[c.i.local];
  const Vec2 pj = c.j.body < 0 ? c.j.fixed : m.bodies[c.j.body].geometry[c.j.local];
  return to_b2((pj - pi).normalized());
}

[[noreturn]] void refuse(const std::string& what, const std::string& element);

void refuse(const std::string& what, const std::string& element) {
  throw Error("Box2D cross-check: " + what, element);
}

const Input* input_of(const Model& m, const std::string& joint, const std::string& suffix) {
  for (const Input& in : m.inputs)
    if (in.joint == joint && in.label == joint + suffix) return &in;
  return nullptr;
}

// A revolute joint (body 1 -> body 2) into j; from the proxy of body 1 when `on_proxy`.
void add_revolute_joint(const Model& m, Box2DWorld& w, const Constraint& c, bool motor,
                        bool on_proxy, const CrosscheckOptions& options, JointMap& j) {
  const auto& r = c.as<Constraint::Revolute>();
  j.body1 = r.body1;
  j.body2 = r.body2;
  if (on_proxy) add_carrier_proxy(w, r.body1);
  b2Body* A = on_proxy ? w.bodies[r.body1].proxy : body_of(w, r.body1);
  b2Body* B = body_of(w, r.body2);
  b2RevoluteJointDef def;
  def.bodyA = A;
  def.bodyB = B;
  def.localAnchorA = local_anchor(m, w, r.a);
  def.localAnchorB = local_anchor(m, w, r.b);
  def.referenceAngle = B->GetAngle() - A->GetAngle();
  j.kind = JointKind::revolute;
  j.motor = motor;
  def.enableMotor = motor;
  def.maxMotorTorque = static_cast<float>(options.max_motor_torque);
  j.joint = w.world->CreateJoint(&def);
}

// A prismatic joint or pin-in-slot into j: b2PrismaticJoint when mo2d locks the rotation, else a
// b2WheelJoint (a pin in a slot, no suspension spring).
void add_slider_joint(const Model& m, Box2DWorld& w, const Constraint& c, bool motors,
                      const CrosscheckOptions& options, JointMap& j) {
  const bool slot = c.kind() == ConstraintKind::slot;
  const Constraint::Slider& s = *c.slider();
  const auto* prismatic = std::get_if<Constraint::Prismatic>(&c.def);
  const bool locked = !slot && (prismatic->lock_position || prismatic->lock_velocity ||
                                (!rotates(w, s.body1) && !rotates(w, s.body2)));
  j.body1 = s.body1;
  j.body2 = s.body2;
  b2Body* A = body_of(w, s.body1);
  b2Body* B = body_of(w, s.body2);
  const bool drives_slide = input_of(m, c.name, ".force") != nullptr;
  const bool drives_rotation = input_of(m, c.name, ".torque") != nullptr;
  if (locked) {
    b2PrismaticJointDef def;
    def.bodyA = A;
    def.bodyB = B;
    def.localAnchorA = local_anchor(m, w, s.i);
    def.localAnchorB = local_anchor(m, w, s.s);
    def.localAxisA = local_axis(m, s);
    def.referenceAngle = B->GetAngle() - A->GetAngle();
    j.kind = JointKind::prismatic;
    j.motor = motors && drives_slide;
    j.linear_motor = true;
    def.enableMotor = j.motor;
    def.maxMotorForce = static_cast<float>(options.max_motor_force);
    j.joint = w.world->CreateJoint(&def);
  } else {
    if (drives_slide && motors)
      refuse(std::string(slot ? "pin-in-slot" : "prismatic") + " joint '" + c.name +
                 "': a driven slide with a free rotation (Box2D's wheel joint has only a "
                 "rotary motor)",
             c.name);
    b2WheelJointDef def;
    def.bodyA = A;
    def.bodyB = B;
    def.localAnchorA = local_anchor(m, w, s.i);
    def.localAnchorB = local_anchor(m, w, s.s);
    def.localAxisA = local_axis(m, s);
    def.stiffness = 0;  // a pin in a slot: no suspension spring
    def.damping = 0;
    j.kind = JointKind::wheel;
    j.motor = motors && drives_rotation;
    def.enableMotor = j.motor;
    def.maxMotorTorque = static_cast<float>(options.max_motor_torque);
    j.joint = w.world->CreateJoint(&def);
  }
}

// A spring reduced to a constraint (reduce: constraint) whose row is constraint ci: a rigid
// b2DistanceJoint (min = max = rest length). False if ci is not such a row.
bool add_rigid_spring(const Model& m, Box2DWorld& w, int ci) {
  for (const ReducedSpring& r : m.reduced_springs) {
    if (r.constraint != ci || r.held_length) continue;
    const SpringLoad& s = r.spring;
    b2DistanceJointDef def;
    def.bodyA = body_of(w, s.a.body);
    def.bodyB = body_of(w, s.b.body);
    def.localAnchorA = local_point(m, w, s.a);
    def.localAnchorB = local_point(m, w, s.b);
    def.length = def.minLength = def.maxLength = static_cast<float>(s.rest_length);
    w.world->CreateJoint(&def);
    return true;
  }
  return false;
}

}  // namespace

double wrap_angle(double a) {
  const double two_pi = 2 * std::numbers::pi;
  a = std::fmod(a + std::numbers::pi, two_pi);
  if (a < 0) a += two_pi;
  return a - std::numbers::pi;
}

double box2d_angle(const Model& m, const Box2DWorld& w, int body, const Eigen::VectorXd& q0) {
  if (body < 0 || !w.bodies[body].oriented) return 0.0;
  return wrap_angle(body_angle(m.bodies[body], q0) - w.bodies[body].alpha);
}

Model with_inertia_floor(const Model& m, double fraction, std::vector<std::string>& notes) {
  Model out = m;
  for (Body& b : out.bodies) {
    if (!b.has_omega || b.inertia > 0 || fraction <= 0) continue;
    const Vec2 c = geometry_point(b, b.ci, b.cj, b.gamma, b.rho);
    double r2 = 0;
    for (const Vec2& p : b.geometry) r2 = std::fmax(r2, (p - c).squaredNorm());
    b.inertia = fraction * b.mass * r2;
    notes.push_back("body '" + b.name + "': centroidal inertia 0 replaced by " +
                    std::to_string(b.inertia) + " kg m^2 in both engines");
  }
  return out;
}

Box2DWorld build_box2d_world(const Model& m, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1,
                             const CrosscheckOptions& options, bool motors) {
  if (m.reduction != Reduction::none)
    refuse("the translated Model must be built with Reduction::none (every joint a constraint)",
           m.name);
  for (const ReducedSpring& s : m.reduced_springs)  // before its user position constraint
    if (s.held_length)
      refuse("spring '" + s.spring.name +
                 "' reduced to its quasi-steady state (reduce: quasi_steady) is not translated "
                 "(Box2D has no joint whose length follows its multiplier)",
             s.spring.name);
  for (const ReducedTorsional& s : m.reduced_torsional)  // before its user position constraint
    refuse("torsional spring '" + s.spring.name +
               "' reduced to a constraint is not translated (Box2D 2.4.1's revolute joint has no "
               "angle lock to hold it)",
           s.spring.name);
  for (const ChainLoad& c : m.chains)
    refuse("chain '" + c.name +
               "' is not translated (Box2D has no chain or belt drive: its spans wrap the "
               "sprockets)",
           c.name);

  Box2DWorld w;
  w.world = std::make_unique<b2World>(to_b2(m.gravity));
  w.world->SetAllowSleeping(false);
  w.world->SetContinuousPhysics(false);
  b2BodyDef ground_def;  // static, at the origin
  w.ground = w.world->CreateBody(&ground_def);

  for (size_t k = 0; k < m.bodies.size(); ++k) {
    const Body& b = m.bodies[k];
    if (!(b.mass > 0))
      refuse("body '" + b.name + "' has no mass (Box2D gives a massless dynamic body 1 kg)",
             b.name);
    if (b.has_omega && !(b.inertia > 0))
      refuse("body '" + b.name +
                 "' rotates but has no centroidal inertia: Box2D cannot turn it (set "
                 "CrosscheckOptions::zero_inertia_fraction > 0, mo2d crosscheck "
                 "--point-mass-inertia, to substitute a small inertia in both engines)",
             b.name);
    BodyMap map;
    map.com_geometry = geometry_point(b, b.ci, b.cj, b.gamma, b.rho);
    map.rotates = b.has_omega;
    map.oriented = b.geometry.size() >= 2;
    if (map.oriented) {
      const Vec2 d = b.geometry[1] - b.geometry[0];
      map.alpha = std::atan2(d.y(), d.x());
    }
    // one node and a rotation (a disc): Box2D turns it from angle 0; its angle is not observable
    // in mo2d's coordinates, so the forward comparison skips it (its rate and loads act)
    w.bodies.push_back(map);

    b2BodyDef def;
    def.type = b2_dynamicBody;
    def.position = to_b2(com_position(b, q0));
    def.angle = static_cast<float>(box2d_angle(m, w, static_cast<int>(k), q0));
    def.linearVelocity = to_b2(com_velocity(b, q1));
    def.angularVelocity = static_cast<float>(omega_value(b.omega, q1));
    def.fixedRotation = !b.has_omega;
    def.allowSleep = false;
    b2Body* body = w.world->CreateBody(&def);
    b2MassData md;
    md.mass = static_cast<float>(b.mass);
    md.center.SetZero();  // the origin is the centre of mass, so I about the origin = I centroidal
    md.I = b.has_omega ? static_cast<float>(b.inertia) : 0.0f;
    body->SetMassData(&md);
    w.bodies.back().body = body;
  }

  const std::vector<char> on_proxy = revolutes_on_proxy(m);
  std::vector<int> gears;
  std::vector<std::pair<int, double>> drives;  // (body, rate) of the constant-speed drives
  for (size_t ci = 0; ci < m.constraints.size(); ++ci) {
    const Constraint& c = m.constraints[ci];
    JointMap j;
    j.name = c.name;
    j.constraint = static_cast<int>(ci);
    switch (c.kind()) {
      case ConstraintKind::rigid:
      case ConstraintKind::coordinate:  // an extra coordinate observes the motion only
        continue;
      case ConstraintKind::user_position: {
        if (add_rigid_spring(m, w, static_cast<int>(ci))) continue;
        double speed = 0;
        const int driven = constant_speed_drive(m, c, speed);
        if (driven >= 0) {  // after the joints: the motor of its revolute joint
          drives.emplace_back(driven, speed);
          continue;
        }
        refuse("user position constraint '" + c.name + "' has no Box2D equivalent", c.name);
        break;
      }
      case ConstraintKind::user_velocity:
        refuse("user velocity constraint '" + c.name + "' has no Box2D equivalent", c.name);
        break;
      case ConstraintKind::gear:  // after the revolute joints it couples (box2d_gears.cpp)
        gears.push_back(static_cast<int>(ci));
        continue;
      case ConstraintKind::revolute:
        add_revolute_joint(m, w, c, motors && input_of(m, c.name, ".torque") != nullptr,
                           on_proxy[ci] != 0, options, j);
        break;
      case ConstraintKind::prismatic:
      case ConstraintKind::slot:
        add_slider_joint(m, w, c, motors, options, j);
        break;
    }
    for (size_t r = 0; r < m.reactions.size(); ++r)
      if (m.reactions[r].label == c.name + ".Fx") j.reaction = static_cast<int>(r);
    w.joints.push_back(j);
  }
  for (int gi : gears) add_gear_joint(m, w, m.constraints[gi]);
  for (const auto& [body, speed] : drives) drive_at_constant_speed(m, w, body, speed, options);
  add_spring_joints(m, w);
  assign_friction_motors(m, w);
  w.q0 = q0;
  w.q1 = q1;
  w.reactions = Eigen::VectorXd::Zero(m.n_reactions());
  w.friction_values = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(m.frictions.size()));
  return w;
}

double joint_coordinate(const Model& m, const Box2DWorld& w, const JointMap& j,
                        const Eigen::VectorXd& q0) {
  if (j.linear_motor) return q0[m.constraints[j.constraint].as<Constraint::Prismatic>().q];
  return wrap_angle(box2d_angle(m, w, j.body2, q0) - box2d_angle(m, w, j.body1, q0));
}

double box2d_joint_coordinate(const JointMap& j) {
  switch (j.kind) {
    case JointKind::revolute:
      return static_cast<b2RevoluteJoint*>(j.joint)->GetJointAngle();
    case JointKind::prismatic:
      return static_cast<b2PrismaticJoint*>(j.joint)->GetJointTranslation();
    case JointKind::wheel:
      return static_cast<b2WheelJoint*>(j.joint)->GetJointAngle();
  }
  return 0;
}

void set_motor_speed(const JointMap& j, double speed) {
  const float s = static_cast<float>(speed);
  switch (j.kind) {
    case JointKind::revolute:
      static_cast<b2RevoluteJoint*>(j.joint)->SetMotorSpeed(s);
      break;
    case JointKind::prismatic:
      static_cast<b2PrismaticJoint*>(j.joint)->SetMotorSpeed(s);
      break;
    case JointKind::wheel:
      static_cast<b2WheelJoint*>(j.joint)->SetMotorSpeed(s);
      break;
  }
}

double motor_effort(const JointMap& j, double inv_dt) {
  const float f = static_cast<float>(inv_dt);
  switch (j.kind) {
    case JointKind::revolute:
      return static_cast<b2RevoluteJoint*>(j.joint)->GetMotorTorque(f);
    case JointKind::prismatic:
      return static_cast<b2PrismaticJoint*>(j.joint)->GetMotorForce(f);
    case JointKind::wheel:
      return static_cast<b2WheelJoint*>(j.joint)->GetMotorTorque(f);
  }
  return 0;
}

Vec2 reaction_force(const JointMap& j, double inv_dt) {
  const b2Vec2 F = j.joint->GetReactionForce(static_cast<float>(inv_dt));  // on body B
  return Vec2(F.x, F.y);
}

}  // namespace mo2d::crosscheck_detail
