// The refusal of parameters that change what an inverse run's positions, rates and accelerations
// depend on (mo2d/sensitivity.hpp, check_parameter_models): the parameter models are compared
// with the run's model, exactly (a number that does not depend on the parameter is computed by
// the same operations on the same values, so it is bitwise equal).
#include <cmath>
#include <string>

#include "mo2d/error.hpp"
#include "mo2d/sensitivity.hpp"

namespace mo2d {

namespace {

[[noreturn]] void refuse(const ParameterModels& p, const std::string& what) {
  throw Error("sensitivity to '" + p.name + "': it changes " + what +
                  "; geometric parameters are not supported yet (only parameters that set mass "
                  "data and load coefficients)",
              p.name);
}

bool differ(double a, double b) {
  return !(a == b);
}  // NaN differs
bool differ(const Vec2& a, const Vec2& b) {
  return differ(a.x(), b.x()) || differ(a.y(), b.y());
}
bool differ(const std::vector<std::pair<VarRef, double>>& a,
            const std::vector<std::pair<VarRef, double>>& b) {
  if (a.size() != b.size()) return true;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (a[k].first.var != b[k].first.var || differ(a[k].second, b[k].second)) return true;
  return false;
}
template <class T>
bool differ_pairs(const std::vector<std::pair<T, double>>& a,
                  const std::vector<std::pair<T, double>>& b) {
  if (a.size() != b.size()) return true;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (a[k].first != b[k].first || differ(a[k].second, b[k].second)) return true;
  return false;
}

void check_structure(const Model& m, const Model& q, const ParameterModels& p) {
  if (m.n0 != q.n0 || m.n1 != q.n1 || m.m0 != q.m0 || m.m1 != q.m1 || m.dof != q.dof ||
      m.n_slots != q.n_slots || m.bodies.size() != q.bodies.size() ||
      m.constraints.size() != q.constraints.size() || m.inputs.size() != q.inputs.size() ||
      m.reactions.size() != q.reactions.size() || m.chains.size() != q.chains.size() ||
      m.reduced_springs.size() != q.reduced_springs.size() ||
      m.reduced_torsional.size() != q.reduced_torsional.size() ||
      m.ground_positions.size() != q.ground_positions.size())
    refuse(p, "the model's structure (its variables, bodies or constraints)");
}

void check_bodies(const Model& m, const Model& q, const ParameterModels& p) {
  for (std::size_t i = 0; i < m.bodies.size(); ++i) {
    const Body &a = m.bodies[i], &b = q.bodies[i];
    if (a.geometry.size() != b.geometry.size() || a.has_omega != b.has_omega ||
        a.frame.size() != b.frame.size())
      refuse(p, "the structure of body '" + a.name + "'");
    for (std::size_t k = 0; k < a.geometry.size(); ++k)
      if (differ(a.geometry[k], b.geometry[k]) || differ(a.nodes[k].fixed, b.nodes[k].fixed))
        refuse(p, "the geometry (body '" + a.name + "' node '" + a.node_names[k] + "')");
    if (differ(a.l01, b.l01)) refuse(p, "the geometry (body '" + a.name + "')");
    for (std::size_t k = 0; k < a.frame.size(); ++k)
      if (differ(a.frame[k], b.frame[k]))
        refuse(p, "the geometry (body '" + a.name + "' node '" + a.node_names[k + 2] + "')");
  }
  for (std::size_t k = 0; k < m.ground_positions.size(); ++k)
    if (differ(m.ground_positions[k], q.ground_positions[k]))
      refuse(p, "the geometry (ground node '" + m.ground_names[k] + "')");
}

// The numbers of a constraint its rows use (the rigid and revolute rows use the bodies' data).
bool constraint_differs(const Constraint& a, const Constraint& b) {
  if (a.kind() != b.kind()) return true;
  if (const auto* s = a.slider()) {
    const auto* t = b.slider();
    if (differ(s->length, t->length)) return true;
  }
  if (a.kind() == ConstraintKind::prismatic)
    return differ(a.as<Constraint::Prismatic>().lock_angle,
                  b.as<Constraint::Prismatic>().lock_angle);
  if (a.kind() == ConstraintKind::coordinate) {
    const auto &x = a.as<Constraint::Coordinate>(), &y = b.as<Constraint::Coordinate>();
    return differ(x.offset, y.offset) || differ(x.rate_terms, y.rate_terms) ||
           differ_pairs(x.coord_terms, y.coord_terms) || differ_pairs(x.angle_terms, y.angle_terms);
  }
  if (a.kind() == ConstraintKind::gear) {
    const auto &x = a.as<Constraint::Gear>(), &y = b.as<Constraint::Gear>();
    return differ(x.ratio, y.ratio) || differ(x.offset, y.offset);
  }
  return false;
}

void check_constraints(const Model& m, const Model& q, const ParameterModels& p) {
  for (std::size_t k = 0; k < m.constraints.size(); ++k)
    if (constraint_differs(m.constraints[k], q.constraints[k]))
      refuse(p, "the constraint '" + m.constraints[k].name + "'");
  for (std::size_t k = 0; k < m.inputs.size(); ++k)
    if (differ(m.inputs[k].terms, q.inputs[k].terms))
      refuse(p, "the input '" + m.inputs[k].label + "' (its column of B)");
  for (std::size_t k = 0; k < m.reactions.size(); ++k)
    if (differ(m.reactions[k].factor, q.reactions[k].factor))
      refuse(p, "the reaction '" + m.reactions[k].label + "'");
  for (std::size_t k = 0; k < m.reduced_springs.size(); ++k) {
    const ReducedSpring &a = m.reduced_springs[k], &b = q.reduced_springs[k];
    if (differ(a.spring.rest_length, b.spring.rest_length) ||
        (a.held_length && b.held_length && differ(*a.held_length, *b.held_length)))
      refuse(p, "the length held by the reduced spring '" + a.spring.name + "'");
  }
  for (std::size_t k = 0; k < m.reduced_torsional.size(); ++k) {
    const ReducedTorsional &a = m.reduced_torsional[k], &b = q.reduced_torsional[k];
    if (differ(a.spring.rest, b.spring.rest) ||
        (a.held_angle && b.held_angle && differ(*a.held_angle, *b.held_angle)))
      refuse(p, "the angle held by the reduced torsional spring '" + a.spring.name + "'");
  }
  for (std::size_t k = 0; k < m.chains.size(); ++k) {
    const ChainLoad &a = m.chains[k], &b = q.chains[k];
    if (a.constraint >= 0 &&
        (differ(a.radius_a, b.radius_a) || differ(a.radius_b, b.radius_b) ||
         differ(a.rest_upper, b.rest_upper) || differ(a.rest_lower, b.rest_lower) ||
         differ(a.offset_upper, b.offset_upper) || differ(a.offset_lower, b.offset_lower)))
      refuse(p, "the length held by the inextensible chain '" + a.name + "'");
  }
}

}  // namespace

double sensitivity_step(double value) {
  return value == 0 ? kSensitivityStep : kSensitivityStep * std::abs(value);
}

void check_parameter_models(const Model& m, const ParameterModels& p) {
  if (!m.frictions.empty())
    throw Error("sensitivity to '" + p.name + "': '" + m.name + "' has joint friction ('" +
                    m.frictions[0].name +
                    "'), whose forces depend on the reactions nonlinearly; sensitivities of runs "
                    "with friction are not supported yet",
                p.name);
  if (p.at.size() != 3 || !(p.step > 0) || !std::isfinite(p.step))
    throw Error("sensitivity to '" + p.name +
                    "': it needs the models at p + h, p + 2h, p + 3h with a step h > 0",
                p.name);
  for (const Model& q : p.at) {
    check_structure(m, q, p);
    check_bodies(m, q, p);
    check_constraints(m, q, p);
    for (int k = 0; k < m.n0; ++k)
      if (differ(m.q0[k], q.q0[k]))
        refuse(p, "the assembled initial configuration ('" + m.coordinate_labels[k] + "')");
  }
}

}  // namespace mo2d
