// PD control as an effort law (mo2d/control.hpp).
#include "mo2d/control.hpp"

#include <cmath>
#include <utility>
#include <vector>

#include "mo2d/error.hpp"

namespace mo2d {
namespace {
bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}
}  // namespace

std::string rate_label(const std::string& coordinate) {
  const std::string stem = coordinate.substr(0, coordinate.size() - 1);
  if (ends_with(coordinate, ".x")) return stem + "vx";
  if (ends_with(coordinate, ".y")) return stem + "vy";
  if (ends_with(coordinate, ".q")) return stem + "v";
  return coordinate + ".rate";
}

Law pd_control(PdControl c) {
  for (auto [gain, name] : {std::pair{c.kp, "kp"}, std::pair{c.kd, "kd"}})
    if (!std::isfinite(gain) || gain < 0)
      throw Error("PD control of '" + c.coordinate + "': " + name + " must be finite and >= 0",
                  c.coordinate);
  if (c.coordinate.empty()) throw Error("PD control: no coordinate", "coordinate");
  std::vector<std::string> args = {c.coordinate,
                                   c.rate.empty() ? rate_label(c.coordinate) : c.rate};
  auto f = [c = std::move(c)](std::span<const Jet> x, Jet t) {
    // r, r', r'' at t.v exactly; along the caller's direction (t.d, t.dd) r is a Jet by the chain
    // rule and r' to first order (r''' is not available); u_ff is a plain time function (its
    // derivative along t is taken as 0)
    const Jet r = c.reference ? c.reference(Jet(t.v, 1, 0)) : Jet();
    const double ff = c.feed_forward ? c.feed_forward(t.v) : 0.0;
    const Jet r_t = chain(t, r.v, r.d, r.dd), rate_t(r.d, r.dd * t.d, 0);
    return Jet(ff) + c.kp * (r_t - x[0]) + c.kd * (rate_t - x[1]);
  };
  return Law(std::move(args), std::move(f));
}

}  // namespace mo2d
