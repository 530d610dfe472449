// Joints of a Model for drawing. Revolute joints reduced by variable elimination have no
// Constraint: each merged joint left a MergeEdge (rotation = false) whose child node is the
// joint's node and whose reaction label "<joint>.Fx" names it.
#include "parts.hpp"

#include "dynamics/points.hpp"
#include "mo2d/error.hpp"
#include "model/suggest.hpp"

namespace mo2d::detail {

namespace {

void attach_inputs(const Model& m, JointPart& j) {
  for (int k = 0; k < m.n_inputs(); ++k) {
    const Input& in = m.inputs[k];
    if (in.joint != j.name) continue;
    const std::string& l = in.label;
    if (l.size() >= 7 && l.compare(l.size() - 7, 7, ".torque") == 0) j.torque_input = k;
    if (l.size() >= 6 && l.compare(l.size() - 6, 6, ".force") == 0) j.force_input = k;
  }
}

}  // namespace

Parts mechanism_parts(const Model& m) {
  Parts p;
  const int nb = static_cast<int>(m.bodies.size());
  p.block.assign(nb, false);
  p.slotted.assign(nb, false);
  for (const Constraint& c : m.constraints) {
    JointPart j;
    j.name = c.name;
    switch (c.kind()) {
      case ConstraintKind::revolute: {
        const auto& r = c.as<Constraint::Revolute>();
        j.body1 = r.body1;
        j.body2 = r.body2;
        j.kind = JointKind::revolute;
        j.node = r.b;
        break;
      }
      case ConstraintKind::prismatic:
      case ConstraintKind::slot: {
        const Constraint::Slider& s = *c.slider();
        j.body1 = s.body1;
        j.body2 = s.body2;
        j.kind = c.kind() == ConstraintKind::prismatic ? JointKind::prismatic : JointKind::slot;
        j.i = s.i;
        j.j = s.j;
        j.s = s.s;
        j.q = s.q;
        if (j.kind == JointKind::prismatic && s.body2 >= 0 && m.bodies[s.body2].nodes.size() == 1)
          p.block[s.body2] = true;
        if (j.kind == JointKind::slot && s.body1 >= 0) p.slotted[s.body1] = true;
        break;
      }
      default:
        continue;
    }
    attach_inputs(m, j);
    p.joints.push_back(std::move(j));
  }
  for (const MergeEdge& e : m.merge_edges) {
    if (e.rotation || e.child_body < 0 || e.reaction < 0) continue;
    const std::string& label = m.reactions[e.reaction].label;  // "<joint>.Fx"
    JointPart j;
    j.kind = JointKind::revolute;
    j.name = label.substr(0, label.rfind('.'));
    j.body1 = e.parent_body;
    j.body2 = e.child_body;
    j.node = m.bodies[e.child_body].nodes[e.child_slot / 2];
    attach_inputs(m, j);
    p.joints.push_back(std::move(j));
  }
  return p;
}

TracePoint trace_point(const Model& m, const std::string& label) {
  for (int k = 0; k < static_cast<int>(m.points.size()); ++k)
    if (m.points[k].name == label) {
      TracePoint t{label, m.points[k].point.body, {}, false};
      t.named = k;
      return t;
    }
  const auto dot = label.rfind('.');
  if (dot != std::string::npos) {
    const std::string body = label.substr(0, dot), what = label.substr(dot + 1);
    for (int b = 0; b < static_cast<int>(m.bodies.size()); ++b) {
      if (m.bodies[b].name != body) continue;
      if (what == "com") return {label, b, {}, true};
      for (size_t k = 0; k < m.bodies[b].nodes.size(); ++k)
        if (m.bodies[b].node_names[k] == label) return {label, b, m.bodies[b].nodes[k], false};
    }
  }
  std::vector<std::string> candidates;
  for (const NamedPoint& p : m.points) candidates.push_back(p.name);
  for (const Body& b : m.bodies) {
    candidates.push_back(b.name + ".com");
    candidates.insert(candidates.end(), b.node_names.begin(), b.node_names.end());
  }
  throw Error("render: no point '" + label + "' to trace" + did_you_mean(label, candidates) +
                  " (use \"body.node\", \"body.com\" or a named point)",
              label);
}

Vec2 point_position(const Model& m, const TracePoint& p,
                    const Eigen::Ref<const Eigen::VectorXd>& q0) {
  if (p.named >= 0) {
    const BodyPoint& bp = m.points[p.named].point;
    if (bp.body < 0) return bp.fixed;
    return local_position_of_point(m.bodies[bp.body], q0, bp.ci, bp.cj, bp.gamma, bp.rho);
  }
  return p.com ? com_position(m.bodies[p.body], q0) : node_position(p.node, q0);
}

}  // namespace mo2d::detail
