// Contact kind: a point or a circle against a cam profile r(phi) (the maths: profile.hpp).
#include "contact/profile.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "mo2d/error.hpp"
#include "run/format.hpp"

namespace mo2d::detail {
namespace {

constexpr double kProfileTurn = 2 * std::numbers::pi;

// The curve and its first two derivatives at phi (body frame).
struct ProfileCurve {
  Vec2 c, d1, d2;
  double r = 0, r1 = 0, r2 = 0;
};

ProfileCurve profile_curve_at(const LookupTable& r, double phi) {
  const Jet s = r(Jet(phi, 1.0, 0.0));  // r, r', r''
  const Vec2 u(std::cos(phi), std::sin(phi)), up(-u.y(), u.x());
  return {s.v * u, s.d * u + s.v * up, (s.dd - s.v) * u + 2 * s.d * up, s.v, s.d, s.dd};
}

double profile_half_square(const Vec2& v) {
  return 0.5 * v.squaredNorm();
}

double profile_wrap(double phi) {
  return phi - kProfileTurn * std::floor(phi / kProfileTurn);
}

// The closest point from a converged phi, made a function of p alone (the events compare gaps
// evaluated from different starts): phi wrapped into [-pi, pi) and rounded to a multiple of
// 2^-30 rad, then two Newton steps (the error 1e-9 rad squared twice: below round-off). Only a phi
// within round-off of a multiple of 2^-30 can round two ways: one in about 1e7.
ProfileFoot profile_polish(const LookupTable& r, const Vec2& p, double phi) {
  constexpr double kGrid = 1073741824.0;                          // 2^30
  phi = profile_wrap(phi + kProfileTurn / 2) - kProfileTurn / 2;  // [-pi, pi): phi = 0 inside
  phi = std::round(phi * kGrid) / kGrid;
  ProfileCurve k = profile_curve_at(r, phi);
  for (int it = 0; it < 2; ++it) {
    const Vec2 w = p - k.c;
    const double F2 = k.d1.squaredNorm() - w.dot(k.d2);
    if (!(F2 > 0)) break;  // (a stalled search's end: kept)
    phi += w.dot(k.d1) / F2;
    k = profile_curve_at(r, phi);
  }
  const double speed2 = k.d1.squaredNorm(), speed = std::sqrt(speed2);
  ProfileFoot out;
  out.phi = phi;
  out.c = k.c;
  out.t = k.d1 / speed;
  out.n = Vec2(out.t.y(), -out.t.x());
  out.kappa = (k.r * k.r + 2 * k.r1 * k.r1 - k.r * k.r2) / (speed2 * speed);
  out.D = out.n.dot(p - k.c);
  return out;
}

}  // namespace

ProfileFoot profile_foot(const LookupTable& r, const Vec2& p, double phi0,
                         const std::string& contact) {
  double phi = std::isfinite(phi0) ? phi0 : std::atan2(p.y(), p.x());
  ProfileCurve k = profile_curve_at(r, phi);
  double F = profile_half_square(p - k.c);
  double step = 0;
  bool stalled = false;  // no step, however short, decreases F: a minimum to round-off
  for (int it = 0; it < kProfileIterations; ++it) {
    const Vec2 w = p - k.c;
    const double f = -w.dot(k.d1), speed2 = k.d1.squaredNorm();
    const double F2 = speed2 - w.dot(k.d2);
    // F'' <= 0 (near a local maximum of the distance): a step of 0.25 rad downhill
    step = F2 > 0 ? std::clamp(-f / F2, -0.5, 0.5) : (f > 0 ? -0.25 : 0.25);
    if ((F2 > 0 && (std::abs(step) <= 1e-13 * (1 + std::abs(phi)) || f == 0)) || stalled)
      return profile_polish(r, p, phi);
    // a Newton step near the minimum (F'' > 0, short) is taken whole: F's round-off (|p - c|
    // times that of r at the wrapped angle) exceeds its decrease there; others are halved until F
    // does not increase
    if (F2 > 0 && std::abs(step) <= 0.05) {
      phi += step;
      k = profile_curve_at(r, phi);
      F = profile_half_square(p - k.c);
      continue;
    }
    stalled = true;
    for (int h = 0; h < 60; ++h) {
      const ProfileCurve trial = profile_curve_at(r, phi + step);
      const double Ft = profile_half_square(p - trial.c);
      if (Ft <= F * (1 + 1e-14) + 1e-300) {
        phi += step;
        k = trial;
        F = Ft;
        stalled = false;
        break;
      }
      step *= 0.5;
    }
  }
  throw Error("contact '" + contact + "': the closest point of its profile '" + r.name() +
                  "' to the point (" + fmt(p.x()) + ", " + fmt(p.y()) +
                  ") m of the profile's frame was not found in " +
                  std::to_string(kProfileIterations) + " Newton steps (phi " + fmt(phi) +
                  " rad, last step " + fmt(step) + ")",
              contact);
}

Jet profile_gap(const LookupTable& r, Jet px, Jet py, Jet ax, Jet ay, Jet bx, Jet by, double rho,
                double& phi, const std::string& contact, ProfileFoot* foot) {
  const Jet dx = bx - ax, dy = by - ay;
  const Jet L = hypot(dx, dy);
  if (!(L.v > 0))
    throw Error("contact '" + contact + "': its profile's axis a -> b has zero length", contact);
  const Jet e1x = dx / L, e1y = dy / L;  // e2 = (-e1y, e1x)
  const Jet wx = px - ax, wy = py - ay;
  const Jet u = e1x * wx + e1y * wy, v = e1x * wy - e1y * wx;  // p in the body frame
  const ProfileFoot f = profile_foot(r, Vec2(u.v, v.v), phi, contact);
  phi = profile_wrap(f.phi);
  if (foot) *foot = f;
  const double bend = 1 + f.kappa * f.D;
  if (!(bend > 0))
    throw Error("contact '" + contact + "': its point is " + fmt(std::abs(f.D)) +
                    " m from its profile '" + r.name() +
                    "' at phi = " + fmt(phi * 180 / std::numbers::pi) +
                    " deg, beyond the centre of curvature of a concave part (radius " +
                    fmt(-1 / f.kappa) + " m): its closest point is not unique",
                contact);
  const double tp = f.t.x() * u.d + f.t.y() * v.d;
  return {f.D - rho, f.n.x() * u.d + f.n.y() * v.d,
          f.n.x() * u.dd + f.n.y() * v.dd + f.kappa / bend * tp * tp};
}

ProfileGradient profile_gradient(const ProfileFoot& f, const Vec2& A, const Vec2& B) {
  const Vec2 d = B - A;
  const double L2 = d.squaredNorm(), L = std::sqrt(L2);
  const Vec2 e1 = d / L, e2(-e1.y(), e1.x());
  const Vec2 nw = f.n.x() * e1 + f.n.y() * e2;
  const Vec2 p = f.c + f.D * f.n;  // the point in the body frame
  const double pxn = p.x() * f.n.y() - p.y() * f.n.x();
  const Vec2 dB = -pxn * Vec2(-d.y(), d.x()) / L2;
  return {nw, -nw - dB, dB};
}

std::string profile_problem(const LookupTable& r, double rho) {
  const std::string what = "its profile table '" + r.name() + "'";
  if (r.options().extrapolation != Extrapolation::periodic)
    return what + " is not periodic (extrapolate: periodic): a cam profile is a closed curve";
  if (r.options().interpolation != Interpolation::cubic)
    return what + " is not a cubic spline: a polyline profile has corners (no normal there)";
  const double period = r.x_max() - r.x_min();
  if (!(std::abs(period - kProfileTurn) <= 1e-9 * kProfileTurn))
    return what + " covers " + fmt(period) + " rad, not one turn (2 pi rad)";
  // sampled: the knots and 32 points inside each piece
  constexpr int kPerPiece = 32;
  const std::span<const double> x = r.x();
  double worst_r = 1e300, at_r = 0, worst_rc = 1e300, at_rc = 0;
  for (size_t i = 0; i + 1 < x.size(); ++i)
    for (int j = 0; j < kPerPiece; ++j) {
      const double phi = x[i] + (x[i + 1] - x[i]) * j / kPerPiece;
      const ProfileCurve k = profile_curve_at(r, phi);
      if (k.r < worst_r) {
        worst_r = k.r;
        at_r = phi;
      }
      const double speed2 = k.d1.squaredNorm();
      const double kappa =
          (k.r * k.r + 2 * k.r1 * k.r1 - k.r * k.r2) / (speed2 * std::sqrt(speed2));
      if (kappa < 0 && -1 / kappa < worst_rc) {
        worst_rc = -1 / kappa;
        at_rc = phi;
      }
    }
  const double deg = 180 / std::numbers::pi;
  if (!(worst_r > 0))
    return what + " has a radius r = " + fmt(worst_r) + " m <= 0 at phi = " + fmt(at_r * deg) +
           " deg (the profile must enclose its centre a)";
  if (rho > 0 && rho >= worst_rc)
    return "its roller (radius " + fmt(rho) +
           " m) is not smaller than the smallest radius of "
           "curvature of a concave part of " +
           what + ", " + fmt(worst_rc) + " m at phi = " + fmt(at_rc * deg) +
           " deg: an undercut (the roller cannot follow the profile there)";
  return {};
}

Vec2 profile_point(const LookupTable& r, const Vec2& A, const Vec2& B, double phi) {
  const Vec2 e1 = (B - A).normalized(), e2(-e1.y(), e1.x());
  const double rad = r(phi);
  return A + rad * (std::cos(phi) * e1 + std::sin(phi) * e2);
}

}  // namespace mo2d::detail
