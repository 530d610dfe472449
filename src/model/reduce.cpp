// Stage 3 of build_model: variable reduction (Orsino §5.3). An eliminated revolute joint merges
// the variables of its two nodes (eq. 5.27: the slave node takes the master's coordinates); an
// eliminated prismatic joint merges the rotation rates of its two bodies (eq. 5.30). Which joints
// are eliminated follows BuildOptions::reduction. Each joint is validated (validate.cpp) just
// before it is merged, so a redundant joint is reported before the errors of later joints.
#include "mo2d/error.hpp"
#include "model/build_stages.hpp"

namespace mo2d::build {
namespace {

// Whether a joint of subsystem `owner` between body1 and body2 (-1: ground) is eliminated.
bool mergeable(const Model& m, Reduction reduction, int owner, int body1, int body2) {
  auto body_owner = [&](int body) { return body < 0 ? -1 : m.bodies[body].owner; };
  switch (reduction) {
    case Reduction::flat:
      return true;
    case Reduction::none:
      return false;
    case Reduction::subsystems:
      return (body1 < 0 || body_owner(body1) == owner) && (body2 < 0 || body_owner(body2) == owner);
  }
  return false;
}

// Revolute joints: node merges. The root of a group is a ground element if it has one, otherwise
// its earliest element.
void merge_nodes(const Flat& flat, const Elements& el, const BuildOptions& options, const Model& m,
                 UnionFind& nodes, Reduced& red) {
  for (const auto& j : flat.revolutes) {
    const std::string what = "revolute joint '" + j.prefix + j.def.name + "'";
    const auto [ea, eb] = check_revolute(j, el, options.joint_tolerance);
    red.revolutes.push_back({ea, eb});
    const bool merge = mergeable(m, options.reduction, j.owner, el.body[ea], el.body[eb]);
    red.revolute_merged.push_back(merge);
    if (!merge) continue;
    const int ra = nodes.find(ea), rb = nodes.find(eb);
    if (ra == rb)
      throw Error(what + " is redundant: its nodes are already joined by other revolute joints",
                  j.prefix + j.def.name);
    // keep a ground element as root; otherwise the earlier element
    const bool a_ground = el.body[ra] < 0, b_ground = el.body[rb] < 0;
    if (a_ground && b_ground)
      throw Error(what + " joins two different ground nodes (conflicting constraints)",
                  j.prefix + j.def.name);
    if (b_ground || (!a_ground && rb < ra))
      nodes.parent[ra] = rb;
    else
      nodes.parent[rb] = ra;
  }
}

// Prismatic joints: rotation merges (rotation element 0 = ground, 1 + b = body b). A joint locks
// the rotations if both sides have one; the lock is eliminated if the joint is mergeable.
void merge_rotations(const Flat& flat, const Elements& el, const BuildOptions& options,
                     const Model& m, UnionFind& rotations, Reduced& red) {
  for (const auto& j : flat.prismatics) {
    const std::string what = "prismatic joint '" + j.prefix + j.def.name + "'";
    AxisJoint p = check_prismatic(j, el, options.joint_tolerance, m.scale);
    const bool has1 = p.body1 < 0 || m.bodies[p.body1].has_omega;
    const bool has2 = p.body2 < 0 || m.bodies[p.body2].has_omega;
    p.lock = has1 && has2;
    p.merged = p.lock && mergeable(m, options.reduction, j.owner, p.body1, p.body2);
    if (p.merged) {
      const int r1 = rotations.find(p.body1 + 1), r2 = rotations.find(p.body2 + 1);
      if (r1 == r2)
        throw Error(what + " is redundant: the rotations of its bodies are already locked together",
                    j.prefix + j.def.name);
      if (r2 == 0 || (r1 != 0 && r2 < r1))
        rotations.parent[r1] = r2;
      else
        rotations.parent[r2] = r1;
    }
    red.prismatics.push_back(p);
  }
}

}  // namespace

Reduced reduce(const Flat& flat, const Elements& el, const BuildOptions& options, const Model& m) {
  Reduced red;
  UnionFind nodes(el.count());
  merge_nodes(flat, el, options, m, nodes, red);
  UnionFind rotations(static_cast<int>(m.bodies.size()) + 1);
  merge_rotations(flat, el, options, m, rotations, red);
  for (const auto& j : flat.slots)  // pin-in-slot joints eliminate nothing
    red.slots.push_back(check_slot(j, el, options.joint_tolerance, m.scale));

  for (int e = 0; e < el.count(); ++e) red.node_root.push_back(nodes.find(e));
  for (int r = 0; r <= static_cast<int>(m.bodies.size()); ++r)
    red.rotation_root.push_back(rotations.find(r));
  return red;
}

}  // namespace mo2d::build
