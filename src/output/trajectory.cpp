// Trajectory: the lookups of its columns by label.
#include "mo2d/trajectory.hpp"

#include "model/suggest.hpp"
#include "output/trajectory_labels.hpp"

namespace mo2d {

const char* to_string(RunKind k) {
  switch (k) {
    case RunKind::inverse:
      return "inverse";
    case RunKind::forward:
      return "forward";
  }
  return "?";
}

Trajectory detail::labelled_trajectory(const Model& m, RunKind kind) {
  Trajectory r;
  r.kind = kind;
  r.coordinate_labels = m.coordinate_labels;
  r.rate_labels = m.rate_labels;
  r.input_labels = m.input_labels();
  r.reaction_labels = m.reaction_labels();
  r.residual_labels = {"residual.position", "residual.velocity"};
  if (kind == RunKind::inverse) r.residual_labels.push_back("residual.acceleration");
  return r;
}

int Trajectory::column(const std::string& l) const {
  return label_index(coordinate_labels, l, "coordinate");
}
int Trajectory::rate_column(const std::string& l) const {
  return label_index(rate_labels, l, "quasi-velocity");
}
int Trajectory::effort(const std::string& l) const {
  return label_index(input_labels, l, "input");
}
int Trajectory::reaction(const std::string& l) const {
  return label_index(reaction_labels, l, "reaction");
}
int Trajectory::output(const std::string& l) const {
  return label_index(output_labels, l, "output column");
}

}  // namespace mo2d
