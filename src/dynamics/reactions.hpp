#pragma once
// Joint reactions from the constraint multipliers (shared by inverse and forward dynamics).
// With M a1 = f + B u - A^T lambda: a joint kept as constraint rows reads its reaction from lambda
// (Model::reactions[k].row, factor); a joint eliminated by variable reduction gets it by splitting
// the merged node's (or rotation's) generalized force between the bodies that share it, walking
// Model::merge_edges from the leaves: each body's own share h = f + B u - M a - A^T lambda
// (its loads, inputs, inertia and its own constraint rows) is balanced by the joint forces.
#include <Eigen/Core>
#include <vector>

#include "mo2d/model.hpp"

namespace mo2d::detail {

// One entry of a velocity row attributed to a body-local slot.
struct SlotEntry {
  int row, slot;
  double value;
};

// Offsets of each merge edge's forces (2 for a node, 1 for a rotation); returns the total.
int merge_edge_layout(const Model& m, std::vector<int>& offsets);

// `local` holds the body-local M a - f on entry and is overwritten. Writes every reaction.
void joint_reactions(const Model& m, const std::vector<SlotEntry>& entries,
                     const Eigen::Ref<const Eigen::VectorXd>& lambda,
                     const Eigen::Ref<const Eigen::VectorXd>& u, Eigen::Ref<Eigen::VectorXd> local,
                     std::vector<double>& edge_force, const std::vector<int>& edge_offset,
                     Eigen::Ref<Eigen::VectorXd> reactions);

}  // namespace mo2d::detail
