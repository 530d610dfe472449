// Stage 5 of build_model, gears and racks (constraints/gear.hpp gives their equations): one row
// each at position and velocity level, after the extra coordinates, since each reads its own
// carrier-relative angle "name.phi" (an extra coordinate that flatten added). With them their
// reactions: the mesh torque on the driven body and on the carrier (gear), the rack force.
#include <cmath>

#include "constraints/common.hpp"
#include "mo2d/error.hpp"
#include "model/build_stages.hpp"
#include "model/suggest.hpp"

namespace mo2d::build {
namespace {

// A body with two nodes ("ground": -1), for the element `what`.
int angle_body(const Model& m, const std::string& prefix, const std::string& name,
               const std::string& role, const std::string& what) {
  if (name == "ground") return -1;
  for (int bi = 0; bi < static_cast<int>(m.bodies.size()); ++bi) {
    if (m.bodies[bi].name != prefix + name) continue;
    if (m.bodies[bi].nodes.size() < 2 || m.bodies[bi].omega.var < 0)
      throw Error(what + ": " + role + " '" + prefix + name +
                      "' needs two nodes and a rotation of its own (its angle is read)",
                  prefix + name);
    return bi;
  }
  std::vector<std::string> names{"ground"};
  for (const auto& b : m.bodies) names.push_back(b.name);
  throw Error(
      what + ": unknown " + role + " '" + prefix + name + "'" + did_you_mean(prefix + name, names),
      prefix + name);
}

void check_ratio(double ratio, const std::string& what, const std::string& name) {
  if (!std::isfinite(ratio) || ratio == 0)
    throw Error(what + ": ratio must be finite and non-zero (got " + std::to_string(ratio) + ")",
                name);
}

// The phi coordinate of `name` (holonomic: flatten gave it integer weights on body angles).
int phi_of(const Model& m, const std::string& name) {
  const int phi = m.coordinate(name + ".phi");
  for (const auto& c : m.constraints)
    if (c.name == name + ".phi" && !c.as<Constraint::Coordinate>().holonomic)
      throw Error("'" + name + "': the driving body needs two nodes (its angle is read)", name);
  return phi;
}

void add_gear(const Owned<GearDef>& gd, const Numbering& num, Model& m) {
  const std::string name = gd.prefix + gd.def.name;
  const std::string what = "gear '" + name + "'";
  check_ratio(gd.def.ratio, what, name);
  Constraint::Gear g;
  g.body = angle_body(m, gd.prefix, gd.def.body, "body", what);
  const int k = angle_body(m, gd.prefix, gd.def.driver, "driver", what);
  g.carrier = angle_body(m, gd.prefix, gd.def.carrier, "carrier", what);
  if (g.body < 0 || g.body == k || g.body == g.carrier || k == g.carrier)
    throw Error(what +
                    ": body, driver and carrier must be three different bodies (the body "
                    "and the driver not the ground)",
                name);
  g.ratio = gd.def.ratio;
  g.phi = phi_of(m, name);
  g.driven = detail::ref_w(m, m.bodies[g.body].omega);
  if (g.carrier >= 0) g.carrier_w = detail::ref_w(m, m.bodies[g.carrier].omega);
  g.phi_rate = m.rate_refs[g.phi];
  g.offset = detail::wrap_angle(initial_angle(m, g.body) - initial_angle(m, g.carrier) -
                                g.ratio * num.q0[g.phi]);
  const double rho = g.ratio;
  const int ci = add_constraint(m, Constraint{.name = name, .owner = gd.owner, .def = g}, 1, 1,
                                {""}, {".rate"});
  const int row = m.constraints[ci].row1;
  m.reactions.push_back({name + ".torque", row, -1});
  m.reactions.push_back({name + ".carrier_torque", row, 1 - rho});
}

void add_rack(const Owned<RackDef>& rd, const Numbering& num, Model& m) {
  const std::string name = rd.prefix + rd.def.name;
  const std::string what = "rack '" + name + "'";
  check_ratio(rd.def.radius, what, name);
  angle_body(m, rd.prefix, rd.def.pinion, "pinion", what);
  Constraint::Gear g;
  g.coord = m.coordinate(rd.prefix + rd.def.slide + ".q");
  g.ratio = rd.def.radius;
  g.phi = phi_of(m, name);
  g.driven = m.rate_refs[g.coord];
  g.phi_rate = m.rate_refs[g.phi];
  g.offset = num.q0[g.coord] - g.ratio * num.q0[g.phi];
  const int ci = add_constraint(m, Constraint{.name = name, .owner = rd.owner, .def = g}, 1, 1,
                                {""}, {".rate"});
  m.reactions.push_back({name + ".force", m.constraints[ci].row1, -1});
}

}  // namespace

void add_gear_rows(const Flat& flat, const Numbering& num, Model& m) {
  for (const auto& g : flat.gears) add_gear(g, num, m);
  for (const auto& r : flat.racks) add_rack(r, num, m);
}

}  // namespace mo2d::build
