// choose_method (src/forward/method_choice.cpp): the stiffness test at the initial state picks
// cvode_bdf on a stiff mechanism and the explicit method of options_for_accuracy otherwise; the
// spectral radius it estimates against the closed form of a spring's frequency; the method chosen
// on a stiff scene reaches the accuracy asked for against a closed form; scenes that name no
// method ask for kDefaultAccuracy.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "mo2d/forward.hpp"
#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"

using namespace mo2d;

namespace {

std::string scene_text(const std::string& name) {
  std::ifstream in(std::string(MO2D_MECHANISMS_DIR) + "/" + name + ".yaml");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string num(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}

// mechanisms/mass_spring_mass.yaml with the spring kept (reduce: none), stiffness k, from a
// consistent start (extension T(0) / k, rate T'(0) / k: the stiff mode at rest, as in
// scene/reduction_scene_test.cpp). Gamba 2009, 2.3: the centre of mass moves as the reduced
// model's v' = -a v + (F1 + F2) / M, the spring's extension follows the quasi-steady tension.
struct MassSpringMass {
  double m1 = 1, m2 = 2, c1 = 0.5, c2 = 2, F1a = 2, F1b = 3, W = 3, F2 = 1;
  double k = 0;
  Scene scene;
  Model model;
  State start;
  double M() const { return m1 + m2; }
  double a() const { return (c1 + c2) / M(); }
  double F1(double t) const { return F1a + F1b * std::sin(W * t); }
  double T(double t) const { return ((c1 * m2 - c2 * m1) * v(t) - (F1(t) * m2 - F2 * m1)) / M(); }
  double vp(double s) const {
    return F1b / M() * (a() * std::sin(W * s) - W * std::cos(W * s)) / (a() * a() + W * W);
  }
  double vs() const { return (F1a + F2) / (c1 + c2); }
  double v(double t) const { return vs() + vp(t) + (0 - vs() - vp(0)) * std::exp(-a() * t); }
  double vdot(double t) const { return -a() * v(t) + (F1(t) + F2) / M(); }
  // displacement of the centre of mass from t = 0: the integral of v
  double x(double t) const {
    const double A = a(), b = F1b / M();
    return vs() * t + b * (A * (1 - std::cos(W * t)) / W - std::sin(W * t)) / (A * A + W * W) +
           (0 - vs() - vp(0)) * (1 - std::exp(-A * t)) / A;
  }
  // the frequency of the spring mode, sqrt(k M / (m1 m2)) (mo2d info --fidelity)
  double omega() const { return std::sqrt(k * M() / (m1 * m2)); }

  explicit MassSpringMass(double stiffness, const std::vector<RunOverride>& run = {})
      : k(stiffness) {
    std::string text = scene_text("mass_spring_mass");
    text.replace(text.find("reduce: constraint}"), 18, "reduce: none");
    const double Tdot = ((c1 * m2 - c2 * m1) * vdot(0) - F1b * W * std::cos(0) * m2) / M();
    const std::vector<ParameterOverride> set = {{"k", num(k)}, {"e0", num(T(0) / k)}};
    scene = parse_scene(text, "mass_spring_mass.yaml", set, run);
    model = build_scene_model(scene);
    const double u0 = Tdot / k;
    start =
        consistent_state(model, {{}, {{"slide1.v", -m2 / M() * u0}, {"slide2.v", m1 / M() * u0}}});
  }
  // largest error of the centre of mass's position against x(t)
  double error(const Trajectory& r) const {
    double worst = 0;
    const double X0 =
        m2 * r.q0(0, r.column("slide2.q")) / M() + m1 * r.q0(0, r.column("slide1.q")) / M();
    for (int i = 0; i < r.time.size(); ++i) {
      const double X =
          (m1 * r.q0(i, r.column("slide1.q")) + m2 * r.q0(i, r.column("slide2.q"))) / M();
      worst = std::max(worst, std::abs(X - X0 - x(r.time[i])));
    }
    return worst;
  }
};

ForwardOptions asking(const MassSpringMass& s, double accuracy) {
  ForwardOptions o = forward_options(s.scene, s.model);
  o.accuracy = accuracy;
  return o;
}

}  // namespace

// The spectral radius at the initial state against the spring's frequency: J has the pair
// +-i omega (slightly damped by the viscous friction, whose rate a = 0.83 /s is far below).
TEST(MethodChoice, SpectralRadiusIsTheSpringFrequency) {
  for (double k : {1e2, 1e6, 1e8}) {
    const MassSpringMass s(k);
    const MethodChoice c = choose_method(s.model, s.start, asking(s, 1e-6));
    EXPECT_NEAR(c.spectral_radius / s.omega(), 1, 0.05) << "k = " << k;
  }
}

// k = 1e8 (omega = 1.2e4 /s, 1.5e4 steps for stability over 3 s) is stiff: cvode_bdf; k = 1e2
// (omega = 12 /s, 15 steps) is not: the explicit method of options_for_accuracy.
TEST(MethodChoice, StiffSpringPicksTheImplicitMethodASoftOneTheExplicit) {
  for (double accuracy : {1e-3, 1e-6, 1e-8}) {
    const MassSpringMass stiff(1e8), soft(1e2);
    const MethodChoice cs = choose_method(stiff.model, stiff.start, asking(stiff, accuracy));
    EXPECT_TRUE(cs.stiff) << cs.reason;
    EXPECT_EQ(cs.options.integrator, Integrator::cvode_bdf) << cs.reason;
    EXPECT_DOUBLE_EQ(cs.options.rtol, accuracy / 1000);
    const MethodChoice cn = choose_method(soft.model, soft.start, asking(soft, accuracy));
    EXPECT_FALSE(cn.stiff) << cn.reason;
    EXPECT_EQ(cn.options.integrator,
              options_for_accuracy(soft.model, asking(soft, accuracy)).integrator)
        << cn.reason;
    EXPECT_NE(cn.reason.find("not stiff"), std::string::npos) << cn.reason;
  }
}

// The stiff run reaches the accuracy asked for against the closed form (the full model departs
// from the reduced one by O(1/k) = 1e-8 m here), and says what it chose; dopri5 at the tolerance
// the accuracy would have given it crawls at its stability limit: more steps than the stability
// estimate, which is what the test predicts, and more evaluations than cvode_bdf (1.5x here:
// the spring mode, excited at ~1e-9 by the start, keeps BDF's steps short at rtol 1e-9 too).
TEST(MethodChoice, StiffRunMeetsTheAccuracyAndTheExplicitOneCrawls) {
  const MassSpringMass s(1e8);
  const double accuracy = 1e-6;
  const Trajectory r = forward_dynamics(s.model, s.start, asking(s, accuracy));
  EXPECT_EQ(r.stats.integrator, "cvode_bdf");
  EXPECT_NE(r.stats.method.find("accuracy 1e-06, stiff"), std::string::npos) << r.stats.method;
  EXPECT_LE(s.error(r) / s.model.scale, accuracy);
  ForwardOptions e = asking(s, 0);
  e.integrator = Integrator::dopri5;
  e.rtol = e.atol = accuracy / 1000;
  const Trajectory x = forward_dynamics(s.model, s.start, e);
  const MethodChoice c = choose_method(s.model, s.start, asking(s, accuracy));
  EXPECT_GT(static_cast<double>(x.stats.steps), c.stability_steps);
  EXPECT_GT(x.stats.rhs_evaluations, r.stats.rhs_evaluations);
  std::printf(
      "k = 1e8, accuracy 1e-6: %s\n  cvode_bdf %ld steps %ld evaluations, error %.2e m; "
      "dopri5 %ld steps %ld evaluations\n",
      r.stats.method.c_str(), r.stats.steps, r.stats.rhs_evaluations, s.error(r), x.stats.steps,
      x.stats.rhs_evaluations);
}

// The double four-bar (slow motion, singular positions) is not stiff: the explicit methods that
// step over its singular instants run, at the accuracy's calibration.
TEST(MethodChoice, DoubleFourBarIsNotStiff) {
  const Model m = build_model(mechanisms::double_fourbar());
  const State s = consistent_state(m, {.positions = {}, .velocities = {{"crank0.w", -1.0}}});
  for (double a : {1e-3, 1e-6, 1e-9}) {
    const MethodChoice c = choose_method(m, s, {.t0 = 0, .t1 = 10, .accuracy = a});
    EXPECT_FALSE(c.stiff) << c.reason;
    EXPECT_EQ(c.options.integrator, options_for_accuracy(m, {.accuracy = a}).integrator);
  }
}

// A scene that names no method asks for kDefaultAccuracy; one that names an integrator or a
// tolerance keeps it (cvode_bdf with the scene's rtol here), and an accuracy asked for wins.
TEST(MethodChoice, ScenesWithoutAMethodAskForTheDefaultAccuracy) {
  const Scene none = parse_scene(scene_text("sprung_double_pendulum"), "s.yaml");
  const Model m = build_scene_model(none);
  EXPECT_FALSE(none.run.method_set);
  EXPECT_EQ(forward_options(none, m).accuracy, kDefaultAccuracy);
  const Trajectory r = forward_dynamics(m, initial_state(none, m), forward_options(none, m));
  EXPECT_NE(r.stats.method.find("accuracy 1e-06, not stiff"), std::string::npos) << r.stats.method;
  const Scene given = parse_scene(scene_text("sprung_double_pendulum"), "s.yaml", {},
                                  std::vector<RunOverride>{{"rtol", "1e-9"}});
  EXPECT_TRUE(given.run.method_set);
  EXPECT_EQ(forward_options(given, m).accuracy, 0);
  EXPECT_EQ(forward_options(given, m).integrator, Integrator::cvode_bdf);
  const Scene asked = parse_scene(scene_text("sprung_double_pendulum"), "s.yaml", {},
                                  std::vector<RunOverride>{{"accuracy", "1e-4"}});
  EXPECT_EQ(forward_options(asked, m).accuracy, 1e-4);
  const Trajectory rb = forward_dynamics(m, initial_state(given, m), forward_options(given, m));
  EXPECT_TRUE(rb.stats.method.empty());
  EXPECT_EQ(rb.stats.integrator, "cvode_bdf");
}

// A stiff mechanism with a quasi-steady spring stays explicit (start_quasi_steady refuses
// cvode_bdf): the mass-spring-mass with its link quasi-steady (k = 1e8) and mass 1 held to the
// ground by a stiff undamped spring (k = 1e7 against the two masses, which the link makes one:
// omega = 1.8e3 /s, 36 steps for stability over 0.05 s against 4 x 3.8 for the accuracy). The
// link must stay the stiffer: with k = 1e4 its held length does not settle (the mount's force
// moves its tension faster than its own law), an error. The choice says so, and the run goes
// through with it.
TEST(MethodChoice, StiffWithQuasiSteadySpringsStaysExplicit) {
  std::string text = scene_text("mass_spring_mass");
  text.replace(text.find("reduce: constraint}"), 18, "reduce: quasi_steady");
  const std::string springs = "  springs:\n";
  text.replace(text.find(springs), springs.size(),
               springs +
                   "    mount: {body_a: ground, point_a: [-1, 0], body_b: mass1, point_b: "
                   "[0, 0], rest_length: 1, stiffness: 1e7, damping: 0}\n");
  const std::vector<ParameterOverride> set = {{"k", "1e8"}};
  const Scene scene = parse_scene(text, "mass_spring_mass.yaml", set);
  const Model m = build_scene_model(scene);
  const State s = initial_state(scene, m);
  ForwardOptions o = forward_options(scene, m);
  o.accuracy = 1e-6;
  o.t1 = 0.05;
  const MethodChoice c = choose_method(m, s, o);
  EXPECT_TRUE(c.stiff) << c.reason;
  EXPECT_NEAR(c.spectral_radius / std::sqrt(1e7 / 3.0), 1, 0.05) << c.reason;
  EXPECT_EQ(c.options.integrator, options_for_accuracy(m, o).integrator) << c.reason;
  EXPECT_NE(c.reason.find("quasi-steady springs"), std::string::npos) << c.reason;
  const Trajectory r = forward_dynamics(m, s, o);
  EXPECT_EQ(r.stats.integrator, std::string(to_string(c.options.integrator)));
}
