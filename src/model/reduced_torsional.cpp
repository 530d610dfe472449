// Stage 6 of build_model, a torsional spring reduced to a constraint (TorsionalSpringDef::reduce;
// docs/reduction.md, "A stiff spring as a constraint" and "The quasi-steady-state model"). The
// limit k -> infinity of a torsional spring whose torque stays finite holds the relative angle of
// its joint's bodies at rest (the twist tau / k -> 0):
//
//   psi(q0) = wrap(theta_2(q0) - theta_1(q0) - rest - a(t)) = 0,   theta = atan2(d_y, d_x),
//   d = p_1 - p_0 (the body's first two nodes; the ground's angle 0)
//
// with a = 0 (reduce: constraint) or, reduce: quasi_steady, the angle from rest a(t) = a_n +
// adot_n (t - t_n) of a HeldLength cell that forward runs settle where the spring's own law at
// zero rate gives the row's torque (src/forward/quasi_steady.cpp: a = -tau / k when linear). A
// user position constraint (constraints/user.hpp) on the four node coordinates of each body, whose
// Jets give A = d theta_rel / d q0 and the acceleration bias exactly. The spring's torque tau on
// body 2 (and -tau on body 1) is the generalized force tau A^T; the constraint's -A^T lambda: so
// tau = -lambda, the reaction "name.torque" (factor -1), the label the spring's torque had.
#include <cmath>
#include <memory>

#include "constraints/common.hpp"
#include "mo2d/error.hpp"
#include "mo2d/quasi_steady.hpp"
#include "model/build_stages.hpp"
#include "model/point_jets.hpp"

namespace mo2d::build {
namespace {

// The first two nodes of body `b` as arguments (b < 0: the ground, none).
struct AngleArgs {
  NodeArg p0, p1;
  bool ground = true;
};

AngleArgs angle_args(const Model& m, int b, std::vector<VarRef>& args, const std::string& what) {
  AngleArgs a;
  if (b < 0) return a;
  const Body& body = m.bodies[b];
  if (body.nodes.size() < 2)
    throw Error(what + ": body '" + body.name + "' has one node and no orientation", body.name);
  a.ground = false;
  a.p0 = node_arg(body.nodes[0], args);
  a.p1 = node_arg(body.nodes[1], args);
  return a;
}

Jet angle_jet(const AngleArgs& a, std::span<const Jet> x) {
  if (a.ground) return Jet(0.0);
  const JetPoint p0 = node_jet(a.p0, x), p1 = node_jet(a.p1, x);
  return atan2(p1.y - p0.y, p1.x - p0.x);
}

}  // namespace

void add_reduced_torsional(const TorsionalLoad& s, int owner, Model& m, bool quasi_steady) {
  const std::string what = "torsional spring '" + s.name +
                           "' (reduce: " + (quasi_steady ? "quasi_steady)" : "constraint)");
  Constraint::UserPosition c;
  const AngleArgs b1 = angle_args(m, s.body1, c.args, what),
                  b2 = angle_args(m, s.body2, c.args, what);
  if (c.args.empty()) throw Error(what + " joins two fixed bodies", s.name);
  ReducedTorsional r;
  std::shared_ptr<HeldLength> held;
  if (quasi_steady) {
    held = std::make_shared<HeldLength>();  // its length: the angle from rest, 0 at rest
    r.held_angle = std::shared_ptr<double>(held, &held->length);  // aliasing: shares the cell
  }
  const double rest = s.rest;
  c.psi = [b1, b2, rest, held](std::span<const Jet> x, Jet t) {
    Jet a = angle_jet(b2, x) - angle_jet(b1, x) - Jet(rest);
    if (held) a = a - (Jet(held->length) + Jet(held->rate) * (t - Jet(held->t0)));
    a.v = detail::wrap_angle(a.v);  // wrap(theta_2 - theta_1 - rest - a(t))
    return a;
  };
  r.spring = s;
  r.constraint = add_constraint(m, Constraint{.name = s.name, .owner = owner, .def = std::move(c)},
                                1, 1, {".angle"}, {".rate"});
  r.reaction = m.n_reactions();
  m.reactions.push_back(
      {s.name + ".torque", m.constraints[r.constraint].row1, -1});  // tau = -lambda
  m.reduced_torsional.push_back(std::move(r));
}

}  // namespace mo2d::build
