// Stage 2 of build_model: validate every definition (errors name the element). Node elements and
// the mechanism's size, bodies with their constant mass data (Example 2.6), one namespace for
// joints, coordinates and constraints, the topology of revolute joints, and the checks of one
// joint that reduce runs joint by joint (the same error wins as when they were one loop).
#include <Eigen/Geometry>
#include <cmath>
#include <set>
#include <sstream>

#include "constraints/constraints.hpp"
#include "mo2d/error.hpp"
#include "model/build_stages.hpp"
#include "model/suggest.hpp"

namespace mo2d::build {
namespace {

using detail::perp;

std::string num(double v) {
  std::ostringstream s;
  s.precision(4);
  s << v;
  return s.str();
}
std::string point_str(const Vec2& p) {
  return std::string("(") + num(p.x()) + ", " + num(p.y()) + ")";
}

// The initial positions define each body's shape (its node distances and angles), so the copies
// of one joint node must coincide and a slider must lie on its axis: a gap is a contradiction in
// the definition, not an approximate position that assembly could fix. `size` is the
// mechanism's size (diagonal of the box around every node), the tolerance is relative to it.
// `detail()` words the gap, called only to throw (formatting positions costs a stream each).
template <class Detail>
void check_joint_gap(double gap, double size, double tolerance, const std::string& what,
                     const Detail& detail, const char* rule, const std::string& element) {
  if (!(gap > tolerance * size)) return;
  throw Error(what + ": " + detail() + " " + num(gap) + " m apart (" + num(gap / size) +
                  " of the mechanism's size " + num(size) + " m; tolerance " + num(tolerance) +
                  "): each body's node positions define its shape, so " + rule +
                  " in the initial configuration",
              element);
}

void add_element(Elements& el, const std::string& label, int body, int local, Vec2 p) {
  if (!el.index.emplace(label, static_cast<int>(el.label.size())).second)
    throw Error("node '" + label + "' is defined twice", label);
  el.label.push_back(label);
  el.body.push_back(body);
  el.local.push_back(local);
  el.position.push_back(p);
}

// Local index of node `node` of body `d`, for its centre of mass.
int com_node(const BodyDef& d, const std::string& node) {
  const int n = static_cast<int>(d.nodes.size());
  for (int k = 0; k < n; ++k)
    if (d.nodes[k].name == node) return k;
  std::vector<std::string> names;
  for (const auto& nd : d.nodes) names.push_back(nd.name);
  throw Error("body '" + d.name + "': centre of mass refers to unknown node '" + node + "'" +
                  did_you_mean(node, names),
              d.name);
}

// Centre of mass by local nodes: at node ci, or gamma, rho on nodes ci, cj (Example 2.6 (b)).
void place_centre_of_mass(const BodyDef& d, double scale, Body& b) {
  const int n = static_cast<int>(d.nodes.size());
  const CenterOfMass com = d.com.value_or(CenterOfMass::at_node(d.nodes[0].name));
  switch (com.kind) {
    case CenterOfMass::Kind::node:
      b.ci = com_node(d, com.node_i);
      break;
    case CenterOfMass::Kind::nodes:
      b.ci = com_node(d, com.node_i);
      b.cj = com_node(d, com.node_j);
      if (b.ci == b.cj)
        throw Error("body '" + d.name + "': centre of mass needs two different nodes", d.name);
      if (!std::isfinite(com.gamma) || !std::isfinite(com.rho))
        throw Error("body '" + d.name + "': centre of mass gamma/rho not finite", d.name);
      b.gamma = com.gamma;
      b.rho = com.rho;
      break;
    case CenterOfMass::Kind::point: {
      if (n < 2) {
        if ((com.point - b.geometry[0]).norm() > 1e-12 * scale)
          throw Error("body '" + d.name + "' has one node: its centre of mass must be the node",
                      d.name);
        break;
      }
      const Vec2 gr = on_first_two_nodes(b.geometry, com.point);
      b.ci = 0;
      b.cj = 1;
      b.gamma = gr.x();
      b.rho = gr.y();
      break;
    }
  }
}

Body make_body(const Owned<BodyDef>& owned, double scale) {
  const BodyDef& d = owned.def;
  Body b;
  b.name = d.name;
  b.owner = owned.owner;
  if (!std::isfinite(d.mass) || d.mass < 0)
    throw Error(
        "body '" + d.name + "': mass must be finite and >= 0 (got " + std::to_string(d.mass) + ")",
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
    if (b.l01 < 1e-9 * scale)
      throw Error("body '" + d.name +
                      "': its first two nodes coincide (a body needs two distinct "
                      "reference nodes)",
                  d.name);
    b.frame.assign(n, Vec2(0, 0));
    for (int k = 2; k < n; ++k) b.frame[k] = on_first_two_nodes(b.geometry, b.geometry[k]);
  }
  place_centre_of_mass(d, scale, b);
  return b;
}

// The words that differ between the two joints with an axis (prismatic, pin-in-slot).
struct AxisJointWords {
  const char* kind;        // "prismatic joint"
  const char* slider;      // the node that slides: "slider"
  const char* other_body;  // error when the slider is on the axis' body
  bool name_coinciding;    // the zero-length-axis error names the two nodes
};

// Distance of the slider (pin) from the line of its axis in the initial configuration, checked
// with every other condition of a joint with an axis.
AxisJoint check_axis_joint(const AxisJointWords& words, const std::string& prefix,
                           const std::string& name, const std::string& axis_from,
                           const std::string& axis_to, const std::string& slider,
                           const Elements& el, double joint_tolerance, double scale) {
  const std::string what = std::string(words.kind) + " '" + prefix + name + "'";
  AxisJoint p{};
  p.ei = el.resolve(prefix, axis_from, what);
  p.ej = el.resolve(prefix, axis_to, what);
  p.es = el.resolve(prefix, slider, what);
  p.body1 = el.body[p.ei];
  p.body2 = el.body[p.es];
  if (el.body[p.ej] != p.body1)
    throw Error(what + ": axis nodes must belong to the same body", prefix + name);
  if (p.body1 == p.body2) throw Error(what + ": " + words.other_body, prefix + name);
  if ((el.position[p.ej] - el.position[p.ei]).norm() < 1e-9 * scale)
    throw Error(what + ": zero-length axis" +
                    (words.name_coinciding
                         ? " (nodes '" + el.label[p.ei] + "' and '" + el.label[p.ej] + "' coincide)"
                         : std::string()),
                prefix + name);
  const Vec2 pi = el.position[p.ei], axis = (el.position[p.ej] - pi).normalized();
  const Vec2 r = el.position[p.es] - pi;
  const double gap = std::abs(axis.x() * r.y() - axis.y() * r.x());
  check_joint_gap(
      gap, el.size, joint_tolerance, what,
      [&] {
        return std::string("its ") + words.slider + " '" + el.label[p.es] + "' at " +
               point_str(el.position[p.es]) + " and the line of its axis '" + el.label[p.ei] +
               "' -> '" + el.label[p.ej] + "' are";
      },
      "a slider must lie on the line of its axis", prefix + name);
  return p;
}

constexpr AxisJointWords kPrismatic{
    "prismatic joint", "slider", "the slider node must belong to another body than the axis", true};
constexpr AxisJointWords kSlot{"pin-in-slot joint", "pin",
                               "the pin must belong to another body than the slot", false};

}  // namespace

Vec2 on_first_two_nodes(const std::vector<Vec2>& geometry, const Vec2& p) {
  const Vec2 dd = geometry[1] - geometry[0], r = p - geometry[0];
  return {r.dot(dd) / dd.squaredNorm(), r.dot(perp(dd)) / dd.squaredNorm()};
}

void check_name(const std::string& name, const std::string& what) {
  if (name.empty()) throw Error(what + " has an empty name", what);
  if (name.find('.') != std::string::npos || name.find(',') != std::string::npos ||
      name.find(' ') != std::string::npos)
    throw Error(what + " '" + name + "': names may not contain '.', ',' or spaces", name);
}

void check_gravity(const Vec2& gravity) {
  if (!std::isfinite(gravity.x()) || !std::isfinite(gravity.y()))
    throw Error("gravity is not finite", "gravity");
}

int Elements::resolve(const std::string& prefix, const std::string& ref,
                      const std::string& what) const {
  auto it = index.find(prefix + ref);
  if (it == index.end()) {
    std::vector<std::string> cands;
    for (const auto& [k, v] : index)
      if (k.compare(0, prefix.size(), prefix) == 0) cands.push_back(k.substr(prefix.size()));
    throw Error(what + ": node '" + prefix + ref + "' not found" + did_you_mean(ref, cands),
                what.substr(what.find('\'') + 1, what.rfind('\'') - what.find('\'') - 1));
  }
  return it->second;
}

Elements collect_elements(const Flat& flat, const BuildOptions& options, Model& m) {
  Elements el;
  const int G = static_cast<int>(flat.ground_names.size());
  for (int g = 0; g < G; ++g) add_element(el, flat.ground_names[g], -1, -1, flat.ground_pos[g]);
  std::set<std::string> body_names;
  for (size_t bi = 0; bi < flat.bodies.size(); ++bi) {
    const BodyDef& d = flat.bodies[bi].def;
    if (!body_names.insert(d.name).second)
      throw Error("body '" + d.name + "' is defined twice", d.name);
    if (d.nodes.empty()) throw Error("body '" + d.name + "' has no nodes", d.name);
    for (size_t k = 0; k < d.nodes.size(); ++k)
      add_element(el, d.name + "." + d.nodes[k].name, static_cast<int>(bi), static_cast<int>(k),
                  d.nodes[k].position);
    for (const auto& n : d.nodes)
      if (!std::isfinite(n.position.x()) || !std::isfinite(n.position.y()))
        throw Error("node '" + d.name + "." + n.name + "' has a non-finite position", d.name);
  }
  const int E = el.count();

  // scale: size of the mechanism
  Eigen::AlignedBox2d box;
  for (const auto& p : el.position) box.extend(p);
  el.size = E > 0 ? box.diagonal().norm() : 0.0;  // for the joint checks, dimensionless
  m.scale = E > 0 ? std::max(el.size, 1e-3) : 1.0;
  if (!(options.joint_tolerance >= 0) || !std::isfinite(options.joint_tolerance))
    throw Error("BuildOptions::joint_tolerance must be finite and >= 0", "joint_tolerance");
  return el;
}

void add_bodies(const Flat& flat, Model& m) {
  for (const auto& owned : flat.bodies) m.bodies.push_back(make_body(owned, m.scale));
  for (auto& b : m.bodies) {
    b.offset = m.n_slots;
    m.n_slots += b.slots();
  }
}

void check_names(const Flat& flat) {
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
  for (const auto& g : flat.gears) claim(g.prefix + g.def.name, "gear");
  for (const auto& r : flat.racks) claim(r.prefix + r.def.name, "rack");
  for (const auto& c : flat.pos) claim(c.prefix + c.def.name, "constraint");
  for (const auto& c : flat.vel) claim(c.prefix + c.def.name, "constraint");
}

void check_revolute_topology(const Flat& flat, const Elements& el) {
  UnionFind topo(el.count());
  for (const auto& j : flat.revolutes) {
    const std::string what = "revolute joint '" + j.prefix + j.def.name + "'";
    const int ea = el.resolve(j.prefix, j.def.node_a, what);
    const int eb = el.resolve(j.prefix, j.def.node_b, what);
    const int ra = topo.find(ea), rb = topo.find(eb);
    if (ra == rb && ea != eb)
      throw Error(what + " is redundant: its nodes are already joined by other revolute joints",
                  j.prefix + j.def.name);
    if (el.body[ra] < 0 && el.body[rb] < 0 && ra != rb)
      throw Error(what + " connects two ground nodes ('" + el.label[ra] + "' and '" + el.label[rb] +
                      "'): conflicting constraints",
                  j.prefix + j.def.name);
    if (el.body[rb] < 0)
      topo.parent[ra] = rb;
    else
      topo.parent[rb] = ra;
  }
}

std::array<int, 2> check_revolute(const Owned<RevoluteDef>& j, const Elements& el,
                                  double joint_tolerance) {
  const std::string what = "revolute joint '" + j.prefix + j.def.name + "'";
  const int ea = el.resolve(j.prefix, j.def.node_a, what);
  const int eb = el.resolve(j.prefix, j.def.node_b, what);
  const int ba = el.body[ea], bb = el.body[eb];
  if (ba < 0 && bb < 0) throw Error(what + " joins two ground nodes", j.prefix + j.def.name);
  if (ba == bb) throw Error(what + " joins two nodes of the same body", j.prefix + j.def.name);
  check_joint_gap((el.position[eb] - el.position[ea]).norm(), el.size, joint_tolerance, what,
                  [&] {
                    return "its nodes '" + el.label[ea] + "' at " + point_str(el.position[ea]) +
                           " and '" + el.label[eb] + "' at " + point_str(el.position[eb]) + " are";
                  },
                  "the two copies of a joint node must coincide", j.prefix + j.def.name);
  return {ea, eb};
}

AxisJoint check_prismatic(const Owned<PrismaticDef>& j, const Elements& el, double joint_tolerance,
                          double scale) {
  return check_axis_joint(kPrismatic, j.prefix, j.def.name, j.def.axis_from, j.def.axis_to,
                          j.def.slider, el, joint_tolerance, scale);
}

AxisJoint check_slot(const Owned<PinInSlotDef>& j, const Elements& el, double joint_tolerance,
                     double scale) {
  return check_axis_joint(kSlot, j.prefix, j.def.name, j.def.axis_from, j.def.axis_to, j.def.pin,
                          el, joint_tolerance, scale);
}

}  // namespace mo2d::build
