#pragma once
// Contact kind: a point P (or a circle of radius rho around it: a knife-edge or a roller follower)
// against a closed cam profile (internal to src/contact/). The profile is given in its body's
// frame as a polar table r(phi) (a periodic C² cubic spline, mo2d/table.hpp) around A, phi from
// the axis A -> B: with e1 = (B - A) / |B - A| and e2 = z x e1 (a rotation by theta = atan2 of
// B - A), the curve is
//
//   c(phi) = r(phi) (cos phi, sin phi)                          (body frame)
//   c' = r' u + r u_perp,   c'' = (r'' - r) u + 2 r' u_perp     (u = (cos, sin), u_perp = z x u)
//
// traversed counter-clockwise (r > 0), with unit tangent t = c' / |c'|, outward normal
// n = (t_y, -t_x) and signed curvature (> 0 convex)
//
//   kappa = (r^2 + 2 r'^2 - r r'') / (r^2 + r'^2)^(3/2).
//
// The point in the body frame is p = (e1 . (P - A), e2 . (P - A)). Its closest point c(phi*)
// minimises F(phi) = |p - c(phi)|^2 / 2: F' = -(p - c) . c' = 0, F'' = |c'|^2 - (p - c) . c''.
// It is found by a safeguarded Newton on phi from the previous closest point (the polar angle of p
// at the first call): a Newton step (at most 0.5 rad) where F'' > 0, a step of 0.25 rad downhill
// otherwise, and, unless it is a Newton step shorter than 0.05 rad (near the minimum, where
// F's round-off exceeds its decrease), halved until F decreases; converged at a step below
// 1e-13 (1 + |phi|) rad; at most kProfileIterations steps, else an Error
// naming the contact (the run adds the time). With D = n . (p - c(phi*)) the signed distance:
//
//   g = D - rho
//   dg/dP = n_w,   dg/dB = -(p x n) (z x (B - A)) / |B - A|^2,   dg/dA = -n_w - dg/dB
//
// (n_w = n_x e1 + n_y e2 the world normal; the closest point is stationary, so g's gradient is
// that of the distance with phi* held: the cam body's part through the closest point fixed on the
// body, its rotation by dtheta moving p by -dtheta z x p). Along the motion, with the points
// moving on Jets (as in point_line.hpp: the points are linear in the node coordinates), p(s) has
// p' and p'', and the signed distance function's Hessian at p is kappa / (1 + kappa D) t t^T
// (the curvature of the curve through p parallel to the profile), so
//
//   g' = n . p',   J' q1 = g'' = n . p'' + kappa / (1 + kappa D) (t . p')^2
//
// (1 + kappa D > 0: p nearer a concave part than its centre of curvature; else an Error). The
// load-time check (profile_problem) refuses a table that is not a periodic cubic spline of period
// 2 pi, a radius r <= 0, and a roller larger than the smallest radius of curvature -1 / kappa of a
// concave part (an undercut: the roller cannot reach the profile there). Checked against central
// differences in tests/contact/gap_test.cpp.
#include <string>

#include "mo2d/jet.hpp"
#include "mo2d/model.hpp"
#include "mo2d/table.hpp"

namespace mo2d::detail {

inline constexpr int kProfileIterations = 60;

// The closest point of a profile to a point p of its body's frame.
struct ProfileFoot {
  double phi = 0;    // its angle (rad, unwrapped)
  Vec2 c, t, n;      // the point, the unit tangent and the outward unit normal (body frame)
  double kappa = 0;  // the signed curvature there (1/m, > 0 convex)
  double D = 0;      // the signed distance n . (p - c) (m)
};

// The closest point of the profile r (polar table, see above) to p, Newton from phi0 (NaN: from
// the polar angle of p). Throws Error naming `contact` if it does not converge.
ProfileFoot profile_foot(const LookupTable& r, const Vec2& p, double phi0,
                         const std::string& contact);

// The gap of a circle of radius rho around P against the profile r around A (axis A -> B), on
// Jets (value, g', J' q1 along the points' motion); phi: the previous closest point's angle in,
// this one's out. foot (if not null): the closest point. Throws Error naming `contact` (a line A
// -> B of zero length, no convergence, the point beyond a concave part's centre of curvature).
Jet profile_gap(const LookupTable& r, Jet px, Jet py, Jet ax, Jet ay, Jet bx, Jet by, double rho,
                double& phi, const std::string& contact, ProfileFoot* foot = nullptr);

// The gradients (dg/dP, dg/dA, dg/dB) above from the closest point at (P, A, B).
struct ProfileGradient {
  Vec2 dP, dA, dB;
};
ProfileGradient profile_gradient(const ProfileFoot& f, const Vec2& A, const Vec2& B);

// What makes the table unfit for a profile with a follower of radius rho (see above), as a
// sentence naming the table and the angle (deg), or "" when it fits.
std::string profile_problem(const LookupTable& r, double rho);

// The profile's point at phi in the world, with the frame A -> B (drawing).
Vec2 profile_point(const LookupTable& r, const Vec2& A, const Vec2& B, double phi);

}  // namespace mo2d::detail
