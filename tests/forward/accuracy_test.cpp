// ForwardOptions::accuracy (run.accuracy): the run reaches the accuracy asked for, checked against
// closed forms and the double four-bar's 40-digit reference, on the calibration runs and on others;
// bad values are refused with the option's name (the scene key: scene/run_override_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>

#include "mo2d/forward.hpp"
#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"

using namespace mo2d;

namespace {

std::string accuracy_scene_path(const std::string& name) {
  return std::string(MO2D_MECHANISMS_DIR) + "/" + name + ".yaml";
}

// The IFToMM double four-bar, 10 s through its ten singular positions: error of the first crank
// tip at t = 10 s against the parallelogram reduction in 40 digits (forward_test.cpp), over the
// mechanism's size.
double double_fourbar_error(double accuracy, int samples) {
  const Model m = build_model(mechanisms::double_fourbar());
  const State s = consistent_state(m, {.positions = {}, .velocities = {{"crank0.w", -1.0}}});
  const Trajectory r =
      forward_dynamics(m, s,
                       {.t0 = 0,
                        .t1 = 10,
                        .samples = samples,
                        .accuracy = accuracy,
                        .error_estimate = ErrorEstimate::off});  // checked by the reference here
  // erk8 from 1e-8 up, rk4 below (src/forward/accuracy.cpp)
  EXPECT_EQ(options_for_accuracy(m, {.accuracy = accuracy}).integrator,
            accuracy >= 1e-8 ? Integrator::erk8 : Integrator::rk4);
  const int k = static_cast<int>(r.time.size()) - 1;
  return std::hypot(r.q0(k, m.coordinate("crank0.B.x")) - 0.328458111541,
                    r.q0(k, m.coordinate("crank0.B.y")) - 0.944518538179) /
         m.scale;
}

// a number as the command line writes it ("1e-09"; std::to_string gives "0.000000")
std::string text(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

TEST(Accuracy, DoubleFourBarReachesTheAccuracyAskedFor) {
  for (double a : {1e-2, 1e-3, 1e-5, 3e-6, 1e-6, 1e-7, 1e-8, 1e-9})
    for (int samples : {11, 101}) {
      const double e = double_fourbar_error(a, samples);
      EXPECT_LE(e, a) << "accuracy " << a << " samples " << samples;
    }
}

// A pendulum released 2 rad from the bottom (not a calibration run): the tip passes the bottom
// (x = 0) at the quarter period sqrt(L/g) K(sin(1)).
TEST(Accuracy, PendulumQuarterPeriod) {
  const double L = 1, g = 9.81, amplitude = 2.0;
  const Model m = build_model(
      mechanisms::pendulum({.L = L, .m = 1, .g = g, .theta0 = -std::numbers::pi / 2 - amplitude})
          .system);
  const State s = consistent_state(m, {.positions = {}, .velocities = {{"link.w", 0.0}}});
  double a_ = 1, b_ = std::sqrt(1 - std::pow(std::sin(amplitude / 2), 2));  // AGM for K(k)
  for (int i = 0; i < 40; ++i) {
    const double an = 0.5 * (a_ + b_);
    b_ = std::sqrt(a_ * b_);
    a_ = an;
  }
  const double quarter = std::sqrt(L / g) * std::numbers::pi / (2 * a_);
  for (double a : {1e-3, 1e-5, 1e-6, 1e-9}) {
    const Trajectory r = forward_dynamics(m, s, {.t1 = 3 * quarter, .samples = 4, .accuracy = a});
    // at T/4 and 3T/4 the tip is at the bottom
    EXPECT_LE(std::abs(r.q0(1, m.coordinate("link.P.x"))) / m.scale, a) << a;
    EXPECT_LE(std::abs(r.q0(3, m.coordinate("link.P.x"))) / m.scale, a) << a;
  }
}

// mechanisms/rack_pinion.yaml (a spring on the rack, a constant torque on the pinion): the rack
// oscillates as x_e (1 - cos w t) (gear_scene_test.cpp), asked for with run.accuracy.
TEST(Accuracy, RackPinionSceneClosedForm) {
  for (double a : {1e-4, 1e-7, 1e-9}) {
    const Scene scene = load_scene(accuracy_scene_path("rack_pinion"), {},
                                   std::vector<RunOverride>{{"accuracy", text(a)}});
    EXPECT_EQ(scene.run.accuracy, a);
    const Model m = build_scene_model(scene);
    const ForwardOptions o = forward_options(scene, m);
    EXPECT_EQ(o.integrator, a >= 1e-8 ? Integrator::erk8 : Integrator::rk4);
    const Trajectory r = forward_dynamics(m, initial_state(scene, m), o);
    const double rr = 0.05, mass = 3, I = 0.01, k = 200, T = 0.5;
    const double xe = -T / (rr * k), w = std::sqrt(k / (mass + I / (rr * rr)));
    double worst = 0;
    for (int i = 0; i < r.time.size(); ++i)
      worst = std::max(
          worst, std::abs(r.q0(i, r.column("slide.q")) - 1 - xe * (1 - std::cos(w * r.time[i]))));
    EXPECT_LE(worst / m.scale, a) << a;
  }
}

TEST(Accuracy, BadValuesAreRefused) {
  const Model m = build_model(mechanisms::double_fourbar());
  for (double a : {-1e-6, 1e-10, 0.5, std::nan(""), std::numeric_limits<double>::infinity()}) {
    try {
      (void)options_for_accuracy(m, {.accuracy = a});
      ADD_FAILURE() << "accepted accuracy " << a;
    } catch (const Error& e) {
      EXPECT_EQ(e.element(), "accuracy");
      EXPECT_NE(std::string(e.what()).find("accuracy must be in [1e-09, 0.01]"), std::string::npos)
          << e.what();
    }
  }
}
