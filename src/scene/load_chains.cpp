// loads: chains: of a system block -> System::add_chain (keys: docs/scene-format.md, "Chain and
// belt drives"; the geometry and forces: src/dynamics/chain.hpp).

#include "load_system.hpp"
#include "model/suggest.hpp"

namespace mo2d::scene_detail {

namespace {

double positive(const Reader& r, const YAML::Node& map, const char* key, const std::string& what) {
  const YAML::Node n = r.required(map, key, what);
  const double v = r.number(n, what + "." + key);
  if (!(v > 0)) r.fail(n, what + "." + key + ": must be > 0");
  return v;
}

ChainFidelity fidelity(const Reader& r, const YAML::Node& node, const std::string& what) {
  if (!node.IsDefined()) return ChainFidelity::unilateral;
  const std::string v = r.string(node, what + ".fidelity");
  if (v == "unilateral") return ChainFidelity::unilateral;
  if (v == "bilateral") return ChainFidelity::bilateral;
  if (v == "inextensible") return ChainFidelity::inextensible;
  if (v == "quasi_steady") return ChainFidelity::quasi_steady;
  const std::vector<std::string> names = {"unilateral", "bilateral", "inextensible",
                                          "quasi_steady"};
  r.fail(node, what + ".fidelity: '" + v +
                   "' is not one of unilateral, bilateral, inextensible, quasi_steady" +
                   did_you_mean(v, names));
}

}  // namespace

// chains: {name: {body_a, centre_a, radius_a, body_b, centre_b, radius_b, stiffness, damping,
//                 rest_upper, rest_lower, fidelity}}
void read_chains(const Reader& r, const YAML::Node& chains, System& out, SystemInfo& info) {
  for (const auto& [key, value] : r.entries(chains, "loads.chains")) {
    const std::string& s = key.Scalar();
    check_element_name(r, key, "chain");
    const std::string what = "chain '" + s + "'";
    r.check_keys(value,
                 {"body_a", "centre_a", "radius_a", "body_b", "centre_b", "radius_b", "stiffness",
                  "damping", "rest_upper", "rest_lower", "fidelity"},
                 what);
    ChainDef c;
    c.name = s;
    c.body_a = body_of(r, value, "body_a", what, info, true);
    c.centre_a = r.vec2(r.required(value, "centre_a", what), what + ".centre_a");
    c.radius_a = positive(r, value, "radius_a", what);
    c.body_b = body_of(r, value, "body_b", what, info, true);
    c.centre_b = r.vec2(r.required(value, "centre_b", what), what + ".centre_b");
    c.radius_b = positive(r, value, "radius_b", what);
    c.fidelity = fidelity(r, value["fidelity"], what);
    // inextensible: no stiffness needed (if given, the fidelity report reads it)
    if (c.fidelity != ChainFidelity::inextensible || value["stiffness"].IsDefined())
      c.stiffness = positive(r, value, "stiffness", what);
    c.damping = r.number_or(value, "damping", 0.0, what);
    if (c.damping < 0) r.fail(value["damping"], what + ".damping: must be >= 0");
    if (value["rest_upper"].IsDefined()) c.rest_upper = positive(r, value, "rest_upper", what);
    if (value["rest_lower"].IsDefined()) c.rest_lower = positive(r, value, "rest_lower", what);
    info.elements.emplace_back(c.name, r.at(key));
    out.add_chain(std::move(c));
  }
}

}  // namespace mo2d::scene_detail
