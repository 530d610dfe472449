// describe(): a readable summary of a model.
#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

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
  // the derived quantities a law may read besides the labels above (mo2d/law.hpp), sorted; the
  // nodes' own coordinates are left out (they are the labels above or constants)
  std::vector<std::string> derived;
  for (const auto& [label, q] : m.quantities)
    if (q.kind != Quantity::Kind::point_x && q.kind != Quantity::Kind::point_y &&
        q.kind != Quantity::Kind::point_vx && q.kind != Quantity::Kind::point_vy)
      derived.push_back(label);
  for (const auto& p : m.points) derived.push_back(p.name + ".x|y|vx|vy");
  for (const auto& b : m.bodies) derived.push_back(b.name + ".com.x|y|vx|vy");
  std::sort(derived.begin(), derived.end());
  constexpr size_t kShown = 40;
  s << "\nquantities for laws:";
  for (size_t k = 0; k < derived.size() && k < kShown; ++k) s << " " << derived[k];
  if (derived.size() > kShown) s << " ... (" << derived.size() << " in all)";
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
