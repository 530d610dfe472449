// Forward dynamics: the reactions of a state (recorded, and those the joint friction reads) and
// the evaluation with joint friction (stages of ForwardData, mo2d/forward_data.hpp).
#include <algorithm>
#include <cmath>
#include <string>

#include "constraints/constraints.hpp"
#include "dynamics/friction.hpp"
#include "dynamics/reactions.hpp"
#include "forward/forward_run.hpp"
#include "forward/least_squares.hpp"
#include "forward/sparse_engine.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"
#include "mo2d/forward_data.hpp"
#include "run/format.hpp"

namespace mo2d {

using detail::fmt;

void ForwardData::compute_reactions(double t, const VectorXd& q0, const VectorXd& q1) {
  inputs(t, q0, q1);
  reactions_at(t, q0, q1);
}

// The reactions at the accelerations a with the efforts u and the friction values: least-squares
// multipliers of A^T lambda = B u + (friction) - (M a - f) (minimum-norm, to the digits of the
// state: least_squares.hpp), split at the eliminated joints.
void ForwardData::reactions_at(double t, const VectorXd& q0, const VectorXd& q1) {
  if (sparse_) {
    sparse_->fill_velocity_slots(q0, t, b, entries_);
  } else {
    A.setZero();
    entries_.clear();
    detail::SlotRecordSink sink{A, m, entries_};
    for (const auto& k : m.constraints) detail::velocity_rows(m, k, q0, t, b, sink);
  }
  body_inertia(m, a, la);
  body_applied(m, q0, q1, t, local);
  la -= local;  // M a - f, body-local
  w.setZero();
  if (!m.frictions.empty()) detail::add_friction_forces(m, friction, -1.0, true, la, w);
  scatter_local(m, la, w);
  if (m.m1 > 0) {
    ls_x = Bu;
    ls_x -= w;
    if (sparse_) {
      sparse_->least_squares(ls_x, 1e-14, lam_ls);
    } else {
      G_ls.noalias() = A * A.transpose();
      G_ls.diagonal().array() += 1e-14 * std::max(1.0, G_ls.diagonal().maxCoeff());
      llt_ls.compute(G_ls);
      detail::refined_least_squares(
          A, ls_x, [this](VectorXd& v) { llt_ls.solveInPlace(v); }, lam_ls, ls_r, ls_d);
    }
  }
  detail::joint_reactions(m, entries_, lam_ls, u, la, edge_force, edge_offset, reactions);
}

// Joint friction: its values depend on the reactions at the accelerations they give (Orsino
// Example 4.5). From zero friction: a, the reactions (as recorded: compute_reactions), the
// regularized friction values; again until no value changes by more than 1e-12 of itself.
void ForwardData::evaluate_friction(double t, const VectorXd& q0, const VectorXd& q1) {
  friction.setZero();
  for (int it = 1;; ++it) {
    rhs = f + Bu;
    detail::add_friction_forces(m, friction, 1.0, false, local, rhs);
    solve_formulation(t, q0);
    reactions_at(t, q0, q1);
    friction_forces(m, q0, q1, reactions, true, friction_next);
    int worst = 0;
    const double change = detail::friction_change(m, friction_next, friction, reactions, &worst);
    if (change <= 1e-12) return;
    if (it >= detail::kMaxFrictionIterations || !std::isfinite(change)) {
      const FrictionLoad& fr = m.frictions[worst];
      throw Error("forward dynamics of '" + m.name + "': the friction '" + fr.name +
                      "' in joint '" + fr.joint + "' and the reactions did not converge at t = " +
                      fmt(t) + " s (" + std::to_string(it) + " iterations; last change " +
                      fmt(change) + " of the friction " + fmt(friction_next[worst]) +
                      "): the friction is too large for the geometry there (a self-locking "
                      "mechanism); reduce mu",
                  fr.name, t);
    }
    friction.swap(friction_next);
  }
}

}  // namespace mo2d
