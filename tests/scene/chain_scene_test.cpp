// Chains from scene files: the shipped example loads and runs (the chain pulls the wheel and the
// arm, its energy balances), and bad input is reported at its line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "mo2d/forward.hpp"
#include "mo2d/output_columns.hpp"
#include "mo2d/scene.hpp"

namespace mo2d {
namespace {

std::string chain_scene_path(const std::string& name) {
  return std::string(MO2D_MECHANISMS_DIR) + "/" + name + ".yaml";
}

// mechanisms/chain_drive.yaml: after the engine's ramp the upper span carries the drive (its
// tension times r_b drives the wheel against the road load and inertia), the lower is slack.
TEST(ChainScene, ChainDriveRunsAndTheUpperSpanPulls) {
  const Scene scene = load_scene(chain_scene_path("chain_drive"));
  const Model m = build_scene_model(scene);
  EXPECT_EQ(m.dof, 3);
  Trajectory r = forward_dynamics(m, initial_state(scene, m), forward_options(scene, m));
  add_output_columns(m, r, scene.outputs);
  const Eigen::Index last = r.time.size() - 1;
  const double Tu = r.outputs(last, r.output("chain.upper.tension"));
  const double Tl = r.outputs(last, r.output("chain.lower.tension"));
  std::printf(
      "chain_drive at t = %.1f s: upper %.1f N, lower %.1f N, wheel %.2f rad/s, arm %.4f "
      "rad/s; energy balance error %.2e J\n",
      r.time[last], Tu, Tl, r.q1(last, r.rate_column("wheel.w")),
      r.q1(last, r.rate_column("arm.w")), energy_balance_error(r));
  EXPECT_GT(Tu, 100);  // about T_eng / r_a = 500 N less the drive sprocket's inertia
  EXPECT_LT(Tu, 600);
  EXPECT_EQ(Tl, 0);
  EXPECT_GT(r.q1(last, r.rate_column("wheel.w")), 1);  // driven forward (counter-clockwise)
  EXPECT_LT(energy_balance_error(r), 1e-3);
}

const std::string kChainBase = R"yaml(name: c
ground:
  O: [0, 0]
bodies:
  a:
    nodes: {C: [0, 0], R: [0.1, 0]}
    mass: 1
    inertia: 0.01
  b:
    nodes: {C: [0.5, 0], R: [0.6, 0]}
    mass: 1
    inertia: 0.01
joints:
  pa: {type: revolute, node_a: ground.O, node_b: a.C}
loads:
  chains:
    ch: {body_a: a, centre_a: [0, 0], radius_a: 0.04, body_b: b, centre_b: [0.5, 0], radius_b: 0.1,
         stiffness: 1e4}
)yaml";

std::string chain_error(const std::string& from, const std::string& to) {
  std::string s = kChainBase;
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  try {
    build_scene_model(parse_scene(s, "bad.yaml", {}));
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

TEST(ChainScene, BadInputAtItsLine) {
  EXPECT_EQ(chain_error("stiffness: 1e4", "stiffness: 1e4"), "");
  auto expect = [](const std::string& e, const std::string& where, const std::string& what) {
    EXPECT_EQ(e.rfind(where + ": ", 0), 0u) << "expected at " << where << ", got: " << e;
    EXPECT_NE(e.find(what), std::string::npos) << "expected '" << what << "' in: " << e;
  };
  expect(chain_error("radius_a: 0.04", "radius_a: 0"), "bad.yaml:18:64",
         "chain 'ch'.radius_a: must be > 0");
  expect(chain_error("body_b: b", "body_b: bb"), "bad.yaml:18:85",
         "chain 'ch'.body_b: undefined body 'bb'");
  expect(chain_error("stiffness: 1e4", "stiffness: 1e4, fidelity: rigid"), "bad.yaml:19:37",
         "'rigid' is not one of unilateral, bilateral");
  expect(chain_error("radius_b: 0.1", "radius_b: 0.5"), "bad.yaml:18:5",
         "the pitch circles overlap");
  expect(chain_error("stiffness: 1e4", "stifness: 1e4"), "bad.yaml:18:9", "stifness");
}

}  // namespace
}  // namespace mo2d
