// gears: and racks: of a system block -> System::add_gear, System::add_rack (keys:
// docs/scene-format.md, "Gears and racks"; the rows: src/constraints/gear.hpp).
#include <algorithm>

#include "load_system.hpp"
#include "model/suggest.hpp"

namespace mo2d::scene_detail {

namespace {

double non_zero(const Reader& r, const YAML::Node& map, const char* key, const std::string& what) {
  const YAML::Node n = r.required(map, key, what);
  const double v = r.number(n, what + "." + key);
  if (v == 0) r.fail(n, what + "." + key + ": must be non-zero");
  return v;
}

}  // namespace

void check_element_name(const Reader& r, const YAML::Node& key, const std::string& what) {
  const std::string& s = key.Scalar();
  if (s.find_first_of(".,: \t") != std::string::npos || s == "ground")
    r.fail(key, what + " '" + s +
                    "': names may not contain '.', ',', ':' or spaces, nor be "
                    "'ground'");
}

std::string body_of(const Reader& r, const YAML::Node& map, const char* key,
                    const std::string& what, const SystemInfo& info, bool ground_allowed) {
  const YAML::Node n = r.required(map, key, what);
  std::string name = r.string(n, what + "." + key);
  if (ground_allowed && name == "ground") return name;
  if (std::find(info.bodies.begin(), info.bodies.end(), name) == info.bodies.end())
    r.fail(n,
           what + "." + key + ": undefined body '" + name + "'" + did_you_mean(name, info.bodies));
  return name;
}

// gears: {name: {body, driver, carrier (default ground), ratio}}
// racks: {name: {slide, pinion, radius}}
void read_gears(const Reader& r, const YAML::Node& gears, const YAML::Node& racks, System& out,
                SystemInfo& info) {
  for (const auto& [key, value] : r.entries(gears, "gears")) {
    check_element_name(r, key, "gear");
    const std::string what = "gear '" + key.Scalar() + "'";
    r.check_keys(value, {"body", "driver", "carrier", "ratio"}, what);
    GearDef g;
    g.name = key.Scalar();
    g.body = body_of(r, value, "body", what, info, false);
    g.driver = body_of(r, value, "driver", what, info, false);
    if (value["carrier"].IsDefined()) g.carrier = body_of(r, value, "carrier", what, info, true);
    g.ratio = non_zero(r, value, "ratio", what);
    info.elements.emplace_back(g.name, r.at(key));
    out.add_gear(std::move(g));
  }
  for (const auto& [key, value] : r.entries(racks, "racks")) {
    check_element_name(r, key, "rack");
    const std::string what = "rack '" + key.Scalar() + "'";
    r.check_keys(value, {"slide", "pinion", "radius"}, what);
    RackDef d;
    d.name = key.Scalar();
    d.slide = r.string(r.required(value, "slide", what), what + ".slide");
    d.pinion = body_of(r, value, "pinion", what, info, false);
    d.radius = non_zero(r, value, "radius", what);
    info.elements.emplace_back(d.name, r.at(key));
    out.add_rack(std::move(d));
  }
}

}  // namespace mo2d::scene_detail
