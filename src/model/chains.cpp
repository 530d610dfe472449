// Stage 6 of build_model, chains (ChainDef; their geometry and forces in dynamics/chain.hpp): the
// sprockets' centres as body points, the coordinates of their unwrapped angles (flatten added
// "name.theta_a" and "name.theta_b"), the parameters checked; then, once the initial
// configuration is assembled, the constants that make each span's material length equal to its
// straight length there.
#include <cmath>
#include <limits>
#include <memory>

#include "dynamics/chain.hpp"
#include "dynamics/points.hpp"
#include "mo2d/error.hpp"
#include "mo2d/quasi_steady.hpp"
#include "model/build_stages.hpp"

namespace mo2d::build {
namespace {

void check_positive(double v, bool strict, const std::string& what, const char* field,
                    const std::string& name) {
  if (!std::isfinite(v) || v < 0 || (strict && v == 0))
    throw Error(what + ": " + field + " must be finite and " + (strict ? "> 0" : ">= 0") +
                    " (got " + std::to_string(v) + ")",
                name);
}

double rest(const std::optional<double>& r, const std::string& what, const char* field,
            const std::string& name) {
  if (!r) return std::numeric_limits<double>::quiet_NaN();  // init_chains: the initial length
  check_positive(*r, true, what, field, name);
  return *r;
}

}  // namespace

void add_chains(const Flat& flat, Model& m) {
  for (const auto& cd : flat.chains) {
    const ChainDef& d = cd.def;
    const std::string name = cd.prefix + d.name;
    const std::string what = "chain '" + name + "'";
    check_positive(d.radius_a, true, what, "radius_a", name);
    check_positive(d.radius_b, true, what, "radius_b", name);
    // inextensible: the stiffness only tells the fidelity report what was reduced
    check_positive(d.stiffness, d.fidelity != ChainFidelity::inextensible, what, "stiffness", name);
    check_positive(d.damping, false, what, "damping", name);
    ChainLoad c;
    c.name = name;
    c.a = body_point(m, cd.prefix, d.body_a, d.centre_a, what + ".body_a");
    c.b = body_point(m, cd.prefix, d.body_b, d.centre_b, what + ".body_b");
    if (c.a.body < 0 && c.b.body < 0) throw Error(what + " joins two ground sprockets", name);
    if (c.a.body >= 0 && c.a.body == c.b.body)
      throw Error(what + ": both sprockets are on body '" + m.bodies[c.a.body].name + "'", name);
    c.body_a = c.a.body;
    c.body_b = c.b.body;
    if (c.body_a >= 0) c.theta_a = m.coordinate(name + ".theta_a");
    if (c.body_b >= 0) c.theta_b = m.coordinate(name + ".theta_b");
    c.radius_a = d.radius_a;
    c.radius_b = d.radius_b;
    c.stiffness = d.stiffness;
    c.damping = d.damping;
    c.rest_upper = rest(d.rest_upper, what, "rest_upper", name);
    c.rest_lower = rest(d.rest_lower, what, "rest_lower", name);
    c.fidelity = d.fidelity;
    if (d.fidelity == ChainFidelity::quasi_steady) {  // the inextensible rows, with held lengths
      c.fidelity = ChainFidelity::inextensible;
      for (auto& h : c.held) {
        const auto cell = std::make_shared<HeldLength>();  // its length: add_inextensible_chains
        h = std::shared_ptr<double>(cell, &cell->length);  // aliasing: shares the cell
      }
    }
    m.chains.push_back(std::move(c));
  }
}

void init_chains(Model& m) {
  for (ChainLoad& c : m.chains) {
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(m.n1);
    const Vec2 pa = detail::point_state(m, c.a, m.q0, zero).p,
               pb = detail::point_state(m, c.b, m.q0, zero).p;
    const double D = (pb - pa).norm();
    if (!(D > c.radius_a + c.radius_b))
      throw Error("chain '" + c.name + "': the pitch circles overlap (centre distance " +
                      std::to_string(D) + " m, radii " + std::to_string(c.radius_a) + " and " +
                      std::to_string(c.radius_b) + " m)",
                  c.name);
    detail::init_chain(m, c);
  }
}

}  // namespace mo2d::build
