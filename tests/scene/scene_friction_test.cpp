// Scenes with joint friction: mechanisms/slider_crank_friction.yaml builds the same frictions as
// the same definitions in C++ and gives the same inverse and forward runs; errors at the key.
#include <gtest/gtest.h>

#include <string>

#include "mo2d/forward.hpp"
#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"

using namespace mo2d;
using mechanisms::Example;

TEST(SceneFriction, SliderCrankWithFrictionEqualsItsCppDefinition) {
  const Scene scene = load_scene(std::string(MO2D_MECHANISMS_DIR) + "/slider_crank_friction.yaml");
  const Model a = build_scene_model(scene);
  ASSERT_EQ(a.frictions.size(), 3u);
  Example ex = mechanisms::slider_crank();
  ex.system.add_friction({.name = "crank_pivot", .joint = "crank_pivot", .viscous = 0.01});
  ex.system.add_friction({.name = "crank_pin", .joint = "crank_pin", .mu = 0.2, .radius = 0.005});
  ex.system.add_friction({.name = "rail", .joint = "rail", .mu = 0.2, .regularization = 1e-3});
  const Model b = build_model(ex.system);
  InverseOptions o = inverse_options(scene);
  const Trajectory ra = inverse_dynamics(a, scene.motion, o);
  const Trajectory rb = inverse_dynamics(b, ex.motion, o);
  EXPECT_LT((ra.efforts - rb.efforts).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((ra.reactions - rb.reactions).cwiseAbs().maxCoeff(), 1e-9);
  // and the friction matters: the frictionless slider-crank needs another torque
  const Trajectory dry =
      inverse_dynamics(build_model(mechanisms::slider_crank().system), ex.motion, o);
  EXPECT_GT((ra.efforts - dry.efforts).cwiseAbs().maxCoeff(), 0.05);
  // forward: the scene's initial state, energy balance with the friction's dissipation
  ForwardOptions f = forward_options(scene, a);
  f.t1 = 0.5;
  f.samples = 11;
  const Trajectory fr = forward_dynamics(a, initial_state(scene, a), f);
  EXPECT_GT(fr.dissipated[10], 0.1);
  EXPECT_LT(energy_balance_error(fr), 1e-6 * fr.dissipated[10]);
}

TEST(SceneFriction, BadFrictionIsAnErrorAtItsKey) {
  const std::string head = R"(
ground: {O: [0, 0], R: [1, 0]}
bodies:
  block: {nodes: {P: [0.5, 0]}, mass: 1}
joints:
)";
  auto message = [&](const std::string& joint) {
    try {
      parse_scene(head + joint, "f.yaml");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("  rail: {type: prismatic, axis_from: ground.O, axis_to: ground.R, slider: "
                    "block.P, friction: {mu: -1}}\n")
                .find("f.yaml:6:"),
            std::string::npos);
  EXPECT_NE(message("  rail: {type: prismatic, axis_from: ground.O, axis_to: ground.R, slider: "
                    "block.P, friction: {mu: 0.1, radius: 1}}\n")
                .find("unknown key 'radius'"),
            std::string::npos);
  EXPECT_NE(message("  rail: {type: prismatic, axis_from: ground.O, axis_to: ground.R, slider: "
                    "block.P, friction: {muu: 0.1}}\n")
                .find("did you mean 'mu'"),
            std::string::npos);
}
