#pragma once
// Internal helpers of src/design/: joint nodes by label, and the columns of each measure
// (four_bar_columns.cpp, frame_loads.cpp, bearings.cpp) appended by add_design_columns.
#include <Eigen/Core>
#include <cmath>
#include <string>
#include <vector>

#include "mo2d/design.hpp"

namespace mo2d::design_detail {

// The angle of a vector (rad) and the z component of u x v.
inline double angle_of(const Vec2& v) {
  return std::atan2(v.y(), v.x());
}
inline double cross_z(const Vec2& u, const Vec2& v) {
  return u.x() * v.y() - u.y() * v.x();
}

// A node of the model by its label ("ground.A0", "coupler.B"): a ground node (var -1, fixed) or
// a body node (NodeRef of Model::bodies). body: -1 for a ground node.
struct NodeAt {
  NodeRef ref{};
  int body = -1;
};
// Throws Error naming the label (with a suggestion) when the model has no such node; `what`
// starts the message.
NodeAt find_node(const Model& m, const std::string& label, const std::string& what);

// The columns of one measure: their labels and values (samples x labels).
struct Block {
  std::vector<std::string> labels;
  Eigen::MatrixXd values;
};
Block four_bar_columns(const Model& m, const Trajectory& r, const FourBarDef& f);
Block frame_columns(const Model& m, const Trajectory& r, const Vec2& about);
Block bearing_columns(const Trajectory& r);

}  // namespace mo2d::design_detail
