#pragma once
// Internal: cvode_bdf's singular passages by rk4 (cvode_hop.cpp).
#include <string>

#include "forward/forward_run.hpp"
#include "mo2d/forward.hpp"

namespace mo2d::detail {

// What a hop brings back: the state at its end, the energy terms gained over it (J, by
// EnergyTerm) and the steps it took.
struct HopResult {
  State state;
  double energies[kEnergyTerms] = {};
  long steps = 0;
};

// The watch for collapses inside singular windows and the hops over them, of one cvode_bdf run
// (forward_cvode.cpp).
struct HopWatch {
  bool allowed = false;  // can_hop, on cvode_bdf
  bool wanted = false;   // the last callback asked for a hop (due)
  // the recent accepted steps' maximum (s; decaying outside singular windows) at step count
  // ref_steps; the last count of regularized evaluations and the evaluation count then; the
  // evaluations in a row with a collapsed step
  double ref_h = 0;
  long ref_steps = 0, last_regularized = 0, regularized_at = 0;
  int tiny_evals = 0;
  // the hops made: count, the first's start (s), their steps, the time they covered (s)
  int hops = 0;
  double first = 0, covered = 0;
  long steps = 0;

  // Whether CVODE's current step h (at accepted step count `steps`, after `regularized` of
  // `evaluations` right-hand sides regularized) is a collapse to hop over.
  bool due(double h, long steps_now, long regularized, long evaluations);
  // Where a hop over a collapse reached at t ends: kHopBeyond recent steps past it, t_out if
  // sooner.
  double next_end(double t, double t_out) const;
  void done(long hop_steps, double t_start, double t_end);  // a hop from t_start to t_end taken
  std::string warning() const;                              // the run's warning about its hops
};

// Whether a run may hand a passage to rk4: not with an event (stop_when) to locate, chains that
// switch spans, or quasi-steady springs (their own drivers).
bool can_hop(const Model& m, const ForwardOptions& o);
// rk4 at fixed `step` (s) from `from` to t_out, within seconds_left and steps_left.
HopResult hop_over(const Model& m, const ForwardOptions& o, const State& from, double t_out,
                   double seconds_left, long steps_left, double step);

}  // namespace mo2d::detail
