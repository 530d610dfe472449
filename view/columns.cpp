// The columns of a run by their CSV labels (trajectory_csv_labels, src/output/csv.cpp), in the
// same order; checked against those labels so that a new column there cannot shift these.
#include "mo2d/csv.hpp"
#include "mo2d/error.hpp"
#include "mo2d/view.hpp"

namespace mo2d {

std::vector<std::pair<std::string, Eigen::VectorXd>> trajectory_columns(const Trajectory& r) {
  std::vector<std::pair<std::string, Eigen::VectorXd>> c;
  auto block = [&](const std::vector<std::string>& labels, const Eigen::MatrixXd& x,
                   const char* suffix) {
    for (size_t k = 0; k < labels.size(); ++k)
      c.emplace_back(labels[k] + suffix, x.col(static_cast<Eigen::Index>(k)));
  };
  c.emplace_back("t", r.time);
  block(r.coordinate_labels, r.q0, "");
  block(r.rate_labels, r.q1, "");
  block(r.rate_labels, r.a1, ".dot");
  block(r.input_labels, r.efforts, "");
  block(r.reaction_labels, r.reactions, "");
  if (r.has_energies()) {
    c.emplace_back("energy.kinetic", r.kinetic);
    c.emplace_back("energy.potential", r.potential);
    c.emplace_back("work.inputs", r.input_work);
    c.emplace_back("energy.dissipated", r.dissipated);
    c.emplace_back("work.loads", r.load_work);
    c.emplace_back("work.constraints", r.constraint_work);
  }
  block(r.residual_labels, r.residuals, "");
  block(r.output_labels, r.outputs, "");
  const std::vector<std::string> labels = trajectory_csv_labels(r);
  bool same = labels.size() == c.size();
  for (size_t k = 0; same && k < c.size(); ++k) same = labels[k] == c[k].first;
  if (!same)
    throw Error("viewer: the run's columns do not follow trajectory_csv_labels (internal error)");
  return c;
}

}  // namespace mo2d
