// build_model: System tree -> flat Model.
//  1. flatten the tree of subsystems (names prefixed by the instance path, placements applied);
//  2. validate every definition (errors name the element);
//  3. variable reduction (eq. 5.27, 5.30): revolute joints merge node variables, prismatic joints
//     merge rotation rates, according to BuildOptions::reduction;
//  4. number the variables and constraint rows, give every one a label;
//  5. assemble the initial configuration and check that no constraint is redundant.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numeric>
#include <set>
#include <sstream>

#include "constraints/constraints.hpp"
#include "mo2d/budget.hpp"
#include "mo2d/error.hpp"
#include "mo2d/kinematics.hpp"
#include "mo2d/model.hpp"
#include "model/suggest.hpp"

namespace mo2d {
namespace {

using detail::perp;

struct Frame {  // world = R p + o
  double angle = 0;
  Vec2 offset{0, 0};
  Vec2 apply(const Vec2& p) const { return Placement{offset, angle}.apply(p); }
  Frame compose(const Placement& child) const {  // this o child
    return {angle + child.angle, apply(child.offset)};
  }
};

template <class Def>
struct Owned {
  Def def;
  int owner;
  std::string prefix;
};

struct Flat {
  std::vector<TreeNode> tree;
  std::vector<std::string> ground_names;
  std::vector<Vec2> ground_pos;
  std::vector<Owned<BodyDef>> bodies;  // node positions already in world coordinates
  std::vector<Owned<RevoluteDef>> revolutes;
  std::vector<Owned<PrismaticDef>> prismatics;
  std::vector<Owned<PinInSlotDef>> slots;
  std::vector<Owned<CoordinateDef>> coordinates;
  std::vector<Owned<PositionConstraintDef>> pos;
  std::vector<Owned<VelocityConstraintDef>> vel;
  std::vector<Owned<ForceDef>> forces;
  std::vector<Owned<TorqueDef>> torques;
  std::vector<Owned<SpringDef>> springs;
  std::vector<Owned<TorsionalSpringDef>> torsional;
};

void check_name(const std::string& name, const std::string& what) {
  if (name.empty()) throw Error(what + " has an empty name", what);
  if (name.find('.') != std::string::npos || name.find(',') != std::string::npos ||
      name.find(' ') != std::string::npos)
    throw Error(what + " '" + name + "': names may not contain '.', ',' or spaces", name);
}

void flatten(const System& s, const std::string& prefix, const Frame& frame, int tree_index,
             Flat& out) {
  for (const auto& g : s.ground()) {
    check_name(g.name, "ground node");
    out.ground_names.push_back(prefix + "ground." + g.name);
    out.ground_pos.push_back(frame.apply(g.position));
  }
  for (const auto& b : s.bodies()) {
    check_name(b.name, "body");
    if (b.name == "ground") throw Error("body name 'ground' is reserved for the base body", b.name);
    BodyDef w = b;
    for (auto& n : w.nodes) {
      check_name(n.name, "node of body '" + prefix + b.name + "'");
      n.position = frame.apply(n.position);
    }
    if (w.com && w.com->kind == CenterOfMass::Kind::point) w.com->point = frame.apply(w.com->point);
    w.name = prefix + b.name;
    out.bodies.push_back({std::move(w), tree_index, prefix});
  }
  for (const auto& j : s.revolutes()) {
    check_name(j.name, "revolute joint");
    out.revolutes.push_back({j, tree_index, prefix});
  }
  for (const auto& j : s.prismatics()) {
    check_name(j.name, "prismatic joint");
    out.prismatics.push_back({j, tree_index, prefix});
  }
  for (const auto& j : s.slots()) {
    check_name(j.name, "pin-in-slot joint");
    out.slots.push_back({j, tree_index, prefix});
  }
  for (const auto& c : s.coordinates()) {  // a label: dots allowed ("crank.angle")
    if (c.name.empty() || c.name.find_first_of(", ") != std::string::npos)
      throw Error("coordinate '" + c.name + "': a coordinate needs a name without ',' or spaces",
                  c.name);
    out.coordinates.push_back({c, tree_index, prefix});
  }
  for (const auto& c : s.position_constraints()) {
    check_name(c.name, "constraint");
    out.pos.push_back({c, tree_index, prefix});
  }
  for (const auto& c : s.velocity_constraints()) {
    check_name(c.name, "constraint");
    out.vel.push_back({c, tree_index, prefix});
  }
  for (const auto& f : s.forces()) {
    ForceDef w = f;
    w.point = frame.apply(f.point);
    const double c = std::cos(frame.angle), sn = std::sin(frame.angle);
    if (f.fx || f.fy) {  // rotate the force vector into the world frame
      Signal fx = f.fx, fy = f.fy;
      w.fx = [fx, fy, c, sn](double t) { return c * (fx ? fx(t) : 0.0) - sn * (fy ? fy(t) : 0.0); };
      w.fy = [fx, fy, c, sn](double t) { return sn * (fx ? fx(t) : 0.0) + c * (fy ? fy(t) : 0.0); };
    }
    out.forces.push_back({std::move(w), tree_index, prefix});
  }
  for (const auto& t : s.torques()) out.torques.push_back({t, tree_index, prefix});
  for (const auto& sp : s.springs()) {
    SpringDef w = sp;
    w.point_a = frame.apply(sp.point_a);
    w.point_b = frame.apply(sp.point_b);
    out.springs.push_back({std::move(w), tree_index, prefix});
  }
  for (const auto& ts : s.torsional_springs()) out.torsional.push_back({ts, tree_index, prefix});
  if (tree_index != 0 && s.gravity() != Vec2(0, 0))
    throw Error("subsystem '" + prefix.substr(0, prefix.size() - 1) +
                    "' sets gravity: gravity belongs to the root system",
                prefix.substr(0, prefix.size() - 1));
  std::set<std::string> seen;
  for (const auto& inst : s.instances()) {
    check_name(inst.name, "instance");
    if (!seen.insert(inst.name).second)
      throw Error("instance name '" + prefix + inst.name + "' is used twice", prefix + inst.name);
    const int child = static_cast<int>(out.tree.size());
    out.tree.push_back({prefix + inst.name, tree_index, {}, {}, {}});
    out.tree[tree_index].children.push_back(child);
    flatten(*inst.system, prefix + inst.name + ".", frame.compose(inst.placement), child, out);
  }
}

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) { return parent[x] == x ? x : parent[x] = find(parent[x]); }
};

bool is_integer(double w) {
  return std::abs(w - std::round(w)) < 1e-12;
}

std::string num(double v) {
  std::ostringstream s;
  s.precision(4);
  s << v;
  return s.str();
}
std::string point_str(const Vec2& p) {
  return "(" + num(p.x()) + ", " + num(p.y()) + ")";
}

// The initial positions define each body's shape (its node distances and angles), so the copies
// of one joint node must coincide and a slider must lie on its axis: a gap is a contradiction in
// the definition, not an approximate position that assembly could fix. `size` is the
// mechanism's size (diagonal of the box around every node), the tolerance is relative to it.
void check_joint_gap(double gap, double size, double tolerance, const std::string& what,
                     const std::string& detail, const char* rule, const std::string& element) {
  if (!(gap > tolerance * size)) return;
  throw Error(what + ": " + detail + " " + num(gap) + " m apart (" + num(gap / size) +
                  " of the mechanism's size " + num(size) + " m; tolerance " + num(tolerance) +
                  "): each body's node positions define its shape, so " + rule +
                  " in the initial configuration",
              element);
}

}  // namespace

std::vector<std::string> Model::input_labels() const {
  std::vector<std::string> out;
  for (const auto& in : inputs) out.push_back(in.label);
  return out;
}

std::vector<std::string> Model::reaction_labels() const {
  std::vector<std::string> out;
  for (const auto& r : reactions) out.push_back(r.label);
  return out;
}

int Model::coordinate(const std::string& label) const {
  auto it = coordinate_index.find(label);
  if (it == coordinate_index.end() && fixed_coordinates.count(label))
    throw Error("coordinate '" + label + "' is fixed (its node is joined to the ground)", label);
  if (it == coordinate_index.end()) {
    std::vector<std::string> names;
    for (const auto& [k, v] : coordinate_index) names.push_back(k);
    std::sort(names.begin(), names.end());
    throw Error("unknown coordinate '" + label + "'" + did_you_mean(label, names), label);
  }
  return it->second;
}

int Model::rate(const std::string& label) const {
  auto it = rate_index.find(label);
  if (it == rate_index.end()) {
    std::vector<std::string> names;
    for (const auto& [k, v] : rate_index) names.push_back(k);
    std::sort(names.begin(), names.end());
    throw Error("unknown quasi-velocity '" + label + "'" + did_you_mean(label, names), label);
  }
  return it->second;
}

Vec2 com_position(const Body& b, const Eigen::Ref<const Eigen::VectorXd>& q0) {
  const Vec2 pi = node_position(b.nodes[b.ci], q0);
  if (b.cj < 0) return pi;
  const Vec2 d = node_position(b.nodes[b.cj], q0) - pi;
  return pi + b.gamma * d + b.rho * perp(d);
}

double body_angle(const Body& b, const Eigen::Ref<const Eigen::VectorXd>& q0) {
  if (b.nodes.size() < 2) return 0.0;
  const Vec2 d = node_position(b.nodes[1], q0) - node_position(b.nodes[0], q0);
  return std::atan2(d.y(), d.x());
}

Model build_model(const System& system, const BuildOptions& options) {
  Flat flat;
  flat.tree.push_back({"", -1, {}, {}, {}});
  flatten(system, "", Frame{}, 0, flat);

  Model m;
  m.name = system.name();
  m.reduction = options.reduction;
  m.gravity = system.gravity();
  m.tree = flat.tree;
  m.ground_names = flat.ground_names;
  m.ground_positions = flat.ground_pos;
  if (!std::isfinite(m.gravity.x()) || !std::isfinite(m.gravity.y()))
    throw Error("gravity is not finite", "gravity");

  // ---- node elements: ground nodes first, then the nodes of every body -----------------------
  const int G = static_cast<int>(flat.ground_names.size());
  std::map<std::string, int> element_of;  // full node label -> element
  std::vector<std::string> element_label;
  std::vector<int> element_body, element_local;
  std::vector<Vec2> element_pos;
  auto add_element = [&](const std::string& label, int body, int local, Vec2 p) {
    if (!element_of.emplace(label, static_cast<int>(element_label.size())).second)
      throw Error("node '" + label + "' is defined twice", label);
    element_label.push_back(label);
    element_body.push_back(body);
    element_local.push_back(local);
    element_pos.push_back(p);
  };
  for (int g = 0; g < G; ++g) add_element(flat.ground_names[g], -1, -1, flat.ground_pos[g]);
  std::set<std::string> body_names;
  for (size_t bi = 0; bi < flat.bodies.size(); ++bi) {
    const BodyDef& d = flat.bodies[bi].def;
    if (!body_names.insert(d.name).second)
      throw Error("body '" + d.name + "' is defined twice", d.name);
    if (d.nodes.empty()) throw Error("body '" + d.name + "' has no nodes", d.name);
    for (size_t k = 0; k < d.nodes.size(); ++k)
      add_element(d.name + "." + d.nodes[k].name, static_cast<int>(bi), static_cast<int>(k),
                  d.nodes[k].position);
    for (const auto& n : d.nodes)
      if (!std::isfinite(n.position.x()) || !std::isfinite(n.position.y()))
        throw Error("node '" + d.name + "." + n.name + "' has a non-finite position", d.name);
  }
  const int E = static_cast<int>(element_label.size());

  // scale: size of the mechanism
  double size = 0;  // box diagonal, unclamped: for the joint checks, dimensionless
  {
    Eigen::AlignedBox2d box;
    for (const auto& p : element_pos) box.extend(p);
    size = E > 0 ? box.diagonal().norm() : 0.0;
    m.scale = E > 0 ? std::max(size, 1e-3) : 1.0;
  }
  if (!(options.joint_tolerance >= 0) || !std::isfinite(options.joint_tolerance))
    throw Error("BuildOptions::joint_tolerance must be finite and >= 0", "joint_tolerance");

  auto resolve = [&](const std::string& prefix, const std::string& ref, const std::string& what) {
    auto it = element_of.find(prefix + ref);
    if (it == element_of.end()) {
      std::vector<std::string> cands;
      for (const auto& [k, v] : element_of)
        if (k.compare(0, prefix.size(), prefix) == 0) cands.push_back(k.substr(prefix.size()));
      throw Error(what + ": node '" + prefix + ref + "' not found" + did_you_mean(ref, cands),
                  what.substr(what.find('\'') + 1, what.rfind('\'') - what.find('\'') - 1));
    }
    return it->second;
  };

  // ---- bodies: validation and constant mass data ----------------------------------------------
  for (size_t bi = 0; bi < flat.bodies.size(); ++bi) {
    const BodyDef& d = flat.bodies[bi].def;
    Body b;
    b.name = d.name;
    b.owner = flat.bodies[bi].owner;
    if (!std::isfinite(d.mass) || d.mass < 0)
      throw Error("body '" + d.name + "': mass must be finite and >= 0 (got " +
                      std::to_string(d.mass) + ")",
                  d.name);
    if (!std::isfinite(d.inertia) || d.inertia < 0)
      throw Error("body '" + d.name + "': inertia must be finite and >= 0 (got " +
                      std::to_string(d.inertia) + ")",
                  d.name);
    b.mass = d.mass;
    b.inertia = d.inertia;
    const int n = static_cast<int>(d.nodes.size());
    if (n == 1 && d.mass <= 0)
      throw Error("body '" + d.name + "' has one node and needs a positive mass", d.name);
    b.has_omega = n >= 2 || d.inertia > 0;
    for (int k = 0; k < n; ++k) {
      b.node_names.push_back(d.name + "." + d.nodes[k].name);
      b.geometry.push_back(d.nodes[k].position);
    }
    if (n >= 2) {
      const Vec2 dd = b.geometry[1] - b.geometry[0];
      b.l01 = dd.norm();
      if (b.l01 < 1e-9 * m.scale)
        throw Error("body '" + d.name +
                        "': its first two nodes coincide (a body needs two distinct "
                        "reference nodes)",
                    d.name);
      b.frame.assign(n, Vec2(0, 0));
      for (int k = 2; k < n; ++k) {
        const Vec2 r = b.geometry[k] - b.geometry[0];
        b.frame[k] = {r.dot(dd) / dd.squaredNorm(), r.dot(perp(dd)) / dd.squaredNorm()};
      }
    }
    auto local = [&](const std::string& node) {
      for (int k = 0; k < n; ++k)
        if (d.nodes[k].name == node) return k;
      std::vector<std::string> names;
      for (const auto& nd : d.nodes) names.push_back(nd.name);
      throw Error("body '" + d.name + "': centre of mass refers to unknown node '" + node + "'" +
                      did_you_mean(node, names),
                  d.name);
    };
    const CenterOfMass com = d.com.value_or(CenterOfMass::at_node(d.nodes[0].name));
    switch (com.kind) {
      case CenterOfMass::Kind::node:
        b.ci = local(com.node_i);
        break;
      case CenterOfMass::Kind::nodes:
        b.ci = local(com.node_i);
        b.cj = local(com.node_j);
        if (b.ci == b.cj)
          throw Error("body '" + d.name + "': centre of mass needs two different nodes", d.name);
        if (!std::isfinite(com.gamma) || !std::isfinite(com.rho))
          throw Error("body '" + d.name + "': centre of mass gamma/rho not finite", d.name);
        b.gamma = com.gamma;
        b.rho = com.rho;
        break;
      case CenterOfMass::Kind::point: {
        if (n < 2) {
          if ((com.point - b.geometry[0]).norm() > 1e-12 * m.scale)
            throw Error("body '" + d.name + "' has one node: its centre of mass must be the node",
                        d.name);
          break;
        }
        const Vec2 dd = b.geometry[1] - b.geometry[0], r = com.point - b.geometry[0];
        b.ci = 0;
        b.cj = 1;
        b.gamma = r.dot(dd) / dd.squaredNorm();
        b.rho = r.dot(perp(dd)) / dd.squaredNorm();
        break;
      }
    }
    m.bodies.push_back(std::move(b));
  }
  const int NB = static_cast<int>(m.bodies.size());
  for (auto& b : m.bodies) {
    b.offset = m.n_slots;
    m.n_slots += b.slots();
  }
  auto body_owner = [&](int body) { return body < 0 ? -1 : m.bodies[body].owner; };
  auto mergeable = [&](int owner, int body1, int body2) {
    switch (options.reduction) {
      case Reduction::flat:
        return true;
      case Reduction::none:
        return false;
      case Reduction::subsystems:
        return (body1 < 0 || body_owner(body1) == owner) &&
               (body2 < 0 || body_owner(body2) == owner);
    }
    return false;
  };

  // ---- one namespace for joints, coordinates and constraints
  // ---------------------------------------
  {
    std::set<std::string> names;
    auto claim = [&](const std::string& full, const char* what) {
      if (!names.insert(full).second)
        throw Error(std::string(what) + " '" + full +
                        "' is defined twice (joints, coordinates "
                        "and constraints share one set of names)",
                    full);
    };
    for (const auto& j : flat.revolutes) claim(j.prefix + j.def.name, "revolute joint");
    for (const auto& j : flat.prismatics) claim(j.prefix + j.def.name, "prismatic joint");
    for (const auto& j : flat.slots) claim(j.prefix + j.def.name, "pin-in-slot joint");
    for (const auto& c : flat.coordinates) claim(c.prefix + c.def.name, "coordinate");
    for (const auto& c : flat.pos) claim(c.prefix + c.def.name, "constraint");
    for (const auto& c : flat.vel) claim(c.prefix + c.def.name, "constraint");
  }

  // ---- topology of all revolute joints, whatever the reduction: cycles at one node are redundant,
  // two ground nodes joined through bodies conflict
  {
    UnionFind topo(E);
    for (const auto& j : flat.revolutes) {
      const std::string what = "revolute joint '" + j.prefix + j.def.name + "'";
      const int ea = resolve(j.prefix, j.def.node_a, what);
      const int eb = resolve(j.prefix, j.def.node_b, what);
      const int ra = topo.find(ea), rb = topo.find(eb);
      if (ra == rb && ea != eb)
        throw Error(what + " is redundant: its nodes are already joined by other revolute joints",
                    j.prefix + j.def.name);
      if (element_body[ra] < 0 && element_body[rb] < 0 && ra != rb)
        throw Error(what + " connects two ground nodes ('" + element_label[ra] + "' and '" +
                        element_label[rb] + "'): conflicting constraints",
                    j.prefix + j.def.name);
      if (element_body[rb] < 0)
        topo.parent[ra] = rb;
      else
        topo.parent[rb] = ra;
    }
  }

  // ---- revolute joints: node merges
  // --------------------------------------------------------------
  UnionFind nodes_uf(E);
  std::vector<std::array<int, 2>> revolute_elements;
  std::vector<bool> revolute_merged;
  for (const auto& j : flat.revolutes) {
    const std::string what = "revolute joint '" + j.prefix + j.def.name + "'";
    const int ea = resolve(j.prefix, j.def.node_a, what);
    const int eb = resolve(j.prefix, j.def.node_b, what);
    const int ba = element_body[ea], bb = element_body[eb];
    if (ba < 0 && bb < 0) throw Error(what + " joins two ground nodes", j.prefix + j.def.name);
    if (ba == bb) throw Error(what + " joins two nodes of the same body", j.prefix + j.def.name);
    check_joint_gap((element_pos[eb] - element_pos[ea]).norm(), size, options.joint_tolerance, what,
                    "its nodes '" + element_label[ea] + "' at " + point_str(element_pos[ea]) +
                        " and '" + element_label[eb] + "' at " + point_str(element_pos[eb]) +
                        " are",
                    "the two copies of a joint node must coincide", j.prefix + j.def.name);
    revolute_elements.push_back({ea, eb});
    const bool merge = mergeable(j.owner, ba, bb);
    revolute_merged.push_back(merge);
    if (merge) {
      const int ra = nodes_uf.find(ea), rb = nodes_uf.find(eb);
      if (ra == rb)
        throw Error(what + " is redundant: its nodes are already joined by other revolute joints",
                    j.prefix + j.def.name);
      // keep a ground element as root; otherwise the earlier element
      const bool a_ground = element_body[ra] < 0, b_ground = element_body[rb] < 0;
      if (a_ground && b_ground)
        throw Error(what + " joins two different ground nodes (conflicting constraints)",
                    j.prefix + j.def.name);
      if (b_ground || (!a_ground && rb < ra))
        nodes_uf.parent[ra] = rb;
      else
        nodes_uf.parent[rb] = ra;
    }
  }

  // distance of a slider (pin) from the line of its axis, in the initial configuration
  auto check_slider_on_axis = [&](int ei, int ej, int es, const std::string& what, const char* role,
                                  const std::string& element) {
    const Vec2 pi = element_pos[ei], axis = (element_pos[ej] - pi).normalized();
    const Vec2 r = element_pos[es] - pi;
    const double gap = std::abs(axis.x() * r.y() - axis.y() * r.x());
    check_joint_gap(gap, size, options.joint_tolerance, what,
                    std::string("its ") + role + " '" + element_label[es] + "' at " +
                        point_str(element_pos[es]) + " and the line of its axis '" +
                        element_label[ei] + "' -> '" + element_label[ej] + "' are",
                    "a slider must lie on the line of its axis", element);
  };

  // ---- rotation merges (prismatic joints) ------------------------------------------------------
  // element 0 = ground rotation, 1 + b = body b
  UnionFind rot_uf(NB + 1);
  struct PrismaticInfo {
    int ei, ej, es, body1, body2;
    bool lock, merged;
  };
  std::vector<PrismaticInfo> pinfo;
  for (const auto& j : flat.prismatics) {
    const std::string what = "prismatic joint '" + j.prefix + j.def.name + "'";
    PrismaticInfo p{};
    p.ei = resolve(j.prefix, j.def.axis_from, what);
    p.ej = resolve(j.prefix, j.def.axis_to, what);
    p.es = resolve(j.prefix, j.def.slider, what);
    p.body1 = element_body[p.ei];
    p.body2 = element_body[p.es];
    if (element_body[p.ej] != p.body1)
      throw Error(what + ": axis nodes must belong to the same body", j.prefix + j.def.name);
    if (p.body1 == p.body2)
      throw Error(what + ": the slider node must belong to another body than the axis",
                  j.prefix + j.def.name);
    if ((element_pos[p.ej] - element_pos[p.ei]).norm() < 1e-9 * m.scale)
      throw Error(what + ": zero-length axis (nodes '" + element_label[p.ei] + "' and '" +
                      element_label[p.ej] + "' coincide)",
                  j.prefix + j.def.name);
    check_slider_on_axis(p.ei, p.ej, p.es, what, "slider", j.prefix + j.def.name);
    const bool has1 = p.body1 < 0 || m.bodies[p.body1].has_omega;
    const bool has2 = p.body2 < 0 || m.bodies[p.body2].has_omega;
    p.lock = has1 && has2;
    p.merged = p.lock && mergeable(j.owner, p.body1, p.body2);
    if (p.merged) {
      const int r1 = rot_uf.find(p.body1 + 1), r2 = rot_uf.find(p.body2 + 1);
      if (r1 == r2)
        throw Error(what + " is redundant: the rotations of its bodies are already locked together",
                    j.prefix + j.def.name);
      if (r2 == 0 || (r1 != 0 && r2 < r1))
        rot_uf.parent[r1] = r2;
      else
        rot_uf.parent[r2] = r1;
    }
    pinfo.push_back(p);
  }
  struct SlotInfo {
    int ei, ej, es, body1, body2;
  };
  std::vector<SlotInfo> sinfo;
  for (const auto& j : flat.slots) {
    const std::string what = "pin-in-slot joint '" + j.prefix + j.def.name + "'";
    SlotInfo p{};
    p.ei = resolve(j.prefix, j.def.axis_from, what);
    p.ej = resolve(j.prefix, j.def.axis_to, what);
    p.es = resolve(j.prefix, j.def.pin, what);
    p.body1 = element_body[p.ei];
    p.body2 = element_body[p.es];
    if (element_body[p.ej] != p.body1)
      throw Error(what + ": axis nodes must belong to the same body", j.prefix + j.def.name);
    if (p.body1 == p.body2)
      throw Error(what + ": the pin must belong to another body than the slot",
                  j.prefix + j.def.name);
    if ((element_pos[p.ej] - element_pos[p.ei]).norm() < 1e-9 * m.scale)
      throw Error(what + ": zero-length axis", j.prefix + j.def.name);
    check_slider_on_axis(p.ei, p.ej, p.es, what, "pin", j.prefix + j.def.name);
    sinfo.push_back(p);
  }

  // ---- variables -------------------------------------------------------------------------------
  std::vector<int> group_var(E, -2);  // by root element: -1 fixed, >= 0 var of x
  for (int e = 0; e < E; ++e) {
    const int r = nodes_uf.find(e);
    if (group_var[r] != -2) continue;
    if (element_body[r] < 0) {
      group_var[r] = -1;
      continue;
    }
    group_var[r] = m.n0;
    m.coordinate_labels.push_back(element_label[e] + ".x");
    m.coordinate_labels.push_back(element_label[e] + ".y");
    m.rate_labels.push_back(element_label[e] + ".vx");
    m.rate_labels.push_back(element_label[e] + ".vy");
    m.rate_refs.push_back({m.n0, element_body[e], 2 * element_local[e]});
    m.rate_refs.push_back({m.n0 + 1, element_body[e], 2 * element_local[e] + 1});
    m.n0 += 2;
  }
  std::set<std::string> fixed_labels;
  for (int e = 0; e < E; ++e) {
    const int v = group_var[nodes_uf.find(e)];
    if (v < 0) {
      if (element_body[e] >= 0) {
        fixed_labels.insert(element_label[e] + ".x");
        fixed_labels.insert(element_label[e] + ".y");
      }
      continue;
    }
    m.coordinate_index[element_label[e] + ".x"] = v;
    m.coordinate_index[element_label[e] + ".y"] = v + 1;
    m.rate_index[element_label[e] + ".vx"] = v;
    m.rate_index[element_label[e] + ".vy"] = v + 1;
  }
  for (int bi = 0; bi < NB; ++bi) {
    Body& b = m.bodies[bi];
    for (size_t k = 0; k < b.geometry.size(); ++k) {
      const int e = element_of.at(b.node_names[k]);
      const int r = nodes_uf.find(e);
      NodeRef n;
      n.var = group_var[r];
      n.fixed = element_pos[r];
      n.body = bi;
      n.local = static_cast<int>(k);
      b.nodes.push_back(n);
    }
  }
  m.fixed_coordinates.insert(fixed_labels.begin(), fixed_labels.end());
  auto node_ref = [&](int e) {
    if (element_body[e] >= 0) return m.bodies[element_body[e]].nodes[element_local[e]];
    NodeRef n;
    n.var = -1;
    n.fixed = element_pos[e];
    return n;
  };
  auto new_var = [&](const std::string& label, const std::string& rate_label) {
    const int v = m.n0++;
    m.coordinate_labels.push_back(label);
    m.rate_labels.push_back(rate_label);
    m.rate_refs.push_back({v, -1, -1});
    m.coordinate_index[label] = v;
    m.rate_index[rate_label] = v;
    return v;
  };
  std::vector<int> prismatic_q, slot_q, coord_var;
  for (const auto& j : flat.prismatics)
    prismatic_q.push_back(new_var(j.prefix + j.def.name + ".q", j.prefix + j.def.name + ".v"));
  for (const auto& j : flat.slots)
    slot_q.push_back(new_var(j.prefix + j.def.name + ".q", j.prefix + j.def.name + ".v"));
  for (const auto& c : flat.coordinates) {
    const std::string label = c.prefix + c.def.name;
    if (m.coordinate_index.count(label))
      throw Error("coordinate '" + label + "' clashes with an existing coordinate label", label);
    coord_var.push_back(new_var(label, label + ".rate"));
  }
  // rotation variables
  m.n1 = m.n0;
  std::vector<int> rot_var(NB + 1, -2);
  rot_var[rot_uf.find(0)] = -1;
  for (int bi = 0; bi < NB; ++bi) {
    Body& b = m.bodies[bi];
    b.omega.body = bi;
    if (!b.has_omega) {
      b.omega.var = -1;
      continue;
    }
    const int r = rot_uf.find(bi + 1);
    if (rot_var[r] == -2) {
      rot_var[r] = m.n1++;
      m.rate_labels.push_back(b.name + ".w");
      m.rate_refs.push_back({rot_var[r], bi, b.slots() - 1});
    }
    b.omega.var = rot_var[r];
    if (rot_var[r] >= 0) m.rate_index[b.name + ".w"] = rot_var[r];
  }
  for (auto& b : m.bodies)
    if (!b.has_omega) b.omega.body = -1;  // no rotation at all: never referenced

  // ---- constraints -----------------------------------------------------------------------------
  auto add_constraint = [&](Constraint c, int nrow0, int nrow1,
                            const std::vector<std::string>& labels0,
                            const std::vector<std::string>& labels1) {
    c.row0 = m.m0;
    c.nrow0 = nrow0;
    c.row1 = m.m1;
    c.nrow1 = nrow1;
    m.m0 += nrow0;
    m.m1 += nrow1;
    for (int k = 0; k < nrow0; ++k)
      m.position_row_labels.push_back(c.name + (k < (int)labels0.size() ? labels0[k] : ""));
    for (int k = 0; k < nrow1; ++k)
      m.velocity_row_labels.push_back(c.name + (k < (int)labels1.size() ? labels1[k] : ""));
    for (int k = 0; k < nrow1; ++k) m.tree[c.owner].rows.push_back(c.row1 + k);
    m.constraints.push_back(std::move(c));
    return static_cast<int>(m.constraints.size()) - 1;
  };
  for (int bi = 0; bi < NB; ++bi) {
    const Body& b = m.bodies[bi];
    const int n = static_cast<int>(b.nodes.size());
    if (n < 2) continue;
    Constraint c;
    c.kind = ConstraintKind::rigid;
    c.name = b.name;
    c.owner = b.owner;
    c.body = bi;
    std::vector<std::string> l0{".rigid(d01)"}, l1;
    for (int k = 2; k < n; ++k) {
      l0.push_back(".rigid(" + std::to_string(k) + "x)");
      l0.push_back(".rigid(" + std::to_string(k) + "y)");
    }
    for (int k = 1; k < n; ++k) {
      l1.push_back(".rigid(v" + std::to_string(k) + "x)");
      l1.push_back(".rigid(v" + std::to_string(k) + "y)");
    }
    add_constraint(std::move(c), 1 + 2 * (n - 2), 2 * (n - 1), l0, l1);
  }

  // merge edges for the reaction split, built per merged group as a tree rooted at the ground
  // element (if any) or the group's root
  struct Adj {
    int other, reaction;
    double sign_if_other_is_child;
  };
  auto build_edges = [&](int n_elements, const std::vector<std::array<int, 2>>& pairs,
                         const std::vector<int>& reaction_index, auto&& body_of, auto&& slot_of,
                         auto&& is_ground, bool rotation) {
    std::vector<std::vector<Adj>> adj(n_elements);
    for (size_t k = 0; k < pairs.size(); ++k) {
      const auto [ea, eb] = pairs[k];
      adj[ea].push_back({eb, reaction_index[k], +1.0});  // eb child of ea: eb is body 2
      adj[eb].push_back({ea, reaction_index[k], -1.0});
    }
    std::vector<bool> visited(n_elements, false);
    std::function<void(int, int)> visit = [&](int e, int parent_edge) {
      visited[e] = true;
      std::vector<int> kids;
      for (const auto& a : adj[e]) {
        if (visited[a.other]) continue;
        MergeEdge me;
        me.parent_body = body_of(e);
        me.child_body = body_of(a.other);
        me.child_slot = slot_of(a.other);
        me.rotation = rotation;
        me.reaction = a.reaction;
        me.sign = a.sign_if_other_is_child;
        m.merge_edges.push_back(me);
        const int idx = static_cast<int>(m.merge_edges.size()) - 1;
        visit(a.other, idx);
        kids.push_back(idx);
      }
      if (parent_edge >= 0) m.merge_edges[parent_edge].child_edges = kids;
    };
    std::vector<int> roots;
    for (int e = 0; e < n_elements; ++e)
      if (is_ground(e) && !adj[e].empty()) roots.push_back(e);
    for (int e = 0; e < n_elements; ++e)
      if (!is_ground(e) && !adj[e].empty()) roots.push_back(e);
    const size_t first = m.merge_edges.size();
    for (int r : roots)
      if (!visited[r]) visit(r, -1);
    // reorder [first, end) into post-order (children first): reverse of pre-order works for a tree
    std::vector<MergeEdge> pre(m.merge_edges.begin() + first, m.merge_edges.end());
    const int count = static_cast<int>(pre.size());
    std::vector<int> newpos(count);
    for (int k = 0; k < count; ++k) newpos[k] = count - 1 - k;
    for (int k = 0; k < count; ++k) {
      MergeEdge e = pre[k];
      for (int& ce : e.child_edges) ce = static_cast<int>(first) + newpos[ce - first];
      m.merge_edges[first + newpos[k]] = e;
    }
  };

  std::vector<std::array<int, 2>> merged_pairs;
  std::vector<int> merged_reactions;
  for (size_t k = 0; k < flat.revolutes.size(); ++k) {
    const auto& j = flat.revolutes[k];
    const std::string name = j.prefix + j.def.name;
    const auto [ea, eb] = revolute_elements[k];
    const int reaction = m.n_reactions();
    m.reactions.push_back({name + ".Fx", -1, -1});
    m.reactions.push_back({name + ".Fy", -1, -1});
    if (revolute_merged[k]) {
      merged_pairs.push_back({ea, eb});
      merged_reactions.push_back(reaction);
    } else {
      Constraint c;
      c.kind = ConstraintKind::revolute;
      c.name = name;
      c.owner = j.owner;
      c.a = node_ref(ea);
      c.b = node_ref(eb);
      c.body1 = element_body[ea];
      c.body2 = element_body[eb];
      const int ci = add_constraint(std::move(c), 2, 2, {".x", ".y"}, {".vx", ".vy"});
      m.reactions[reaction].row = m.constraints[ci].row1;
      m.reactions[reaction + 1].row = m.constraints[ci].row1 + 1;
    }
    if (j.def.actuated) {
      Input in;
      in.label = name + ".torque";
      in.joint = name;
      const int b1 = element_body[ea], b2 = element_body[eb];
      for (auto [body, sgn] : {std::pair{b2, 1.0}, std::pair{b1, -1.0}}) {
        if (body < 0) continue;
        if (!m.bodies[body].has_omega)
          throw Error("actuated revolute joint '" + name + "': body '" + m.bodies[body].name +
                          "' has no rotation (a one-node body without inertia)",
                      name);
        in.terms.push_back({detail::ref_w(m, m.bodies[body].omega), sgn});
      }
      m.inputs.push_back(std::move(in));
    }
  }
  build_edges(
      E, merged_pairs, merged_reactions, [&](int e) { return element_body[e]; },
      [&](int e) { return 2 * element_local[e]; }, [&](int e) { return element_body[e] < 0; },
      false);

  std::vector<std::array<int, 2>> rot_pairs;
  std::vector<int> rot_reactions;
  for (size_t k = 0; k < flat.prismatics.size(); ++k) {
    const auto& j = flat.prismatics[k];
    const PrismaticInfo& p = pinfo[k];
    const std::string name = j.prefix + j.def.name;
    Constraint c;
    c.kind = ConstraintKind::prismatic;
    c.name = name;
    c.owner = j.owner;
    c.i = node_ref(p.ei);
    c.j = node_ref(p.ej);
    c.s = node_ref(p.es);
    c.q = prismatic_q[k];
    c.length = (element_pos[p.ej] - element_pos[p.ei]).norm();
    c.body1 = p.body1;
    c.body2 = p.body2;
    const bool oriented1 = p.body1 < 0 || m.bodies[p.body1].nodes.size() >= 2;
    const bool oriented2 = p.body2 < 0 || m.bodies[p.body2].nodes.size() >= 2;
    c.lock_position = p.lock && oriented1 && oriented2;
    c.lock_velocity = p.lock && !p.merged;
    if (p.lock) {
      c.w1 = p.body1 < 0 ? OmegaRef{} : m.bodies[p.body1].omega;
      c.w2 = p.body2 < 0 ? OmegaRef{} : m.bodies[p.body2].omega;
    }
    if (c.lock_position) {
      auto th = [&](int body) {
        if (body < 0) return 0.0;
        const Vec2 d = m.bodies[body].geometry[1] - m.bodies[body].geometry[0];
        return std::atan2(d.y(), d.x());
      };
      c.lock_angle = th(p.body2) - th(p.body1);
    }
    std::vector<std::string> l0{".x", ".y"}, l1{".vx", ".vy"};
    if (c.lock_position) l0.push_back(".angle");
    if (c.lock_velocity) l1.push_back(".w");
    const int nr0 = 2 + (c.lock_position ? 1 : 0), nr1 = 2 + (c.lock_velocity ? 1 : 0);
    const int ci = add_constraint(std::move(c), nr0, nr1, l0, l1);
    const int reaction = m.n_reactions();
    m.reactions.push_back({name + ".Fx", m.constraints[ci].row1, -1});
    m.reactions.push_back({name + ".Fy", m.constraints[ci].row1 + 1, -1});
    m.tree[j.owner].vars.push_back(prismatic_q[k]);
    if (p.lock) {
      m.reactions.push_back({name + ".T", p.merged ? -1 : m.constraints[ci].row1 + 2, -1});
      if (p.merged) {
        rot_pairs.push_back({p.body1 + 1, p.body2 + 1});
        rot_reactions.push_back(reaction + 2);
      }
    }
    if (j.def.actuated)
      m.inputs.push_back({name + ".force", name, {{VarRef{prismatic_q[k], -1, -1}, 1.0}}});
  }
  build_edges(
      NB + 1, rot_pairs, rot_reactions, [&](int e) { return e - 1; },
      [&](int e) { return e == 0 ? -1 : m.bodies[e - 1].slots() - 1; },
      [&](int e) { return e == 0; }, true);

  for (size_t k = 0; k < flat.slots.size(); ++k) {
    const auto& j = flat.slots[k];
    const SlotInfo& p = sinfo[k];
    const std::string name = j.prefix + j.def.name;
    Constraint c;
    c.kind = ConstraintKind::slot;
    c.name = name;
    c.owner = j.owner;
    c.i = node_ref(p.ei);
    c.j = node_ref(p.ej);
    c.s = node_ref(p.es);
    c.q = slot_q[k];
    c.length = (element_pos[p.ej] - element_pos[p.ei]).norm();
    c.body1 = p.body1;
    c.body2 = p.body2;
    const int ci = add_constraint(std::move(c), 2, 2, {".x", ".y"}, {".vx", ".vy"});
    m.reactions.push_back({name + ".Fx", m.constraints[ci].row1, -1});
    m.reactions.push_back({name + ".Fy", m.constraints[ci].row1 + 1, -1});
    m.tree[j.owner].vars.push_back(slot_q[k]);
    if (j.def.actuated_slide)
      m.inputs.push_back({name + ".force", name, {{VarRef{slot_q[k], -1, -1}, 1.0}}});
    if (j.def.actuated_rotation) {
      Input in;
      in.label = name + ".torque";
      in.joint = name;
      for (auto [body, sgn] : {std::pair{p.body2, 1.0}, std::pair{p.body1, -1.0}}) {
        if (body < 0) continue;
        if (!m.bodies[body].has_omega)
          throw Error("pin-in-slot joint '" + name + "': torque on body '" + m.bodies[body].name +
                          "', which has no rotation",
                      name);
        in.terms.push_back({detail::ref_w(m, m.bodies[body].omega), sgn});
      }
      m.inputs.push_back(std::move(in));
    }
  }

  // initial configuration, as given (assembly below makes it consistent)
  Eigen::VectorXd q0 = Eigen::VectorXd::Zero(m.n0);
  for (int e = 0; e < E; ++e) {
    const int r = nodes_uf.find(e);
    if (r == e && group_var[r] >= 0) q0.segment<2>(group_var[r]) = element_pos[e];
  }
  for (size_t k = 0; k < pinfo.size(); ++k) {
    const Vec2 pi = element_pos[pinfo[k].ei], pj = element_pos[pinfo[k].ej];
    q0[prismatic_q[k]] = (element_pos[pinfo[k].es] - pi).dot((pj - pi).normalized());
  }
  for (size_t k = 0; k < sinfo.size(); ++k) {
    const Vec2 pi = element_pos[sinfo[k].ei], pj = element_pos[sinfo[k].ej];
    q0[slot_q[k]] = (element_pos[sinfo[k].es] - pi).dot((pj - pi).normalized());
  }

  // owned variables of the tree (node groups and rotations: owner of their first body)
  for (int v = 0; v < m.n1; ++v) {
    const VarRef& r = m.rate_refs[v];
    if (r.body >= 0) m.tree[m.bodies[r.body].owner].vars.push_back(v);
  }

  auto find_coordinate = [&](const std::string& prefix, const std::string& label,
                             const std::string& what) {
    auto it = m.coordinate_index.find(prefix + label);
    if (it != m.coordinate_index.end()) return it->second;
    if (fixed_labels.count(prefix + label))
      throw Error(what + ": coordinate '" + prefix + label + "' is fixed (joined to the ground)",
                  prefix + label);
    std::vector<std::string> names;
    for (const auto& [k, v] : m.coordinate_index) names.push_back(k);
    throw Error(what + ": unknown coordinate '" + prefix + label + "'" +
                    did_you_mean(prefix + label, names),
                prefix + label);
  };
  auto find_rate = [&](const std::string& prefix, const std::string& label,
                       const std::string& what) {
    auto it = m.rate_index.find(prefix + label);
    if (it != m.rate_index.end()) return it->second;
    std::vector<std::string> names;
    for (const auto& [k, v] : m.rate_index) names.push_back(k);
    throw Error(what + ": unknown quasi-velocity '" + prefix + label + "'" +
                    did_you_mean(prefix + label, names),
                prefix + label);
  };

  for (size_t k = 0; k < flat.coordinates.size(); ++k) {
    const auto& cd = flat.coordinates[k];
    const std::string name = cd.prefix + cd.def.name;
    const std::string what = "coordinate '" + name + "'";
    if (cd.def.rate.empty()) throw Error(what + " has no rate terms", name);
    Constraint c;
    c.kind = ConstraintKind::coordinate;
    c.name = name;
    c.owner = cd.owner;
    c.coord = coord_var[k];
    double implied = 0;
    for (const auto& [label, w] : cd.def.rate) {
      if (!std::isfinite(w)) throw Error(what + ": non-finite weight for '" + label + "'", name);
      const int v = find_rate(cd.prefix, label, what);
      if (v == c.coord) throw Error(what + " is defined by its own rate", name);
      c.rate_terms.push_back({m.rate_refs[v], w});
      if (v < m.n0) {
        c.coord_terms.push_back({v, w});
        implied += w * q0[v];
      } else {
        const int body = m.rate_refs[v].body;
        if (m.bodies[body].nodes.size() < 2 || !is_integer(w)) {
          c.holonomic = false;
        } else {
          c.angle_terms.push_back({body, w});
          const Vec2 d = m.bodies[body].geometry[1] - m.bodies[body].geometry[0];
          implied += w * std::atan2(d.y(), d.x());
        }
      }
    }
    if (!c.holonomic) {
      c.coord_terms.clear();
      c.angle_terms.clear();
    }
    if (cd.def.initial && !std::isfinite(*cd.def.initial))
      throw Error(what + ": initial value is not finite", name);
    q0[c.coord] = cd.def.initial.value_or(implied);
    c.offset = q0[c.coord] - implied;
    const bool hol = c.holonomic;
    m.tree[cd.owner].vars.push_back(coord_var[k]);
    add_constraint(std::move(c), hol ? 1 : 0, 1, {""}, {".rate"});
  }

  for (const auto& pc : flat.pos) {
    const std::string name = pc.prefix + pc.def.name;
    const std::string what = "constraint '" + name + "'";
    if (!pc.def.psi) throw Error(what + " has no function", name);
    if (pc.def.args.size() > static_cast<size_t>(detail::kMaxUserArgs))
      throw Error(what + " has more than 32 arguments", name);
    Constraint c;
    c.kind = ConstraintKind::user_position;
    c.name = name;
    c.owner = pc.owner;
    c.psi = pc.def.psi;
    for (const auto& a : pc.def.args)
      c.args.push_back(m.rate_refs[find_coordinate(pc.prefix, a, what)]);
    const int ci = add_constraint(std::move(c), 1, 1, {""}, {".rate"});
    m.reactions.push_back({name + ".lambda", m.constraints[ci].row1, 1});
  }
  for (const auto& vc : flat.vel) {
    const std::string name = vc.prefix + vc.def.name;
    const std::string what = "constraint '" + name + "'";
    if (!vc.def.g) throw Error(what + " has no function", name);
    if (vc.def.coords.size() > static_cast<size_t>(detail::kMaxUserArgs) ||
        vc.def.rates.size() > static_cast<size_t>(detail::kMaxUserArgs))
      throw Error(what + " has more than 32 arguments", name);
    Constraint c;
    c.kind = ConstraintKind::user_velocity;
    c.name = name;
    c.owner = vc.owner;
    c.g = vc.def.g;
    for (const auto& a : vc.def.coords)
      c.args.push_back(m.rate_refs[find_coordinate(vc.prefix, a, what)]);
    for (const auto& a : vc.def.rates)
      c.rates.push_back(m.rate_refs[find_rate(vc.prefix, a, what)]);
    const int ci = add_constraint(std::move(c), 0, 1, {}, {""});
    m.reactions.push_back({name + ".lambda", m.constraints[ci].row1, 1});
  }

  // ---- loads -----------------------------------------------------------------------------------
  auto find_body = [&](const std::string& prefix, const std::string& name,
                       const std::string& what) {
    for (int bi = 0; bi < NB; ++bi)
      if (m.bodies[bi].name == prefix + name) return bi;
    std::vector<std::string> names;
    for (const auto& b : m.bodies) names.push_back(b.name);
    throw Error(
        what + ": unknown body '" + prefix + name + "'" + did_you_mean(prefix + name, names),
        prefix + name);
  };
  for (const auto& f : flat.forces) {
    const std::string what = "force '" + f.prefix + f.def.name + "'";
    PointLoad l;
    l.name = f.prefix + f.def.name;
    l.body = find_body(f.prefix, f.def.body, what);
    const Body& b = m.bodies[l.body];
    if (b.nodes.size() >= 2) {
      const Vec2 dd = b.geometry[1] - b.geometry[0], r = f.def.point - b.geometry[0];
      l.ci = 0;
      l.cj = 1;
      l.gamma = r.dot(dd) / dd.squaredNorm();
      l.rho = r.dot(perp(dd)) / dd.squaredNorm();
    } else if ((f.def.point - b.geometry[0]).norm() > 1e-12 * m.scale) {
      throw Error(what + ": body '" + b.name + "' has one node: the force must act at it", l.name);
    }
    l.fx = f.def.fx;
    l.fy = f.def.fy;
    m.forces.push_back(std::move(l));
  }
  for (const auto& t : flat.torques) {
    const std::string what = "torque '" + t.prefix + t.def.name + "'";
    TorqueLoad l;
    l.name = t.prefix + t.def.name;
    l.body = find_body(t.prefix, t.def.body, what);
    if (!m.bodies[l.body].has_omega)
      throw Error(what + ": body '" + m.bodies[l.body].name + "' has no rotation", l.name);
    l.torque = t.def.torque;
    m.torques.push_back(std::move(l));
  }

  // ---- springs
  // -----------------------------------------------------------------------------------
  auto body_point = [&](const std::string& prefix, const std::string& body, const Vec2& p,
                        const std::string& what) {
    BodyPoint bp;
    if (body == "ground") {
      bp.fixed = p;
      return bp;
    }
    bp.body = find_body(prefix, body, what);
    const Body& b = m.bodies[bp.body];
    if (b.geometry.size() >= 2) {
      const Vec2 dd = b.geometry[1] - b.geometry[0], r = p - b.geometry[0];
      bp.ci = 0;
      bp.cj = 1;
      bp.gamma = r.dot(dd) / dd.squaredNorm();
      bp.rho = r.dot(perp(dd)) / dd.squaredNorm();
    } else if ((p - b.geometry[0]).norm() > 1e-12 * m.scale) {
      throw Error(what + ": body '" + b.name + "' has one node: the point must be the node",
                  b.name);
    }
    return bp;
  };
  auto nonnegative = [](double v, const std::string& what, const char* field,
                        const std::string& el) {
    if (!std::isfinite(v) || v < 0)
      throw Error(what + ": " + field + " must be finite and >= 0 (got " + std::to_string(v) + ")",
                  el);
  };
  for (const auto& sp : flat.springs) {
    const std::string name = sp.prefix + sp.def.name;
    const std::string what = "spring '" + name + "'";
    check_name(sp.def.name, "spring");
    nonnegative(sp.def.rest_length, what, "rest_length", name);
    nonnegative(sp.def.stiffness, what, "stiffness", name);
    nonnegative(sp.def.damping, what, "damping", name);
    SpringLoad l;
    l.name = name;
    l.a = body_point(sp.prefix, sp.def.body_a, sp.def.point_a, what);
    l.b = body_point(sp.prefix, sp.def.body_b, sp.def.point_b, what);
    if (l.a.body < 0 && l.b.body < 0) throw Error(what + " joins two ground points", name);
    l.rest_length = sp.def.rest_length;
    l.stiffness = sp.def.stiffness;
    l.damping = sp.def.damping;
    m.springs.push_back(std::move(l));
  }
  for (const auto& ts : flat.torsional) {
    const std::string name = ts.prefix + ts.def.name;
    const std::string what = "torsional spring '" + name + "'";
    check_name(ts.def.name, "torsional spring");
    nonnegative(ts.def.stiffness, what, "stiffness", name);
    nonnegative(ts.def.damping, what, "damping", name);
    int found = -1;
    for (size_t k = 0; k < flat.revolutes.size(); ++k)
      if (flat.revolutes[k].prefix + flat.revolutes[k].def.name == ts.prefix + ts.def.joint)
        found = static_cast<int>(k);
    if (found < 0) {
      std::vector<std::string> names;
      for (const auto& j : flat.revolutes) names.push_back(j.prefix + j.def.name);
      throw Error(what + ": unknown revolute joint '" + ts.prefix + ts.def.joint + "'" +
                      did_you_mean(ts.prefix + ts.def.joint, names),
                  name);
    }
    TorsionalLoad l;
    l.name = name;
    l.body1 = element_body[revolute_elements[found][0]];
    l.body2 = element_body[revolute_elements[found][1]];
    auto angle0 = [&](int body) {
      if (body < 0) return 0.0;
      const Body& b = m.bodies[body];
      if (b.geometry.size() < 2)
        throw Error(what + ": body '" + b.name + "' has one node and no orientation", name);
      const Vec2 d = b.geometry[1] - b.geometry[0];
      return std::atan2(d.y(), d.x());
    };
    const double implied = angle0(l.body2) - angle0(l.body1);
    if (ts.def.rest && !std::isfinite(*ts.def.rest))
      throw Error(what + ": rest angle not finite", name);
    l.rest = ts.def.rest.value_or(implied);
    l.stiffness = ts.def.stiffness;
    l.damping = ts.def.damping;
    m.torsional_springs.push_back(std::move(l));
  }

  // aliases of rotation labels (bodies sharing a rotation) and input label uniqueness
  std::set<std::string> input_labels;
  for (const auto& in : m.inputs)
    if (!input_labels.insert(in.label).second)
      throw Error("input '" + in.label + "' is defined twice", in.label);

  m.q0 = q0;
  m.holonomic = true;
  for (const auto& c : m.constraints)
    if ((c.kind == ConstraintKind::coordinate && !c.holonomic) ||
        c.kind == ConstraintKind::user_velocity)
      m.holonomic = false;
  m.dof = m.n1 - m.m1;
  if (options.assemble) {
    check_memory("building '" + m.name + "' (assembly and rank checks)",
                 build_memory_bytes(m.n0, m.m0, m.n1, m.m1), options.max_memory, model_sizes(m),
                 "max_memory");
    try {
      m.q0 = assemble(m, q0, 0.0, {}, options.assembly_tolerance);
      check_constraint_ranks(m, m.q0, 0.0);
    } catch (const Error& e) {  // a build-time error: no run time
      throw Error(e.what(), e.element());
    }
  }
  return m;
}

}  // namespace mo2d
