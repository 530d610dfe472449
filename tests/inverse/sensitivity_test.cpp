// Exact sensitivities of inverse dynamics (mo2d/sensitivity.hpp, issue 36 item 2): against closed
// forms (a driven pendulum), central finite differences of whole runs (the scene read again with
// the parameter moved, as --set does), summary values, a metamorphic relation (all masses scaled
// by s: d efforts / ds = efforts) and the refusals (geometry, motion, nonlinear dependence).
#include "mo2d/sensitivity.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"
#include "mo2d/scene_sensitivity.hpp"

namespace mo2d {
namespace {

// A pendulum: link O-P of length l, mass m at P, centroidal inertia I; theta from +x.
// tau = (I + m l^2) theta'' + m g l cos(theta).
const char* kPendulum = R"(name: pendulum
parameters:
  l: 0.8
  m: 1.5
  I: 0.05
  g: 9.81
ground: {O: [0, 0]}
bodies:
  link:
    nodes: {O: [0, 0], P: [l, 0]}
    mass: m
    inertia: I
    com: P
joints:
  pivot: {type: revolute, node_a: ground.O, node_b: link.O, actuated: true}
coordinates:
  link.angle: {rate: {link.w: 1}}
loads:
  gravity: [0, -g]
motion:
  link.angle: 0.5 * sin(3 * t) + t^2
run: {solve: inverse, duration: 1, samples: 41}
)";

// A four-bar with a spring, a damper, a constant force and a torque; every load and mass data
// term depends on a parameter, s scales every mass and inertia, gc moves the coupler's centre of
// mass (a quadratic dependence), L2 is the coupler's length (geometry), w the crank speed.
const char* kFourbar = R"(name: fourbar
parameters:
  s: 1
  m2: 0.5
  gc: 0.4
  k: 120
  c: 1.5
  F: 3
  T: 0.2
  g: 9.81
  L2: 0.35
  w: 2 * pi
  sq: 4
ground:
  A0: [0, 0]
  B0: [0.4, 0]
bodies:
  crank:
    nodes: {O: [0, 0], A: [0, 0.1]}
    mass: 0.2 * s
    inertia: 0.2 * s * 0.01 / 12
    com: {between: [O, A], gamma: 0.5}
  coupler:
    nodes: {A: [0, 0.1], B: [0.1 + 0.25 * L2 / 0.35, 0.3]}
    mass: m2 * s
    inertia: m2 * s * 0.1225 / 12
    com: {between: [A, B], gamma: gc}
  rocker:
    nodes: {O: [0.4, 0], B: [0.1 + 0.25 * L2 / 0.35, 0.3]}
    mass: 0.4 * s
    inertia: 0.4 * s * 0.09 / 12
    com: {between: [O, B], gamma: 0.5}
joints:
  crank_pivot:  {type: revolute, node_a: ground.A0, node_b: crank.O, actuated: true}
  crank_pin:    {type: revolute, node_a: crank.A, node_b: coupler.A}
  rocker_pin:   {type: revolute, node_a: coupler.B, node_b: rocker.B}
  rocker_pivot: {type: revolute, node_a: ground.B0, node_b: rocker.O}
coordinates:
  crank.angle: {rate: {crank.w: 1}}
loads:
  gravity: [0, -g]
  forces:
    push: {body: coupler, point: [0.2, 0.2], fx: F + 0 * exp(sq), fy: -0.5 * F}
  torques:
    brake: {body: rocker, torque: -T * rocker.w}
  springs:
    tether: {body_a: ground, point_a: [0.2, 0.5], body_b: coupler, point_b: [0.2, 0.2],
             rest_length: 0.1, stiffness: k, damping: c}
motion:
  crank.angle: pi/2 + w * t
run: {solve: inverse, duration: 0.5, samples: 51}
)";

struct SensRun {
  Scene scene;
  Model model;
  Trajectory r;
  InverseSensitivity d;
};

SensRun run_with(const std::string& text, const std::vector<std::string>& names,
                 const std::vector<ParameterOverride>& set = {}) {
  SensRun out;
  out.scene = parse_scene(text, "test.yaml", set);
  out.model = build_scene_model(out.scene);
  const InverseOptions o = inverse_options(out.scene);
  const std::vector<ParameterModels> p =
      scene_parameter_models(text, out.scene, set, {}, names, out.model, {}, o);
  out.d = inverse_dynamics_sensitivity(out.model, out.scene.motion, o, p, out.r);
  return out;
}

Trajectory plain_run(const std::string& text, const std::vector<ParameterOverride>& set) {
  const Scene s = parse_scene(text, "test.yaml", set);
  const Model m = build_scene_model(s);
  return inverse_dynamics(m, s.motion, inverse_options(s));
}

std::string number(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

TEST(InverseSensitivity, PendulumClosedForms) {
  const SensRun run = run_with(kPendulum, {"m", "I", "g"});
  const double l = 0.8, m = 1.5, I = 0.05, g = 9.81;
  const Trajectory& r = run.r;
  ASSERT_EQ(run.d.parameters.size(), 3u);
  for (Eigen::Index k = 0; k < r.time.size(); ++k) {
    const double t = r.time[k];
    const double th = 0.5 * std::sin(3 * t) + t * t, thdd = -4.5 * std::sin(3 * t) + 2;
    // the run itself against the closed form, then its derivatives
    EXPECT_NEAR(r.efforts(k, 0), (I + m * l * l) * thdd + m * g * l * std::cos(th), 1e-11);
    EXPECT_NEAR(run.d.efforts[0](k, 0), l * l * thdd + g * l * std::cos(th), 1e-11) << t;
    EXPECT_NEAR(run.d.efforts[1](k, 0), thdd, 1e-11) << t;
    EXPECT_NEAR(run.d.efforts[2](k, 0), m * l * std::cos(th), 1e-11) << t;
  }
}

// Central finite differences of whole runs (the scene read with the parameter at p +- h, as
// --set does) against the exact derivatives, for every effort and reaction column. The
// dependence on these parameters is a polynomial of degree <= 2, for which the central
// difference has no truncation error: the step only trades rounding (eps |column| / h), so
// h = 1e-2 |p| keeps it near 1e-13 of the columns; the check is 1e-7 (issue 36's target).
TEST(InverseSensitivity, FourbarAgainstCentralDifferences) {
  const std::vector<std::string> names{"m2", "gc", "k", "c", "F", "T", "g"};
  const SensRun run = run_with(kFourbar, names);
  for (std::size_t j = 0; j < names.size(); ++j) {
    double p = 0;
    for (const auto& q : run.scene.parameters)
      if (q.first == names[j]) p = q.second;
    const double h = 1e-2 * std::abs(p);
    const Trajectory up = plain_run(kFourbar, {{names[j], number(p + h)}});
    const Trajectory dn = plain_run(kFourbar, {{names[j], number(p - h)}});
    const Eigen::MatrixXd de = (up.efforts - dn.efforts) / (2 * h);
    const Eigen::MatrixXd dr = (up.reactions - dn.reactions) / (2 * h);
    const double se = std::max(de.cwiseAbs().maxCoeff(), 1e-300);
    const double sr = std::max(dr.cwiseAbs().maxCoeff(), 1e-300);
    EXPECT_LT((run.d.efforts[j] - de).cwiseAbs().maxCoeff(), 1e-7 * se) << names[j];
    EXPECT_LT((run.d.reactions[j] - dr).cwiseAbs().maxCoeff(), 1e-7 * sr) << names[j];
    EXPECT_GT(se, 0) << names[j];
  }
}

// Peak, RMS, mean and peak-to-peak of the crank torque and of a reaction against central
// differences of the same summary values of whole runs. The RMS is not a polynomial in p (a
// square root): its central difference has a truncation error ~ h^2 rms''' / 6, 2e-7 relative at
// h = 1e-2 p, so the step here is h = 1e-3 p (truncation ~ 2e-9, rounding ~ 1e-13 / 1e-3).
TEST(InverseSensitivity, SummaryValuesAgainstCentralDifferences) {
  const SensRun run = run_with(kFourbar, {"m2", "k"});
  const double values[] = {0.5, 120};
  const int col = run.model.n_reactions() - 1;
  for (int j = 0; j < 2; ++j) {
    const double p = values[j], h = 1e-3 * p;
    const std::string name = run.d.parameters[j];
    const Trajectory up = plain_run(kFourbar, {{name, number(p + h)}});
    const Trajectory dn = plain_run(kFourbar, {{name, number(p - h)}});
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(up.time.size());
    for (int which = 0; which < 2; ++which) {
      auto column = [&](const Trajectory& r) -> Eigen::VectorXd {
        return which == 0 ? Eigen::VectorXd(r.efforts.col(0))
                          : Eigen::VectorXd(r.reactions.col(col));
      };
      const Eigen::VectorXd dx = which == 0 ? Eigen::VectorXd(run.d.efforts[j].col(0))
                                            : Eigen::VectorXd(run.d.reactions[j].col(col));
      const SummaryDerivative s = summary_derivative(run.r.time, column(run.r), dx);
      const SummaryDerivative a = summary_derivative(up.time, column(up), zero);
      const SummaryDerivative b = summary_derivative(dn.time, column(dn), zero);
      auto fd = [&](double SummaryDerivative::*v) { return (a.*v - b.*v) / (2 * h); };
      const double tol = 1e-7 * std::max(std::abs(fd(&SummaryDerivative::peak)), 1e-3);
      EXPECT_NEAR(s.d_peak, fd(&SummaryDerivative::peak), tol) << name << which;
      EXPECT_NEAR(s.d_rms, fd(&SummaryDerivative::rms), tol) << name << which;
      EXPECT_NEAR(s.d_mean, fd(&SummaryDerivative::mean), tol) << name << which;
      EXPECT_NEAR(s.d_peak_to_peak, fd(&SummaryDerivative::peak_to_peak), tol) << name << which;
      EXPECT_NEAR(s.rms, (a.rms + b.rms) / 2, 1e-3 * s.rms);
    }
  }
}

// Scaling every mass and inertia by s, with gravity the only load besides those set to zero:
// the efforts and reactions scale by s, so at s = 1 their derivative to s is themselves.
TEST(InverseSensitivity, MassScaleGivesTheEffortsThemselves) {
  const std::vector<ParameterOverride> set{{"k", "0"}, {"c", "0"}, {"F", "0"}, {"T", "0"}};
  const SensRun run = run_with(kFourbar, {"s"}, set);
  const double se = run.r.efforts.cwiseAbs().maxCoeff();
  const double sr = run.r.reactions.cwiseAbs().maxCoeff();
  EXPECT_LT((run.d.efforts[0] - run.r.efforts).cwiseAbs().maxCoeff(), 1e-12 * se);
  EXPECT_LT((run.d.reactions[0] - run.r.reactions).cwiseAbs().maxCoeff(), 1e-12 * sr);
}

std::string refusal(const std::string& text, const std::string& name) {
  try {
    run_with(text, {name});
  } catch (const Error& e) {
    EXPECT_EQ(e.element(), name);
    return e.what();
  }
  return "no error";
}

TEST(InverseSensitivity, RefusesGeometryMotionAndNonlinearParameters) {
  const std::string geometry = refusal(kFourbar, "L2");
  EXPECT_NE(geometry.find("sensitivity to 'L2': it changes the geometry (body 'coupler' node "
                          "'coupler.B')"),
            std::string::npos)
      << geometry;
  EXPECT_NE(geometry.find("not supported"), std::string::npos) << geometry;
  const std::string motion = refusal(kFourbar, "w");
  EXPECT_NE(motion.find("sensitivity to 'w': it changes the prescribed motion of 'crank.angle'"),
            std::string::npos)
      << motion;
  const std::string none = refusal(kFourbar, "sq");  // 0 * exp(sq): exactly no dependence
  EXPECT_EQ(none, "no error");
  std::string text = kFourbar;
  text.replace(text.find("0 * exp(sq)"), 11, "0.1 * exp(sq)");
  const std::string root = refusal(text, "sq");
  EXPECT_NE(root.find("sensitivity to 'sq': the forces on body 'coupler' at t = 0 s are not a "
                      "polynomial of degree <= 2"),
            std::string::npos)
      << root;
  const std::string unknown = refusal(kFourbar, "m3");
  EXPECT_NE(unknown.find("not a parameter"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("did you mean 'm2'"), std::string::npos) << unknown;
}

}  // namespace
}  // namespace mo2d
