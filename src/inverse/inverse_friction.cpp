// Inverse dynamics with joint friction (Orsino Example 4.5): the reactions depend on the friction
// forces and these on the reactions (N, src/dynamics/friction.hpp). Per sample, from zero
// friction: efforts, multipliers, reactions -> friction values -> again, until no friction
// changes by more than InverseOptions::friction_tolerance of itself. The motion is prescribed, so
// every joint rate v is known: sgn(v) = sign(v), 0 at v = 0 exactly (where the Coulomb force is
// undetermined: a slider at rest at a dead centre; the effort jumps there by 2 mu N times the
// lever). At a sample on a reversal the computed rate is rounding (1e-17) and its sign picks one
// of the two one-sided limits, both consistent with static friction (|F| <= mu N). The map is a
// contraction when mu times the sensitivity of N to the friction is < 1; a self-locking mechanism
// (no consistent solution) is reported, not returned.
#include <cmath>

#include "dynamics/friction.hpp"
#include "inverse/inverse_stages.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"
#include "run/format.hpp"

namespace mo2d {

void inverse_friction(const Model& m, InverseData& d, double t) {
  d.local_base = d.local_a;
  d.friction.setZero();
  const InverseOptions& o = d.options;
  for (int it = 1;; ++it) {
    d.local_a = d.local_base;
    inverse_efforts_and_reactions(m, d);
    friction_forces(m, d.q0, d.q1, d.reactions, false, d.friction_next);
    int worst = 0;
    const double change =
        detail::friction_change(m, d.friction_next, d.friction, d.reactions, &worst);
    d.friction_iterations = it;
    if (change <= o.friction_tolerance) return;
    if (it >= o.max_friction_iterations || !std::isfinite(change)) {
      const FrictionLoad& f = m.frictions[worst];
      throw Error("inverse dynamics of '" + m.name + "': the friction '" + f.name + "' in joint '" +
                      f.joint + "' and the reactions did not converge at t = " + detail::fmt(t) +
                      " s (" + std::to_string(it) + " iterations; last change " +
                      detail::fmt(change) + " of the friction " +
                      detail::fmt(d.friction_next[worst]) +
                      "): the friction is too large for the geometry there (a self-locking "
                      "mechanism has no consistent solution); reduce mu",
                  f.name, t);
    }
    d.friction.swap(d.friction_next);
  }
}

}  // namespace mo2d
