// Joint friction: rates, normal forces, values and their generalized forces (see the header).
#include "dynamics/friction.hpp"

#include <algorithm>
#include <cmath>

#include "mo2d/dynamics.hpp"

namespace mo2d {
namespace detail {

double friction_rate(const FrictionLoad& f, const Eigen::Ref<const Eigen::VectorXd>& q1) {
  double v = 0;
  for (const auto& [ref, coef] : f.terms)
    if (ref.var >= 0) v += coef * q1[ref.var];
  return v;
}

double friction_normal(const Model& m, const FrictionLoad& f,
                       const Eigen::Ref<const Eigen::VectorXd>& q0,
                       const Eigen::Ref<const Eigen::VectorXd>& reactions) {
  const Vec2 r{reactions[f.reaction], reactions[f.reaction + 1]};
  if (f.slider < 0) return f.radius * r.norm();
  const Constraint::Slider& s = *m.constraints[f.slider].slider();
  const Vec2 d = node_position(s.j, q0) - node_position(s.i, q0);
  return std::abs(r.x() * d.y() - r.y() * d.x()) / d.norm();
}

void add_friction_forces(const Model& m, const Eigen::Ref<const Eigen::VectorXd>& values,
                         double sign, bool to_local, Eigen::Ref<Eigen::VectorXd> local,
                         Eigen::Ref<Eigen::VectorXd> gen) {
  for (size_t k = 0; k < m.frictions.size(); ++k)
    for (const auto& [ref, coef] : m.frictions[k].terms) {
      const double F = sign * coef * values[static_cast<int>(k)];
      if (to_local && ref.body >= 0)
        local[m.bodies[ref.body].offset + ref.slot] += F;
      else if (ref.var >= 0)
        gen[ref.var] += F;
    }
}

double friction_power(const Model& m, const Eigen::Ref<const Eigen::VectorXd>& values,
                      const Eigen::Ref<const Eigen::VectorXd>& q1) {
  double p = 0;
  for (size_t k = 0; k < m.frictions.size(); ++k)
    p += values[static_cast<int>(k)] * friction_rate(m.frictions[k], q1);
  return p;
}

double friction_change(const Model& m, const Eigen::Ref<const Eigen::VectorXd>& a,
                       const Eigen::Ref<const Eigen::VectorXd>& b,
                       const Eigen::Ref<const Eigen::VectorXd>& reactions, int* worst) {
  const double R = reactions.size() ? reactions.lpNorm<Eigen::Infinity>() : 0.0;
  double change = 0;
  for (int k = 0; k < a.size(); ++k) {
    const FrictionLoad& f = m.frictions[k];
    const double carry = f.mu * (f.slider < 0 ? f.radius : 1.0) * R;
    const double scale = std::max({std::abs(a[k]), std::abs(b[k]), carry, 1e-300});
    const double e = std::abs(a[k] - b[k]) / scale;
    if (!(e <= change)) {  // (a NaN is the worst)
      change = e;
      if (worst) *worst = k;
    }
  }
  return change;
}

}  // namespace detail

void friction_forces(const Model& m, const Eigen::Ref<const VectorXd>& q0,
                     const Eigen::Ref<const VectorXd>& q1,
                     const Eigen::Ref<const VectorXd>& reactions, bool regularized,
                     Eigen::Ref<VectorXd> out) {
  for (size_t k = 0; k < m.frictions.size(); ++k) {
    const FrictionLoad& f = m.frictions[k];
    const double v = detail::friction_rate(f, q1);
    const double N = f.mu != 0 ? detail::friction_normal(m, f, q0, reactions) : 0.0;
    const double sgn =
        regularized ? std::tanh(v / f.regularization) : static_cast<double>((v > 0) - (v < 0));
    out[static_cast<int>(k)] = -f.viscous * v - f.mu * N * sgn;
  }
}

}  // namespace mo2d
