#pragma once
// Contact law: compliant, Lankarani and Nikravesh (1990, "A contact force model with hysteresis
// damping for impact analysis of multibody systems", J. Mech. Des. 112:369), the Hertz force
// with the hysteresis damping of Hunt and Crossley (1975) tuned to a restitution e:
//
//   d = -g (penetration), d' = -g',  v0 = -g' at the onset (the approach speed),
//   F = K d^n (1 + 3 (1 - e^2) / (4 v0) d')    (>= 0: clipped at 0, the surfaces do not pull)
//
// The damping's energy loss over a cycle, integrated on the elastic (undamped) cycle, is
// (1 - e^2) m v0^2 / 2: the law gives the rebound speed e v0 only to first order in the damping,
// a good approximation for e near 1 (Lankarani and Nikravesh; Flores et al. 2011, Nonlinear Dyn.
// 65:87, fig. 6: the effective restitution exceeds e increasingly as e decreases).
// tests/contact/compliant_test.cpp measures it: within 0.01 of e down to e = 0.8 (docs/contact.md).
// Within a leg the force is the law's odd extension K |d|^n sgn(d) (1 + D d') past the exit
// (g > 0), smooth for the integrator, which never keeps a step there: the exit is an event.
// Power: F g' = -dV/dt - P_diss with V = K |d|^(n + 1) / (n + 1) (elastic) and
// P_diss = (F - K |d|^n sgn(d)) d' >= 0 (the damping, or the elastic force the clipping removes).
#include <cmath>

#include "mo2d/contact.hpp"

namespace mo2d::detail {

struct CompliantForce {
  double force = 0;        // F (N) along the gap's gradient
  double dissipation = 0;  // P_diss (W)
};

inline CompliantForce lankarani_nikravesh(const ContactLaw& l, double g, double rate, double v0) {
  const double d = -g, dd = -rate;
  const double elastic = l.stiffness * std::copysign(std::pow(std::abs(d), l.exponent), d);
  const double D =
      3 * (1 - l.restitution * l.restitution) / (4 * std::max(v0, l.min_approach_speed));
  double F = elastic * (1 + D * dd);
  if (d > 0 && F < 0) F = 0;  // the surfaces push only
  return {F, (F - elastic) * dd};
}

}  // namespace mo2d::detail
