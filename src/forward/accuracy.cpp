// ForwardOptions::accuracy: the integrator and tolerances for an accuracy asked for.
//
// Calibration on the IFToMM double four-bar (10 s through ten singular positions; error of the
// first crank tip at t = 10 s against the 40-digit reference; bench/speed_vs_error.cpp and
// docs/performance.md, "Issue 14, items 2 and 4"):
//  - erk8 (Fehlberg 8(7)): error / tolerance between 52 and 630 for tolerances 1e-4 ... 1e-9
//    (error per step control: the global error adds up over the ~100-200 steps). Below a tolerance
//    of 1e-8 it cannot always step over the singular instants (next to one the augmented
//    Lagrangian's accelerations are accurate to ~1e-8 relative only: at rtol 1e-9 and atol 5e-10
//    it ended 1.7e-2 away), so erk8 serves accuracies >= 1e-5 with rtol = atol = accuracy / 1000
//    (atol = rtol as calibrated: a smaller atol is a tighter tolerance).
//  - dopri5: error / tolerance ~370 from 1e-7 down to its floor, 5e-10 (3.7e-7 at 1e-9): it
//    serves accuracies in [1e-6, 1e-5) with rtol = atol = accuracy / 1000.
//  - rk4 (fixed step h): error 3.3e-7 at h = 4e-3, 1.1e-8 at 2e-3, 3.4e-10 at 1e-3, below
//    3.3e-7 (h / 4e-3)^4; it serves accuracies below 1e-6 with the step of that bound, with a
//    margin of 3 (1e-6 (h / 4e-3)^4 = accuracy), at most 4e-3 s. The step is this
//    mechanism's: its motion (bars of 1 m under gravity, periods of seconds) sets the constant,
//    so a mechanism with faster motion needs a shorter step than the one chosen here.
#include <algorithm>
#include <cmath>
#include <string>

#include "mo2d/error.hpp"
#include "mo2d/forward.hpp"
#include "run/format.hpp"

namespace mo2d {

const double kMinAccuracy = 1e-9, kMaxAccuracy = 1e-2;

namespace {

constexpr double kErk8Below = 1e-5, kDopri5Below = 1e-6;  // erk8, dopri5 from these up
constexpr double kTolerancePerAccuracy = 1e-3;            // erk8, dopri5: rtol / accuracy
constexpr double kRk4Step = 4e-3, kRk4Error = 1e-6;       // rk4: 3 x the error at that step

}  // namespace

ForwardOptions options_for_accuracy(const Model& /*m*/, ForwardOptions o) {
  if (o.accuracy == 0) return o;
  if (!(o.accuracy >= kMinAccuracy && o.accuracy <= kMaxAccuracy))
    throw Error("forward dynamics: accuracy must be in [" + detail::fmt(kMinAccuracy) + ", " +
                    detail::fmt(kMaxAccuracy) + "] (got " + detail::fmt(o.accuracy) +
                    "; the error of the positions relative to the mechanism's size), or 0",
                "accuracy");
  if (o.accuracy >= kDopri5Below) {
    o.integrator = o.accuracy >= kErk8Below ? Integrator::erk8 : Integrator::dopri5;
    o.rtol = o.atol = kTolerancePerAccuracy * o.accuracy;
  } else {
    o.integrator = Integrator::rk4;
    o.step = kRk4Step * std::min(1.0, std::pow(o.accuracy / kRk4Error, 0.25));
  }
  return o;
}

}  // namespace mo2d
