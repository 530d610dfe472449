// Joint reactions from multipliers, with the split at eliminated joints (see the header).
#include "dynamics/reactions.hpp"

namespace mo2d::detail {

int merge_edge_layout(const Model& m, std::vector<int>& offsets) {
  offsets.clear();
  int total = 0;
  for (const auto& e : m.merge_edges) {
    offsets.push_back(total);
    total += e.rotation ? 1 : 2;
  }
  return total;
}

void joint_reactions(const Model& m, const std::vector<SlotEntry>& entries,
                     const Eigen::Ref<const Eigen::VectorXd>& lambda,
                     const Eigen::Ref<const Eigen::VectorXd>& u, Eigen::Ref<Eigen::VectorXd> local,
                     std::vector<double>& edge_force, const std::vector<int>& edge_offset,
                     Eigen::Ref<Eigen::VectorXd> reactions) {
  for (int k = 0; k < m.n_reactions(); ++k)
    if (m.reactions[k].row >= 0) reactions[k] = m.reactions[k].factor * lambda[m.reactions[k].row];
  if (m.merge_edges.empty()) return;
  // h = f + B u - M a - A^T lambda, per body slot
  local *= -1.0;
  for (int k = 0; k < m.n_inputs(); ++k)
    for (const auto& [ref, coef] : m.inputs[k].terms)
      if (ref.body >= 0) local[m.bodies[ref.body].offset + ref.slot] += coef * u[k];
  for (const auto& e : entries) local[e.slot] -= e.value * lambda[e.row];
  for (size_t k = 0; k < m.merge_edges.size(); ++k) {
    const MergeEdge& e = m.merge_edges[k];
    const int n = e.rotation ? 1 : 2;
    const int base = m.bodies[e.child_body].offset + e.child_slot;
    double* F = edge_force.data() + edge_offset[k];
    for (int i = 0; i < n; ++i) {
      F[i] = -local[base + i];
      for (int ce : e.child_edges) F[i] += edge_force[edge_offset[ce] + i];
      reactions[e.reaction + i] = e.sign * F[i];
    }
  }
}

}  // namespace mo2d::detail
