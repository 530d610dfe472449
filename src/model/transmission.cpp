// The lumped transmission's parameters from the shafts' invariants (mo2d/transmission.hpp).
#include "mo2d/transmission.hpp"

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
