// Exact sensitivities of an inverse run (mo2d/sensitivity.hpp; docs/performance.md,
// "Sensitivities"): a four-bar with a spring, a damper and a force, 401 samples, its run alone
// (BM_Run/0) against the same run with the derivatives of every effort and reaction to
// 1, 2, 5 and 10 of its parameters (BM_Run/k; the parameter models built beforehand), and the
// cost of building those models from the scene (BM_ParameterModels/k: the scene parsed and built
// three times per parameter). Issue 36's target: the 10-parameter gradient <= 3 x the run.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"
#include "mo2d/scene_sensitivity.hpp"
#include "mo2d/sensitivity.hpp"

namespace {

const char* kScene = R"(name: fourbar10
parameters:
  m1: 0.2
  m2: 0.5
  m3: 0.4
  I1: 0.0002
  I2: 0.005
  I3: 0.003
  k: 120
  c: 1.5
  F: 3
  g: 9.81
ground: {A0: [0, 0], B0: [0.4, 0]}
bodies:
  crank:
    nodes: {O: [0, 0], A: [0, 0.1]}
    mass: m1
    inertia: I1
    com: {between: [O, A], gamma: 0.5}
  coupler:
    nodes: {A: [0, 0.1], B: [0.35, 0.3]}
    mass: m2
    inertia: I2
    com: {between: [A, B], gamma: 0.4}
  rocker:
    nodes: {O: [0.4, 0], B: [0.35, 0.3]}
    mass: m3
    inertia: I3
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
    push: {body: coupler, point: [0.2, 0.2], fx: F, fy: -0.5 * F}
  springs:
    tether: {body_a: ground, point_a: [0.2, 0.5], body_b: coupler, point_b: [0.2, 0.2],
             rest_length: 0.1, stiffness: k, damping: c}
motion:
  crank.angle: pi/2 + 2 * pi * t
run: {solve: inverse, duration: 1, samples: 401}
)";

const std::vector<std::string> kNames{"m1", "m2", "m3", "I1", "I2", "I3", "k", "c", "F", "g"};

struct Setup {
  mo2d::Scene scene = mo2d::parse_scene(kScene, "fourbar10.yaml");
  mo2d::Model model = mo2d::build_scene_model(scene);
  mo2d::InverseOptions options = mo2d::inverse_options(scene);
  std::vector<mo2d::ParameterModels> models(int k) const {
    const std::vector<std::string> names(kNames.begin(), kNames.begin() + k);
    return mo2d::scene_parameter_models(kScene, scene, {}, {}, names, model, {}, options);
  }
};

void BM_Run(benchmark::State& state) {
  const Setup s;
  const auto p = s.models(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    mo2d::Trajectory r;
    if (p.empty()) {
      r = mo2d::inverse_dynamics(s.model, s.scene.motion, s.options);
    } else {
      const mo2d::InverseSensitivity d =
          mo2d::inverse_dynamics_sensitivity(s.model, s.scene.motion, s.options, p, r);
      benchmark::DoNotOptimize(d.efforts.data());
    }
    benchmark::DoNotOptimize(r.efforts.data());
  }
}
BENCHMARK(BM_Run)->Arg(0)->Arg(1)->Arg(2)->Arg(5)->Arg(10)->Unit(benchmark::kMillisecond);

void BM_ParameterModels(benchmark::State& state) {
  const Setup s;
  for (auto _ : state) {
    const auto p = s.models(static_cast<int>(state.range(0)));
    benchmark::DoNotOptimize(p.data());
  }
}
BENCHMARK(BM_ParameterModels)->Arg(1)->Arg(10)->Unit(benchmark::kMillisecond);

}  // namespace
