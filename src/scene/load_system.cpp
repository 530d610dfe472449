// One system block of a scene -> System (keys: docs/scene-format.md, "System blocks").
#include "load_system.hpp"

#include <algorithm>

#include "mo2d/sketched_body.hpp"
#include "model/suggest.hpp"

namespace mo2d::scene_detail {

namespace {

struct Context {
  const Reader& r;
  System& out;
  SystemInfo info{};
  std::vector<std::string> revolutes{};
};

void check_node(const Context& c, const YAML::Node& node, const std::string& what) {
  const std::string label = c.r.string(node, what);
  if (std::find(c.info.nodes.begin(), c.info.nodes.end(), label) == c.info.nodes.end())
    c.r.fail(node, what + ": undefined node '" + label + "'" + did_you_mean(label, c.info.nodes) +
                       " (nodes are written body.node or ground.node)");
}

std::string node_ref(const Context& c, const YAML::Node& map, const char* key,
                     const std::string& what) {
  const YAML::Node n = c.r.required(map, key, what);
  check_node(c, n, what + "." + key);
  return n.Scalar();
}

std::string body_ref(const Context& c, const YAML::Node& map, const char* key,
                     const std::string& what, bool ground_allowed) {
  const YAML::Node n = c.r.required(map, key, what);
  std::string name = c.r.string(n, what + "." + key);
  if (ground_allowed && name == "ground") return name;
  if (std::find(c.info.bodies.begin(), c.info.bodies.end(), name) == c.info.bodies.end())
    c.r.fail(n, what + "." + key + ": undefined body '" + name + "'" +
                    did_you_mean(name, c.info.bodies));
  return name;
}

void check_plain_name(const Reader& r, const YAML::Node& key, const std::string& what) {
  const std::string& s = key.Scalar();
  if (s.find_first_of(".,: \t") != std::string::npos)
    r.fail(key, what + " '" + s + "': names may not contain '.', ',', ':' or spaces");
  if (s == "ground" && what != "ground node")
    r.fail(key, what + ": 'ground' is reserved for the base body");
}

void read_ground(Context& c, const YAML::Node& node) {
  for (const auto& [key, value] : c.r.entries(node, "ground")) {
    check_plain_name(c.r, key, "ground node");
    const std::string name = key.Scalar();
    c.out.add_ground_node(name, c.r.vec2(value, "ground." + name));
    c.info.nodes.push_back("ground." + name);
  }
}

CenterOfMass read_com(const Reader& r, const YAML::Node& node, const BodyDef& b,
                      const std::string& what) {
  std::vector<std::string> local;
  for (const auto& n : b.nodes) local.push_back(n.name);
  auto check_local = [&](const YAML::Node& n, const std::string& w) {
    std::string name = r.string(n, w);
    if (std::find(local.begin(), local.end(), name) == local.end())
      r.fail(n,
             w + ": body '" + b.name + "' has no node '" + name + "'" + did_you_mean(name, local));
    return name;
  };
  if (node.IsScalar()) return CenterOfMass::at_node(check_local(node, what));
  r.check_keys(node, {"node", "between", "gamma", "rho", "point"}, what);
  const int given =
      node["node"].IsDefined() + node["between"].IsDefined() + node["point"].IsDefined();
  if (given != 1) r.fail(node, what + ": give exactly one of 'node', 'between' or 'point'");
  if (node["node"].IsDefined())
    return CenterOfMass::at_node(check_local(node["node"], what + ".node"));
  if (node["point"].IsDefined())
    return CenterOfMass::at_point(r.vec2(node["point"], what + ".point"));
  const YAML::Node between = node["between"];
  if (!between.IsSequence() || between.size() != 2)
    r.fail(between, what + ".between: expected two node names [i, j]");
  return CenterOfMass::between(
      check_local(between[0], what + ".between"), check_local(between[1], what + ".between"),
      r.number_or(node, "gamma", 0.5, what), r.number_or(node, "rho", 0.0, what));
}

// `nodes`: the node positions (exact, or the sketch of a body given by its shape).
void read_nodes(const Reader& r, const YAML::Node& value, BodyDef& b, const std::string& what) {
  const YAML::Node nodes = r.required(value, "nodes", what);
  const Entries entries = r.entries(nodes, what + ".nodes");
  if (entries.empty()) r.fail(nodes, what + ".nodes: a body needs at least one node");
  for (const auto& [nk, nv] : entries) {
    check_plain_name(r, nk, "node");
    b.nodes.push_back({nk.Scalar(), r.vec2(nv, what + ".nodes." + nk.Scalar())});
  }
}

// `shape` (node coordinates in the body's frame) with its sketch: `nodes` (the same nodes in the
// same order, at approximate positions) or `at` (an approximate placement of the shape).
void read_shape(const Reader& r, const YAML::Node& value, BodyDef& b, const std::string& what) {
  const YAML::Node shape = value["shape"];
  std::vector<std::string> names;
  for (const auto& [nk, nv] : r.entries(shape, what + ".shape")) {
    check_plain_name(r, nk, "node");
    names.push_back(nk.Scalar());
    b.shape.push_back(r.vec2(nv, what + ".shape." + nk.Scalar()));
  }
  if (names.empty()) r.fail(shape, what + ".shape: a body needs at least one node");
  const YAML::Node at = value["at"];
  if (!at.IsDefined()) {
    read_nodes(r, value, b, what);
    std::string order;
    for (const auto& n : names) order += (order.empty() ? "" : ", ") + n;
    const Entries entries = r.entries(value["nodes"], what + ".nodes");
    for (size_t k = 0; k < std::max(names.size(), entries.size()); ++k)
      if (k >= names.size() || k >= entries.size() || entries[k].first.Scalar() != names[k])
        r.fail(k < entries.size() ? entries[k].first : value["nodes"],
               what +
                   ".nodes: the sketch of a body given by its shape lists the shape's nodes in "
                   "the same order (" +
                   order + ")");
    return;
  }
  if (value["nodes"].IsDefined())
    r.fail(at, what + ".at: give the sketch either as 'nodes' or as 'at', not both");
  r.check_keys(at, {"origin", "angle"}, what + ".at");
  const Placement placement{r.vec2(r.required(at, "origin", what + ".at"), what + ".at.origin"),
                            r.number_or(at, "angle", 0.0, what + ".at")};
  std::vector<NodeDef> sketched;  // the sketch from the placement: mo2d/sketched_body.hpp
  for (size_t k = 0; k < names.size(); ++k) sketched.push_back({names[k], b.shape[k]});
  b = placed_body(b.name, std::move(sketched), placement);
}

// The geometry of a body: exact `nodes`, or `shape` / `length` with a sketch.
void read_geometry(const Reader& r, const YAML::Node& value, BodyDef& b, const std::string& what) {
  const YAML::Node length = value["length"];
  if (value["shape"].IsDefined()) {
    if (length.IsDefined()) r.fail(length, what + ": give either 'shape' or 'length', not both");
    read_shape(r, value, b, what);
    return;
  }
  if (value["at"].IsDefined())
    r.fail(value["at"],
           what + ".at: places a body given by its 'shape'" +
               std::string(length.IsDefined() ? " (a bar given by 'length' is sketched by its two "
                                                "'nodes')"
                                              : ""));
  read_nodes(r, value, b, what);
  if (!length.IsDefined()) return;
  if (b.nodes.size() != 2)
    r.fail(length, what +
                       ".length: a bar given by its length has exactly two nodes (the first at "
                       "(0, 0), the second at (length, 0) in its frame)");
  const double l = r.number(length, what + ".length");
  if (!(l > 0)) r.fail(length, what + ".length: a length must be > 0 m");
  b = bar_body(b.name, l, b.nodes[0], b.nodes[1]);  // mo2d/sketched_body.hpp
}

void read_bodies(Context& c, const YAML::Node& node) {
  const Reader& r = c.r;
  for (const auto& [key, value] : r.entries(node, "bodies")) {
    check_plain_name(r, key, "body");
    const std::string what = "body '" + key.Scalar() + "'";
    r.check_keys(value, {"nodes", "shape", "length", "at", "mass", "inertia", "com"}, what);
    BodyDef b;
    b.name = key.Scalar();
    read_geometry(r, value, b, what);
    const YAML::Node mass = r.required(value, "mass", what);
    b.mass = r.number(mass, what + ".mass");
    if (b.mass < 0) r.fail(mass, what + ".mass: a mass must be >= 0 kg");
    if (value["inertia"].IsDefined()) {
      b.inertia = r.number(value["inertia"], what + ".inertia");
      if (b.inertia < 0)
        r.fail(value["inertia"], what + ".inertia: an inertia must be >= 0 kg m^2");
    }
    if (value["com"].IsDefined()) b.com = read_com(r, value["com"], b, what + ".com");
    for (const auto& n : b.nodes) c.info.nodes.push_back(b.name + "." + n.name);
    c.info.bodies.push_back(b.name);
    c.info.elements.emplace_back(b.name, r.at(key));
    c.out.add_body(std::move(b));
  }
}

void read_joints(Context& c, const YAML::Node& node) {
  const Reader& r = c.r;
  for (const auto& [key, value] : r.entries(node, "joints")) {
    check_plain_name(r, key, "joint");
    const std::string name = key.Scalar();
    const std::string what = "joint '" + name + "'";
    if (!value.IsMap()) r.fail(value, what + ": expected a map, got " + type_name(value));
    const std::string type = r.string(r.required(value, "type", what), what + ".type");
    if (type == "revolute") {
      r.check_keys(value, {"type", "node_a", "node_b", "actuated", "friction"}, what);
      RevoluteDef j;
      j.name = name;
      j.node_a = node_ref(c, value, "node_a", what);
      j.node_b = node_ref(c, value, "node_b", what);
      if (value["actuated"].IsDefined())
        j.actuated = r.boolean(value["actuated"], what + ".actuated");
      c.out.add_revolute(std::move(j));
      c.revolutes.push_back(name);
    } else if (type == "prismatic") {
      r.check_keys(value, {"type", "axis_from", "axis_to", "slider", "actuated", "friction"}, what);
      PrismaticDef j;
      j.name = name;
      j.axis_from = node_ref(c, value, "axis_from", what);
      j.axis_to = node_ref(c, value, "axis_to", what);
      j.slider = node_ref(c, value, "slider", what);
      if (value["actuated"].IsDefined())
        j.actuated = r.boolean(value["actuated"], what + ".actuated");
      c.out.add_prismatic(std::move(j));
    } else if (type == "pin_in_slot") {
      r.check_keys(value,
                   {"type", "axis_from", "axis_to", "pin", "actuated_slide", "actuated_rotation",
                    "friction"},
                   what);
      PinInSlotDef j;
      j.name = name;
      j.axis_from = node_ref(c, value, "axis_from", what);
      j.axis_to = node_ref(c, value, "axis_to", what);
      j.pin = node_ref(c, value, "pin", what);
      if (value["actuated_slide"].IsDefined())
        j.actuated_slide = r.boolean(value["actuated_slide"], what + ".actuated_slide");
      if (value["actuated_rotation"].IsDefined())
        j.actuated_rotation = r.boolean(value["actuated_rotation"], what + ".actuated_rotation");
      c.out.add_pin_in_slot(std::move(j));
    } else {
      const std::vector<std::string> types = {"revolute", "prismatic", "pin_in_slot"};
      r.fail(value["type"], what + ": unknown joint type '" + type + "'" +
                                did_you_mean(type, types) +
                                "; expected revolute, prismatic or pin_in_slot");
    }
    read_joint_friction(r, value, name, type == "revolute", c.out);
    c.info.elements.emplace_back(name, r.at(key));
  }
}

void read_coordinates(Context& c, const YAML::Node& node) {
  const Reader& r = c.r;
  for (const auto& [key, value] : r.entries(node, "coordinates")) {
    const std::string what = "coordinate '" + key.Scalar() + "'";
    r.check_keys(value, {"rate", "initial"}, what);
    CoordinateDef d;
    d.name = key.Scalar();
    const YAML::Node rate = r.required(value, "rate", what);
    for (const auto& [rk, rv] : r.entries(rate, what + ".rate"))
      d.rate.emplace_back(rk.Scalar(), r.number(rv, what + ".rate." + rk.Scalar()));
    if (d.rate.empty()) r.fail(rate, what + ".rate: needs at least one quasi-velocity label");
    if (value["initial"].IsDefined()) d.initial = r.number(value["initial"], what + ".initial");
    c.info.elements.emplace_back(d.name, r.at(key));
    c.out.add_coordinate(std::move(d));
  }
}

// Binds the names of a constraint expression: parameters, then t, then labels (the arguments, in
// order of first use, each once); records where each label is written, for errors the model finds.
std::vector<std::string> bind_labels(Context& c, const YAML::Node& text, Expression& e,
                                     const std::string& element, const std::string& what) {
  const Reader& r = c.r;
  std::vector<std::string> args;
  try {
    e.bind([&](const std::string& n) {
      if (auto b = r.parameter_binding(n); b.kind != Binding::Kind::unbound) return b;
      if (n == "t") return Binding{Binding::Kind::time, 0, -1};
      auto it = std::find(args.begin(), args.end(), n);
      if (it == args.end()) it = args.insert(args.end(), n);
      return Binding{Binding::Kind::variable, 0, static_cast<int>(it - args.begin())};
    });
  } catch (const ExpressionError& err) {
    r.fail_expression(text, err, what);
  }
  for (const auto& a : args) c.info.labels.push_back({a, element, r.at_column(text, e.column(a))});
  return args;
}

// psi: position level (PositionConstraintDef); g: velocity level, linear in the rates
// (VelocityConstraintDef::labels, sorted into coordinates and quasi-velocities by build_model).
void read_constraints(Context& c, const YAML::Node& node) {
  const Reader& r = c.r;
  for (const auto& [key, value] : r.entries(node, "constraints")) {
    check_plain_name(r, key, "constraint");
    const std::string what = "constraint '" + key.Scalar() + "'";
    r.check_keys(value, {"psi", "g"}, what);
    if (value["psi"].IsDefined() == value["g"].IsDefined())
      r.fail(value, what + ": give exactly one of 'psi' (position level, psi(x, t) = 0) or 'g' " +
                        "(velocity level, g linear in quasi-velocities = 0)");
    const bool position = value["psi"].IsDefined();
    const char* k = position ? "psi" : "g";
    const YAML::Node text = value[k];
    auto e = std::make_shared<Expression>(r.expression(text, what + "." + k));
    std::vector<std::string> args = bind_labels(c, text, *e, key.Scalar(), what + "." + k);
    if (args.empty())
      r.fail(text, what + "." + k + ": a constraint must use at least one " +
                       (position ? "coordinate" : "quasi-velocity"));
    if (position) {
      PositionConstraintDef d;
      d.name = key.Scalar();
      d.args = std::move(args);
      d.psi = [e](std::span<const Jet> x, Jet t) { return e->evaluate(x, t); };
      c.out.add_constraint(std::move(d));
    } else {
      VelocityConstraintDef d;
      d.name = key.Scalar();
      d.labels = std::move(args);
      d.g_labels = [e](std::span<const Jet> a, Jet t) { return e->evaluate(a, t); };
      c.out.add_constraint(std::move(d));
    }
    c.info.elements.emplace_back(key.Scalar(), r.at(key));
  }
}

}  // namespace

namespace {

Law law(Context& c, const YAML::Node& node, const std::string& what, const std::string& element) {
  return state_law(c.r, node, what, element, &c.info.law_labels);
}

double nonnegative(const Reader& r, const YAML::Node& map, const char* key,
                   const std::string& what) {
  const double v = r.number_or(map, key, 0.0, what);
  if (v < 0) r.fail(map[key], what + "." + key + ": must be >= 0");
  return v;
}

SpringActs spring_acts(const Reader& r, const YAML::Node& node, const std::string& what) {
  if (!node.IsDefined()) return SpringActs::both;
  const std::string v = r.string(node, what + ".acts");
  if (v == "both") return SpringActs::both;
  if (v == "tension") return SpringActs::tension_only;
  if (v == "compression") return SpringActs::compression_only;
  const std::vector<std::string> names = {"both", "tension", "compression"};
  r.fail(node, what + ".acts: '" + v + "' is not one of both, tension, compression" +
                   did_you_mean(v, names));
}

SpringReduce spring_reduce(const Reader& r, const YAML::Node& node, const std::string& what) {
  if (!node.IsDefined()) return SpringReduce::none;
  const std::string v = r.string(node, what + ".reduce");
  if (v == "none") return SpringReduce::none;
  if (v == "constraint") return SpringReduce::constraint;
  if (v == "quasi_steady") return SpringReduce::quasi_steady;
  const std::vector<std::string> names = {"none", "constraint", "quasi_steady"};
  r.fail(node, what + ".reduce: '" + v + "' is not one of none, constraint, quasi_steady" +
                   did_you_mean(v, names));
}

void read_loads(Context& c, const YAML::Node& node, bool root) {
  const Reader& r = c.r;
  if (!node.IsDefined() || node.IsNull()) return;
  if (root)
    r.check_keys(node, {"gravity", "forces", "torques", "springs", "torsional_springs", "chains"},
                 "loads");
  else
    r.check_keys(node, {"forces", "torques", "springs", "torsional_springs", "chains"},
                 "loads (gravity belongs to the root scene)");
  if (node["gravity"].IsDefined()) c.out.set_gravity(r.vec2(node["gravity"], "loads.gravity"));
  for (const auto& [key, value] : r.entries(node["forces"], "loads.forces")) {
    check_plain_name(r, key, "force");
    const std::string what = "force '" + key.Scalar() + "'";
    r.check_keys(value, {"body", "point", "fx", "fy"}, what);
    ForceDef f;
    f.name = key.Scalar();
    f.body = body_ref(c, value, "body", what, false);
    f.point = r.vec2(r.required(value, "point", what), what + ".point");
    f.fx = law(c, value["fx"], what + ".fx", f.name);
    f.fy = law(c, value["fy"], what + ".fy", f.name);
    c.info.elements.emplace_back(f.name, r.at(key));
    c.out.add_force(std::move(f));
  }
  for (const auto& [key, value] : r.entries(node["torques"], "loads.torques")) {
    check_plain_name(r, key, "torque");
    const std::string what = "torque '" + key.Scalar() + "'";
    r.check_keys(value, {"body", "torque"}, what);
    TorqueDef t;
    t.name = key.Scalar();
    t.body = body_ref(c, value, "body", what, false);
    t.torque = law(c, r.required(value, "torque", what), what + ".torque", t.name);
    c.info.elements.emplace_back(t.name, r.at(key));
    c.out.add_torque(std::move(t));
  }
  for (const auto& [key, value] : r.entries(node["springs"], "loads.springs")) {
    check_plain_name(r, key, "spring");
    const std::string what = "spring '" + key.Scalar() + "'";
    r.check_keys(value,
                 {"body_a", "point_a", "body_b", "point_b", "rest_length", "stiffness", "damping",
                  "tension", "acts", "reduce"},
                 what);
    SpringDef s;
    s.name = key.Scalar();
    s.body_a = body_ref(c, value, "body_a", what, true);
    s.point_a = r.vec2(r.required(value, "point_a", what), what + ".point_a");
    s.body_b = body_ref(c, value, "body_b", what, true);
    s.point_b = r.vec2(r.required(value, "point_b", what), what + ".point_b");
    s.rest_length = nonnegative(r, value, "rest_length", what);
    s.stiffness = nonnegative(r, value, "stiffness", what);
    s.damping = nonnegative(r, value, "damping", what);
    s.tension = law(c, value["tension"], what + ".tension", s.name);
    if (s.tension && (value["stiffness"].IsDefined() || value["damping"].IsDefined()))
      r.fail(value["tension"],
             what + ": a tension law replaces stiffness and damping (give one or the other)");
    s.acts = spring_acts(r, value["acts"], what);
    s.reduce = spring_reduce(r, value["reduce"], what);
    c.info.elements.emplace_back(s.name, r.at(key));
    c.out.add_spring(std::move(s));
  }
  for (const auto& [key, value] : r.entries(node["torsional_springs"], "loads.torsional_springs")) {
    check_plain_name(r, key, "torsional spring");
    const std::string what = "torsional spring '" + key.Scalar() + "'";
    r.check_keys(value, {"joint", "stiffness", "damping", "rest", "torque", "reduce"}, what);
    TorsionalSpringDef s;
    s.name = key.Scalar();
    const YAML::Node joint = r.required(value, "joint", what);
    s.joint = r.string(joint, what + ".joint");
    if (std::find(c.revolutes.begin(), c.revolutes.end(), s.joint) == c.revolutes.end())
      r.fail(joint, what + ".joint: undefined revolute joint '" + s.joint + "'" +
                        did_you_mean(s.joint, c.revolutes));
    s.stiffness = nonnegative(r, value, "stiffness", what);
    s.damping = nonnegative(r, value, "damping", what);
    if (value["rest"].IsDefined()) s.rest = r.number(value["rest"], what + ".rest");
    s.torque = law(c, value["torque"], what + ".torque", s.name);
    if (s.torque && (value["stiffness"].IsDefined() || value["damping"].IsDefined()))
      r.fail(value["torque"],
             what + ": a torque law replaces stiffness and damping (give one or the other)");
    s.reduce = spring_reduce(r, value["reduce"], what);
    c.info.elements.emplace_back(s.name, r.at(key));
    c.out.add_torsional_spring(std::move(s));
  }
  read_chains(r, node["chains"], c.out, c.info);
}

const BuiltSubsystem& subsystem(const Reader& r, const YAML::Node& ref, Subsystems& lib) {
  const std::string name = r.string(ref, "instance.subsystem");
  if (auto it = lib.built.find(name); it != lib.built.end()) return it->second;
  std::vector<std::string> names;
  YAML::Node def;
  bool found = false;
  for (const auto& [k, v] : r.entries(lib.definitions, "subsystems")) {
    names.push_back(k.Scalar());
    if (k.Scalar() == name) def.reset(v), found = true;
  }
  if (!found) r.fail(ref, "undefined subsystem '" + name + "'" + did_you_mean(name, names));
  if (!lib.building.insert(name).second)
    r.fail(ref, "subsystem '" + name + "' contains itself (through its instances)");
  r.check_keys(def, kSystemKeys, "subsystem '" + name + "'");
  auto s = std::make_shared<System>(name);
  SystemInfo info = read_system(r, def, *s, false, lib);
  lib.building.erase(name);
  return lib.built[name] = BuiltSubsystem{std::move(s), std::move(info)};
}

void read_instances(Context& c, const YAML::Node& node, Subsystems& lib) {
  const Reader& r = c.r;
  for (const auto& [key, value] : r.entries(node, "instances")) {
    check_plain_name(r, key, "instance");
    const std::string name = key.Scalar();
    const std::string what = "instance '" + name + "'";
    r.check_keys(value, {"subsystem", "offset", "angle"}, what);
    const BuiltSubsystem& sub = subsystem(r, r.required(value, "subsystem", what), lib);
    Placement p;
    if (value["offset"].IsDefined()) p.offset = r.vec2(value["offset"], what + ".offset");
    p.angle = r.number_or(value, "angle", 0.0, what);
    c.out.add_instance(name, *sub.system, p);
    for (const auto& n : sub.info.nodes) c.info.nodes.push_back(name + "." + n);
    for (const auto& b : sub.info.bodies) c.info.bodies.push_back(name + "." + b);
    for (const auto& p : sub.info.points) c.info.points.push_back(name + "." + p);
    for (const auto& [e, l] : sub.info.elements) c.info.elements.emplace_back(name + "." + e, l);
    for (const auto& [e, l] : sub.info.law_labels)
      c.info.law_labels.emplace_back(name + "." + e, l);
    for (const auto& u : sub.info.labels)
      c.info.labels.push_back({name + "." + u.label, name + "." + u.element, u.where});
    c.info.elements.emplace_back(name, r.at(key));
  }
}

}  // namespace

SystemInfo read_system(const Reader& r, const YAML::Node& block, System& out, bool root,
                       Subsystems& library) {
  Context c{r, out};
  // bodies and instances first: joints and loads refer to their nodes
  read_ground(c, block["ground"]);
  read_bodies(c, block["bodies"]);
  read_instances(c, block["instances"], library);
  read_joints(c, block["joints"]);
  read_coordinates(c, block["coordinates"]);
  read_gears(r, block["gears"], block["racks"], out, c.info);
  read_transmissions(r, block["transmissions"], out, c.info);
  read_constraints(c, block["constraints"]);
  read_loads(c, block["loads"], root);
  read_points(r, block["points"], out, c.info);
  return std::move(c.info);
}

}  // namespace mo2d::scene_detail
