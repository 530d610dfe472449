// mo2d inverse SCENE [--set name=value]... [--out DIR]: inverse dynamics of a scene; writes
// DIR/NAME_inverse.csv and DIR/NAME_inverse.json.
#include <cstdio>

#include "command.hpp"
#include "mo2d/mo2d.hpp"
#include "scene_options.hpp"
#include "summary.hpp"
#include "table.hpp"

namespace mo2d::cli {

namespace {

int inverse(const SceneOptions& o) {
  const Scene scene = load_scene_with_overrides(o);
  const Model model = build_scene_model(scene);
  if (static_cast<int>(scene.motion.size()) != model.dof)
    throw SceneError(Location{scene.file, 0, 0},
                     "inverse dynamics needs one prescribed motion per DOF: the model has " +
                         std::to_string(model.dof) + " DOF and 'motion' prescribes " +
                         std::to_string(scene.motion.size()));
  const InverseOptions run = inverse_options(scene);
  const InverseResult r = inverse_dynamics(model, scene.motion, run);
  std::printf("mo2d inverse dynamics: %s\n", model.name.c_str());
  print_inverse_table(model, r, run);
  if (scene.run.csv) {
    const std::string path = output_path(o, scene, "inverse.csv");
    write_inverse_csv(r, path);
    std::printf("  wrote %s\n", path.c_str());
  }
  if (scene.run.json) {
    const std::string path = output_path(o, scene, "inverse.json");
    write_file_atomically(path, inverse_summary(scene, model, r));
    std::printf("  wrote %s\n", path.c_str());
  }
  return 0;
}

}  // namespace

Command add_inverse_command(CLI::App& app) {
  auto o = std::make_shared<SceneOptions>();
  CLI::App* sub = app.add_subcommand(
      "inverse", "Inverse dynamics of a scene: efforts and reactions for its prescribed motion");
  add_scene_options(sub, *o, true);
  return {sub, [o] { return inverse(*o); }};
}

}  // namespace mo2d::cli
