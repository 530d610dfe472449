// The error estimate of contact runs (src/contact/contact_estimate.cpp): the estimate against the
// run's actual error, the events compared between the two runs, and when it runs.
#include <gtest/gtest.h>

#include <cmath>

#include "contact_support.hpp"

namespace {

using namespace contact_test;

// The pendulum of RigidContact.PendulumHitsAStop: a uniform rod (0.8 m, 2 kg) released horizontal
// hits the stop x = 0 with its tip when vertical (e = 0.6). Its coordinates are the tip's position
// (lengths).
Model estimate_pendulum() {
  return stop_pendulum(0.8, 2, 9.81);
}

std::vector<ContactDef> stop_contact() {
  return {{.name = "stop",
           .point = "rod.B",
           .target = ContactDef::Target::line,
           .a = "ground.S1",
           .b = "ground.S2",
           .law = rigid(0.6)}};
}

ContactRun stop_run(const Model& m, double rtol, ErrorEstimate estimate, double accuracy = 0) {
  ContactOptions o;
  o.forward = {.t0 = 0,
               .t1 = 1.5,
               .samples = 31,
               .integrator = Integrator::dopri5,
               .rtol = rtol,
               .atol = rtol * 1e-2,
               .error_estimate = estimate};
  o.accuracy = accuracy;
  return contact_dynamics(
      m, stop_contact(), consistent_state(m, {.positions = {}, .velocities = {{"rod.w", 0.0}}}), o);
}

// The estimate is the difference from a second run 16 times tighter: it must give the run's
// actual error (its difference from a run a million times tighter, whose own error is negligible)
// to within a factor 3 — the estimator's use is the order of magnitude; an estimator that compares
// the wrong runs or columns, or a second run that is not tighter, is off by orders of magnitude.
TEST(ContactEstimate, GivesTheErrorOfARunWithImpacts) {
  const Model m = estimate_pendulum();
  const ContactRun run = stop_run(m, 1e-6, ErrorEstimate::on);
  const ContactRun ref = stop_run(m, 1e-12, ErrorEstimate::off);
  ASSERT_EQ(run.trajectory.time.size(), ref.trajectory.time.size());
  double actual = 0;
  for (Eigen::Index k = 0; k < run.trajectory.time.size(); ++k)
    for (int j = 0; j < m.n0; ++j)
      actual = std::max(actual, std::abs(run.trajectory.q0(k, j) - ref.trajectory.q0(k, j)));
  actual /= m.scale;
  const RunStats& st = run.trajectory.stats;
  ASSERT_GT(actual, 1e-9);  // a run with an error to estimate
  EXPECT_GT(st.estimated_error, actual / 3) << st.error_estimate;
  EXPECT_LT(st.estimated_error, actual * 3) << st.error_estimate;
  EXPECT_NE(st.error_estimate.find("difference from a second run"), std::string::npos)
      << st.error_estimate;
  // both runs see the same impacts (at least two), at times within the tolerance's reach
  ASSERT_GE(run.events.size(), 2U);
  EXPECT_NE(st.error_estimate.find("the same " + std::to_string(run.events.size()) + " events"),
            std::string::npos)
      << st.error_estimate;
  EXPECT_TRUE(st.warnings.empty()) << st.warnings.front();
}

TEST(ContactEstimate, RunsWhenAskedForOrForAnAccuracy) {
  const Model m = estimate_pendulum();
  // automatic without an accuracy: not estimated, and said so
  ContactRun r = stop_run(m, 1e-6, ErrorEstimate::automatic);
  EXPECT_TRUE(std::isnan(r.trajectory.stats.estimated_error));
  EXPECT_NE(r.trajectory.stats.error_estimate.find("not estimated"), std::string::npos);
  // automatic with an accuracy: estimated, and a warning where it is not met
  r = stop_run(m, 1e-6, ErrorEstimate::automatic, 1e-12);
  EXPECT_GT(r.trajectory.stats.estimated_error, 1e-12);
  ASSERT_FALSE(r.trajectory.stats.warnings.empty());
  EXPECT_NE(r.trajectory.stats.warnings.front().find("accuracy 1e-12 not met"), std::string::npos)
      << r.trajectory.stats.warnings.front();
  // off: not estimated
  r = stop_run(m, 1e-6, ErrorEstimate::off, 1e-3);
  EXPECT_TRUE(std::isnan(r.trajectory.stats.estimated_error));
}

}  // namespace
