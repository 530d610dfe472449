// Linearization along a reference motion (mo2d/modes.hpp, docs/linearization.md): eq. 4.24 at
// every state of the reference, x = (z, w) in ONE set of independent coordinates. z = E0 q0 and
// w = E q1 are selections of labels; G(t) at two times is a derivative in the same variables only
// when E0 and E are the same at both, so they are chosen once (given, or among the pivot's choices
// at the states the one that stays best conditioned over all of them; the further
// quasi-velocities by pivoting at the first state) and checked at every state: the conditioning of
// the chart (the smallest singular value of the selected rows of orthonormal tangent bases) must
// stay above LinearizeOptions::min_conditioning, else an Error names the time and the coordinates.
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "mo2d/error.hpp"
#include "mo2d/kinematics.hpp"
#include "modes/modes_internal.hpp"

namespace mo2d {

namespace {

std::string joined(const std::vector<std::string>& labels, const std::vector<int>& idx, int from,
                   int to) {
  std::string s;
  for (int i = from; i < to; ++i) s += (s.empty() ? "" : ", ") + labels[idx[i]];
  return s;
}

std::string time_text(double t) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.9g s", t);
  return buf;
}

std::string short_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

// What the pivoting would choose at s (for the error message), or "" if nothing.
std::string pivot_choice(const Model& m, const State& s) {
  try {
    StateSpace ss;
    detail::choose_coordinates(m, s, {}, ss);
    const std::string coords = joined(m.coordinate_labels, ss.coordinate_vars, 0, ss.p);
    const std::string extra = joined(m.rate_labels, ss.velocity_vars, ss.p, ss.dof);
    return extra.empty() ? coords : coords + "; " + extra;
  } catch (const Error&) {
    return "";
  }
}

[[noreturn]] void lost_chart(const Model& m, const State& s, const LinearizeOptions& fixed,
                             const std::string& why) {
  std::string coords;
  for (const auto& l : fixed.coordinates) coords += (coords.empty() ? "" : ", ") + l;
  if (!fixed.velocities.empty()) coords += ";";
  for (const auto& l : fixed.velocities) coords += " " + l;
  const std::string better = pivot_choice(m, s);
  throw Error("linearization of '" + m.name + "' along the reference: at t = " + time_text(s.t) +
                  " the independent coordinates (" + coords + ") " + why +
                  "; they are kept fixed along the whole reference (G(t) in switching "
                  "coordinates cannot be integrated). Choose coordinates that stay good (there: " +
                  (better.empty() ? std::string("none found") : better) +
                  ") or split the reference",
              m.name, s.t);
}

}  // namespace

State chart_state(const Model& m, const StateSpace& ss, const VectorXd& dx) {
  if (dx.size() != ss.n())
    throw Error("chart_state: dx has " + std::to_string(dx.size()) + " entries, the state space " +
                    std::to_string(ss.n()),
                m.name, ss.t);
  State s{ss.t, chart_positions(m, ss, dx.head(ss.p)), VectorXd()};
  VectorXd b(m.m1);
  MatrixXd K = MatrixXd::Zero(m.m1 + ss.dof, m.n1);
  velocity_jacobian(m, s.q0, ss.t, K.topRows(m.m1), b);
  VectorXd rhs(m.m1 + ss.dof);
  rhs.head(m.m1) = b;
  for (int i = 0; i < ss.dof; ++i) {
    K(m.m1 + i, ss.velocity_vars[i]) = 1.0;
    rhs[m.m1 + i] = ss.q1[ss.velocity_vars[i]] + dx[ss.p + i];
  }
  Eigen::ColPivHouseholderQR<MatrixXd> qr(K);
  if (qr.rank() < m.n1)
    throw Error("chart_state: the quasi-velocities " +
                    joined(m.rate_labels, ss.velocity_vars, 0, ss.dof) +
                    " do not determine the velocities at the displaced configuration",
                m.name, ss.t);
  s.q1 = qr.solve(rhs);
  return s;
}

VectorXd independent_state(const StateSpace& ss, const State& s) {
  VectorXd x(ss.n());
  for (int i = 0; i < ss.p; ++i) x[i] = s.q0[ss.coordinate_vars[i]];
  for (int i = 0; i < ss.dof; ++i) x[ss.p + i] = s.q1[ss.velocity_vars[i]];
  return x;
}

namespace {

// The linearization at s in the coordinates of `fixed` (out.front()'s), checked: the chart is
// regular and conditioned there, the degrees of freedom are those of the first state.
StateSpace along_step(const Model& m, const State& s, const LinearizeOptions& fixed,
                      const StateSpace* first, detail::RunBudget& budget) {
  StateSpace ss;
  try {
    ss = detail::linearize_within(m, s, fixed, budget);
  } catch (const BudgetExhausted&) {
    throw;
  } catch (const Error& e) {
    if (first == nullptr) throw;
    lost_chart(m, s, fixed, std::string("do not parametrize the state (") + e.what() + ")");
  }
  if (first != nullptr && (ss.p != first->p || ss.dof != first->dof))
    lost_chart(m, s, fixed, "meet a change of the degrees of freedom (a singular configuration)");
  if (!(ss.conditioning >= fixed.min_conditioning)) {
    char c[96];
    std::snprintf(c, sizeof c, "are badly conditioned (conditioning %.3g < %.3g)", ss.conditioning,
                  fixed.min_conditioning);
    lost_chart(m, s, first ? fixed : detail::same_coordinates(m, ss, fixed), c);
  }
  return ss;
}

// The budgets of a linearization along `states` states (refused before any work when the
// estimate exceeds them; the wall-clock budget checked at every stage).
detail::RunBudget along_budget(const Model& m, const LinearizeOptions& o, std::size_t states,
                               double t) {
  const std::string what = "linearization of '" + m.name + "' along a reference";
  const int k = static_cast<int>(std::min<std::size_t>(states, 1'000'000'000));
  detail::check_modes_budget(what, m, o.forward.max_seconds, o.forward.max_memory, k, false);
  return detail::RunBudget(detail::modes_budget(what, m, t, o.forward.max_seconds));
}

}  // namespace

std::vector<StateSpace> linearize_along(const Model& m, const std::vector<State>& reference,
                                        const LinearizeOptions& o) {
  std::vector<StateSpace> out;
  detail::RunBudget budget =
      along_budget(m, o, reference.size(), reference.empty() ? 0.0 : reference.front().t);
  out.reserve(reference.size());
  LinearizeOptions fixed = o;
  if (fixed.coordinates.empty() && !reference.empty())
    for (int k : detail::coordinates_along(m, reference, &budget))
      fixed.coordinates.push_back(m.coordinate_labels[k]);
  for (const State& s : reference) {
    out.push_back(along_step(m, s, fixed, out.empty() ? nullptr : &out.front(), budget));
    if (out.size() == 1) fixed = detail::same_coordinates(m, out.front(), o);
  }
  return out;
}

namespace {

// The efforts and accelerations of linearization ss must be those the run recorded at sample i.
void check_against_run(const Model& m, const Trajectory& r, Eigen::Index i, const StateSpace& ss) {
  const VectorXd u = r.efforts.row(i).transpose();
  const double du = (ss.u - u).lpNorm<Eigen::Infinity>();
  if (u.size() == ss.u.size() && du > 1e-9 * (1 + u.lpNorm<Eigen::Infinity>()))
    throw Error("linearization along the run of '" + m.name + "': at t = " + time_text(ss.t) +
                    " the efforts of the options differ from the run's by " + short_number(du) +
                    ": pass the laws the run used (LinearizeOptions::forward.efforts)",
                m.name, ss.t);
  double da = 0, scale = 1;
  for (int k = 0; k < ss.dof; ++k) {
    const double a = r.a1(i, ss.velocity_vars[k]);
    da = std::max(da, std::abs(ss.drift[ss.p + k] - a));
    scale = std::max(scale, std::abs(a));
  }
  if (da > 1e-6 * scale)
    throw Error("linearization along the run of '" + m.name + "': at t = " + time_text(ss.t) +
                    " the accelerations differ from the run's by " + short_number(da) +
                    " (another model, loads or formulation than the run's?)",
                m.name, ss.t);
}

}  // namespace

std::vector<StateSpace> linearize_along(const Model& m, const Trajectory& r,
                                        const LinearizeOptions& o) {
  if (r.q0.cols() != m.n0 || r.q1.cols() != m.n1)
    throw Error("linearization along a run: the run is not of the model '" + m.name + "'", m.name);
  std::vector<State> states;
  for (Eigen::Index i = 0; i < r.time.size(); ++i)
    states.push_back({r.time[i], r.q0.row(i).transpose(), r.q1.row(i).transpose()});
  if (r.kind == RunKind::forward) {
    std::vector<StateSpace> out = linearize_along(m, states, o);
    for (Eigen::Index i = 0; i < r.time.size(); ++i) check_against_run(m, r, i, out[i]);
    return out;
  }
  // inverse run: its efforts held at each sample, the coordinates those of the first sample
  std::vector<StateSpace> out;
  detail::RunBudget budget = along_budget(m, o, states.size(), states.empty() ? 0.0 : states[0].t);
  LinearizeOptions held = o;
  if (held.coordinates.empty() && !states.empty())
    for (int k : detail::coordinates_along(m, states, &budget))
      held.coordinates.push_back(m.coordinate_labels[k]);
  for (Eigen::Index i = 0; i < r.time.size(); ++i) {
    held.forward.efforts.clear();
    for (Eigen::Index k = 0; k < r.efforts.cols(); ++k)
      held.forward.efforts.push_back(Law::constant(r.efforts(i, k)));
    out.push_back(along_step(m, states[i], held, out.empty() ? nullptr : &out.front(), budget));
    if (i == 0) held = detail::same_coordinates(m, out.front(), held);
  }
  return out;
}

}  // namespace mo2d
