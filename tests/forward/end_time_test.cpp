// Every run ends (issue 30, item 1): over random start times, durations, sample counts, steps and
// tolerances, on every integrator, a forward run reaches t1 exactly, records every output time and
// takes a bounded number of steps. The grid's last time t0 + (t1 - t0) k / (n - 1) at k = n - 1 can
// round one ulp past t1 (0.123 with n = 18): the embedded RK drivers then took steps of length 0
// at t1 until the budget ended the run (2.6 million steps for the double four-bar at 0.123 s).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <string>

#include "mo2d/forward.hpp"
#include "mo2d/inverse.hpp"
#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"
#include "run/time_grid.hpp"

using namespace mo2d;

namespace {

// A duration as a user writes it: 1 to 4 significant digits, 1e-3 ... 1 s.
double user_duration(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> digits(1, 4), decade(-3, -1);
  const double scale = std::pow(10.0, digits(rng));
  std::uniform_real_distribution<double> u(1.0, 10.0);
  return std::round(u(rng) * scale) / scale * std::pow(10.0, decade(rng) + 1) / 10;
}

double user_start(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> kind(0, 3);
  std::uniform_real_distribution<double> u(-10.0, 10.0);
  switch (kind(rng)) {
    case 0:
      return 0.0;
    case 1:
      return std::round(u(rng) * 1000) / 1000;
    case 2:
      return u(rng);
    default:
      return 1e3 * std::abs(u(rng));
  }
}

struct Case {
  Integrator integrator;
  double t0, duration, step, tol;
  int samples;
  std::string text() const {
    char s[200];
    std::snprintf(s, sizeof s,
                  "%s t0 = %.17g, duration = %.17g, samples = %d, step = %.3g, tol = %.3g",
                  to_string(integrator), t0, duration, samples, step, tol);
    return s;
  }
};

// Steps a run of the case may take: a fixed step ends on every output time (at most one extra
// step per output interval); an adaptive one is not shortened by output times (RK) or stops at
// each (CVODE), and a pendulum needs far fewer than 2000 steps at these tolerances over 1 s.
long step_bound(const Case& c) {
  if (c.integrator == Integrator::rk4 || c.integrator == Integrator::baumgarte)
    return static_cast<long>(std::ceil(c.duration / c.step)) + c.samples + 1;
  return 2000 + 2L * c.samples;
}

}  // namespace

// The last grid time is t1 exactly, the grid non-decreasing, for the durations of the report.
TEST(ForwardEndTime, TheGridEndsOnTheEndTimeExactly) {
  for (double t1 : {0.123, 0.7771, 0.0838, 0.085, 0.12, 1.3})
    for (long long n = 2; n < 3000; ++n) {
      ASSERT_EQ(detail::sample_time(0.0, t1, n, n - 1), t1) << n;
      ASSERT_LE(detail::sample_time(0.0, t1, n, n - 2), t1) << n;
    }
  std::mt19937_64 rng(7);
  for (int i = 0; i < 2000; ++i) {
    const double t0 = user_start(rng), t1 = t0 + user_duration(rng);
    const long long n = 2 + static_cast<long long>(rng() % 5000);
    double prev = t0;
    for (long long k = 0; k < n; ++k) {
      const double t = detail::sample_time(t0, t1, n, k);
      ASSERT_GE(t, prev);
      prev = t;
    }
    ASSERT_EQ(prev, t1);
  }
}

// Random grids on every integrator: the run ends at t1 exactly with every sample, within the
// bound of steps (max_steps set far above it, so that a run that loops fails here quickly).
TEST(ForwardEndTime, RandomGridsEndWithinABoundedNumberOfSteps) {
  auto ex = mechanisms::pendulum({.theta0 = -0.4});
  const Model m = build_model(ex.system);
  const State s0 = consistent_state(m, {.positions = {}, .velocities = {{"link.w", 0.5}}});
  const Integrator all[] = {Integrator::rk4,      Integrator::dopri5,    Integrator::erk6,
                            Integrator::erk8,     Integrator::cvode_bdf, Integrator::cvode_adams,
                            Integrator::baumgarte};
  std::mt19937_64 rng(20261206);
  std::uniform_int_distribution<int> samples(2, 400);
  std::uniform_real_distribution<double> log_step(-4, -2), log_tol(-10, -4);
  int runs = 0;
  for (int round = 0; round < 40; ++round)
    for (Integrator integrator : all) {
      const Case c{integrator,
                   user_start(rng),
                   user_duration(rng),
                   std::pow(10.0, log_step(rng)),
                   std::pow(10.0, log_tol(rng)),
                   samples(rng)};
      ForwardOptions o{.t0 = c.t0,
                       .t1 = c.t0 + c.duration,
                       .samples = c.samples,
                       .integrator = c.integrator,
                       .rtol = c.tol,
                       .atol = c.tol,
                       .step = c.step};
      o.max_steps = 200000;
      o.max_seconds = 20;
      Trajectory r;
      ASSERT_NO_THROW(r = forward_dynamics(m, s0, o)) << c.text();
      ASSERT_EQ(r.time.size(), c.samples) << c.text();
      EXPECT_EQ(r.time[r.time.size() - 1], o.t1) << c.text();
      EXPECT_EQ(r.stats.t_end, o.t1) << c.text();
      EXPECT_LE(r.stats.steps, step_bound(c)) << c.text();
      ++runs;
    }
  EXPECT_EQ(runs, 40 * 7);
}

// The shipped scene and duration of the report (double four-bar, 0.123 s, dopri5 and erk8)
// and the grids that hung: each ends at t1 with a handful of steps.
TEST(ForwardEndTime, TheReportedDurationsEnd) {
  const Model m = build_model(mechanisms::double_fourbar());
  const State s = consistent_state(m, {.positions = {}, .velocities = {{"crank0.w", -1.0}}});
  for (Integrator integrator : {Integrator::dopri5, Integrator::erk6, Integrator::erk8})
    for (double t1 : {0.123, 0.0838, 0.085, 0.7771})
      for (int n : {18, 124, 1231}) {
        ForwardOptions o{
            .t0 = 0, .t1 = t1, .samples = n, .integrator = integrator, .rtol = 1e-8, .atol = 1e-10};
        o.max_steps = 100000;
        o.max_seconds = 20;
        Trajectory r;
        ASSERT_NO_THROW(r = forward_dynamics(m, s, o)) << to_string(integrator) << " " << t1;
        EXPECT_EQ(r.stats.t_end, t1);
        EXPECT_LT(r.stats.steps, 2000) << to_string(integrator) << " " << t1 << " " << n;
      }
}

// Inverse dynamics samples the same grid: its last sample is at t1 exactly.
TEST(ForwardEndTime, InverseSamplesEndOnTheEndTime) {
  const auto ex = mechanisms::slider_crank();
  const Model m = build_model(ex.system);
  InverseOptions o = ex.run;
  for (double t1 : {0.123, 0.7771})
    for (int n : {18, 22}) {
      o.t0 = 0, o.t1 = t1, o.samples = n;
      const Trajectory r = inverse_dynamics(m, ex.motion, o);
      EXPECT_EQ(r.time[n - 1], t1);
    }
}
