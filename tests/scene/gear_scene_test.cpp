// Gears and racks from scene files: the shipped examples against closed forms, and bad input at
// its line.
#include <gtest/gtest.h>

#include <cmath>

#include "mo2d/forward.hpp"
#include "mo2d/scene.hpp"

namespace mo2d {
namespace {

std::string scene_path(const std::string& name) {
  return std::string(MO2D_MECHANISMS_DIR) + "/" + name + ".yaml";
}

// mechanisms/rack_pinion.yaml: x = slide.q - 1 oscillates about x_e = -T / (r k) with
// omega = sqrt(k / (m + I / r^2)), from rest at x = 0: x = x_e (1 - cos(omega t)).
TEST(GearScene, RackPinionOscillatesWithTheReflectedInertia) {
  const Scene scene = load_scene(scene_path("rack_pinion"));
  const Model m = build_scene_model(scene);
  ForwardOptions o = forward_options(scene, m);
  o.rtol = 1e-11;
  o.atol = 1e-13;
  const Trajectory r = forward_dynamics(m, initial_state(scene, m), o);
  const double rr = 0.05, mass = 3, I = 0.01, k = 200, T = 0.5;
  const double xe = -T / (rr * k), w = std::sqrt(k / (mass + I / (rr * rr)));
  for (int i = 0; i < r.time.size(); i += 10) {
    const double t = r.time[i];
    EXPECT_NEAR(r.q0(i, r.column("slide.q")) - 1, xe * (1 - std::cos(w * t)), 1e-7) << t;
    // the teeth push the rack: m x'' = F - k x
    const double x = xe * (1 - std::cos(w * t)), xdd = xe * w * w * std::cos(w * t);
    EXPECT_NEAR(r.reactions(i, r.reaction("teeth.force")), mass * xdd + k * x, 1e-5) << t;
  }
  EXPECT_LT(energy_balance_error(r), 1e-8);
}

// mechanisms/gear_train.yaml: the train's kinematics and the carrier torques of each pair.
TEST(GearScene, GearTrainRatiosAndCarrierTorques) {
  const Scene scene = load_scene(scene_path("gear_train"));
  const Model m = build_scene_model(scene);
  EXPECT_EQ(m.dof, 2);
  ForwardOptions o = forward_options(scene, m);
  o.t1 = 0.5;
  o.samples = 6;
  const Trajectory r = forward_dynamics(m, initial_state(scene, m), o);
  for (int i = 0; i < r.time.size(); ++i) {
    const double wc = r.q1(i, r.rate_column("case.w"));
    const double win = r.q1(i, r.rate_column("input.w")) - wc;
    const double wid = r.q1(i, r.rate_column("idler.w")) - wc;
    const double wout = r.q1(i, r.rate_column("output.w")) - wc;
    EXPECT_NEAR(wid, -0.4 * win, 1e-9);
    EXPECT_NEAR(wout, 0.8 * win, 1e-9);
    EXPECT_NEAR(r.reactions(i, r.reaction("first.carrier_torque")),
                -1.4 * r.reactions(i, r.reaction("first.torque")), 1e-9);
    EXPECT_NEAR(r.reactions(i, r.reaction("second.carrier_torque")),
                -3.0 * r.reactions(i, r.reaction("second.torque")), 1e-9);
    // the output's only torque is the mesh's: I_out times its acceleration
    EXPECT_NEAR(r.reactions(i, r.reaction("second.torque")),
                0.08 * r.a1(i, r.rate_column("output.w")), 1e-6);
  }
  EXPECT_GT(std::abs(r.q1(5, r.rate_column("input.w"))), 2.0);  // the train turns
  EXPECT_LT(energy_balance_error(r), 1e-8);
}

std::string error_of(const std::string& text) {
  try {
    build_scene_model(parse_scene(text, "bad.yaml"));
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

const std::string kPair = R"yaml(name: pair
ground: {O1: [0, 0], O2: [1, 0]}
bodies:
  a: {nodes: {C: [0, 0], R: [0.1, 0]}, mass: 1, inertia: 0.1}
  b: {nodes: {C: [1, 0], R: [1.1, 0]}, mass: 1, inertia: 0.1}
joints:
  p1: {type: revolute, node_a: ground.O1, node_b: a.C}
  p2: {type: revolute, node_a: ground.O2, node_b: b.C}
gears:
  mesh: {body: b, driver: a, ratio: RATIO}
)yaml";

std::string pair(const std::string& ratio, const std::string& extra = "") {
  std::string s = kPair;
  s.replace(s.find("RATIO"), 5, ratio);
  const size_t at = s.find("ratio:");
  if (!extra.empty()) s.insert(at, extra + ", ");
  return s;
}

TEST(GearScene, BadInputAtItsLine) {
  EXPECT_EQ(error_of(pair("-2")), "");
  EXPECT_NE(error_of(pair("0")).find("bad.yaml:10:"), std::string::npos) << error_of(pair("0"));
  EXPECT_NE(error_of(pair("0")).find("non-zero"), std::string::npos);
  const std::string e = error_of(pair("2", "carrier: bb"));
  EXPECT_NE(e.find("bad.yaml:10:"), std::string::npos) << e;
  EXPECT_NE(e.find("undefined body 'bb'"), std::string::npos) << e;
  const std::string k = error_of(pair("2", "teeth: 3"));
  EXPECT_NE(k.find("teeth"), std::string::npos) << k;
  EXPECT_NE(error_of(pair("2", "carrier: a")).find("three different bodies"), std::string::npos)
      << error_of(pair("2", "carrier: a"));
}

}  // namespace
}  // namespace mo2d
