// The warnings of the span switching, handovers summarized, and the legs' statistics summed
// (src/forward/chain_log.hpp).
#include "forward/chain_log.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "output/trajectory_labels.hpp"
#include "run/time_grid.hpp"

namespace mo2d::detail {

std::string chain_log_number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.10g", v);
  return b;
}

// The fidelity a chain was given (a quasi-steady chain is compiled as inextensible, with cells).
const char* chain_fidelity_name(const ChainLoad& c) {
  return c.held[0] ? "quasi_steady" : "inextensible";
}

// A span settled short of its rest length (under the T < 0 of a jump of the loads) and then put
// back at it: its bodies moved by |stretch| and back within the instant (docs/reduction.md,
// "Speed against error": the half-bike's swing arm kicked at the brake step).
std::string short_span_note(double stretch) {
  return "; it had been settled " + chain_log_number(-stretch) +
         " m short of its rest length past the jump and its bodies moved back by as much: the "
         "quasi-steady chain is not accurate across this jump (fidelity unilateral or "
         "inextensible is)";
}

void add_leg_stats(RunStats& a, const RunStats& b) {
  a.cpu_seconds += b.cpu_seconds;
  a.steps += b.steps;
  a.rhs_evaluations += b.rhs_evaluations;
  a.factorizations += b.factorizations;
  a.projections += b.projections;
  a.error_test_failures += b.error_test_failures;
  a.solver_iterations += b.solver_iterations;
  a.regularized_evaluations += b.regularized_evaluations;
  a.stepped_over += b.stepped_over;
  a.min_pivot_ratio = std::min(a.min_pivot_ratio, b.min_pivot_ratio);
  a.max_drift = std::max(a.max_drift, b.max_drift);
  a.sparse = a.sparse || b.sparse;
  a.t_end = b.t_end;
  for (const std::string& w : b.warnings) a.warnings.push_back(w);
}

bool ChainLog::listed(size_t k) {
  Counts& c = chains_.at(k);
  if (c.lines < kListed) return ++c.lines, true;
  ++c.unlisted;
  return false;
}

void ChainLog::handover(size_t k, int from, double t) {
  Counts& c = chains_.at(k);
  if (c.handovers[0] + c.handovers[1] == 0) c.first = t;
  c.last = t;
  ++c.handovers[from];
}

std::vector<std::string> ChainLog::summary(const std::vector<std::string>& names) const {
  std::vector<std::string> out;
  for (size_t k = 0; k < chains_.size(); ++k) {
    const Counts& c = chains_[k];
    const std::string who = "chain '" + names.at(k) + "': ";
    const int n = c.handovers[0] + c.handovers[1];
    if (n > 0)
      out.push_back(
          who + std::to_string(n) + " direct handover" + (n > 1 ? "s" : "") +
          " between the taut spans (" + std::to_string(c.handovers[0]) + " upper to lower, " +
          std::to_string(c.handovers[1]) +
          " lower to upper; no slack, no impulse), the first at t = " + chain_log_number(c.first) +
          " s, the last at t = " + chain_log_number(c.last) + " s");
    if (c.unlisted > 0)
      out.push_back(who + std::to_string(c.unlisted) + " more switch lines not listed (the first " +
                    std::to_string(kListed) + " are)");
  }
  return out;
}

Trajectory switching_trajectory(const Model& m, int samples) {
  const Eigen::Index N = samples;
  Trajectory out = labelled_trajectory(m, RunKind::forward);
  out.time = Eigen::VectorXd::Zero(N);
  out.q0 = Eigen::MatrixXd::Zero(N, m.n0);
  out.q1 = out.a1 = Eigen::MatrixXd::Zero(N, m.n1);
  out.efforts = Eigen::MatrixXd::Zero(N, m.n_inputs());
  out.reactions = Eigen::MatrixXd::Zero(N, m.n_reactions());
  out.residuals = Eigen::MatrixXd::Zero(N, 2);
  out.kinetic = out.potential = out.input_work = out.load_work = out.constraint_work =
      out.dissipated = Eigen::VectorXd::Zero(N);
  return out;
}

void append_leg(Trajectory& out, int& filled, const Trajectory& r, const ForwardOptions& o,
                double (&off)[kEnergyTerms]) {
  const double h = (o.t1 - o.t0) / (o.samples - 1);
  std::vector<int> col(out.reaction_labels.size(), -1);
  for (size_t j = 0; j < col.size(); ++j)
    for (size_t i = 0; i < r.reaction_labels.size(); ++i)
      if (r.reaction_labels[i] == out.reaction_labels[j]) col[j] = static_cast<int>(i);
  for (Eigen::Index i = 0; i < r.time.size() && filled < o.samples; ++i) {
    const double t_k = sample_time(o.t0, o.t1, o.samples, filled);
    if (!(std::abs(r.time[i] - t_k) <= 1e-9 * h)) continue;
    const int k = filled++;
    out.time[k] = t_k;
    out.q0.row(k) = r.q0.row(i);
    out.q1.row(k) = r.q1.row(i);
    out.a1.row(k) = r.a1.row(i);
    out.efforts.row(k) = r.efforts.row(i);
    for (size_t j = 0; j < col.size(); ++j)
      out.reactions(k, static_cast<Eigen::Index>(j)) = col[j] < 0 ? 0.0 : r.reactions(i, col[j]);
    out.residuals.row(k) = r.residuals.row(i);
    out.kinetic[k] = r.kinetic[i];
    out.potential[k] = r.potential[i];
    out.input_work[k] = off[kInputWork] + r.input_work[i];
    out.load_work[k] = off[kLoadWork] + r.load_work[i];
    out.constraint_work[k] = off[kConstraintWork] + r.constraint_work[i];
    out.dissipated[k] = off[kDissipated] + r.dissipated[i];
  }
  const Eigen::Index e = r.time.size() - 1;
  off[kInputWork] += r.input_work[e];
  off[kLoadWork] += r.load_work[e];
  off[kConstraintWork] += r.constraint_work[e];
  off[kDissipated] += r.dissipated[e];
  add_leg_stats(out.stats, r.stats);
}

}  // namespace mo2d::detail
