// The derivative columns of a run with sensitivities (mo2d/sensitivity.hpp,
// add_sensitivity_columns): what mo2d inverse --sensitivity writes to the CSV and Python's
// mo2d.inverse(..., sensitivity=[...]) returns as r["d(COLUMN)/d(NAME)"].
#include "mo2d/sensitivity.hpp"

namespace mo2d {

std::string sensitivity_label(const std::string& label, const std::string& p) {
  return "d(" + label + ")/d(" + p + ")";
}

void add_sensitivity_columns(Trajectory& r, const InverseSensitivity& d) {
  const Eigen::Index n = r.time.size(), old = r.outputs.cols();
  const Eigen::Index per = r.efforts.cols() + r.reactions.cols();
  const auto k = static_cast<Eigen::Index>(d.parameters.size());
  Eigen::MatrixXd out(n, old + k * per);
  if (old > 0) out.leftCols(old) = r.outputs;
  for (Eigen::Index j = 0; j < k; ++j) {
    const auto i = static_cast<std::size_t>(j);
    const Eigen::Index c = old + j * per;
    out.middleCols(c, r.efforts.cols()) = d.efforts[i];
    out.middleCols(c + r.efforts.cols(), r.reactions.cols()) = d.reactions[i];
    for (const auto& l : r.input_labels)
      r.output_labels.push_back(sensitivity_label(l, d.parameters[i]));
    for (const auto& l : r.reaction_labels)
      r.output_labels.push_back(sensitivity_label(l, d.parameters[i]));
  }
  r.outputs = std::move(out);
}

}  // namespace mo2d
