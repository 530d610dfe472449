// Model: label lookups and the positions derived from a body's nodes.
#include "mo2d/model.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <variant>

#include "constraints/constraints.hpp"
#include "mo2d/error.hpp"
#include "model/suggest.hpp"

namespace mo2d {

using detail::perp;

namespace {
template <class T>
constexpr bool in_kind_order() {
  return std::is_same_v<std::variant_alternative_t<static_cast<size_t>(T::kind), Constraint::Def>,
                        T>;
}
static_assert(in_kind_order<Constraint::Rigid>() && in_kind_order<Constraint::Revolute>() &&
                  in_kind_order<Constraint::Prismatic>() && in_kind_order<Constraint::Slider>() &&
                  in_kind_order<Constraint::Coordinate>() &&
                  in_kind_order<Constraint::UserPosition>() &&
                  in_kind_order<Constraint::UserVelocity>() && in_kind_order<Constraint::Gear>() &&
                  std::variant_size_v<Constraint::Def> == 8,
              "Constraint::Def lists one struct per ConstraintKind, in the order of the enum");
}  // namespace

const char* constraint_kind_name(ConstraintKind k) {
  switch (k) {
    case ConstraintKind::rigid:
      return "rigid body";
    case ConstraintKind::revolute:
      return "revolute";
    case ConstraintKind::prismatic:
      return "prismatic";
    case ConstraintKind::slot:
      return "pin-in-slot";
    case ConstraintKind::coordinate:
      return "coordinate";
    case ConstraintKind::user_position:
      return "user (position)";
    case ConstraintKind::user_velocity:
      return "user (velocity)";
    case ConstraintKind::gear:
      return "gear";
  }
  return "?";
}

void Constraint::wrong_kind(ConstraintKind wanted) const {
  throw Error("constraint '" + name + "' is a " + constraint_kind_name(kind()) +
                  " constraint, not a " + constraint_kind_name(wanted) + " one",
              name);
}

double SketchReport::max_moved() const {
  double m = 0;
  for (const auto& n : nodes) m = std::max(m, n.moved);
  return m;
}

std::vector<std::string> Model::input_labels() const {
  std::vector<std::string> out;
  for (const auto& in : inputs) out.push_back(in.label);
  return out;
}

std::vector<std::string> Model::reaction_labels() const {
  std::vector<std::string> out;
  for (const auto& r : reactions) out.push_back(r.label);
  return out;
}

int Model::coordinate(const std::string& label) const {
  auto it = coordinate_index.find(label);
  if (it == coordinate_index.end() && fixed_coordinates.count(label))
    throw Error("coordinate '" + label + "' is fixed (its node is joined to the ground)", label);
  if (it == coordinate_index.end()) {
    std::vector<std::string> names;
    for (const auto& [k, v] : coordinate_index) names.push_back(k);
    std::sort(names.begin(), names.end());
    throw Error("unknown coordinate '" + label + "'" + did_you_mean(label, names), label);
  }
  return it->second;
}

int Model::rate(const std::string& label) const {
  auto it = rate_index.find(label);
  if (it == rate_index.end()) {
    std::vector<std::string> names;
    for (const auto& [k, v] : rate_index) names.push_back(k);
    std::sort(names.begin(), names.end());
    throw Error("unknown quasi-velocity '" + label + "'" + did_you_mean(label, names), label);
  }
  return it->second;
}

Vec2 com_position(const Body& b, const Eigen::Ref<const Eigen::VectorXd>& q0) {
  Vec2 pi = node_position(b.nodes[b.ci], q0);
  if (b.cj < 0) return pi;
  const Vec2 d = node_position(b.nodes[b.cj], q0) - pi;
  return pi + b.gamma * d + b.rho * perp(d);
}

double body_angle(const Body& b, const Eigen::Ref<const Eigen::VectorXd>& q0) {
  if (b.nodes.size() < 2) return 0.0;
  const Vec2 d = node_position(b.nodes[1], q0) - node_position(b.nodes[0], q0);
  return std::atan2(d.y(), d.x());
}

}  // namespace mo2d
