// Controllers (issue 12, item 4): PD feedback on a coordinate towards a reference, with an
// optional feed-forward (mo2d/control.hpp; scene key `controllers:`). Checked against the closed
// loop of a pure inertia (exactly linear: I e'' + kd e' + kp e = 0), against the exact
// feed-forward from inverse dynamics on the slider-crank (the reference is then a solution and the
// tracking error stays at the integration error), the scene against the same law built in C++,
// and the refusals of bad input at their file:line:column.
#include "mo2d/control.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"

namespace mo2d {
namespace {

// A disc (inertia I about its pivot, centre of mass on the pivot), no gravity: under the torque u
// its angle obeys I theta'' = u exactly, so PD control towards a constant r0 gives
// I e'' + kd e' + kp e = 0 for e = theta - r0.
const std::string kDisc = R"yaml(name: disc
parameters:
  I: 0.5
  kp: 8
  kd: 0.8
  r0: 1.0
ground:
  O: [0, 0]
bodies:
  disc:
    nodes: {O: [0, 0], A: [0.1, 0]}
    mass: 2
    inertia: I
    com: O
joints:
  pivot: {type: revolute, node_a: ground.O, node_b: disc.O, actuated: true}
coordinates:
  disc.angle: {rate: {disc.w: 1}}
controllers:
  pivot.torque: {coordinate: disc.angle, reference: r0, kp: kp, kd: kd}
initial:
  velocities: {disc.w: 0}
run:
  solve: forward
  duration: 5
  samples: 501
  rtol: 1e-10
  atol: 1e-12
)yaml";

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

struct SceneRun {
  Scene scene;
  Model model;
  Trajectory r;
};

SceneRun run_scene(const std::string& text) {
  SceneRun s{parse_scene(text, "control.yaml"), {}, {}};
  s.model = build_scene_model(s.scene);
  const ForwardOptions o = forward_options(s.scene, s.model);
  s.r = forward_dynamics(s.model, initial_state(s.scene, s.model), o);
  return s;
}

TEST(Controller, PdOnAPureInertiaFollowsTheClosedLoopClosedForm) {
  const SceneRun s = run_scene(kDisc);
  const double I = 0.5, kp = 8, kd = 0.8, r0 = 1.0;
  const double wn = std::sqrt(kp / I), zeta = kd / (2 * std::sqrt(kp * I));
  const double wd = wn * std::sqrt(1 - zeta * zeta), e0 = 0 - r0;  // theta(0) = 0, at rest
  const int col = s.model.coordinate("disc.angle");
  double worst = 0;
  for (Eigen::Index k = 0; k < s.r.time.size(); ++k) {
    const double t = s.r.time[k];
    const double exact =
        e0 * std::exp(-zeta * wn * t) * (std::cos(wd * t) + zeta * wn / wd * std::sin(wd * t));
    worst = std::max(worst, std::abs(s.r.q0(k, col) - r0 - exact));
  }
  std::printf("disc PD: max |e - e_exact| = %.3e rad (zeta %.2f, wn %.2f rad/s)\n", worst, zeta,
              wn);
  // rtol 1e-10 on an O(1) angle: the global error of CVODE is a small multiple of it
  EXPECT_LT(worst, 1e-8) << "max |e - e_exact| " << worst;
  // the tracking error report: the largest |e| is the initial one, the final one the decay
  const std::vector<TrackingError> te = tracking_errors(s.scene, s.model, s.r);
  ASSERT_EQ(te.size(), 1u);
  EXPECT_EQ(te[0].input, "pivot.torque");
  EXPECT_EQ(te[0].coordinate, "disc.angle");
  EXPECT_DOUBLE_EQ(te[0].max_error, -1.0);
  EXPECT_DOUBLE_EQ(te[0].t_max, 0.0);
  const double t1 = 5;
  const double e1 =
      e0 * std::exp(-zeta * wn * t1) * (std::cos(wd * t1) + zeta * wn / wd * std::sin(wd * t1));
  EXPECT_NEAR(te[0].final_error, e1, 1e-8);
  // the effort recorded is the PD law at the recorded state
  const int w = s.model.rate("disc.w");
  for (Eigen::Index k = 0; k < s.r.time.size(); k += 50)
    EXPECT_NEAR(s.r.efforts(k, 0), kp * (r0 - s.r.q0(k, col)) - kd * s.r.q1(k, w), 1e-12);
}

TEST(Controller, ExpressionFeedForwardOfTheExactTorqueTracksAMovingReference) {
  // r = sin(2t): the exact torque is I r'' = -4 I sin(2t); from r(0) = 0, r'(0) = 2 the
  // reference is the solution and the error stays at the integration error. Without the
  // feed-forward the error is the forced response of the PD loop (~0.5 rad).
  std::string text = replaced(kDisc, "reference: r0, kp: kp, kd: kd}",
                              "reference: sin(2*t), kp: kp, kd: kd, feed_forward: -4*I*sin(2*t)}");
  text = replaced(text, "{disc.w: 0}", "{disc.w: 2}");
  const SceneRun s = run_scene(text);
  const TrackingError e = tracking_errors(s.scene, s.model, s.r).at(0);
  EXPECT_LT(std::abs(e.max_error), 1e-8) << e.max_error << " at t = " << e.t_max;
  const SceneRun pd = run_scene(replaced(text, ", feed_forward: -4*I*sin(2*t)", ""));
  EXPECT_GT(std::abs(tracking_errors(pd.scene, pd.model, pd.r).at(0).max_error), 0.1);
}

// The slider-crank of mechanisms/slider_crank.yaml driven by a controller on the crank torque
// towards crank.angle = omega t, from the reference's initial state.
const std::string kSliderCrank = R"yaml(name: slider_crank
parameters:
  r: 0.1
  L: 0.35
  e: 0.03
  m_crank: 0.5
  m_rod: 0.3
  m_slider: 1.0
  omega: 4 * pi
  gravity: 9.81
  xb: r + sqrt(L^2 - e^2)
ground:
  O: [0, 0]
  R1: [0, e]
  R2: [1, e]
bodies:
  crank:
    nodes: {O: [0, 0], A: [r, 0]}
    mass: m_crank
    inertia: m_crank * r * r / 12
    com: {between: [O, A]}
  rod:
    nodes: {A: [r, 0], B: [xb, e]}
    mass: m_rod
    inertia: m_rod * L * L / 12
    com: {between: [A, B]}
  slider:
    nodes: {B: [xb, e]}
    mass: m_slider
joints:
  crank_pivot: {type: revolute, node_a: ground.O, node_b: crank.O, actuated: true}
  crank_pin:   {type: revolute, node_a: crank.A, node_b: rod.A}
  wrist_pin:   {type: revolute, node_a: rod.B, node_b: slider.B}
  rail:        {type: prismatic, axis_from: ground.R1, axis_to: ground.R2, slider: slider.B}
coordinates:
  crank.angle: {rate: {crank.w: 1}}
loads:
  gravity: [0, -gravity]
controllers:
  crank_pivot.torque: {coordinate: crank.angle, reference: omega * t, kp: 100, kd: 2, feed_forward: inverse}
initial:
  velocities: {crank.w: omega}
run:
  solve: forward
  duration: 1
  samples: 201
  rtol: RTOL
  atol: 1e-12
)yaml";

double slider_crank_error(const std::string& rtol, const std::string& from = "",
                          const std::string& to = "") {
  std::string text = replaced(kSliderCrank, "RTOL", rtol);
  if (!from.empty()) text = replaced(text, from, to);
  const SceneRun s = run_scene(text);
  return std::abs(tracking_errors(s.scene, s.model, s.r).at(0).max_error);
}

TEST(Controller, ExactFeedForwardFromInverseDynamicsTracksAtIntegrationAccuracy) {
  // the reference turns 4 pi rad in 1 s: the integration error of the angle is about rtol times
  // that, and it follows rtol; PD alone (the same gains) leaves the error the gains allow
  const double e8 = slider_crank_error("1e-8"), e10 = slider_crank_error("1e-10");
  const double pd = slider_crank_error("1e-8", ", feed_forward: inverse", "");
  const double open = slider_crank_error("1e-8", "kp: 100, kd: 2", "kp: 0, kd: 0");
  std::printf(
      "slider-crank max tracking error: ff+PD %.3e (rtol 1e-8), %.3e (rtol 1e-10); "
      "ff alone %.3e; PD alone %.3e rad\n",
      e8, e10, open, pd);
  EXPECT_LT(e8, 4 * M_PI * 1e-8 * 10);
  EXPECT_LT(e10, 4 * M_PI * 1e-10 * 10);
  EXPECT_LT(e10, e8);
  EXPECT_LT(open, 4 * M_PI * 1e-8 * 10);  // feed-forward alone: the reference is a solution
  EXPECT_GT(pd, 1e-3);
}

TEST(Controller, SceneControllerEqualsTheSameLawBuiltInCpp) {
  const SceneRun s = run_scene(replaced(kSliderCrank, "RTOL", "1e-8"));
  const mechanisms::Example ex = mechanisms::slider_crank();
  const Model model = build_model(ex.system);
  ASSERT_EQ(model.coordinate_labels, s.model.coordinate_labels);
  InverseOptions io = inverse_options(s.scene);
  PdControl pd;
  pd.coordinate = "crank.angle";
  pd.reference = [](Jet t) { return 4 * M_PI * t; };
  pd.kp = 100;
  pd.kd = 2;
  pd.feed_forward = efforts_from_inverse(model, ex.motion, io)[0];
  ForwardOptions o;
  o.t1 = 1;
  o.samples = 201;
  o.rtol = 1e-8;
  o.atol = 1e-12;
  o.efforts = EffortLaws{pd_control(pd)};
  const State x0 = consistent_state(model, {{}, {{"crank.w", 4 * M_PI}}}, 0);
  const Trajectory r = forward_dynamics(model, x0, o);
  ASSERT_EQ(r.time.size(), s.r.time.size());
  const double dq = (r.q0 - s.r.q0).cwiseAbs().maxCoeff();
  const double du = (r.efforts - s.r.efforts).cwiseAbs().maxCoeff();
  EXPECT_LT(dq, 1e-12) << dq;
  EXPECT_LT(du, 1e-9) << du;
}

TEST(Controller, PdControlRefusesNegativeOrNonFiniteGains) {
  PdControl c;
  c.coordinate = "crank.angle";
  c.kp = -1;
  EXPECT_THROW((void)pd_control(c), Error);
  c.kp = 1;
  c.kd = std::nan("");
  EXPECT_THROW((void)pd_control(c), Error);
  c.kd = 0;
  EXPECT_NO_THROW((void)pd_control(c));
  EXPECT_EQ(rate_label("crank.A.x"), "crank.A.vx");
  EXPECT_EQ(rate_label("rail.q"), "rail.v");
  EXPECT_EQ(rate_label("crank.angle"), "crank.angle.rate");
}

std::string error_of(const std::string& text) {
  try {
    const Scene s = parse_scene(text, "bad.yaml");
    const Model m = build_scene_model(s);
    (void)forward_options(s, m);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

TEST(Controller, BadControllersAreReportedAtTheirLine) {
  // kDisc: the controller is on line 20; its coordinate's value at column 30, kp's at 61
  EXPECT_EQ(error_of(replaced(kDisc, "kp: kp, kd", "kp: -1, kd")),
            "bad.yaml:20:61: controllers.pivot.torque.kp: must be >= 0");
  EXPECT_EQ(error_of(replaced(kDisc, "coordinate: disc.angle", "coordinate: disc.angel")),
            "bad.yaml:20:30: unknown coordinate 'disc.angel' (did you mean 'disc.angle'?)");
  EXPECT_EQ(error_of(replaced(kDisc, "controllers:", "efforts:\n  pivot.torque: 1\ncontrollers:")),
            "bad.yaml:22:3: controllers.pivot.torque: input 'pivot.torque' has an effort too "
            "(give its open-loop part as feed_forward)");
  EXPECT_EQ(
      error_of(replaced(kDisc, "controllers:\n  pivot.torque", "controllers:\n  pivot.force")),
      "bad.yaml:20:3: unknown input 'pivot.force' (did you mean 'pivot.torque'?)");
  const std::string no_ref = error_of(replaced(kDisc, "reference: r0, ", ""));
  EXPECT_NE(no_ref.find("bad.yaml:20:"), std::string::npos) << no_ref;
  EXPECT_NE(no_ref.find("reference"), std::string::npos) << no_ref;
  const std::string state_ref = error_of(replaced(kDisc, "reference: r0", "reference: disc.w"));
  std::printf("%s\n%s\n", no_ref.c_str(), state_ref.c_str());
  EXPECT_NE(state_ref.find("bad.yaml:20:"), std::string::npos) << state_ref;
}

}  // namespace
}  // namespace mo2d
