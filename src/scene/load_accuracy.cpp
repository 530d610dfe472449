// run.accuracy (ForwardOptions::accuracy): read from a run: block, and the run settings it
// cannot be given with.
#include <algorithm>
#include <sstream>
#include <string>

#include "load_system.hpp"
#include "mo2d/scene.hpp"

namespace mo2d::scene_detail {

// run.accuracy (ForwardOptions::accuracy) chooses the integrator and its tolerances: written with
// one of them in the same block it is refused; a method set later (a command-line flag over the
// scene) replaces an accuracy set earlier, and an accuracy set later replaces the method.
void read_accuracy(const Reader& r, const YAML::Node& node, RunSettings& run) {
  const char* method_keys[] = {"integrator", "rtol", "atol", "step"};
  if (!node["accuracy"].IsDefined()) {
    for (const char* k : method_keys)
      if (node[k].IsDefined()) {
        run.accuracy = 0;
        run.method_set = true;  // no default accuracy either
      }
    return;
  }
  for (const char* k : method_keys)
    if (node[k].IsDefined())
      r.fail(node["accuracy"], std::string("run.accuracy: chooses the integrator and its "
                                           "tolerances; remove run.") +
                                   k + " (or run.accuracy)");
  run.accuracy = r.number_or(node, "accuracy", 0, "run");
  if (!(run.accuracy >= kMinAccuracy && run.accuracy <= kMaxAccuracy)) {
    std::ostringstream m;
    m << "run.accuracy: must be in [" << kMinAccuracy << ", " << kMaxAccuracy
      << "] (the error of the positions relative to the mechanism's size)";
    r.fail(node["accuracy"], m.str());
  }
}

// --accuracy with --integrator, --rtol, --atol or --step: the same refusal as in a scene. On a
// scene that asks for an accuracy, --rtol, --atol or --step alone would apply to no integrator
// chosen: they need --integrator.
void check_accuracy_overrides(std::span<const RunOverride> overrides, bool scene_accuracy) {
  const auto given = [&](const char* k) {
    return std::any_of(overrides.begin(), overrides.end(),
                       [&](const RunOverride& o) { return o.key == k; });
  };
  if (scene_accuracy && !given("accuracy") && !given("integrator"))
    for (const char* k : {"rtol", "atol", "step"})
      if (given(k))
        throw SceneError(Location{run_override_flag(k), 0, 0},
                         std::string("the scene asks for run.accuracy, which chooses the "
                                     "integrator: give --integrator with ") +
                             run_override_flag(k) + " (or --accuracy)");
  if (!given("accuracy")) return;
  for (const char* k : {"integrator", "rtol", "atol", "step"})
    if (given(k))
      throw SceneError(Location{"--accuracy", 0, 0},
                       std::string("run.accuracy: chooses the integrator and its tolerances; "
                                   "remove ") +
                           run_override_flag(k) + " (or --accuracy)");
}

}  // namespace mo2d::scene_detail
