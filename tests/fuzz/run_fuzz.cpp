// libFuzzer target for the runs: a byte string that loads as a scene is run, with budgets, as the
// scene asks (inverse or forward dynamics, its integrator, formulation and settings). Every input
// must either give a finite result or be rejected with mo2d::Error; a crash, a sanitizer report, a
// hang (libFuzzer's -timeout), any other exception, or a result holding a non-finite value (a
// silent wrong answer) is a bug. Built and run by scripts/fuzz.sh run [SECONDS].
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"

namespace {

// Budgets: a tiny run of each scene (the fuzzer looks for crashes, not for long integrations; at
// these sizes it runs a few hundred inputs per second). A larger run only repeats the same code.
constexpr int kMaxSamples = 3;         // output samples (inverse: solved instants)
constexpr int kMaxSteps = 200;         // forward: integrator steps
constexpr double kMaxDuration = 0.05;  // s of simulated time
constexpr double kMaxSeconds = 0.05;   // wall-time budget of a run (ASan included)
constexpr int kMaxCoordinates = 48;    // larger models are skipped after they are built

// The scene's run shrunk to the budgets above (the feed-forward inverse of its controllers
// included: it reads the same settings).
void shrink_run(mo2d::RunSettings& run) {
  run.samples = std::min(run.samples > 0 ? run.samples : kMaxSamples, kMaxSamples);
  run.duration = std::min(run.duration, kMaxDuration);
  run.max_steps = std::min(run.max_steps, kMaxSteps);
  run.max_seconds = std::min(run.max_seconds, kMaxSeconds);
}

// Abort (a finding) if a returned result holds a non-finite value, naming the field and sample.
void require_finite(const Eigen::MatrixXd& x, const char* field, const char* what) {
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    for (Eigen::Index j = 0; j < x.cols(); ++j)
      if (!std::isfinite(x(i, j))) {
        std::fprintf(stderr, "%s returned a non-finite %s(%ld, %ld) without an error\n", what,
                     field, static_cast<long>(i), static_cast<long>(j));
        std::abort();
      }
}

template <class Result>
void require_finite(const Result& r, const char* what) {
  require_finite(r.time, "time", what);
  require_finite(r.q0, "q0", what);
  require_finite(r.q1, "q1", what);
  require_finite(r.a1, "a1", what);
  require_finite(r.efforts, "efforts", what);
  require_finite(r.reactions, "reactions", what);
}

void run_inverse(const mo2d::Scene& scene, const mo2d::Model& model) {
  const mo2d::InverseOptions o = mo2d::inverse_options(scene);
  require_finite(mo2d::inverse_dynamics(model, scene.motion, o), "inverse_dynamics");
}

void run_forward(const mo2d::Scene& scene, const mo2d::Model& model) {
  mo2d::ForwardOptions o = mo2d::forward_options(scene, model);
  // forward_options may choose an integrator (and so its step) for the accuracy asked: the
  // budgets again
  o.samples = std::min(o.samples, kMaxSamples);
  o.max_steps = std::min(o.max_steps, kMaxSteps);
  o.max_seconds = std::min(o.max_seconds, kMaxSeconds);
  const mo2d::State initial = mo2d::initial_state(scene, model);
  require_finite(mo2d::forward_dynamics(model, initial, o), "forward_dynamics");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    mo2d::Scene scene = mo2d::parse_scene(text, "fuzz.yaml");
    shrink_run(scene.run);
    const mo2d::Model model = mo2d::build_scene_model(scene);
    if (model.n0 > kMaxCoordinates) return 0;
    if (scene.run.solve == mo2d::Solve::inverse)
      run_inverse(scene, model);
    else
      run_forward(scene, model);
  } catch (const mo2d::Error&) {
    // rejected with a message: the expected outcome for most inputs
  }
  return 0;
}
