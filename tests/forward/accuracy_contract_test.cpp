// The accuracy contract (issue 30, item 2): a run asked for accuracy A either meets A at its
// output times or ends with a warning naming its estimated error, checked on a table of scenes x
// accuracies 1e-2 ... 1e-10 against references computed at much tighter settings (1e-10 is below
// kMinAccuracy: refused with an error). The a-posteriori estimate (src/forward/error_estimate.cpp)
// against the true error; the method choice on a stiff seven-body mechanism never picks a step
// beyond what the accuracy needs. The full table (longer runs, more scenes):
// bench/accuracy_table.cpp and docs/performance.md, "Issue 30".
#include <gtest/gtest.h>

#include <cmath>
#include <initializer_list>
#include <numbers>
#include <sstream>
#include <string>

#include "mo2d/forward.hpp"
#include "mo2d/kinematics.hpp"
#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"

using namespace mo2d;

namespace {

struct ContractCase {
  std::string name;
  Model model;
  State start;
  ForwardOptions base;       // times and samples (and efforts) of the run
  ForwardOptions reference;  // the tight run the errors are measured against
};

// Largest position error over the output times, each coordinate in lengths (a rotation as the arc
// of its body's size), relative to the mechanism's size: the measure of accuracy.
double contract_error(const Model& m, const Trajectory& r, const Trajectory& ref) {
  const VectorXd d = column_scaling(m).head(m.n0);
  double worst = 0;
  for (Eigen::Index k = 0; k < std::min(r.time.size(), ref.time.size()); ++k)
    for (int j = 0; j < m.n0; ++j)
      worst = std::max(worst, std::abs(r.q0(k, j) - ref.q0(k, j)) / d[j] / m.scale);
  return worst;
}

bool contract_warned(const Trajectory& r, double a) {
  std::ostringstream s;
  s << "accuracy " << a;
  for (const std::string& w : r.stats.warnings)
    if (w.find(s.str()) == 0 && w.find("not met: estimated error") != std::string::npos)
      return true;
  return false;
}

// A pendulum released 2 rad from the bottom, 2 s (no singular position; large amplitude).
ContractCase contract_pendulum(double duration) {
  const Model m = build_model(
      mechanisms::pendulum({.L = 1, .m = 1, .g = 9.81, .theta0 = -std::numbers::pi / 2 - 2.0})
          .system);
  const State s = consistent_state(m, {.positions = {}, .velocities = {{"link.w", 0.0}}});
  const ForwardOptions base{.t0 = 0, .t1 = duration, .samples = 41};
  ForwardOptions ref = base;
  ref.integrator = Integrator::erk8;
  ref.rtol = ref.atol = 1e-14;
  return {"pendulum", m, s, base, ref};
}

// tests/data/stiff_chain7.yaml: seven sliders joined by stiff springs (|lambda|max ~ 1.1e3 /s).
ContractCase contract_stiff_chain(double duration) {
  const Scene sc = load_scene(std::string(MO2D_TEST_DATA_DIR) + "/stiff_chain7.yaml");
  const Model m = build_scene_model(sc);
  ForwardOptions base = forward_options(sc, m);
  base.t1 = base.t0 + duration;
  base.samples = 21;
  ForwardOptions ref = base;
  ref.accuracy = 0;
  ref.integrator = Integrator::cvode_bdf;
  ref.rtol = 1e-13;
  ref.atol = 1e-15;
  return {"stiff_chain7", m, initial_state(sc, m), base, ref};
}

// mechanisms/rack_pinion.yaml (a spring on the rack, a torque on the pinion), 1 s.
ContractCase contract_rack_pinion() {
  const Scene sc = load_scene(std::string(MO2D_MECHANISMS_DIR) + "/rack_pinion.yaml");
  const Model m = build_scene_model(sc);
  ForwardOptions base = forward_options(sc, m);
  base.t1 = base.t0 + 1;
  base.samples = 21;
  ForwardOptions ref = base;
  ref.accuracy = 0;
  ref.integrator = Integrator::erk8;
  ref.rtol = ref.atol = 1e-14;
  return {"rack_pinion", m, initial_state(sc, m), base, ref};
}

void contract_check(const ContractCase& c, std::initializer_list<double> accuracies = {
                                               1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9}) {
  const Trajectory ref = forward_dynamics(c.model, c.start, c.reference);
  for (double a : accuracies) {
    ForwardOptions o = c.base;
    o.accuracy = a;
    const Trajectory r = forward_dynamics(c.model, c.start, o);
    const double e = contract_error(c.model, r, ref);
    const bool warned = contract_warned(r, a);
    // met, or refused with a warning naming the estimate
    EXPECT_TRUE(e <= a || warned) << c.name << " accuracy " << a << ": error " << e
                                  << " and no warning; " << r.stats.method;
    // the estimate is there, and a warning only where the estimate exceeds A
    ASSERT_FALSE(std::isnan(r.stats.estimated_error)) << c.name << " " << r.stats.error_estimate;
    EXPECT_EQ(warned, r.stats.estimated_error > a) << c.name << " accuracy " << a;
    // the estimate follows the error: within a factor 3 where the error is above round-off
    if (e > 1e-11) {
      EXPECT_LT(std::abs(std::log(r.stats.estimated_error / e)), std::log(3.0))
          << c.name << " accuracy " << a << ": error " << e << ", estimated "
          << r.stats.estimated_error;
    }
  }
  ForwardOptions o = c.base;
  o.accuracy = 1e-10;  // below what the methods are calibrated for: refused
  EXPECT_THROW((void)forward_dynamics(c.model, c.start, o), Error) << c.name;
}

}  // namespace

TEST(AccuracyContract, PendulumMetOrWarned) {
  contract_check(contract_pendulum(2));
}

TEST(AccuracyContract, StiffSevenBodyChainMetOrWarned) {
  contract_check(contract_stiff_chain(0.02), {1e-2, 1e-4, 1e-6, 1e-8});
}

// A long run: the pendulum asked for 1e-6 over 100 s (erk8, tol 1e-9, calibrated on 10 s) ends
// about 2e-5 off; the run finds it by its estimate and is run again at a tighter accuracy
// (meet_accuracy.cpp) until it meets 1e-6. At the floor of the accuracies (1e-9) no tighter run
// is possible: the run says that it misses the accuracy, with its estimate.
TEST(AccuracyContract, LongPendulumRunIsRetriedOrSaysItMissesTheAccuracy) {
  const ContractCase c = contract_pendulum(100);
  const Trajectory ref = forward_dynamics(c.model, c.start, c.reference);
  ForwardOptions o = c.base;
  o.accuracy = 1e-6;
  Trajectory r = forward_dynamics(c.model, c.start, o);
  double e = contract_error(c.model, r, ref);
  EXPECT_TRUE(e <= 1e-6 || contract_warned(r, 1e-6)) << e;
  EXPECT_NE(r.stats.error_estimate.find("retried for the accuracy asked for"), std::string::npos)
      << r.stats.error_estimate;
  EXPECT_LT(std::abs(std::log(r.stats.estimated_error / e)), std::log(3.0))
      << e << " " << r.stats.estimated_error;
  o.accuracy = 1e-9;
  r = forward_dynamics(c.model, c.start, o);
  e = contract_error(c.model, r, ref);
  EXPECT_GT(e, 1e-9);
  EXPECT_TRUE(contract_warned(r, 1e-9)) << e;
  EXPECT_LT(std::abs(std::log(r.stats.estimated_error / e)), std::log(3.0))
      << e << " " << r.stats.estimated_error;
  EXPECT_NE(r.stats.estimated_error_variable.find("link."), std::string::npos);
}

TEST(AccuracyContract, RackPinionMetOrWarned) {
  contract_check(contract_rack_pinion());
}

// The stiff seven-body chain asked for 1e-9: the stiffness test measured against rk4's fixed step
// (the explicit method below 1e-8) called it "not stiff" and rk4 ran at 7.1e-4 s, 1e5 x worse
// than asked, without a warning. The choice is now stiff at every accuracy on it (against the
// adaptive method's step) and the run meets 1e-9.
TEST(AccuracyContract, StiffChainAtTightAccuracyIsNotGivenALongFixedStep) {
  const ContractCase c = contract_stiff_chain(0.02);
  const Trajectory ref = forward_dynamics(c.model, c.start, c.reference);
  for (double a : {1e-8, 1e-9}) {
    ForwardOptions o = c.base;
    o.accuracy = a;
    const MethodChoice choice = choose_method(c.model, c.start, o);
    EXPECT_TRUE(choice.stiff) << choice.reason;
    EXPECT_NE(choice.options.integrator, Integrator::rk4) << choice.reason;
    const Trajectory r = forward_dynamics(c.model, c.start, o);
    EXPECT_LE(contract_error(c.model, r, ref), a) << r.stats.method;
  }
}

// A mechanism faster than rk4's calibration (the double four-bar's slow motion) but not stiff:
// below 1e-8 an adaptive method (erk8) instead of rk4's calibrated step.
TEST(AccuracyContract, FastNonStiffMechanismGetsTheAdaptiveMethod) {
  const ContractCase c = contract_pendulum(0.5);
  // a pendulum 100 times shorter: |lambda| ~ 10 sqrt(g / L) = 31 /s x 10
  const Model m = build_model(
      mechanisms::pendulum({.L = 1e-2, .m = 1, .g = 9.81, .theta0 = -std::numbers::pi / 2 - 2.0})
          .system);
  const State s = consistent_state(m, {.positions = {}, .velocities = {{"link.w", 0.0}}});
  const MethodChoice choice = choose_method(m, s, {.t0 = 0, .t1 = 0.5, .accuracy = 1e-9});
  EXPECT_FALSE(choice.stiff) << choice.reason;
  EXPECT_EQ(choice.options.integrator, Integrator::erk8) << choice.reason;
  // the slow one keeps rk4
  const MethodChoice slow = choose_method(c.model, c.start, {.t0 = 0, .t1 = 0.5, .accuracy = 1e-9});
  EXPECT_EQ(slow.options.integrator, Integrator::rk4) << slow.reason;
}

// A run without an accuracy reports no estimate unless asked (ErrorEstimate::on), and says why.
TEST(AccuracyContract, EstimateOnlyWhereAskedFor) {
  const ContractCase c = contract_pendulum(0.5);
  ForwardOptions o = c.base;
  o.integrator = Integrator::dopri5;
  o.rtol = o.atol = 1e-6;
  const Trajectory plain = forward_dynamics(c.model, c.start, o);
  EXPECT_TRUE(std::isnan(plain.stats.estimated_error));
  EXPECT_NE(plain.stats.error_estimate.find("not estimated"), std::string::npos);
  o.error_estimate = ErrorEstimate::on;
  const Trajectory est = forward_dynamics(c.model, c.start, o);
  const Trajectory ref = forward_dynamics(c.model, c.start, c.reference);
  const double e = contract_error(c.model, est, ref);
  EXPECT_LT(std::abs(std::log(est.stats.estimated_error / e)), std::log(3.0))
      << e << " " << est.stats.estimated_error;
  EXPECT_GT(est.stats.estimate_cpu_seconds, 0);
  EXPECT_NE(est.stats.error_estimate.find("second run, dopri5, rtol 6.25e-08"), std::string::npos)
      << est.stats.error_estimate;
  o.accuracy = 1e-6;  // with an accuracy: off is off
  o.error_estimate = ErrorEstimate::off;
  EXPECT_TRUE(std::isnan(forward_dynamics(c.model, c.start, o).stats.estimated_error));
}

// The double four-bar at 1e-8 (erk8, tol 1e-11, its floor next to the singular passages): a
// second run at tol / 16 gained nothing and crawled (2.45 s for a 10.6 ms run, 1.3e-5 apart: a
// false alarm); the second run is rk4 at its calibrated step there, and the run meets 1e-8.
TEST(AccuracyContract, EstimateAtTheFloorOfTheMethodNextToSingularInstants) {
  const Model m = build_model(mechanisms::double_fourbar());
  const State s = consistent_state(m, {.positions = {}, .velocities = {{"crank0.w", -1.0}}});
  const Trajectory r = forward_dynamics(m, s, {.t0 = 0, .t1 = 4, .samples = 11, .accuracy = 1e-8});
  EXPECT_GT(r.stats.regularized_evaluations, 0);
  EXPECT_NE(r.stats.error_estimate.find("rk4"), std::string::npos) << r.stats.error_estimate;
  EXPECT_LE(r.stats.estimated_error, 1e-8) << r.stats.error_estimate;
  EXPECT_FALSE(contract_warned(r, 1e-8));
}
