// ForwardOptions::accuracy: the integrator and tolerances for an accuracy asked for.
//
// Calibration on the IFToMM double four-bar (10 s through ten singular positions; error of the
// first crank tip at t = 10 s against the 40-digit reference; bench/speed_vs_error.cpp and
// docs/performance.md, "Issue 14, items 2 and 4"):
//  - erk8 (Fehlberg 8(7)): error / tolerance between 12 and 390 for tolerances 1e-4 ... 1e-11
//    (error per step control: the global error adds up over the ~50-300 steps), with the stages
//    of the steps next to a singular instant projected (forward_rk.cpp). It serves accuracies
//    >= 1e-8 with rtol = atol = accuracy / 1000 (atol = rtol as calibrated: a smaller atol is a
//    tighter tolerance): at 1e-6 it takes 2,791 evaluations where dopri5 (error / tolerance
//    ~370) takes 5,888, at 1e-8 4,689 where rk4 takes 32,402. At tolerance 1e-12 it needs
//    143,052 (next to the instants the augmented Lagrangian's ~1e-8 relative accuracy shows).
//  - rk4 (fixed step h): error 3.3e-7 at h = 4e-3, 1.1e-8 at 2e-3, 3.4e-10 at 1e-3, below
//    3.3e-7 (h / 4e-3)^4; it serves accuracies below 1e-8 with the step of that bound, with a
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

constexpr double kErk8Below = 1e-8;                  // erk8 from this accuracy up
constexpr double kTolerancePerAccuracy = 1e-3;       // erk8: rtol / accuracy
constexpr double kRk4Step = 4e-3, kRk4Error = 1e-6;  // rk4: 3 x the error at that step

}  // namespace

ForwardOptions options_for_accuracy(const Model& /*m*/, ForwardOptions o) {
  if (o.accuracy == 0) return o;
  if (!(o.accuracy >= kMinAccuracy && o.accuracy <= kMaxAccuracy))
    throw Error("forward dynamics: accuracy must be in [" + detail::fmt(kMinAccuracy) + ", " +
                    detail::fmt(kMaxAccuracy) + "] (got " + detail::fmt(o.accuracy) +
                    "; the error of the positions relative to the mechanism's size), or 0",
                "accuracy");
  if (o.accuracy >= kErk8Below) {
    o.integrator = Integrator::erk8;
    o.rtol = o.atol = kTolerancePerAccuracy * o.accuracy;
  } else {
    o.integrator = Integrator::rk4;
    o.step = kRk4Step * std::min(1.0, std::pow(o.accuracy / kRk4Error, 0.25));
  }
  return o;
}

}  // namespace mo2d
