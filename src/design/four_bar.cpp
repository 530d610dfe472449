// Closed forms of a four-bar loop from its link lengths (mo2d/design.hpp): Grashof's class, the
// transmission angle by the cosine law, the limit (toggle) and dead positions. With the input
// pivot A0 at the origin and B0 = (d, 0): A = a (cos theta, sin theta), z = |A - B0|,
//   z^2 = a^2 + d^2 - 2 a d cos theta,   cos mu = (b^2 + c^2 - z^2) / (2 b c)
// (a input, b coupler, c output, d ground). The loop closes where |b - c| <= z <= b + c.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <sstream>

#include "design/design_internal.hpp"
#include "mo2d/error.hpp"

namespace mo2d {

namespace {

using design_detail::angle_of;
using design_detail::cross_z;
constexpr double kPiFourBar = std::numbers::pi;
constexpr double kNaNFourBar = std::numeric_limits<double>::quiet_NaN();

void check_lengths(const FourBarLengths& l) {
  const std::array<double, 4> v{l.ground, l.input, l.coupler, l.output};
  const char* names[4] = {"ground", "input", "coupler", "output"};
  double sum = 0;
  for (int k = 0; k < 4; ++k) {
    if (!std::isfinite(v[k]) || v[k] <= 0) {
      std::ostringstream s;
      s << "four-bar: the " << names[k] << " link's length " << v[k]
        << " is not a finite length > 0";
      throw Error(s.str(), names[k]);
    }
    sum += v[k];
  }
  for (int k = 0; k < 4; ++k)
    if (v[k] > sum - v[k]) {
      std::ostringstream s;
      s << "four-bar: the " << names[k] << " link (" << v[k]
        << " m) is longer than the other three together (" << sum - v[k]
        << " m): the loop cannot close";
      throw Error(s.str(), names[k]);
    }
}

// acos clamped to its domain only for rounding (|x| <= 1 + 1e-12); NaN beyond.
double safe_acos(double x) {
  if (std::abs(x) > 1 + 1e-12) return kNaNFourBar;
  return std::acos(std::clamp(x, -1.0, 1.0));
}

// Input angle (in [0, pi]) at which |A - B0| = z; NaN if the input never gets there.
double input_angle_at(const FourBarLengths& l, double z) {
  const double a = l.input, d = l.ground;
  return safe_acos((a * a + d * d - z * z) / (2 * a * d));
}

// A limit position: B at distance r = |A0 B| from A0 with the input in line with the coupler,
// u the unit vector A0 -> B: extended (r = a + b, A = a u) or folded (r = |b - a|; A = -a u when
// b > a, A = a u when a > b). Of the two positions of B (mirror images), the one of the branch of
// FourBarPositions (B on the clockwise side of B0 -> A). Writes the input and output angles.
void limit_position(const FourBarLengths& l, bool extended, double& theta, double& psi) {
  const double a = l.input, b = l.coupler, c = l.output, d = l.ground;
  const double r = extended ? a + b : std::abs(b - a);
  theta = psi = kNaNFourBar;
  if (r <= 0) return;  // a == b folded: B at A0, every input angle
  const double phi = safe_acos((d * d + r * r - c * c) / (2 * d * r));
  if (std::isnan(phi)) return;
  const Vec2 B0(l.ground, 0);
  for (double s : {1.0, -1.0}) {
    const Vec2 u(std::cos(s * phi), std::sin(s * phi));  // A0 -> B
    const Vec2 B = r * u;
    const Vec2 A = (!extended && a < b ? -a : a) * u;  // folded with b > a: A behind A0
    if (cross_z(A - B0, B - B0) < 0) {                 // clockwise from B0 -> A to B0 -> B
      theta = angle_of(A);
      psi = angle_of(B - B0);
      return;
    }
  }
}

}  // namespace

const char* to_string(GrashofClass k) {
  switch (k) {
    case GrashofClass::crank_rocker:
      return "crank-rocker";
    case GrashofClass::double_crank:
      return "double-crank";
    case GrashofClass::rocker_crank:
      return "rocker-crank";
    case GrashofClass::double_rocker:
      return "double-rocker";
    case GrashofClass::change_point:
      return "change-point";
    case GrashofClass::triple_rocker:
      return "triple-rocker";
  }
  return "?";
}

GrashofClass grashof_class(const FourBarLengths& l) {
  check_lengths(l);
  const std::array<double, 4> v{l.ground, l.input, l.coupler, l.output};
  const double s = *std::min_element(v.begin(), v.end());
  const double L = *std::max_element(v.begin(), v.end());
  const double pq = v[0] + v[1] + v[2] + v[3] - s - L;
  if (std::abs(s + L - pq) <= 1e-12 * L) return GrashofClass::change_point;
  if (s + L > pq) return GrashofClass::triple_rocker;
  if (l.ground == s) return GrashofClass::double_crank;
  if (l.input == s) return GrashofClass::crank_rocker;
  if (l.output == s) return GrashofClass::rocker_crank;
  return GrashofClass::double_rocker;
}

double transmission_angle(const FourBarLengths& l, double theta) {
  const double a = l.input, b = l.coupler, c = l.output, d = l.ground;
  const double z2 = a * a + d * d - 2 * a * d * std::cos(theta);
  return safe_acos((b * b + c * c - z2) / (2 * b * c));
}

FourBarPositions four_bar_positions(const FourBarLengths& l) {
  check_lengths(l);
  const double a = l.input, b = l.coupler, c = l.output, d = l.ground;
  FourBarPositions p;
  // z over a turn of the input: [|d - a|, d + a]; the loop closes for z in [|b - c|, b + c]
  const double z_lo = std::max(std::abs(d - a), std::abs(b - c));
  const double z_hi = std::min(d + a, b + c);
  const bool lo_limited = std::abs(d - a) < std::abs(b - c);
  const bool hi_limited = d + a > b + c;
  p.input_rotates = !lo_limited && !hi_limited;
  if (!p.input_rotates) {
    // z grows with theta on [0, pi]: the range is [theta(z_lo), theta(z_hi)] there (and its mirror)
    const double t_lo = lo_limited ? input_angle_at(l, std::abs(b - c)) : 0.0;
    const double t_hi = hi_limited ? input_angle_at(l, b + c) : kPiFourBar;
    if (lo_limited && hi_limited) {
      p.input_min = t_lo;
      p.input_max = t_hi;
    } else if (hi_limited) {  // through theta = 0
      p.input_min = -t_hi;
      p.input_max = t_hi;
    } else {  // through theta = pi
      p.input_min = t_lo;
      p.input_max = 2 * kPiFourBar - t_lo;
    }
  }
  limit_position(l, true, p.limit_extended, p.output_extended);
  limit_position(l, false, p.limit_folded, p.output_folded);
  // mu grows with z
  p.min_transmission = safe_acos((b * b + c * c - z_lo * z_lo) / (2 * b * c));
  p.max_transmission = safe_acos((b * b + c * c - z_hi * z_hi) / (2 * b * c));
  return p;
}

}  // namespace mo2d
