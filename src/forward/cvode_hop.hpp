#pragma once
// Internal: cvode_bdf's singular passages by rk4 (cvode_hop.cpp).
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

// Whether a run may hand a passage to rk4: not with an event (stop_when) to locate, chains that
// switch spans, or quasi-steady springs (their own drivers).
bool can_hop(const Model& m, const ForwardOptions& o);
// rk4 at fixed `step` (s) from `from` to t_out, within seconds_left and steps_left.
HopResult hop_over(const Model& m, const ForwardOptions& o, const State& from, double t_out,
                   double seconds_left, long steps_left, double step);

}  // namespace mo2d::detail
