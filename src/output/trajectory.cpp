// Trajectory: the lookups of its columns by label.
#include "mo2d/trajectory.hpp"

#include "model/suggest.hpp"

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

}  // namespace mo2d
