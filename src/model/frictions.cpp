// Stage 6 of build_model (with the loads): joint friction (FrictionDef -> FrictionLoad). Each
// friction gets the generalized-force column of its joint's own motion (the slide coordinate q of
// a prismatic joint or pin-in-slot; w2 - w1 across a revolute joint, like an actuator's torque),
// the reaction column it reads its normal force from and, for a slide, the constraint that gives
// the axis direction. Evaluated in src/dynamics/friction.cpp.
#include <cmath>

#include "constraints/common.hpp"
#include "mo2d/error.hpp"
#include "model/build_stages.hpp"
#include "model/suggest.hpp"

namespace mo2d::build {
namespace {

void check_coefficient(double v, const std::string& what, const char* field,
                       const std::string& name) {
  if (!std::isfinite(v) || v < 0)
    throw Error(what + ": " + field + " must be finite and >= 0", name);
}

int reaction_column(const Model& m, const std::string& joint) {
  for (int k = 0; k < m.n_reactions(); ++k)
    if (m.reactions[k].label == joint + ".Fx") return k;
  return -1;
}

// The slide of a prismatic joint or pin-in-slot named `joint`: its constraint index, or -1.
int slide_constraint(const Model& m, const std::string& joint) {
  for (int k = 0; k < static_cast<int>(m.constraints.size()); ++k)
    if (m.constraints[k].name == joint && m.constraints[k].slider()) return k;
  return -1;
}

// The revolute joint named `joint` (index in flat.revolutes), or -1.
int revolute_index(const Flat& flat, const std::string& joint) {
  for (size_t k = 0; k < flat.revolutes.size(); ++k)
    if (flat.revolutes[k].prefix + flat.revolutes[k].def.name == joint) return static_cast<int>(k);
  return -1;
}

[[noreturn]] void unknown_joint(const Flat& flat, const std::string& what, const std::string& joint,
                                const std::string& name) {
  std::vector<std::string> names;
  for (const auto& j : flat.revolutes) names.push_back(j.prefix + j.def.name);
  for (const auto& j : flat.prismatics) names.push_back(j.prefix + j.def.name);
  for (const auto& j : flat.slots) names.push_back(j.prefix + j.def.name);
  throw Error(what + ": unknown joint '" + joint +
                  "' (friction acts in a revolute, prismatic or "
                  "pin-in-slot joint)" +
                  did_you_mean(joint, names),
              name);
}

void revolute_terms(const Model& m, int body1, int body2, const std::string& what,
                    const std::string& name, FrictionLoad& l) {
  for (auto [body, sgn] : {std::pair{body2, 1.0}, std::pair{body1, -1.0}}) {
    if (body < 0) continue;
    if (!m.bodies[body].has_omega)
      throw Error(what + ": body '" + m.bodies[body].name +
                      "' has no rotation (a one-node body without inertia): no friction torque",
                  name);
    l.terms.push_back({detail::ref_w(m, m.bodies[body].omega), sgn});
  }
}

}  // namespace

void add_frictions(const Flat& flat, const Elements& el, const Reduced& red, Model& m) {
  for (const auto& fr : flat.frictions) {
    const std::string name = fr.prefix + fr.def.name;
    const std::string what = "friction '" + name + "'";
    check_name(fr.def.name, "friction");
    check_coefficient(fr.def.viscous, what, "viscous", name);
    check_coefficient(fr.def.mu, what, "mu", name);
    check_coefficient(fr.def.radius, what, "radius", name);
    if (!std::isfinite(fr.def.regularization) || fr.def.regularization <= 0)
      throw Error(what + ": regularization must be finite and > 0", name);
    FrictionLoad l;
    l.name = name;
    l.joint = fr.prefix + fr.def.joint;
    l.viscous = fr.def.viscous;
    l.mu = fr.def.mu;
    l.radius = fr.def.radius;
    l.regularization = fr.def.regularization;
    l.reaction = reaction_column(m, l.joint);
    l.slider = slide_constraint(m, l.joint);
    if (l.slider >= 0) {
      if (fr.def.radius != 0)
        throw Error(what + ": radius is for a revolute joint ('" + l.joint + "' is a slide)", name);
      l.terms.push_back({VarRef{m.constraints[l.slider].slider()->q, -1, -1}, 1.0});
    } else if (const int k = revolute_index(flat, l.joint); k >= 0) {
      if (fr.def.mu != 0 && fr.def.radius == 0)
        throw Error(what + ": Coulomb friction in revolute joint '" + l.joint +
                        "' needs the pin radius (torque = mu * radius * |reaction|)",
                    name);
      revolute_terms(m, el.body[red.revolutes[k][0]], el.body[red.revolutes[k][1]], what, name, l);
    } else {
      unknown_joint(flat, what, l.joint, name);
    }
    if (l.reaction < 0) throw Error(what + ": joint '" + l.joint + "' has no reaction", name);
    m.frictions.push_back(std::move(l));
  }
}

}  // namespace mo2d::build
