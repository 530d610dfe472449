#pragma once
// Contact kind: a point P (or a circle of radius r around it) against the line through A and B
// (internal to src/contact/). With d = B - A, L = |d|, w = P - A and the unit normal
// n = z x d / L (the free side is the left of A -> B):
//
//   g = (d x w) / L - r = n . (P - A) - r
//   dg/dP = n,   dg/dB = -(z x w) / L - (g + r) d / L^2,   dg/dA = -n - dg/dB
//
// (translation invariance: the three sum to 0; a rotation of the line's body about A moves P's
// foot along the line, which changes g by the lever arm in dg/dB). The rate g' and J' q1 come
// from the same expression evaluated on Jets (mo2d/jet.hpp) with the points moving at their
// velocities: the points are linear in the node coordinates, so g(q0 + s q1) has
// d/ds = J q1 = g' and d^2/ds^2 = q1^T (d^2 g / dq^2) q1 = J' q1. The gradient is checked against
// finite differences in tests/contact/gap_test.cpp.
#include "mo2d/jet.hpp"
#include "mo2d/model.hpp"

namespace mo2d::detail {

template <class T>
T point_line_gap(T px, T py, T ax, T ay, T bx, T by, double r) {
  using std::hypot;
  const T dx = bx - ax, dy = by - ay;
  const T L = hypot(dx, dy);
  return (dx * (py - ay) - dy * (px - ax)) / L - r;
}

// The gradients (dg/dP, dg/dA, dg/dB) above; L > 0.
struct LineGradient {
  Vec2 dP, dA, dB;
};
inline LineGradient point_line_gradient(const Vec2& P, const Vec2& A, const Vec2& B, double r) {
  const Vec2 d = B - A, w = P - A;
  const double L = d.norm();
  const Vec2 n(-d.y() / L, d.x() / L);
  const double h = point_line_gap(P.x(), P.y(), A.x(), A.y(), B.x(), B.y(), r) + r;
  const Vec2 dB = Vec2(w.y(), -w.x()) / L - h * d / (L * L);
  return {n, -n - dB, dB};
}

}  // namespace mo2d::detail
