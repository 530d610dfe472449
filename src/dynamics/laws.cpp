// Laws at a state (mo2d/law.hpp): the quantities a law reads, from (q0, q1), and its value.
#include <array>
#include <cmath>
#include <sstream>

#include "constraints/common.hpp"
#include "dynamics/derivatives.hpp"
#include "dynamics/points.hpp"
#include "mo2d/error.hpp"
#include "mo2d/model.hpp"
#include "run/format.hpp"
#include "run/user_code.hpp"

namespace mo2d {
namespace {

double theta(const Model& m, int body, const Eigen::Ref<const Eigen::VectorXd>& q0) {
  return body < 0 ? 0.0 : body_angle(m.bodies[body], q0);
}
double omega(const Model& m, int body, const Eigen::Ref<const Eigen::VectorXd>& q1) {
  return body < 0 ? 0.0 : omega_value(m.bodies[body].omega, q1);
}

// |p_b - p_a| and its rate e . (v_b - v_a), e the unit vector from a to b (0 where they meet).
std::pair<double, double> distance(const Model& m, const Quantity& q,
                                   const Eigen::Ref<const Eigen::VectorXd>& q0,
                                   const Eigen::Ref<const Eigen::VectorXd>& q1) {
  const detail::PointState a = detail::point_state(m, q.a, q0, q1);
  const detail::PointState b = detail::point_state(m, q.b, q0, q1);
  const Vec2 d = b.p - a.p;
  const double l = d.norm();
  const Vec2 e = l > 0 ? Vec2(d / l) : Vec2(0, 0);  // as a spring's state (the same round-off)
  return {l, e.dot(b.v - a.v)};
}

}  // namespace

double quantity_value(const Model& m, const Quantity& q,
                      const Eigen::Ref<const Eigen::VectorXd>& q0,
                      const Eigen::Ref<const Eigen::VectorXd>& q1) {
  using K = Quantity::Kind;
  switch (q.kind) {
    case K::coordinate:
      return q0[q.var];
    case K::rate:
      return q1[q.var];
    case K::constant:
      return q.value;
    case K::point_x:
      return detail::point_state(m, q.a, q0, q1).p.x();
    case K::point_y:
      return detail::point_state(m, q.a, q0, q1).p.y();
    case K::point_vx:
      return detail::point_state(m, q.a, q0, q1).v.x();
    case K::point_vy:
      return detail::point_state(m, q.a, q0, q1).v.y();
    case K::distance:
      return distance(m, q, q0, q1).first - q.value;
    case K::distance_rate:
      return distance(m, q, q0, q1).second;
    case K::body_angle:
      return detail::wrap_angle(theta(m, q.body1, q0) - q.value);
    case K::relative_angle:
      return detail::wrap_angle(theta(m, q.body2, q0) - theta(m, q.body1, q0) - q.value);
    case K::relative_rate:
      return omega(m, q.body2, q1) - omega(m, q.body1, q1);
  }
  return 0;
}

namespace detail {

Jet call_law(const CompiledLaw& law, std::span<const Jet> x, double t, const char* role,
             const std::string& element) {
  return call_user_code([&] { return law.f(x, Jet(t)); }, role, element, t);
}

}  // namespace detail

double law_value(const Model& m, const CompiledLaw& law,
                 const Eigen::Ref<const Eigen::VectorXd>& q0,
                 const Eigen::Ref<const Eigen::VectorXd>& q1, double t, const char* role,
                 const std::string& element) {
  if (!law.f) return 0;
  std::array<Jet, kMaxLawArgs> x;
  const size_t n = law.args.size();
  for (size_t k = 0; k < n; ++k) x[k] = Jet(quantity_value(m, law.args[k], q0, q1));
  const double v = detail::call_law(law, std::span<const Jet>(x.data(), n), t, role, element).v;
  if (std::isfinite(v)) return v;
  std::ostringstream s;
  s << role << " '" << element << "' is not finite at t = " << detail::fmt(t) << " s";
  if (n > 0) {
    s << " (value " << detail::fmt(v) << " at";
    for (size_t k = 0; k < n; ++k)
      s << (k ? ", " : " ") << law.labels[k] << " = " << detail::fmt(x[k].v);
    s << ")";
  }
  throw Error(s.str(), element, t);
}

}  // namespace mo2d
