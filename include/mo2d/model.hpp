#pragma once
// Model: the constant, compiled description of a mechanism (Pinocchio's Model): variables with
// labels, bodies with their constant mass data, constraints, inputs, loads and the subsystem tree.
// It is built once from a System by build_model() and never written by an algorithm.
//
// Variables (Orsino §5.3): q0 = node coordinates (two per independent node), slider coordinates,
// extra coordinates. q1 = the rates of q0 in the same order (so d/dt q0 = q1.head(n0), the
// kinematic map Z = [I 0] is constant), followed by one rotation rate per independent body
// rotation. Revolute joints eliminate the slave node's variables (eq. 5.27); prismatic joints
// eliminate the slave body's rotation rate (eq. 5.30).
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <variant>
#include <vector>

#include "mo2d/budget.hpp"
#include "mo2d/jet.hpp"
#include "mo2d/system.hpp"

namespace mo2d {

// Which revolute/prismatic joints are reduced by variable elimination.
enum class Reduction {
  flat,        // all of them (Mo2DPack's VariableReduction on the flattened mechanism)
  subsystems,  // only joints inside one subsystem; joints between subsystems are constraint rows
  none,        // none: every joint is a constraint row (the Lagrange-multiplier formulation)
};

// The settings of build_model().
struct BuildOptions {
  // which joints are eliminated by variable reduction
  Reduction reduction = Reduction::flat;
  double assembly_tolerance = 1e-12;  // relative to the mechanism's size
  // Largest gap between the two copies of a joint node (revolute: node_a and node_b; prismatic,
  // pin-in-slot: the slider from its axis line) in the initial positions, relative to the
  // mechanism's size (diagonal of the box around all nodes). Node positions define every body's
  // shape, so a larger gap is refused (it would silently change a link's length).
  double joint_tolerance = 1e-6;
  bool assemble = true;                   // assemble the initial configuration and check ranks
  double max_memory = kDefaultMaxMemory;  // bytes of dense matrices for that; above: refused
};

// A body-local slot: node k of a body has slots 2k (x) and 2k+1 (y); the rotation rate has 2n.
struct NodeRef {
  int var = -1;      // index of x in q0 (and q1); y is var + 1; -1: fixed node (ground)
  Vec2 fixed{0, 0};  // position when var == -1
  int body = -1;     // body index, -1 for ground
  int local = -1;    // node index within the body
};
// The quasi-velocity of a body's rotation rate omega (rad/s).
struct OmegaRef {
  int var = -1;   // index in q1; -1: zero (ground, or a body without rotation)
  int body = -1;  // -1 for ground
};
// A reference to one quasi-velocity with its body-local slot (for reaction bookkeeping).
struct VarRef {
  // index in q1 (-1: none), its body (-1: ground) and its body-local slot
  int var = -1;
  int body = -1;
  int slot = -1;
};

// A body of the compiled model (Orsino 2016 Example 2.6): its nodes' variables, its shape and its
// constant mass data.
struct Body {
  // the body's label
  std::string name;
  std::vector<std::string> node_names;  // full labels
  // the variables of its nodes, in the order of node_names
  std::vector<NodeRef> nodes;
  std::vector<Vec2> geometry;  // node positions that define the rigid shape (initial, world)
  OmegaRef omega;              // rotation rate (var -1 if the body has none)
  bool has_omega = false;      // >= 2 nodes, or one node with inertia > 0
  // mass (kg) and centroidal moment of inertia (kg m^2)
  double mass = 0, inertia = 0;
  int ci = 0, cj = -1;        // centre of mass by local nodes (cj = -1: at node ci)
  double gamma = 0, rho = 0;  // Example 2.6 (b)
  double l01 = 0;             // distance of nodes 0 and 1 (rigid rows)
  std::vector<Vec2> frame;    // node k >= 2: p_k = p_0 + a d + b z x d, d = p_1 - p_0
  int owner = 0;              // subsystem tree node
  int offset = 0;             // first local slot in a concatenation over all bodies
  // The number of body-local slots: two per node and the rotation rate.
  int slots() const { return 2 * static_cast<int>(geometry.size()) + 1; }
};

// The kinds of constraint, in the order of the alternatives of Constraint::Def.
enum class ConstraintKind {
  rigid,
  revolute,
  prismatic,
  slot,
  coordinate,
  user_position,
  user_velocity,
  gear
};
const char* constraint_kind_name(ConstraintKind k);  // "rigid body", "pin-in-slot", ...

// One constraint: what every kind shares (name, subsystem, rows) and the data of its kind (`def`,
// one struct per kind; their rows are written in src/constraints/<kind>.hpp).
struct Constraint {
  struct Rigid {  // the rigid rows of one body (nodes, l01 and frame from the Body)
    // the ConstraintKind of this struct
    static constexpr ConstraintKind kind = ConstraintKind::rigid;
    // the body index
    int body = -1;
  };
  struct Revolute {  // a revolute joint kept as rows: node a on body 1, b on body 2
    // the ConstraintKind of this struct
    static constexpr ConstraintKind kind = ConstraintKind::revolute;
    // the joined node on body 1 (a) and on body 2 (b)
    NodeRef a, b;
    // body indices (-1: ground)
    int body1 = -1, body2 = -1;
  };
  struct Slider {  // pin-in-slot: axis i -> j (body 1), slider s (body 2)
    // the ConstraintKind of this struct
    static constexpr ConstraintKind kind = ConstraintKind::slot;
    // axis nodes i, j of body 1 and the slider node s of body 2
    NodeRef i, j, s;
    int q = -1;         // slider coordinate
    double length = 0;  // |p_j - p_i| (constant)
    // body indices (-1: ground)
    int body1 = -1, body2 = -1;
  };
  struct Prismatic : Slider {  // a slider with the rotation lock of body 2 on body 1
    // the ConstraintKind of this struct
    static constexpr ConstraintKind kind = ConstraintKind::prismatic;
    // whether the angle lock has a position row and a velocity row
    bool lock_position = false, lock_velocity = false;
    double lock_angle = 0;  // theta_2 - theta_1 at the initial configuration
    // rotation rates of bodies 1 and 2
    OmegaRef w1, w2;
  };
  // Extra coordinate: d/dt q[coord] = sum rate_terms; position invariant
  //   q[coord] - sum coord_terms - sum angle_terms(theta_body) - offset = 0 (mod 2 pi if angles)
  // Extra coordinate (CoordinateDef), see above.
  struct Coordinate {
    // the ConstraintKind of this struct
    static constexpr ConstraintKind kind = ConstraintKind::coordinate;
    // q0 index of the coordinate
    int coord = -1;
    // (quasi-velocity, weight) terms of its rate
    std::vector<std::pair<VarRef, double>> rate_terms;
    // (q0 index, weight) terms of the position invariant
    std::vector<std::pair<int, double>> coord_terms;
    std::vector<std::pair<int, double>> angle_terms;  // (body, weight); body -1 = ground
    // whether the position invariant exists (integer weights on angles, see CoordinateDef)
    bool holonomic = true;
    // the invariant's constant, from the initial configuration
    double offset = 0;
  };
  struct UserPosition {  // psi(x, t) = 0, x = the q0 variables args
    // the ConstraintKind of this struct
    static constexpr ConstraintKind kind = ConstraintKind::user_position;
    // the variables x of psi (q0 entries)
    std::vector<VarRef> args;
    // psi(x, t)
    std::function<Jet(std::span<const Jet>, Jet)> psi;
  };
  struct UserVelocity {  // g(x, v, t) = 0, x = the q0 variables args, v = the q1 rates
    // the ConstraintKind of this struct
    static constexpr ConstraintKind kind = ConstraintKind::user_velocity;
    // the variables x (q0 entries) and v (q1 entries)
    std::vector<VarRef> args, rates;
    // g(x, v, t)
    std::function<Jet(std::span<const Jet>, std::span<const Jet>, Jet)> g;
  };
  // Gear pair or rack and pinion (GearDef, RackDef; src/constraints/gear.hpp): with
  // phi = q0[phi] the carrier-relative angle of the driving body k (an extra coordinate,
  // d/dt phi = omega_k - omega_c),
  //   gear: theta_j - theta_c - ratio phi - offset = 0 (mod 2 pi),  omega_j - omega_c = ratio phi'
  //   rack: q0[coord] - ratio phi - offset = 0,                      q' = ratio phi'
  struct Gear {
    // the ConstraintKind of this struct
    static constexpr ConstraintKind kind = ConstraintKind::gear;
    int body = -1;     // driven body j (gear); -1 for a rack
    int carrier = -1;  // carrier (housing) body c; -1: the ground
    int coord = -1;    // rack: the slide coordinate (q0 index); -1 for a gear
    int phi = -1;      // q0 index of the carrier-relative angle of the driving body k
    double ratio = 1;  // rho (gear, dimensionless) or the pinion radius r (rack, m)
    // the invariant's constant, from the initial configuration (rad or m)
    double offset = 0;
    VarRef driven{};     // q1 entry of omega_j (gear) or of q' (rack)
    VarRef carrier_w{};  // q1 entry of omega_c (gear with a moving carrier; else var -1, body -1)
    VarRef phi_rate{};   // q1 entry of phi'
  };
  using Def = std::variant<Rigid, Revolute, Prismatic, Slider, Coordinate, UserPosition,
                           UserVelocity, Gear>;  // in the order of ConstraintKind

  // the constraint's label
  std::string name;
  // owning node of the subsystem tree (Model::tree)
  int owner = 0;
  int row0 = 0, nrow0 = 0;  // position rows
  int row1 = 0, nrow1 = 0;  // velocity rows
  // the data of its kind
  Def def;

  // The kind of the constraint (the alternative of def).
  ConstraintKind kind() const { return static_cast<ConstraintKind>(def.index()); }
  // The data of kind T; an Error naming the constraint if it is of another kind.
  template <class T>
  const T& as() const {
    if (const T* d = std::get_if<T>(&def)) return *d;
    wrong_kind(T::kind);
  }
  // The slider of a prismatic joint or pin-in-slot; nullptr for the other kinds.
  const Slider* slider() const {
    if (const auto* p = std::get_if<Prismatic>(&def)) return p;
    return std::get_if<Slider>(&def);
  }

 private:
  [[noreturn]] void wrong_kind(ConstraintKind wanted) const;
};

// An input of the mechanism (an actuated joint): its effort u enters the equations as B u (Orsino
// 2016 eq. 4.1 with the inputs separated; docs/equations.md).
struct Input {
  std::string label;  // "drive.torque", "slide.force"
  // the joint it actuates
  std::string joint;
  std::vector<std::pair<VarRef, double>> terms;  // column of B (generalized force per unit effort)
};

// A point fixed in a body (by local nodes like the centre of mass) or in the ground.
struct BodyPoint {
  int body = -1;  // -1: ground, at `fixed`
  // local nodes i, j of the point (cj = -1: at node ci)
  int ci = 0, cj = -1;
  // Example 2.6 (b) coefficients of the point on ci -> cj
  double gamma = 0, rho = 0;
  // position on the ground (m), when body == -1
  Vec2 fixed{0, 0};
};

// One quantity of the state a law reads (mo2d/law.hpp), resolved from its label by build_model.
struct Quantity {
  // What the quantity is (each enumerator says how it is computed).
  enum class Kind {
    coordinate,      // q0[var]
    rate,            // q1[var]
    constant,        // value (a coordinate of a node joined to the ground)
    point_x,         // position of point a, x
    point_y,         //   y
    point_vx,        // velocity of point a, x
    point_vy,        //   y
    distance,        // |p_b - p_a| - value (length, or extension when value = rest length)
    distance_rate,   // d/dt |p_b - p_a|
    body_angle,      // direction of body1's first two nodes (body1 -1: 0), minus value, wrapped
    relative_angle,  // theta(body2) - theta(body1) - value, wrapped to (-pi, pi]
    relative_rate,   // omega(body2) - omega(body1)
    // the kind of quantity
  } kind = Kind::constant;
  // q0 or q1 index (coordinate, rate)
  int var = -1;
  // the constant, rest length or reference angle the kind subtracts
  double value = 0;
  // the points of the point and distance kinds
  BodyPoint a{}, b{};
  // the bodies of the angle kinds (-1: ground)
  int body1 = -1, body2 = -1;
};

// A Law with its labels resolved: f(x, t), x[k] = args[k] at the state. Empty f: the value 0.
struct CompiledLaw {
  // the quantities x the law reads
  std::vector<Quantity> args;
  std::vector<std::string> labels;  // the labels of args, as the law wrote them
  // f(x, t)
  std::function<Jet(std::span<const Jet>, Jet)> f;
  // Whether the law is set.
  explicit operator bool() const { return static_cast<bool>(f); }
};
inline constexpr int kMaxLawArgs = 64;  // arguments of one law (evaluated without allocation)

// A force load of the compiled model (ForceDef): its point and its component laws.
struct PointLoad {
  // the load's label
  std::string name;
  // the body it acts on
  int body = -1;
  int ci = 0, cj = -1;  // point by local nodes, like the centre of mass
  // Example 2.6 (b) coefficients of the point
  double gamma = 0, rho = 0;
  double cos = 1, sin = 0;  // rotation of the owning System's frame: F = R (fx, fy)
  // the component laws (N) in the owning System's frame
  CompiledLaw fx, fy;
};
// A torque load of the compiled model (TorqueDef).
struct TorqueLoad {
  // the load's label
  std::string name;
  // the body it acts on
  int body = -1;
  // the torque law (N m, counter-clockwise)
  CompiledLaw torque;
};

// A spring-damper of the compiled model (SpringDef).
struct SpringLoad {
  // the spring's label
  std::string name;
  // its two points
  BodyPoint a, b;
  // rest length (m), stiffness (N/m), damping (N s/m)
  double rest_length = 0, stiffness = 0, damping = 0;
  CompiledLaw tension;  // empty: linear
  // which sign of tension it carries
  SpringActs acts = SpringActs::both;
};
// A spring reduced to a constraint (SpringDef::reduce, src/model/reduced_springs.cpp): the user
// position constraint |p_b - p_a| - spring.rest_length = 0, m.constraints[constraint], whose
// multiplier is the tension, m.reactions[reaction] ("name.tension"). `spring` is the load it
// replaces (not applied; its stiffness, damping or law are read by the fidelity report).
// With reduce: quasi_steady the constraint holds the length of a HeldLength cell instead (the
// quasi-steady length, settled by forward runs at every projection: mo2d/quasi_steady.hpp).
struct ReducedSpring {
  // the spring it replaces (not applied)
  SpringLoad spring;
  // index of its constraint in Model::constraints and of its reaction in Model::reactions
  int constraint = -1, reaction = -1;
  // quasi_steady: points at the cell's first member (HeldLength::length, held_of); else null
  std::shared_ptr<double> held_length{};
};
// A torsional spring-damper of the compiled model (TorsionalSpringDef).
struct TorsionalLoad {
  // the spring's label
  std::string name;
  int body1 = -1, body2 = -1;  // -1: ground
  // stiffness (N m/rad), damping (N m s/rad), rest angle (rad)
  double stiffness = 0, damping = 0, rest = 0;
  CompiledLaw torque;  // empty: linear
};
// A torsional spring reduced to a constraint (TorsionalSpringDef::reduce,
// src/model/reduced_torsional.cpp): the user position constraint wrap(theta_2 - theta_1 - rest
// - a) = 0, a = 0 (reduce: constraint) or the held angle of a HeldLength cell (quasi_steady:
// its `length` is the angle from rest, mo2d/quasi_steady.hpp), m.constraints[constraint]; the
// torque on body 2 is minus its multiplier, m.reactions[reaction] ("name.torque").
struct ReducedTorsional {
  // the torsional spring it replaces (not applied)
  TorsionalLoad spring;
  // index of its constraint in Model::constraints and of its reaction in Model::reactions
  int constraint = -1, reaction = -1;
  // quasi_steady: points at the cell's first member (HeldLength::length, held_of); else null
  std::shared_ptr<double> held_angle{};
};

// A chain or belt drive (ChainDef; its spans' lengths and forces in src/dynamics/chain.hpp).
struct ChainLoad {
  // the chain's label
  std::string name;
  BodyPoint a, b;                  // the sprockets' centres
  int body_a = -1, body_b = -1;    // their bodies (-1: ground)
  int theta_a = -1, theta_b = -1;  // q0 of "name.theta_a", "name.theta_b" (-1: on the ground)
  // pitch radii (m), stiffness (N/m) and damping (N s/m) of each span
  double radius_a = 0, radius_b = 0, stiffness = 0, damping = 0;
  double rest_upper = 0, rest_lower = 0;  // m
  // spans that only pull, or bilateral
  ChainFidelity fidelity = ChainFidelity::unilateral;
  // Set from the assembled configuration (build_model): the centre line's initial direction
  // (beta is unwrapped near it) and the constants that make l = L there.
  double beta0 = 0, offset_upper = 0, offset_lower = 0;
  // Gamba's printed extension (2009, §2.2: without the wrap term (r_b - r_a)(beta +- alpha)), for
  // comparison in tests only: its forces have no potential (energy is not conserved).
  bool printed_extension = false;
  // Inextensible (src/model/inextensible_chains.cpp): the span held at its rest length by
  // m.constraints[constraint] (the user position row l - rest = 0; its multiplier the tension,
  // reactions "name.upper.tension" and "name.lower.tension"): 0 upper, 1 lower, -1 none (slack,
  // no row). mode_fixed: a model of one mode (chain_mode_model), integrated as it is; otherwise
  // forward_dynamics switches the spans (src/forward/chain_switching.cpp).
  int constraint = -1, active_span = -1;
  bool mode_fixed = false;
  // ChainFidelity::quasi_steady (compiled as inextensible): the lengths the upper and lower span
  // rows hold, HeldLength cells (mo2d/quasi_steady.hpp; the taut span's rest + T / k); else null
  std::shared_ptr<double> held[2]{};
};

// Friction in a joint (FrictionDef; evaluated in src/dynamics/friction.cpp). Its value F (N or
// N m) acts as the generalized force F * terms; its rate is v = sum coef * q1[var] over terms.
struct FrictionLoad {
  // the friction's label and its joint's label
  std::string name, joint;
  std::vector<std::pair<VarRef, double>> terms;  // like an Input's column of B
  int reaction = -1;  // column of the joint's "Fx" in the reactions ("Fy" follows)
  int slider = -1;    // Model::constraints index of the slide (axis direction); -1: revolute
  // viscous coefficient (N s/m or N m s/rad), Coulomb mu, pin radius (m), tanh regularization speed
  // (m/s or rad/s)
  double viscous = 0, mu = 0, radius = 0, regularization = 1e-3;
};

// A named point (System::add_point): an output of every run and a quantity laws may read.
struct NamedPoint {
  // the point's label
  std::string name;
  // where it is fixed
  BodyPoint point;
};

// A joint eliminated by variable reduction: its reaction is recovered by splitting the merged
// node's (or rotation's) generalized force between the bodies that share it.
struct MergeEdge {
  int parent_body = -1;  // -1: ground
  // the child body (body 2 or body 1 of the joint)
  int child_body = -1;
  int child_slot = -1;  // body-local slot of x (node) or of the rotation
  // whether the edge merges a rotation rate (prismatic) rather than a node (revolute)
  bool rotation = false;
  int reaction = -1;             // first reaction column it fills (x, y; or the torque)
  double sign = 1;               // +1 if the child is the joint's body 2
  std::vector<int> child_edges;  // edges whose parent is this edge's child at the same slot
};

// A reaction of the mechanism (a joint force or torque, a multiplier), read from the multipliers
// lambda of the velocity rows.
struct Reaction {
  std::string label;  // "elbow.Fx"
  int row = -1;       // velocity row whose multiplier gives it: value = factor * lambda
  // value = factor * lambda[row]
  double factor = -1;
};

// A node of the tree of subsystems (Orsino 2016 Theorem 2.10): what each System instance owns.
struct TreeNode {
  std::string name;  // instance path, "" for the root
  // index of the parent node (-1: the root)
  int parent = -1;
  // indices of the child nodes
  std::vector<int> children;
  std::vector<int> vars;  // q1 variables owned here
  std::vector<int> rows;  // velocity rows owned here
};

// Bodies given by their shape (BodyDef::shape): where each of their nodes was sketched and where
// the initial configuration (Model::q0) has it. Empty when no body has a shape.
struct SketchedNode {
  std::string label;     // full node label, "coupler.B"
  Vec2 sketch{0, 0};     // the sketched position (world)
  Vec2 assembled{0, 0};  // its position in the initial configuration (world)
  double moved = 0;      // |assembled - sketch| (m)
};
// Where build_model placed the bodies given by their shape (see SketchedNode).
struct SketchReport {
  std::vector<SketchedNode> nodes;  // every node of every body with a shape, in body order
  // The configuration nearest to the sketch was found (the distance to it cannot decrease);
  // false: Gauss-Newton stopped short of it (a warning says by how much).
  bool nearest = true;
  // A warning per node moved by more than kSketchWarnFraction of the mechanism's size (the sketch
  // is far from the configuration, which may be on another branch than the one intended), and
  // the one of `nearest` false.
  std::vector<std::string> warnings;
  static constexpr double kSketchWarnFraction = 0.1;
  double max_moved() const;  // largest SketchedNode::moved (0 without nodes)
};

// The compiled mechanism (see the file's description): variables and their labels, bodies,
// constraints, inputs, reactions, loads and the subsystem tree. Built by build_model(), read by
// every algorithm.
struct Model {
  // the mechanism's name (the root System's)
  std::string name;
  int n0 = 0, n1 = 0;  // coordinates, quasi-velocities
  int m0 = 0, m1 = 0;  // position rows, velocity rows
  int dof = 0;         // n1 - rank(A) at the initial configuration
  // whether every constraint has a position row (no velocity-only constraint)
  bool holonomic = true;
  // the reduction it was built with
  Reduction reduction = Reduction::flat;
  double scale = 1;  // characteristic length (m)

  std::vector<std::string> coordinate_labels;  // n0
  std::vector<std::string> rate_labels;        // n1
  // labels of the position rows psi and of the velocity rows A q1 = b
  std::vector<std::string> position_row_labels, velocity_row_labels;
  std::unordered_map<std::string, int> coordinate_index, rate_index;  // includes aliases
  std::unordered_set<std::string> fixed_coordinates;  // node coordinates joined to the ground
  std::vector<VarRef> rate_refs;  // n1: first body/slot owning each quasi-velocity

  // the bodies
  std::vector<Body> bodies;
  // names and positions (m) of the ground nodes
  std::vector<std::string> ground_names;
  std::vector<Vec2> ground_positions;
  // every constraint, with its rows
  std::vector<Constraint> constraints;
  // the inputs (columns of B)
  std::vector<Input> inputs;
  // the reactions
  std::vector<Reaction> reactions;
  std::vector<MergeEdge> merge_edges;  // in post-order (children before parents)
  int n_slots = 0;                     // local slots of all bodies
  // The number of reactions and of inputs.
  int n_reactions() const { return static_cast<int>(reactions.size()); }
  int n_inputs() const { return static_cast<int>(inputs.size()); }

  // gravity (m/s^2)
  Vec2 gravity{0, 0};
  // the loads: forces, torques, springs, torsional springs, chains
  std::vector<PointLoad> forces;
  std::vector<TorqueLoad> torques;
  std::vector<SpringLoad> springs;
  std::vector<ReducedSpring> reduced_springs;  // springs replaced by constraints (not loads)
  // the torsional springs and the chains
  std::vector<TorsionalLoad> torsional_springs;
  std::vector<ReducedTorsional> reduced_torsional;  // torsional springs replaced by constraints
  std::vector<ChainLoad> chains;                    // the chain and belt drives
  // the named points
  std::vector<NamedPoint> points;
  // the joint frictions
  std::vector<FrictionLoad> frictions;
  // Derived quantities by label (mo2d/law.hpp): bodies, joints, springs, points, node aliases.
  std::unordered_map<std::string, Quantity> quantities;

  std::vector<TreeNode> tree;  // tree[0] is the root
  Eigen::VectorXd q0;          // initial configuration (assembled)
  SketchReport sketch;         // bodies given by their shape: how far assembly moved their nodes

  std::vector<std::string> input_labels() const;     // Model::inputs[k].label
  std::vector<std::string> reaction_labels() const;  // Model::reactions[k].label
  int coordinate(const std::string& label) const;    // throws Error naming the label
  // index of a quasi-velocity label in q1; throws Error naming the label
  int rate(const std::string& label) const;
};

// Compiles a System into a Model: numbers the variables, eliminates joints by variable reduction
// (Orsino 2016 eq. 5.27, 5.30), builds the constraint rows and mass data (eq. 5.25-5.26, errata
// applied), assembles the initial configuration and checks ranks. Throws Error naming the element
// at fault.
Model build_model(const System& system, const BuildOptions& options = {});

// A law's labels resolved against m: `prefix` is the instance path of the System that owns it
// ("" at the root, "leg." ...), `locals` the quantities only this law may read ("length" of its
// spring). Throws Error (message starting with `what`, element `element`) naming the unknown
// label, with a suggestion.
CompiledLaw compile_law(const Model& m, const Law& law, const std::string& what,
                        const std::string& element, const std::string& prefix = "",
                        const std::vector<std::pair<std::string, Quantity>>& locals = {});
// The value of a compiled law at (t, q0, q1) (0 for an empty law). Not finite: an Error
// "<role> '<element>' is not finite at t = ..." with the values of its arguments. No allocation
// otherwise.
double law_value(const Model& m, const CompiledLaw& law,
                 const Eigen::Ref<const Eigen::VectorXd>& q0,
                 const Eigen::Ref<const Eigen::VectorXd>& q1, double t, const char* role,
                 const std::string& element);
// The value of one quantity at (q0, q1).
double quantity_value(const Model& m, const Quantity& q,
                      const Eigen::Ref<const Eigen::VectorXd>& q0,
                      const Eigen::Ref<const Eigen::VectorXd>& q1);

// Position of node k of body b for coordinates q0.
inline Vec2 node_position(const NodeRef& n, const Eigen::Ref<const Eigen::VectorXd>& q0) {
  return n.var < 0 ? n.fixed : Vec2(q0[n.var], q0[n.var + 1]);
}
// Velocity of a node for quasi-velocities q1 (m/s).
inline Vec2 node_velocity(const NodeRef& n, const Eigen::Ref<const Eigen::VectorXd>& q1) {
  return n.var < 0 ? Vec2(0, 0) : Vec2(q1[n.var], q1[n.var + 1]);
}
// Rotation rate of a body for quasi-velocities q1 (rad/s).
inline double omega_value(const OmegaRef& w, const Eigen::Ref<const Eigen::VectorXd>& q1) {
  return w.var < 0 ? 0.0 : q1[w.var];
}
// Centre-of-mass position, velocity and body angle (angle of node 1 seen from node 0).
Vec2 com_position(const Body& b, const Eigen::Ref<const Eigen::VectorXd>& q0);
double body_angle(const Body& b, const Eigen::Ref<const Eigen::VectorXd>& q0);

// Human-readable summary: variables, constraints, inputs, DOF (and, for bodies given by their
// shape, how far each sketched node moved).
std::string describe(const Model& model);

}  // namespace mo2d
