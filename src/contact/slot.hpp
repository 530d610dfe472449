#pragma once
// Contact kind: a circle of radius r around P (a pin) in a straight slot of width w > 2 r (internal
// to src/contact/). The slot's centre line runs from A (its closed end) to B (its open mouth), A
// and B on one body or the ground. With d = B - A, L = |d|, the axis t = d / L, the lateral
// normal n = z x t (the left of A -> B), w_P = P - A, the pin's axial and lateral coordinates
//   s = t . w_P,   l = n . w_P,
// and h = w/2 - r (the pin centre's room on either side of the centre line), the slot is three
// contacts (parts), each with its own gap and mode:
//
//   inside the slot (0 <= s <= L, |l| <= w/2):
//     left wall   g = h - l               dg/dP = -n,  dg/dB = s n / L,  dg/dA = n - s n / L
//     right wall  g = h + l               (the left's gradients negated)
//     end         g = s - r               dg/dP = t,   dg/dB = l n / L,  dg/dA = -t - l n / L
//   (the closed end a flat wall through A across the slot, not a semicircle);
//   outside it, each wall's gap is its lip: the wall's end corner C_k = B + k (w/2) n (k = +1
//   left, -1 right), touched by the pin from anywhere as a point contact, and the end has no gap:
//     lip         g = |P - C_k| - r,      u = (P - C_k) / |P - C_k|,
//                 dg/dP = u,  dg/dB = -u + k (w/2) (t . u) n / L,  dg/dA = -k (w/2) (t . u) n / L
//     end         g = w (a constant: never closes, no force)
//
// (from ds/dP = t, ds/dB = l n / L, dl/dP = n, dl/dB = -s n / L, dn/dd = -t n^T / L; the
// gradients with respect to P, A and B sum to 0). Where the pin crosses the mouth (s = L with
// |l| <= h) the wall's gap and its lip's agree to first order: the lip's gap is the distance to
// the corner, (s - L)^2 / 2 off the wall's, so a wall contact holding the pin as it leaves goes on
// as its lip contact (the pin rolling over the corner) until its multiplier says lift-off.
//
// Whether the pin is inside is a state of the slot (SlotRegions, slot.cpp), switched by located
// events: inside, the condition min(L - s, w/2 - |l|, s) > 0; outside, max(s - L, |l| - w/2, -s) >
// 0. Crossing the mouth (s = L, |l| <= w/2) switches it (an `enter` or `leave` event); crossing
// any other side of the rectangle is refused, naming the time: the slot's outside (the wheel's
// rim, the walls' backs, the material behind the closed end) is not modelled, so a pin that
// would reach the slot other than through its mouth is an error, never a silent pass. A pin that
// meets the mouth off the band |l| <= h hits a lip first (its gap reaches 0 before s = L): an
// impact or a persistent contact on the corner, like any other. A pin outside that passes the
// mouth's line beyond the lips (|l| > w/2 + r) touches nothing of the slot.
//
// g' and J' q1 come from the same expressions on Jets (as in point_line.hpp).
#include "contact/point_line.hpp"
#include "mo2d/jet.hpp"
#include "mo2d/model.hpp"

namespace mo2d::detail {

// The slot's parts (the order of the three contacts a slot compiles into).
enum SlotPart { kSlotLeft = 0, kSlotRight = 1, kSlotEnd = 2 };

// The gap of part `part` of the slot (see the file's description).
template <class T>
T slot_gap(T px, T py, T ax, T ay, T bx, T by, double r, double w, int part, bool inside) {
  using std::hypot;
  if (part == kSlotEnd && !inside) return T(w);
  const T dx = bx - ax, dy = by - ay;
  const T L = hypot(dx, dy);
  const T tx = dx / L, ty = dy / L;  // n = (-ty, tx)
  if (!inside) {
    const double k = part == kSlotLeft ? 1.0 : -1.0;
    const T cx = bx - k * (w / 2) * ty, cy = by + k * (w / 2) * tx;
    return hypot(px - cx, py - cy) - r;
  }
  const T wx = px - ax, wy = py - ay;
  if (part == kSlotEnd) return tx * wx + ty * wy - r;
  const T l = tx * wy - ty * wx;
  const double h = w / 2 - r;
  return part == kSlotLeft ? h - l : h + l;
}

// The pin's coordinates in the slot: s along the axis from A, l across it (left +), L = |B - A|.
struct SlotCoordinates {
  double s = 0, l = 0, L = 0;
};
inline SlotCoordinates slot_coordinates(const Vec2& P, const Vec2& A, const Vec2& B) {
  const Vec2 d = B - A, w = P - A;
  const double L = d.norm();
  const Vec2 t = d / L;
  return {t.dot(w), t.x() * w.y() - t.y() * w.x(), L};
}

// The gradients (dg/dP, dg/dA, dg/dB) of part `part` (see the file's description); L > 0 and,
// outside, P off the lip's corner (else the lip's gradient is 0: the pin's centre on the corner).
inline LineGradient slot_gradient(const Vec2& P, const Vec2& A, const Vec2& B, double w, int part,
                                  bool inside) {
  const Vec2 d = B - A;
  const double L = d.norm();
  const Vec2 t = d / L, n(-t.y(), t.x());
  if (part == kSlotEnd && !inside) return {Vec2::Zero(), Vec2::Zero(), Vec2::Zero()};
  if (!inside) {
    const double k = part == kSlotLeft ? 1.0 : -1.0;
    const Vec2 q = P - (B + k * (w / 2) * n);
    const double D = q.norm();
    if (!(D > 0)) return {Vec2::Zero(), Vec2::Zero(), Vec2::Zero()};
    const Vec2 u = q / D;
    const Vec2 m = k * (w / 2) * t.dot(u) * n / L;
    return {u, -m, m - u};
  }
  const SlotCoordinates c = slot_coordinates(P, A, B);
  if (part == kSlotEnd) {
    const Vec2 dB = c.l * n / L;
    return {t, -t - dB, dB};
  }
  const double k = part == kSlotLeft ? 1.0 : -1.0;
  const Vec2 dB = k * c.s * n / L;
  return {-k * n, k * n - dB, dB};
}

}  // namespace mo2d::detail
