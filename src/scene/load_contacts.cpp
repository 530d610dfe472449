// contacts: of a scene -> Scene::contacts, and the contact run's keys of run: -> Scene::contact
// (docs/scene-format.md, "Contacts"; the elements and laws: docs/contact.md).
#include <algorithm>
#include <cmath>

#include "contact/profile.hpp"
#include "load_system.hpp"
#include "model/suggest.hpp"

namespace mo2d::scene_detail {

namespace {

// A point a contact names: a body or ground node ("ball.C") or a named point.
std::string point_of(const Reader& r, const YAML::Node& node, const std::string& what,
                     const SystemInfo& info) {
  std::string label = r.string(node, what);
  const bool known = std::find(info.nodes.begin(), info.nodes.end(), label) != info.nodes.end() ||
                     std::find(info.points.begin(), info.points.end(), label) != info.points.end();
  if (!known) {
    std::vector<std::string> all = info.nodes;
    all.insert(all.end(), info.points.begin(), info.points.end());
    r.fail(node, what + ": undefined node or point '" + label + "'" + did_you_mean(label, all));
  }
  return label;
}

double non_negative(const Reader& r, const YAML::Node& map, const char* key, double fallback,
                    const std::string& what) {
  const double v = r.number_or(map, key, fallback, what);
  if (!(v >= 0)) r.fail(map[key], what + "." + key + ": must be >= 0");
  return v;
}

double positive(const Reader& r, const YAML::Node& n, const std::string& what) {
  const double v = r.number(n, what);
  if (!(v > 0)) r.fail(n, what + ": must be > 0");
  return v;
}

// slot: [a, b] with width: a pin in a slot from its closed end a to its mouth b.
void read_slot(const Reader& r, const YAML::Node& value, const std::string& what,
               const SystemInfo& info, ContactDef& c) {
  const YAML::Node t = value["slot"];
  const std::string key = what + ".slot";
  if (!t.IsSequence() || t.size() != 2)
    r.fail(t, key + ": expected two points [A, B] (its closed end A, its mouth B)");
  c.target = ContactDef::Target::slot;
  c.a = point_of(r, t[0], key, info);
  c.b = point_of(r, t[1], key, info);
  if (c.a == c.b) r.fail(t[1], key + ": the slot's two ends are the same point ('" + c.a + "')");
  if (value["target_radius"].IsDefined())
    r.fail(value["target_radius"], what + ".target_radius: only for a circle or a hole");
  if (!value["width"].IsDefined()) r.fail(value, what + ": a slot needs its width (width)");
  c.width = positive(r, value["width"], what + ".width");
  if (!(c.width > 2 * c.radius))
    r.fail(value["width"], what + ".width: the slot (" + std::to_string(c.width) +
                               " m) must be wider than the pin's diameter (2 radius = " +
                               std::to_string(2 * c.radius) +
                               " m): the clearance is their difference");
}

// profile: [centre, axis point] with table: the scene's table r(phi) (docs/scene-format.md).
void read_profile(const Reader& r, const YAML::Node& value, const std::string& what,
                  const SystemInfo& info, ContactDef& c) {
  const YAML::Node t = value["profile"];
  const std::string key = what + ".profile";
  if (!t.IsSequence() || t.size() != 2)
    r.fail(t, key + ": expected two points [centre, axis] (phi = 0 along centre -> axis)");
  c.target = ContactDef::Target::profile;
  c.a = point_of(r, t[0], key, info);
  c.b = point_of(r, t[1], key, info);
  if (c.a == c.b)
    r.fail(t[1], key + ": the centre and the axis point are the same ('" + c.a + "')");
  const YAML::Node table = r.required(value, "table", what);
  const std::string name = r.string(table, what + ".table");
  std::vector<std::string> names;
  for (const auto& [n, tab] : r.tables) {
    names.push_back(n);
    if (n == name) c.profile = tab;
  }
  if (!c.profile)
    r.fail(table, what + ".table: no table '" + name + "' in the scene's tables" +
                      did_you_mean(name, names));
  if (value["friction"].IsDefined())
    r.fail(value["friction"], what +
                                  ".friction: not supported on a cam profile (its tangent is "
                                  "not implemented)");
  const std::string problem = detail::profile_problem(*c.profile, c.radius);
  if (!problem.empty()) r.fail(table, what + ": " + problem);
}

// line: [a, b] | circle: c | hole: c | slot: [a, b] | profile: [a, b], with target_radius for a
// circle or a hole, width for a slot, table for a profile.
void read_target(const Reader& r, const YAML::Node& value, const std::string& what,
                 const SystemInfo& info, ContactDef& c) {
  const char* kinds[] = {"line", "circle", "hole", "slot", "profile"};
  const char* given = nullptr;
  for (const char* k : kinds) {
    if (!value[k].IsDefined()) continue;
    if (given)
      r.fail(value[k],
             what + ": give one target, 'line', 'circle', 'hole', 'slot' or 'profile' (both '" +
                 given + "' and '" + k + "' given)");
    given = k;
  }
  if (!given)
    r.fail(value, what +
                      ": no target: give 'line: [A, B]', 'circle: C', 'hole: C', 'slot: [A, B]' "
                      "or 'profile: [C, A]'");
  if (std::string(given) != "slot" && value["width"].IsDefined())
    r.fail(value["width"], what + ".width: only for a slot");
  if (std::string(given) != "profile" && value["table"].IsDefined())
    r.fail(value["table"], what + ".table: only for a profile");
  if (std::string(given) == "slot") return read_slot(r, value, what, info, c);
  const YAML::Node t = value[given];
  const std::string key = what + "." + given;
  const YAML::Node radius = value["target_radius"];
  if (std::string(given) == "profile") {
    if (radius.IsDefined()) r.fail(radius, what + ".target_radius: only for a circle or a hole");
    read_profile(r, value, what, info, c);
    return;
  }
  if (std::string(given) == "line") {
    if (!t.IsSequence() || t.size() != 2)
      r.fail(t, key + ": expected two points [A, B] (the free side is the left of A -> B)");
    c.target = ContactDef::Target::line;
    c.a = point_of(r, t[0], key, info);
    c.b = point_of(r, t[1], key, info);
    if (c.a == c.b) r.fail(t[1], key + ": the line's two points are the same ('" + c.a + "')");
    if (radius.IsDefined()) r.fail(radius, what + ".target_radius: only for a circle or a hole");
    return;
  }
  c.target = std::string(given) == "circle" ? ContactDef::Target::circle : ContactDef::Target::hole;
  c.a = point_of(r, t, key, info);
  if (!radius.IsDefined())
    r.fail(value, what + ": a " + given + " needs its radius (target_radius)");
  c.target_radius = positive(r, radius, what + ".target_radius");
  if (c.target == ContactDef::Target::hole && !(c.target_radius > c.radius))
    r.fail(radius, what + ".target_radius: the hole (" + std::to_string(c.target_radius) +
                       " m) must be larger than the circle in it (radius " +
                       std::to_string(c.radius) + " m): the clearance is their difference");
}

void read_law(const Reader& r, const YAML::Node& value, const std::string& what, ContactLaw& l) {
  const YAML::Node kind = r.required(value, "law", what);
  const std::string k = r.string(kind, what + ".law");
  if (k != "rigid" && k != "compliant")
    r.fail(kind, what + ".law: unknown law '" + k + "'" +
                     did_you_mean(k, std::vector<std::string>{"rigid", "compliant"}) +
                     "; expected rigid or compliant");
  l.kind = k == "rigid" ? ContactLaw::Kind::rigid : ContactLaw::Kind::compliant;
  const YAML::Node e = r.required(value, "restitution", what);
  l.restitution = r.number(e, what + ".restitution");
  if (!(l.restitution >= 0 && l.restitution <= 1))
    r.fail(e, what + ".restitution: must be in [0, 1] (got " + std::to_string(l.restitution) + ")");
  if (value["friction"].IsDefined()) l.friction = non_negative(r, value, "friction", 0.0, what);
  const bool compliant = l.kind == ContactLaw::Kind::compliant;
  for (const char* key : {"stiffness", "exponent", "min_approach_speed"})
    if (!compliant && value[key].IsDefined())
      r.fail(value[key], what + "." + key + ": only for law: compliant");
  if (!compliant) return;
  l.stiffness = positive(r, r.required(value, "stiffness", what), what + ".stiffness");
  if (value["exponent"].IsDefined())
    l.exponent = positive(r, value["exponent"], what + ".exponent");
  if (value["min_approach_speed"].IsDefined())
    l.min_approach_speed = positive(r, value["min_approach_speed"], what + ".min_approach_speed");
}

}  // namespace

void read_contacts(const Reader& r, const YAML::Node& node, SystemInfo& info, Scene& scene) {
  for (const auto& [key, value] : r.entries(node, "contacts")) {
    check_element_name(r, key, "contact");
    const std::string what = "contact '" + key.Scalar() + "'";
    r.check_keys(
        value,
        {"point", "radius", "line", "circle", "hole", "slot", "profile", "table", "target_radius",
         "width", "law", "restitution", "stiffness", "exponent", "min_approach_speed", "friction"},
        what);
    for (const ContactDef& c : scene.contacts)
      if (c.name == key.Scalar()) r.fail(key, what + ": defined twice");
    ContactDef c;
    c.name = key.Scalar();
    c.point = point_of(r, r.required(value, "point", what), what + ".point", info);
    c.radius = non_negative(r, value, "radius", 0.0, what);
    read_target(r, value, what, info, c);
    if (c.point == c.a || c.point == c.b)
      r.fail(value["point"], what + ".point: '" + c.point + "' is also a point of its target");
    read_law(r, value, what, c.law);
    if (c.target == ContactDef::Target::slot && c.law.friction > 0)
      r.fail(value["friction"], what + ".friction: friction in a slot is not modelled (use 0)");
    info.elements.emplace_back(c.name, r.at(key));
    scene.contact_where.push_back(r.at(key));
    scene.contacts.push_back(std::move(c));
  }
}

// run: {max_events, zeno_time, zeno_speed, baumgarte_rate}: the contact run's settings.
void read_contact_run(const Reader& r, const YAML::Node& run, Scene& scene) {
  if (!run.IsDefined() || !run.IsMap()) return;
  ContactOptions& o = scene.contact;
  for (const char* key : {"max_events", "zeno_time", "zeno_speed", "baumgarte_rate"}) {
    const YAML::Node v = run[key];
    if (!v.IsDefined()) continue;
    const std::string what = std::string("run.") + key;
    if (scene.contacts.empty()) r.fail(v, what + ": only for a scene with contacts (contacts:)");
    if (std::string(key) == "max_events") {
      o.max_events = r.integer(v, what);
      if (o.max_events < 1) r.fail(v, what + ": must be >= 1");
    } else if (std::string(key) == "zeno_time") {
      o.zeno_time = positive(r, v, what);
    } else if (std::string(key) == "zeno_speed") {
      o.zeno_speed = positive(r, v, what);
    } else {
      o.baumgarte_rate = r.number(v, what);
      if (!(o.baumgarte_rate >= 0)) r.fail(v, what + ": must be >= 0");
    }
  }
}

}  // namespace mo2d::scene_detail
