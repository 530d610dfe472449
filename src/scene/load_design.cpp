// The `design:` block of a scene (Scene::design, mo2d/design.hpp; docs/design.md): four-bar
// loops by their joint nodes, the frame's shaking force and moment, bearing loads, and the
// coefficient of speed fluctuation of the flywheel.
#include <algorithm>

#include "load_system.hpp"
#include "model/suggest.hpp"

namespace mo2d::scene_detail {

namespace {

// A node label of the scene ("ground.A0", "coupler.B"), checked at its place in the file.
std::string design_node(const Reader& r, const YAML::Node& map, const char* key,
                        const SystemInfo& info, const std::string& what) {
  const YAML::Node node = r.required(map, key, what);
  std::string label = r.string(node, what + "." + key);
  if (std::find(info.nodes.begin(), info.nodes.end(), label) == info.nodes.end())
    r.fail(node,
           what + "." + key + ": undefined node '" + label + "'" + did_you_mean(label, info.nodes));
  return label;
}

void read_four_bars(const Reader& r, const YAML::Node& node, const SystemInfo& info,
                    DesignRequest& d) {
  for (const auto& [key, value] : r.entries(node, "design.four_bars")) {
    FourBarDef f;
    f.name = key.Scalar();
    const std::string what = "design.four_bars." + f.name;
    r.check_keys(
        value, {"input_pivot", "input_pin", "output_pin", "output_pivot", "coupler_points"}, what);
    f.input_pivot = design_node(r, value, "input_pivot", info, what);
    f.input_pin = design_node(r, value, "input_pin", info, what);
    f.output_pin = design_node(r, value, "output_pin", info, what);
    f.output_pivot = design_node(r, value, "output_pivot", info, what);
    if (value["coupler_points"].IsDefined()) {
      const YAML::Node points = value["coupler_points"];
      f.coupler_points = r.strings(points, what + ".coupler_points");
      for (const std::string& p : f.coupler_points)
        if (std::find(info.points.begin(), info.points.end(), p) == info.points.end())
          r.fail(points, what + ".coupler_points: undefined point '" + p + "'" +
                             did_you_mean(p, info.points) +
                             " (points are defined under 'points:')");
    }
    d.four_bars.push_back(std::move(f));
  }
}

}  // namespace

// design: {four_bars: {NAME: {input_pivot, input_pin, output_pin, output_pivot, coupler_points}},
//          frame: bool | {about: [x, y]}, bearings: bool, speed_fluctuation: Cs}
void read_design(const Reader& r, const YAML::Node& node, const SystemInfo& info, Scene& scene) {
  if (!node.IsDefined() || node.IsNull()) return;
  DesignRequest& d = scene.design;
  r.check_keys(node, {"four_bars", "frame", "bearings", "speed_fluctuation"}, "design");
  if (node["four_bars"].IsDefined()) read_four_bars(r, node["four_bars"], info, d);
  if (const YAML::Node frame = node["frame"]; frame.IsDefined()) {
    if (frame.IsMap()) {
      r.check_keys(frame, {"about"}, "design.frame");
      d.frame = true;
      if (frame["about"].IsDefined()) d.moment_about = r.vec2(frame["about"], "design.frame.about");
    } else {
      d.frame = r.boolean(frame, "design.frame");
    }
  }
  if (node["bearings"].IsDefined()) d.bearings = r.boolean(node["bearings"], "design.bearings");
  if (const YAML::Node cs = node["speed_fluctuation"]; cs.IsDefined()) {
    d.speed_fluctuation = r.number(cs, "design.speed_fluctuation");
    if (!(d.speed_fluctuation > 0 && d.speed_fluctuation < 1))
      r.fail(cs,
             "design.speed_fluctuation: the coefficient (w_max - w_min) / w_mean must be in "
             "(0, 1)");
  }
}

}  // namespace mo2d::scene_detail
