#pragma once
// Options shared by the subcommands that read a scene (SCENE, --set, --out) and the helpers
// they share: loading with overrides, the output folder, a progress bar.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "mo2d/scene.hpp"

namespace mo2d::cli {

struct SceneOptions {
  std::string scene{};
  std::vector<std::string> set{};  // name=value
  std::string out = "out";
};

// SCENE positional (required) and --set; with_out: --out DIR too.
void add_scene_options(CLI::App* app, SceneOptions& o, bool with_out);
Scene load_scene_with_overrides(const SceneOptions& o);
// OUT/<scene name>_<suffix>: creates OUT when needed.
std::string output_path(const SceneOptions& o, const Scene& s, const std::string& suffix);

bool isatty_stderr();

// A progress bar on stderr, drawn only when stderr is a terminal and the run has lasted more
// than half a second; erased by finish().
class Progress {
 public:
  Progress(double t0, double t1);
  void update(double t);
  void finish();

 private:
  double t0_ = 0, t1_ = 1;
  double start_ = 0, last_draw_ = 0;
  bool enabled_ = false, drawn_ = false;
};

}  // namespace mo2d::cli
