// CVODE across a jump of the loads just past an output time (src/forward/forward_cvode.cpp,
// restart): a wheel spun up by a constant torque, the torque off and a viscous brake on from
// t_j = 0.5 + 2e-16 s, one rounding step past the output time 0.5 s (the half-bike's brake at
// 10 s, after the output time 10.2 * 50000 / 51000 = 10 - 1.8e-15 s). CVODE stopped at the output
// time, then every try of the next step extrapolated the loads before the jump across it and the
// error test failed 7 times: "CVODE could not continue (flag -3)" at t = 0.5 s (at rtol 1e-10
// whatever the output spacing; at rtol 1e-8 with a brake 10 times harder). Now it restarts there
// and the wheel's speed is the closed form w(t) = w_j exp(-c (t - t_j) / J) past the jump.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "mo2d/forward.hpp"
#include "mo2d/scene.hpp"

namespace mo2d {
namespace {

constexpr const char* kBrake = R"yaml(name: brake
parameters:
  c: 0.1
  tj: 0.5000000000000002
ground:
  O: [0, 0]
bodies:
  wheel: {nodes: {C: [0, 0], R: [0.3, 0]}, mass: 15, inertia: 0.08, com: C}
joints:
  axle: {type: revolute, node_a: ground.O, node_b: wheel.C}
loads:
  torques:
    engine: {body: wheel, torque: "2 * (t < tj)"
}
  torsional_springs:
    brake: {joint: axle, torque: "-c * (t >= tj) * rate"}
initial:
  velocities: {wheel.w: 100}
run: {solve: forward, duration: 1, integrator: cvode_bdf, atol: 1e-9}
)yaml";

TEST(CvodeRestart, AJumpOfTheLoadsJustPastAnOutputTimeIsCrossed) {
  const double J = 0.08, tj = 0.5000000000000002, wj = 100 + 2 * tj / J;
  for (const auto& [c, rtol, samples] :
       {std::tuple{"0.1", "1e-10", "11"}, std::tuple{"0.1", "1e-10", "1001"},
        std::tuple{"1", "1e-8", "1001"}}) {
    SCOPED_TRACE(std::string("c ") + c + ", rtol " + rtol + ", samples " + samples);
    const std::vector<ParameterOverride> set = {{"c", c}};
    const std::vector<RunOverride> run = {{"rtol", rtol}, {"samples", samples}};
    const Scene s = parse_scene(kBrake, "brake.yaml", set, run);
    const Model m = build_scene_model(s);
    try {
      const Trajectory r = forward_dynamics(m, initial_state(s, m), forward_options(s, m));
      const Eigen::Index e = r.time.size() - 1;
      const double w = wj * std::exp(-std::stod(c) * (1 - tj) / J);
      const double err = std::abs(r.q1(e, r.rate_column("wheel.w")) - w) / w;
      std::printf("c %s, rtol %s, %s samples: w(1) relative error %.2e, %ld steps\n", c, rtol,
                  samples, err, r.stats.steps);
      EXPECT_LT(err, 100 * std::stod(rtol));
      ASSERT_EQ(r.stats.warnings.size(), 1u);
      EXPECT_EQ(r.stats.warnings[0],
                "cvode_bdf restarted 1 time, the first at t = 0.5 s: its error test failed "
                "repeatedly on the step after it (a jump of the loads there)");
    } catch (const Error& e) {
      ADD_FAILURE() << e.what();
    }
  }
}

}  // namespace
}  // namespace mo2d
