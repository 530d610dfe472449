#pragma once
// The description of a mechanism as a user writes it: plain definition structs collected in a
// System. A System is one node of the tree of subsystems (Orsino, Theorem 2.10): it owns bodies,
// joints, extra coordinates and constraints, and may contain instances of other Systems, each with
// its own name and placement. Names are local to a System; a parent reaches into an instance with
// "instance.body.node". The ground (base body, Mo2DPack's body 0) is called "ground" everywhere.
//
// Sign conventions (all angles counter-clockwise, SI units):
//  - a revolute joint between node_a (body 1) and node_b (body 2): the actuator torque u acts on
//    body 2 and -u on body 1, so its power is u * (omega_2 - omega_1); the reaction (Fx, Fy) is the
//    force that body 1 exerts on body 2 at the joint;
//  - a prismatic joint / pin-in-slot: the axis is fixed in the body of axis_from/axis_to, the
//  slider
//    node belongs to body 2; the slider coordinate q is the signed distance of the slider node from
//    axis_from towards axis_to (eq. 5.31, corrected); the actuator force u pushes body 2 along
//    +axis (power u * q_dot); (Fx, Fy) is the force of the joint on body 2 at the slider node
//    (actuator included), T the torque of the rotation lock on body 2 (prismatic only).
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "mo2d/jet.hpp"
#include "mo2d/law.hpp"

namespace mo2d {

// A point or vector of the plane (m for a point).
using Vec2 = Eigen::Vector2d;

// A node: a named point of a body or of the ground.
struct NodeDef {
  // name, local to its body (or to the ground)
  std::string name{};
  // Coordinates in the initial configuration, in the System's own frame. For a body without a
  // shape (BodyDef::shape empty) and for a ground node they are exact: they define the body's
  // shape and its placement, and the copies of a joint node in two such bodies must coincide (and
  // a slider lie on its axis line) to BuildOptions::joint_tolerance, or build_model refuses the
  // joint. For a body given by its shape they are a sketch: approximate, moved by build_model to
  // where the joints close (see BodyDef::shape).
  Vec2 position{0, 0};
};

// Centre of mass: Example 2.6 (b) r(b*|b_i) = gamma r(b_j|b_i) + rho z x r(b_j|b_i), or a point
// (converted to gamma, rho on the body's first two nodes), or a node.
struct CenterOfMass {
  // how the centre of mass is given: at a node, between two nodes (gamma, rho) or at a point
  enum class Kind { node, nodes, point } kind = Kind::node;
  std::string node_i{}, node_j{};  // node names local to the body
  // Example 2.6 (b): the fraction gamma along node_i -> node_j and rho across it (dimensionless)
  double gamma = 0, rho = 0;
  // the point (m), in the System's frame (or the body's frame for a body given by its shape)
  Vec2 point{0, 0};
  // The centre of mass at node `node`.
  static CenterOfMass at_node(std::string node) {
    CenterOfMass c;
    c.kind = Kind::node;
    c.node_i = std::move(node);
    return c;
  }
  // The centre of mass at gamma (along) and rho (across) of node_i -> node_j (Example 2.6 (b)).
  static CenterOfMass between(std::string node_i, std::string node_j, double gamma,
                              double rho = 0) {
    CenterOfMass c;
    c.kind = Kind::nodes;
    c.node_i = std::move(node_i);
    c.node_j = std::move(node_j);
    c.gamma = gamma;
    c.rho = rho;
    return c;
  }
  // The centre of mass at point p (m).
  static CenterOfMass at_point(Vec2 p) {
    CenterOfMass c;
    c.kind = Kind::point;
    c.point = p;
    return c;
  }
};

// A rigid body (Orsino 2016 Example 2.6): its nodes, optional shape, mass, inertia and centre of
// mass.
struct BodyDef {
  // name, unique in its System
  std::string name{};
  // The body's nodes, with their positions in the System's frame: exact without a shape, a sketch
  // with one. One node: a point mass (with a rotation only if inertia > 0).
  std::vector<NodeDef> nodes{};
  // Geometry given by shape (optional): the coordinates of every node in the body's own frame,
  // one per node in the order of `nodes`; exact. A bar of length L: {{0, 0}, {L, 0}}; a point
  // mass: {{0, 0}}. Empty: the node positions are exact (they are the shape and the placement).
  // With a shape, the node positions are a sketch of where the body is: build_model places the
  // body rigidly (its shape unchanged) at the configuration where every joint closes that moves
  // the sketched nodes least (the sum of their squared displacements), holding the ground and
  // every body without a shape where they are written; the sketch therefore chooses the
  // assembly branch (elbow up or down). Model::sketch reports how far each node moved (and warns
  // above 10 % of the mechanism's size); lengths that cannot close a loop are refused naming the
  // joint left open, its gap and the loop. Points given on a body with a shape (a centre of mass
  // `point`, a force's `point`, a spring's `point_a`/`point_b`) are in this body frame too.
  std::vector<Vec2> shape{};
  double mass = 0;                    // kg, >= 0
  double inertia = 0;                 // kg m^2 about the centre of mass, >= 0
  std::optional<CenterOfMass> com{};  // default: the first node
};

// A revolute joint: node_a of body 1 and node_b of body 2 coincide (Orsino 2016 eq. 5.27);
// optionally actuated by a torque.
struct RevoluteDef {
  // name, unique in its System (prefix of its input and reaction labels)
  std::string name{};
  // the two joined nodes
  std::string node_a{},
      node_b{};           // "body.node" or "ground.node"; node_b's variables are eliminated
  bool actuated = false;  // adds the input "name.torque"
};

// A prismatic joint: the slider node of body 2 slides on the axis axis_from -> axis_to of body 1
// and the relative rotation is locked (Orsino 2016 eq. 5.30, 5.31 corrected); coordinate "name.q"
// (m).
struct PrismaticDef {
  // name, unique in its System
  std::string name{};
  std::string axis_from{}, axis_to{};  // two nodes of body 1 ("ground.node" allowed)
  std::string slider{};                // node of body 2
  bool actuated = false;               // adds the input "name.force"
};

// A pin-in-slot joint: the pin node of body 2 slides on the axis axis_from -> axis_to of body 1 and
// turns freely (eq. 5.31 corrected without the rotation lock); coordinate "name.q" (m).
struct PinInSlotDef {
  // name, unique in its System
  std::string name{};
  // two nodes of body 1, the slot's axis ("ground.node" allowed)
  std::string axis_from{}, axis_to{};
  // node of body 2 in the slot
  std::string pin{};
  bool actuated_slide = false;     // input "name.force"
  bool actuated_rotation = false;  // input "name.torque" (between the two bodies)
};

// Extra coordinate defined by its rate (Mo2DPack AddCoordinate): d/dt name = sum c_k * qv_k, over
// quasi-velocity labels such as "crank.w" (body rotation rate), "slide.v", "crank.A.vx".
// Rates of coordinates and body rotations with integer weights give an exact position invariant.
struct CoordinateDef {
  // name of the coordinate (its label)
  std::string name{};
  // (quasi-velocity label, weight c_k) pairs of its rate
  std::vector<std::pair<std::string, double>> rate{};
  std::optional<double> initial{};  // default: the value implied by the initial configuration
  // non-empty: an input of this label acting on the coordinate, the generalized force u times
  // each weight on its rate's terms (power u * d/dt name); e.g. a motor on a geared shaft
  std::string input{};
};

// User constraint at position level: psi(x, t) = 0, x = the coordinates named in args.
struct PositionConstraintDef {
  // name, unique in its System (label of its multiplier "name.lambda")
  std::string name{};
  std::vector<std::string> args{};  // coordinate labels ("crank.A.x", "slide.q", "crank.angle")
  // psi(x, t), in the unit of the constraint (evaluated on Jets: exact derivatives)
  std::function<Jet(std::span<const Jet> x, Jet t)> psi{};
};

// User constraint at velocity level, linear in the quasi-velocities: g(x, v, t) = 0 (a simple
// non-holonomic invariant, Orsino eq. 2.11: A q1 + b = 0 with A, b functions of q0 and t), e.g.
// rolling without slipping. Give the variables in one of two ways:
//  - coords + rates, and g(x, v, t) with x[k] = coords[k], v[k] = rates[k];
//  - labels (either kind, in any order), and g_labels(a, t) with a[k] the value of labels[k]:
//    build_model sorts each label into a coordinate or a quasi-velocity (the form scene files use).
// build_model refuses a g that is not linear in the rates at the initial configuration.
struct VelocityConstraintDef {
  // name, unique in its System (label of its multiplier "name.lambda")
  std::string name{};
  std::vector<std::string> coords{};  // coordinate labels the coefficients depend on
  std::vector<std::string> rates{};   // quasi-velocity labels it is linear in
  // g(x, v, t), linear in v (first form)
  std::function<Jet(std::span<const Jet> x, std::span<const Jet> v, Jet t)> g{};
  std::vector<std::string> labels{};  // coordinate and quasi-velocity labels, sorted by build_model
  // g_labels(a, t) (second form)
  std::function<Jet(std::span<const Jet> a, Jet t)> g_labels{};
};

// A gear pair (src/constraints/gear.hpp): the driving body `driver` (k) turns the driven body
// `body` (j), both carried by `carrier` (c, the housing; "ground" allowed), on carrier-relative
// rates:  omega_j - omega_c = ratio (omega_k - omega_c).  ratio = -z_k / z_j for two external
// spur gears of z_k and z_j teeth, +z_k / z_j for an internal (ring) gear. The bodies need two
// nodes each (their angles). Adds the coordinate "name.phi" (theta_k - theta_c, unwrapped), the
// reactions "name.torque" (the mesh torque on j; -ratio times it acts on k) and
// "name.carrier_torque" (the mesh torque on the carrier, -(1 - ratio) name.torque).
struct GearDef {
  // name, unique in its System
  std::string name{};
  std::string body{};             // driven body j
  std::string driver{};           // driving body k
  std::string carrier{"ground"};  // housing c
  double ratio = 1;               // rho, finite and non-zero
};

// A rack and pinion (src/constraints/gear.hpp): the slide coordinate q of a prismatic joint or
// pin-in-slot `slide` (its rack) follows the pinion's rotation relative to the slide's axis body
// c (the carrier):  q' = radius (omega_pinion - omega_c). radius is signed (the pitch radius,
// positive when a counter-clockwise pinion drives the rack along +q). Adds the coordinate
// "name.phi" (the pinion angle relative to c, unwrapped) and the reaction "name.force" (the
// force on the rack along the axis; -radius times it acts on the pinion).
struct RackDef {
  // name, unique in its System
  std::string name{};
  std::string slide{};   // a prismatic or pin-in-slot joint of this System
  std::string pinion{};  // body with two nodes
  double radius = 0;     // m, finite and non-zero
};

// A force applied at a point fixed in a body (given in the System's frame at the initial
// configuration) or a pure torque on a body. The components are laws (mo2d/law.hpp): functions of
// time, or of time and the state ("crank.theta", "crank.w"); the force's components are in the
// System's frame (rotated with its instance).
struct ForceDef {
  // name, unique in its System
  std::string name{};
  // the body the force acts on
  std::string body{};
  // the point of application (m), in the System's frame at the initial configuration
  Vec2 point{0, 0};
  Law fx{}, fy{};  // N; empty = 0
};
// A pure torque on a body (see ForceDef).
struct TorqueDef {
  // name, unique in its System
  std::string name{};
  // the body the torque acts on
  std::string body{};
  Law torque{};  // N m, counter-clockwise on the body; empty = 0
};

// Which sign of the tension a spring can carry: both (a spring), tension only (a chain, a cable,
// a rope: slack when the tension would push) or compression only (a bump stop: acts only while
// compressed below its rest length).
enum class SpringActs { both, tension_only, compression_only };

// How a spring is modelled (docs/reduction.md, "A stiff spring as a constraint"):
//  - none: the spring-damper as written;
//  - constraint: the k -> infinity limit. The spring is replaced by the holonomic constraint
//    |p_b - p_a| - rest_length = 0 (rest_length > 0; the initial configuration is assembled onto
//    it) whose multiplier is the tension T, reported as the reaction "name.tension". Its law,
//    stiffness and damping are not used by the dynamics (the fidelity report still reads them).
//    A unilateral spring stays bilateral: a tension of the wrong sign (a rope that would go
//    slack) is a run warning naming the time.
//  - quasi_steady: the quasi-steady-state model (Gamba 2009, 2.3): the same row (the multiplier
//    the tension T) but the length held is the spring's equilibrium length under T, the l at
//    which its own law at zero rate gives T (l = rest_length + T / k when linear, Newton on a
//    tension law), settled at every projection of forward runs and extrapolated linearly between
//    them (mo2d/quasi_steady.hpp). Needs stiffness > 0 or a tension law; forward runs with an
//    explicit integrator that projects only (dopri5, rk4, erk6, erk8). A Model with such springs
//    holds their current lengths: one forward run at a time per Model object.
// A torsional spring takes the same values (TorsionalSpringDef::reduce): its relative angle held
// at rest (constraint) or at the angle where its own law at zero rate gives the row's torque
// (quasi_steady), the torque on body 2 the reaction "name.torque".
enum class SpringReduce { none, constraint, quasi_steady };

// A spring-damper between two points fixed in bodies ("ground" allowed), given in the System's
// frame at the initial configuration. Its tension T pulls the points together when positive:
//  - linear: T = k (l - rest_length) + c dl/dt; its elastic energy is a potential;
//  - any law: T = tension(...), a Law that may read "length", "extension" (l - rest_length) and
//    "rate" (dl/dt) of this spring besides any state quantity; its work is counted as load work.
// `acts` clips T: tension_only gives max(T, 0), and a linear spring is slack (T = 0) while
// l < rest_length; compression_only gives min(T, 0), and a linear one acts only while
// l < rest_length (a bump stop).
struct SpringDef {
  // name, unique in its System
  std::string name{};
  // body of the first point ("ground" allowed)
  std::string body_a{};
  // first point (m), in the System's frame at the initial configuration
  Vec2 point_a{0, 0};
  // body of the second point ("ground" allowed)
  std::string body_b{};
  // second point (m), in the System's frame at the initial configuration
  Vec2 point_b{0, 0};
  double rest_length = 0;  // m (>= 0)
  double stiffness = 0;    // N/m (>= 0); with a tension law: must be 0
  double damping = 0;      // N s/m (>= 0); with a tension law: must be 0
  Law tension{};           // N; empty: the linear law above
  // which sign of tension it carries
  SpringActs acts = SpringActs::both;
  // as written, or reduced to a constraint
  SpringReduce reduce = SpringReduce::none;
};

// How a chain or belt drive is modelled (src/dynamics/chain.hpp, docs/reduction.md): each of
// its two spans a spring that only pulls (a chain, a belt: slack while shorter than its rest
// length), or a bilateral spring (also pushes: the upper- and lower-span models of Gamba 2009,
// §2.5), or inextensible: the taut span's material length held at its rest length by a holonomic
// constraint whose multiplier is its tension, the spans switching by the sign of the tension
// (slack in between; src/model/inextensible_chains.cpp, src/forward/chain_switching.cpp); or
// quasi_steady: the inextensible chain's rows and switching, the taut span's length held at
// rest + T / k (its spring law at zero rate under its tension T; mo2d/quasi_steady.hpp; needs
// stiffness > 0 and an explicit integrator that projects).
enum class ChainFidelity { unilateral, bilateral, inextensible, quasi_steady };

// A chain or belt drive between two sprockets (or pulleys): sprocket a of pitch radius radius_a
// centred at centre_a, fixed in body_a, and sprocket b likewise ("ground" allowed for either: a
// sprocket that does not turn); the centres may move (a sprocket on a swing arm). The open-belt
// geometry is exact: the two straight spans are the outer common tangents of the pitch circles,
// the "upper" span on the left of the line from centre a to centre b (above it when b is to the
// right of a), the "lower" span on the right. Each span's material length l (the chain between
// two marks on the sprockets, the wrapped arcs inextensible) is, with D = |c_b - c_a|,
// beta = direction of c_b - c_a, cos alpha = (r_a - r_b) / D, L = sqrt(D^2 - (r_a - r_b)^2):
//   l_upper = L + (r_b - r_a)(beta + alpha) + r_a theta_a - r_b theta_b + const
//   l_lower = L + (r_a - r_b)(beta - alpha) - r_a theta_a + r_b theta_b + const
// (const: l = L at the initial configuration), theta the bodies' unwrapped angles (the
// coordinates "name.theta_a", "name.theta_b" this element adds). Each span's tension
// T = k (l - rest) + c dl/dt acts at the material tangent points along the span (power
// -T dl/dt). A counter-clockwise turn of sprocket a tightens the upper span.
struct ChainDef {
  // name, unique in its System
  std::string name{};
  // body of sprocket a ("ground" allowed)
  std::string body_a{};
  Vec2 centre_a{0, 0};  // in the System's frame at the initial configuration
  double radius_a = 0;  // m, > 0 (pitch radius)
  // body of sprocket b ("ground" allowed)
  std::string body_b{};
  // in the System's frame at the initial configuration
  Vec2 centre_b{0, 0};
  double radius_b = 0;   // m, > 0; the pitch circles may not overlap (|c_b - c_a| > r_a + r_b)
  double stiffness = 0;  // N/m per span (> 0; inextensible: >= 0, read by the fidelity report only)
  double damping = 0;    // N s/m per span (>= 0; not used by inextensible)
  std::optional<double> rest_upper{}, rest_lower{};  // m (> 0); default: the initial span length
  // spans that only pull, or bilateral springs
  ChainFidelity fidelity = ChainFidelity::unilateral;
};

// A torsional spring-damper at a revolute joint: torque -k (theta - rest) - c (w2 - w1) on body 2
// and the opposite on body 1, theta = relative angle of the bodies (measured within +-pi of rest);
// or any law: torque = torque(...), a Law that may read "angle" (theta - rest, within +-pi) and
// "rate" (w2 - w1) besides any state quantity (its work is counted as load work).
struct TorsionalSpringDef {
  // name, unique in its System
  std::string name{};
  std::string joint{};           // a revolute joint of this System
  double stiffness = 0;          // N m / rad; with a torque law: must be 0
  double damping = 0;            // N m s / rad; with a torque law: must be 0
  std::optional<double> rest{};  // rad; default: the relative angle at the initial configuration
  Law torque{};                  // N m on body 2 (and -torque on body 1); empty: the linear law
  // as written, or reduced to a constraint (SpringReduce: rest angle, or quasi-steady angle)
  SpringReduce reduce = SpringReduce::none;
};

// Friction in a joint (src/dynamics/friction.hpp): a generalized force along the joint's own
// motion that opposes its relative rate v (a prismatic joint or pin-in-slot: the slide rate
// "joint.q" rate, a force on the slider and the opposite on the axis body; a revolute joint: the
// relative rate w2 - w1, a torque on body 2 and the opposite on body 1):
//   F = -viscous v - mu N sgn(v),
// N the normal force from the joint's reaction (a slide: the reaction's component normal to the
// axis, the lock torque left out; a revolute: radius * |reaction|, the pin's friction arm).
// Inverse dynamics: sgn(v) = sign(v) (0 at v = 0) and the reaction and the friction solved
// together by a fixed-point iteration per sample (Orsino Example 4.5). Forward dynamics:
// sgn(v) = tanh(v / regularization), iterated with the reaction at the current accelerations.
struct FrictionDef {
  // name, unique in its System
  std::string name{};
  std::string joint{};           // a revolute, prismatic or pin-in-slot joint of this System
  double viscous = 0;            // N s / m (slide) or N m s / rad (revolute)
  double mu = 0;                 // Coulomb coefficient (>= 0)
  double radius = 0;             // m, revolute only: friction torque mu * radius * |reaction|
  double regularization = 1e-3;  // v_s (m/s or rad/s) of tanh(v / v_s) in forward dynamics
};

// A named point fixed in a body ("ground" allowed), given in the System's frame at the initial
// configuration: its position and velocity are quantities laws may read ("name.x", "name.vy")
// and outputs of every run.
struct PointDef {
  // name, unique in its System (prefix of its quantities "name.x", "name.vy", ...)
  std::string name{};
  // the body it is fixed in ("ground" allowed)
  std::string body{};
  // the point (m), in the System's frame at the initial configuration
  Vec2 point{0, 0};
};

// Where an instance of a subsystem goes in its parent: rotated by `angle`, then shifted by
// `offset`.
struct Placement {
  // shift (m)
  Vec2 offset{0, 0};
  double angle = 0;  // rad, applied before the offset
  // The point p of the subsystem's frame in the parent's frame (m).
  Vec2 apply(const Vec2& p) const;
  // An angle a of the subsystem's frame in the parent's frame (rad).
  double rotate_angle(double a) const { return a + angle; }
};

class System;

// A subsystem placed in a System (Orsino 2016 Theorem 2.10, the tree of subsystems).
struct Instance {
  // the instance's name (prefix of its labels: "name.body.node")
  std::string name{};
  // the subsystem, shared between its instances
  std::shared_ptr<const System> system{};
  // where it goes
  Placement placement{};
};

// A mechanism or a subsystem as written (see the file's description): definitions added one by one,
// then compiled by build_model().
class System {
 public:
  // An empty System named `name` (the root of a mechanism: "root").
  explicit System(std::string name = "root") : name_(std::move(name)) {}

  // Adds a ground node, body, joint, coordinate, gear, rack, constraint, load, spring, chain, named
  // point, friction or subsystem instance (its Def struct describes it) and returns *this;
  // build_model checks names and references. set_gravity: the gravity vector (m/s^2), default (0,
  // 0): none.
  System& add_ground_node(std::string name, Vec2 position);
  System& add_body(BodyDef body);
  System& add_revolute(RevoluteDef joint);
  System& add_prismatic(PrismaticDef joint);
  System& add_pin_in_slot(PinInSlotDef joint);
  System& add_coordinate(CoordinateDef coordinate);
  System& add_gear(GearDef gear);
  System& add_rack(RackDef rack);
  System& add_constraint(PositionConstraintDef constraint);
  System& add_constraint(VelocityConstraintDef constraint);
  System& add_force(ForceDef force);
  System& add_torque(TorqueDef torque);
  System& add_spring(SpringDef spring);
  System& add_torsional_spring(TorsionalSpringDef spring);
  System& add_chain(ChainDef chain);
  System& add_point(PointDef point);
  System& add_friction(FrictionDef friction);
  System& add_instance(std::string name, const System& sub, Placement placement = {});
  System& set_gravity(Vec2 g);

  // The System's name and its definitions, in the order added.
  const std::string& name() const { return name_; }
  const std::vector<NodeDef>& ground() const { return ground_; }
  const std::vector<BodyDef>& bodies() const { return bodies_; }
  // The body `name` of this System (not of an instance) to change its definition, as
  // add_transmission does; nullptr if there is none.
  BodyDef* find_body(const std::string& name);
  const std::vector<RevoluteDef>& revolutes() const { return revolutes_; }
  const std::vector<PrismaticDef>& prismatics() const { return prismatics_; }
  const std::vector<PinInSlotDef>& slots() const { return slots_; }
  const std::vector<CoordinateDef>& coordinates() const { return coordinates_; }
  const std::vector<GearDef>& gears() const { return gears_; }
  const std::vector<RackDef>& racks() const { return racks_; }
  const std::vector<PositionConstraintDef>& position_constraints() const { return pos_; }
  const std::vector<VelocityConstraintDef>& velocity_constraints() const { return vel_; }
  const std::vector<ForceDef>& forces() const { return forces_; }
  const std::vector<TorqueDef>& torques() const { return torques_; }
  const std::vector<SpringDef>& springs() const { return springs_; }
  const std::vector<TorsionalSpringDef>& torsional_springs() const { return torsional_; }
  const std::vector<ChainDef>& chains() const { return chains_; }
  const std::vector<PointDef>& points() const { return points_; }
  const std::vector<FrictionDef>& frictions() const { return frictions_; }
  const std::vector<Instance>& instances() const { return instances_; }
  const Vec2& gravity() const { return gravity_; }

 private:
  std::string name_;
  std::vector<NodeDef> ground_;
  std::vector<BodyDef> bodies_;
  std::vector<RevoluteDef> revolutes_;
  std::vector<PrismaticDef> prismatics_;
  std::vector<PinInSlotDef> slots_;
  std::vector<CoordinateDef> coordinates_;
  std::vector<GearDef> gears_;
  std::vector<RackDef> racks_;
  std::vector<PositionConstraintDef> pos_;
  std::vector<VelocityConstraintDef> vel_;
  std::vector<ForceDef> forces_;
  std::vector<TorqueDef> torques_;
  std::vector<SpringDef> springs_;
  std::vector<TorsionalSpringDef> torsional_;
  std::vector<ChainDef> chains_;
  std::vector<PointDef> points_;
  std::vector<FrictionDef> frictions_;
  std::vector<Instance> instances_;
  Vec2 gravity_{0, 0};
};

}  // namespace mo2d
