// Stage 1 of build_model: flatten the tree of subsystems (Orsino, Theorem 2.10). Every definition
// is copied with its owner (the subsystem tree node) and its instance prefix; names are prefixed
// by the instance path and positions are placed in the world frame by composing the placements of
// the enclosing instances. Names are checked here, where each is seen in its own system.
#include <cmath>
#include <set>

#include "mo2d/error.hpp"
#include "model/build_stages.hpp"
#include "model/suggest.hpp"

namespace mo2d::build {
namespace {

struct Frame {  // world = R p + o
  double angle = 0;
  Vec2 offset{0, 0};
  Vec2 apply(const Vec2& p) const { return Placement{offset, angle}.apply(p); }
  Frame compose(const Placement& child) const {  // this o child
    return {angle + child.angle, apply(child.offset)};
  }
};

void flatten_bodies(const System& s, const std::string& prefix, const Frame& frame, int tree_index,
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
    // a body given by its shape keeps its centre-of-mass point in its own frame (sketch.cpp)
    if (w.com && w.com->kind == CenterOfMass::Kind::point && w.shape.empty())
      w.com->point = frame.apply(w.com->point);
    w.name = prefix + b.name;
    out.bodies.push_back({std::move(w), tree_index, prefix});
  }
}

// The axis body of a rack's slide ("ground" too): the body of its axis_from node "body.node".
std::string rack_carrier(const System& s, const RackDef& r) {
  auto body_of = [](const std::string& node) { return node.substr(0, node.rfind('.')); };
  for (const auto& j : s.prismatics())
    if (j.name == r.slide) return body_of(j.axis_from);
  for (const auto& j : s.slots())
    if (j.name == r.slide) return body_of(j.axis_from);
  throw Error("rack '" + r.name + "': unknown slide '" + r.slide +
                  "' (a prismatic or pin-in-slot joint of the same system)",
              r.name);
}

// A gear or a rack with its carrier-relative angle phi: an extra coordinate "name.phi",
// d/dt phi = omega_k - omega_c (holonomic: integer weights), that its rows read (gears.cpp). The
// carrier of a rack is its slide's axis body.
void flatten_gears(const System& s, const std::string& prefix, int tree_index, Flat& out) {
  for (const auto& g : s.gears()) {
    check_name(g.name, "gear");
    CoordinateDef phi{.name = g.name + ".phi", .rate = {{g.driver + ".w", 1.0}}};
    if (g.carrier != "ground") phi.rate.emplace_back(g.carrier + ".w", -1.0);
    out.coordinates.push_back({std::move(phi), tree_index, prefix});
    out.gears.push_back({g, tree_index, prefix});
  }
  for (const auto& r : s.racks()) {
    check_name(r.name, "rack");
    CoordinateDef phi{.name = r.name + ".phi", .rate = {{r.pinion + ".w", 1.0}}};
    const std::string carrier = rack_carrier(s, r);
    if (carrier != "ground") phi.rate.emplace_back(carrier + ".w", -1.0);
    out.coordinates.push_back({std::move(phi), tree_index, prefix});
    out.racks.push_back({r, tree_index, prefix});
  }
}

void flatten_joints(const System& s, const std::string& prefix, int tree_index, Flat& out) {
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
  flatten_gears(s, prefix, tree_index, out);
  for (const auto& c : s.position_constraints()) {
    check_name(c.name, "constraint");
    out.pos.push_back({c, tree_index, prefix});
  }
  for (const auto& c : s.velocity_constraints()) {
    check_name(c.name, "constraint");
    out.vel.push_back({c, tree_index, prefix});
  }
}

void flatten_loads(const System& s, const std::string& prefix, const Frame& frame, int tree_index,
                   Flat& out) {
  for (const auto& f : s.forces()) {
    ForceDef w = f;
    w.point = frame.apply(f.point);
    out.forces.push_back({std::move(w), tree_index, prefix});
    out.force_angle.push_back(frame.angle);  // the components are rotated where they are applied
  }
  for (const auto& t : s.torques()) out.torques.push_back({t, tree_index, prefix});
  for (const auto& sp : s.springs()) {
    SpringDef w = sp;
    w.point_a = frame.apply(sp.point_a);
    w.point_b = frame.apply(sp.point_b);
    out.springs.push_back({std::move(w), tree_index, prefix});
  }
  for (const auto& ts : s.torsional_springs()) out.torsional.push_back({ts, tree_index, prefix});
  for (const auto& fr : s.frictions()) out.frictions.push_back({fr, tree_index, prefix});
  for (const auto& p : s.points()) {
    PointDef w = p;
    w.point = frame.apply(p.point);
    out.points.push_back({std::move(w), tree_index, prefix});
  }
}

// A chain's sprocket body: "ground", or a body of this System with a rotation (its angle is
// read through the coordinate "name.theta_a" or "name.theta_b", d/dt = the body's rate).
void check_sprocket(const System& s, const ChainDef& c, const std::string& body, const char* key) {
  const std::string what = "chain '" + c.name + "'." + key;
  if (body == "ground") return;
  std::vector<std::string> names{"ground"};
  for (const auto& b : s.bodies()) {
    if (b.name != body) {
      names.push_back(b.name);
      continue;
    }
    if (b.nodes.size() < 2 && !(b.inertia > 0))
      throw Error(what + ": body '" + body +
                      "' has no rotation (a point mass: give it two nodes or an inertia)",
                  c.name);
    return;
  }
  throw Error(what + ": unknown body '" + body + "'" + did_you_mean(body, names), c.name);
}

// Chains: centres to world, and the unwrapped angle of each turning sprocket as a coordinate.
void flatten_chains(const System& s, const std::string& prefix, const Frame& frame, int tree_index,
                    Flat& out) {
  for (const auto& c : s.chains()) {
    check_name(c.name, "chain");
    check_sprocket(s, c, c.body_a, "body_a");
    check_sprocket(s, c, c.body_b, "body_b");
    ChainDef w = c;
    w.centre_a = frame.apply(c.centre_a);
    w.centre_b = frame.apply(c.centre_b);
    for (const auto& [body, suffix] : {std::pair{c.body_a, ".theta_a"}, {c.body_b, ".theta_b"}})
      if (body != "ground")
        out.coordinates.push_back(
            {CoordinateDef{.name = c.name + suffix, .rate = {{body + ".w", 1.0}}}, tree_index,
             prefix});
    out.chains.push_back({std::move(w), tree_index, prefix});
  }
}

void flatten(const System& s, const std::string& prefix, const Frame& frame, int tree_index,
             Flat& out) {
  flatten_bodies(s, prefix, frame, tree_index, out);
  flatten_joints(s, prefix, tree_index, out);
  flatten_loads(s, prefix, frame, tree_index, out);
  flatten_chains(s, prefix, frame, tree_index, out);
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
    const Frame child_frame = frame.compose(inst.placement);
    out.frames.push_back({child_frame.offset, child_frame.angle});
    flatten(*inst.system, prefix + inst.name + ".", child_frame, child, out);
  }
}

}  // namespace

Flat flatten(const System& system) {
  Flat flat;
  flat.tree.push_back({"", -1, {}, {}, {}});
  flat.frames.push_back({});
  flatten(system, "", Frame{}, 0, flat);
  return flat;
}

}  // namespace mo2d::build
