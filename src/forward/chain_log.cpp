// The warnings of the span switching, handovers summarized, and the legs' statistics summed
// (src/forward/chain_log.hpp).
#include "forward/chain_log.hpp"

#include <algorithm>
#include <cstdio>

namespace mo2d::detail {

std::string chain_log_number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.10g", v);
  return b;
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

}  // namespace mo2d::detail
