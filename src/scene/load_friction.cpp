// Scenes: the `friction:` entry of a joint (FrictionDef, mo2d/system.hpp):
//   rail:  {type: prismatic, ..., friction: {mu: 0.2, viscous: 5, regularization: 1e-3}}
//   pivot: {type: revolute, ..., friction: {mu: 0.1, radius: 0.01}}
// The friction is named after its joint.
#include "load_system.hpp"

namespace mo2d::scene_detail {

void read_joint_friction(const Reader& r, const YAML::Node& joint, const std::string& name,
                         bool revolute, System& out) {
  const YAML::Node node = joint["friction"];
  if (!node.IsDefined()) return;
  const std::string what = "joint '" + name + "'.friction";
  if (!node.IsMap()) r.fail(node, what + ": expected a map {mu, viscous, ...}");
  if (revolute)
    r.check_keys(node, {"mu", "viscous", "radius", "regularization"}, what);
  else
    r.check_keys(node, {"mu", "viscous", "regularization"}, what);
  FrictionDef f{.name = name, .joint = name};
  auto nonnegative = [&](const char* key, double& v) {
    v = r.number_or(node, key, v, what);
    if (!(v >= 0)) r.fail(node[key], what + "." + key + ": must be >= 0");
  };
  nonnegative("mu", f.mu);
  nonnegative("viscous", f.viscous);
  nonnegative("radius", f.radius);
  f.regularization = r.number_or(node, "regularization", f.regularization, what);
  if (!(f.regularization > 0))
    r.fail(node["regularization"], what + ".regularization: must be > 0 (m/s or rad/s)");
  if (revolute && f.mu > 0 && !node["radius"].IsDefined())
    r.fail(node, what +
                     ": Coulomb friction in a revolute joint needs the pin radius "
                     "(torque = mu * radius * |reaction|)");
  out.add_friction(std::move(f));
}

}  // namespace mo2d::scene_detail
