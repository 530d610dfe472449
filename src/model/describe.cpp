// describe(): a readable summary of a model.
#include <sstream>

#include "mo2d/model.hpp"

namespace mo2d {

std::string describe(const Model& m) {
  std::ostringstream s;
  s << "model '" << m.name << "': " << m.bodies.size() << " bodies, " << m.n0 << " coordinates, "
    << m.n1 << " quasi-velocities, " << m.m0 << " position rows, " << m.m1 << " velocity rows, "
    << m.dof << " DOF" << (m.holonomic ? "" : " (non-holonomic)") << "\n";
  s << "coordinates:";
  for (const auto& l : m.coordinate_labels) s << " " << l;
  s << "\nquasi-velocities:";
  for (const auto& l : m.rate_labels) s << " " << l;
  s << "\ninputs:";
  for (const auto& in : m.inputs) s << " " << in.label;
  s << "\nreactions:";
  for (const auto& r : m.reactions) s << " " << r.label;
  s << "\n";
  if (!m.sketch.nodes.empty()) {
    s << "sketch: bodies given by their shape, placed where their joints close nearest to their "
         "sketch (largest move "
      << m.sketch.max_moved() << " m):\n";
    for (const auto& n : m.sketch.nodes)
      s << "  " << n.label << " sketched (" << n.sketch.x() << ", " << n.sketch.y() << ") -> ("
        << n.assembled.x() << ", " << n.assembled.y() << "), moved " << n.moved << " m\n";
    for (const auto& w : m.sketch.warnings) s << "warning: " << w << "\n";
  }
  return s.str();
}

}  // namespace mo2d
