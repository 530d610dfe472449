// Run settings from the command line (RunOverride, mo2d/scene.hpp): applied on top of the scene's
// run: block with the same checks, refusals reported at the flag that gave them.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "mo2d/scene.hpp"

namespace mo2d {
namespace {

const std::string kScene = R"yaml(name: p
parameters:
  T: 2.0
ground:
  O: [0, 0]
bodies:
  link:
    nodes: {O: [0, 0], P: [1, 0]}
    mass: 1
    inertia: 0.1
joints:
  pivot: {type: revolute, node_a: ground.O, node_b: link.O, actuated: true}
coordinates:
  link.angle: {rate: {link.w: 1}}
loads:
  gravity: [0, -9.81]
motion:
  link.angle: sin(t)
initial:
  velocities: {link.w: 0}
run:
  duration: 3
  samples: 31
  integrator: rk4
  step: 0.01
)yaml";

Scene with(std::vector<RunOverride> run) {
  return parse_scene(kScene, "p.yaml", {}, run);
}

std::string error_of(std::vector<RunOverride> run) {
  try {
    with(std::move(run));
  } catch (const SceneError& e) {
    return e.what();
  }
  return "no error";
}

TEST(RunOverride, ReplacesTheScenesSettings) {
  const Scene s = with({{"duration", "2 * T"},
                        {"samples", "5"},
                        {"integrator", "dopri5"},
                        {"rtol", "1e-6"},
                        {"max_steps", "100"}});
  EXPECT_EQ(s.run.duration, 4.0);  // an expression of the parameters
  EXPECT_EQ(s.run.samples, 5);
  EXPECT_EQ(s.run.integrator, Integrator::dopri5);
  EXPECT_EQ(s.run.rtol, 1e-6);
  EXPECT_EQ(s.run.max_steps, 100);
  EXPECT_EQ(s.run.step, 0.01);  // not overridden: the scene's
  const Scene plain = with({});
  EXPECT_EQ(plain.run.duration, 3.0);
  EXPECT_EQ(plain.run.integrator, Integrator::rk4);
}

TEST(RunOverride, BadValuesAreRefusedAtTheFlag) {
  EXPECT_EQ(error_of({{"duration", "-1"}}), "--duration: run.duration: must be > 0 s");
  EXPECT_EQ(error_of({{"samples", "1"}}), "--samples: run.samples: must be >= 2");
  EXPECT_EQ(error_of({{"samples", "2.5"}}), "--samples: run.samples: expected an integer");
  EXPECT_EQ(error_of({{"max_steps", "0"}}), "--max-steps: run.max_steps: must be >= 1");
  EXPECT_EQ(error_of({{"rtol", "0"}}), "--rtol: run.rtol: must be > 0");
  EXPECT_EQ(error_of({{"integrator", "rk5"}}),
            "--integrator: run.integrator: unknown value 'rk5' (did you mean 'rk4'?); expected "
            "one of: cvode_bdf, cvode_adams, rk4, dopri5, erk6, erk8, baumgarte");
  EXPECT_NE(error_of({{"duration", "2 * TT"}})
                .find("--duration: run.duration: in expression "
                      "'2 * TT': undefined name 'TT'"),
            std::string::npos)
      << error_of({{"duration", "2 * TT"}});
  EXPECT_EQ(error_of({{"solve", "forward"}}).substr(0, 9), "--solve: ");
  EXPECT_NE(error_of({{"duratoin", "1"}}).find("did you mean 'duration'"), std::string::npos);
}

TEST(RunOverride, LaterChecksNameTheFlag) {
  // a fixed step that needs more steps than the budget: refused by check_scene_options, at the
  // flag that set it rather than at the scene's run.step line
  const Scene s = with({{"step", "1e-9"}});
  const Model m = build_scene_model(s);
  try {
    check_scene_options(s, m, forward_options(s, m));
    FAIL() << "expected a SceneError";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.where().file, "--step") << e.what();
    EXPECT_EQ(e.where().line, 0);
  }
  const Scene from_file = parse_scene(
      std::string(kScene).replace(kScene.find("step: 0.01"), 10, "step: 1e-9"), "p.yaml");
  try {
    check_scene_options(from_file, m, forward_options(from_file, m));
    FAIL() << "expected a SceneError";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.where().file, "p.yaml");
    EXPECT_GT(e.where().line, 0);
  }
}

// run.error_estimate (ForwardOptions::error_estimate): automatic by default, on or off from the
// command line into the run's options; it is not a method (the scene's rk4 stays); another value
// is refused naming the flag.
TEST(RunOverride, ErrorEstimate) {
  EXPECT_EQ(with({}).run.error_estimate, ErrorEstimate::automatic);
  const Scene on = with({{"error_estimate", "on"}});
  EXPECT_EQ(on.run.error_estimate, ErrorEstimate::on);
  EXPECT_EQ(on.run.integrator, Integrator::rk4);
  EXPECT_EQ(with({{"error_estimate", "off"}}).run.error_estimate, ErrorEstimate::off);
  EXPECT_NE(error_of({{"error_estimate", "yes"}}).find("--error-estimate: run.error_estimate"),
            std::string::npos)
      << error_of({{"error_estimate", "yes"}});
}

// run.accuracy picks the integrator and its tolerances: with one of them in the same place it is
// refused; a later setting (the command line over the scene) replaces the earlier one.
TEST(RunOverride, AccuracyAndMethodSettings) {
  EXPECT_EQ(with({{"accuracy", "1e-6"}}).run.accuracy, 1e-6);  // over the scene's rk4
  EXPECT_EQ(with({}).run.accuracy, 0);
  EXPECT_EQ(error_of({{"accuracy", "1e-6"}, {"integrator", "dopri5"}}),
            "--accuracy: run.accuracy: chooses the integrator and its tolerances; remove "
            "--integrator (or --accuracy)");
  EXPECT_NE(error_of({{"accuracy", "0"}})
                .find("--accuracy: run.accuracy: must be in [1e-09, 0.01] (the error of the "
                      "positions relative to the mechanism's size)"),
            std::string::npos);
  EXPECT_NE(error_of({{"accuracy", "1"}}).find("must be in [1e-09, 0.01]"), std::string::npos);
  std::string both = kScene;
  both.replace(both.find("  step: 0.01"), 12, "  accuracy: 1e-6");
  try {
    parse_scene(both, "p.yaml");
    ADD_FAILURE() << "accuracy with integrator accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              "p.yaml:25:13: run.accuracy: chooses the integrator and its tolerances; remove "
              "run.integrator (or run.accuracy)");
  }
  // the scene's accuracy, replaced by a method from the command line
  std::string asked = kScene;
  asked.replace(asked.find("  integrator: rk4\n  step: 0.01"), 30, "  accuracy: 1e-6");
  EXPECT_EQ(parse_scene(asked, "p.yaml").run.accuracy, 1e-6);
  const Scene replaced =
      parse_scene(asked, "p.yaml", {}, std::vector<RunOverride>{{"integrator", "dopri5"}});
  EXPECT_EQ(replaced.run.accuracy, 0);
  EXPECT_EQ(replaced.run.integrator, Integrator::dopri5);
  try {  // a step alone would apply to the default integrator, not to the scene's choice
    parse_scene(asked, "p.yaml", {}, std::vector<RunOverride>{{"step", "1e-3"}});
    ADD_FAILURE() << "--step over run.accuracy accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              "--step: the scene asks for run.accuracy, which chooses the integrator: give "
              "--integrator with --step (or --accuracy)");
  }
}

}  // namespace
}  // namespace mo2d
