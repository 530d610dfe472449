// The lumped transmission's parameters from the shafts' invariants (mo2d/transmission.hpp).
#include "mo2d/transmission.hpp"

#include <algorithm>
#include <cmath>

#include "mo2d/error.hpp"

namespace mo2d {
namespace {

void check(bool ok, const std::string& name, const std::string& what) {
  if (!ok) throw Error("transmission '" + name + "': " + what, name);
}

}  // namespace

LumpedTransmission lump_transmission(const TransmissionHousing& housing,
                                     std::span<const TransmissionShaft> shafts,
                                     const std::string& name) {
  check(!shafts.empty(), name, "needs at least one shaft");
  check(std::isfinite(housing.mass) && housing.mass >= 0 && std::isfinite(housing.inertia) &&
            housing.inertia >= 0 && housing.com.allFinite(),
        name, "the housing's mass, inertia and centre of mass must be finite and >= 0");
  LumpedTransmission out;
  double mass = 0;
  Vec2 moment(0, 0);
  for (size_t k = 0; k < shafts.size(); ++k) {
    const TransmissionShaft& sh = shafts[k];
    check(std::isfinite(sh.mass) && sh.mass >= 0 && std::isfinite(sh.inertia) && sh.inertia >= 0 &&
              sh.axis.allFinite() && std::isfinite(sh.ratio),
          name,
          "shaft " + std::to_string(k) + ": mass and inertia must be finite and >= 0, " +
              "axis and ratio finite");
    mass += sh.mass;
    moment += sh.mass * sh.axis;
    out.sigma += sh.inertia;
    out.s += sh.ratio * sh.inertia;
    out.p += sh.ratio * sh.ratio * sh.inertia;
  }
  check(out.p > 0, name, "the shafts have no rotational inertia (sum rho_k^2 J_k = 0)");
  out.axis = mass > 0 ? Vec2(moment / mass) : shafts[0].axis;
  double spread = 0;
  for (const TransmissionShaft& sh : shafts) spread += sh.mass * (sh.axis - out.axis).squaredNorm();
  out.housing = {housing.mass, housing.com, housing.inertia + spread};
  out.shaft_mass = mass / 2;
  out.ratio = std::sqrt(out.p / out.sigma);
  out.inertia_a = (out.sigma + out.s / out.ratio) / 2;
  // (Sigma - S / rho_e) / 2 >= 0 by Cauchy-Schwarz; clamp its rounding
  out.inertia_b = std::max(0.0, (out.sigma - out.s / out.ratio) / 2);
  return out;
}

}  // namespace mo2d

// ---- the element: add_transmission ----
namespace mo2d {
namespace {

constexpr double kShaftArm = 0.02;  // m, a shaft body's second node from its axis (its angle)

// A shaft on `axis`, its second node along the unit vector `dir`.
BodyDef shaft_body(const std::string& name, Vec2 axis, Vec2 dir, double mass, double inertia) {
  return {.name = name,
          .nodes = {{"C", axis}, {"R", axis + kShaftArm * dir}},
          .mass = mass,
          .inertia = inertia};
}

// A law times a constant (a torque mapped by the cotangent lift).
Law scaled(const Law& law, double c) {
  if (!law) return {};
  return Law(law.args, [f = law.f, c](std::span<const Jet> x, Jet t) { return f(x, t) * c; });
}

BodyDef& housing_of(System& s, const TransmissionDef& d) {
  BodyDef* h = s.find_body(d.housing);
  check(h != nullptr, d.name, "undefined housing body '" + d.housing + "'");
  check(h->nodes.size() >= 2, d.name,
        "the housing '" + d.housing + "' needs two nodes (its angle)");
  check((h->nodes[1].position - h->nodes[0].position).norm() > 0, d.name,
        "the housing '" + d.housing + "' has its first two nodes at one point");
  check(h->shape.empty(), d.name,
        "the housing '" + d.housing + "' is given by its shape; give its nodes instead");
  return *h;
}

void add_full(System& s, const TransmissionDef& d, const TransmissionShaftDef& in) {
  const std::string& T = d.name;
  BodyDef& housing = housing_of(s, d);
  for (const auto& sh : d.shafts) housing.nodes.push_back({T + "_" + sh.name, sh.shaft.axis});
  for (const auto& sh : d.shafts) {
    s.add_body(shaft_body(sh.name, sh.shaft.axis, {1, 0}, sh.shaft.mass, sh.shaft.inertia));
    s.add_revolute({.name = T + "_" + sh.name,
                    .node_a = d.housing + "." + T + "_" + sh.name,
                    .node_b = sh.name + ".C"});
    if (&sh != &in)
      s.add_gear({.name = T + "_" + sh.name + "_mesh",
                  .body = sh.name,
                  .driver = in.name,
                  .carrier = d.housing,
                  .ratio = sh.shaft.ratio});
    if (sh.torque)
      s.add_torque({.name = T + "_" + sh.name + "_torque", .body = sh.name, .torque = sh.torque});
  }
  s.add_coordinate({.name = T + ".phi",
                    .rate = {{in.name + ".w", 1.0}, {d.housing + ".w", -1.0}},
                    .initial = 0.0,
                    .input = T + ".torque"});
}

void add_lumped(System& s, const TransmissionDef& d, const LumpedTransmission& L) {
  const std::string& T = d.name;
  BodyDef& housing = housing_of(s, d);
  housing.inertia = L.housing.inertia;
  housing.nodes.push_back({T + "_axis", L.axis});
  // A and B along the housing's first two nodes: NAME_pair.phi starts at 0 (NAME.phi's rows,
  // numbered before the pair's, read it at its initial value)
  const Vec2 dir = (housing.nodes[1].position - housing.nodes[0].position).normalized();
  for (const char* ab : {"a", "b"}) {
    const std::string body = T + "_" + ab;
    s.add_body(
        shaft_body(body, L.axis, dir, L.shaft_mass, ab[0] == 'a' ? L.inertia_a : L.inertia_b));
    s.add_revolute({.name = body + "_bearing",
                    .node_a = d.housing + "." + T + "_axis",
                    .node_b = body + ".C"});
  }
  s.add_gear({.name = T + "_pair",
              .body = T + "_b",
              .driver = T + "_a",
              .carrier = d.housing,
              .ratio = -1});
  // tau_k from outside: tau_k on the housing and rho_k tau_k / rho_e on A relative to it
  for (const auto& sh : d.shafts) {
    if (!sh.torque) continue;
    const double on_a = sh.shaft.ratio / L.ratio;
    s.add_torque({.name = T + "_" + sh.name + "_torque_a",
                  .body = T + "_a",
                  .torque = scaled(sh.torque, on_a)});
    s.add_torque({.name = T + "_" + sh.name + "_torque_housing",
                  .body = d.housing,
                  .torque = scaled(sh.torque, 1 - on_a)});
  }
  // phi = (theta_a - theta_c) / rho_e: the input u maps to u / rho_e on A relative to the housing
  s.add_coordinate({.name = T + ".phi",
                    .rate = {{T + "_pair.phi.rate", 1 / L.ratio}},
                    .initial = 0.0,
                    .input = T + ".torque"});
}

}  // namespace

void add_transmission(System& system, const TransmissionDef& def) {
  const auto in = std::find_if(def.shafts.begin(), def.shafts.end(),
                               [&](const TransmissionShaftDef& s) { return s.name == def.input; });
  check(!def.shafts.empty(), def.name, "needs at least one shaft");
  check(in != def.shafts.end(), def.name, "the input '" + def.input + "' is not one of its shafts");
  check(in->shaft.ratio == 1, def.name,
        "the input shaft '" + def.input + "' has ratio 1 (the others' ratios are relative to it)");
  const BodyDef& h = housing_of(system, def);
  std::vector<TransmissionShaft> shafts;
  for (const auto& sh : def.shafts) shafts.push_back(sh.shaft);
  const TransmissionHousing housing{.mass = h.mass, .com = {0, 0}, .inertia = h.inertia};
  const LumpedTransmission L = lump_transmission(housing, shafts, def.name);
  if (def.fidelity == TransmissionFidelity::full)
    add_full(system, def, *in);
  else
    add_lumped(system, def, L);
}

}  // namespace mo2d
