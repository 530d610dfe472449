// cvode_bdf over a singular passage where its step collapses. Next to a singular configuration
// the accelerations are regularized (ForwardData): not a smooth function of the state at the
// scale of BDF's Newton iterations, so its error test or its Newton iteration can fail at every
// step size: four-bar chains of 11 to 40 loops collapsed to steps of 1e-8 ... 1e-35 s at their
// flat position (t = 0.72 s), and the double four-bar at rtol 1e-12, at some tolerances and not
// at others. Fixed-step rk4 steps over such instants (forward_rk.cpp: stages projected), so the
// passage is handed to rk4 at the step CVODE took before the collapse, from the last step CVODE
// accepted (forward_cvode.cpp: hop); CVODE restarts after it. The error over a hop is not
// controlled by rtol: the run's warning names the hops, their steps and the time they covered.
#include "forward/cvode_hop.hpp"

#include <algorithm>
#include <string>

#include "forward/forward_run.hpp"
#include "mo2d/quasi_steady.hpp"
#include "run/format.hpp"

namespace mo2d::detail {

namespace {
// A collapse at a singular passage: CVODE's step below kHopRatio of its recent accepted steps for
// kHopEvaluations evaluations in a row, inside a singular window (a regularized evaluation among
// the last kHopRecent: ForwardData's solve near a singular configuration). The reference is the
// recent accepted steps' maximum, decaying by kHopDecay per accepted step outside the windows and
// held inside them: the 20-loop chain at rtol 1e-8 took thousands of accepted steps shrinking from
// 1e-6 to 1e-9 s in its window, under a decaying reference a step "like the recent ones". A
// passage that BDF manages takes steps of 1e-3 to 1e-5 of the recent ones (the double four-bar).
constexpr double kHopRatio = 1e-3, kHopDecay = 0.97;
constexpr int kHopEvaluations = 30;
constexpr long kHopRecent = 100;   // evaluations since a regularized one
constexpr long kStartSteps = 10;   // CVODE's start-up steps are small: not judged
constexpr double kHopBeyond = 20;  // a hop ends this many recent steps past the collapse
}  // namespace

bool HopWatch::due(double h, long steps_now, long regularized, long evaluations) {
  if (!allowed || !(h > 0)) return false;
  if (regularized > last_regularized) last_regularized = regularized, regularized_at = evaluations;
  const bool window = last_regularized > 0 && evaluations - regularized_at <= kHopRecent;
  if (steps_now > ref_steps) {  // the reference is held (no decay) inside a singular window
    ref_h = std::max(h, window ? ref_h : ref_h * kHopDecay);
    ref_steps = steps_now;
  }
  const bool tiny = h < kHopRatio * ref_h && window;
  tiny_evals = tiny ? tiny_evals + 1 : 0;
  return steps_now >= kStartSteps && tiny_evals >= kHopEvaluations;
}

double HopWatch::next_end(double t, double t_out) const {
  return std::min(t_out, t + kHopBeyond * ref_h);
}

void HopWatch::done(long hop_steps, double t_start, double t_end) {
  if (hops++ == 0) first = t_start;
  steps += hop_steps;
  covered += t_end - t_start;
  wanted = false;
  tiny_evals = 0;
}

std::string HopWatch::warning() const {
  return "cvode_bdf's step collapsed next to a singular configuration " + std::to_string(hops) +
         " time" + (hops > 1 ? "s" : "") + ", the first at t = " + fmt(first) +
         " s; rk4 at fixed steps (the steps before the collapse) took the run over it each time (" +
         std::to_string(steps) + " steps over " + fmt(covered) +
         " s, its error not controlled by rtol there), CVODE restarted after";
}

bool can_hop(const Model& m, const ForwardOptions& o) {
  return !o.stop_when && !switches_chains(m) && !has_quasi_steady(m);
}

HopResult hop_over(const Model& m, const ForwardOptions& o, const State& from, double t_out,
                   double seconds_left, long steps_left, double step) {
  ForwardOptions h = o;
  h.t0 = from.t;
  h.t1 = t_out;
  h.samples = 2;
  h.integrator = Integrator::rk4;
  h.step = step;
  h.accuracy = 0;
  h.error_estimate = ErrorEstimate::off;
  h.max_seconds = o.max_seconds > 0 ? std::max(seconds_left, 1e-3) : 0;
  h.max_steps = static_cast<int>(std::max(1L, std::min<long>(steps_left, o.max_steps)));
  const Trajectory r = forward_run(m, from, h);
  const Eigen::Index e = r.time.size() - 1;
  HopResult out;
  out.state = {r.time[e], r.q0.row(e).transpose(), r.q1.row(e).transpose()};
  out.energies[kInputWork] = r.input_work[e] - r.input_work[0];
  out.energies[kLoadWork] = r.load_work[e] - r.load_work[0];
  out.energies[kConstraintWork] = r.constraint_work[e] - r.constraint_work[0];
  out.energies[kDissipated] = r.dissipated[e] - r.dissipated[0];
  out.steps = r.stats.steps;
  return out;
}

}  // namespace mo2d::detail
