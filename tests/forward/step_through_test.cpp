// The last resort of the explicit Runge-Kutta drivers (forward_rk.cpp, RkDriver::step_through):
// where every retry length puts a stage on a singular instant, the longest try is taken with the
// regularized accelerations, its error estimated and reported. Reached on the IFToMM double
// four-bar by erk6 and dopri5 at rtol 1e-10 (steps of ~1e-4 s, shorter than the instant's
// neighbourhood); the end point is checked against the 40-digit reference (shared/notes/peers.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <string>

#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"

namespace step_through_test {

using namespace mo2d;

// The error estimate a "could not step over" warning reports (times rtol/atol), -1 if none.
double reported_estimate(const std::string& w) {
  const std::string key = " step ";
  const auto at = w.find("error estimate of the ");
  if (at == std::string::npos) return -1;
  const auto k = w.find(key, at);
  return k == std::string::npos ? -1 : std::strtod(w.c_str() + k + key.size(), nullptr);
}

TEST(ForwardStepThrough, UnavoidableSingularStepsAreErrorEstimatedAndReported) {
  const Model m = build_model(mechanisms::double_fourbar());
  const State s = consistent_state(m, {.positions = {}, .velocities = {{"crank0.w", -1.0}}});
  const int ix = m.coordinate("crank0.B.x"), iy = m.coordinate("crank0.B.y");
  for (const Integrator i : {Integrator::erk6, Integrator::dopri5}) {
    const double tol = 1e-10;
    const ForwardOptions o{
        .t0 = 0, .t1 = 10, .samples = 11, .integrator = i, .rtol = tol, .atol = tol};
    const Trajectory r = forward_dynamics(m, s, o);
    int fallbacks = 0;
    for (const std::string& w : r.stats.warnings) {
      if (w.find("could not step over a singular configuration near t = ") == std::string::npos)
        continue;
      ++fallbacks;
      // the estimate, the variable where it is largest, and the step's length are named
      const double e = reported_estimate(w);
      EXPECT_GT(e, 0) << w;
      EXPECT_LE(e * tol, 1e-3) << w;  // not gross: the run goes on (else an Error)
      EXPECT_NE(w.find("largest in 'coupler"), std::string::npos) << w;
    }
    EXPECT_GT(fallbacks, 0) << to_string(i) << ": the last resort was not reached";
    // the steps so taken keep the physical branch (a branch flip ends 0.9 m away)
    const int k = static_cast<int>(r.time.size()) - 1;
    EXPECT_LE(std::hypot(r.q0(k, ix) - 0.328458111541, r.q0(k, iy) - 0.944518538179), 1000 * tol)
        << to_string(i);
  }
}

}  // namespace step_through_test
