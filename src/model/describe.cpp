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
  return s.str();
}

}  // namespace mo2d
