// Stage 6 of build_model, a spring reduced to a constraint (SpringDef::reduce; docs/reduction.md,
// "A stiff spring as a constraint"). The limit k -> infinity of a spring whose tension T stays
// finite holds its length at the rest length (extension T / k -> 0):
//
//   psi(q0) = |p_b(q0) - p_a(q0)| - l_0 = 0,   p = (1 - gamma) p_i + gamma p_j + rho z x (p_j -
//   p_i)
//
// (Example 2.6 (b), the points by local nodes). It is written as a user position constraint
// (constraints/user.hpp) on the coordinates of the two points' nodes, whose Jets give the velocity
// row A = d psi / d q0 = e^T (dp_b/dq0 - dp_a/dq0) (e the unit vector a -> b) and the acceleration
// bias exactly. The constraint force is -A^T lambda = -lambda e^T (...), and the spring's force
// on the mechanism is -T d l / d q0: so T = lambda, reported as the reaction "name.tension"
// (factor +1), the label the spring's tension had.
//
// reduce: quasi_steady (docs/reduction.md, "The quasi-steady-state model") is the same row with
// the length l_0 replaced by a held length L(t) = L_n + Ldot_n (t - t_n) that forward runs move to
// the spring's equilibrium length under T (src/forward/quasi_steady.cpp): psi = |p_b - p_a| -
// L(t), L read from a cell shared with m.reduced_springs (A does not depend on L; the row's
// right-hand side is Ldot_n).
#include <array>
#include <cmath>
#include <memory>

#include "constraints/common.hpp"
#include "mo2d/error.hpp"
#include "mo2d/quasi_steady.hpp"
#include "model/build_stages.hpp"
#include "model/point_jets.hpp"

namespace mo2d::build {

void add_reduced_spring(const SpringLoad& s, int owner, Model& m, bool quasi_steady) {
  const std::string what =
      "spring '" + s.name + "' (reduce: " + (quasi_steady ? "quasi_steady)" : "constraint)");
  if (!(s.rest_length > 0))
    throw Error(what +
                    ": needs rest_length > 0 (the length the constraint holds; a zero length "
                    "has no direction)",
                s.name);
  Constraint::UserPosition c;
  const PointArgs a = point_args(m, s.a, c.args), b = point_args(m, s.b, c.args);
  if (c.args.empty()) throw Error(what + " joins two fixed points", s.name);
  ReducedSpring r;
  if (quasi_steady) {
    const auto held = std::make_shared<HeldLength>();
    held->length = s.rest_length;
    r.held_length = std::shared_ptr<double>(held, &held->length);  // aliasing: shares the cell
    c.psi = [a, b, held](std::span<const Jet> x, Jet t) {
      const JetPoint pa = point_jet(a, x), pb = point_jet(b, x);
      const Jet L = Jet(held->length) + Jet(held->rate) * (t - Jet(held->t0));
      return hypot(pb.x - pa.x, pb.y - pa.y) - L;  // |p_b - p_a| - L(t)
    };
  } else {
    const double length = s.rest_length;
    c.psi = [a, b, length](std::span<const Jet> x, Jet) {
      const JetPoint pa = point_jet(a, x), pb = point_jet(b, x);
      return hypot(pb.x - pa.x, pb.y - pa.y) - Jet(length);  // |p_b - p_a| - l_0
    };
  }
  r.spring = s;
  r.constraint = add_constraint(m, Constraint{.name = s.name, .owner = owner, .def = std::move(c)},
                                1, 1, {".length"}, {".rate"});
  r.reaction = m.n_reactions();
  m.reactions.push_back({s.name + ".tension", m.constraints[r.constraint].row1, 1});  // T = lambda
  m.reduced_springs.push_back(std::move(r));
}

}  // namespace mo2d::build
