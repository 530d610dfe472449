#pragma once
// The warnings of the span switching (src/forward/chain_switching.cpp; docs/reduction.md, "The
// inextensible chain"). A handover from one taut span directly to the other (the other span at
// its length pulls at once: no slack, no impulse) is the normal operation of a chain on fixed
// centres, whose load reverses: they are counted, one line per chain at the end of the run
// (count, first and last time). Everything else (slack intervals, engagements with an impulse, a
// span that does not hold) is a line of its own, the first kListed of each chain; the rest are
// counted in a closing line. The legs' samples and statistics gathered into the run's.
#include <cstddef>
#include <string>
#include <vector>

#include "forward/forward_run.hpp"
#include "mo2d/trajectory.hpp"

namespace mo2d::detail {

// Times, impulses and energies of the switch lines: 10 significant digits (a switch time is
// compared with closed forms to 1e-7 s).
std::string chain_log_number(double v);

// The fidelity a chain was given: "quasi_steady" (compiled as inextensible, with held cells) or
// "inextensible".
const char* chain_fidelity_name(const ChainLoad& c);

// The end of the release line of a quasi-steady span settled `stretch` (< 0) short of its rest
// length past a jump of the loads and put back at it.
std::string short_span_note(double stretch);

// A leg's statistics and warnings added to the run's (its t_end the leg's).
void add_leg_stats(RunStats& run, const RunStats& leg);

// The switching run's trajectory: m's forward labels, `samples` rows of zeros.
Trajectory switching_trajectory(const Model& m, int samples);

// A leg's samples that fall on the output grid of o (t0 + (t1 - t0) k / (samples - 1)) written to
// `out` from row `filled` on, reactions by label and the energy terms plus `off` (their values at
// the leg's start); off is then advanced to the leg's end, and the leg's statistics added.
void append_leg(Trajectory& out, int& filled, const Trajectory& leg, const ForwardOptions& o,
                double (&off)[kEnergyTerms]);

class ChainLog {
 public:
  static constexpr int kListed = 50;  // individual lines listed per chain
  explicit ChainLog(size_t chains = 0) : chains_(chains) {}
  // whether chain k's next individual line is listed (else it is counted)
  bool listed(size_t k);
  // chain k's span `from` (0 upper, 1 lower) hands over to the other at t
  void handover(size_t k, int from, double t);
  // the closing lines of the chains named `names`: their handovers and lines not listed
  std::vector<std::string> summary(const std::vector<std::string>& names) const;

 private:
  struct Counts {
    int lines = 0, unlisted = 0, handovers[2] = {0, 0};
    double first = 0, last = 0;
  };
  std::vector<Counts> chains_;
};

}  // namespace mo2d::detail
