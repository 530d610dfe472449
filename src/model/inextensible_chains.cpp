// Stage 8b of build_model, inextensible chains (ChainFidelity::inextensible; docs/reduction.md,
// "The inextensible chain"), and the models of one span mode that forward_dynamics switches
// between (src/forward/chain_switching.cpp). The limit k -> infinity of a taut span whose tension
// T stays finite holds its material length (dynamics/chain.hpp, with the wrap term) at the rest
// length:
//
//   psi_s(q0) = l_s(c_a, c_b, theta_a, theta_b) - rest_s = 0,     s = upper or lower
//
// a user position constraint (constraints/user.hpp) on the coordinates of the centres' nodes and
// of the unwrapped angles theta_a, theta_b, whose Jets give the velocity row A = d l_s / d q0 and
// the acceleration bias exactly. The span's force on the mechanism is -T dl_s/dq0, the
// constraint's -A^T lambda: T = lambda, reported as the reaction "name.upper.tension" or
// "name.lower.tension" (factor +1; the other span's reaction has factor 0, it is slack). One row
// per chain in the built model (the upper span); chain_mode_model replaces it by the lower span's
// or removes it (slack). The assembly onto the spans' rows (chain_start): only of the spans at
// their length; a chain whose spans are both shorter than their rest lengths starts slack
// (assembled on the upper span's row, the half-bike's swing arm moved by -2.04e-3 rad to take up
// its 0.5 mm of slack, and rang for 1 s).
#include <algorithm>
#include <cmath>
#include <limits>

#include "dynamics/chain.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"
#include "mo2d/kinematics.hpp"
#include "mo2d/quasi_steady.hpp"
#include "model/build_stages.hpp"
#include "model/point_jets.hpp"

namespace mo2d::build {
namespace {

// The user position row of span `span` (0 upper, 1 lower) of chain c (initialized).
Constraint::UserPosition span_row(const Model& m, const ChainLoad& c, int span) {
  Constraint::UserPosition u;
  const PointArgs a = point_args(m, c.a, u.args), b = point_args(m, c.b, u.args);
  auto theta_arg = [&](int var) {
    if (var < 0) return -1;
    const int at = static_cast<int>(u.args.size());
    VarRef r = m.rate_refs[var];
    r.var = var;
    u.args.push_back(r);
    return at;
  };
  const int ta = theta_arg(c.theta_a), tb = theta_arg(c.theta_b);
  const double rest = span == 0 ? c.rest_upper : c.rest_lower;
  const std::shared_ptr<double> held = c.held[span];  // quasi_steady: the held length L(t)
  u.psi = [c, a, b, ta, tb, span, rest, held](std::span<const Jet> x, Jet t) {
    const JetPoint pa = point_jet(a, x), pb = point_jet(b, x);
    const Jet zero(0.0);
    const detail::ChainInput<Jet> in{pa.x,
                                     pa.y,
                                     pb.x,
                                     pb.y,
                                     zero,
                                     zero,
                                     zero,
                                     zero,
                                     ta < 0 ? zero : x[ta],
                                     tb < 0 ? zero : x[tb],
                                     zero,
                                     zero};
    const detail::Spans<Jet> sp = detail::chain_spans(c, in, t.v);
    const Jet l = span == 0 ? sp.upper.length : sp.lower.length;
    if (!held) return l - Jet(rest);  // l_s - rest_s
    const HeldLength& h = *reinterpret_cast<const HeldLength*>(held.get());
    return l - (Jet(h.length) + Jet(h.rate) * (t - Jet(h.t0)));  // l_s - L_s(t)
  };
  return u;
}

void set_factors(Model& m, const ChainLoad& c) {
  for (Reaction& r : m.reactions) {
    if (r.label == c.name + ".upper.tension") r.factor = c.active_span == 0 ? 1 : 0;
    if (r.label == c.name + ".lower.tension") r.factor = c.active_span == 1 ? 1 : 0;
  }
}

// Index maps after erasing reactions: old index -> new (-1: erased).
void renumber_reactions(Model& m, const std::vector<int>& map) {
  for (ReducedSpring& s : m.reduced_springs) s.reaction = map[s.reaction];
  for (ReducedTorsional& s : m.reduced_torsional) s.reaction = map[s.reaction];
  for (FrictionLoad& f : m.frictions)
    if (f.reaction >= 0) f.reaction = map[f.reaction];
  for (MergeEdge& e : m.merge_edges)
    if (e.reaction >= 0) e.reaction = map[e.reaction];
}

// Removes chain c's row (the chain slack): its constraint, rows, labels and reactions.
void remove_row(Model& m, ChainLoad& c) {
  const int ci = c.constraint;
  const Constraint k = m.constraints[ci];
  m.position_row_labels.erase(m.position_row_labels.begin() + k.row0,
                              m.position_row_labels.begin() + k.row0 + k.nrow0);
  m.velocity_row_labels.erase(m.velocity_row_labels.begin() + k.row1,
                              m.velocity_row_labels.begin() + k.row1 + k.nrow1);
  m.m0 -= k.nrow0;
  m.m1 -= k.nrow1;
  m.dof += k.nrow1;
  m.constraints.erase(m.constraints.begin() + ci);
  for (Constraint& o : m.constraints) {
    if (o.row0 > k.row0) o.row0 -= k.nrow0;
    if (o.row1 > k.row1) o.row1 -= k.nrow1;
  }
  for (ChainLoad& o : m.chains)
    if (o.constraint > ci) --o.constraint;
  for (ReducedSpring& s : m.reduced_springs)
    if (s.constraint > ci) --s.constraint;
  for (ReducedTorsional& s : m.reduced_torsional)
    if (s.constraint > ci) --s.constraint;
  for (FrictionLoad& f : m.frictions)
    if (f.slider > ci) --f.slider;
  std::vector<int> map(m.reactions.size(), -1);
  std::vector<Reaction> kept;
  for (size_t j = 0; j < m.reactions.size(); ++j) {
    Reaction r = m.reactions[j];
    if (r.row >= k.row1 && r.row < k.row1 + k.nrow1) continue;
    if (r.row >= k.row1 + k.nrow1) r.row -= k.nrow1;
    map[j] = static_cast<int>(kept.size());
    kept.push_back(r);
  }
  m.reactions = std::move(kept);
  renumber_reactions(m, map);
  for (TreeNode& n : m.tree) {
    std::vector<int> rows;
    for (int r : n.rows)
      if (r < k.row1 || r >= k.row1 + k.nrow1) rows.push_back(r >= k.row1 ? r - k.nrow1 : r);
    n.rows = std::move(rows);
  }
  c.constraint = -1;
}

}  // namespace

bool add_inextensible_chains(Model& m) {
  bool any = false;
  for (ChainLoad& c : m.chains) {
    if (c.fidelity != ChainFidelity::inextensible) continue;
    if (c.held[0]) *c.held[0] = c.rest_upper, *c.held[1] = c.rest_lower;  // quasi_steady: at rest
    c.active_span = 0;
    c.constraint =
        add_constraint(m, Constraint{.name = c.name, .owner = 0, .def = span_row(m, c, 0)}, 1, 1,
                       {".span"}, {".span_rate"});
    const int row = m.constraints[c.constraint].row1;
    m.reactions.push_back({c.name + ".upper.tension", row, 1});  // T = lambda
    m.reactions.push_back({c.name + ".lower.tension", row, 0});
    any = true;
  }
  return any;
}

}  // namespace mo2d::build

namespace mo2d::detail {

Model chain_mode_model(const Model& m, const std::vector<int>& spans) {
  Model out = m;
  size_t k = 0;
  for (ChainLoad& c : out.chains) {
    if (c.fidelity != ChainFidelity::inextensible) continue;
    if (k >= spans.size()) throw Error("chain_mode_model: too few span modes", c.name);
    const int s = spans[k++];
    c.mode_fixed = true;
    if (s == c.active_span) continue;
    if (s < 0) {
      build::remove_row(out, c);
      c.active_span = -1;
      continue;
    }
    if (c.constraint < 0)
      throw Error("chain_mode_model: a slack model cannot take a span back", c.name);
    c.active_span = s;
    std::get<Constraint::UserPosition>(out.constraints[c.constraint].def) =
        build::span_row(out, c, s);
    build::set_factors(out, c);
  }
  return out;
}

// The tolerance of an engagement's assembly, relative to m.scale: 1e-13, or above the round-off of
// the span lengths, which carry r theta of the unwrapped sprocket angles (the QSS half-bike's
// scenario 2 turns the shaft by ~1e4 rad: Newton stalled at a residual of 2.5e-13 m).
double span_assembly_tolerance(const Model& m, const VectorXd& q0) {
  double wrapped = 0;  // m
  for (const ChainLoad& c : m.chains)
    for (const auto& [var, r] :
         {std::pair{c.theta_a, c.radius_a}, std::pair{c.theta_b, c.radius_b}})
      if (var >= 0) wrapped += r * std::abs(q0[var]);
  return std::max(1e-13, 16 * std::numeric_limits<double>::epsilon() * wrapped / m.scale);
}

ChainStart chain_start(const Model& m, const VectorXd& q0, double t, const std::vector<int>& fixed,
                       double tol) {
  constexpr double kAtLength = 1e-9;  // a span within 1e-9 of its rest length is at it
  std::vector<int> spans;
  for (const ChainLoad& c : m.chains)
    if (c.fidelity == ChainFidelity::inextensible) spans.push_back(-1);
  // the rest of the mechanism first (every chain slack), then the spans at their length
  VectorXd q = assemble(chain_mode_model(m, spans), q0, t, fixed, tol);
  const VectorXd still = VectorXd::Zero(m.n1);
  bool taut = false;
  size_t k = 0;
  for (const ChainLoad& c : m.chains) {
    if (c.fidelity != ChainFidelity::inextensible) continue;
    const ChainValue v = chain_value(m, c, q, still, t);
    const double gap[2] = {(c.rest_upper - v.upper_length) / c.rest_upper,
                           (c.rest_lower - v.lower_length) / c.rest_lower};
    const int s = gap[1] < gap[0] ? 1 : 0;  // the span nearer its length (or beyond it)
    if (gap[s] <= kAtLength) spans[k] = s, taut = true;
    ++k;
  }
  if (taut) q = assemble(chain_mode_model(m, spans), q, t, fixed, tol);
  return {q, spans};
}

}  // namespace mo2d::detail
