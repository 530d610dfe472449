// The unit of every CSV column (mo2d/csv.hpp, trajectory_csv_units), from the kind of the column:
// what the model numbered it as (node coordinate, slider, extra coordinate, rotation rate), the
// suffix the model gives efforts, reactions and the requested output columns.
#include <string_view>

#include "mo2d/csv.hpp"
#include "mo2d/error.hpp"

namespace mo2d {

namespace {

bool ends_with(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

// u per second: m -> m/s, m/s -> m/s² (rad likewise); "" stays "".
std::string per_second(const std::string& u) {
  if (u.empty()) return u;
  if (ends_with(u, "/s")) return u + "²";
  return u + "/s";
}

// Coordinate v (< n0): node coordinates and sliders are lengths; an extra coordinate has the unit
// its rate terms share (rad for body rotation rates), "" when they mix units.
std::string coordinate_unit(const Model& m, int v, int depth = 0) {
  for (const Constraint& c : m.constraints) {
    const auto* d = std::get_if<Constraint::Coordinate>(&c.def);
    if (d == nullptr || d->coord != v) continue;
    if (depth > 16) return "";  // extra coordinates defined by each other
    std::string unit;
    for (const auto& term : d->rate_terms) {
      const int w = term.first.var;
      const std::string u = w >= m.n0 ? "rad" : coordinate_unit(m, w, depth + 1);
      if (u.empty() || (!unit.empty() && u != unit)) return "";
      unit = u;
    }
    return unit;
  }
  return "m";
}

std::string rate_unit(const Model& m, int v) {
  return v >= m.n0 ? "rad/s" : per_second(coordinate_unit(m, v));
}

std::string effort_unit(const std::string& label) {
  if (ends_with(label, ".torque")) return "N·m";
  if (ends_with(label, ".force")) return "N";
  return "";
}

std::string reaction_unit(const std::string& label) {
  if (ends_with(label, ".Fx") || ends_with(label, ".Fy")) return "N";
  if (ends_with(label, ".T")) return "N·m";
  return "";  // .lambda: the multiplier of a user constraint, in the units of its expression
}

bool is_torsional_spring(const Model& m, std::string_view name) {
  for (const TorsionalLoad& s : m.torsional_springs)
    if (s.name == name) return true;
  return false;
}

// Output columns (mo2d/output_columns.hpp): loads, named points, centres of mass; and the design
// columns (mo2d/design.hpp): shaking force and moment, bearing loads, four-bar angles.
std::string output_unit(const Model& m, const std::string& label) {
  const auto field = [&](std::string_view f) { return ends_with(label, f); };
  if (field(".fx") || field(".fy") || field(".tension")) return "N";
  if (field(".Fx") || field(".Fy") || field(".F") || field(".load")) return "N";
  if (field(".M")) return "N·m";
  if (field("_angle")) return "rad";
  if (field(".torque")) return "N·m";
  if (field(".power")) return "W";
  if (field(".length") || field(".x") || field(".y")) return "m";
  if (field(".vx") || field(".vy")) return "m/s";
  if (field(".rate"))
    return is_torsional_spring(m, std::string_view(label).substr(0, label.size() - 5)) ? "rad/s"
                                                                                       : "m/s";
  return "";
}

}  // namespace

std::vector<std::string> trajectory_csv_units(const Model& m, const Trajectory& r) {
  if (r.coordinate_labels != m.coordinate_labels || r.rate_labels != m.rate_labels)
    throw Error("CSV units: the trajectory is not a run of model '" + m.name + "'", m.name);
  std::vector<std::string> u{"s"};
  for (int v = 0; v < m.n0; ++v) u.push_back(coordinate_unit(m, v));
  for (int v = 0; v < m.n1; ++v) u.push_back(rate_unit(m, v));
  for (int v = 0; v < m.n1; ++v) u.push_back(per_second(rate_unit(m, v)));
  for (const auto& l : r.input_labels) u.push_back(effort_unit(l));
  for (const auto& l : r.reaction_labels) u.push_back(reaction_unit(l));
  if (r.has_energies()) u.insert(u.end(), 6, "J");
  u.insert(u.end(), r.residual_labels.size(), "");  // norms over rows of different units
  for (const auto& l : r.output_labels) u.push_back(output_unit(m, l));
  return u;
}

}  // namespace mo2d
