#pragma once
// Private to mo2d_box2d: a Box2D 2.4.1 world built from a mo2d Model, with the map back to the
// Model's bodies and joints.
//
// Frames: body b's Box2D origin is its centre of mass; its local axes are the world axes of the
// Model's geometry (the shape as defined), so a node's local position is geometry - com(geometry)
// and the Box2D angle phi is the rotation since that definition: phi = body_angle(q0) - alpha_b,
// alpha_b = angle of node 1 seen from node 0 in the geometry.
#include <box2d/box2d.h>

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "mo2d/contact.hpp"
#include "mo2d/crosscheck.hpp"
#include "mo2d/model.hpp"

namespace mo2d::crosscheck_detail {

struct BodyMap {
  b2Body* body = nullptr;
  Vec2 com_geometry{0, 0};  // centre of mass in the geometry (world, as defined)
  double alpha = 0;         // geometry angle of node 1 seen from node 0 (0 for one node)
  bool rotates = false;     // has a rotation in mo2d (and in Box2D)
  bool oriented = false;    // has >= 2 nodes, so its angle is observable from q0
  // A carrier of gear pairs: the second half of the body, welded to `body` (box2d_gears.cpp).
  b2Body* proxy = nullptr;
};

enum class JointKind { revolute, prismatic, wheel };

struct JointMap {
  std::string name{};
  JointKind kind = JointKind::revolute;
  b2Joint* joint = nullptr;
  int constraint = -1;  // index in Model::constraints
  int body1 = -1, body2 = -1;
  bool motor = false;         // driven (an input of the Model)
  bool linear_motor = false;  // motor drives the slider coordinate (prismatic) or the rotation
  int reaction = -1;          // column of "name.Fx" in Model::reactions (-1: none)
  // Model::frictions index whose Coulomb and viscous parts this joint's motor carries (Box2D's
  // friction idiom: motor speed 0, limit = the friction's magnitude; -1: none)
  int friction = -1;
};

struct Box2DWorld {
  std::unique_ptr<b2World> world{};
  b2Body* ground = nullptr;
  std::vector<BodyMap> bodies{};  // one per Model body
  std::vector<JointMap> joints{};
  // Per Model::springs: the b2DistanceJoint that is the spring (linear, bilateral, k > 0), or
  // null when the spring's tension is applied as a force pair each step (box2d_loads.cpp).
  std::vector<b2DistanceJoint*> spring_joints{};
  // Per Model::inputs, forward: the effort laws applied each step (empty: no effort).
  std::vector<CompiledLaw> efforts{};
  // Frictions: tanh-regularized (forward, as mo2d integrates them) or sign (inverse).
  bool regularized_friction = false;
  // Box2D's own state in mo2d's variables (read_box2d_state), the joint reactions of Box2D's
  // last step in Model::reactions order (0 before the first step), and scratch.
  Eigen::VectorXd q0{}, q1{}, reactions{}, friction_values{};
  double last_inv_dt = 0;
};

// Refuses (Error naming the element) what Box2D cannot represent. The Model must be built with
// Reduction::none. Bodies are placed at (q0, q1). Without `motors` the driven joints are free
// (forward dynamics with zero efforts).
Box2DWorld build_box2d_world(const Model& m, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1,
                             const CrosscheckOptions& options, bool motors);

// Box2D's angle of body b for mo2d coordinates q0 (0 for a body that does not rotate), wrapped to
// (-pi, pi].
double box2d_angle(const Model& m, const Box2DWorld& w, int body, const Eigen::VectorXd& q0);

// The coordinate a joint's motor drives, from mo2d's q0: relative angle phi2 - phi1 (wrapped) or
// the slider coordinate; and the same read from Box2D (unwrapped for angles).
double joint_coordinate(const Model& m, const Box2DWorld& w, const JointMap& j,
                        const Eigen::VectorXd& q0);
double box2d_joint_coordinate(const JointMap& j);

// Set the motor speed / read the motor effort (N m or N) and the reaction force on body 2 (N).
void set_motor_speed(const JointMap& j, double speed);
double motor_effort(const JointMap& j, double inv_dt);
Vec2 reaction_force(const JointMap& j, double inv_dt);

// Small conversions shared by the world's builder and the loads (box2d_world.cpp): a Vec2 as
// Box2D's float vector; d turned by +90 degrees; the point (nodes ci, cj, gamma, rho; Example 2.6
// (b)) on a body's geometry; the Box2D body of a mo2d body (the ground for body < 0).
b2Vec2 to_b2(const Vec2& v);
Vec2 perp(const Vec2& d);
Vec2 geometry_point(const Body& b, int ci, int cj, double gamma, double rho);
b2Body* body_of(const Box2DWorld& w, int body);

// Loads applied each Box2D step (box2d_loads.cpp): mo2d's load code (point_force, torque_value,
// spring_value, torsional_value, friction_forces, law_value) evaluated on Box2D's own state read
// back by read_box2d_state, applied with ApplyForce / ApplyTorque (Box2D clears them after each
// step); the friction motors' limits set from Box2D's last reactions. h: the step about to run.
void apply_loads(const Model& m, Box2DWorld& w, double t, double h);
// Box2D's state as mo2d coordinates: w.q0, w.q1 (node positions and velocities from the bodies,
// rotation rates, slider coordinates, extra coordinates unwrapped from their last value) and
// w.reactions from the joints' reaction forces of the last step.
void read_box2d_state(const Model& m, Box2DWorld& w, double h);
// The Box2D local point (body frame) of a BodyPoint; ground: the world point.
b2Vec2 local_point(const Model& m, const Box2DWorld& w, const BodyPoint& p);
// Springs as distance joints (the linear bilateral ones with k > 0), after the bodies.
void add_spring_joints(const Model& m, Box2DWorld& w);
// Joint frictions carried by the motors of free revolute and prismatic joints.
void assign_friction_motors(const Model& m, Box2DWorld& w);

// Contacts (box2d_contacts.cpp): each contact's two shapes as fixtures of its two bodies
// (restitution e, friction 0, restitution_threshold); an Error naming a contact Box2D cannot
// represent (a hole, a compliant law, two bodies a joint connects).
void add_contact_shapes(const Model& m, Box2DWorld& w, const std::vector<ContactDef>& contacts,
                        const CrosscheckOptions& options);
// A constant-speed drive: user position constraint c is psi = a x + b t + const on an extra
// coordinate x that integrates one body's rotation rate, the body pivoted on the ground. Returns
// the body and its rate in `speed` (rad/s), -1 if c is not such a drive.
int constant_speed_drive(const Model& m, const Constraint& c, double& speed);
// The motor of `body`'s revolute joint to the ground at `speed` (the body's rate).
void drive_at_constant_speed(const Model& m, Box2DWorld& w, int body, double speed,
                             const CrosscheckOptions& options);

// Model with every rotating zero-inertia body given I = fraction m r^2; notes what it changed.
Model with_inertia_floor(const Model& m, double fraction, std::vector<std::string>& notes);

double wrap_angle(double a);

// Gear pairs (box2d_gears.cpp). The driver k of a gear pair (-1: none found).
int gear_driver(const Model& m, const Constraint::Gear& g);
// Per constraint: 1 for the revolute joints that must start on their carrier's proxy, so that no
// gear joint has both its joints on the same moving body (Box2D 2.4.1's gear joint loses the
// carrier's share of the impulse then).
std::vector<char> revolutes_on_proxy(const Model& m);
// Split the carrier's Box2D body into two welded halves (idempotent).
void add_carrier_proxy(Box2DWorld& w, int carrier);
// The gear pair c as a b2GearJoint between its two revolute joints (created before).
void add_gear_joint(const Model& m, Box2DWorld& w, const Constraint& c);

}  // namespace mo2d::crosscheck_detail
