#pragma once
// What a frame draws, read off a Model once: the joints (including the revolute joints that
// variable reduction merged away, recovered from Model::merge_edges), their actuators, and the
// points chosen for traces. Internal to mo2d_render.
#include <string>
#include <vector>

#include "mo2d/model.hpp"

namespace mo2d::detail {

enum class JointKind { revolute, prismatic, slot };

struct JointPart {
  JointKind kind = JointKind::revolute;
  std::string name{};
  int body1 = -1, body2 = -1;  // -1: ground
  NodeRef node{};              // revolute: the joint's node (both bodies share its position)
  NodeRef i{}, j{}, s{};       // prismatic / slot: axis i -> j on body 1, slider (pin) s on body 2
  int q = -1;                  // prismatic / slot: index of the slider coordinate in q0
  int torque_input = -1;       // index in Model::inputs, -1 if not actuated
  int force_input = -1;
};

// A point traced over the motion: a node, a body's centre of mass or a named point.
struct TracePoint {
  std::string label{};
  int body = -1;   // colour; -1 ground
  NodeRef node{};  // used when com is false and named < 0
  bool com = false;
  int named = -1;  // index in Model::points
};

struct Parts {
  std::vector<JointPart> joints{};
  std::vector<bool> block{};    // per body: a one-node body drawn as its prismatic slider block
  std::vector<bool> slotted{};  // per body: carries a slot (drawn wider)
};

Parts mechanism_parts(const Model& m);
// "body.node", "body.com" or a named point; throws Error naming the label if there is no such
// point.
TracePoint trace_point(const Model& m, const std::string& label);
Vec2 point_position(const Model& m, const TracePoint& p,
                    const Eigen::Ref<const Eigen::VectorXd>& q0);

}  // namespace mo2d::detail
