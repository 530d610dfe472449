// The named points of a system block (`points:`, System::add_point) and the extra columns of a
// run (`outputs:`, OutputRequest) of a scene (docs/scene-format.md, "Named points and output
// columns").
#include <algorithm>

#include "load_system.hpp"
#include "model/suggest.hpp"

namespace mo2d::scene_detail {

// points: {name: {body: B | ground, point: [x, y]}} (the point in the block's frame at the
// initial configuration).
void read_points(const Reader& r, const YAML::Node& node, System& out, SystemInfo& info) {
  for (const auto& [key, value] : r.entries(node, "points")) {
    const std::string& name = key.Scalar();
    check_element_name(r, key, "point");
    const std::string what = "point '" + name + "'";
    r.check_keys(value, {"body", "point"}, what);
    const YAML::Node body = r.required(value, "body", what);
    PointDef p;
    p.name = name;
    p.body = r.string(body, what + ".body");
    if (p.body != "ground" &&
        std::find(info.bodies.begin(), info.bodies.end(), p.body) == info.bodies.end())
      r.fail(body,
             what + ".body: undefined body '" + p.body + "'" + did_you_mean(p.body, info.bodies));
    p.point = r.vec2(r.required(value, "point", what), what + ".point");
    info.elements.emplace_back(name, r.at(key));
    info.points.push_back(name);
    out.add_point(std::move(p));
  }
}

// outputs: {loads: bool, com: bool, points: bool | [names], columns: {NAME: law}} (default: no
// load or centre-of-mass columns, every named point, no law column).
void read_outputs(const Reader& r, const YAML::Node& node, const SystemInfo& info, Scene& scene) {
  OutputRequest& o = scene.outputs;
  o.all_points = true;
  if (!node.IsDefined() || node.IsNull()) return;
  r.check_keys(node, {"loads", "com", "points", "columns"}, "outputs");
  if (node["loads"].IsDefined()) o.loads = r.boolean(node["loads"], "outputs.loads");
  if (node["com"].IsDefined()) o.com = r.boolean(node["com"], "outputs.com");
  for (const auto& [key, value] : r.entries(node["columns"], "outputs.columns")) {
    const std::string& name = key.Scalar();
    check_element_name(r, key, "output column");
    o.columns.emplace_back(name,
                           state_law(r, value, "outputs.columns." + name, name, &scene.law_labels));
  }
  const YAML::Node points = node["points"];
  if (!points.IsDefined()) return;
  if (!points.IsSequence()) {
    o.all_points = r.boolean(points, "outputs.points");
    return;
  }
  o.all_points = false;
  for (const auto& p : points) {
    const std::string name = r.string(p, "outputs.points");
    if (std::find(info.points.begin(), info.points.end(), name) == info.points.end())
      r.fail(p, "outputs.points: undefined point '" + name + "'" + did_you_mean(name, info.points) +
                    " (points are defined under 'points:')");
    o.points.push_back(name);
  }
}

}  // namespace mo2d::scene_detail
