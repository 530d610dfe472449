#pragma once
// The stages of build_model() and the data passed between them (internal header).
//
// build_model (build_model.cpp) runs them in this order; each stage throws mo2d::Error naming the
// element at fault, and the order of the checks is part of the behaviour (the first error wins):
//
//   1. flatten   (flatten.cpp)     System tree -> Flat: every definition with its subsystem and
//                                  instance prefix, positions in world coordinates.
//   1b. sketch   (sketch.cpp,      bodies given by their shape (BodyDef::shape) placed where the
//        sketch_solve.cpp)         joints close, nearest to their sketch; Flat then holds exact
//                                  positions as if the user had written them (only when some
//                                  body has a shape).
//   2. validate  (validate.cpp)    node elements and the mechanism's size, bodies with their
//                                  constant mass data, one namespace for joints, coordinates and
//                                  constraints, the topology of revolute joints; the per-joint
//                                  checks that reduce runs joint by joint.
//   3. reduce    (reduce.cpp)      variable reduction (eq. 5.27, 5.30): revolute joints merge
//                                  node variables, prismatic joints merge rotation rates,
//                                  according to BuildOptions::reduction.
//   4. number    (number.cpp)      variables, their labels and the given initial configuration.
//   5. rows      (rows.cpp)        constraint rows with their labels, reactions and inputs.
//   6. loads     (loads.cpp)       point forces, torques, springs, torsional springs.
//   7. merge edges (merge_edges.cpp) the trees that split a merged node's (or rotation's)
//                                  generalized force into the reactions of eliminated joints.
//   8. assemble  (build_model.cpp) input labels, DOF, the assembled q0 and the rank checks.
//
// Indices used throughout: an *element* is one node as defined (ground nodes first, then the
// nodes of every body in order), E of them; a *rotation element* is 0 for the ground and 1 + b for
// body b, NB + 1 of them (NB = number of bodies).
#include <array>
#include <map>
#include <numeric>
#include <string>
#include <vector>

#include "mo2d/model.hpp"
#include "mo2d/system.hpp"

namespace mo2d::build {

// Disjoint sets of integers (the merges of variable reduction); find compresses paths.
struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) { return parent[x] == x ? x : parent[x] = find(parent[x]); }
};

// ---- 1. flatten ---------------------------------------------------------------------------------

// A definition with the subsystem that owns it (index in Flat::tree) and its instance prefix
// ("" at the root, "left.arm." in nested instances).
template <class Def>
struct Owned {
  Def def;
  int owner;
  std::string prefix;
};

// Every definition of the System tree in one list per kind, in depth-first order (a system's own
// definitions, then its instances in order). Written by flatten; read by every later stage. Body
// names are prefixed; every other definition keeps its local name (full name: prefix + def.name)
// and its node references are resolved from its prefix.
struct Flat {
  std::vector<TreeNode> tree;             // subsystem tree; tree[0] is the root (vars, rows empty)
  std::vector<Placement> frames;          // same size: each subsystem's frame in the world
  std::vector<std::string> ground_names;  // full labels "left.ground.O"
  std::vector<Vec2> ground_pos;           // same size: world positions
  // name prefixed, node and centre positions in world (a body given by its shape: its nodes'
  // sketch in world, its shape and centre-of-mass point in its own frame, until resolve_sketches
  // places it)
  std::vector<Owned<BodyDef>> bodies;
  std::vector<Owned<RevoluteDef>> revolutes;
  std::vector<Owned<PrismaticDef>> prismatics;
  std::vector<Owned<PinInSlotDef>> slots;
  std::vector<Owned<CoordinateDef>> coordinates;  // with one "name.phi" per gear and rack
  std::vector<Owned<GearDef>> gears;
  std::vector<Owned<RackDef>> racks;
  std::vector<Owned<PositionConstraintDef>> pos;
  std::vector<Owned<VelocityConstraintDef>> vel;
  std::vector<Owned<ForceDef>> forces;  // point in world, force components in the owner's frame
  std::vector<double> force_angle;      // per force: angle of its owner's frame (rad)
  std::vector<Owned<TorqueDef>> torques;
  std::vector<Owned<SpringDef>> springs;  // attachment points in world
  std::vector<Owned<TorsionalSpringDef>> torsional;
  std::vector<Owned<ChainDef>> chains;  // centres in world; "name.theta_a/b" in coordinates
  std::vector<Owned<PointDef>> points;  // point in world
  std::vector<Owned<FrictionDef>> frictions;
};

Flat flatten(const System& system);

// ---- 1b. sketch ---------------------------------------------------------------------------------

// Places every body of `flat` that has a shape: its node positions (the sketch) become the placed
// shape, and the points given in its frame (centre-of-mass point, force points, spring points)
// world points of that placement. Returns the sketch of every such node (SketchReport::nodes with
// `sketch` set) and SketchReport::nearest; complete_sketch_report fills in the rest once the model
// is assembled. Throws Error naming the joint left open when the shapes cannot close a loop.
SketchReport resolve_sketches(Flat& flat, const BuildOptions& options);
void complete_sketch_report(Model& m);

// ---- 2. validate --------------------------------------------------------------------------------

// Node elements: every ground node, then every node of every body in Flat order. Written by
// collect_elements; read by every later stage. Each vector has E entries.
struct Elements {
  std::map<std::string, int> index;  // full node label -> element
  std::vector<std::string> label;    // full node label ("crank.A", "ground.O")
  std::vector<int> body;             // body index; -1 for a ground node
  std::vector<int> local;            // node index within its body; -1 for a ground node
  std::vector<Vec2> position;        // initial position, world
  double size = 0;  // diagonal of the box around every node (unclamped; 0 without nodes)

  int count() const { return static_cast<int>(label.size()); }
  // Element of node `ref` seen from the instance `prefix`; throws naming `what` ("revolute joint
  // 'x'") with a suggestion among the nodes visible from that instance.
  int resolve(const std::string& prefix, const std::string& ref, const std::string& what) const;
};

// A prismatic or pin-in-slot joint after validation (check_prismatic, check_slot); reduce
// decides `lock` and `merged` for prismatic joints.
struct AxisJoint {
  int ei = -1, ej = -1, es = -1;  // elements: axis_from, axis_to, slider (pin)
  int body1 = -1, body2 = -1;     // body of the axis, of the slider; -1: ground
  bool lock = false;    // prismatic joint with a rotation on both sides: locks their angle
  bool merged = false;  // that lock is eliminated by merging the two rotation rates (eq. 5.30)
};

// (gamma, rho) of point p on a body's first two nodes (Example 2.6 (b)):
// p = p_0 + gamma d + rho z x d with d = p_1 - p_0, for its initial node positions `geometry`.
Vec2 on_first_two_nodes(const std::vector<Vec2>& geometry, const Vec2& p);
// Names may not contain '.', ',' or spaces (they are joined into labels).
void check_name(const std::string& name, const std::string& what);
void check_gravity(const Vec2& gravity);
// Elements, with the duplicate and finiteness checks of nodes and bodies; writes m.scale (the
// characteristic length) and checks BuildOptions::joint_tolerance.
Elements collect_elements(const Flat& flat, const BuildOptions& options, Model& m);
// m.bodies with their constant mass data (Example 2.6), m.n_slots and every Body::offset.
void add_bodies(const Flat& flat, Model& m);
// Joints, coordinates and constraints share one set of names.
void check_names(const Flat& flat);
// Over all revolute joints, whatever the reduction: a cycle at one node is redundant, two ground
// nodes joined through bodies conflict.
void check_revolute_topology(const Flat& flat, const Elements& el);
// One joint, checked where reduce meets it: returns its elements (node_a, node_b) or
// (axis_from, axis_to, slider) and checks that the initial positions agree with it.
std::array<int, 2> check_revolute(const Owned<RevoluteDef>& j, const Elements& el,
                                  double joint_tolerance);
AxisJoint check_prismatic(const Owned<PrismaticDef>& j, const Elements& el, double joint_tolerance,
                          double scale);
AxisJoint check_slot(const Owned<PinInSlotDef>& j, const Elements& el, double joint_tolerance,
                     double scale);

// ---- 3. reduce ----------------------------------------------------------------------------------

// Which joints are eliminated, and the resulting groups of merged nodes and rotations. Written by
// reduce; read by number, rows, loads and merge_edges.
struct Reduced {
  std::vector<int> node_root;      // E: element whose variables element e uses (a ground element
                                   // if its group touches the ground, else the group's earliest)
  std::vector<int> rotation_root;  // NB + 1: rotation element whose rate rotation element r uses
                                   // (0 if the group is locked to the ground)
  std::vector<std::array<int, 2>> revolutes;  // per revolute joint: elements (node_a, node_b)
  std::vector<bool> revolute_merged;          // per revolute joint: eliminated (eq. 5.27)
  std::vector<AxisJoint> prismatics;          // per prismatic joint
  std::vector<AxisJoint> slots;               // per pin-in-slot joint (lock, merged: false)
};

Reduced reduce(const Flat& flat, const Elements& el, const BuildOptions& options, const Model& m);

// ---- 4. number ----------------------------------------------------------------------------------

// Variables (model.hpp: q0 = node coordinates, slider coordinates, extra coordinates; q1 = their
// rates, then the rotation rates). Written by number_variables, which also writes m.n0, m.n1, the
// labels and indices of m, m.fixed_coordinates, m.rate_refs, every Body::nodes and Body::omega,
// and TreeNode::vars.
struct Numbering {
  std::vector<int> node_var;      // E, at root elements: -1 fixed (ground), else index of x in q0;
                                  // -2 at the other elements
  std::vector<int> prismatic_q;   // per prismatic joint: index of its slider coordinate
  std::vector<int> slot_q;        // per pin-in-slot joint: index of its slider coordinate
  std::vector<int> coordinate_q;  // per extra coordinate: its index
  // n0: the initial configuration as given (assembly makes it consistent): node positions and
  // slider coordinates written by number_variables, extra coordinates by add_rows.
  Eigen::VectorXd q0;
};

Numbering number_variables(const Flat& flat, const Elements& el, const Reduced& red, Model& m);
// Reference to element e's coordinates (a body's node, or a fixed ground position).
NodeRef node_ref(const Model& m, const Elements& el, int e);
// Angle of a body's first two nodes in the initial configuration (rad); 0 for the ground (body <
// 0).
double initial_angle(const Model& m, int body);

// ---- 5. rows ------------------------------------------------------------------------------------

// The reaction columns of joints that reduce may have eliminated. Written by add_rows; read by
// add_merge_edges.
struct JointReactions {
  std::vector<int> revolute;   // per revolute joint: column of its Fx (Fy follows)
  std::vector<int> prismatic;  // per prismatic joint: column of its torque T (-1: no lock)
};

// m.constraints with their rows and labels (rigid bodies, revolute, prismatic, pin-in-slot,
// extra coordinates, user constraints, in that order), m.reactions, m.inputs; completes
// Numbering::q0 with the extra coordinates.
JointReactions add_rows(const Flat& flat, const Elements& el, const Reduced& red, Numbering& num,
                        Model& m);

// Appends c with nrow0 position rows and nrow1 velocity rows (labelled c.name + labels0[k],
// c.name + labels1[k]); returns its index in m.constraints.
int add_constraint(Model& m, Constraint c, int nrow0, int nrow1,
                   const std::vector<std::string>& labels0,
                   const std::vector<std::string>& labels1);
// Gears and racks (gears.cpp): their rows after the extra coordinates (they read "name.phi").
void add_gear_rows(const Flat& flat, const Numbering& num, Model& m);

// A velocity constraint given by labels (VelocityConstraintDef::labels, g_labels), as coords,
// rates and g: each label sorted by the model's coordinate and quasi-velocity labels (seen from
// the instance `prefix`); an Error naming a label that is neither (with a suggestion).
VelocityConstraintDef sort_velocity_labels(const Model& m, const std::string& prefix,
                                           const VelocityConstraintDef& def,
                                           const std::string& what);
// Refuses a compiled velocity constraint whose g is not affine in its rates (eq. 2.11) at the
// configuration q0 (t = 0), naming the rate (def.rates) it is not linear in.
void check_linear_in_rates(const Constraint::UserVelocity& c, const VelocityConstraintDef& def,
                           const Eigen::VectorXd& q0, const std::string& what,
                           const std::string& name);

// ---- 6. loads -----------------------------------------------------------------------------------

// m.forces, m.torques, m.springs, m.torsional_springs, m.points, then m.quantities (the derived
// quantities laws may read, laws.cpp) and the loads' laws compiled against them.
void add_loads(const Flat& flat, const Elements& el, const Reduced& red, Model& m);
// Chains (chains.cpp): m.chains after the coordinates "name.theta_a/b"; init_chains sets their
// initial geometry once m.q0 is assembled.
void add_chains(const Flat& flat, Model& m);
void init_chains(Model& m);
// Inextensible chains (inextensible_chains.cpp), once init_chains has set their geometry: one row
// each, the upper span held at its rest length, reactions "name.upper.tension" (the multiplier)
// and "name.lower.tension" (factor 0). True if it added any (the model is then assembled again).
bool add_inextensible_chains(Model& m);
// A spring with reduce: constraint (reduced_springs.cpp): its constraint row (|p_b - p_a| = rest
// length), the reaction "name.tension" and m.reduced_springs, instead of a load.
// quasi_steady: the length held is a cell forward runs update (ReducedSpring::held_length).
void add_reduced_spring(const SpringLoad& s, int owner, Model& m, bool quasi_steady);
// A torsional spring with reduce (reduced_torsional.cpp): its row (the relative angle at rest, or
// at the held quasi-steady angle), the reaction "name.torque" and m.reduced_torsional.
void add_reduced_torsional(const TorsionalLoad& s, int owner, Model& m, bool quasi_steady);
// Joint friction (frictions.cpp): after the rows (reactions, slides) are known.
void add_frictions(const Flat& flat, const Elements& el, const Reduced& red, Model& m);
// laws.cpp: m.quantities from the bodies, nodes, revolute joints, springs and points.
void add_quantities(const Flat& flat, const Elements& el, const Reduced& red, Model& m);
// A body point from a point given in world coordinates at the initial configuration ("ground"
// allowed); throws naming `what` if the body is unknown or has one node elsewhere.
BodyPoint body_point(const Model& m, const std::string& prefix, const std::string& body,
                     const Vec2& p, const std::string& what);

// ---- 7. merge edges -----------------------------------------------------------------------------

// m.merge_edges: node groups first, then rotation groups, each in post-order.
void add_merge_edges(const Elements& el, const Reduced& red, const JointReactions& reactions,
                     Model& m);

}  // namespace mo2d::build
