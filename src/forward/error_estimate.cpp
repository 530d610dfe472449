// The a-posteriori estimate of a forward run's global error (ForwardOptions::error_estimate).
//
// Estimator: a second run of the same method from the same initial state on the same output
// times, at tighter settings: tolerances rtol, atol / kTighten for the adaptive methods (dopri5,
// erk6, erk8, cvode_bdf, cvode_adams), the fixed step / 2 for rk4 and baumgarte (order 4: an
// error 2^4 = kTighten times smaller). The error of the second run is then about 1 / kTighten
// of the first's (tolerance proportionality; the order of the fixed-step method), so the
// difference of the two at the output times is the first run's error to within about
// 1 / kTighten of it: the estimate. It is taken over the position coordinates q0, each in
// lengths (a rotation as the arc of its body's size, column_scaling), relative to the mechanism's
// size (Model::scale): the measure of ForwardOptions::accuracy. Where the second run cannot be
// made more accurate (next to the floor of a method: erk8 near 1e-12, the augmented Lagrangian's
// ~1e-8 at singular instants) the difference underestimates the error; where it fails, the run
// says that its error was not estimated. Cost: the second run, 0.9 to 1.3 times the first's CPU
// for erk8 on the shipped scenes (16^(1/8) = 1.4 times the steps at most), about 2 times for rk4
// (half the step); measured in docs/performance.md, "Issue 30".
#include <algorithm>
#include <cmath>
#include <string>

#include "forward/forward_run.hpp"
#include "mo2d/error.hpp"
#include "mo2d/kinematics.hpp"
#include "run/cpu_time.hpp"

namespace mo2d::detail {

namespace {

constexpr double kTighten = 16;  // the second run's error: ~1/16 of the first's
constexpr std::size_t kMaxWarnings = 20;

bool fixed_step(Integrator i) {
  return i == Integrator::rk4 || i == Integrator::baumgarte;
}

// Next to singular configurations (the run's regularized evaluations) dopri5 below rtol 5e-10 and
// erk6/erk8 below 1e-11 gain no accuracy (forward_rk.cpp's floor: the augmented Lagrangian's
// ~1e-8 there) and crawl: on the double four-bar at accuracy 1e-8 (erk8, tol 1e-11) a second run
// at tol 6.25e-13 took 2.45 s for a 10.6 ms run and differed by 1.3e-5, a false alarm. There the
// second run is rk4 at the step of its calibration (accuracy.cpp: error ~ 1e-6 (h / 4e-3)^4) for
// 1 / kTighten of the accuracy the tolerance stands for (rtol x 1000, options_for_accuracy).
constexpr double kErkFloor = 1e-11, kDopri5Floor = 5e-10;
constexpr double kRk4Step = 4e-3, kRk4Error = 1e-6, kAccuracyPerTolerance = 1e3;

// The second run's options: the method that ran, tighter; no accuracy (no second choice), no
// estimate of its own, no progress report (the first run's progress has reached its end).
ForwardOptions reference_options(const ForwardOptions& ran, const RunStats& stats) {
  ForwardOptions o = ran;
  o.accuracy = 0;
  o.error_estimate = ErrorEstimate::off;
  o.progress = {};
  if (fixed_step(o.integrator)) {
    o.step = ran.step / 2;
    return o;
  }
  o.rtol = ran.rtol / kTighten;
  o.atol = ran.atol / kTighten;
  const bool explicit_rk = o.integrator == Integrator::dopri5 || o.integrator == Integrator::erk6 ||
                           o.integrator == Integrator::erk8;
  const double floor = o.integrator == Integrator::dopri5 ? kDopri5Floor : kErkFloor;
  if (explicit_rk && stats.regularized_evaluations > 0 && o.rtol < floor) {
    o.integrator = Integrator::rk4;
    const double target = kAccuracyPerTolerance * ran.rtol / kTighten;
    o.step = kRk4Step * std::min(1.0, std::pow(target / kRk4Error, 0.25));
  }
  return o;
}

std::string setting_text(const ForwardOptions& o, const ForwardOptions& ran) {
  if (fixed_step(o.integrator))
    return std::string(to_string(o.integrator)) + ", step " + fmt(o.step) + " s" +
           (fixed_step(ran.integrator) ? " (half the run's)"
                                       : " (the run's method is at its floor next to singular "
                                         "configurations)");
  return std::string(to_string(o.integrator)) + ", rtol " + fmt(o.rtol) + ", atol " + fmt(o.atol) +
         " (the run's / " + fmt(kTighten) + ")";
}

bool wanted(const ForwardOptions& o) {
  switch (o.error_estimate) {
    case ErrorEstimate::on:
      return true;
    case ErrorEstimate::off:
      return false;
    case ErrorEstimate::automatic:
      return o.accuracy > 0;
  }
  return false;
}

void warn(Trajectory& r, const std::string& w) {
  if (r.stats.warnings.size() < kMaxWarnings) r.stats.warnings.push_back(w);
}

}  // namespace

void estimate_global_error(const Model& m, const State& initial, const ForwardOptions& asked,
                           const ForwardOptions& ran, Trajectory& r) {
  estimate_global_error(m, asked, ran, r,
                        [&](const ForwardOptions& o) { return forward_run(m, initial, o); });
}

bool estimate_global_error(const Model& m, const ForwardOptions& asked, const ForwardOptions& ran,
                           Trajectory& r, const SecondRun& second_run) {
  if (!wanted(asked)) {
    r.stats.error_estimate =
        asked.error_estimate == ErrorEstimate::off
            ? "not estimated (error_estimate off)"
            : "not estimated: no accuracy asked for (error_estimate on estimates it by a second "
              "run at tighter settings, 1 to 2 times the run's CPU)";
    return false;
  }
  const ForwardOptions o = reference_options(ran, r.stats);
  const std::string how = "difference from a second run, " + setting_text(o, ran);
  const double start = cpu_seconds();
  Trajectory ref;
  try {
    ref = second_run(o);
  } catch (const Error& e) {
    r.stats.estimate_cpu_seconds = cpu_seconds() - start;
    r.stats.error_estimate =
        "not estimated: the second run (" + setting_text(o, ran) + ") failed: " + e.what();
    warn(r, "the run's error is not estimated: the second run (" + setting_text(o, ran) +
                ") failed: " + e.what());
    return false;
  }
  r.stats.estimate_cpu_seconds = cpu_seconds() - start;
  const VectorXd d = column_scaling(m).head(m.n0);  // lengths per unit of each coordinate
  const Eigen::Index n = std::min(r.time.size(), ref.time.size());
  double worst = 0, t_worst = n > 0 ? r.time[0] : 0;
  int j_worst = 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    if (r.time[k] != ref.time[k]) continue;  // an event located at another time
    for (int j = 0; j < m.n0; ++j) {
      const double e = std::abs(r.q0(k, j) - ref.q0(k, j)) / d[j] / m.scale;
      if (!(e <= worst)) worst = e, t_worst = r.time[k], j_worst = j;
    }
  }
  r.stats.estimated_error = worst;
  r.stats.estimated_error_t = t_worst;
  r.stats.estimated_error_variable = m.n0 > 0 ? m.coordinate_labels[j_worst] : "";
  r.stats.error_estimate = how;
  if (asked.accuracy > 0 && !(worst <= asked.accuracy))
    warn(r, "accuracy " + fmt(asked.accuracy) + " not met: estimated error " + fmt(worst) +
                " of the mechanism's size (" + fmt(m.scale) + " m), largest at t = " +
                fmt(t_worst) + " s in '" + r.stats.estimated_error_variable + "' (" + how +
                "); ask for a tighter accuracy or name the integrator and its tolerances");
  return true;
}

}  // namespace mo2d::detail
