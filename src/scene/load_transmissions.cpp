// transmissions: of a system block -> mo2d::add_transmission at the fidelity written (keys:
// docs/scene-format.md, "Transmissions"; the two models: mo2d/transmission.hpp).
#include <algorithm>

#include "load_system.hpp"
#include "mo2d/error.hpp"
#include "mo2d/transmission.hpp"
#include "model/suggest.hpp"

namespace mo2d::scene_detail {

namespace {

double nonnegative(const Reader& r, const YAML::Node& map, const char* key, const std::string& what,
                   const char* unit) {
  const YAML::Node n = r.required(map, key, what);
  const double v = r.number(n, what + "." + key);
  if (v < 0) r.fail(n, what + "." + key + ": must be >= 0 " + unit);
  return v;
}

// shafts: {name: {axis, mass, inertia, ratio, torque}}
TransmissionShaftDef read_shaft(const Reader& r, const YAML::Node& key, const YAML::Node& value,
                                const std::string& element, SystemInfo& info) {
  check_element_name(r, key, "shaft");
  const std::string what = "transmission '" + element + "' shaft '" + key.Scalar() + "'";
  r.check_keys(value, {"axis", "mass", "inertia", "ratio", "torque"}, what);
  TransmissionShaftDef s;
  s.name = key.Scalar();
  s.shaft.axis = r.vec2(r.required(value, "axis", what), what + ".axis");
  s.shaft.mass = nonnegative(r, value, "mass", what, "kg");
  s.shaft.inertia = nonnegative(r, value, "inertia", what, "kg m^2");
  s.shaft.ratio = r.number_or(value, "ratio", 1.0, what);
  if (s.shaft.ratio == 0) r.fail(value["ratio"], what + ".ratio: must be non-zero");
  s.torque = state_law(r, value["torque"], what + ".torque", element, &info.law_labels);
  return s;
}

TransmissionFidelity transmission_fidelity(const Reader& r, const YAML::Node& value,
                                           const std::string& what) {
  if (!value["fidelity"].IsDefined()) return TransmissionFidelity::full;
  const YAML::Node n = value["fidelity"];
  const std::string f = r.string(n, what + ".fidelity");
  if (f == "full") return TransmissionFidelity::full;
  if (f == "lumped") return TransmissionFidelity::lumped;
  const std::vector<std::string> kinds = {"full", "lumped"};
  r.fail(n, what + ".fidelity: '" + f + "' is not one of full, lumped" + did_you_mean(f, kinds));
}

// The labels the element adds, for errors at its key and for later references (loads on a
// shaft of the full model).
void record(const TransmissionDef& d, const Location& at, SystemInfo& info) {
  const std::string& T = d.name;
  std::vector<std::string> names = {T, T + ".phi"};
  if (d.fidelity == TransmissionFidelity::full) {
    for (const auto& s : d.shafts) {
      info.bodies.push_back(s.name);
      info.nodes.push_back(s.name + ".C");
      info.nodes.push_back(s.name + ".R");
      info.nodes.push_back(d.housing + "." + T + "_" + s.name);
      for (const char* suffix : {"", "_mesh", "_torque"})
        names.push_back(T + "_" + s.name + suffix);
    }
  } else {
    info.nodes.push_back(d.housing + "." + T + "_axis");
    for (const char* n : {"_a", "_b", "_a_bearing", "_b_bearing", "_pair"}) names.push_back(T + n);
    for (const auto& s : d.shafts)
      for (const char* n : {"_torque_a", "_torque_housing"}) names.push_back(T + "_" + s.name + n);
  }
  for (auto& n : names) info.elements.emplace_back(std::move(n), at);
}

}  // namespace

// transmissions: {name: {housing, input, fidelity, shafts}}
void read_transmissions(const Reader& r, const YAML::Node& node, System& out, SystemInfo& info) {
  for (const auto& [key, value] : r.entries(node, "transmissions")) {
    check_element_name(r, key, "transmission");
    const std::string what = "transmission '" + key.Scalar() + "'";
    r.check_keys(value, {"housing", "input", "fidelity", "shafts"}, what);
    TransmissionDef d;
    d.name = key.Scalar();
    d.housing = body_of(r, value, "housing", what, info, false);
    d.fidelity = transmission_fidelity(r, value, what);
    const YAML::Node shafts = r.required(value, "shafts", what);
    for (const auto& [k, v] : r.entries(shafts, what + ".shafts")) {
      if (std::find(info.bodies.begin(), info.bodies.end(), k.Scalar()) != info.bodies.end())
        r.fail(k, what + ": shaft '" + k.Scalar() +
                      "' has the name of a body (a shaft is a body of the full model)");
      d.shafts.push_back(read_shaft(r, k, v, d.name, info));
    }
    if (d.shafts.empty()) r.fail(shafts, what + ".shafts: a transmission needs at least one shaft");
    const YAML::Node input = r.required(value, "input", what);
    d.input = r.string(input, what + ".input");
    std::vector<std::string> names;
    for (const auto& s : d.shafts) names.push_back(s.name);
    const auto in = std::find(names.begin(), names.end(), d.input);
    if (in == names.end())
      r.fail(input, what + ".input: '" + d.input + "' is not one of its shafts" +
                        did_you_mean(d.input, names));
    const TransmissionShaftDef& s = d.shafts[in - names.begin()];
    if (s.shaft.ratio != 1)
      r.fail(value["shafts"][d.input]["ratio"],
             what + ": the input shaft's ratio is 1 (the other shafts' ratios are relative to it)");
    try {
      add_transmission(out, d);
    } catch (const Error& e) {
      r.fail(key, e.what());
    }
    record(d, r.at(key), info);
  }
}

}  // namespace mo2d::scene_detail
