// The plot strip of an animation by a run's column (mo2d/render/animate.hpp, animation_plot):
// the column looked up among the run's CSV columns, its unit in the axis label.
#include <utility>

#include "mo2d/csv.hpp"
#include "mo2d/error.hpp"
#include "mo2d/render/animate.hpp"

namespace mo2d {

AnimationPlot animation_plot(const Model& model, const Trajectory& run, const std::string& label) {
  const std::pair<const std::vector<std::string>*, const Eigen::MatrixXd*> groups[] = {
      {&run.coordinate_labels, &run.q0},
      {&run.rate_labels, &run.q1},
      {&run.input_labels, &run.efforts},
      {&run.reaction_labels, &run.reactions},
      {&run.output_labels, &run.outputs}};
  const std::vector<std::string> labels = trajectory_csv_labels(run);
  const std::vector<std::string> units = trajectory_csv_units(model, run);
  for (const auto& [names, values] : groups)
    for (size_t c = 0; c < names->size(); ++c) {
      if ((*names)[c] != label) continue;
      AnimationPlot p;
      std::string unit;
      for (size_t k = 0; k < labels.size() && k < units.size(); ++k)
        if (labels[k] == label) unit = units[k];
      p.label = unit.empty() ? label : label + " (" + unit + ")";
      const Eigen::VectorXd v = values->col(static_cast<Eigen::Index>(c));
      p.values.assign(v.data(), v.data() + v.size());
      return p;
    }
  std::string known;
  for (const auto& [names, values] : groups)
    for (const auto& n : *names) known += (known.empty() ? "" : ", ") + n;
  throw Error("render: the animation's plot strip: the run has no column '" + label +
                  "' (columns: " + known + ")",
              label);
}

}  // namespace mo2d
