// A scene run from C++, the reference of the Python binding's overhead (docs/python.md): the
// sequence mo2d.inverse(scene) / mo2d.forward(scene) runs (python/src/bind_scene.cpp):
// build_scene_model, the run, the output columns. The scene is loaded once, as in the Python
// measurement (bench/python_overhead.py).
#include <benchmark/benchmark.h>

#include <fstream>
#include <sstream>
#include <string>

#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"

namespace {

using namespace mo2d;

const std::string kMechanisms = MO2D_MECHANISMS_DIR;

void BM_SceneInverse(benchmark::State& state, const char* file) {
  const Scene scene = load_scene(kMechanisms + "/" + file);
  for (auto _ : state) {
    const Model model = build_scene_model(scene);
    const InverseOptions run = inverse_options(scene);
    check_scene_options(scene, model, run);
    Trajectory r = inverse_dynamics(model, scene.motion, run);
    add_output_columns(model, r, scene.outputs);
    benchmark::DoNotOptimize(r.efforts.data());
  }
}
BENCHMARK_CAPTURE(BM_SceneInverse, pendulum, "pendulum.yaml")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_SceneInverse, fourbar, "fourbar.yaml")->Unit(benchmark::kMicrosecond);

// forward: the scene with an initial rate of its link (pendulum.yaml has none: it is an inverse
// scene); the same text as bench/python_overhead.py
void BM_SceneForward(benchmark::State& state, const char* file) {
  std::ifstream in(kMechanisms + "/" + file);
  std::stringstream text;
  text << in.rdbuf() << "\ninitial:\n  velocities: {link.w: 1.0}\n";
  const Scene scene = parse_scene(text.str(), "pendulum_forward.yaml");
  for (auto _ : state) {
    const Model model = build_scene_model(scene);
    const ForwardOptions run = forward_options(scene, model);
    check_scene_options(scene, model, run);
    Trajectory r = forward_dynamics(model, initial_state(scene, model), run);
    add_output_columns(model, r, scene.outputs);
    benchmark::DoNotOptimize(r.q0.data());
  }
}
BENCHMARK_CAPTURE(BM_SceneForward, pendulum, "pendulum.yaml")->Unit(benchmark::kMicrosecond);

}  // namespace
