// libFuzzer target for the runs: a byte string that loads as a scene is run, with budgets, as the
// scene asks (inverse or forward dynamics, its integrator, formulation and settings). Every input
// must either give a finite result or be rejected with mo2d::Error; a crash, a sanitizer report, a
// hang (libFuzzer's -timeout), any other exception, or a result holding a non-finite value (a
// silent wrong answer) is a bug. Built and run by scripts/fuzz.sh run [SECONDS].
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"

namespace {

// Budgets: a short run of each scene (the fuzzer looks for crashes, not for long integrations).
constexpr int kMaxSamples = 11;
constexpr int kMaxSteps = 20'000;

template <class Result>
void require_finite(const Result& r, const char* what) {
  const bool finite = r.time.allFinite() && r.q0.allFinite() && r.q1.allFinite() &&
                      r.a1.allFinite() && r.efforts.allFinite() && r.reactions.allFinite();
  if (finite) return;
  std::fprintf(stderr, "%s returned a non-finite value without an error\n", what);
  std::abort();
}

void run_inverse(const mo2d::Scene& scene, const mo2d::Model& model) {
  mo2d::InverseOptions o = mo2d::inverse_options(scene);
  o.samples = std::min(o.samples, kMaxSamples);
  require_finite(mo2d::inverse_dynamics(model, scene.motion, o), "inverse_dynamics");
}

void run_forward(const mo2d::Scene& scene, const mo2d::Model& model) {
  mo2d::ForwardOptions o = mo2d::forward_options(scene, model);
  o.samples = std::min(o.samples, kMaxSamples);
  o.max_steps = std::min(o.max_steps, kMaxSteps);
  const mo2d::State initial = mo2d::initial_state(scene, model);
  require_finite(mo2d::forward_dynamics(model, initial, o), "forward_dynamics");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const mo2d::Scene scene = mo2d::parse_scene(text, "fuzz.yaml");
    const mo2d::Model model = mo2d::build_scene_model(scene);
    if (scene.run.solve == mo2d::Solve::inverse)
      run_inverse(scene, model);
    else
      run_forward(scene, model);
  } catch (const mo2d::Error&) {
    // rejected with a message: the expected outcome for most inputs
  }
  return 0;
}
