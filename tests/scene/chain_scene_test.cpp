// Chains from scene files: the shipped example loads and runs (the chain pulls the wheel and the
// arm, its energy balances), and bad input is reported at its line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "mo2d/dynamics.hpp"
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
  expect(chain_error("radius_a: 0.04", "radius_a: 0"), "bad.yaml:17:49",
         "chain 'ch'.radius_a: must be > 0");
  expect(chain_error("body_b: b", "body_b: bb"), "bad.yaml:17:63",
         "chain 'ch'.body_b: undefined body 'bb'");
  expect(chain_error("stiffness: 1e4", "stiffness: 1e4, fidelity: rigid"), "bad.yaml:18:36",
         "'rigid' is not one of unilateral, bilateral");
  expect(chain_error("radius_b: 0.1", "radius_b: 0.5"), "bad.yaml:17:5",
         "the pitch circles overlap");
  expect(chain_error("stiffness: 1e4", "stifness: 1e4"), "bad.yaml:18:10", "stifness");
  // inextensible (docs/reduction.md): no stiffness needed; a misspelt name gets the suggestion
  EXPECT_EQ(chain_error("stiffness: 1e4", "fidelity: inextensible"), "");
  expect(chain_error("stiffness: 1e4", "stiffness: 1e4, fidelity: inextensibel"), "bad.yaml:18:36",
         "'inextensibel' is not one of unilateral, bilateral, inextensible");
  expect(chain_error("stiffness: 1e4", "stiffness: 1e4, fidelity: inextensibel"), "bad.yaml:18:36",
         "did you mean 'inextensible'");
  expect(chain_error("stiffness: 1e4", "stiffness: 0, fidelity: inextensible"), "bad.yaml:18:21",
         "chain 'ch'.stiffness: must be > 0");
  expect(chain_error("stiffness: 1e4", "fidelity: inextensible, rest_lower: -1"), "bad.yaml:18:46",
         "chain 'ch'.rest_lower: must be > 0");
}

// The inextensible chain from a scene: the tension is the reaction column, the warnings name the
// start mode; the loads' outputs have the lengths only.
TEST(ChainScene, InextensibleChainRunsFromAScene) {
  std::string s = kChainBase;
  s.replace(s.find("stiffness: 1e4"), 14, "fidelity: inextensible");
  s.replace(s.find("loads:"), 6,
            "  pb: {type: revolute, node_a: ground.B, node_b: b.C}\nloads:\n  torques:\n"
            "    drive: {body: a, torque: 1}");
  s.replace(s.find("  O: [0, 0]"), 11, "  O: [0, 0]\n  B: [0.5, 0]");
  s += "initial:\n  velocities: {a.w: 0}\noutputs:\n  loads: true\nrun:\n  duration: 0.2\n";
  const Scene scene = parse_scene(s, "inext.yaml", {});
  const Model m = build_scene_model(scene);
  Trajectory r = forward_dynamics(m, initial_state(scene, m), forward_options(scene, m));
  add_output_columns(m, r, scene.outputs);
  const Eigen::Index last = r.time.size() - 1;
  // a counter-clockwise torque on a: the upper span pulls
  EXPECT_GT(r.reactions(last, r.reaction("ch.upper.tension")), 0);
  EXPECT_EQ(r.reactions(last, r.reaction("ch.lower.tension")), 0);
  EXPECT_NEAR(r.outputs(last, r.output("ch.upper.length")), m.chains[0].rest_upper, 1e-9);
  EXPECT_THROW(r.output("ch.upper.tension"), Error);
  EXPECT_FALSE(r.stats.warnings.empty());
}

// The drift of the inextensible chain over a 100 s run: the half-bike's scenario 1 (engine ramp,
// coasting, brake step at 10 s, then braked to the end) with `fidelity: inextensible`, the
// scene's 1 mm of slack: the lower span pulls, the upper while coasting, slack between, each
// engagement an impact. Reported: max |l - rest| of the taut span, and the largest stretch
// l - rest of any span (> 0 would be a span longer than the chain), over the 100 s.
TEST(ChainScene, InextensibleHalfBikeDriftOver100s) {
  std::ifstream in(chain_scene_path("half_bike"));
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  const size_t at = yaml.find("fidelity: unilateral");
  ASSERT_NE(at, std::string::npos);
  yaml.replace(at, 20, "fidelity: inextensible");
  // the chain's row takes one degree of freedom: the wheel's rate follows the shaft's
  const std::string v = "velocities: {shaft.w: 0, arm.w: 0, wheel.w: 0}";
  ASSERT_NE(yaml.find(v), std::string::npos);
  yaml.replace(yaml.find(v), v.size(), "velocities: {shaft.w: 0, arm.w: 0}");
  const std::vector<RunOverride> run = {{"duration", "100"}, {"samples", "10001"}};
  const Scene scene = parse_scene(yaml, "half_bike_inextensible.yaml", {}, run);
  const Model m = build_scene_model(scene);
  const Trajectory r = forward_dynamics(m, initial_state(scene, m), forward_options(scene, m));
  const ChainLoad& c = m.chains.at(0);
  const int Tu = r.reaction("chain.upper.tension"), Tl = r.reaction("chain.lower.tension");
  double drift = 0, stretch = -1e9;
  int taut = 0;
  // A span is taut where its row is in the model: its tension is not exactly 0 (a slack span has
  // none) and not pushing beyond round-off. From ~45 s the braked bike is at rest and the taut
  // span's tension is 0 to round-off (|T| ~ 1e-13 N, either sign, of a largest ~1e2 N).
  const double T_max = std::max(r.reactions.col(Tu).cwiseAbs().maxCoeff(),
                                r.reactions.col(Tl).cwiseAbs().maxCoeff());
  auto is_taut = [&](double T) { return T != 0 && T > -1e-9 * T_max; };
  for (Eigen::Index i = 0; i < r.time.size(); ++i) {
    const ChainValue v =
        chain_value(m, c, r.q0.row(i).transpose(), r.q1.row(i).transpose(), r.time[i]);
    const double eu = v.upper_length - c.rest_upper, el = v.lower_length - c.rest_lower;
    if (is_taut(r.reactions(i, Tu))) drift = std::max(drift, std::abs(eu)), ++taut;
    if (is_taut(r.reactions(i, Tl))) drift = std::max(drift, std::abs(el)), ++taut;
    stretch = std::max({stretch, eu, el});
  }
  int switches = 0;
  for (const std::string& w : r.stats.warnings)
    if (w.find("chain 'chain'") != std::string::npos) ++switches, std::printf("  %s\n", w.c_str());
  std::printf(
      "half-bike, inextensible chain, 100 s (%s, rtol %g): %d chain events, %d of %d samples "
      "taut; max |l - rest| of the taut span %.3e m, largest stretch %.3e m; max_drift %.3e; "
      "energy balance error %.3e J; %.2f s CPU\n",
      to_string(forward_options(scene, m).integrator), forward_options(scene, m).rtol, switches,
      taut, static_cast<int>(r.time.size()), drift, stretch, r.stats.max_drift,
      energy_balance_error(r), r.stats.cpu_seconds);
  EXPECT_EQ(r.time.size(), 10001);
  EXPECT_GT(taut, 9000);
  EXPECT_GT(switches, 2);  // start, and at least one switch of span
  EXPECT_LT(drift, 1e-9);
  EXPECT_LT(stretch, 1e-9);
}

// The chain four-bar (mechanisms/chain_fourbar.yaml) with an inextensible chain on its fixed
// centres: the load reverses twice per crank turn, 45 direct handovers in 3 s. At BDF rtol 1e-4,
// atol 1e-6 the switching's thresholds are the run's accuracy (src/forward/chain_switching.cpp);
// with thresholds of 1e-9 the run chattered ("more than 10000 span switches"). Against a tight
// reference (rtol 1e-9): the same handovers, no slack, and the crank's speed within 30 rtol of
// its largest value (measured 1e-3, 10 rtol: the global error of BDF over the 45 restarts).
std::string chain_fourbar_inextensible() {
  std::ifstream in(chain_scene_path("chain_fourbar"));
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  const std::string f = "fidelity: unilateral}", v = "velocities: {motor.w: 0, crank.w: 0}";
  if (yaml.find(f) == std::string::npos || yaml.find(v) == std::string::npos) return "";
  yaml.replace(yaml.find(f), f.size(), "fidelity: inextensible}");
  yaml.replace(yaml.find(v), v.size(), "velocities: {motor.w: 0}");  // the chain's row: 1 DOF
  return yaml;
}

Trajectory run_chain_fourbar(const std::string& yaml, const std::string& rtol,
                             const std::string& atol) {
  const std::vector<RunOverride> run = {
      {"integrator", "cvode_bdf"}, {"rtol", rtol}, {"atol", atol}};
  const Scene scene = parse_scene(yaml, "chain_fourbar_inextensible.yaml", {}, run);
  const Model m = build_scene_model(scene);
  return forward_dynamics(m, initial_state(scene, m), forward_options(scene, m));
}

int handovers(const Trajectory& r) {  // from the closing line; -1 if the chain went slack
  int n = 0;
  for (const std::string& w : r.stats.warnings) {
    if (w.find("slack from") != std::string::npos) return -1;
    const size_t at = w.find("direct handovers");
    if (at != std::string::npos) n = std::stoi(w.substr(w.rfind(": ", at) + 2));
  }
  return n;
}

TEST(ChainScene, InextensibleChainFourBarAtALooseBdfTolerance) {
  const std::string yaml = chain_fourbar_inextensible();
  ASSERT_FALSE(yaml.empty());
  const Trajectory ref = run_chain_fourbar(yaml, "1e-9", "1e-11");
  const Trajectory r = run_chain_fourbar(yaml, "1e-4", "1e-6");
  ASSERT_EQ(r.time.size(), ref.time.size());
  const int w = r.rate_column("crank.w");
  const double dw = (r.q1.col(w) - ref.q1.col(w)).lpNorm<Eigen::Infinity>();
  const double w_max = ref.q1.col(w).lpNorm<Eigen::Infinity>();
  std::printf(
      "chain four-bar, inextensible: %d handovers at rtol 1e-4 (%zu warnings), %d at 1e-9; max "
      "|crank.w - reference| %.3e rad/s of %.2f (%.1f rtol); CPU %.3f s and %.3f s\n",
      handovers(r), r.stats.warnings.size(), handovers(ref), dw, w_max, dw / w_max / 1e-4,
      r.stats.cpu_seconds, ref.stats.cpu_seconds);
  EXPECT_GT(handovers(ref), 40);  // twice per crank turn
  EXPECT_LE(std::abs(handovers(r) - handovers(ref)), 2);
  EXPECT_LE(r.stats.warnings.size(), 3u);  // the start and the handovers' line
  EXPECT_LT(dw, 30 * 1e-4 * w_max);
}

}  // namespace
}  // namespace mo2d
