#pragma once
// Contact kind: a circle of radius r around P against a circle of radius R around C (internal to
// src/contact/), touched from outside or from inside (a hole: a pin in a hole with the clearance
// R - r). With D = |P - C| and u = (P - C) / D:
//
//   outside:  g = D - R - r,   dg/dP = u,  dg/dC = -u
//   hole:     g = R - r - D,   dg/dP = -u, dg/dC = u
//
// The rate g' and J' q1 come from the expression on Jets (as in point_line.hpp). At D = 0 the
// gradient is undefined: outside that is a penetration by R + r (refused); in a hole the pin is
// centred, g = R - r > 0, and the gap's one-sided rate is used (no force acts there).
#include "mo2d/jet.hpp"
#include "mo2d/model.hpp"

namespace mo2d::detail {

// sign +1: outside, -1: hole
template <class T>
T circle_circle_gap(T px, T py, T cx, T cy, double R, double r, double sign) {
  using std::hypot;
  const T dx = px - cx, dy = py - cy;
  const T D = hypot(dx, dy);  // one-sided rates at D = 0 (mo2d/jet.hpp)
  return sign * (D - R) - r;
}

}  // namespace mo2d::detail
