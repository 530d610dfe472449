// mo2d inverse --sensitivity: columns, JSON and table (sensitivity_output.hpp).
#include "sensitivity_output.hpp"

#include <cstdio>
#include <nlohmann/json.hpp>

namespace mo2d::cli {

using json = nlohmann::ordered_json;

namespace {

json summary_json(const Eigen::VectorXd& t, const Eigen::VectorXd& x, const Eigen::VectorXd& dx) {
  const SummaryDerivative s = summary_derivative(t, x, dx);
  return {{"peak", s.d_peak}, {"max", s.d_max}, {"min", s.d_min},
          {"mean", s.d_mean}, {"rms", s.d_rms}, {"peak_to_peak", s.d_peak_to_peak}};
}

}  // namespace

std::string add_sensitivity_json(const std::string& summary, const Trajectory& r,
                                 const InverseSensitivity& d,
                                 const std::vector<ParameterModels>& parameters) {
  json j = json::parse(summary);
  json all = json::object();
  for (std::size_t k = 0; k < d.parameters.size(); ++k) {
    json columns = json::object();
    for (Eigen::Index c = 0; c < r.efforts.cols(); ++c)
      columns[sensitivity_label(r.input_labels[c], d.parameters[k])] =
          summary_json(r.time, r.efforts.col(c), d.efforts[k].col(c));
    for (Eigen::Index c = 0; c < r.reactions.cols(); ++c)
      columns[sensitivity_label(r.reaction_labels[c], d.parameters[k])] =
          summary_json(r.time, r.reactions.col(c), d.reactions[k].col(c));
    all[d.parameters[k]] = {
        {"value", parameters[k].value}, {"step", parameters[k].step}, {"columns", columns}};
  }
  j["sensitivities"] = all;
  return j.dump(2) + "\n";
}

void print_sensitivity_table(const Trajectory& r, const InverseSensitivity& d) {
  std::printf("  %-24s %-12s %16s %16s %16s\n", "input (sensitivity)", "parameter", "d peak |u|",
              "d RMS", "d peak-to-peak");
  for (Eigen::Index c = 0; c < r.efforts.cols(); ++c)
    for (std::size_t k = 0; k < d.parameters.size(); ++k) {
      const SummaryDerivative s = summary_derivative(r.time, r.efforts.col(c), d.efforts[k].col(c));
      std::printf("  %-24s %-12s %16.10g %16.10g %16.10g\n", r.input_labels[c].c_str(),
                  d.parameters[k].c_str(), s.d_peak, s.d_rms, s.d_peak_to_peak);
    }
}

}  // namespace mo2d::cli
